//! Markdown or plain text, as the client asks (`contentFormat` for hovers,
//! `documentationFormat` for completion items). Features write Markdown; this turns it
//! into plain text at the edge for clients that show text as it is.

use tower_lsp_server::ls_types::{MarkupContent, MarkupKind};

/// Whether a client's list of formats, in order of preference, asks for plain text: it
/// prefers it, or does not list Markdown at all. No list means Markdown (what every
/// client that says nothing renders).
pub fn wants_plain(formats: Option<&[MarkupKind]>) -> bool {
    match formats {
        Some([first, ..]) if *first == MarkupKind::PlainText => true,
        Some(list) if !list.is_empty() => !list.contains(&MarkupKind::Markdown),
        _ => false,
    }
}

/// The content in the requested kind (unchanged when Markdown is fine).
pub fn content(markdown: String, plain: bool) -> MarkupContent {
    if plain {
        MarkupContent {
            kind: MarkupKind::PlainText,
            value: to_plain(&markdown),
        }
    } else {
        MarkupContent {
            kind: MarkupKind::Markdown,
            value: markdown,
        }
    }
}

/// The Markdown the features write, without its markup: code spans (`` ` ``), bold
/// (`**`) and italics (`_` at the edge of a word). Quoted templates never hold a backtick
/// (the hover writes it as `'`), so every backtick is markup.
pub fn to_plain(markdown: &str) -> String {
    let text = markdown.replace("**", "").replace('`', "");
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    for (i, &c) in chars.iter().enumerate() {
        if c == '_' {
            let before = i.checked_sub(1).map(|j| chars[j]);
            let after = chars.get(i + 1).copied();
            let opens = before.is_none_or(char::is_whitespace);
            let closes = after.is_none_or(|a| a.is_whitespace() || a == '.');
            if opens || closes {
                continue;
            }
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_text_drops_the_markup_only() {
        assert_eq!(
            to_plain("**key** `+30/5` turns.\n\n_Model: 100 layers × 0.2 mm._ snake_case"),
            "key +30/5 turns.\n\nModel: 100 layers × 0.2 mm. snake_case"
        );
        assert!(wants_plain(Some(&[
            MarkupKind::PlainText,
            MarkupKind::Markdown
        ])));
        assert!(!wants_plain(Some(&[
            MarkupKind::Markdown,
            MarkupKind::PlainText
        ])));
        assert!(!wants_plain(None));
        assert!(!wants_plain(Some(&[])));
    }
}
