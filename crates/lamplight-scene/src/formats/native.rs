//! The native scene format: TOML text to a [`SceneDescription`].
//!
//! Reading checks the file before parsing (a directory, a missing file, an empty
//! file, more than [`MAX_FILE_BYTES`], not UTF-8). The text is parsed into
//! `toml`'s spanned document tree and converted to the generic [`Table`] of
//! [`lamplight_core::params`], every key and value keeping its byte span; the
//! [`Source`] kept beside the description turns spans into lines and columns
//! for errors found later, while the scene is built.

use std::ops::Range;
use std::path::{Path, PathBuf};

use lamplight_core::params::{Entry, Item, Loc, ParamError, Table, Value};
use toml::de::{DeTable, DeValue};

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
    /// What the reader warned about, one line each (`FILE:LINE:COL: message`).
    pub warnings: Vec<String>,
    /// The folder relative paths resolve against when it is not `path`'s
    /// (a dict's: [`Source::for_dict`]).
    pub base_dir: Option<PathBuf>,
}

impl Source {
    /// A source with no text (data from elsewhere, named by `path`).
    pub fn without_text(path: impl Into<PathBuf>) -> Source {
        Source { path: path.into(), text: None, warnings: Vec::new(), base_dir: None }
    }

    /// The source of a scene dict (Python's): its errors read
    /// `scene dict: key.path: message`, and its relative paths resolve against
    /// `base_dir`.
    pub fn for_dict(base_dir: PathBuf) -> Source {
        Source { base_dir: Some(base_dir), ..Source::without_text("scene dict") }
    }

    /// Whether this is a dict's source ([`Source::for_dict`]).
    pub fn is_dict(&self) -> bool {
        self.base_dir.is_some()
    }

    /// The folder relative mesh, texture and include paths resolve against.
    pub fn dir(&self) -> PathBuf {
        match &self.base_dir {
            Some(dir) => dir.clone(),
            None => self.path.parent().map(Path::to_path_buf).unwrap_or_default(),
        }
    }

    /// The location of byte span `span`: its start as `line:col`, or the whole file.
    pub fn locate_span(&self, span: Option<&Range<usize>>) -> Location {
        match (span, &self.text) {
            (Some(span), Some(text)) => {
                let (line, column) = line_column(text, span.start);
                Location::LineColumn { line, column }
            }
            _ => Location::File,
        }
    }

    /// The location `loc` names: a line and column, a key path, or the whole file.
    pub fn locate(&self, loc: &Loc) -> Location {
        match loc {
            Loc::Span(span) => self.locate_span(Some(span)),
            Loc::Path(path) => Location::KeyPath(path.clone()),
            Loc::Unknown => Location::File,
        }
    }

    /// An error at `loc`.
    pub fn error(&self, loc: &Loc, message: impl Into<String>) -> LoadError {
        LoadError { path: self.path.clone(), location: self.locate(loc), message: message.into() }
    }

    /// A parameter error as a [`LoadError`] of this source.
    pub fn param_error(&self, e: ParamError) -> LoadError {
        self.error(&e.loc, e.message)
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
    let text = super::read_text(path, MAX_FILE_BYTES)?;
    parse(path, text)
}

/// Parses scene text `text`, reporting errors against `path`.
pub fn parse(path: &Path, text: String) -> Result<(SceneDescription, Source), LoadError> {
    if text.trim().is_empty() {
        return Err(LoadError::file(path, "is empty, expected a scene (at least a [camera] table)"));
    }
    let source = Source::without_text(path);
    if let Some(offset) = too_deep(&text) {
        let source = Source { text: Some(text), ..source };
        let message =
            format!("nested more than {MAX_DEPTH} levels deep (tables, arrays and dotted keys together), expected at most {MAX_DEPTH}");
        return Err(source.error(&Loc::Span(offset..offset + 1), message));
    }
    let table = match DeTable::parse(&text) {
        Ok(doc) => {
            let span = doc.span();
            table(doc.into_inner(), span)
        }
        Err(e) => {
            let mut message = tidy(e.message());
            if let (true, Some(key)) = (message == "duplicate key", e.span().and_then(|s| text.get(s))) {
                message = format!("duplicate key `{}`, expected each key once per table", key.trim());
            }
            let source = Source { text: Some(text.clone()), ..source };
            return Err(source.error(&e.span().map_or(Loc::Unknown, Loc::Span), message));
        }
    };
    let source = Source { text: Some(text), ..source };
    match table.and_then(SceneDescription::from_table) {
        Ok(description) => Ok((description, source)),
        Err(e) => Err(source.param_error(e)),
    }
}

/// Deepest nesting of a scene file: tables, arrays and the parts of dotted keys
/// together. Scenes nest a few levels; the TOML parser stops at 80 with no
/// position, so the file is checked against this bound first.
pub const MAX_DEPTH: usize = 64;

/// The byte offset where `text` first nests deeper than [`MAX_DEPTH`]: brackets
/// and braces outside strings and comments, plus the dots of the key being
/// written (a dot between digits is a number's).
fn too_deep(text: &str) -> Option<usize> {
    let bytes = text.as_bytes();
    let (mut depth, mut dots, mut i) = (0usize, 0usize, 0usize);
    while i < bytes.len() {
        let b = bytes[i];
        match b {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'"' | b'\'' => {
                i = string_end(bytes, i);
                continue;
            }
            b'[' | b'{' => depth += 1,
            b']' | b'}' => depth = depth.saturating_sub(1),
            b'=' | b',' | b'\n' => dots = 0,
            b'.' => {
                let digit = |j: Option<&u8>| j.is_some_and(u8::is_ascii_digit);
                if !(digit(i.checked_sub(1).and_then(|j| bytes.get(j))) && digit(bytes.get(i + 1))) {
                    dots += 1;
                }
            }
            _ => {}
        }
        if depth + dots > MAX_DEPTH {
            return Some(i);
        }
        i += 1;
    }
    None
}

/// The index just past the string that starts at `start` (`"`, `'`, `"""` or
/// `'''`); backslash escapes count in basic strings only. An unclosed string
/// runs to the end (the parser reports it).
fn string_end(bytes: &[u8], start: usize) -> usize {
    let quote = bytes[start];
    let triple = bytes.get(start..start + 3) == Some(&[quote; 3][..]);
    let mut i = start + if triple { 3 } else { 1 };
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if quote == b'"' => i += 1,
            b'\n' if !triple => return i,
            q if q == quote && (!triple || bytes.get(i..i + 3) == Some(&[quote; 3][..])) => return i + if triple { 3 } else { 1 },
            _ => {}
        }
        i += 1;
    }
    bytes.len()
}

