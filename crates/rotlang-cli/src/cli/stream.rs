//! A JSON answer written a piece at a time (`preview --format json`: a layer at a time),
//! so that listing every layer of a tall part holds one layer in memory, not all of them.
//!
//! To `--out FILE` it goes through a file beside it, renamed over `FILE` once whole: an
//! error part-way leaves no half document there (and an older `FILE` as it was); a
//! `FILE` that is not a regular one (`/dev/null`, a named pipe) is written directly. To
//! stdout it goes as it is made; a reader that stops reading (a closed pipe) ends the
//! work quietly, as the whole-text answers do.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use super::UsageError;

/// Where the pieces go, and the first failure to write them (later pieces are dropped).
pub(super) struct JsonOut<'a> {
    sink: BufWriter<&'a mut dyn Write>,
    failed: Option<io::Error>,
    /// Array items written so far (each after the first goes after a comma).
    items: usize,
}

impl<'a> JsonOut<'a> {
    fn new(sink: &'a mut dyn Write) -> JsonOut<'a> {
        JsonOut {
            sink: BufWriter::new(sink),
            failed: None,
            items: 0,
        }
    }

    /// Writes some JSON text as it is.
    pub(super) fn text(&mut self, s: &str) {
        if self.failed.is_none()
            && let Err(e) = self.sink.write_all(s.as_bytes())
        {
            self.failed = Some(e);
        }
    }

    /// Writes a value as the next item of the array being written: a comma before each
    /// but the first.
    pub(super) fn item(&mut self, v: &serde_json::Value) {
        if self.items > 0 {
            self.text(",");
        }
        self.items += 1;
        self.value(v);
    }

    /// Writes a value as `serde_json::to_string` spells it.
    pub(super) fn value(&mut self, v: &serde_json::Value) {
        if self.failed.is_none()
            && let Err(e) = serde_json::to_writer(&mut self.sink, v)
        {
            self.failed = Some(e.into());
        }
    }

    /// Whether writing failed (nothing more is worth making).
    pub(super) fn closed(&self) -> bool {
        self.failed.is_some()
    }
}

/// Runs `body` writing to `path` (through a file beside it) or to `out`.
pub(super) fn stream(
    path: Option<&Path>,
    out: &mut dyn Write,
    body: impl FnOnce(&mut JsonOut<'_>) -> Result<(), UsageError>,
) -> Result<(), UsageError> {
    let Some(path) = path else {
        let mut w = JsonOut::new(out);
        body(&mut w)?;
        let flushed = match w.failed.take() {
            Some(e) => Err(e),
            None => w.sink.flush(),
        };
        return match flushed {
            Err(e) if e.kind() != io::ErrorKind::BrokenPipe => {
                Err(UsageError(format!("cannot write output: {e}")))
            }
            _ => Ok(()),
        };
    };
    let cannot = |e: io::Error| UsageError(format!("cannot write {}: {e}", path.display()));
    // Through links to the file they name (replaced, the links kept).
    let resolved = std::fs::canonicalize(path).ok();
    let path = resolved.as_deref().unwrap_or(path);
    // Not a regular file (`/dev/null`, a pipe): written as it is, nothing to rename over.
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file()) {
        let mut file = File::create(path).map_err(cannot)?;
        let mut w = JsonOut::new(&mut file);
        body(&mut w)?;
        return match w.failed.take() {
            Some(e) => Err(e),
            None => w.sink.flush(),
        }
        .map_err(cannot);
    }
    let tmp = beside(path);
    let mut file = File::create(&tmp).map_err(cannot)?;
    let mut w = JsonOut::new(&mut file);
    let made = body(&mut w);
    let written = match w.failed.take() {
        Some(e) => Err(e),
        None => w.sink.flush(),
    };
    drop(w);
    let done = made.and_then(|()| {
        written
            .and_then(|()| file.sync_all())
            .and_then(|()| std::fs::rename(&tmp, path))
            .map_err(cannot)
    });
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

/// A name beside `path` for the file being written (`.name.rotlang-tmp`).
fn beside(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.rotlang-tmp"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failure_part_way_leaves_no_half_file() {
        let dir = tempfile_dir();
        let path = dir.join("out.json");
        std::fs::write(&path, "old").unwrap();
        let r = stream(Some(&path), &mut Vec::new(), |w| {
            w.text("{\"layers\":[");
            Err(UsageError("layer 3: no".into()))
        });
        assert_eq!(r.unwrap_err().0, "layer 3: no");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert!(!beside(&path).exists());
        stream(Some(&path), &mut Vec::new(), |w| {
            w.text("[");
            w.item(&serde_json::json!(1));
            w.item(&serde_json::json!({"b": 2, "a": 1}));
            w.text("]");
            Ok(())
        })
        .unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            r#"[1,{"a":1,"b":2}]"#
        );
        assert!(!beside(&path).exists());
        std::fs::remove_dir_all(dir).unwrap();
    }

    /// A named pipe (as `/dev/null` is not a regular file either) is written into, not
    /// replaced by a file; a link is followed to its file, which is replaced.
    #[cfg(unix)]
    #[test]
    fn a_pipe_is_written_and_a_link_followed() {
        let dir = tempfile_dir();
        let fifo = dir.join("pipe");
        assert!(
            std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success()
        );
        let reading = fifo.clone();
        let reader = std::thread::spawn(move || std::fs::read_to_string(reading).unwrap());
        stream(Some(&fifo), &mut Vec::new(), |w| {
            w.text("{}");
            Ok(())
        })
        .unwrap();
        assert_eq!(reader.join().unwrap(), "{}");
        assert!(!std::fs::metadata(&fifo).unwrap().is_file());
        let target = dir.join("target.json");
        std::fs::write(&target, "old").unwrap();
        let link = dir.join("link.json");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        stream(Some(&link), &mut Vec::new(), |w| {
            w.text("[]");
            Ok(())
        })
        .unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "[]");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_closed_pipe_ends_the_work_quietly() {
        struct Closed;
        impl Write for Closed {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::ErrorKind::BrokenPipe.into())
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let mut made = 0;
        let r = stream(None, &mut Closed, |w| {
            // Large enough to pass the buffer.
            let big = "x".repeat(20_000);
            while !w.closed() && made < 100 {
                w.text(&big);
                made += 1;
            }
            Ok(())
        });
        assert!(r.is_ok());
        assert_eq!(made, 1);
    }

    fn tempfile_dir() -> PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "rotlang-stream-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }
}
