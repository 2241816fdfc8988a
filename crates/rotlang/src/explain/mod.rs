//! Templates and diagnostic codes explained in plain words.
//!
//! - [`template`]: a template on a model, each instruction in words with the layers it
//!   governs (what `rotlang explain TEMPLATE` prints).
//! - [`code`] / [`codes`]: every diagnostic code with a summary, an example and the fix
//!   (what `rotlang explain CODE` prints).
//! - [`instruction`], [`turn`], [`Run`]: the pieces the language server's hover and inlay
//!   hints use, so the editor and the CLI say the same thing.
//!
//! ```
//! use rotlang::{eval::Model, explain, Target};
//!
//! let text = explain::template("+10L25%, -10l25%", Target::Sparse, &Model::cube20());
//! assert!(text.contains("layers 0–24"));
//! let doc = explain::code("rotlang::unknown-sign").expect("documented");
//! assert!(!doc.fix.is_empty());
//! ```

mod codes;
mod words;

pub use codes::{CodeDoc, code, codes};
pub use words::{Run, deg, deg_and_lines, instruction, model, num, turn, turn_deg};

use crate::eval::{self, Model, Options};
use crate::ir::{Target, Template};

/// Blocks of consecutive layers listed per instruction; the rest are counted.
const MAX_RUNS: usize = 8;
/// Layers evaluated in search of first runs, per call: bounds the cost on long templates
/// over tall models (each search evaluates the model up to the end of one run).
pub const FIRST_RUN_BUDGET: usize = 2_000_000;
/// Longest template text quoted.
const MAX_QUOTE: usize = 80;

/// Per instruction: its first runs of consecutive layers, how many runs and layers in all.
#[derive(Clone, Debug, Default)]
struct Governed {
    runs: Vec<Run>,
    more_runs: usize,
    layers: usize,
}

/// The template in plain words on `model`: each instruction, what it does and the layer
/// ranges it governs, then the range of angles. Instructions with errors are left out
/// (the text says how many errors there are).
pub fn template(text: &str, target: Target, model: &Model) -> String {
    let parse = crate::parse(text, target);
    let t = &parse.template;
    let mut out = format!(
        "{} ({} infill) on {}:\n",
        quote(text),
        match target {
            Target::Sparse => "sparse",
            Target::Solid => "solid",
        },
        words::model(model)
    );
    let errors = parse.diagnostics.iter().filter(|d| d.is_error()).count();
    if errors > 0 {
        out.push_str(&format!(
            "(the template has {} error{}: only the instructions that parse are explained)\n",
            if parse.omitted > 0 {
                format!("{errors}+")
            } else {
                errors.to_string()
            },
            if errors == 1 { "" } else { "s" }
        ));
    }
    let (governed, holds, range) = evaluate(t, model);
    let mut budget = FIRST_RUN_BUDGET;
    if t.instructions.is_empty() {
        out.push_str("\nThe template is empty: every layer keeps the base direction.\n");
    }
    for (i, ins) in t.instructions.iter().enumerate() {
        let ins_text = text.get(ins.span.range()).unwrap_or("");
        out.push_str(&format!(
            "\n{}. {} {}.\n",
            i + 1,
            quote(ins_text),
            instruction(ins, model)
        ));
        let g = &governed[i];
        if ins.is_dummy() {
            out.push_str("   Takes no range of its own.");
            if g.layers > 0 {
                // When nothing else is live, the layers keep the dummy's angle.
                out.push_str(&format!(
                    " Holds {} of the {} layers with its angle once the others are spent.",
                    g.layers,
                    model.len()
                ));
            }
            out.push('\n');
            continue;
        }
        if g.layers == 0 {
            out.push_str("   Governs no layer of this model (never reached).\n");
            continue;
        }
        let mut line = String::from("   ");
        if let Some(run) = first_run(t, i, model, &mut budget).or(g.runs.first().copied()) {
            line.push_str(&format!(
                "First acts on {}: {}.",
                run.layers_words(),
                turn(ins, &run)
            ));
        }
        let blocks: Vec<String> = g
            .runs
            .iter()
            .map(|r| {
                r.layers_words()
                    .replace("layers ", "")
                    .replace("layer ", "")
            })
            .collect();
        line.push_str(&format!(
            " Governs {} of the {} layers: {}{}.\n",
            g.layers,
            model.len(),
            blocks.join(", "),
            if g.more_runs > 0 {
                format!(" and {} more", g.more_runs)
            } else {
                String::new()
            }
        ));
        out.push_str(&line);
    }
    if let Some(run) = holds {
        out.push_str(&format!(
            "\nFrom layer {} on, every instruction is spent: the angle holds at {}.\n",
            run.first_layer,
            deg(run.to)
        ));
    }
    if let Some((min, max, lines_min, lines_max)) = range {
        out.push_str(&format!(
            "\nAngles from {} to {} over the {} layers; infill lines (wrapped to [0°, 180°)) from {} to {}.\n",
            deg(min),
            deg(max),
            model.len(),
            deg(lines_min),
            deg(lines_max)
        ));
    }
    out
}

