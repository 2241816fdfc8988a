//! The OrcaSlicer dialect (SEMANTICS.md section 10): how OrcaSlicer's
//! `calculate_infill_rotation_angle` reads any text, valid or not, layer by layer.
//!
//! This is a reader of its own, beside the grammar: OrcaSlicer has no grammar, it scans
//! characters, and accepts (and means something by) text the grammar rejects. The text is
//! cut into tokens and each token is decoded once, up front; the layers then stream at
//! O(1) amortised cost each. OrcaSlicer recomputes every layer from the bottom (quadratic);
//! this reader keeps the state between layers, skips spent tokens through a linked list and
//! remembers long runs of dummies, so a walk is paid once, not per layer.
//!
//! Where OrcaSlicer never finishes (a walk that loops), crashes (a count outside the
//! 32-bit range) or yields NaN or infinite angles, the stream stays finite as section 10
//! prescribes and [`Layers::findings`] reports the layers.
//!
//! ```
//! use rotlang::dialect::orcaslicer;
//! use rotlang::eval::{Model, Options};
//!
//! // OrcaSlicer reads a plain list separated by spaces as its first number only.
//! let model = Model::cube20();
//! let angles: Vec<f64> = orcaslicer::layers("0 90", &model, Options::default())
//!     .map(|layer| layer.angle)
//!     .take(3)
//!     .collect();
//! assert_eq!(angles, [0.0, 0.0, 0.0]);
//!
//! // `10!, 5*` never finishes slicing in OrcaSlicer: reported, and the angle holds.
//! let mut layers = orcaslicer::layers("10!, 5*", &model, Options::default());
//! let angles: Vec<f64> = layers.by_ref().map(|layer| layer.angle).take(3).collect();
//! assert_eq!(angles, [10.0, 10.0, 10.0]);
//! assert_eq!(layers.findings()[0].code, "orcaslicer::hangs");
//! assert_eq!(layers.findings()[0].first_layer, 1);
//! ```

mod scan;
mod store;
#[cfg(test)]
mod tests;
mod token;

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::hash::{BuildHasherDefault, Hasher};

use store::Tokens;
use token::{Count, Token, Unit, is_joint};

use super::{Finding, HANGS, NAN, UNDEFINED};
use crate::diagnostic::Span;
use crate::eval::{Cursor, Cycle, Layer, Model, Options, random_unit};
use crate::ir::{Fill, Joint};

/// A walk that reads at least this many dummies is remembered (with its effect composed)
/// so that the next walk from the same token over the same live tokens costs O(1). Shorter
/// walks are replayed, which keeps their sums in OrcaSlicer's order bit for bit.
const REMEMBER_AFTER: usize = 64;

/// The characters that select the metalanguage reading (10.2), besides the joint signs.
const META: &[u8] = b"+-%*@'\"cm";

/// Whether OrcaSlicer reads `text` as a plain list (10.2): it contains none of
/// `+ - % * @ ' " c m` and no joint sign. (An empty text gives the base direction.)
pub fn is_list(text: &str) -> bool {
    !text.bytes().any(|b| META.contains(&b) || is_joint(b))
}

/// The options of `text`, a template of a profile whose infill direction (OrcaSlicer's
/// `sparse_infill_direction`, `infill_direction` or `solid_infill_direction`) is
/// `options.base`, in either reading. OrcaSlicer uses the direction only for an empty
/// template: any other template's angles are the template's alone (SEMANTICS 10.2), so
/// the base is dropped. rotlang reads a profile the same way
/// (`rotlang_profile::profile::ProfileModel::options` calls this), so one profile gives one set
/// of angles.
///
/// [`layers`] itself adds `options.base` to every angle (a base chosen on the command line
/// or by an embedder); pass its options through this function when the base is a
/// profile's direction.
pub fn profile_options(text: &str, options: Options) -> Options {
    if text.is_empty() {
        options
    } else {
        Options {
            base: 0.0,
            ..options
        }
    }
}

