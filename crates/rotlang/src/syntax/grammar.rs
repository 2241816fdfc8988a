//! The pest parser generated from `grammar/rotlang.pest`, and the words a user sees for
//! each rule in "expected …".

use pest_derive::Parser;

#[derive(Parser)]
#[grammar = "../../../grammar/rotlang.pest"]
pub(crate) struct RotParser;

/// What a rule is called in an error message. Exhaustive on purpose: a new rule must get
/// a name here before the crate compiles.
pub(crate) fn rule_name(rule: Rule) -> &'static str {
    match rule {
        Rule::EOI => "the end of the instruction",
        Rule::template => "a template",
        Rule::instruction => "an instruction",
        Rule::item => "an instruction",
        Rule::instruction_body => "an instruction",
        Rule::separator => "a separator (`,` or a space)",
        Rule::signs => "a solid or joint sign",
        Rule::angle => "an angle",
        Rule::sign => "a sign (`+` or `-`)",
        Rule::turn_fraction => "a fraction of a turn (`1:4`)",
        Rule::percent => "a percentage of a turn (`25%`)",
        Rule::number => "a number",
        Rule::integer => "a whole number",
        Rule::runtime => "a runtime mark (`*`, `*ℤ`, `!`)",
        Rule::star => "`*` or `*ℤ`",
        Rule::bang => "`!`",
        Rule::solid => "a solid sign (`D S O M R`)",
        Rule::joint => "a joint sign (`/ N n Z z $ L l U u Q q ~ ^ | #`)",
        Rule::flip => "a flip (`-`)",
        Rule::count => "a count (`ℕ`, `B` or `T`)",
        Rule::shell_count => "`B` or `T`",
        Rule::height_fraction => "a fraction of the height (`1:2`)",
        Rule::unit => "a length unit (`mm cm m ' \" # %`)",
        Rule::trailing => "a trailing `*` or `!`",
    }
}
