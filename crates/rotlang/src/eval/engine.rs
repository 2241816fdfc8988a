//! The state machine of SEMANTICS.md sections 3, 4 and 6: ranges, walks and runs.
//!
//! One [`Engine`] steps through the layers bottom to top. Its memory is O(instructions):
//! a prepared copy of each instruction, the links of the cycle of live positions and the
//! remembered walks. Nothing is ever looped over or allocated per count, so `*1000000000`
//! or a 1e6 mm length cost no more than a plain instruction, and a walk across many
//! dummies is paid once, not per layer: time is O(layers + instructions × spent ones).

use super::model::{Cursor, Model};
use super::{Layer, Options, random, shape::shape};
use crate::diagnostic::Span;
use crate::ir::{CountKind, Fill, Instruction, Joint, Template, Unit};
use std::collections::HashMap;
use std::sync::Arc;

/// Mid-layer ties (`m[i]` equal to a range end up to rounding) go to the current range.
const TIE: f64 = 1e-6;

/// Every angle, turn and height the engine keeps stays within ±LIMIT, so that no sum or
/// product can overflow to infinity and no NaN can be born (`inf - inf`, `0 × inf`).
/// Only absurd input (a 400-digit angle, `*1e300` counts) ever reaches the bound.
const LIMIT: f64 = 1e300;

#[inline]
fn finite(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-LIMIT, LIMIT)
    }
}

/// How far an instruction's range reaches, resolved against the model.
#[derive(Clone, Copy, Debug)]
enum Extent {
    /// The layer where the range starts, alone.
    OneLayer,
    /// `n ≥ 1` whole layers (a float, so that `/1e30` stays representable).
    Layers(f64),
    /// A height in mm above the bottom of the starting layer.
    Length(f64),
}

/// An instruction prepared for evaluation: everything the engine needs, in the form
/// it needs it, computed once per evaluation instead of once per layer. 56 bytes: with
/// the IR dropped, this is what a huge template costs the evaluator.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step {
    span: Span,
    /// `α`, the angle in degrees.
    alpha: f64,
    relative: bool,
    dummy: bool,
    one_time: bool,
    runs: u64,
    joint: Joint,
    flipped: bool,
    fill: Fill,
    /// The extent, stored as a kind and a value (an `Extent` field would take 16 bytes
    /// and make a step 64).
    extent_kind: ExtentKind,
    extent_value: f64,
    /// The turn `d` a relative set-up makes (section 3, "The turn").
    turn: f64,
}

