//! The codes of the compat lint's findings (a leaf: the lint and its rules report them).

use crate::dialect::{HANGS, NAN, UNDEFINED};

/// OrcaSlicer's angle or fill differs from rotlang's on some layer of the model.
pub const DIFFERS: &str = "orcaslicer::differs";
/// `0 90`: OrcaSlicer reads a plain list only at commas (`0`).
pub const SPACE_SEPARATED_LIST: &str = "orcaslicer::space-separated-list";
/// `α:β` or `ℍ:ℕ`: OrcaSlicer reads the first number only.
pub const FRACTION: &str = "orcaslicer::fraction";
/// `D S O M R`: OrcaSlicer has no solid signs; the layers stay sparse.
pub const SOLID_SIGN: &str = "orcaslicer::solid-sign";
/// `+10/B`: OrcaSlicer reads no count after a joint's `B`/`T`.
pub const SHELLS_AFTER_JOINT: &str = "orcaslicer::shells-after-joint";
/// `+7!B`: OrcaSlicer ignores everything after a `!` that follows the angle.
pub const TEXT_AFTER_BANG: &str = "orcaslicer::text-after-bang";
/// `, +10`, `10,,20`: OrcaSlicer reads an empty instruction as 0°.
pub const EMPTY_INSTRUCTION: &str = "orcaslicer::empty-instruction";
/// `10!, 20`: in a plain list OrcaSlicer ignores `!`, `B` and `T`.
pub const IGNORED_IN_LIST: &str = "orcaslicer::ignored-in-list";
/// `~`, `^`: OrcaSlicer's random numbers differ from run to run.
pub const RANDOM: &str = "orcaslicer::random";
/// The codes of the findings that hold on every model (the rule-based ones).
pub const RULES: [&str; 8] = [
    SPACE_SEPARATED_LIST,
    FRACTION,
    SOLID_SIGN,
    SHELLS_AFTER_JOINT,
    TEXT_AFTER_BANG,
    EMPTY_INSTRUCTION,
    IGNORED_IN_LIST,
    RANDOM,
];

/// Every code the lint can report.
pub const CODES: [&str; 12] = [
    DIFFERS,
    HANGS,
    UNDEFINED,
    NAN,
    SPACE_SEPARATED_LIST,
    FRACTION,
    SOLID_SIGN,
    SHELLS_AFTER_JOINT,
    TEXT_AFTER_BANG,
    EMPTY_INSTRUCTION,
    IGNORED_IN_LIST,
    RANDOM,
];