/// The layers of `model` as OrcaSlicer computes them for `text`, bottom to top.
pub fn layers<'a>(text: &str, model: &'a Model, options: Options) -> Layers<'a> {
    let reading = if text.is_empty() {
        Reading::Empty
    } else if is_list(text) {
        list_reading(text)
    } else {
        Reading::Meta(Box::new(Meta::new(text, model)))
    };
    Layers {
        model,
        options,
        reading,
        at: Cursor::new(model),
        findings: Vec::new(),
        nan: None,
        below: options.base,
        halted: false,
    }
}

/// The stream returned by [`layers`]. Every angle is finite, and so is its value in radians.
#[derive(Clone, Debug)]
pub struct Layers<'a> {
    model: &'a Model,
    options: Options,
    reading: Reading,
    at: Cursor,
    findings: Vec<Finding>,
    /// Index of the NaN finding in `findings`, once there is one.
    nan: Option<usize>,
    /// The angle of the layer below (the base at layer 0): what held layers show.
    below: f64,
    /// OrcaSlicer hung or crashed: every layer from here up holds.
    halted: bool,
}

impl Layers<'_> {
    /// `fold` over the layers left, keeping the stream (for its findings): `next` in a
    /// loop, with the metalanguage's layers inside a range (no walk, a finite angle: most
    /// layers) computed in a tight loop that keeps the state in registers, exactly as
    /// `Meta::layer` computes them; every other layer goes through `next`.
    #[inline]
    pub fn fold_rest<B, F: FnMut(B, Layer) -> B>(&mut self, init: B, mut f: F) -> B {
        let mut acc = init;
        let len = self.model.len();
        loop {
            if let (false, Reading::Meta(meta)) = (self.halted, &mut self.reading) {
                let (base, seed) = (self.options.base, self.options.seed);
                let at = &mut self.at;
                while at.index < len {
                    let (below, top) = (at.bottom, at.top);
                    if meta.limit < 0.5 * (below + top) {
                        break;
                    }
                    let Some(angle) = meta.in_range(top, at.index, seed) else {
                        break;
                    };
                    let angle = base + angle;
                    if !angle.is_finite() {
                        break;
                    }
                    let layer = Layer {
                        index: at.index,
                        bottom: below,
                        top,
                        angle,
                        fill: Fill::Sparse,
                        instruction: meta.governing,
                    };
                    self.below = angle;
                    at.advance_in(self.model);
                    acc = f(acc, layer);
                }
            }
            match self.next() {
                Some(layer) => acc = f(acc, layer),
                None => return acc,
            }
        }
    }

    /// `Some` when OrcaSlicer reads the text as a list (10.2) whose every piece gives a
    /// finite angle: layer `k` then takes piece `k mod n`, with no finding, and
    /// [`Cycle::write`] gives the same angles as this stream (every fill sparse).
    pub fn plain_cycle(&self) -> Option<Cycle> {
        let Reading::Table { pieces, .. } = &self.reading else {
            return None;
        };
        if self.halted {
            return None;
        }
        let base = self.options.base;
        pieces
            .iter()
            .map(|&(value, _)| {
                let a = base + value;
                (finite_in_radians(value) && a.is_finite()).then_some((a, Fill::Sparse))
            })
            .collect::<Option<Vec<_>>>()
            .map(|entries| Cycle { entries })
    }

    /// What was found in the layers yielded so far: a hang, undefined behaviour, NaN
    /// layers (codes `orcaslicer::hangs`, `orcaslicer::undefined`, `orcaslicer::nan`).
    pub fn findings(&self) -> &[Finding] {
        &self.findings
    }

    /// The index of the layer the next call to `next` yields.
    pub fn position(&self) -> usize {
        self.at.index
    }

    /// The stream consumed to the end, for its findings.
    pub fn into_findings(mut self) -> Vec<Finding> {
        for _ in self.by_ref() {}
        self.findings
    }

    fn halt(&mut self, code: &'static str, layer: usize, span: Option<Span>) {
        self.halted = true;
        let left = self.model.len() - layer;
        let message = if code == HANGS {
            format!(
                "OrcaSlicer never finishes slicing: its walk through the template loops forever at layer {layer}"
            )
        } else {
            format!(
                "OrcaSlicer's behaviour is undefined at layer {layer} (a count outside the 32-bit range): in practice it crashes"
            )
        };
        self.findings.push(Finding {
            code,
            message,
            first_layer: layer,
            layers: left,
            span,
        });
    }

    fn record_nan(&mut self, layer: usize, span: Option<Span>) {
        match self.nan {
            Some(at) => self.findings[at].layers += 1,
            None => {
                self.nan = Some(self.findings.len());
                self.findings.push(Finding {
                    code: NAN,
                    message: format!(
                        "OrcaSlicer computes a NaN or infinite angle from layer {layer}"
                    ),
                    first_layer: layer,
                    layers: 1,
                    span,
                });
            }
        }
    }
}

