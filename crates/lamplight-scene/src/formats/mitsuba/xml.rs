//! Mitsuba XML structure: the document tree with `<include>` spliced in,
//! `<default>` and `-D` values substituted for `$name`, `<path>` folders
//! collected, and version 0.x names upgraded (`fovAxis` -> `fov_axis`).
//!
//! Every element and attribute keeps its place: a byte span of the main file
//! ([`Loc::Span`]), or `FILE:LINE:COL` for an included file ([`Loc::Path`]).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use lamplight_core::params::{Loc, ParamError};

use crate::formats::native::line_column;

/// Largest XML file read, in bytes (the native format's bound).
pub const MAX_FILE_BYTES: u64 = crate::formats::native::MAX_FILE_BYTES;
/// Deepest element nesting.
pub const MAX_DEPTH: usize = 64;
/// Deepest chain of `<include>`s.
pub const MAX_INCLUDE_DEPTH: usize = 16;
/// Most elements of a scene, includes together.
pub const MAX_ELEMENTS: usize = 1 << 20;
/// Most `<include>`s one scene reads, each time a file is included counted
/// (eleven files each including the next four times would be 4^10).
pub const MAX_INCLUDES: usize = 1024;
/// Most bytes of XML one scene reads: the main file and every included file
/// together, each time it is included (64 MiB: four files at the size cap).
pub const MAX_XML_BYTES: u64 = 64 << 20;
/// Longest attribute value after `$name` substitution (1 MiB): a chain of
/// `<default>`s that each double the last stops here, at its line.
pub const MAX_VALUE_BYTES: u64 = 1 << 20;
/// Most bytes the substitutions of one scene make together (16 MiB, a scene
/// file's size): a long `-D` value named many times stops here.
pub const MAX_SUBSTITUTED_BYTES: u64 = 16 << 20;

/// One attribute: name, value (substituted) and the value's place.
#[derive(Clone, Debug)]
pub struct Attr {
    /// The attribute's name.
    pub name: String,
    /// Its value, `$name`s replaced.
    pub value: String,
    /// Where the value is written.
    pub loc: Loc,
}

/// One element.
#[derive(Clone, Debug)]
pub struct El {
    /// The tag (`shape`, `float`, ...).
    pub tag: String,
    /// Attributes in source order.
    pub attrs: Vec<Attr>,
    /// Child elements, includes spliced in.
    pub children: Vec<El>,
    /// Where the element starts.
    pub loc: Loc,
}

impl El {
    /// The attribute called `name`.
    pub fn attr(&self, name: &str) -> Option<&Attr> {
        self.attrs.iter().find(|a| a.name == name)
    }

    /// The value of attribute `name`.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.attr(name).map(|a| a.value.as_str())
    }

    /// The value of attribute `name`, or an error naming the element.
    pub fn require(&self, name: &str) -> Result<&Attr, ParamError> {
        self.attr(name)
            .ok_or_else(|| ParamError { loc: self.loc.clone(), message: format!("<{}>: needs the attribute `{name}`", self.tag) })
    }

    /// `<tag type="...">` as messages name it.
    pub fn label(&self) -> String {
        match self.get("type") {
            Some(t) => format!("{} \"{t}\"", self.tag),
            None => format!("<{}>", self.tag),
        }
    }
}

/// A parsed document: the root `<scene>` and what reading it found.
#[derive(Debug)]
pub struct Document {
    /// The root element (`<scene>`), includes spliced in.
    pub root: El,
    /// Folders `<path>` named, searched for files after the scene's own folder.
    pub search_paths: Vec<PathBuf>,
    /// The main file's text (spans index it).
    pub text: String,
}

struct Reader {
    params: HashMap<String, String>,
    search_paths: Vec<PathBuf>,
    elements: usize,
    /// Files being read, outermost first (cycle check; includes resolve
    /// against the folder of the last).
    stack: Vec<PathBuf>,
    /// `<include>`s read so far.
    includes: usize,
    /// Bytes of XML read so far, the main file's included.
    xml_bytes: u64,
    /// Bytes the substitutions made so far.
    substituted: u64,
}