impl Step {
    pub(crate) fn new(instruction: &Instruction, model: &Model) -> Step {
        let alpha = finite(instruction.degrees());
        // A count of `n` layers (section 3); 0, or nonsense (negative, NaN) from a
        // hand-built IR, is one layer turning by α.
        let counted = |n: f64| {
            if n.is_nan() || n <= 0.0 {
                return (Extent::OneLayer, alpha);
            }
            let whole = n.floor();
            // One α per layer when no joint spreads the turn: `+30B` turns 30° per layer.
            let turn = if instruction.joint.is_none() {
                finite(alpha * whole)
            } else {
                alpha
            };
            (Extent::Layers(whole.max(1.0)), turn)
        };
        let length = |mm: f64| (Extent::Length(finite(mm)), alpha);
        let (extent, turn) = match instruction.count.map(|c| c.kind) {
            None => (Extent::OneLayer, alpha),
            Some(CountKind::Layers(n)) => counted(n),
            Some(CountKind::Bottom) => counted(f64::from(model.bottom_shells())),
            Some(CountKind::Top) => counted(f64::from(model.top_shells())),
            Some(CountKind::Length { value, unit }) => length(match unit {
                Unit::StandardLayers => value * model.layer_height(),
                // The object height is computed only when a template asks for it.
                Unit::PercentOfHeight => value / 100.0 * model.object_height(),
                fixed => value * fixed.millimetres().unwrap_or(1.0),
            }),
            Some(CountKind::HeightFraction { num, den }) => {
                length(num / den * model.object_height())
            }
        };
        Step {
            span: instruction.span,
            alpha,
            relative: instruction.is_relative(),
            dummy: instruction.is_dummy(),
            one_time: instruction.is_one_time(),
            runs: instruction.runs(),
            joint: instruction.shape(),
            flipped: instruction.is_flipped(),
            fill: instruction.fill(),
            extent_kind: match extent {
                Extent::OneLayer => ExtentKind::OneLayer,
                Extent::Layers(_) => ExtentKind::Layers,
                Extent::Length(_) => ExtentKind::Length,
            },
            extent_value: match extent {
                Extent::OneLayer => 0.0,
                Extent::Layers(v) | Extent::Length(v) => v,
            },
            turn,
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum ExtentKind {
    OneLayer,
    Layers,
    Length,
}

impl Step {
    /// A step that does nothing (a relative 0 over one layer), for an out-of-range
    /// position, which the engine never asks for.
    const HOLD: Step = Step {
        span: Span::new(0, 0),
        alpha: 0.0,
        relative: true,
        dummy: false,
        one_time: false,
        runs: 1,
        joint: Joint::Linear,
        flipped: false,
        fill: Fill::Sparse,
        extent_kind: ExtentKind::OneLayer,
        extent_value: 0.0,
        turn: 0.0,
    };

    /// Everything but the span, as bits: equal keys, equal evaluation.
    fn key(&self) -> [u64; 5] {
        let flags = u64::from(self.relative)
            | u64::from(self.dummy) << 1
            | u64::from(self.one_time) << 2
            | u64::from(self.flipped) << 3
            | (self.joint as u64) << 8
            | (self.fill as u64) << 16
            | (self.extent_kind as u64) << 24;
        [
            self.alpha.to_bits(),
            self.runs,
            self.turn.to_bits(),
            self.extent_value.to_bits(),
            flags,
        ]
    }

    #[inline]
    fn extent(&self) -> Extent {
        match self.extent_kind {
            ExtentKind::OneLayer => Extent::OneLayer,
            ExtentKind::Layers => Extent::Layers(self.extent_value),
            ExtentKind::Length => Extent::Length(self.extent_value),
        }
    }
}

/// The prepared steps of a template: for each instruction its span and the index of its
/// step, each distinct step stored once. What a template costs the evaluator: 12 bytes per
/// instruction and 56 per distinct step (a million `0`s hold one step).
#[derive(Debug)]
pub(crate) struct Program {
    slots: Slots,
    cores: Vec<Step>,
}

/// Per instruction: span start, span end, step index. In `u32` while they fit (any text
/// under 4 GiB), in `usize` beyond.
#[derive(Debug)]
enum Slots {
    Narrow(Vec<[u32; 3]>),
    Wide(Vec<[usize; 3]>),
}

impl Slots {
    #[inline]
    fn get(&self, c: usize) -> Option<[usize; 3]> {
        match self {
            Slots::Narrow(v) => v.get(c).map(|s| s.map(|x| x as usize)),
            Slots::Wide(v) => v.get(c).copied(),
        }
    }

    fn len(&self) -> usize {
        match self {
            Slots::Narrow(v) => v.len(),
            Slots::Wide(v) => v.len(),
        }
    }

    fn push(&mut self, slot: [usize; 3]) {
        if let Slots::Narrow(v) = self {
            match slot.map(u32::try_from) {
                [Ok(a), Ok(b), Ok(c)] => return v.push([a, b, c]),
                _ => *self = Slots::Wide(v.iter().map(|s| s.map(|x| x as usize)).collect()),
            }
        }
        if let Slots::Wide(v) = self {
            v.push(slot);
        }
    }

    fn shrink_to_fit(&mut self) {
        match self {
            Slots::Narrow(v) => v.shrink_to_fit(),
            Slots::Wide(v) => v.shrink_to_fit(),
        }
    }
}

impl Program {
    pub fn len(&self) -> usize {
        self.slots.len()
    }

    #[inline]
    pub fn get(&self, c: usize) -> Option<Step> {
        let [start, end, core] = self.slots.get(c)?;
        let core = self.cores.get(core)?;
        Some(Step {
            span: Span::new(start, end),
            ..*core
        })
    }

    /// The step at a position below `len()` (a position always is).
    #[inline]
    fn at(&self, c: usize) -> Step {
        self.get(c).unwrap_or(Step::HOLD)
    }
}

/// Builds a [`Program`], storing equal steps once. The table of steps seen is bounded
/// (cleared when full), so memory stays a small multiple of the template whatever it holds.
pub(crate) struct ProgramBuilder {
    program: Program,
    seen: HashMap<[u64; 5], usize>,
}

/// Distinct steps remembered for sharing, at most (a few MB of table).
const SEEN: usize = 1 << 16;

impl ProgramBuilder {
    /// For at most `n` instructions. The capacities are reserved, not touched: pages not
    /// written are not resident, so reserving the bound costs nothing.
    pub fn with_capacity(n: usize) -> ProgramBuilder {
        ProgramBuilder {
            program: Program {
                slots: Slots::Narrow(Vec::with_capacity(n)),
                cores: Vec::with_capacity(n),
            },
            seen: HashMap::new(),
        }
    }

    pub fn push(&mut self, step: Step) {
        let key = step.key();
        let cores = &mut self.program.cores;
        let core = match self.seen.get(&key) {
            Some(&core) => core,
            None => {
                if self.seen.len() >= SEEN {
                    self.seen.clear();
                }
                cores.push(step);
                self.seen.insert(key, cores.len() - 1);
                cores.len() - 1
            }
        };
        self.program
            .slots
            .push([step.span.start, step.span.end, core]);
    }

    pub fn finish(mut self) -> Program {
        self.program.slots.shrink_to_fit();
        self.program.cores.shrink_to_fit();
        self.program
    }
}

/// The evaluation state after some layers. Cloning it is a checkpoint.
#[derive(Clone, Debug)]
pub(crate) struct Engine {
    /// Shared, so that a checkpoint costs a few words, not a copy of the steps.
    steps: Arc<Program>,
    /// The live positions; `None` until a one-time instruction is spent (until then
    /// position `c` is followed by `c + 1`, and a template without `!` costs nothing here).
    links: Option<Box<Links>>,
    cursor: usize,
    /// The walks over dummies remembered; `None` until the first long one.
    walks: Option<Box<Walks>>,
    /// How many one-time instructions are spent.
    spent: usize,
    base: f64,
    seed: u64,
    // The current range (section 3).
    zs: f64,
    ze: f64,
    a0: f64,
    d: f64,
    joint: Joint,
    flipped: bool,
    fill: Fill,
    governing: Option<Span>,
    /// The instruction whose runs are left, and how many.
    current: usize,
    runs_left: u64,
}

impl Engine {
    pub fn new(template: &Template, model: &Model, options: Options) -> Engine {
        let mut program = ProgramBuilder::with_capacity(template.instructions.len());
        for i in &template.instructions {
            program.push(Step::new(i, model));
        }
        Engine::from_program(program.finish(), options)
    }

    pub fn from_program(program: Program, options: Options) -> Engine {
        let steps = Arc::new(program);
        Engine {
            links: None,
            cursor: 0,
            walks: None,
            spent: 0,
            steps,
            base: finite(options.base),
            seed: options.seed,
            // The empty range before layer 0 ends at b[0] = 0.
            zs: 0.0,
            ze: 0.0,
            a0: 0.0,
            d: 0.0,
            joint: Joint::Linear,
            flipped: false,
            fill: Fill::Sparse,
            governing: None,
            current: 0,
            runs_left: 0,
        }
    }

    /// The layer the cursor stands on. Layers must come bottom to top, one by one.
    // Always inlined into the loops of `Layers`: the state then lives in registers, which
    // halves the cost of a layer (measured: ~28 → ~11 ns) against a call per layer.
    #[inline(always)]
    pub fn layer(&mut self, at: &Cursor, model: &Model) -> Layer {
        let (bottom, top) = (at.bottom, at.top);
        if (bottom + top) / 2.0 > self.ze + TIE {
            self.zs = bottom;
            if self.runs_left > 0 {
                // Section 6: the run plays again, measured afresh from here, same a0 and d.
                self.runs_left -= 1;
                let extent = self
                    .steps
                    .get(self.current)
                    .map_or(Extent::OneLayer, |s| s.extent());
                self.ze = measure(extent, at, model);
            } else {
                self.start_range(at, model);
            }
        }
        let progress = if self.ze > self.zs {
            let p = (top - self.zs) / (self.ze - self.zs);
            // Heights are finite and bounded, so NaN cannot arise; the guard costs nothing.
            if p.is_nan() { 0.0 } else { p.clamp(0.0, 1.0) }
        } else {
            1.0
        };
        let p = if self.flipped {
            1.0 - progress
        } else {
            progress
        };
        let seed = self.seed;
        let s = shape(self.joint, p, self.flipped, || random::unit(seed, at.index));
        Layer {
            index: at.index,
            bottom,
            top,
            angle: finite(self.base + self.a0 + self.d * s),
            fill: self.fill,
            instruction: self.governing,
        }
    }

    /// Section 3 step 1 without runs left: this layer alone, then a walk.
    #[inline]
    fn start_range(&mut self, at: &Cursor, model: &Model) {
        self.ze = at.top;
        self.fill = Fill::Sparse;
        self.governing = None;
        self.runs_left = 0;
        if self.all_spent() {
            // Everything is spent: the layer holds. Keeping the previous range's shape and
            // flip over this one-layer range shows exactly `a0 + d × shape(end)`.
            return;
        }
        self.joint = Joint::Linear;
        self.flipped = false;
        let start = self.cursor;
        let chain = if self.steps.at(start).dummy {
            let remembered = self.walks.as_ref().and_then(|w| w.get(start, self.spent));
            remembered.unwrap_or_else(|| self.walk_dummies(start))
        } else {
            // The common walk: one instruction that sets a range.
            Chain {
                dummies: None,
                then: Then::SetUp(start),
            }
        };
        if let Some(effect) = chain.dummies {
            self.a0 = finite(match effect.reset {
                Some(alpha) => alpha + effect.offset,
                None => self.a0 + self.d + effect.offset,
            });
            self.d = effect.d;
            self.governing = self.steps.get(effect.last).map(|s| s.span);
        }
        match chain.then {
            Then::SetUp(c) => {
                self.set_up(c, at, model);
                if !self.all_spent() {
                    self.cursor = self.next(c);
                }
            }
            Then::Stop(c) => self.cursor = c,
            Then::Exhausted => {}
        }
    }

    /// Walks from `start` (live) over the dummies (section 4), spending the one-time ones,
    /// and returns their combined effect and how the walk ends. Remembers a long walk that
    /// spent no dummy, since the same walk will then happen again.
    fn walk_dummies(&mut self, start: usize) -> Chain {
        let spent_before = self.spent;
        let mut dummies: Option<Dummies> = None;
        // Section 4's "already set up" rule, which makes every walk end, without marking
        // positions: the walk follows the cycle of live positions, and the dummies it has
        // set up and left live form an arc of that cycle, so the first position it comes
        // back to is the first of them.
        let mut first_kept: Option<usize> = None;
        let mut crossed = 0usize;
        let mut c = start;
        let then = loop {
            // `c` is live here.
            if first_kept == Some(c) {
                break Then::Stop(c);
            }
            let step = self.steps.at(c);
            if !step.dummy {
                break Then::SetUp(c);
            }
            crossed += 1;
            // Each dummy commits (`a0 += d`), then sets `a0` (absolute) or `d` (relative).
            let effect = dummies.get_or_insert(Dummies {
                reset: None,
                offset: 0.0,
                d: 0.0,
                last: c,
            });
            if effect.last != c {
                // The commit of a `d` this walk set; the first commit adds the outer `d`.
                effect.offset = finite(effect.offset + effect.d);
            }
            effect.last = c;
            if step.relative {
                effect.d = step.alpha;
            } else {
                *effect = Dummies {
                    reset: Some(step.alpha),
                    offset: 0.0,
                    d: 0.0,
                    last: c,
                };
            }
            if step.one_time {
                self.spend(c);
                if self.all_spent() {
                    break Then::Exhausted;
                }
            } else if first_kept.is_none() {
                first_kept = Some(c);
            }
            c = self.next(c);
            // After a dummy the walk goes on, but not past the wrap to a live first position.
            if c == 0 {
                break Then::Stop(c);
            }
        };
        let chain = Chain { dummies, then };
        if self.spent == spent_before && crossed >= REMEMBERED_WALK {
            let n = self.steps.len();
            self.walks
                .get_or_insert_with(|| Box::new(Walks::new(n)))
                .remember(start, spent_before, chain);
        }
        chain
    }

    /// Sets up the instruction (not a dummy) at position `c`: commits the previous turn
    /// and starts the instruction's range.
    #[inline]
    fn set_up(&mut self, c: usize, at: &Cursor, model: &Model) {
        let step = self.steps.at(c);
        self.a0 = finite(self.a0 + self.d);
        self.d = 0.0;
        if step.one_time {
            self.spend(c);
        }
        self.governing = Some(step.span);
        if step.relative {
            self.d = step.turn;
        } else {
            self.a0 = step.alpha;
        }
        self.joint = step.joint;
        self.flipped = step.flipped;
        self.fill = step.fill;
        self.current = c;
        self.runs_left = step.runs.saturating_sub(1);
        self.ze = measure(step.extent(), at, model);
    }

    /// The angle and fill of each step when the template is a plain cycle: every step
    /// absolute, one layer, run once, never spent, not a dummy, not flipped and not
    /// random. Then every layer starts a range (a layer is at least 0.001 mm, far more
    /// than `TIE`), the steps come in turn, and layer `k` takes step `k mod n` whatever
    /// came before: `a0` is the step's angle, `d` is 0 and the progress is 1, so its
    /// angle is exactly what `layer` computes, `finite(base + alpha + 0 · shape(1))`.
    pub(crate) fn plain_cycle(&self) -> Option<Vec<(f64, Fill)>> {
        let n = self.steps.len();
        if n == 0 {
            return None;
        }
        (0..n)
            .map(|c| {
                let step = self.steps.at(c);
                let plain = !step.relative
                    && !step.dummy
                    && !step.one_time
                    && step.runs == 1
                    && !step.flipped
                    && matches!(step.extent_kind, ExtentKind::OneLayer)
                    && !matches!(step.joint, Joint::Random | Joint::PseudoRandom);
                plain.then(|| {
                    let s = shape(step.joint, 1.0, false, || 0.0);
                    (finite(self.base + step.alpha + 0.0 * s), step.fill)
                })
            })
            .collect()
    }

    fn all_spent(&self) -> bool {
        self.spent == self.steps.len()
    }

    fn spend(&mut self, c: usize) {
        let len = self.steps.len();
        self.links
            .get_or_insert_with(|| Box::new(Links::new(len)))
            .remove(c);
        self.spent += 1;
    }

    /// The live position after `c` (or the one a just-spent `c` was followed by).
    #[inline]
    fn next(&self, c: usize) -> usize {
        match &self.links {
            Some(links) => links.next(c),
            None if c + 1 < self.steps.len() => c + 1,
            None => 0,
        }
    }
}

/// The live (not spent) positions form a circular doubly linked list: a walk skips spent
/// one-time instructions in O(1). A removed position keeps its `next`, so the walk can
/// still step off an instruction it has just spent. In `u32` while positions fit (8 bytes
/// an instruction, against 16 in `usize`: the links of a template full of `!` are most of
/// what evaluating it costs).
#[derive(Clone, Debug)]
enum Links {
    Narrow { next: Vec<u32>, prev: Vec<u32> },
    Wide { next: Vec<usize>, prev: Vec<usize> },
}

impl Links {
    fn new(n: usize) -> Links {
        match u32::try_from(n) {
            Ok(m) => Links::Narrow {
                next: (0..m).map(|c| (c + 1) % m).collect(),
                prev: (0..m).map(|c| (c + m - 1) % m).collect(),
            },
            Err(_) => Links::Wide {
                next: (0..n).map(|c| (c + 1) % n).collect(),
                prev: (0..n).map(|c| (c + n - 1) % n).collect(),
            },
        }
    }

    #[inline]
    fn next(&self, c: usize) -> usize {
        match self {
            Links::Narrow { next, .. } => next[c] as usize,
            Links::Wide { next, .. } => next[c],
        }
    }

    fn remove(&mut self, c: usize) {
        match self {
            Links::Narrow { next, prev } => {
                let (p, n) = (prev[c], next[c]);
                next[p as usize] = n;
                prev[n as usize] = p;
            }
            Links::Wide { next, prev } => {
                let (p, n) = (prev[c], next[c]);
                next[p] = n;
                prev[n] = p;
            }
        }
    }
}

/// A walk is remembered when it crosses at least this many dummies: a shorter one costs
/// about what looking it up does, and each remembered walk costs memory.
const REMEMBERED_WALK: usize = 4;

/// The walks over dummies remembered (section 4). A walk is a function of the cursor and
/// of which instructions are live, so a long run of dummies is crossed once, not on every
/// layer.
#[derive(Clone, Debug)]
struct Walks {
    /// `index[c]`: 1 + the entry of the walk from position `c`, or 0. Allocated zeroed, so
    /// its pages cost nothing until a walk from one of their positions is remembered
    /// (a long template on a short model touches few).
    index: Vec<u32>,
    /// The remembered walks, each with the `spent` count it is valid for (it is replaced
    /// when the walk from its position is taken again after a spend).
    entries: Vec<(usize, Chain)>,
}

impl Walks {
    fn new(n: usize) -> Walks {
        Walks {
            index: vec![0; n],
            entries: Vec::new(),
        }
    }

    /// The walk from `start`, if it is remembered for `spent`.
    #[inline]
    fn get(&self, start: usize, spent: usize) -> Option<Chain> {
        let entry = (*self.index.get(start)? as usize).checked_sub(1)?;
        let &(valid, chain) = self.entries.get(entry)?;
        (valid == spent).then_some(chain)
    }

    fn remember(&mut self, start: usize, spent: usize, chain: Chain) {
        let Some(slot) = self.index.get_mut(start) else {
            return;
        };
        match (*slot as usize).checked_sub(1) {
            Some(entry) => {
                if let Some(kept) = self.entries.get_mut(entry) {
                    *kept = (spent, chain);
                }
            }
            // Past 4e9 remembered walks (never, in memory), walks are walked again.
            None => {
                if let Ok(next) = u32::try_from(self.entries.len() + 1) {
                    self.entries.push((spent, chain));
                    *slot = next;
                }
            }
        }
    }
}

/// What one walk does (section 4): cross some dummies, then set up an instruction or stop.
#[derive(Clone, Copy, Debug)]
struct Chain {
    dummies: Option<Dummies>,
    then: Then,
}

/// The combined effect of the dummies a walk sets up, as a function of the `(a0, d)` it
/// finds: `a0` becomes `reset + offset`, or `a0 + d + offset` when no dummy was absolute;
/// `d` becomes `d`. Summing the dummies' turns first (instead of one commit at a time)
/// can differ in the last bits only.
#[derive(Clone, Copy, Debug)]
struct Dummies {
    /// The angle of the last absolute dummy, which discards everything before it.
    reset: Option<f64>,
    /// The turns committed after the reset (or after the outer `a0 + d`).
    offset: f64,
    /// The last dummy's relative angle, left uncommitted (0 if it was absolute).
    d: f64,
    /// The position of the last dummy: it governs a layer the walk sets no range for.
    last: usize,
}

#[derive(Clone, Copy, Debug)]
enum Then {
    /// Set up the instruction at this position (not a dummy); the walk ends after it.
    SetUp(usize),
    /// Stop with the cursor here.
    Stop(usize),
    /// Every instruction is spent.
    Exhausted,
}

/// The end `ze` of a range of the given extent that starts at the cursor's layer.
fn measure(extent: Extent, at: &Cursor, model: &Model) -> f64 {
    match extent {
        Extent::OneLayer => at.top,
        Extent::Length(length) => finite(at.bottom + length),
        Extent::Layers(n) => {
            let layers = model.len() as f64;
            let j = at.index as f64 + n - 1.0;
            if j >= layers - 1.0 {
                // Past the top, standard layers extend the range (`j − L`, as OrcaSlicer
                // counts; SEMANTICS.md section 3).
                finite(model.last_top() + (j - layers).max(0.0) * model.layer_height())
            } else {
                // `j < L - 1` here, so the cast is exact.
                model.top_at(at, j as usize)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_step_is_small() {
        // What a huge template costs the evaluator per instruction (see eval::parse_layers).
        assert!(std::mem::size_of::<super::Step>() <= 56);
    }
}
