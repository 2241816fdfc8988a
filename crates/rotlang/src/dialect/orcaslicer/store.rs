//! The tokens of the metalanguage reading, kept in a few bytes each.
//!
//! A decoded [`Token`] is 48 bytes, and a template of short tokens (`0/5, 400, …`) has one
//! every two or three bytes: decoded up front, with a linked list of the live ones, a
//! 16 MiB template cost twenty times its size (issue 22). Here the text is kept once, each
//! token is its start offset (4 bytes while the text is under 4 GiB) and is decoded again
//! when the walk reads it (at the cost of its length: what reading it cost OrcaSlicer);
//! only tokens longer than [`LONG`] bytes are decoded once and kept, so that a megabyte
//! number read on every layer is not read again each time. The live tokens are found by a
//! union-find over the spent ones (path halving), one more offset per token.

use super::scan;
use super::token::Token;
use crate::diagnostic::Span;

/// Tokens longer than this are decoded once and kept (at most one per `LONG + 1` bytes of
/// text, so at most about 1.7 bytes of decoded token per byte of text).
const LONG: usize = 32;

/// Runs of these cut the text into tokens (10.3).
pub(super) fn is_separator(b: u8) -> bool {
    b == b',' || scan::is_space(b)
}

/// Offsets into the text or the token list, in `u32` while they fit.
#[derive(Clone, Debug)]
enum Offsets {
    Narrow(Vec<u32>),
    Wide(Vec<usize>),
}

impl Offsets {
    fn with_capacity(max: usize, len: usize) -> Offsets {
        if u32::try_from(max).is_ok() {
            Offsets::Narrow(Vec::with_capacity(len))
        } else {
            Offsets::Wide(Vec::with_capacity(len))
        }
    }

    #[inline]
    fn get(&self, i: usize) -> usize {
        match self {
            Offsets::Narrow(v) => v[i] as usize,
            Offsets::Wide(v) => v[i],
        }
    }

    /// `v` is at most the `max` given at creation.
    #[inline]
    fn set(&mut self, i: usize, v: usize) {
        match self {
            Offsets::Narrow(o) => o[i] = v as u32,
            Offsets::Wide(o) => o[i] = v,
        }
    }

    fn len(&self) -> usize {
        match self {
            Offsets::Narrow(v) => v.len(),
            Offsets::Wide(v) => v.len(),
        }
    }

    fn push(&mut self, v: usize) {
        match self {
            Offsets::Narrow(o) => o.push(v as u32),
            Offsets::Wide(o) => o.push(v),
        }
    }
}

/// The tokens of a text (10.3) and which of them are spent.
#[derive(Clone, Debug)]
pub(super) struct Tokens {
    text: Box<[u8]>,
    starts: Offsets,
    /// The tokens longer than [`LONG`], decoded, by index.
    long: Vec<(usize, Token)>,
    /// `ahead[i]` leads to the first live token at or after `i` (`ahead[i] == i`: `i` is
    /// live; index `len` stands for the end and is always "live").
    ahead: Offsets,
    live: usize,
    /// The tokens decoded last, by index modulo its size: a template of a few hundred
    /// tokens, walked on every layer, decodes each once.
    recent: Box<[Option<(usize, Token)>]>,
}

/// Entries of [`Tokens::recent`], at most (16 KiB).
const RECENT: usize = 256;

impl Tokens {
    /// 10.3: split at runs of whitespace and commas; a run at the start yields an empty
    /// token.
    pub(super) fn new(text: &str) -> Tokens {
        let bytes = text.as_bytes();
        let leading = bytes.first().is_some_and(|&b| is_separator(b));
        // Counted first, so that the offsets are allocated once at their size.
        let mut n = usize::from(leading);
        let mut previous = true;
        for &b in bytes {
            let separator = is_separator(b);
            n += usize::from(previous && !separator);
            previous = separator;
        }
        let mut starts = Offsets::with_capacity(bytes.len(), n);
        let mut long = Vec::new();
        let mut add = |starts: &mut Offsets, span: Span| {
            if span.len() > LONG {
                long.push((starts.len(), Token::new(bytes, span)));
            }
            starts.push(span.start);
        };
        if leading {
            add(&mut starts, Span::new(0, 0));
        }
        let mut i = 0;
        while i < bytes.len() {
            while i < bytes.len() && is_separator(bytes[i]) {
                i += 1;
            }
            let start = i;
            while i < bytes.len() && !is_separator(bytes[i]) {
                i += 1;
            }
            if i > start {
                add(&mut starts, Span::new(start, i));
            }
        }
        let mut ahead = Offsets::with_capacity(n, n + 1);
        for i in 0..=n {
            ahead.push(i);
        }
        Tokens {
            text: bytes.into(),
            starts,
            long,
            ahead,
            live: n,
            recent: vec![None; n.clamp(1, RECENT)].into(),
        }
    }

