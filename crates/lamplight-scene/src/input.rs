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
    let meta = std::fs::metadata(path).map_err(|e| Refusal::io(&e))?;
    if meta.is_dir() {
        return Err(Refusal::Directory);
    }
    if !meta.is_file() {
        return Err(Refusal::NotRegular(kind_of(meta.file_type())));
    }
    if meta.len() > max {
        return Err(Refusal::TooLarge { len: meta.len(), max });
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

/// The whole of `path` when it is a regular file of at most `max` bytes.
pub fn read_regular(path: &Path, max: u64) -> Result<Vec<u8>, Refusal> {
    let (file, len) = open_regular(path, max)?;
    let mut bytes = Vec::with_capacity(len as usize);
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
            }
        }
    }
}
