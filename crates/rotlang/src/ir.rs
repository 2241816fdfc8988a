//! The typed IR of a template: what the evaluator, formatter, linter and language server
//! consume. Every node keeps its byte span into the template text.

use crate::diagnostic::Span;

/// A value with the span of the text it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spanned<T> {
    /// The value.
    pub value: T,
    /// Where it was written.
    pub span: Span,
}

impl<T> Spanned<T> {
    /// `value`, written at `span`.
    pub fn new(value: T, span: Span) -> Self {
        Spanned { value, span }
    }
}

/// Which setting the template belongs to. Solid signs are legal only in sparse templates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Target {
    /// `sparse_infill_rotate_template`: solid signs are allowed.
    #[default]
    Sparse,
    /// `solid_infill_rotate_template`: every layer is solid already.
    Solid,
}

/// A whole template: its instructions in order. An empty list means `0`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Template {
    /// The instructions, in the order written.
    pub instructions: Vec<Instruction>,
}

/// One instruction:
/// `[±]α[*ℤ | ! | *!][solid][joint][-][ℕ | B | T][unit][* | !]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Instruction {
    /// The whole instruction's text.
    pub span: Span,
    /// Absent in the forms without an angle (`B!`, `#14`, `M3`): a relative 0.
    pub angle: Option<Angle>,
    /// `*ℤ` with ℤ ≥ 1: how many times the instruction runs in a row.
    pub repeat: Option<Spanned<u64>>,
    /// `*` or `*0` (right after the angle, or trailing): a dummy that sets no range.
    pub dummy: Option<Span>,
    /// The first `!`: the instruction runs once for the whole model.
    pub one_time: Option<Span>,
    /// The solid sign (`D S O M R`): the layers it governs are solid.
    pub solid: Option<Spanned<Solid>>,
    /// The joint (`L l N n ...`): the shape of the turn over the count.
    pub joint: Option<Spanned<Joint>>,
    /// The `-` before the count: the shape runs from the end angle back to the start.
    pub flip: Option<Span>,
    /// The count: how many layers (or how much height) the instruction takes.
    pub count: Option<Count>,
}

impl Instruction {
    /// The angle in degrees (0 when absent), signed for relative angles.
    pub fn degrees(&self) -> f64 {
        self.angle.as_ref().map_or(0.0, Angle::degrees)
    }

    /// Relative (a turn) or absolute (a direction). No angle means a relative 0.
    pub fn is_relative(&self) -> bool {
        self.angle.as_ref().is_none_or(|a| a.sign.is_some())
    }

    /// Whether it is a dummy (`*`): it sets an angle but takes no layers.
    pub fn is_dummy(&self) -> bool {
        self.dummy.is_some()
    }

    /// Whether it runs once for the whole model (`!`).
    pub fn is_one_time(&self) -> bool {
        self.one_time.is_some()
    }

    /// How many times the instruction runs in a row (1 unless `*ℤ`).
    pub fn runs(&self) -> u64 {
        self.repeat.map_or(1, |r| r.value.max(1))
    }

    /// Whether the shape runs backwards (the `-` before the count).
    pub fn is_flipped(&self) -> bool {
        self.flip.is_some()
    }

    /// The shape of the turn; `Linear` when no joint is written.
    pub fn shape(&self) -> Joint {
        self.joint.map_or(Joint::Linear, |j| j.value)
    }

    /// The kind of fill of this instruction's layers.
    pub fn fill(&self) -> Fill {
        self.solid.map_or(Fill::Sparse, |s| s.value.fill())
    }
}

/// The sign of a relative angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// `+`: a turn counter-clockwise.
    Plus,
    /// `-`: a turn clockwise.
    Minus,
}

/// An angle as written: a turn (signed) or a direction.
#[derive(Clone, Debug, PartialEq)]
pub struct Angle {
    /// Where it was written.
    pub span: Span,
    /// Present: a relative angle (a turn). Absent: an absolute direction.
    pub sign: Option<Sign>,
    /// Its magnitude as written.
    pub value: AngleValue,
}

impl Angle {
    /// Degrees, with the sign applied.
    pub fn degrees(&self) -> f64 {
        let d = self.value.degrees();
        if self.sign == Some(Sign::Minus) {
            -d
        } else {
            d
        }
    }
}

/// The magnitude of an angle, in the form it was written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AngleValue {
    /// `α`
    Degrees(f64),
    /// `α%`: a percentage of 360°.
    Percent(f64),
    /// `α:β`: the fraction α/β of 360° (β ≠ 0).
    Fraction(f64, f64),
}

impl AngleValue {
    /// Degrees (not signed).
    pub fn degrees(self) -> f64 {
        match self {
            AngleValue::Degrees(d) => d,
            AngleValue::Percent(p) => p * 3.6,
            AngleValue::Fraction(a, b) => a / b * 360.0,
        }
    }
}