/// Reads the Mitsuba scene at `path`; `defines` are `-D name=value` pairs
/// (they win over `<default>`).
pub fn read(path: &Path, text: String, defines: &[(String, String)]) -> Result<Document, (ParamError, Option<String>)> {
    let mut reader = Reader {
        params: defines.iter().cloned().collect(),
        search_paths: Vec::new(),
        elements: 0,
        stack: vec![path.to_path_buf()],
        includes: 0,
        xml_bytes: text.len() as u64,
        substituted: 0,
    };
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    reader.search_paths.push(dir);
    match reader.document(&text, None) {
        Ok(root) => Ok(Document { root, search_paths: reader.search_paths, text }),
        Err(e) => Err((e, Some(text))),
    }
}

/// Where byte `offset` of a file is: a span of the main file, else `FILE:LINE:COL`.
fn place(text: &str, file: Option<&Path>, range: std::ops::Range<usize>) -> Loc {
    match file {
        None => Loc::Span(range),
        Some(f) => {
            let (line, col) = line_column(text, range.start);
            Loc::Path(format!("{}:{line}:{col}", f.display()))
        }
    }
}

impl Reader {
    /// Parses `text` (the main file when `file` is `None`) to its root `<scene>`.
    fn document(&mut self, text: &str, file: Option<&Path>) -> Result<El, ParamError> {
        let options = roxmltree::ParsingOptions { allow_dtd: false, nodes_limit: MAX_ELEMENTS as u32 * 4, ..Default::default() };
        let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| {
            let pos = e.pos();
            let offset = offset_of(text, pos.row as usize, pos.col as usize);
            let message = e.to_string();
            let message = match message.rfind(" at ") {
                Some(i) if message[i + 4..].contains(':') => message[..i].to_string(),
                _ => message,
            };
            ParamError { loc: place(text, file, offset..offset), message: format!("malformed XML: {message}") }
        })?;
        let root = doc.root_element();
        let loc = place(text, file, root.range());
        if root.tag_name().name() != "scene" {
            return Err(ParamError { loc, message: format!("expected a <scene> root element, got <{}>", root.tag_name().name()) });
        }
        let upgrade = match root.attribute("version") {
            None => return Err(ParamError { loc, message: "<scene>: needs the attribute `version` (such as \"3.0.0\")".into() }),
            Some(v) => {
                let major = v.split('.').next().and_then(|m| m.trim().parse::<u32>().ok());
                match major {
                    Some(m) => m < 2,
                    None => {
                        let loc = place(text, file, root.attribute_node("version").expect("present").range_value());
                        return Err(ParamError {
                            loc,
                            message: format!("<scene>: version: expected a version such as \"3.0.0\", got \"{v}\""),
                        });
                    }
                }
            }
        };
        self.element(root, text, file, 0, upgrade)
    }

    fn element(
        &mut self,
        node: roxmltree::Node<'_, '_>,
        text: &str,
        file: Option<&Path>,
        depth: usize,
        upgrade: bool,
    ) -> Result<El, ParamError> {
        let loc = place(text, file, node.range());
        if depth > MAX_DEPTH {
            return Err(ParamError { loc, message: format!("elements nest more than {MAX_DEPTH} deep, expected at most {MAX_DEPTH}") });
        }
        self.elements += 1;
        if self.elements > MAX_ELEMENTS {
            return Err(ParamError { loc, message: format!("more than {MAX_ELEMENTS} elements, expected at most {MAX_ELEMENTS}") });
        }
        let mut tag = node.tag_name().name().to_string();
        if upgrade {
            tag = tag.to_ascii_lowercase();
        }
        let mut attrs = Vec::new();
        for a in node.attributes() {
            let aloc = place(text, file, a.range_value());
            let value = self.substitute(a.value(), &aloc)?;
            let value = if upgrade && a.name() == "name" { snake_case(&value) } else { value };
            attrs.push(Attr { name: a.name().to_string(), value, loc: aloc });
        }
        let mut el = El { tag, attrs, children: Vec::new(), loc };
        for child in node.children() {
            if child.is_text() && child.text().is_some_and(|t| !t.trim().is_empty()) {
                let loc = place(text, file, child.range());
                return Err(ParamError { loc, message: format!("<{}>: unexpected text, expected only elements", el.tag) });
            }
            if !child.is_element() {
                continue;
            }
            let c = self.element(child, text, file, depth + 1, upgrade)?;
            match c.tag.as_str() {
                "default" => {
                    let name = c.require("name")?.value.clone();
                    let value = c.require("value")?.value.clone();
                    self.params.entry(name).or_insert(value);
                }
                "path" => {
                    let value = c.require("value")?;
                    let p = PathBuf::from(&value.value);
                    let p = if p.is_absolute() { p } else { self.search_paths[0].join(p) };
                    self.search_paths.push(p);
                }
                "include" => {
                    let name = c.require("filename")?;
                    let included = self.include(name)?;
                    el.children.extend(included.children);
                }
                _ => el.children.push(c),
            }
        }
        Ok(el)
    }

    /// The file an `<include>` names, found as Mitsuba 3 finds it: beside the
    /// file that includes it, then in the scene's folder and the `<path>`
    /// folders (Mitsuba 3.9.1 reads `sub/b.xml` for an `<include
    /// filename="b.xml"/>` in `sub/a.xml`, even when the scene's folder has a
    /// `b.xml` too). Each include counts against [`MAX_INCLUDES`] and its bytes
    /// against [`MAX_XML_BYTES`], checked before the file is read.
    fn include(&mut self, name: &Attr) -> Result<El, ParamError> {
        let err = |message: String| ParamError { loc: name.loc.clone(), message };
        let here = self.stack.last().and_then(|p| p.parent()).map(Path::to_path_buf).unwrap_or_default();
        let folders: Vec<PathBuf> = std::iter::once(here).chain(self.search_paths.iter().cloned()).collect();
        let path = resolve(&folders, &name.value).ok_or_else(|| err(format!("include: no such file \"{}\"", name.value)))?;
        if self.stack.len() > MAX_INCLUDE_DEPTH {
            return Err(err(format!("includes nest more than {MAX_INCLUDE_DEPTH} deep")));
        }
        if self.stack.iter().any(|p| same_file(p, &path)) {
            return Err(err(format!("include: \"{}\" includes itself", name.value)));
        }
        self.includes += 1;
        if self.includes > MAX_INCLUDES {
            return Err(err(format!(
                "include: more than {MAX_INCLUDES} includes in one scene (each time a file is included counts), expected at most {MAX_INCLUDES}"
            )));
        }
        let refused = |r: crate::input::Refusal| err(format!("include: \"{}\" {}", path.display(), r.describe("an XML file")));
        let (file, len) = crate::input::open_regular(&path, MAX_FILE_BYTES).map_err(refused)?;
        if self.xml_bytes + len > MAX_XML_BYTES {
            return Err(err(format!(
                "include: \"{}\" ({len} bytes) would make the scene read more than {MAX_XML_BYTES} bytes of XML \
                 (the main file and each included file, each time it is included), expected at most 64 MiB",
                name.value
            )));
        }
        self.xml_bytes += len;
        let bytes = crate::input::read_opened(file, len, MAX_FILE_BYTES).map_err(refused)?;
        let text = String::from_utf8(bytes).map_err(|_| err(format!("include: \"{}\" is not UTF-8 text", path.display())))?;
        self.stack.push(path.clone());
        let root = self.document(&text, Some(&path));
        self.stack.pop();
        root
    }

    /// `value` with every `$name` replaced by its parameter. The length is
    /// added up first, so that a value over [`MAX_VALUE_BYTES`], or one that
    /// takes the scene past [`MAX_SUBSTITUTED_BYTES`], is refused before it is
    /// allocated.
    fn substitute(&mut self, value: &str, loc: &Loc) -> Result<String, ParamError> {
        if !value.contains('$') {
            return Ok(value.to_string());
        }
        let pieces = self.pieces(value, loc)?;
        let length: u64 = pieces.iter().map(|p| p.len() as u64).sum();
        let fail = |message: String| Err(ParamError { loc: loc.clone(), message });
        if length > MAX_VALUE_BYTES {
            return fail(format!(
                "substituting the $names would make this value {length} bytes long, expected at most {MAX_VALUE_BYTES} (1 MiB)"
            ));
        }
        if self.substituted + length > MAX_SUBSTITUTED_BYTES {
            return fail(format!(
                "substituting the $names would make the scene's values more than {MAX_SUBSTITUTED_BYTES} bytes together \
                 (a long value named many times), expected at most 16 MiB"
            ));
        }
        let out = pieces.concat();
        self.substituted += length;
        Ok(out)
    }

    /// `value` cut into literal text and the parameters its `$name`s name.
    fn pieces<'v>(&'v self, value: &'v str, loc: &Loc) -> Result<Vec<&'v str>, ParamError> {
        let mut out = Vec::new();
        let mut rest = value;
        while let Some(i) = rest.find('$') {
            out.push(&rest[..i]);
            let after = &rest[i + 1..];
            let len = after.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(after.len());
            let name = &after[..len];
            if name.is_empty() {
                out.push("$");
            } else {
                match self.params.get(name) {
                    Some(v) => out.push(v.as_str()),
                    None => {
                        return Err(ParamError {
                            loc: loc.clone(),
                            message: format!(
                                "undefined parameter ${name} (give it with <default name=\"{name}\" value=\"...\"/> or -D {name}=VALUE)"
                            ),
                        })
                    }
                }
            }
            rest = &after[len..];
        }
        out.push(rest);
        Ok(out)
    }
}

