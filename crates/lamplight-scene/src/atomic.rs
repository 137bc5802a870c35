//! Atomic file writes, for every file lamplight writes (images, `.npy` answers).
//!
//! The contents go to a new temporary file `.<name>.<random>.tmp` beside the
//! target ([`tempfile::NamedTempFile`]), which is synced and then renamed over the
//! target ([`tempfile::NamedTempFile::persist`]). The temporary file is owned by
//! a value that deletes it when dropped, so every early return, error and panic
//! removes it; the target is only ever replaced whole, by the rename. A process
//! killed mid-write (SIGKILL, or a signal the program does not handle) can leave
//! the temporary file behind, never a truncated target.
//!
//! New files get mode `0666` less the umask, as `std::fs::write` gives them (the
//! temporary file would otherwise be `0600`).

use std::fs::File;
use std::io::{self, Write};
use std::path::Path;

/// Writes `path` atomically with `write`, which gets the temporary file; on any
/// error (or panic) in `write`, the sync or the rename, the temporary file is
/// removed and an existing `path` is left as it was.
/// Errors are the system's, without the temporary file's name (the caller names
/// the target).
pub fn write_with(path: &Path, write: impl FnOnce(&mut File) -> io::Result<()>) -> io::Result<()> {
    let mut temp = create_temp(path)?;
    write(temp.as_file_mut())?;
    temp.as_file().sync_all()?;
    // A failed rename hands the temporary file back inside the error; dropping
    // the error removes it.
    temp.persist(path).map_err(|e| plain(e.error))?;
    // The directory is not synced: the rename is atomic, so after a crash the
    // name holds either the old file or the new one, each complete; syncing the
    // directory as well would cost 5-10 ms per image for durability of the name
    // alone, more than a tenth of a small render's whole run.
    Ok(())
}

/// Writes `bytes` to `path` atomically ([`write_with`]).
pub fn write(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_with(path, |file| file.write_all(bytes))
}

/// Checks that `path`'s directory accepts new files, by creating a temporary
/// file there and removing it again. The target itself is not touched.
pub fn check_writable(path: &Path) -> io::Result<()> {
    create_temp(path).map(drop)
}

/// A new, empty temporary file beside `path`, deleted when dropped.
fn create_temp(path: &Path) -> io::Result<tempfile::NamedTempFile> {
    let name = path.file_name().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let mut builder = tempfile::Builder::new();
    let prefix = format!(".{}.", name.to_string_lossy());
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(parent_dir(path)).map_err(plain)
}

/// `error` without what tempfile appends (` at path "<temporary name>"`), and
/// without ` (os error N)`: "Not a directory" rather than "Not a directory (os
/// error 20) at path \"/d/.out.png.x2Zq.tmp\"".
fn plain(error: io::Error) -> io::Error {
    let text = error.to_string();
    let end = [" at path ", " (os error "].iter().filter_map(|cut| text.find(cut)).min();
    match end {
        Some(end) => io::Error::new(error.kind(), &text[..end]),
        None => error,
    }
}

/// The directory that holds `path` (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
        names.sort();
        names
    }

    #[test]
    fn a_failed_write_leaves_no_temporary_file_and_the_old_output_whole() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.png");
        fs::write(&target, b"old image").unwrap();
        let err = write_with(&target, |file| {
            file.write_all(b"half of a new")?;
            Err(io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "disk on fire");
        assert_eq!(entries(dir.path()), ["out.png"], "no stray .tmp file");
        assert_eq!(fs::read(&target).unwrap(), b"old image");
        // A panic while writing cleans up the same way.
        let panicked = std::panic::catch_unwind(|| write_with(&target, |_| panic!("encoder bug")));
        assert!(panicked.is_err());
        assert_eq!(entries(dir.path()), ["out.png"]);
        assert_eq!(fs::read(&target).unwrap(), b"old image");
    }

    #[test]
    fn a_failed_rename_removes_the_temporary_file() {
        // A non-empty directory cannot be replaced by a file, for root too.
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.npy");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("inside"), b"old").unwrap();
        assert!(write(&target, b"new").is_err());
        assert_eq!(entries(dir.path()), ["out.npy"]);
        assert_eq!(fs::read(target.join("inside")).unwrap(), b"old");
    }

    #[test]
    fn success_replaces_the_target_whole_with_the_usual_mode() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.ppm");
        fs::write(&target, vec![b'x'; 10_000]).unwrap();
        write(&target, b"P6 short").unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"P6 short");
        check_writable(&target).unwrap();
        assert_eq!(entries(dir.path()), ["out.ppm"]);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let plain = dir.path().join("plain");
            fs::write(&plain, b"").unwrap();
            let mode = |p: &Path| fs::metadata(p).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode(&target), mode(&plain), "the same mode as std::fs::write gives");
        }
        let err = check_writable(&dir.path().join("missing").join("out.png")).unwrap_err();
        assert_eq!(err.to_string(), "No such file or directory");
    }
}