/// A count: how far the instruction reaches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Count {
    /// Where it was written.
    pub span: Span,
    /// What it counts.
    pub kind: CountKind,
}

/// What a count counts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CountKind {
    /// `ℕ`: a number of layers (may be a decimal; the evaluator floors it).
    Layers(f64),
    /// `B`: the bottom shell layer count.
    Bottom,
    /// `T`: the top shell layer count.
    Top,
    /// `ℕ` with a length unit.
    Length {
        /// The number.
        value: f64,
        /// Its unit.
        unit: Unit,
    },
    /// `ℍ:ℕ`: the fraction ℍ/ℕ of the object height (ℕ ≠ 0).
    HeightFraction {
        /// ℍ.
        num: f64,
        /// ℕ.
        den: f64,
    },
}

/// The unit of a length count.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Unit {
    /// `mm`
    Millimetre,
    /// `cm` (10 mm)
    Centimetre,
    /// `m` (1000 mm)
    Metre,
    /// `'` (304.8 mm)
    Foot,
    /// `"` (25.4 mm)
    Inch,
    /// `#`: standard layers (ℕ × h)
    StandardLayers,
    /// `%`: percent of the object height
    PercentOfHeight,
}

impl Unit {
    /// Its symbol as written in templates (`mm`, `#`, `%`, ...).
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::Millimetre => "mm",
            Unit::Centimetre => "cm",
            Unit::Metre => "m",
            Unit::Foot => "'",
            Unit::Inch => "\"",
            Unit::StandardLayers => "#",
            Unit::PercentOfHeight => "%",
        }
    }

    /// The unit written `s`, if any.
    pub fn from_symbol(s: &str) -> Option<Unit> {
        Some(match s {
            "mm" => Unit::Millimetre,
            "cm" => Unit::Centimetre,
            "m" => Unit::Metre,
            "'" => Unit::Foot,
            "\"" => Unit::Inch,
            "#" => Unit::StandardLayers,
            "%" => Unit::PercentOfHeight,
            _ => return None,
        })
    }

    /// Millimetres per unit for the fixed units; `None` for `#` and `%`, which depend on
    /// the model.
    pub fn millimetres(self) -> Option<f64> {
        match self {
            Unit::Millimetre => Some(1.0),
            Unit::Centimetre => Some(10.0),
            Unit::Metre => Some(1000.0),
            Unit::Foot => Some(304.8),
            Unit::Inch => Some(25.4),
            Unit::StandardLayers | Unit::PercentOfHeight => None,
        }
    }

    /// What it means, in words (for hovers and `rotlang explain`).
    pub fn meaning(self) -> &'static str {
        match self {
            Unit::Millimetre => "millimetres",
            Unit::Centimetre => "centimetres (10 mm)",
            Unit::Metre => "metres (1000 mm)",
            Unit::Foot => "feet (304.8 mm)",
            Unit::Inch => "inches (25.4 mm)",
            Unit::StandardLayers => "standard layers (ℕ × layer height)",
            Unit::PercentOfHeight => "percent of the object height",
        }
    }

    /// Every unit.
    pub const ALL: [Unit; 7] = [
        Unit::Millimetre,
        Unit::Centimetre,
        Unit::Metre,
        Unit::Foot,
        Unit::Inch,
        Unit::StandardLayers,
        Unit::PercentOfHeight,
    ];
}

/// The shape of a turn across its range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Joint {
    /// `/` (also the shape when no joint is written)
    Linear,
    /// `N`
    SineVertical,
    /// `n`
    SineVerticalLazy,
    /// `Z`
    SineHorizontal,
    /// `z`
    SineHorizontalLazy,
    /// `$`
    Arcsine,
    /// `L`
    QuarterCircleHV,
    /// `l`
    QuarterCircleVH,
    /// `U`
    Square,
    /// `u`
    SquareInverse,
    /// `Q`
    Cubic,
    /// `q`
    CubicInverse,
    /// `~`
    Random,
    /// `^`
    PseudoRandom,
    /// `|`
    Middle,
    /// `#`
    Step,
}

impl Joint {
    /// Every joint.
    pub const ALL: [Joint; 16] = [
        Joint::Linear,
        Joint::SineVertical,
        Joint::SineVerticalLazy,
        Joint::SineHorizontal,
        Joint::SineHorizontalLazy,
        Joint::Arcsine,
        Joint::QuarterCircleHV,
        Joint::QuarterCircleVH,
        Joint::Square,
        Joint::SquareInverse,
        Joint::Cubic,
        Joint::CubicInverse,
        Joint::Random,
        Joint::PseudoRandom,
        Joint::Middle,
        Joint::Step,
    ];