/// The file `name` names: absolute, or in the first search folder where
/// something of that name exists (as Mitsuba's file resolver: what it is, a
/// FIFO, a folder or a device, is for the reader to say, not "no such file").
pub fn resolve(search_paths: &[PathBuf], name: &str) -> Option<PathBuf> {
    let p = Path::new(name);
    if p.is_absolute() {
        return p.exists().then(|| p.to_path_buf());
    }
    search_paths.iter().map(|d| d.join(p)).find(|c| c.exists())
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// The byte offset of 1-based `row`, `col` (characters) in `text`.
fn offset_of(text: &str, row: usize, col: usize) -> usize {
    let mut offset = 0;
    for (i, line) in text.split_inclusive('\n').enumerate() {
        if i + 1 == row {
            return offset + line.char_indices().nth(col.saturating_sub(1)).map_or(line.len(), |(b, _)| b);
        }
        offset += line.len();
    }
    text.len()
}

/// `fovAxis` as `fov_axis`: an underscore before an upper-case letter that
/// follows a lower-case letter or digit, then lower case (Mitsuba 3's upgrade
/// of 0.x names, so `intIOR` is `int_ior`).
pub fn snake_case(name: &str) -> String {
    let mut out = String::with_capacity(name.len() + 4);
    let mut prev_lower = false;
    for c in name.chars() {
        if c.is_ascii_uppercase() && prev_lower {
            out.push('_');
        }
        prev_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        out.push(c.to_ascii_lowercase());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn old_names_become_snake_case() {
        assert_eq!(snake_case("fovAxis"), "fov_axis");
        assert_eq!(snake_case("intIOR"), "int_ior");
        assert_eq!(snake_case("sampleCount"), "sample_count");
    }

    #[test]
    fn offsets_follow_rows_and_columns() {
        assert_eq!(offset_of("ab\ncd", 2, 2), 4);
        assert_eq!(offset_of("ab\ncd", 1, 1), 0);
    }
}
