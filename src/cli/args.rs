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

/// A finite number of millimetres or degrees (ranges are checked by the model).
pub fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("must be a finite number; `{}` is not", text.trim())),
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
    let looks_like_template = arg[1..].starts_with(|c: char| {
        c.is_ascii_digit() || c == '.' || crate::Joint::from_symbol(c).is_some() || c == 'B'
    }) || arg == "-";
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