/// OrcaSlicer's result is the radian value `π × a / 180`, computed left to right.
fn finite_in_radians(a: f64) -> bool {
    (PI * a / 180.0).is_finite()
}

impl Iterator for Layers<'_> {
    type Item = Layer;

    fn next(&mut self) -> Option<Layer> {
        let index = self.at.index;
        if index >= self.model.len() {
            return None;
        }
        let (bottom, top) = (self.at.bottom, self.at.top);
        let mut instruction = None;
        let angle = if self.halted {
            self.below
        } else {
            let base = self.options.base;
            let outcome = match &mut self.reading {
                Reading::Empty => Outcome::Angle(base),
                Reading::Table { pieces, next } => {
                    // Layer i gets piece i mod n, and layers come in order.
                    let (value, span) = pieces[*next];
                    *next = if *next + 1 == pieces.len() {
                        0
                    } else {
                        *next + 1
                    };
                    instruction = Some(span);
                    if finite_in_radians(value) {
                        Outcome::Angle(base + value)
                    } else {
                        Outcome::Nan(None)
                    }
                }
                Reading::List { text, next } => {
                    // As above, the pieces read in turn from the text, from the first
                    // again after the last.
                    let (value, span, after) = piece(text, *next);
                    *next = after.unwrap_or(0);
                    instruction = Some(span);
                    if finite_in_radians(value) {
                        Outcome::Angle(base + value)
                    } else {
                        Outcome::Nan(None)
                    }
                }
                Reading::Meta(meta) => {
                    let outcome = meta.layer(&self.at, self.model, self.options.seed);
                    instruction = meta.governing;
                    match outcome {
                        Ok(Ok(a)) => Outcome::Angle(base + a),
                        Ok(Err(clamped)) => Outcome::Nan(clamped.map(|a| base + a)),
                        Err(halt) => Outcome::Halt(halt),
                    }
                }
            };
            match outcome {
                Outcome::Angle(a) if a.is_finite() => a,
                Outcome::Angle(_) => self.below,
                Outcome::Nan(clamped) => {
                    self.record_nan(index, instruction);
                    clamped.filter(|a| a.is_finite()).unwrap_or(self.below)
                }
                Outcome::Halt(halt) => {
                    let at_fault = match halt {
                        Halt::Hang => None,
                        Halt::Undefined => instruction,
                    };
                    instruction = None;
                    self.halt(halt.code(), index, at_fault);
                    self.below
                }
            }
        };
        self.below = angle;
        self.at.advance_in(self.model);
        Some(Layer {
            index,
            bottom,
            top,
            angle,
            fill: Fill::Sparse,
            instruction,
        })
    }

    #[inline]
    fn fold<B, F: FnMut(B, Layer) -> B>(mut self, init: B, f: F) -> B {
        self.fold_rest(init, f)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.model.len().saturating_sub(self.at.index);
        (left, Some(left))
    }
}

impl ExactSizeIterator for Layers<'_> {}
impl std::iter::FusedIterator for Layers<'_> {}

enum Outcome {
    Angle(f64),
    /// A NaN layer, with the angle recomputed on clamped progress when that is finite.
    Nan(Option<f64>),
    Halt(Halt),
}

#[derive(Clone, Copy, Debug)]
enum Halt {
    Hang,
    Undefined,
}

