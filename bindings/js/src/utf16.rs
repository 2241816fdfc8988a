//! Byte offsets (the core's spans) to UTF-16 offsets (JavaScript string indices), for
//! editors. One pass over the text for any number of offsets.

/// Maps byte offsets of one text to UTF-16 code-unit offsets.
pub struct Utf16Map {
    /// Sorted, distinct byte offsets and their UTF-16 offsets; empty for ASCII text,
    /// where both are the same.
    table: Vec<(usize, usize)>,
}

impl Utf16Map {
    /// Prepares the conversion of `offsets` (any order, duplicates allowed).
    pub fn new(text: &str, mut offsets: Vec<usize>) -> Utf16Map {
        if text.is_ascii() {
            return Utf16Map { table: Vec::new() };
        }
        offsets.sort_unstable();
        offsets.dedup();
        let mut table = Vec::with_capacity(offsets.len());
        let mut units = 0;
        let mut chars = text.char_indices().peekable();
        for offset in offsets {
            // Count every char that starts before the offset; an offset inside a char
            // (never produced by the core) lands after it.
            while let Some(&(i, c)) = chars.peek() {
                if i >= offset {
                    break;
                }
                units += c.len_utf16();
                chars.next();
            }
            table.push((offset, units));
        }
        Utf16Map { table }
    }

    /// The UTF-16 offset of a byte offset given to [`Utf16Map::new`] (identity otherwise).
    pub fn get(&self, offset: usize) -> usize {
        if self.table.is_empty() {
            return offset;
        }
        match self.table.binary_search_by_key(&offset, |&(b, _)| b) {
            Ok(i) => self.table[i].1,
            Err(_) => offset,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_units_not_bytes() {
        let text = "+30°, α, 𝕏 +10";
        let plus = text.rfind('+').unwrap();
        let map = Utf16Map::new(text, vec![plus, 0, text.len(), 3]);
        assert_eq!(map.get(0), 0);
        assert_eq!(map.get(3), 3);
        assert_eq!(map.get(plus), text[..plus].encode_utf16().count());
        assert_eq!(map.get(text.len()), text.encode_utf16().count());
    }
}
