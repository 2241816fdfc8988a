//! `rotlang completions SHELL` and `rotlang man`: generated from the clap definitions, so
//! they list exactly the commands and options the binary has.

use std::io::Write;

use super::UsageError;

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang completions bash > ~/.local/share/bash-completion/completions/rotlang
  rotlang completions zsh > ~/.zfunc/_rotlang         (with fpath+=~/.zfunc)
  rotlang completions fish > ~/.config/fish/completions/rotlang.fish
  rotlang completions powershell >> $PROFILE")]
pub struct CompletionsArgs {
    /// The shell to complete in.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

#[derive(clap::Args, Debug)]
#[command(after_long_help = "\
Examples:
  rotlang man | man -l -                    read it now
  rotlang man > ~/.local/share/man/man1/rotlang.1
  rotlang man expand > rotlang-expand.1     the page of one command")]
pub struct ManArgs {
    /// A command whose page to print (`check`, `fmt`, ...); without it, rotlang(1).
    #[arg(value_name = "COMMAND")]
    pub command: Option<String>,
}

pub fn completions(
    args: &CompletionsArgs,
    mut command: clap::Command,
    out: &mut dyn Write,
) -> Result<i32, UsageError> {
    let name = command.get_name().to_owned();
    clap_complete::generate(args.shell, &mut command, name, out);
    Ok(0)
}

pub fn man(args: &ManArgs, command: clap::Command, out: &mut dyn Write) -> Result<i32, UsageError> {
    let page = match &args.command {
        None => command,
        Some(name) => {
            let sub = command
                .get_subcommands()
                .find(|s| s.get_name() == name)
                .cloned()
                .ok_or_else(|| {
                    let names: Vec<&str> =
                        command.get_subcommands().map(|s| s.get_name()).collect();
                    UsageError(format!(
                        "no command `{name}`; the commands are {}",
                        names.join(", ")
                    ))
                })?;
            let full = format!("{}-{}", command.get_name(), sub.get_name());
            sub.name(full)
        }
    };
    clap_mangen::Man::new(page)
        .render(out)
        .map_err(|e| UsageError(format!("cannot write output: {e}")))?;
    Ok(0)
}
