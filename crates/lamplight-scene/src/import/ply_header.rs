//! The PLY header: its format line, its `element` and `property` lines, and
//! the check that the sizes it claims fit in the file before anything is
//! allocated ([`super::ply`] reads the body it describes).

use std::path::Path;

use super::words;
use crate::error::LoadError;

/// A scalar type of the PLY header.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    pub(super) fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(super) fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }

    /// The integer range of the type (`None` for floats).
    pub(super) fn int_range(self) -> Option<(i64, i64)> {
        Some(match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => return None,
        })
    }
}

/// A property: one scalar, or a list with a count type and an item type.
#[derive(Clone, Debug)]
pub(super) struct Property {
    pub(super) name: String,
    pub(super) count: Option<Scalar>,
    pub(super) item: Scalar,
}

/// An element of the header with the line it was declared on.
#[derive(Clone, Debug)]
pub(super) struct Element {
    pub(super) name: String,
    pub(super) count: u64,
    pub(super) props: Vec<Property>,
    pub(super) line: usize,
    pub(super) count_column: usize,
}

/// How the body is encoded (the header's `format` line).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Format {
    Ascii,
    Binary { big_endian: bool },
}

/// Splits the header into elements; returns the body's byte offset.
pub(super) fn parse_header(path: &Path, bytes: &[u8]) -> Result<(Format, Vec<Element>, usize), LoadError> {
    let mut pos = 0;
    let mut line_no = 0;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if pos >= bytes.len() {
            return Err(LoadError::at(path, line_no.max(1), 1, "the PLY header ends without an `end_header` line"));
        }
        line_no += 1;
        let end = bytes[pos..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |i| pos + i);
        let raw = &bytes[pos..end];
        pos = (end + 1).min(bytes.len());
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let Ok(line) = std::str::from_utf8(raw) else {
            return Err(LoadError::at(path, line_no, 1, "expected a PLY header line of text, found binary data"));
        };
        let words: Vec<(usize, &str)> = words(line);
        let err = |i: usize, msg: String| {
            let col = words.get(i).map_or(line.chars().count() + 1, |w| w.0);
            LoadError::at(path, line_no, col, msg)
        };
        if line_no == 1 {
            if line.trim_end() != "ply" {
                return Err(LoadError::at(path, 1, 1, "expected the magic line `ply` (not a PLY file)"));
            }
            continue;
        }
        let Some(&(_, keyword)) = words.first() else { continue };
        match keyword {
            "comment" | "obj_info" => {}
            "format" => {
                format = Some(match words.get(1).map(|w| w.1) {
                    Some("ascii") => Format::Ascii,
                    Some("binary_little_endian") => Format::Binary { big_endian: false },
                    Some("binary_big_endian") => Format::Binary { big_endian: true },
                    other => {
                        return Err(err(
                            1,
                            format!(
                                "expected `ascii`, `binary_little_endian` or `binary_big_endian`, found {}",
                                other.map_or("nothing".to_string(), |o| format!("`{o}`"))
                            ),
                        ))
                    }
                });
            }
            "element" => {
                let (Some(name), Some(count)) = (words.get(1), words.get(2)) else {
                    return Err(err(words.len(), "expected `element <name> <count>`".to_string()));
                };
                let Ok(n) = count.1.parse::<u64>() else {
                    return Err(err(2, format!("expected a non-negative element count, found `{}`", count.1)));
                };
                elements.push(Element { name: name.1.to_string(), count: n, props: Vec::new(), line: line_no, count_column: count.0 });
            }
            "property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(err(0, "expected an `element` line before the first `property`".to_string()));
                };
                let ty = |i: usize| {
                    let w = words.get(i).map_or("nothing", |w| w.1);
                    Scalar::parse(w).ok_or_else(|| {
                        err(i, format!("expected a PLY type (char, uchar, short, ushort, int, uint, float, double), found `{w}`"))
                    })
                };
                let prop = if words.get(1).map(|w| w.1) == Some("list") {
                    let count = ty(2)?;
                    if count.int_range().is_none() {
                        return Err(err(2, format!("a list's count type must be an integer type, found `{}`", count.name())));
                    }
                    Property {
                        count: Some(count),
                        item: ty(3)?,
                        name: words.get(4).map(|w| w.1.to_string()).ok_or_else(|| err(4, "expected a property name".into()))?,
                    }
                } else {
                    Property {
                        count: None,
                        item: ty(1)?,
                        name: words.get(2).map(|w| w.1.to_string()).ok_or_else(|| err(2, "expected a property name".into()))?,
                    }
                };
                element.props.push(prop);
            }
            "end_header" => break,
            other => return Err(err(0, format!("expected `format`, `element`, `property`, `comment` or `end_header`, found `{other}`"))),
        }
    }
    let Some(format) = format else {
        return Err(LoadError::at(path, 2, 1, "the PLY header has no `format` line"));
    };
    Ok((format, elements, pos))
}

/// The number of lines the header takes (where the ASCII body's line count starts).
pub(super) fn header_lines(bytes: &[u8], body_start: usize) -> usize {
    bytes[..body_start].iter().filter(|&&b| b == b'\n').count()
}

/// Refuses headers whose elements cannot fit in the bytes that follow, before anything is allocated.
pub(super) fn check_sizes(path: &Path, format: Format, elements: &[Element], body_len: usize) -> Result<(), LoadError> {
    let mut needed: u128 = 0;
    for e in elements {
        // The fewest bytes one item can take: binary, its scalars and list counts;
        // ASCII, one character and one separator per value.
        let per_item: u128 = match format {
            Format::Binary { .. } => e.props.iter().map(|p| p.count.unwrap_or(p.item).size() as u128).sum(),
            Format::Ascii => 2 * e.props.len() as u128,
        };
        needed += per_item * u128::from(e.count);
        if needed > body_len as u128 + 1 {
            return Err(LoadError::at(
                path,
                e.line,
                e.count_column,
                format!(
                    "element `{}` claims {} items, which need at least {} bytes, but only {} bytes follow the header",
                    e.name, e.count, needed, body_len
                ),
            ));
        }
    }
    Ok(())
}
