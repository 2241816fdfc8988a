//! Every diagnostic code the library emits, documented: what `rotlang explain CODE` prints.
//!
//! A test (`explain::tests`) reads the library's sources and fails when a code is emitted
//! but not listed here, and parses every example to check it reports its code.

/// One diagnostic code, documented.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CodeDoc {
    /// The stable code, e.g. `rotlang::unknown-sign`.
    pub code: &'static str,
    /// `error` or `warning`.
    pub severity: &'static str,
    /// One line: what is wrong.
    pub summary: &'static str,
    /// Why it is a problem, in a few sentences.
    pub explanation: &'static str,
    /// A template that gets this diagnostic.
    pub example: &'static str,
    /// What to write instead.
    pub fix: &'static str,
}

/// The documentation of a code (with or without its `rotlang::` prefix).
pub fn code(code: &str) -> Option<&'static CodeDoc> {
    let code = code.trim();
    CODES
        .iter()
        .find(|d| d.code == code || d.code.strip_prefix("rotlang::") == Some(code))
}

/// Every documented code, sorted by code.
pub fn codes() -> &'static [CodeDoc] {
    CODES
}

const fn doc(
    code: &'static str,
    severity: &'static str,
    summary: &'static str,
    explanation: &'static str,
    example: &'static str,
    fix: &'static str,
) -> CodeDoc {
    CodeDoc {
        code,
        severity,
        summary,
        explanation,
        example,
        fix,
    }
}

const E: &str = "error";
const W: &str = "warning";

