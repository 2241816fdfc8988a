//! The `rotlang` command.

use std::io::Write;
use std::process::ExitCode;

use clap::{CommandFactory, Parser, Subcommand};
use rotlang_cli::cli;

/// rotlang: check, format and expand infill rotation templates.
///
/// A template tells the slicer which direction the infill lines run on every layer
/// (OrcaSlicer's sparse_infill_rotate_template and solid_infill_rotate_template):
/// `0, 90` alternates 0° and 90°; `+30/50%` turns 30° linearly over half the height;
/// `B!, +30` holds the bottom shell layers, then turns 30° per layer.
#[derive(Parser, Debug)]
#[command(
    name = "rotlang",
    version,
    propagate_version = true,
    after_help = "\
Examples:
  rotlang check '+10L25%, -10l25%'
  rotlang fmt '0 90  +30/50%'
  rotlang expand '+10L25%, -10l25%' --layers 200 --layer-height 0.1
  rotlang plot '+10L25%, -10l25%' --out angles.svg
  rotlang preview '+45' --pattern grid --density 20 --out layers.svg
  rotlang explain '+10L25%, -10l25%'
  rotlang explain rotlang::space-splits-instruction
Run `rotlang help COMMAND` for a command's options and examples."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Report errors and warnings in templates, with the characters at fault.
    Check(cli::check::CheckArgs),
    /// Print templates in canonical form (or check that they are).
    Fmt(cli::fmt::FmtArgs),
    /// Print the angle and fill of every layer of a model.
    Expand(cli::expand::ExpandArgs),
    /// Draw the angle against height as an SVG chart.
    Plot(cli::plot::PlotArgs),
    /// Draw the infill of some layers (SVG), or list its paths (JSON).
    Preview(cli::preview::PreviewArgs),
    /// Explain a template in plain words, or a diagnostic code.
    Explain(cli::explain::ExplainArgs),
    /// Print a template as the settings of Cura, SuperSlicer, PrusaSlicer or OrcaSlicer.
    Export(cli::export::ExportArgs),
    /// Measure the infill direction of every layer of a G-code file, against the template.
    Gcode(cli::gcode::GcodeArgs),
    /// Print a shell completion script (bash, zsh, fish, powershell, elvish).
    Completions(cli::completions::CompletionsArgs),
    /// Print the manual page (roff), of rotlang or of one command.
    Man(cli::completions::ManArgs),
}

/// stdout, remembering whether its reader went away (a write failed with a broken pipe).
struct PipeWatch<W> {
    inner: W,
    closed: bool,
}

impl<W: Write> PipeWatch<W> {
    fn watch<T>(&mut self, r: std::io::Result<T>) -> std::io::Result<T> {
        if let Err(e) = &r
            && e.kind() == std::io::ErrorKind::BrokenPipe
        {
            self.closed = true;
        }
        r
    }
}

impl<W: Write> Write for PipeWatch<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let r = self.inner.write(buf);
        self.watch(r)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let r = self.inner.flush();
        self.watch(r)
    }
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let cli = match Cli::try_parse_from(&argv) {
        Ok(cli) => cli,
        Err(e) => {
            // `expand 0 --range -5..3`: the value of an option, read by the option's parser.
            if let Some(joined) = cli::args::join_option_value(&e, &Cli::command(), &argv) {
                match Cli::try_parse_from(&joined) {
                    Ok(cli) => cli,
                    Err(e) => e.exit(),
                }
            } else {
                // `check -50%Z1cm`: a template that begins with `-`, not an unknown option.
                if let Some(message) = cli::args::template_after_dashdash(&e, &argv) {
                    let _ = write!(std::io::stderr(), "{message}");
                    return ExitCode::from(2);
                }
                // `rotlang '+30'`: a template (or a file) where the command goes.
                if e.kind() == clap::error::ErrorKind::InvalidSubcommand
                    && let Some(arg) = argv.get(1)
                    && !arg.chars().all(|c| c.is_ascii_alphabetic())
                {
                    let _ = write!(
                        std::io::stderr(),
                        "{}\n  tip: to check a template or a file, run: rotlang check {}\n",
                        e.render(),
                        cli::shell_quote(arg)
                    );
                    return ExitCode::from(2);
                }
                // `expand 0, 90`: pieces of one template, split by the shell.
                if let Some(note) = cli::args::pieces_of_one_template(&e, &Cli::command(), &argv) {
                    let _ = write!(std::io::stderr(), "{}\n{note}", e.render());
                    return ExitCode::from(2);
                }
                e.exit()
            }
        }
    };
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(PipeWatch {
        inner: stdout.lock(),
        closed: false,
    });
    let mut err = std::io::stderr();
    let result = match &cli.command {
        Command::Check(args) => cli::check::run(args, &mut out, &mut err),
        Command::Fmt(args) => cli::fmt::run(args, &mut out, &mut err),
        Command::Expand(args) => cli::expand::run(args, &mut out, &mut err),
        Command::Plot(args) => cli::plot::run(args, &mut out, &mut err),
        Command::Preview(args) => cli::preview::run(args, &mut out, &mut err),
        Command::Explain(args) => cli::explain::run(args, &mut out, &mut err),
        Command::Export(args) => cli::export::run(args, &mut out, &mut err),
        Command::Gcode(args) => cli::gcode::run(args, &mut out, &mut err),
        Command::Completions(args) => cli::completions::completions(args, Cli::command(), &mut out),
        Command::Man(args) => cli::completions::man(args, Cli::command(), &mut out),
    };
    let flushed = out.flush();
    // `rotlang completions bash | head -1`: a reader that stops reading is not an error.
    // End quietly, as `cat` would (rust ignores SIGPIPE, so writes fail instead).
    if out.get_ref().closed {
        return ExitCode::SUCCESS;
    }
    match result {
        Ok(code) => {
            if let Err(e) = flushed
                && e.kind() != std::io::ErrorKind::BrokenPipe
            {
                let _ = writeln!(err, "rotlang: cannot write output: {e}");
                return ExitCode::from(2);
            }
            ExitCode::from(code as u8)
        }
        Err(e) => {
            let _ = writeln!(err, "rotlang: {e}");
            ExitCode::from(2)
        }
    }
}