/// The document tree as a [`Table`]. Tables of `[header]` sections span their
/// header line; inline tables span their braces.
fn table(de: DeTable<'_>, span: Range<usize>) -> Result<Table, ParamError> {
    let mut entries = Vec::with_capacity(de.len());
    for (key, value) in de {
        let key_loc = Loc::Span(key.span());
        let value_span = value.span();
        entries.push(Entry { key: key.into_inner().into_owned(), key_loc, item: item(value.into_inner(), value_span)? });
    }
    Ok(Table { entries, loc: Loc::Span(span) })
}

fn item(value: DeValue<'_>, span: Range<usize>) -> Result<Item, ParamError> {
    let loc = Loc::Span(span.clone());
    let value = match value {
        DeValue::String(s) => Value::String(s.into_owned()),
        DeValue::Boolean(b) => Value::Bool(b),
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(v) => Value::Integer(v),
            Err(_) => return Err(ParamError { loc, message: format!("integer {i} does not fit in 64 bits") }),
        },
        DeValue::Float(f) => match parse_float(f.as_str()) {
            Some(v) => Value::Number(v),
            None => return Err(ParamError { loc, message: format!("cannot read the number {}", f.as_str()) }),
        },
        DeValue::Datetime(_) => return Err(ParamError { loc, message: "a date or time is not a scene value".into() }),
        DeValue::Array(a) => {
            let mut items = Vec::new();
            for v in a {
                let s = v.span();
                items.push(item(v.into_inner(), s)?);
            }
            Value::Array(items)
        }
        DeValue::Table(t) => Value::Table(table(t, span)?),
    };
    Ok(Item { value, loc })
}

/// TOML's float syntax as Rust reads it (`inf`, `nan` and their signs included).
fn parse_float(text: &str) -> Option<f64> {
    let text = text.replace('_', "");
    match text.trim_start_matches(['+', '-']) {
        "nan" => Some(f64::NAN),
        _ => text.parse().ok(),
    }
}

/// The TOML parser's messages, made one line.
fn tidy(message: &str) -> String {
    message.trim().replace('\n', "; ")
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

    #[test]
    fn nesting_is_counted_outside_strings_and_comments_and_numbers() {
        let deep = |n: usize| format!("a{} = 1\n", ".a".repeat(n));
        assert_eq!(too_deep(&deep(MAX_DEPTH)), None);
        assert_eq!(too_deep(&deep(MAX_DEPTH + 1)), Some(1 + 2 * MAX_DEPTH));
        let arrays = format!("x = {}1{}\n", "[".repeat(MAX_DEPTH + 1), "]".repeat(MAX_DEPTH + 1));
        assert_eq!(too_deep(&arrays), Some(4 + MAX_DEPTH));
        let quiet = format!("s = \"{0}\"\nt = '{0}'\nu = \"\"\"\n{0}\"\"\"\n# {0}\nv = [{1}]\n", "[.".repeat(100), "1.5, ".repeat(100));
        assert_eq!(too_deep(&quiet), None);
        assert_eq!(too_deep("s = \"\\\"[[[\"\n"), None, "an escaped quote does not end a basic string");
    }
}