    pub(super) fn len(&self) -> usize {
        self.starts.len()
    }

    /// How many tokens are not spent.
    pub(super) fn live(&self) -> usize {
        self.live
    }

    /// Token `k`, decoded.
    #[inline]
    pub(super) fn get(&mut self, k: usize) -> Token {
        let slot = k % self.recent.len();
        if let Some((at, token)) = self.recent[slot]
            && at == k
        {
            return token;
        }
        let token = self.decode(k);
        self.recent[slot] = Some((k, token));
        token
    }

    fn decode(&self, k: usize) -> Token {
        let start = self.starts.get(k);
        let rest = &self.text[start..];
        match rest.iter().take(LONG + 1).position(|&b| is_separator(b)) {
            Some(len) => Token::new(&self.text, Span::new(start, start + len)),
            None if rest.len() <= LONG => Token::new(&self.text, Span::new(start, self.text.len())),
            None => {
                let at = self
                    .long
                    .binary_search_by_key(&k, |&(i, _)| i)
                    .expect("every long token is kept");
                self.long[at].1
            }
        }
    }

    pub(super) fn is_spent(&self, k: usize) -> bool {
        self.ahead.get(k) != k
    }

    /// Marks live token `k` spent.
    pub(super) fn spend(&mut self, k: usize) {
        self.ahead.set(k, k + 1);
        self.live -= 1;
    }

    /// The first live token at or after `i` (`len()` when there is none).
    fn first_live(&mut self, mut i: usize) -> usize {
        loop {
            let up = self.ahead.get(i);
            if up == i {
                return i;
            }
            // Path halving: every other step points two ahead, so later searches are short.
            let further = self.ahead.get(up);
            self.ahead.set(i, further);
            i = further;
        }
    }

    /// The live token after `k`, round the circle (`k` itself when it is the only one);
    /// `k` may have just been spent. There is a live token.
    pub(super) fn next_live(&mut self, k: usize) -> usize {
        let n = self.len();
        match self.first_live(k + 1) {
            next if next == n => self.first_live(0),
            next => next,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every token as 10.3 cuts the text, decoded once (what the reader kept before).
    fn decoded(text: &str) -> Vec<Token> {
        let bytes = text.as_bytes();
        let mut out = Vec::new();
        if bytes.first().is_some_and(|&b| is_separator(b)) {
            out.push(Token::new(bytes, Span::new(0, 0)));
        }
        let mut start = None;
        for (i, &b) in bytes.iter().chain([&b',']).enumerate() {
            match (is_separator(b), start) {
                (false, None) => start = Some(i),
                (true, Some(s)) => {
                    out.push(Token::new(bytes, Span::new(s, i)));
                    start = None;
                }
                _ => {}
            }
        }
        out
    }

    #[test]
    fn tokens_decode_as_when_decoded_once() {
        let long = format!("+{}L{}%!", "1".repeat(40), "2".repeat(33));
        let texts = [
            "+10L25%, -10l25%",
            ", +5*0, 7!",
            " \t+5",
            "+5,",
            &format!("{long}, +3, {long}"),
            &format!(", {long}"),
            &format!("+1 {}", "9".repeat(32)),
            &format!("+1 {}", "9".repeat(33)),
            &"0*0, +1!, ".repeat(50),
        ];
        for text in texts {
            let mut tokens = Tokens::new(text);
            let want = decoded(text);
            assert_eq!(tokens.len(), want.len(), "{text:?}");
            // Twice: decoded, then from the recent ones.
            for (k, w) in want.iter().enumerate().chain(want.iter().enumerate()) {
                assert_eq!(
                    format!("{:?}", tokens.get(k)),
                    format!("{w:?}"),
                    "{text:?} #{k}"
                );
            }
        }
    }

    /// The union-find gives the live token after each one, round the circle, as a linked
    /// list of the live tokens does, whatever is spent and in which order.
    #[test]
    fn next_live_follows_the_live_tokens() {
        let n = 37;
        let text = "+1, ".repeat(n);
        let mut tokens = Tokens::new(&text);
        let mut live = vec![true; n];
        // A fixed order of spending that is neither ascending nor descending.
        for step in 0..n - 1 {
            let k = (step * 17 + 5) % n;
            tokens.spend(k);
            live[k] = false;
            assert_eq!(tokens.live(), live.iter().filter(|&&l| l).count());
            for from in 0..n {
                let want = (1..=n).map(|d| (from + d) % n).find(|&j| live[j]).unwrap();
                assert_eq!(
                    tokens.next_live(from),
                    want,
                    "after {step} spends, from {from}"
                );
                assert_eq!(tokens.is_spent(from), !live[from]);
            }
        }
    }
}
