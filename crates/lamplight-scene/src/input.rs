//! Reading an input file: the one place that opens scene, mesh, environment and
//! texture files, so that each is refused the same way when it is not a file
//! one can read to its end.
//!
//! A FIFO blocks its reader forever and a device such as `/dev/zero` never ends,
//! so only regular files are read (a symbolic link counts as what it points at).
//! The size is checked against a cap before anything is allocated, and the read
//! itself stops one byte past the cap, so a file that grows while it is read is
//! refused too.

use std::fs::File;
use std::io::Read;
use std::path::Path;

/// Why a file was not read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// Nothing at the path.
    NotFound,
    /// Not allowed to read it.
    PermissionDenied,
    /// A directory.
    Directory,
    /// A FIFO, socket or device: `a FIFO`, `a device`, `a socket`.
    NotRegular(&'static str),
    /// Larger than the cap.
    TooLarge {
        /// Its size in bytes (at least what was read).
        len: u64,
        /// The cap.
        max: u64,
    },
    /// Any other I/O error.
    Io(String),
}

impl Refusal {
    /// What is wrong, in words, for a file that should be `expected` (`a mesh
    /// file`): `no such file`, `is a FIFO, not a regular file (expected a mesh
    /// file)`, `is a directory, expected a mesh file`. Every reader's message
    /// about a file it could not open comes from here, so a FIFO, a folder and
    /// `/dev/zero` are each named for what they are.
    pub fn describe(&self, expected: &str) -> String {
        match self {
            Refusal::NotFound => "no such file".to_string(),
            Refusal::PermissionDenied => "permission denied".to_string(),
            Refusal::Directory => format!("is a directory, expected {expected}"),
            Refusal::NotRegular(kind) => format!("is {kind}, not a regular file (expected {expected})"),
            Refusal::TooLarge { len, max } => format!("is {len} bytes, larger than the {max} bytes {expected} may have"),
            Refusal::Io(e) => format!("cannot be read: {e}"),
        }
    }

    fn io(e: &std::io::Error) -> Refusal {
        match e.kind() {
            std::io::ErrorKind::NotFound => Refusal::NotFound,
            std::io::ErrorKind::PermissionDenied => Refusal::PermissionDenied,
            _ => Refusal::Io(e.to_string()),
        }
    }
}

/// Opens `path` for reading when it is a regular file of at most `max` bytes;
/// returns the file and its size.
pub fn open_regular(path: &Path, max: u64) -> Result<(File, u64), Refusal> {
    let len = check_regular(path)?;
    if len > max {
        return Err(Refusal::TooLarge { len, max });
    }
    let file = File::open(path).map_err(|e| Refusal::io(&e))?;
    // The path may have been replaced between the two calls: check what was opened.
    let opened = file.metadata().map_err(|e| Refusal::io(&e))?;
    if !opened.is_file() {
        return Err(Refusal::NotRegular(kind_of(opened.file_type())));
    }
    Ok((file, opened.len()))
}

/// What a file that is not a regular file is, in words.
fn kind_of(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    let _ = file_type;
    "not a regular file"
}

/// Whether `path` is a regular file one may open (no file is opened: a FIFO
/// is told apart without blocking); its size.
pub fn check_regular(path: &Path) -> Result<u64, Refusal> {
    let meta = std::fs::metadata(path).map_err(|e| Refusal::io(&e))?;
    if meta.is_dir() {
        return Err(Refusal::Directory);
    }
    if !meta.is_file() {
        return Err(Refusal::NotRegular(kind_of(meta.file_type())));
    }
    Ok(meta.len())
}

/// The whole of `path` when it is a regular file of at most `max` bytes.
pub fn read_regular(path: &Path, max: u64) -> Result<Vec<u8>, Refusal> {
    let (file, len) = open_regular(path, max)?;
    read_opened(file, len, max)
}

/// The whole of a file [`open_regular`] opened (`len` bytes when opened), at
/// most `max` bytes even if it grows.
pub fn read_opened(file: File, len: u64, max: u64) -> Result<Vec<u8>, Refusal> {
    let mut bytes = Vec::with_capacity(len.min(max) as usize);
    file.take(max + 1).read_to_end(&mut bytes).map_err(|e| Refusal::io(&e))?;
    if bytes.len() as u64 > max {
        return Err(Refusal::TooLarge { len: bytes.len() as u64, max });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_regular_files_within_the_cap_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.toml");
        std::fs::write(&file, b"0123456789").unwrap();
        assert_eq!(read_regular(&file, 10).unwrap(), b"0123456789");
        assert_eq!(read_regular(&file, 9).unwrap_err(), Refusal::TooLarge { len: 10, max: 9 });
        assert_eq!(read_regular(dir.path(), 10).unwrap_err(), Refusal::Directory);
        assert_eq!(read_regular(&dir.path().join("none"), 10).unwrap_err(), Refusal::NotFound);
        assert_eq!(read_regular(Path::new("/dev/zero"), 10).unwrap_err(), Refusal::NotRegular("a device"));
        #[cfg(unix)]
        {
            let link = dir.path().join("z.toml");
            std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
            assert_eq!(read_regular(&link, 1 << 20).unwrap_err(), Refusal::NotRegular("a device"), "a link to a device");
            let fifo = dir.path().join("f.toml");
            if std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
                // Returns at once: a FIFO is refused before it is opened.
                assert_eq!(read_regular(&fifo, 1 << 20).unwrap_err(), Refusal::NotRegular("a FIFO"));
                assert_eq!(Refusal::NotRegular("a FIFO").describe("a mesh file"), "is a FIFO, not a regular file (expected a mesh file)");
            }
        }
    }
}
