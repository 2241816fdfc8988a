//! Reading option values, and the usage errors clap cannot word well for templates.
//!
//! Numeric options accept a leading `-` (`allow_negative_numbers`) so that `--layers -5`
//! reaches these parsers and gets the allowed range, instead of clap's tip to write
//! `-- -5` (which would make `-5` the template).

/// A whole number in `min..=max`, with the range in the error.
fn whole(text: &str, min: u64, max: u64) -> Result<u64, String> {
    let t = text.trim();
    let range = || format!("a whole number from {min} to {max}");
    if t.starts_with('-') && t[1..].bytes().all(|b| b.is_ascii_digit()) && t.len() > 1 {
        return Err(format!("must be {}, not negative", range()));
    }
    match t.parse::<u64>() {
        Ok(n) if (min..=max).contains(&n) => Ok(n),
        Ok(_) => Err(format!("must be {}", range())),
        Err(_) => Err(format!("must be {}; `{t}` is not", range())),
    }
}

/// `--layers N`: 1 to the evaluator's maximum.
pub fn layers(text: &str) -> Result<usize, String> {
    whole(text, 1, crate::eval::MAX_LAYERS as u64).map(|n| n as usize)
}

/// `--seed N`: any u64.
pub fn seed(text: &str) -> Result<u64, String> {
    whole(text, 0, u64::MAX)
}

/// `--bottom-shell-layers N`, `--top-shell-layers N`.
pub fn shells(text: &str) -> Result<u32, String> {
    whole(text, 0, u64::from(u32::MAX)).map(|n| n as u32)
}

/// `preview --columns N`: panels per row.
pub fn columns(text: &str) -> Result<usize, String> {
    whole(text, 1, 64).map(|n| n as usize)
}

/// A finite number of millimetres or degrees (ranges are checked by the model).
pub fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("must be a finite number; `{}` is not", text.trim())),
    }
}

/// A length in millimetres (`--layer-height`, `--height`): a number, or a number with a
/// length unit of the language (`0.2mm`, `2cm`, `0.02m`, `0.01"`, `1'`).
pub fn millimetres(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let (number, scale) = [
        ("mm", 1.0),
        ("cm", 10.0),
        ("m", 1000.0),
        ("\"", 25.4),
        ("'", 304.8),
    ]
    .iter()
    .find_map(|(unit, scale)| t.strip_suffix(unit).map(|n| (n.trim_end(), *scale)))
    .unwrap_or((t, 1.0));
    match number.parse::<f64>() {
        Ok(v) if (v * scale).is_finite() => Ok(v * scale),
        _ => Err(format!(
            "must be a length in millimetres (`0.2`, or with a unit: `0.2mm`, `2cm`); `{t}` is not"
        )),
    }
}

/// A usage error that clap words for options, but which is about a template: an argument
/// that begins with `-` and is not an option (`check -50%Z1cm`) is a template that belongs
/// after `--`. Returns the message to print instead of clap's, if this is such a case.
pub fn template_after_dashdash(error: &clap::Error, argv: &[String]) -> Option<String> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if error.kind() != ErrorKind::UnknownArgument {
        return None;
    }
    let Some(ContextValue::String(unknown)) = error.get(ContextKind::InvalidArg) else {
        return None;
    };
    // The whole argument the unknown piece came from (clap reports `-5` of `-50%Z1cm`).
    let dashdash = argv.iter().position(|a| a == "--").unwrap_or(argv.len());
    let arg = argv[..dashdash]
        .iter()
        .find(|a| a.starts_with(unknown.as_str()) && !a.starts_with("--"))?;
    // Only an argument that begins with `-` was taken for an option: `expand 0, 90`
    // fails on `90`, a second template, which is not this case.
    let looks_like_template = arg.starts_with('-')
        && arg[1..].starts_with(|c: char| {
            c.is_ascii_digit() || c == '.' || crate::Joint::from_symbol(c).is_some() || c == 'B'
        })
        || arg == "-";
    if !looks_like_template {
        return None;
    }
    let command = argv.get(1).map_or("check", String::as_str);
    let shown = if arg
        .bytes()
        .all(|b| b.is_ascii_alphanumeric() || b"-_./%:".contains(&b))
    {
        arg.clone()
    } else {
        format!("'{}'", arg.replace('\'', r"'\''"))
    };
    Some(format!(
        "error: `{arg}` looks like a template that begins with `-`, but a leading `-` \
         starts an option\n\n  \
         tip: put templates that begin with `-` after `--`, after every option: \
         rotlang {command} [OPTIONS] -- {shown}\n"
    ))
}