impl Halt {
    fn code(self) -> &'static str {
        match self {
            Halt::Hang => HANGS,
            Halt::Undefined => UNDEFINED,
        }
    }
}

#[derive(Clone, Debug)]
enum Reading {
    Empty,
    /// The list reading: the text, and where the piece of the next layer begins. No piece
    /// is stored: a megabyte list costs its text, not a vector of pieces.
    List {
        text: Box<str>,
        next: usize,
    },
    /// The list reading with every piece read once: for lists of few or long pieces,
    /// where reading a piece again on every layer would cost its length each time (a
    /// megabyte number re-read on every layer), and a plain list is `pieces[i mod n]`.
    Table {
        pieces: Box<[(f64, Span)]>,
        next: usize,
    },
    Meta(Box<Meta>),
}

/// The list reading of `text`: a table of its pieces when it costs at most a few
/// thousand entries or no more than the text itself (24 bytes a piece against at least
/// 24 bytes of text a piece); otherwise the pieces are read from the text in turn, each
/// then costing fewer than 24 bytes of reading on average.
fn list_reading(text: &str) -> Reading {
    const FEW: usize = 4096;
    let commas = text.bytes().filter(|&b| b == b',').count();
    if commas < FEW || commas * size_of::<(f64, Span)>() <= text.len() {
        let mut pieces = Vec::with_capacity(commas + 1);
        let mut from = Some(0);
        while let Some(at) = from {
            let (value, span, next) = piece(text, at);
            pieces.push((value, span));
            from = next;
        }
        Reading::Table {
            pieces: pieces.into(),
            next: 0,
        }
    } else {
        Reading::List {
            text: text.into(),
            next: 0,
        }
    }
}

/// 10.2: split at every `,`; a trailing `,` adds no piece; trim; read a decimal prefix.
/// The piece that begins at byte `from`: its number, its span, and where the next piece
/// begins (`None` after the last).
fn piece(text: &str, from: usize) -> (f64, Span, Option<usize>) {
    let bytes = text.as_bytes();
    let end = bytes[from..]
        .iter()
        .position(|&b| b == b',')
        .map_or(bytes.len(), |p| from + p);
    let (mut a, mut b) = (from, end);
    while a < b && scan::is_space(bytes[a]) {
        a += 1;
    }
    while b > a && scan::is_space(bytes[b - 1]) {
        b -= 1;
    }
    let next = (end != bytes.len() && end + 1 != bytes.len()).then_some(end + 1);
    (scan::list_number(&bytes[a..b]), Span::new(a, b), next)
}

/// The pieces of the list reading, one at a time: each piece's number.
fn pieces(text: &str) -> impl Iterator<Item = f64> + '_ {
    let mut from = Some(0);
    std::iter::from_fn(move || {
        let (value, _, next) = piece(text, from?);
        from = next;
        Some(value)
    })
}

/// The tokens of the metalanguage reading (10.3), as text: split at runs of whitespace
/// and commas; a run at the start yields an empty first token.
fn token_texts(text: &str) -> impl Iterator<Item = &[u8]> + '_ {
    let bytes = text.as_bytes();
    let separator = |b: &u8| *b == b',' || scan::is_space(*b);
    let leading = bytes.first().filter(|b| separator(b)).map(|_| &bytes[..0]);
    leading
        .into_iter()
        .chain(bytes.split(separator).filter(|t| !t.is_empty()))
}

/// Whether OrcaSlicer reads `a` and `b` alike on every model, decided from the texts
/// alone: both empty; both plain lists whose pieces read the same numbers; or both read
/// by the metalanguage with the same tokens (it sees nothing but their texts). Streaming,
/// without allocation: a cheap exact check before comparing angles layer by layer. `false`
/// does not prove the angles differ (`0 0` and `0, 0` give the same angles).
pub fn same_reading(a: &str, b: &str) -> bool {
    if a.is_empty() || b.is_empty() {
        return a.is_empty() && b.is_empty();
    }
    match (is_list(a), is_list(b)) {
        (true, true) => pieces(a).map(f64::to_bits).eq(pieces(b).map(f64::to_bits)),
        (false, false) => token_texts(a).eq(token_texts(b)),
        _ => false,
    }
}

