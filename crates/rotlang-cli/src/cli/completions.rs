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
  rotlang man --dir ~/.local/share/man/man1 every page: rotlang.1, rotlang-check.1, ...
  rotlang man expand > rotlang-expand.1     the page of one command")]
pub struct ManArgs {
    /// A command whose page to print (`check`, `fmt`, ...); without it, rotlang(1).
    #[arg(value_name = "COMMAND", conflicts_with = "dir")]
    pub command: Option<String>,
    /// Write every page into DIR (rotlang.1 and rotlang-COMMAND.1 for each command, the
    /// pages rotlang(1) refers to) instead of printing one.
    #[arg(long, value_name = "DIR")]
    pub dir: Option<std::path::PathBuf>,
}

pub fn completions(
    args: &CompletionsArgs,
    mut command: clap::Command,
    out: &mut dyn Write,
) -> Result<i32, UsageError> {
    let name = command.get_name().to_owned();
    // Generated in memory: clap_complete panics on a failed write (a closed pipe); the
    // write here reports it as every command does.
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut command, name, &mut script);
    out.write_all(&script)
        .map_err(|e| UsageError(format!("cannot write output: {e}")))?;
    Ok(0)
}

/// The page of `rotlang` itself, or of one command (`rotlang-check`), with the version.
fn page(command: &clap::Command, sub: Option<&clap::Command>) -> clap::Command {
    let version = env!("CARGO_PKG_VERSION");
    match sub {
        None => {
            // NAME is `rotlang - check, format ...`, not `rotlang - rotlang: check ...`.
            let about = command
                .get_about()
                .map(|a| a.to_string())
                .unwrap_or_default();
            let about = about
                .strip_prefix(&format!("{}: ", command.get_name()))
                .unwrap_or(&about)
                .to_owned();
            command.clone().about(about).version(version)
        }
        Some(sub) => {
            let full = format!("{}-{}", command.get_name(), sub.get_name());
            sub.clone().name(full).version(version)
        }
    }
}

fn render(page: clap::Command, out: &mut dyn Write) -> Result<(), UsageError> {
    clap_mangen::Man::new(page)
        .render(out)
        .map_err(|e| UsageError(format!("cannot write output: {e}")))
}

pub fn man(args: &ManArgs, command: clap::Command, out: &mut dyn Write) -> Result<i32, UsageError> {
    let mut command = command;
    command.build();
    if let Some(dir) = &args.dir {
        std::fs::create_dir_all(dir)
            .map_err(|e| UsageError(format!("cannot create {}: {e}", dir.display())))?;
        let mut pages = vec![(command.get_name().to_owned(), page(&command, None))];
        for sub in command.get_subcommands().filter(|s| s.get_name() != "help") {
            let p = page(&command, Some(sub));
            pages.push((p.get_name().to_owned(), p));
        }
        for (name, p) in pages {
            let path = dir.join(format!("{name}.1"));
            let mut bytes = Vec::new();
            render(p, &mut bytes)?;
            std::fs::write(&path, bytes)
                .map_err(|e| UsageError(format!("cannot write {}: {e}", path.display())))?;
            writeln!(out, "{}", path.display())
                .map_err(|e| UsageError(format!("cannot write output: {e}")))?;
        }
        return Ok(0);
    }
    let p = match &args.command {
        None => page(&command, None),
        Some(name) => {
            let sub = command
                .get_subcommands()
                .find(|s| s.get_name() == name)
                .ok_or_else(|| {
                    let names: Vec<&str> = command
                        .get_subcommands()
                        .map(|s| s.get_name())
                        .filter(|n| *n != "help")
                        .collect();
                    UsageError(format!(
                        "no command `{name}`; the commands are {}",
                        names.join(", ")
                    ))
                })?;
            page(&command, Some(sub))
        }
    };
    render(p, out)?;
    Ok(0)
}
