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

/// The format of files ending in `.extension`.
pub fn find(extension: &str) -> Option<&'static Format> {
    FORMATS.iter().find(|f| f.extension == extension)
}