/// C's `(int)x`: `None` where it is undefined (NaN, infinite, outside the 32-bit range).
fn c_int(x: f64) -> Option<i64> {
    (x > -2_147_483_649.0 && x < 2_147_483_648.0).then(|| x.trunc() as i64)
}

/// What a remembered walk does (see [`REMEMBER_AFTER`]).
#[derive(Clone, Copy, Debug)]
struct Chain {
    /// The number of live tokens when it was recorded: the chain holds while it is unchanged
    /// (tokens are only ever spent, so the count identifies the set).
    live: usize,
    /// Where the walk stands after the dummies.
    end: usize,
    /// Whether the walk stops there (else it reads the token at `end` next).
    stops: bool,
    moves: u64,
    /// The effect on `start` of the dummies: `(start + add) + sum`, or a constant.
    start: ChainStart,
    /// `add` after the dummies.
    add: f64,
    /// The last dummy read.
    last: Span,
}

#[derive(Clone, Copy, Debug)]
enum ChainStart {
    Relative(f64),
    Absolute(f64),
}

/// A token index's hash, one multiplication (Fibonacci hashing): the chains are looked up
/// on every walk, where SipHash doubled the cost of a walk of dummies.
#[derive(Clone, Copy, Debug, Default)]
struct IndexHash(u64);

