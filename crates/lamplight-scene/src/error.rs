//! Errors of loading scenes and meshes: one message that names the file, the
//! place in it and what was expected.

use std::fmt;
use std::path::{Path, PathBuf};

/// Where in a file a problem is.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Location {
    /// The file as a whole (missing, empty, a directory, unreadable).
    File,
    /// A text position, both 1-based.
    LineColumn {
        /// Line number, from 1.
        line: usize,
        /// Column number (in characters), from 1.
        column: usize,
    },
    /// A JSON path such as `meshes[0].primitives[1].attributes.POSITION` (glTF).
    JsonPath(String),
    /// A byte offset into a binary file (PLY body, glTF buffer).
    ByteOffset(u64),
    /// A key path into a Python dict, such as `objects[2].radius`.
    KeyPath(String),
}

/// A scene or mesh file could not be loaded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    /// The file.
    pub path: PathBuf,
    /// Where in it.
    pub location: Location,
    /// What was found and what was expected.
    pub message: String,
}

impl LoadError {
    /// An error about the file as a whole.
    pub fn file(path: &Path, message: impl Into<String>) -> LoadError {
        LoadError { path: path.to_path_buf(), location: Location::File, message: message.into() }
    }

    /// An error at a line and column (1-based).
    pub fn at(path: &Path, line: usize, column: usize, message: impl Into<String>) -> LoadError {
        LoadError { path: path.to_path_buf(), location: Location::LineColumn { line, column }, message: message.into() }
    }

    /// An error at a JSON path.
    pub fn json(path: &Path, json_path: impl Into<String>, message: impl Into<String>) -> LoadError {
        LoadError { path: path.to_path_buf(), location: Location::JsonPath(json_path.into()), message: message.into() }
    }

    /// An error at a byte offset.
    pub fn byte(path: &Path, offset: u64, message: impl Into<String>) -> LoadError {
        LoadError { path: path.to_path_buf(), location: Location::ByteOffset(offset), message: message.into() }
    }
}

impl fmt::Display for LoadError {
    /// `file:line:col: message`, `file: at JSON path: message`, `file: at byte N: message`,
    /// `scene dict: key.path: message`, or `file: message`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self.path.display();
        match &self.location {
            Location::File => write!(f, "{path}: {}", self.message),
            Location::LineColumn { line, column } => write!(f, "{path}:{line}:{column}: {}", self.message),
            Location::JsonPath(p) => write!(f, "{path}: at {p}: {}", self.message),
            Location::ByteOffset(o) => write!(f, "{path}: at byte {o}: {}", self.message),
            Location::KeyPath(p) => write!(f, "{path}: {p}: {}", self.message),
        }
    }
}

impl std::error::Error for LoadError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_file_and_place() {
        let p = Path::new("scene.toml");
        assert_eq!(LoadError::at(p, 3, 7, "expected a number").to_string(), "scene.toml:3:7: expected a number");
        assert_eq!(
            LoadError::json(p, "nodes[2].mesh", "index 9 out of range").to_string(),
            "scene.toml: at nodes[2].mesh: index 9 out of range"
        );
        assert_eq!(LoadError::byte(p, 120, "truncated").to_string(), "scene.toml: at byte 120: truncated");
        assert_eq!(LoadError::file(p, "is a directory").to_string(), "scene.toml: is a directory");
    }
}
