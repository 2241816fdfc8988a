//! `rotlang gcode`'s reader: throughput on a generated 200 MB G-code stream, read in
//! constant memory (the stream is synthesised as it is read; nothing is stored).
//!
//! `cargo bench --bench gcode`: divan reports bytes per second.

use std::io::Read;

fn main() {
    divan::main();
}

/// One layer as OrcaSlicer writes it: a change-layer block, walls and zigzag sparse
/// infill, about 9 KB.
fn layer(i: usize) -> Vec<u8> {
    let mut s = format!(
        "; CHANGE_LAYER\n; Z_HEIGHT: {:.1}\n; LAYER_HEIGHT: 0.2\nG1 Z{:.1} F600\n; FEATURE: Outer wall\n",
        0.2 * (i + 1) as f64,
        0.2 * (i + 1) as f64
    );
    for k in 0..40 {
        s.push_str(&format!(
            "G1 X{:.3} Y{:.3} E.0321\n",
            90.0 + k as f64 * 0.5,
            90.0
        ));
    }
    s.push_str("; FEATURE: Sparse infill\n; LINE_WIDTH: 0.45\n");
    for k in 0..120 {
        let y = 90.0 + k as f64 * 0.18;
        s.push_str(&format!(
            "G1 X90.512 Y{y:.3} F12000\nG1 X109.488 Y{:.3} E.61234\n",
            y + 0.3
        ));
    }
    s.into_bytes()
}

/// A reader that repeats `unit` until `total` bytes were given.
struct Repeat {
    unit: Vec<u8>,
    at: usize,
    left: usize,
}

impl Read for Repeat {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = buf.len().min(self.left).min(self.unit.len() - self.at);
        buf[..n].copy_from_slice(&self.unit[self.at..self.at + n]);
        self.at = (self.at + n) % self.unit.len();
        self.left -= n;
        Ok(n)
    }
}

const TOTAL: usize = 200 * 1024 * 1024;

#[divan::bench(sample_count = 3, sample_size = 1)]
fn scan_200mb(bencher: divan::Bencher) {
    let unit: Vec<u8> = (0..50).flat_map(layer).collect();
    let total = TOTAL - TOTAL % unit.len();
    bencher
        .counter(divan::counter::BytesCount::new(total))
        .bench(|| {
            let mut layers = 0usize;
            let scan = rotlang_profile::gcode::scan(
                Repeat {
                    unit: unit.clone(),
                    at: 0,
                    left: total,
                },
                &Default::default(),
                |_| layers += 1,
            )
            .expect("scan");
            assert_eq!(scan.bytes as usize, total);
            layers
        });
}