impl Hasher for IndexHash {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(self.0 ^ u64::from(b));
        }
    }

    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0 ^ n).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }

    fn write_usize(&mut self, n: usize) {
        self.write_u64(n as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// The state of the metalanguage reading (10.3), kept across layers.
#[derive(Clone, Debug)]
struct Meta {
    tokens: Tokens,
    /// The walk remembered from a token, by token: few tokens start long walks.
    chains: HashMap<usize, Chain, BuildHasherDefault<IndexHash>>,
    k: usize,
    start: f64,
    add: f64,
    repeats: i32,
    zs: f64,
    limit: f64,
    noop: bool,
    negative: bool,
    form: Option<Joint>,
    /// The token that set up the current range (the last one read).
    governing: Option<Span>,
    /// `Hs`, the object height in nanometres, computed when a `%` length first needs it.
    object_nm: Option<f64>,
}

impl Meta {
    fn new(text: &str, _model: &Model) -> Meta {
        Meta {
            tokens: Tokens::new(text),
            chains: HashMap::default(),
            k: 0,
            start: 0.0,
            add: 0.0,
            repeats: 0,
            zs: 0.0,
            limit: 0.0,
            noop: false,
            negative: false,
            form: None,
            governing: None,
            object_nm: None,
        }
    }

    /// 10.4 for the layer under `at`: `Ok(Ok(angle))`, `Ok(Err(clamped))` for a NaN layer
    /// (with the angle on clamped progress when that one is finite), or a halt.
    fn layer(
        &mut self,
        at: &Cursor,
        model: &Model,
        seed: u64,
    ) -> Result<Result<f64, Option<f64>>, Halt> {
        let (below, top) = (at.bottom, at.top);
        // 10.1: OrcaSlicer stores the layer's height and derives its bottom from it.
        let bottom = top - (top - below);
        let middle = 0.5 * (below + top);
        if self.limit < middle {
            if self.repeats > 0 {
                self.limit = self.limit + (self.limit - self.zs);
                self.zs = bottom;
                self.repeats -= 1;
            } else {
                self.zs = bottom;
                self.limit = top;
                self.form = None;
                self.walk(at, bottom, model)?;
            }
        }
        if let Some(angle) = self.in_range(top, at.index, seed) {
            return Ok(Ok(angle));
        }
        let progress = if self.negative {
            (self.limit - top) / (self.limit - self.zs)
        } else {
            (top - self.zs) / (self.limit - self.zs)
        };
        let random = || random_unit(seed, at.index);
        // 10.7: a NaN layer; progress clamped (1 for an empty range) gives rotlang's angle.
        let clamped = if self.limit == self.zs {
            1.0
        } else {
            progress.clamp(0.0, 1.0)
        };
        let angle = self.start + self.add * shape(self.form, clamped, self.negative, random);
        Ok(Err(finite_in_radians(angle).then_some(angle)))
    }

    /// The angle of the layer of top `top` in the current range, when it is finite in
    /// radians (10.4 step 3).
    #[inline(always)]
    fn in_range(&self, top: f64, index: usize, seed: u64) -> Option<f64> {
        let progress = if self.negative {
            (self.limit - top) / (self.limit - self.zs)
        } else {
            (top - self.zs) / (self.limit - self.zs)
        };
        let random = || random_unit(seed, index);
        let angle = self.start + self.add * shape(self.form, progress, self.negative, random);
        finite_in_radians(angle).then_some(angle)
    }

    /// 10.5: read tokens from the cursor until the walk stops.
    fn walk(&mut self, at: &Cursor, bottom: f64, model: &Model) -> Result<(), Halt> {
        let n = self.tokens.len();
        if self.tokens.live() == 0 {
            self.k = (self.k + 1) % n;
            return Ok(());
        }
        let from = self.k;
        let live_before = self.tokens.live();
        let mut moves: u64 = 0;
        let mut dummies = 0;
        let mut remembered = false;
        let remembered_here = self.chains.get(&from).copied();
        if let Some(chain) = remembered_here.filter(|c| c.live == self.tokens.live()) {
            self.apply(chain);
            moves = chain.moves;
            remembered = true;
            self.k = chain.end;
            if chain.stops {
                return Ok(());
            }
        }
        let limit = 3 * n as u64;
        loop {
            let k = self.k;
            let token = self.tokens.get(k);
            let dummy = token.repeats == 0;
            let unchanged = !remembered && self.tokens.live() == live_before;
            if !dummy && dummies >= REMEMBER_AFTER && unchanged {
                self.remember(from, k, false, moves, dummies);
            }
            self.read(k, token, at, bottom, model)?;
            if dummy {
                dummies += 1;
            }
            if self.tokens.live() == 0 {
                self.k = (k + 1) % n;
                return Ok(());
            }
            // The next live token (`k` may have just been spent).
            let next = self.tokens.next_live(k);
            moves += if next > k { next - k } else { next + n - k } as u64;
            self.k = next;
            if !(next != 0 && self.noop) {
                if dummy
                    && dummies >= REMEMBER_AFTER
                    && !remembered
                    && self.tokens.live() == live_before
                {
                    self.remember(from, next, true, moves, dummies);
                }
                return Ok(());
            }
            if moves > limit {
                return Err(Halt::Hang);
            }
        }
    }

    /// Records the walk from `from` over `count` dummies (in live order) to `end`.
    fn remember(&mut self, from: usize, end: usize, stops: bool, moves: u64, count: usize) {
        let mut start = ChainStart::Relative(0.0);
        let mut add = None::<f64>;
        let mut p = from;
        let mut last = Span::default();
        for _ in 0..count {
            // start = start + add (the first dummy adds the add from before the walk).
            start = match (start, add) {
                (s, None) => s,
                (ChainStart::Relative(s), Some(a)) => ChainStart::Relative(s + a),
                (ChainStart::Absolute(s), Some(a)) => ChainStart::Absolute(s + a),
            };
            let token = self.tokens.get(p);
            add = Some(token.value);
            if token.absolute {
                start = ChainStart::Absolute(token.value);
                add = Some(0.0);
            }
            last = token.span;
            p = self.tokens.next_live(p);
        }
        let chain = Chain {
            live: self.tokens.live(),
            end,
            stops,
            moves,
            start,
            add: add.unwrap_or(self.add),
            last,
        };
        self.chains.insert(from, chain);
    }

    fn apply(&mut self, chain: Chain) {
        self.start = match chain.start {
            ChainStart::Relative(sum) => self.start + self.add + sum,
            ChainStart::Absolute(c) => c,
        };
        self.add = chain.add;
        self.noop = true;
        self.negative = false;
        self.repeats = 0;
        self.governing = Some(chain.last);
    }

    /// 10.6: read token `k` at the layer under `at`.
    fn read(
        &mut self,
        k: usize,
        token: Token,
        at: &Cursor,
        bottom: f64,
        model: &Model,
    ) -> Result<(), Halt> {
        self.noop = false;
        self.negative = false;
        self.start += self.add;
        if token.bang && !self.tokens.is_spent(k) {
            self.tokens.spend(k);
        }
        self.governing = Some(token.span);
        self.add = token.value;
        self.repeats = token.repeats;
        if token.repeats != 0 {
            let steps = match token.count {
                Count::Bottom => f64::from(model.bottom_shells()),
                Count::Top => f64::from(model.top_shells()),
                Count::Layers(steps) => {
                    self.form = token.form;
                    self.negative = token.negative;
                    steps
                }
                Count::Length(steps, unit) => {
                    self.form = token.form;
                    self.negative = token.negative;
                    self.limit = match unit {
                        Unit::Percent => steps * self.object_nm(model) * 1e-8,
                        Unit::StandardLayers => steps * model.layer_height(),
                        Unit::Foot => steps * 12.0 * 25.4,
                        Unit::Inch => steps * 25.4,
                        Unit::Centimetre => steps * 10.0,
                        Unit::Millimetre => steps * 1.0,
                        Unit::Metre => steps * 1000.0,
                        Unit::Keep => self.limit,
                    };
                    self.limit += bottom;
                    0.0
                }
            };
            if steps != 0.0 {
                if self.form.is_none() && !token.absolute {
                    let whole = c_int(steps).ok_or(Halt::Undefined)?;
                    self.add *= whole as f64;
                }
                // C's `std::max(steps - 1, 0)`: NaN passes through (and is undefined below).
                let extra = if steps - 1.0 < 0.0 { 0.0 } else { steps - 1.0 };
                let j = c_int(at.index as f64 + extra).ok_or(Halt::Undefined)?;
                let layers = model.len() as i64;
                let over = (j - layers).max(0);
                let j = j.min(layers - 1);
                // `j ≥ at.index`: a range the stream is about to walk through.
                let j = usize::try_from(j).unwrap_or(at.index).max(at.index);
                self.limit = model.top_at(at, j) + over as f64 * model.layer_height();
            }
            self.repeats = self.repeats.wrapping_sub(1).max(0);
        } else {
            self.noop = true;
        }
        if token.absolute {
            self.start = self.add;
            self.add = 0.0;
        }
        Ok(())
    }

    fn object_nm(&mut self, model: &Model) -> f64 {
        *self
            .object_nm
            .get_or_insert_with(|| (model.last_top() / 0.000001).round())
    }
}

/// Section 5's shapes as OrcaSlicer computes them (10.4 step 3), on unclamped progress.
#[inline]
fn shape(form: Option<Joint>, v: f64, negative: bool, random: impl FnOnce() -> f64) -> f64 {
    let Some(joint) = form else { return v };
    match joint {
        Joint::Linear => v,
        Joint::SineVertical => v - (TAU * v).sin() / TAU,
        Joint::SineVerticalLazy => v - (TAU * v).sin() / (2.0 * TAU),
        Joint::SineHorizontal => v + (TAU * v).sin() / TAU,
        Joint::SineHorizontalLazy => v + (TAU * v).sin() / (2.0 * TAU),
        Joint::Arcsine => (2.0 * v - 1.0).asin() / PI + 0.5,
        Joint::QuarterCircleHV => (FRAC_PI_2 * v).sin(),
        Joint::QuarterCircleVH => 1.0 - (FRAC_PI_2 * v).cos(),
        Joint::Square => 1.0 - (1.0 - v) * (1.0 - v),
        Joint::SquareInverse => (1.0 - v) * (1.0 - v),
        Joint::Cubic => 1.0 - (1.0 - v).powf(3.0),
        Joint::CubicInverse => (1.0 - v).powf(3.0),
        Joint::Random => random(),
        Joint::PseudoRandom => v + random() - 0.5,
        Joint::Middle => 0.5,
        Joint::Step => {
            if negative {
                0.0
            } else {
                1.0
            }
        }
    }
}
