//! The streaming G-code reader: layers, features, moves and settings comments.

use std::io::{self, Read};

use super::measure::{Accumulator, Direction};
use super::settings::Settings;

/// The slicer that wrote a file, from its header comment.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Flavor {
    OrcaSlicer,
    BambuStudio,
    PrusaSlicer,
    SuperSlicer,
    Cura,
    /// No known header: layers and features are still read from the comments found.
    #[default]
    Unknown,
}

impl Flavor {
    pub fn name(self) -> &'static str {
        match self {
            Flavor::OrcaSlicer => "OrcaSlicer",
            Flavor::BambuStudio => "Bambu Studio",
            Flavor::PrusaSlicer => "PrusaSlicer",
            Flavor::SuperSlicer => "SuperSlicer",
            Flavor::Cura => "Cura",
            Flavor::Unknown => "unknown slicer",
        }
    }

    /// OrcaSlicer and the slicers that read its templates (Bambu Studio shares its
    /// G-code conventions; forks such as Snapmaker Orca and ElegooSlicer name themselves
    /// in the header and are read as OrcaSlicer).
    pub fn is_orca_family(self) -> bool {
        matches!(self, Flavor::OrcaSlicer | Flavor::BambuStudio)
    }
}

/// One layer as printed.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Layer {
    /// 0 for the first layer of the file (Cura's raft layers, numbered below 0, are skipped).
    pub index: usize,
    /// The layer's print height (mm) from its comment, or from its first Z move.
    pub z: Option<f64>,
    /// The layer's height (mm) from its comment (`;HEIGHT:`, `; LAYER_HEIGHT:`), or the rise
    /// from the layer below.
    pub height: Option<f64>,
    /// The sparse infill's direction, when the layer has sparse infill.
    pub sparse: Option<Direction>,
    /// The solid infill's direction (internal solid, top and bottom surfaces, bridges: a
    /// shell's first layer over sparse infill is a bridge, run as the slicer finds best).
    pub solid: Option<Direction>,
}

/// What a scan found besides the layers.
#[derive(Clone, Debug, Default)]
pub struct Scan {
    pub flavor: Flavor,
    /// The slicer's name and version as its header gives it (`OrcaSlicer 2.3.0`).
    pub generator: Option<String>,
    pub settings: Settings,
    /// Only filled by [`scan_all`].
    pub layers: Vec<Layer>,
    pub bytes: u64,
    pub lines: u64,
}

/// Options of a scan.
#[derive(Clone, Copy, Debug, Default)]
pub struct ScanOptions {}

/// The largest line kept whole: longer lines (a huge settings comment) are cut here, so
/// memory stays bounded whatever the file.
const MAX_LINE: usize = 1 << 20;
const BLOCK: usize = 1 << 18;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Feature {
    Sparse,
    Solid,
    Other,
}

fn feature(name: &[u8]) -> Feature {
    let name = trim(name);
    match name {
        b"Sparse infill" | b"Internal infill" | b"FILL" | b"Infill" => Feature::Sparse,
        b"Internal solid infill"
        | b"Solid infill"
        | b"Top surface"
        | b"Bottom surface"
        | b"Top solid infill"
        | b"Bottom solid infill"
        | b"SKIN"
        | b"Bridge infill"
        | b"Internal bridge infill"
        | b"Bridge"
        | b"Internal Bridge" => Feature::Solid,
        _ => Feature::Other,
    }
}

struct State {
    flavor: Flavor,
    generator: Option<String>,
    settings: Settings,
    absolute_xyz: bool,
    absolute_e: bool,
    x: f64,
    y: f64,
    z: f64,
    e: f64,
    feature: Feature,
    /// The layer being read: `None` before the first layer change.
    layer: Option<Open>,
    next_index: usize,
    last_z: Option<f64>,
    sparse: Accumulator,
    solid: Accumulator,
    /// Cura's raft layers (`;LAYER:-2`) are not the object's.
    in_raft: bool,
}

#[derive(Clone, Copy)]
struct Open {
    index: usize,
    z: Option<f64>,
    z_from_comment: bool,
    height: Option<f64>,
    extruded: bool,
}

