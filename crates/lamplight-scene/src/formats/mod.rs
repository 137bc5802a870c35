//! Scene file formats, each chosen by its file extension ([`FORMATS`]): the
//! native TOML format ([`native`]) and Mitsuba 3 XML ([`mitsuba`]).

use std::path::Path;

use crate::description::SceneDescription;
use crate::error::LoadError;

pub mod mitsuba;
pub mod native;
pub mod native_writer;

/// A scene format: its extension (lower case) and its reader, which takes the
/// file and the `-D name=value` definitions (formats without parameters ignore them).
pub struct Format {
    /// The extension, without the dot.
    pub extension: &'static str,
    /// Reads a file.
    pub read: fn(&Path, &[(String, String)]) -> Read,
}

/// What a reader returns: the description and its source, or the error.
pub type Read = Result<(SceneDescription, native::Source), LoadError>;

/// The scene formats.
pub static FORMATS: &[Format] =
    &[Format { extension: "toml", read: |path, _| native::read(path) }, Format { extension: "xml", read: mitsuba::read }];

/// The text of the scene file at `path` (a regular file of at most `max_bytes`,
/// valid UTF-8), or the one error every format gives for a file it cannot read.
pub(crate) fn read_text(path: &Path, max_bytes: u64) -> Result<String, LoadError> {
    use crate::input::{self, Refusal};
    let bytes = input::read_regular(path, max_bytes).map_err(|r| {
        LoadError::file(
            path,
            match r {
                Refusal::NotFound => "no such file".to_string(),
                Refusal::PermissionDenied => "permission denied".to_string(),
                Refusal::Directory => "is a directory, expected a scene file".to_string(),
                Refusal::NotRegular(kind) => format!("is {kind}, expected a scene file"),
                Refusal::TooLarge { len, max } => format!("is {len} bytes, larger than the {max} bytes a scene file may have"),
                Refusal::Io(e) => format!("cannot read: {e}"),
            },
        )
    })?;
    String::from_utf8(bytes).map_err(|e| {
        let (line, column) = native::line_column(&String::from_utf8_lossy(e.as_bytes()), e.utf8_error().valid_up_to());
        LoadError::at(path, line, column, "invalid UTF-8, expected a text file")
    })
}

/// The format of files ending in `.extension`.
pub fn find(extension: &str) -> Option<&'static Format> {
    FORMATS.iter().find(|f| f.extension == extension)
}
