//! Rewriting a file in place (`fmt --write`, `check --fix --write`): through a symbolic
//! link to its target, keeping the file's inode (so hard links stay one file), mode and
//! owner; refusing a read-only file, and a file that changed since it was read.
//!
//! A temporary file renamed over the target is atomic (a crash leaves the old text or the
//! new, never half of each) but makes a new inode: it is used only where that is invisible,
//! a file with one link whose owner and mode the new file can be given. Otherwise (a hard
//! link, a file owned by someone else, a folder we may not write in) the file is rewritten
//! in place: not atomic, but the only way to change the one file all its names share.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};

/// Writes `new` to `path`, which held `read` when it was read. The error says why the file
/// was left as it is (or, for an I/O failure, what failed).
pub(crate) fn write_file(path: &Path, read: &[u8], new: &[u8]) -> Result<(), String> {
    let shown = path.display();
    // The file the name leads to, through every link (a link to a link, a linked folder).
    let target = fs::canonicalize(path).map_err(|e| format!("cannot write {shown}: {e}"))?;
    let meta = fs::metadata(&target).map_err(|e| format!("cannot write {shown}: {e}"))?;
    if !meta.is_file() {
        return Err(format!("cannot write {shown}: not a regular file"));
    }
    // The permission bits, not only what the kernel allows: root may write a 0444 file,
    // but a read-only file says "do not change me" to every user.
    if meta.permissions().readonly() {
        return Err(format!(
            "{shown} is read-only: not written (make it writable, e.g. `chmod u+w`, to let \
             rotlang rewrite it)"
        ));
    }
    // Opening for writing (no truncation: nothing changes yet) asks the kernel whether we
    // may write it at all; renaming over it would otherwise succeed where writing it would
    // not (another user's file in a folder we may write in).
    let mut file = OpenOptions::new()
        .read(true)
        .write(true)
        .open(&target)
        .map_err(|e| format!("{shown} cannot be written: {e}: not written"))?;
    unchanged(&mut file, read).map_err(|why| format!("{shown} {why}: not written"))?;
    if let Some(tmp) = atomic_candidate(&target, &meta) {
        match replace(&target, &tmp, read, new, &meta) {
            Ok(()) => return Ok(()),
            Err(Replace::Changed(why)) => return Err(format!("{shown} {why}: not written")),
            // The temporary file could not be given the owner or mode: in place instead.
            Err(Replace::Fallback) => {}
        }
    }
    in_place(&mut file, new).map_err(|e| format!("cannot write {shown}: {e}"))
}

/// Whether the open file still holds what was read.
fn unchanged(file: &mut File, read: &[u8]) -> Result<(), String> {
    let mut now = Vec::with_capacity(read.len());
    (&mut *file)
        .take(read.len() as u64 + 1)
        .read_to_end(&mut now)
        .map_err(|e| format!("cannot be read again ({e})"))?;
    if now != read {
        return Err("changed since it was read (another program wrote it?)".to_owned());
    }
    Ok(())
}

/// The temporary file beside `target` for an atomic replacement, if one is safe: the file
/// has one name (a rename would split hard links) and the folder can hold a new file.
fn atomic_candidate(target: &Path, meta: &fs::Metadata) -> Option<PathBuf> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if meta.nlink() != 1 {
            return None;
        }
    }
    #[cfg(not(unix))]
    let _ = meta;
    let name = target.file_name()?.to_string_lossy().into_owned();
    Some(target.with_file_name(format!(".{name}.rotlang-{}", std::process::id())))
}

enum Replace {
    Changed(String),
    Fallback,
}

/// Writes `new` into `tmp`, gives it the target's mode and owner, checks the target once
/// more, and renames it over the target.
fn replace(
    target: &Path,
    tmp: &Path,
    read: &[u8],
    new: &[u8],
    meta: &fs::Metadata,
) -> Result<(), Replace> {
    let written = (|| -> io::Result<()> {
        let mut f = OpenOptions::new().write(true).create_new(true).open(tmp)?;
        f.write_all(new)?;
        f.set_permissions(meta.permissions())?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            let mine = fs::metadata(tmp)?;
            if mine.uid() != meta.uid() || mine.gid() != meta.gid() {
                std::os::unix::fs::fchown(&f, Some(meta.uid()), Some(meta.gid()))?;
            }
        }
        f.sync_all()
    })();
    if written.is_err() {
        let _ = fs::remove_file(tmp);
        return Err(Replace::Fallback);
    }
    // The last look before the rename: a write by another program since the first look is
    // caught here (one in the instant between this look and the rename is not).
    let check = File::open(target)
        .map_err(|e| e.to_string())
        .and_then(|mut f| unchanged(&mut f, read));
    if let Err(why) = check {
        let _ = fs::remove_file(tmp);
        return Err(Replace::Changed(why));
    }
    fs::rename(tmp, target).map_err(|_| {
        let _ = fs::remove_file(tmp);
        Replace::Fallback
    })
}

/// Rewrites the open file from its start and cuts it at the new length: same inode.
fn in_place(file: &mut File, new: &[u8]) -> io::Result<()> {
    use std::io::Seek;
    file.seek(io::SeekFrom::Start(0))?;
    file.write_all(new)?;
    file.set_len(new.len() as u64)?;
    file.sync_all()
}

#[cfg(test)]
mod tests {
    use super::write_file;

    fn scratch(name: &str, text: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("rotlang-write-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    /// A file that changed between the read and the write is left alone.
    #[test]
    fn a_file_changed_since_it_was_read_is_not_written() {
        let path = scratch("changed.rot", "0, 90, 45\n");
        let why = write_file(&path, b"0,90\n", b"0, 90\n").unwrap_err();
        assert!(why.contains("changed since it was read"), "{why}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "0, 90, 45\n");
        // The same file, unchanged since the read, is written.
        write_file(&path, b"0, 90, 45\n", b"0, 90\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "0, 90\n");
        // A longer file whose start is what was read has changed too.
        std::fs::write(&path, "0, 90\n, 5").unwrap();
        assert!(write_file(&path, b"0, 90\n", b"x").is_err());
        let _ = std::fs::remove_file(&path);
    }
}
