//! The native scene format: TOML text to a [`SceneDescription`].
//!
//! Reading checks the file before parsing (a directory, a missing file, an empty
//! file, more than [`MAX_FILE_BYTES`], not UTF-8), and every TOML or schema error
//! becomes one [`LoadError`] at `file:line:col`. The [`Source`] kept beside the
//! description converts byte spans to lines and columns for errors found later.

use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::description::SceneDescription;
use crate::error::{LoadError, Location};

/// Largest scene file read, in bytes. Mesh data belongs in mesh files; this
/// bounds the memory a malformed or hostile file can make the parser use.
pub const MAX_FILE_BYTES: u64 = 16 << 20;

/// Where a description came from: the file and its text (for positions).
#[derive(Clone, Debug)]
pub struct Source {
    /// The file (relative mesh paths are resolved against its folder).
    pub path: PathBuf,
    /// Its text, when the description was parsed from text.
    pub text: Option<String>,
}

impl Source {
    /// A source with no text (data from elsewhere, named by `path`).
    pub fn without_text(path: impl Into<PathBuf>) -> Source {
        Source { path: path.into(), text: None }
    }

    /// The location of byte span `span`: its start as `line:col`, or the whole file.
    pub fn locate(&self, span: Option<&Range<usize>>) -> Location {
        match (span, &self.text) {
            (Some(span), Some(text)) => {
                let (line, column) = line_column(text, span.start);
                Location::LineColumn { line, column }
            }
            _ => Location::File,
        }
    }

    /// An error at `span`.
    pub fn error(&self, span: Option<&Range<usize>>, message: impl Into<String>) -> LoadError {
        LoadError { path: self.path.clone(), location: self.locate(span), message: message.into() }
    }
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

/// Reads and parses the scene file at `path`.
pub fn read(path: &Path) -> Result<(SceneDescription, Source), LoadError> {
    let meta = std::fs::metadata(path).map_err(|e| LoadError::file(path, io_message(&e)))?;
    if meta.is_dir() {
        return Err(LoadError::file(path, "is a directory, expected a scene file"));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(LoadError::file(
            path,
            format!("is {} bytes, larger than the {MAX_FILE_BYTES} bytes a scene file may have", meta.len()),
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| LoadError::file(path, io_message(&e)))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let (line, column) = line_column(&String::from_utf8_lossy(e.as_bytes()), e.utf8_error().valid_up_to());
        LoadError::at(path, line, column, "invalid UTF-8, expected a text file")
    })?;
    parse(path, text)
}

/// Parses scene text `text`, reporting errors against `path`.
pub fn parse(path: &Path, text: String) -> Result<(SceneDescription, Source), LoadError> {
    if text.trim().is_empty() {
        return Err(LoadError::file(path, "is empty, expected a scene (at least a [camera] table)"));
    }
    match toml::from_str::<SceneDescription>(&text) {
        Ok(description) => Ok((description, Source { path: path.to_path_buf(), text: Some(text) })),
        Err(e) => {
            let source = Source { path: path.to_path_buf(), text: Some(text) };
            Err(source.error(e.span().as_ref(), tidy(e.message())))
        }
    }
}

/// serde's messages, made one line and in the file's terms.
fn tidy(message: &str) -> String {
    let mut one_line = message.trim().replace('\n', "; ");
    // A node's key list (every key of every node type) is too long to help;
    // the builder lists the keys of the node's own type when `type` is known.
    if one_line.starts_with("unknown field") && one_line.contains("`own_object`") {
        if let Some(cut) = one_line.find(", expected one of") {
            one_line.truncate(cut);
            one_line.push_str(", expected a key of this node type (see docs/scene-format.md)");
        }
    }
    one_line
        .replace("a spanned value", "a table")
        .replace("$__serde_spanned_private_Spanned", "table")
        .replace("invalid type: floating point", "invalid type: number")
        .replace("invalid type: integer", "invalid type: number")
        .replace("expected f64", "expected a number")
        .replace("expected u32", "expected a whole number from 0 to 4294967295")
        .replace("expected u64", "expected a non-negative whole number")
        .replace("expected u8", "expected a whole number from 0 to 255")
}

fn io_message(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".to_string(),
        std::io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        _ => format!("cannot read: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_characters_from_one() {
        let text = "a\nbé = 1\n";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 2), (2, 1));
        assert_eq!(line_column(text, 6), (2, 4), "é is one character, two bytes");
        assert_eq!(line_column(text, 100), (3, 1));
    }
}
