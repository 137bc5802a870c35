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
//! A signal the program handles does not run destructors, so every temporary
//! file is also registered while it exists: [`remove_temporaries`] removes
//! them all and refuses new ones, for a signal handler to call before the
//! process exits (the `lamplight` binary does so on Ctrl-C, SIGTERM and SIGHUP).
//!
//! New files get mode `0666` less the umask, as `std::fs::write` gives them (the
//! temporary file would otherwise be `0600`).

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// The temporary files that exist now, and whether new ones are refused.
struct Live {
    paths: Vec<PathBuf>,
    closed: bool,
}

/// The process's registry (tests make their own, so as not to close this one).
type Registry = &'static Mutex<Live>;

static LIVE: Mutex<Live> = Mutex::new(Live { paths: Vec::new(), closed: false });

fn lock(registry: Registry) -> MutexGuard<'static, Live> {
    // A panic elsewhere while holding the lock leaves the list itself intact.
    registry.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Removes every temporary file of a write in progress and makes later writes
/// fail, so that nothing is left beside the outputs when the process exits now
/// (a signal handler's job: the handler of the `lamplight` binary calls it, then
/// exits). Returns how many files were removed. Outputs already renamed into
/// place are kept; outputs not yet renamed are not written.
pub fn remove_temporaries() -> usize {
    remove_registered(&LIVE)
}

fn remove_registered(registry: Registry) -> usize {
    let mut live = lock(registry);
    live.closed = true;
    live.paths.drain(..).filter(|p| std::fs::remove_file(p).is_ok()).count()
}

/// A registered temporary file: removed (and unregistered) when dropped, unless persisted.
struct Temp {
    file: Option<tempfile::NamedTempFile>,
    path: PathBuf,
    registry: Registry,
}

impl Temp {
    fn file(&mut self) -> &mut File {
        self.file.as_mut().expect("present until persisted or dropped").as_file_mut()
    }

    /// Renames the file to `target`; on failure the file is removed.
    fn persist(mut self, target: &Path) -> io::Result<()> {
        let file = self.file.take().expect("present until persisted or dropped");
        // A failed rename hands the temporary file back inside the error;
        // dropping the error removes it.
        file.persist(target).map(drop).map_err(|e| plain(e.error))
    }
}

impl Drop for Temp {
    fn drop(&mut self) {
        // The file goes first, then its registration: a signal in between finds
        // a name that no longer exists, never a file that is no longer listed.
        drop(self.file.take());
        let mut live = lock(self.registry);
        if let Some(i) = live.paths.iter().position(|p| *p == self.path) {
            live.paths.swap_remove(i);
        }
    }
}

/// Writes `path` atomically with `write`, which gets the temporary file; on any
/// error (or panic) in `write`, the sync or the rename, the temporary file is
/// removed and an existing `path` is left as it was.
/// Errors are the system's, without the temporary file's name (the caller names
/// the target).
pub fn write_with(path: &Path, write: impl FnOnce(&mut File) -> io::Result<()>) -> io::Result<()> {
    write_registered(&LIVE, path, write)
}

fn write_registered(registry: Registry, path: &Path, write: impl FnOnce(&mut File) -> io::Result<()>) -> io::Result<()> {
    let mut temp = create_temp(registry, path)?;
    write(temp.file())?;
    temp.file().sync_all()?;
    temp.persist(path)?;
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
    create_temp(&LIVE, path).map(drop)
}

/// Whether `a` and `b` name the same file, so that writing both would leave
/// only the second: the same path after resolving `.`, `..` and symbolic links
/// in their folders, or, when both exist, the same device and inode (a hard link
/// or a symbolic link to the other).
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            if (ma.dev(), ma.ino()) == (mb.dev(), mb.ino()) {
                return true;
            }
        }
    }
    let resolved = |p: &Path| -> Option<std::path::PathBuf> {
        let name = p.file_name()?;
        Some(parent_dir(p).canonicalize().ok()?.join(name))
    };
    match (resolved(a), resolved(b)) {
        (Some(ra), Some(rb)) => ra == rb,
        _ => a == b,
    }
}