/// `--range -5..3`: clap takes `-5..3` for an option, not for the value of `--range`.
/// When the argument clap refused follows an option that takes a value, returns the
/// command line with the two joined (`--range=-5..3`), so that parsing it again reaches
/// the option's own parser and its message says what the option allows.
pub fn join_option_value(
    error: &clap::Error,
    command: &clap::Command,
    argv: &[String],
) -> Option<Vec<String>> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if error.kind() != ErrorKind::UnknownArgument {
        return None;
    }
    let Some(ContextValue::String(unknown)) = error.get(ContextKind::InvalidArg) else {
        return None;
    };
    let dashdash = argv.iter().position(|a| a == "--").unwrap_or(argv.len());
    let at = (2..dashdash)
        .find(|&i| argv[i].starts_with('-') && argv[i].starts_with(unknown.as_str()))?;
    let sub = command.find_subcommand(argv.get(1)?)?;
    let option = &argv[at - 1];
    let takes_value = |a: &clap::Arg| a.get_action().takes_values() && !a.is_positional();
    let known = if let Some(long) = option.strip_prefix("--") {
        !long.contains('=')
            && sub
                .get_arguments()
                .any(|a| takes_value(a) && a.get_long() == Some(long))
    } else if let Some(short) = option.strip_prefix('-') {
        let mut chars = short.chars();
        matches!((chars.next(), chars.next()), (Some(c), None)
            if sub.get_arguments().any(|a| takes_value(a) && a.get_short() == Some(c)))
    } else {
        false
    };
    if !known {
        return None;
    }
    let mut joined = argv.to_vec();
    let value = joined.remove(at);
    joined[at - 1] = format!("{option}={value}");
    Some(joined)
}

/// `expand 0, 90` and `expand +30/50 %`: commands of one template get clap's "unexpected
/// argument" for the second piece. Returns the quoting note `check` and `fmt` print, when
/// the arguments look like the pieces of one template.
pub fn pieces_of_one_template(
    error: &clap::Error,
    command: &clap::Command,
    argv: &[String],
) -> Option<String> {
    use clap::error::ErrorKind;
    if error.kind() != ErrorKind::UnknownArgument {
        return None;
    }
    let name = argv.get(1)?;
    let sub = command.find_subcommand(name)?;
    // The positional arguments: neither options nor their values.
    let mut pieces = Vec::new();
    let mut i = 2;
    while i < argv.len() {
        let a = &argv[i];
        if a == "--" {
            pieces.extend(argv[i + 1..].iter().cloned());
            break;
        }
        if let Some(long) = a.strip_prefix("--") {
            let takes_value = sub
                .get_arguments()
                .any(|x| x.get_long() == Some(long) && x.get_action().takes_values());
            i += if takes_value { 2 } else { 1 };
            continue;
        }
        if a.len() == 2 && a.starts_with('-') && !a[1..].starts_with(|c: char| c.is_ascii_digit()) {
            let c = a[1..].chars().next();
            let takes_value = sub
                .get_arguments()
                .any(|x| x.get_short() == c && x.get_action().takes_values());
            i += if takes_value { 2 } else { 1 };
            continue;
        }
        pieces.push(a.clone());
        i += 1;
    }
    super::pieces_note_saying(name, &pieces, "this command takes one template")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_named() {
        assert_eq!(layers("5"), Ok(5));
        assert_eq!(
            layers("-5").unwrap_err(),
            "must be a whole number from 1 to 100000000, not negative"
        );
        assert_eq!(
            layers("0").unwrap_err(),
            "must be a whole number from 1 to 100000000"
        );
        assert!(layers("2.5").unwrap_err().contains("`2.5` is not"));
        assert!(
            seed("-1")
                .unwrap_err()
                .contains("from 0 to 18446744073709551615")
        );
        assert!(shells("-1").unwrap_err().contains("not negative"));
        assert_eq!(finite("-0.5"), Ok(-0.5));
        assert!(finite("nan").is_err());
    }
}