/// Reads `reader` to the end, calling `on_layer` for every finished layer in order.
/// Memory is bounded (a fixed block, one line of at most 1 MiB, the settings kept).
pub fn scan(
    mut reader: impl Read,
    _options: &ScanOptions,
    mut on_layer: impl FnMut(Layer),
) -> io::Result<Scan> {
    let mut state = State {
        flavor: Flavor::Unknown,
        generator: None,
        settings: Settings::default(),
        absolute_xyz: true,
        absolute_e: true,
        x: 0.0,
        y: 0.0,
        z: 0.0,
        e: 0.0,
        feature: Feature::Other,
        layer: None,
        next_index: 0,
        last_z: None,
        sparse: Accumulator::default(),
        solid: Accumulator::default(),
        in_raft: false,
    };
    let mut block = vec![0u8; BLOCK];
    let mut carry: Vec<u8> = Vec::new();
    let mut carry_cut = false;
    let (mut bytes, mut lines) = (0u64, 0u64);
    loop {
        let n = match reader.read(&mut block) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        bytes += n as u64;
        let mut rest = &block[..n];
        while let Some(at) = rest.iter().position(|&b| b == b'\n') {
            let line = &rest[..at];
            rest = &rest[at + 1..];
            lines += 1;
            if carry.is_empty() && !carry_cut {
                state.line(line, &mut on_layer);
            } else {
                if !carry_cut {
                    let room = MAX_LINE.saturating_sub(carry.len());
                    carry.extend_from_slice(&line[..line.len().min(room)]);
                }
                let whole = std::mem::take(&mut carry);
                state.line(&whole, &mut on_layer);
                carry = whole;
                carry.clear();
                carry_cut = false;
            }
        }
        if !rest.is_empty() {
            let room = MAX_LINE.saturating_sub(carry.len());
            if rest.len() > room {
                carry_cut = true;
            }
            carry.extend_from_slice(&rest[..rest.len().min(room)]);
        }
    }
    if !carry.is_empty() {
        lines += 1;
        let whole = std::mem::take(&mut carry);
        state.line(&whole, &mut on_layer);
    }
    state.finish_layer(&mut on_layer);
    state.settings.finish();
    Ok(Scan {
        flavor: state.flavor,
        generator: state.generator,
        settings: state.settings,
        layers: Vec::new(),
        bytes,
        lines,
    })
}

/// The most layers [`scan_all`] keeps: 20 m of 0.1 mm layers, a few tens of MB. A file
/// with more (a hostile one: a layer marker and a move repeated) is refused.
pub const MAX_LAYERS: usize = 200_000;

/// [`scan`], keeping every layer in [`Scan::layers`] (at most [`MAX_LAYERS`]: an
/// `InvalidData` error beyond).
pub fn scan_all(reader: impl Read, options: &ScanOptions) -> io::Result<Scan> {
    let mut layers = Vec::new();
    let mut over = false;
    let mut scan = scan(reader, options, |l| {
        if layers.len() < MAX_LAYERS {
            layers.push(l);
        } else {
            over = true;
        }
    })?;
    if over {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("more than {MAX_LAYERS} layers: not a print"),
        ));
    }
    scan.layers = layers;
    Ok(scan)
}

fn trim(b: &[u8]) -> &[u8] {
    let start = b
        .iter()
        .position(|c| !c.is_ascii_whitespace())
        .unwrap_or(b.len());
    let end = b
        .iter()
        .rposition(|c| !c.is_ascii_whitespace())
        .map_or(start, |e| e + 1);
    &b[start..end]
}

fn number_after(line: &[u8], prefix: &[u8]) -> Option<f64> {
    line.strip_prefix(prefix)
        .and_then(|r| parse_number(trim(r)))
}

/// A G-code number (`-12.5`, `.4`, `3`); others (exponents) through the standard parser.
#[inline]
fn parse_number(b: &[u8]) -> Option<f64> {
    let (neg, digits) = match b.first() {
        Some(b'-') => (true, &b[1..]),
        Some(b'+') => (false, &b[1..]),
        _ => (false, b),
    };
    let mut mantissa: u64 = 0;
    let mut scale = 0usize;
    let mut seen_dot = false;
    let mut any = false;
    for (i, &c) in digits.iter().enumerate() {
        match c {
            b'0'..=b'9' => {
                if mantissa > (u64::MAX - 9) / 10 {
                    return std::str::from_utf8(b).ok()?.parse().ok();
                }
                mantissa = mantissa * 10 + u64::from(c - b'0');
                any = true;
                if seen_dot {
                    scale += 1;
                }
            }
            b'.' if !seen_dot => seen_dot = true,
            _ => {
                if i == 0 && !any {
                    return None;
                }
                return std::str::from_utf8(b)
                    .ok()?
                    .parse()
                    .ok()
                    .filter(|v: &f64| v.is_finite());
            }
        }
    }
    if !any {
        return None;
    }
    const POW10: [f64; 19] = [
        1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
        1e17, 1e18,
    ];
    let v = mantissa as f64 / *POW10.get(scale)?;
    Some(if neg { -v } else { v })
}