/// A new, empty temporary file beside `path`, registered, deleted when dropped.
fn create_temp(registry: Registry, path: &Path) -> io::Result<Temp> {
    let name = path.file_name().ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let mut builder = tempfile::Builder::new();
    let prefix = format!(".{}.", name.to_string_lossy());
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    // Created under the lock, so that `remove_temporaries` sees every file.
    let mut live = lock(registry);
    if live.closed {
        return Err(io::Error::new(io::ErrorKind::Interrupted, "interrupted"));
    }
    let file = builder.tempfile_in(parent_dir(path)).map_err(plain)?;
    let temp = Temp { path: file.path().to_path_buf(), file: Some(file), registry };
    live.paths.push(temp.path.clone());
    Ok(temp)
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

    #[test]
    fn an_interrupt_removes_the_temporary_files_of_writes_in_progress() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.exr");
        fs::write(&target, b"old image").unwrap();
        let registry: Registry = Box::leak(Box::new(Mutex::new(Live { paths: Vec::new(), closed: false })));
        // The handler runs while the contents are being written.
        let err = write_registered(registry, &target, |file| {
            file.write_all(b"half of a new")?;
            assert_eq!(entries(dir.path()).len(), 2, "the temporary file exists");
            assert_eq!(remove_registered(registry), 1);
            assert_eq!(entries(dir.path()), ["out.exr"], "removed at once");
            file.write_all(b" image")
        });
        // Writing to the unlinked file succeeds, the rename cannot.
        assert_eq!(err.unwrap_err().kind(), io::ErrorKind::NotFound);
        assert_eq!(entries(dir.path()), ["out.exr"]);
        assert_eq!(fs::read(&target).unwrap(), b"old image", "the old output is whole");
        // After it, no write starts.
        let later = write_registered(registry, &dir.path().join("later.png"), |file| file.write_all(b"x"));
        assert_eq!(later.unwrap_err().to_string(), "interrupted");
        assert_eq!(entries(dir.path()), ["out.exr"]);
        // A write that ends normally leaves nothing registered.
        let fresh: Registry = Box::leak(Box::new(Mutex::new(Live { paths: Vec::new(), closed: false })));
        write_registered(fresh, &target, |file| file.write_all(b"new image")).unwrap();
        assert!(lock(fresh).paths.is_empty());
        assert_eq!(fs::read(&target).unwrap(), b"new image");
    }

    #[test]
    fn the_same_file_is_found_through_dots_and_links() {
        let dir = tempfile::tempdir().unwrap();
        let p = |name: &str| dir.path().join(name);
        fs::create_dir(p("sub")).unwrap();
        assert!(same_file(&p("a.exr"), &p("a.exr")), "not yet written");
        assert!(same_file(&p("a.exr"), &p("sub/../a.exr")));
        assert!(!same_file(&p("a.exr"), &p("b.exr")));
        assert!(!same_file(&p("a.exr"), &p("sub/a.exr")));
        fs::write(p("a.exr"), b"old").unwrap();
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(p("a.exr"), p("link.exr")).unwrap();
            assert!(same_file(&p("a.exr"), &p("link.exr")));
            std::os::unix::fs::symlink(p("sub"), p("alias")).unwrap();
            assert!(same_file(&p("sub/v.exr"), &p("alias/v.exr")), "a linked folder, the file not yet written");
        }
        fs::hard_link(p("a.exr"), p("hard.exr")).unwrap();
        assert!(same_file(&p("hard.exr"), &p("a.exr")));
        fs::write(p("b.exr"), b"old").unwrap();
        assert!(!same_file(&p("a.exr"), &p("b.exr")), "two files with the same contents");
    }
}