type Range = (f64, f64, f64, f64);

/// The first run of instruction `index`: the layers of its first range(s) before another
/// instruction takes over, and the turn across them.
///
/// Provenance alone cannot tell where one range of an instruction ends and its next range
/// begins (in `B!, +30` every layer after the shells is a new range of `+30`). So the
/// template is evaluated with that instruction made one-time: it then acts exactly once,
/// and the layers it governs are its first run. Evaluation stops at the run's end, and
/// `budget` (layers, less one per instruction copied) bounds the total work; `None` when
/// it runs out or the instruction never acts.
pub fn first_run(t: &Template, index: usize, model: &Model, budget: &mut usize) -> Option<Run> {
    let ins = t.instructions.get(index)?;
    if ins.is_dummy() {
        return None;
    }
    *budget = budget.checked_sub(t.instructions.len())?;
    let mut once = t.clone();
    let target = once.instructions.get_mut(index)?;
    if target.one_time.is_none() {
        target.one_time = Some(target.span);
    }
    let span = ins.span;
    let mut run: Option<Run> = None;
    let mut previous = 0.0;
    for layer in eval::layers(&once, model, Options::default()) {
        *budget = budget.checked_sub(1)?;
        let mine = layer.instruction == Some(span);
        match (&mut run, mine) {
            (None, true) => {
                run = Some(Run {
                    first_layer: layer.index,
                    layers: 1,
                    from: previous,
                    first: layer.angle,
                    to: layer.angle,
                })
            }
            (Some(r), true) => {
                r.layers += 1;
                r.to = layer.angle;
            }
            (Some(_), false) => break,
            (None, false) => {}
        }
        previous = layer.angle;
    }
    run
}

/// One pass over the layers: the runs of every instruction, where the angle holds, and
/// the range of angles (raw and wrapped to [0, 180)).
fn evaluate(t: &Template, model: &Model) -> (Vec<Governed>, Option<Run>, Option<Range>) {
    let mut governed = vec![Governed::default(); t.instructions.len()];
    let mut holds: Option<Run> = None;
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut lmin, mut lmax) = (f64::INFINITY, f64::NEG_INFINITY);
    // (instruction index or None, angle) of the layer below.
    let mut previous: (Option<usize>, f64) = (None, 0.0);
    let mut current: Option<Run> = None;
    let mut first = true;
    for layer in eval::layers(t, model, Options::default()) {
        let angle = layer.angle;
        min = min.min(angle);
        max = max.max(angle);
        let lines = crate::number::wrap(angle, crate::number::Wrap::HalfTurn);
        lmin = lmin.min(lines);
        lmax = lmax.max(lines);
        let which = layer.instruction.and_then(|span| {
            let i = t
                .instructions
                .partition_point(|ins| ins.span.start < span.start);
            (t.instructions.get(i)?.span == span).then_some(i)
        });
        if !first && which == previous.0 {
            if let Some(run) = &mut current {
                run.layers += 1;
                run.to = angle;
            }
        } else {
            close(&mut governed, previous.0, current.take());
            current = Some(Run {
                first_layer: layer.index,
                layers: 1,
                from: previous.1,
                first: angle,
                to: angle,
            });
        }
        if let Some(i) = which {
            governed[i].layers += 1;
        }
        first = false;
        previous = (which, angle);
    }
    match previous.0 {
        Some(_) => close(&mut governed, previous.0, current),
        None => holds = current.filter(|_| !t.instructions.is_empty()),
    }
    let range = min.is_finite().then_some((min, max, lmin, lmax));
    (governed, holds, range)
}

fn close(governed: &mut [Governed], which: Option<usize>, run: Option<Run>) {
    if let (Some(i), Some(run)) = (which, run)
        && let Some(g) = governed.get_mut(i)
    {
        if g.runs.len() < MAX_RUNS {
            g.runs.push(run);
        } else {
            g.more_runs += 1;
        }
    }
}

/// Text in backticks, shortened, on one line.
fn quote(text: &str) -> String {
    let head: String = text.trim().chars().take(MAX_QUOTE + 1).collect();
    if head.is_empty() {
        return "The empty template".into();
    }
    let mut q = head.replace(['\n', '\r', '\t'], " ");
    if head.chars().count() > MAX_QUOTE {
        q = q.chars().take(MAX_QUOTE).collect();
        q.push('…');
    }
    format!("`{q}`")
}

#[cfg(test)]
mod tests;