impl State {
    fn line(&mut self, raw: &[u8], on_layer: &mut impl FnMut(Layer)) {
        let line = match raw.last() {
            Some(b'\r') => &raw[..raw.len() - 1],
            _ => raw,
        };
        match line.first() {
            Some(b'G' | b'g') => self.command(line),
            Some(b'M' | b'm') => match command_word(line) {
                b"M82" => self.absolute_e = true,
                b"M83" => self.absolute_e = false,
                _ => {}
            },
            Some(b';') => self.comment(line, on_layer),
            _ => {
                let t = trim(line);
                if matches!(t.first(), Some(b'G' | b'M')) {
                    self.line(t, on_layer);
                }
            }
        }
    }

    fn comment(&mut self, line: &[u8], on_layer: &mut impl FnMut(Layer)) {
        if line == b";LAYER_CHANGE" || line == b"; CHANGE_LAYER" {
            self.new_layer(on_layer);
        } else if let Some(n) = line.strip_prefix(b";LAYER:") {
            // Cura: `;LAYER:n`, raft layers below 0.
            let n = parse_number(trim(n)).unwrap_or(0.0);
            self.new_layer(on_layer);
            self.in_raft = n < 0.0;
        } else if let Some(z) =
            number_after(line, b";Z:").or_else(|| number_after(line, b"; Z_HEIGHT:"))
        {
            if let Some(open) = &mut self.layer {
                open.z = Some(z);
                open.z_from_comment = true;
            }
        } else if let Some(h) =
            number_after(line, b";HEIGHT:").or_else(|| number_after(line, b"; LAYER_HEIGHT:"))
        {
            if let Some(open) = &mut self.layer {
                open.height = Some(h);
            }
        } else if let Some(name) = line
            .strip_prefix(b";TYPE:")
            .or_else(|| line.strip_prefix(b"; FEATURE:"))
        {
            self.feature = feature(name);
        } else if let Some(chunk) = line.strip_prefix(b";SETTING_3 ") {
            self.settings.cura_chunk(chunk);
        } else if self.layer.is_none() && self.generator.is_none() {
            self.header(line);
        } else if line.starts_with(b"; ") && line.contains(&b'=') {
            self.settings.comment(&line[2..]);
        }
    }

    fn header(&mut self, line: &[u8]) {
        let text = String::from_utf8_lossy(line);
        let lower = text.to_ascii_lowercase();
        let (flavor, name) = if let Some(at) = lower.find("generated by ") {
            let name = text[at + 13..]
                .split(" on ")
                .next()
                .unwrap_or("")
                .trim()
                .to_owned();
            let l = name.to_ascii_lowercase();
            let flavor = if l.contains("orca") || l.contains("elegooslicer") {
                Flavor::OrcaSlicer
            } else if l.contains("bambu") {
                Flavor::BambuStudio
            } else if l.contains("superslicer") {
                Flavor::SuperSlicer
            } else if l.contains("prusaslicer") {
                Flavor::PrusaSlicer
            } else {
                Flavor::Unknown
            };
            (flavor, name)
        } else if lower.starts_with("; bambustudio") {
            (Flavor::BambuStudio, text[1..].trim().to_owned())
        } else if let Some(at) = lower.find("generated with cura") {
            (Flavor::Cura, text[at + 15..].trim().to_owned())
        } else if lower.starts_with(";flavor:") {
            self.flavor = Flavor::Cura;
            return;
        } else {
            if line.starts_with(b"; ") && line.contains(&b'=') {
                self.settings.comment(&line[2..]);
            }
            return;
        };
        self.flavor = flavor;
        self.generator = Some(name);
    }

    fn new_layer(&mut self, on_layer: &mut impl FnMut(Layer)) {
        // OrcaSlicer writes `;LAYER_CHANGE` and `; CHANGE_LAYER` at one change on some
        // printers: a marker before anything was printed on the layer opens no new one.
        if self.layer.is_some_and(|o| !o.extruded) {
            return;
        }
        self.finish_layer(on_layer);
        self.layer = Some(Open {
            index: self.next_index,
            z: None,
            z_from_comment: false,
            height: None,
            extruded: false,
        });
    }

    fn finish_layer(&mut self, on_layer: &mut impl FnMut(Layer)) {
        let Some(open) = self.layer.take() else {
            return;
        };
        let sparse = self.sparse.take();
        let solid = self.solid.take();
        if self.in_raft {
            return;
        }
        self.next_index += 1;
        let height = open
            .height
            .or_else(|| Some(open.z? - self.last_z.unwrap_or(0.0)));
        if open.z.is_some() {
            self.last_z = open.z;
        }
        on_layer(Layer {
            index: open.index,
            z: open.z,
            height,
            sparse,
            solid,
        });
    }

