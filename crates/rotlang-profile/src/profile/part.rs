//! What a part (a mesh sliced and filled) takes from a profile or an OrcaSlicer project:
//! its templates and its infill settings, an object's overrides first. One reading for
//! `rotlang preview project.3mf [--object NAME]` and the playground's `part` (the npm
//! package), so that the two give the same part.

use super::{Found, Profile, Settings};
use crate::Target;

impl Profile {
    /// The settings of `object` (its overrides in `Metadata/model_settings.config`), if it
    /// has any.
    pub fn object_settings(&self, object: Option<&str>) -> Option<&Settings> {
        object.and_then(|o| self.objects.iter().find(|(n, _)| n == o).map(|(_, s)| s))
    }

    /// The template of `target` a part of `object` (all objects: `None`) is filled with:
    /// the object's own, else the project's (never another object's); `None` when the file
    /// has none (OrcaSlicer's default, the empty template).
    pub fn part_template(&self, target: Target, object: Option<&str>) -> Option<&Found> {
        object
            .and_then(|o| {
                self.templates
                    .iter()
                    .find(|f| f.target == target && f.object.as_deref() == Some(o))
            })
            .or_else(|| {
                self.templates
                    .iter()
                    .find(|f| f.target == target && f.object.is_none())
            })
    }

    /// The infill settings a part of `object` takes from the file: each the object's
    /// override, else the project's; `None` where neither sets a usable one (with a note).
    pub fn part_infill(&self, object: Option<&str>) -> PartInfill {
        let own = self.object_settings(object);
        let get = |key: &str| {
            own.and_then(|o| o.values.get(key))
                .or_else(|| self.settings.values.get(key))
                .map(|s| s.value.trim().to_owned())
        };
        let mut notes = Vec::new();
        let mut pattern = |key: &str, solid: bool| {
            let v = get(key)?;
            let p = orcaslicer_pattern(&v, solid);
            if p.is_none() {
                notes.push(format!(
                    "`{key}` = `{v}` is not a pattern rotlang draws: the option's default is used"
                ));
            }
            p
        };
        let sparse = pattern("sparse_infill_pattern", false);
        let solid = pattern("internal_solid_infill_pattern", true);
        let density = get("sparse_infill_density").and_then(|v| {
            let d = number(v.trim_end_matches('%')).map(|d| d / 100.0);
            let d = d.filter(|d| *d > 0.0 && *d <= 1.0);
            if d.is_none() {
                notes.push(format!(
                    "`sparse_infill_density` = `{v}` is not a density above 0% and at most 100%: the option's default is used"
                ));
            }
            d
        });
        let nozzle = get("nozzle_diameter")
            .and_then(|v| number(&v))
            .filter(|v| (0.01..=10.0).contains(v))
            .unwrap_or(0.4);
        // OrcaSlicer's widths: mm, or a percentage of the nozzle; 0 is "the default".
        let mut width = |key: &str| {
            let v = get(key)?;
            let w = match v.strip_suffix('%') {
                Some(p) => number(p).map(|p| p / 100.0 * nozzle),
                None => number(&v),
            };
            let w = w.filter(|w| (0.01..=10.0).contains(w));
            if w.is_none() && number(&v) != Some(0.0) {
                notes.push(format!(
                    "`{key}` = `{v}` is not a line width from 0.01 to 10 mm: not used"
                ));
            }
            w
        };
        let line_width = width("sparse_infill_line_width")
            .or_else(|| width("line_width"))
            .or_else(|| get("nozzle_diameter").map(|_| nozzle));
        let walls = get("wall_loops").and_then(|v| {
            let n = number(&v).filter(|n| n.fract() == 0.0 && (0.0..=100.0).contains(n));
            if n.is_none() {
                notes.push(format!(
                    "`wall_loops` = `{v}` is not a count from 0 to 100: the option's default is used"
                ));
            }
            n.map(|n| n as u32)
        });
        PartInfill {
            pattern: sparse,
            density,
            solid_pattern: solid,
            line_width,
            walls,
            notes,
        }
    }
}

/// The infill settings a profile (and an object's overrides) gives a part, each `None`
/// when it is not set or not usable (with a note). Patterns are rotlang's names
/// (`lines`, `grid`, …: `rotlang_geometry::infill::Pattern` parses them).
#[derive(Debug, Default, PartialEq)]
pub struct PartInfill {
    pub pattern: Option<&'static str>,
    /// 0 to 1.
    pub density: Option<f64>,
    pub solid_pattern: Option<&'static str>,
    /// mm.
    pub line_width: Option<f64>,
    pub walls: Option<u32>,
    pub notes: Vec<String>,
}

fn number(text: &str) -> Option<f64> {
    text.trim().parse::<f64>().ok().filter(|v| v.is_finite())
}

/// OrcaSlicer's name of an infill pattern as the name of the pattern rotlang draws for it:
/// the same, or the nearest (rectilinear kinds are lines, honeycomb is hexagons, the cubic
/// kinds cubic); `None` for those it has no likeness of.
pub fn orcaslicer_pattern(name: &str, solid: bool) -> Option<&'static str> {
    Some(match name.trim().to_ascii_lowercase().as_str() {
        "zig-zag" | "rectilinear" | "alignedrectilinear" | "line" | "monotonic"
        | "monotonicline" => "lines",
        "grid" | "crosshatch" => "grid",
        "triangles" | "tri-hexagon" => "triangles",
        "honeycomb" | "3dhoneycomb" => "hexagons",
        "concentric" => "concentric",
        "gyroid" => "gyroid",
        "archimedeanchords" | "octagramspiral" => "spiral",
        "lightning" if !solid => "lightning",
        "cubic" | "adaptivecubic" | "supportcubic" | "quartercubic" => "cubic",
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    #[test]
    fn an_object_reads_its_overrides_first_then_the_profile() {
        let p = super::super::parse(
            Path::new("p.json"),
            br#"{"sparse_infill_pattern": "honeycomb", "sparse_infill_density": "15%",
                 "wall_loops": "3", "line_width": "120%", "nozzle_diameter": "0.5",
                 "internal_solid_infill_pattern": "lightning"}"#,
        )
        .unwrap();
        let i = p.part_infill(None);
        assert_eq!(i.pattern, Some("hexagons"));
        assert_eq!(i.density, Some(0.15));
        assert_eq!(i.walls, Some(3));
        assert!((i.line_width.unwrap() - 0.6).abs() < 1e-12);
        // Lightning is no solid pattern: the default, with a note.
        assert_eq!(i.solid_pattern, None);
        assert_eq!(i.notes.len(), 1, "{:?}", i.notes);
        assert!(p.part_template(crate::Target::Sparse, Some("x")).is_none());
    }
}