static CODES: &[CodeDoc] = &[
    doc(
        "rotlang::angle-out-of-range",
        W,
        "an absolute angle outside 0–360°",
        "An angle without a sign is a direction. Directions repeat every 360°, so `400` is the same as `40`; a value outside the circle usually means a sign was forgotten.",
        "400",
        "Write the direction within 0–360 (`40`), or a turn with a sign (`+400`).",
    ),
    doc(
        "rotlang::bad-fraction",
        E,
        "a fraction `a:b` with a missing or extra `:`",
        "`a:b` means a/b: a share of a full turn as an angle (`1:4` is 90°), or of the object height as a count. It needs one number on each side of one `:`.",
        "+1:2:3",
        "Write one fraction: `+1:4`, or `+30/1:2`.",
    ),
    doc(
        "rotlang::bad-number",
        E,
        "a number written in a way the language does not read",
        "Numbers are digits with an optional fractional part and exponent: `22.5`, `1e3`. Two decimal points or an exponent without digits are not numbers.",
        "1.2.3",
        "Write one decimal point (`1.2`) and digits after an exponent (`1e3`).",
    ),
    doc(
        "rotlang::bracket",
        E,
        "a bracket around a template or an instruction",
        "A template is instructions separated by commas or spaces, with nothing around them. Brackets, as in a list or a formula, are not part of the language.",
        "[0, 90]",
        "Remove the brackets: `0, 90`.",
    ),
    doc(
        "rotlang::byte-order-mark",
        E,
        "an invisible byte-order mark (U+FEFF) inside a template",
        "Some editors write a byte-order mark at the start of a file. At the very start of a template it is skipped; anywhere else it is an invisible character in an instruction.",
        "0, \u{feff}90",
        "Remove the character; save files as UTF-8 without BOM.",
    ),
    doc(
        "rotlang::decimal-comma",
        E,
        "a decimal comma, read as a separator",
        "A comma separates instructions, so `1,5mm` is the two instructions `1` and `5mm`. Decimals use a dot.",
        "+30/1,5mm",
        "Write a decimal point: `+30/1.5mm`.",
    ),
    doc(
        "rotlang::degree-sign",
        E,
        "an angle written with `°` or `deg`",
        "Every angle is in degrees already; the language has no unit of angle.",
        "+30°",
        "Remove the degree sign: `+30`.",
    ),
    doc(
        "rotlang::dummy-and-repeat",
        E,
        "an instruction that is both a dummy `*` and repeated `*ℤ`",
        "A dummy sets an angle without taking layers; a repeat count runs the instruction several times. Together they mean nothing.",
        "+30*2*",
        "Keep one: `+30*` (a dummy) or `+30*2` (twice).",
    ),
    doc(
        "rotlang::dummy-ignores-range",
        W,
        "a dummy with a shape or count, which it ignores",
        "A dummy (`*`) takes no layers, so a joint, flip or count after it has nothing to act on.",
        "+30*/5",
        "Remove the `*` to turn over the range (`+30/5`), or remove the range (`+30*`).",
    ),
    doc(
        "rotlang::dummy-without-effect",
        W,
        "a dummy that never changes the angle",
        "A relative dummy of 0° takes no layer and adds nothing to the next instruction's start angle.",
        "+0*",
        "Remove it, or give it an angle: `30*` or `+30*`.",
    ),
    doc(
        "rotlang::duplicate-mark",
        W,
        "a runtime mark `!` or `*` written twice",
        "An instruction is one-time or not, a dummy or not: the second mark changes nothing.",
        "+30!/5!",
        "Remove the second mark: `+30!/5`.",
    ),
    doc(
        "rotlang::empty-instruction",
        W,
        "an empty instruction between separators",
        "Two commas in a row, a leading comma or a comma alone enclose nothing. OrcaSlicer reads an empty instruction as `0`; rotlang ignores it. One trailing comma (`0, 90,`) only ends the last instruction and is fine.",
        "10,,20",
        "Remove the extra comma: `10, 20`.",
    ),
    doc(
        "rotlang::flip-without-count",
        E,
        "a flip `-` with no count after it",
        "The flip reverses the shape over its range, so it needs the count that sets the range.",
        "+30/-",
        "Add a count (`+30/-5`) or remove the `-`.",
    ),
    doc(
        "rotlang::incomplete",
        E,
        "an instruction that ends too early",
        "The instruction stops where the grammar needs more, such as a number after a sign.",
        "+",
        "Complete the instruction (`+30`) or remove it.",
    ),
    doc(
        "rotlang::joint-on-absolute-angle",
        W,
        "a joint or flip on an absolute angle",
        "An angle without a sign is a constant direction over its range, so a shape (joint or flip) has nothing to shape.",
        "30/5",
        "For a turn over the range write a sign: `+30/5`; for a constant direction, drop the joint: `30`.",
    ),
    doc(
        "rotlang::leading-dot",
        E,
        "a number that starts with `.`",
        "Numbers are written with a digit before the decimal point.",
        "+.5",
        "Write a 0 before the dot: `+0.5`.",
    ),
    doc(
        "rotlang::look-alike-character",
        E,
        "a typographic or full-width character that looks like a sign",
        "Word processors and some keyboards replace `-` with `−` (minus) or `–` (dash), `*` with `×`, and so on. Templates are plain ASCII.",
        "\u{2212}30",
        "Type the ASCII character: `-30`.",
    ),
    doc(
        "rotlang::misplaced-number",
        E,
        "a number where none can stand",
        "After the angle, a number is a count and needs a joint, a flip, the angle's `%` or a `!` before it; after a unit nothing but `*` or `!` may follow.",
        "+30/5mm3",
        "Keep one count with its unit: `+30/5mm`.",
    ),
    doc(
        "rotlang::misplaced-sign",
        E,
        "a sign out of order in an instruction",
        "The parts of an instruction come in a fixed order: angle, runtime mark (`*`, `*ℤ`, `!`), solid sign (`D S O M R`), joint, flip `-`, count (`ℕ`, `B`, `T`), unit, trailing `*` or `!`.",
        "+30/5D",
        "Move the sign to its place: `+30D/5`.",
    ),
    doc(
        "rotlang::missing-separator",
        E,
        "two instructions with no separator between them",
        "A `+` can only begin an instruction, so `+10+20` is two instructions run together.",
        "+10+20",
        "Separate them with a comma: `+10, +20`.",
    ),
    doc(
        "rotlang::number-not-finite",
        E,
        "a number that is not finite (`inf`, `nan`, or too many digits)",
        "Angles, counts and lengths are finite decimal numbers.",
        "+inf",
        "Write a finite number such as `+30`.",
    ),
    doc(
        "rotlang::number-too-large",
        E,
        "a number beyond the accepted range",
        "Counts, lengths and repeats are at most 1e9, angles at most 1e9 degrees: no printer goes further, and larger numbers lose the fractions that matter.",
        "+30/2e9",
        "Use a sensible value: `+30/200`.",
    ),
    doc(
        "rotlang::quoted-template",
        E,
        "a template copied with its quotes",
        "The setting holds the template's text alone; quotes would be read as the units feet (`'`) and inches (`\"`).",
        "\"0, 90\"",
        "Remove the quotes: `0, 90`.",
    ),
    doc(
        "rotlang::repeat-after-joint",
        E,
        "a repeat count `*ℤ` at the end of an instruction",
        "A repeat count belongs right after the angle; at the end of an instruction only a trailing `*` (dummy) or `!` may stand. An instruction has at most one repeat count.",
        "+45/10*2",
        "Move the repeat count after the angle: `+45*2/10`.",
    ),
    doc(
        "rotlang::repeat-not-whole",
        E,
        "a repeat count that is not a whole number",
        "`*ℤ` runs the instruction ℤ times in a row, so ℤ is whole digits.",
        "+30*2.5",
        "Write a whole number: `+30*2`.",
    ),
    doc(
        "rotlang::solid-sign-in-solid-template",
        E,
        "a solid sign in a solid infill template",
        "Solid signs (`D S O M R`) put solid layers into sparse infill; in `solid_infill_rotate_template` every layer is solid already. (Only reported with `--target solid`.)",
        "+30S",
        "Remove the solid sign, or move the template to `sparse_infill_rotate_template`.",
    ),
    doc(
        "rotlang::space-after-joint",
        E,
        "a count cut off from its joint by a space",
        "A space ends an instruction, so in `+30/ 5cm` the instruction `+30/` has lost its count, and `5cm` (a length with no joint) cannot stand alone.",
        "+30/ 5cm",
        "Remove the space: `+30/5cm`.",
    ),
    doc(
        "rotlang::space-before-unit",
        E,
        "a unit cut off from its number by a space or a comma",
        "A space or comma ends an instruction, so the unit stands alone as an instruction it cannot be.",
        "+30/50 %",
        "Remove the space: `+30/50%`.",
    ),
    doc(
        "rotlang::space-splits-instruction",
        W,
        "a space splits what reads as one instruction into two",
        "A space separates instructions. `+30 /50%` and `+30/ 50%` are each two instructions: a turn of 30° in one layer, then an instruction of its own; `+30/ 50%` even sets the absolute direction 180° (50% of a turn). Both are legal, so this is a warning.",
        "+30/ 50%",
        "Remove the space: `+30/50%`; or, if two instructions are meant, separate them with a comma.",
    ),
    doc(
        "rotlang::too-many-diagnostics",
        E,
        "more diagnostics than are shown",
        "At most 100 diagnostics are reported per template; this entry counts the rest. It is an error when any of the shown ones is.",
        "x x x … (101 times)",
        "Fix the ones shown first; the rest are often the same mistake.",
    ),
    doc(
        "rotlang::trailing-dot",
        E,
        "a number that ends with `.`",
        "A decimal point needs digits after it.",
        "+10.",
        "Remove the dot (`+10`) or add digits (`+10.5`).",
    ),
    doc(
        "rotlang::two-counts",
        E,
        "an instruction with two counts",
        "An instruction has one count: a number, `B` (the bottom shell layer count) or `T` (the top shell layer count).",
        "+30/5B",
        "Keep one: `+30/5` or `+30/B`.",
    ),
    doc(
        "rotlang::two-joints",
        E,
        "an instruction with two joint signs",
        "An instruction has at most one shape.",
        "+30/N5",
        "Keep the shape you want (`+30N5`), or chain two instructions: `+15/5, +15N5`.",
    ),
    doc(
        "rotlang::two-signs",
        E,
        "an angle with two signs",
        "`+30` turns counter-clockwise, `-30` clockwise; an angle has one sign.",
        "+-30",
        "Keep one sign: `-30`.",
    ),
    doc(
        "rotlang::two-solid-signs",
        E,
        "an instruction with two solid signs",
        "Each layer gets one kind of fill, so an instruction has at most one solid sign.",
        "+30DS",
        "Keep one: `+30D` or `+30S`.",
    ),
    doc(
        "rotlang::two-units",
        E,
        "a count with two length units",
        "A count is a number and at most one unit.",
        "+30/5mmcm",
        "Keep one unit: `+30/5mm`.",
    ),
    doc(
        "rotlang::unexpected-character",
        E,
        "a character that is not part of the language",
        "Templates are digits and the signs `+ - % : * ! / # | $ ~ ^ ' \"`, the letters `D S O M R N n Z z L l U u Q q B T m c`, separated by commas or spaces.",
        "0; 90",
        "Remove the character, or use a comma between instructions: `0, 90`.",
    ),
    doc(
        "rotlang::unit-after-angle",
        E,
        "a length unit right after an angle",
        "A length says how far a turn takes, so it is a count after a joint or a flip: `+30/10mm`. Right after the angle there is no count for it to belong to.",
        "+30mm",
        "Put a joint and a count before the unit: `+30/10mm`.",
    ),
    doc(
        "rotlang::unit-after-fraction",
        E,
        "a unit after a fraction `a:b`",
        "A fraction is already a share: of a full turn as an angle, of the object height as a count. A unit after it means nothing.",
        "+1:4%",
        "Write the fraction alone (`+1:4`) or a number with its unit (`+25%`).",
    ),
    doc(
        "rotlang::unit-after-shell-count",
        E,
        "a unit after `B` or `T`",
        "`B` and `T` are numbers of layers (the bottom and top shell layer counts) and take no unit.",
        "+30/Bmm",
        "Remove the unit: `+30/B`.",
    ),
    doc(
        "rotlang::unit-without-count",
        E,
        "a unit with no number before it",
        "A unit belongs to a count: `10mm`, `50%`.",
        "+30/mm",
        "Write how many: `+30/10mm`.",
    ),
    doc(
        "rotlang::unknown-sign",
        E,
        "a letter or sign the language does not know",
        "Signs are case-sensitive single characters: solid signs `D S O M R`, joints `/ N n Z z $ L l U u Q q ~ ^ | #`, counts `B T`, units `mm cm m ' \" # %`.",
        "+30X5",
        "Use a sign of the language, such as `+30/5`; `rotlang explain` on a template shows what each sign does.",
    ),
    doc(
        "rotlang::unknown-unit",
        E,
        "a misspelt or foreign length unit",
        "Length units are `mm cm m ' \" # %` (`'` feet, `\"` inches, `#` standard layers).",
        "+30/5CM",
        "Write the unit as the language spells it: `+30/5cm`.",
    ),
    doc(
        "rotlang::zero-count",
        W,
        "a count below one layer",
        "A range shorter than one layer still covers one layer: the count does not do what it says.",
        "+30/0",
        "Write the number of layers (or the length) the turn should take, or leave the count out.",
    ),
    doc(
        "rotlang::zero-denominator",
        E,
        "a fraction with 0 below the line",
        "`a:b` means a/b, so `b` cannot be 0.",
        "+1:0",
        "Write a non-zero denominator: `+1:4`.",
    ),
];