    #[inline]
    fn command(&mut self, line: &[u8]) {
        let word = command_word(line);
        match word {
            b"G0" | b"G1" | b"G2" | b"G3" | b"G00" | b"G01" | b"G02" | b"G03" => {}
            b"G90" => {
                self.absolute_xyz = true;
                return;
            }
            b"G91" => {
                self.absolute_xyz = false;
                return;
            }
            b"G92" => {
                for (letter, value) in words(&line[word.len()..]) {
                    match letter {
                        b'E' => self.e = value,
                        b'X' => self.x = value,
                        b'Y' => self.y = value,
                        b'Z' => self.z = value,
                        _ => {}
                    }
                }
                return;
            }
            _ => return,
        }
        let (mut x, mut y, mut z) = (self.x, self.y, self.z);
        let mut extruded = false;
        for (letter, value) in words(&line[word.len()..]) {
            match letter {
                b'X' => x = if self.absolute_xyz { value } else { x + value },
                b'Y' => y = if self.absolute_xyz { value } else { y + value },
                b'Z' => {
                    z = if self.absolute_xyz { value } else { z + value };
                }
                b'E' => {
                    if self.absolute_e {
                        extruded = value > self.e + 1e-9;
                        self.e = value;
                    } else {
                        extruded = value > 0.0;
                    }
                }
                _ => {}
            }
        }
        if extruded && let Some(open) = &mut self.layer {
            // Without a Z comment, the layer is at the height of its first extrusion (Cura
            // moves to the next layer's Z before its `;LAYER:n`).
            if !open.z_from_comment && open.z.is_none() {
                open.z = Some(z);
            }
            open.extruded = true;
            let (dx, dy) = (x - self.x, y - self.y);
            match self.feature {
                Feature::Sparse => self.sparse.add(dx, dy),
                Feature::Solid => self.solid.add(dx, dy),
                Feature::Other => {}
            }
        }
        self.x = x;
        self.y = y;
        self.z = z;
    }
}

/// The command word of a line (`G1`), up to the first space or comment.
#[inline]
fn command_word(line: &[u8]) -> &[u8] {
    let end = line
        .iter()
        .position(|&c| c == b' ' || c == b';' || c == b'\t')
        .unwrap_or(line.len());
    &line[..end]
}

/// The `X12.5`-style words of a command (up to its comment).
#[inline]
fn words(rest: &[u8]) -> impl Iterator<Item = (u8, f64)> + '_ {
    let rest = match rest.iter().position(|&c| c == b';') {
        Some(at) => &rest[..at],
        None => rest,
    };
    rest.split(|&c| c == b' ' || c == b'\t')
        .filter(|w| w.len() > 1)
        .filter_map(|w| Some((w[0].to_ascii_uppercase(), parse_number(&w[1..])?)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(parse_number(b"12.5"), Some(12.5));
        assert_eq!(parse_number(b"-.4"), Some(-0.4));
        assert_eq!(parse_number(b"3"), Some(3.0));
        assert_eq!(parse_number(b"1e2"), Some(100.0));
        assert_eq!(parse_number(b""), None);
        assert_eq!(parse_number(b"-"), None);
        assert_eq!(parse_number(b"x"), None);
        assert_eq!(parse_number(b"nan"), None);
    }

    #[test]
    fn relative_moves_and_extrusion() {
        let g = b";LAYER_CHANGE\n;Z:0.2\n;TYPE:Solid infill\nG91\nM83\nG1 X10 Y0 E1\nG1 X0 Y0.5 E-1\nG1 X-10 E0.5\n";
        let s = scan_all(&g[..], &ScanOptions::default()).expect("scan");
        assert_eq!(s.layers.len(), 1);
        let d = s.layers[0].solid.expect("solid");
        assert_eq!(d.moves, 2);
        assert!(d.direction.abs() < 1e-9);
    }

    #[test]
    fn double_markers_open_one_layer() {
        let g = b";LAYER_CHANGE\n; CHANGE_LAYER\n; Z_HEIGHT: 0.2\n; FEATURE: Sparse infill\nG1 X1 Y1 E1\n;LAYER_CHANGE\n; CHANGE_LAYER\n; Z_HEIGHT: 0.4\nG1 X2 Y1 E2\n";
        let s = scan_all(&g[..], &ScanOptions::default()).expect("scan");
        assert_eq!(s.layers.len(), 2);
        assert_eq!(s.layers[1].z, Some(0.4));
        assert!((s.layers[1].height.expect("height") - 0.2).abs() < 1e-12);
    }

    #[test]
    fn a_line_without_end_or_over_the_cap_is_bounded() {
        let mut g = b";LAYER_CHANGE\n; ".to_vec();
        g.extend(std::iter::repeat_n(b'x', 3 * MAX_LINE));
        g.extend_from_slice(b"\n;TYPE:FILL\nG1 X5 E1\n");
        let s = scan_all(&g[..], &ScanOptions::default()).expect("scan");
        assert_eq!(s.layers.len(), 1);
        assert!(s.layers[0].sparse.is_some());
    }
}