    /// Its letter in templates.
    pub fn symbol(self) -> char {
        match self {
            Joint::Linear => '/',
            Joint::SineVertical => 'N',
            Joint::SineVerticalLazy => 'n',
            Joint::SineHorizontal => 'Z',
            Joint::SineHorizontalLazy => 'z',
            Joint::Arcsine => '$',
            Joint::QuarterCircleHV => 'L',
            Joint::QuarterCircleVH => 'l',
            Joint::Square => 'U',
            Joint::SquareInverse => 'u',
            Joint::Cubic => 'Q',
            Joint::CubicInverse => 'q',
            Joint::Random => '~',
            Joint::PseudoRandom => '^',
            Joint::Middle => '|',
            Joint::Step => '#',
        }
    }

    /// The joint written `c`, if any.
    pub fn from_symbol(c: char) -> Option<Joint> {
        Joint::ALL.into_iter().find(|j| j.symbol() == c)
    }

    /// Plain words for hovers and completion.
    pub fn meaning(self) -> &'static str {
        match self {
            Joint::Linear => "linearly",
            Joint::SineVertical => "along a sine (vertical connection)",
            Joint::SineVerticalLazy => "along a lazy sine (vertical connection)",
            Joint::SineHorizontal => "along a sine (horizontal connection)",
            Joint::SineHorizontalLazy => "along a lazy sine (horizontal connection)",
            Joint::Arcsine => "along an arcsine",
            Joint::QuarterCircleHV => "along a quarter circle (horizontal to vertical)",
            Joint::QuarterCircleVH => "along a quarter circle (vertical to horizontal)",
            Joint::Square => "along a square curve",
            Joint::SquareInverse => "along an inverse square curve",
            Joint::Cubic => "along a cubic curve",
            Joint::CubicInverse => "along an inverse cubic curve",
            Joint::Random => "to a random angle on each layer",
            Joint::PseudoRandom => "linearly with pseudorandom jitter",
            Joint::Middle => "in one step at the middle angle",
            Joint::Step => "in one step at the start of the range",
        }
    }

    /// Whether the shape draws random numbers.
    pub fn is_random(self) -> bool {
        matches!(self, Joint::Random | Joint::PseudoRandom)
    }
}

/// Solid signs (sparse templates only).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Solid {
    /// `D`: the sparse pattern at 100% density
    Dense,
    /// `S`: the profile's solid infill pattern
    Solid,
    /// `O`: concentric
    Concentric,
    /// `M`: monotonic
    Monotonic,
    /// `R`: rectilinear
    Rectilinear,
}

impl Solid {
    /// Every solid sign.
    pub const ALL: [Solid; 5] = [
        Solid::Dense,
        Solid::Solid,
        Solid::Concentric,
        Solid::Monotonic,
        Solid::Rectilinear,
    ];

    /// Its letter in templates.
    pub fn symbol(self) -> char {
        match self {
            Solid::Dense => 'D',
            Solid::Solid => 'S',
            Solid::Concentric => 'O',
            Solid::Monotonic => 'M',
            Solid::Rectilinear => 'R',
        }
    }

    /// The solid sign written `c`, if any.
    pub fn from_symbol(c: char) -> Option<Solid> {
        Solid::ALL.into_iter().find(|s| s.symbol() == c)
    }

    /// The kind of fill it gives its layers.
    pub fn fill(self) -> Fill {
        match self {
            Solid::Dense => Fill::Dense,
            Solid::Solid => Fill::Solid,
            Solid::Concentric => Fill::Concentric,
            Solid::Monotonic => Fill::Monotonic,
            Solid::Rectilinear => Fill::Rectilinear,
        }
    }

    /// What it means, in words (for hovers and `rotlang explain`).
    pub fn meaning(self) -> &'static str {
        match self {
            Solid::Dense => "solid layers of the sparse pattern at 100% density",
            Solid::Solid => "solid layers of the profile's solid infill pattern",
            Solid::Concentric => "concentric solid layers",
            Solid::Monotonic => "monotonic solid layers",
            Solid::Rectilinear => "rectilinear solid layers",
        }
    }
}

/// The kind of fill a layer gets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Fill {
    /// Sparse infill, the profile's pattern.
    #[default]
    Sparse,
    /// Solid infill in the sparse pattern (`D`).
    Dense,
    /// Solid infill in the profile's solid pattern (`S`).
    Solid,
    /// Concentric solid infill (`O`).
    Concentric,
    /// Monotonic solid infill (`M`).
    Monotonic,
    /// Rectilinear solid infill (`R`).
    Rectilinear,
}

impl Fill {
    /// The name used in JSON output and the conformance corpus.
    pub fn name(self) -> &'static str {
        match self {
            Fill::Sparse => "sparse",
            Fill::Dense => "dense",
            Fill::Solid => "solid",
            Fill::Concentric => "concentric",
            Fill::Monotonic => "monotonic",
            Fill::Rectilinear => "rectilinear",
        }
    }
}
