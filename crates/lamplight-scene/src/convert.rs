//! `lamplight convert`: another format's scene written as a native TOML file
//! that builds to the same scene (and so renders to the same bytes).
//!
//! Mitsuba XML is read to the located table a TOML file would give
//! ([`crate::formats::mitsuba::read_table`]) and written by
//! [`crate::formats::native_writer`]. Relative `file` paths are relative to the
//! scene's folder; when the TOML goes to another folder they are made absolute.

use std::path::Path;

use lamplight_core::params::{Table, Value};

use crate::error::LoadError;
use crate::formats::{mitsuba, native_writer};

/// A converted scene: the TOML text and the reader's warnings.
#[derive(Debug)]
pub struct Converted {
    /// The native scene file.
    pub toml: String,
    /// Warnings, one line each.
    pub warnings: Vec<String>,
}

/// Converts the scene file `input` for writing to `output`.
pub fn convert(input: &Path, output: &Path, defines: &[(String, String)]) -> Result<Converted, LoadError> {
    let ext = input.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if ext.as_deref() != Some("xml") {
        return Err(LoadError::file(
            input,
            "convert reads Mitsuba scenes (.xml); mesh files render directly (`lamplight render model.obj`)",
        ));
    }
    let (mut table, source) = mitsuba::read_table(input, defines)?;
    let from = input.parent().unwrap_or(Path::new(""));
    let to = output.parent().unwrap_or(Path::new(""));
    if !crate::atomic::same_file(&absolute(from), &absolute(to)) {
        relocate(&mut table, &absolute(from));
    }
    let header = format!("Converted from {} by `lamplight convert`.", input.display());
    Ok(Converted { toml: native_writer::write(&table, &header), warnings: source.warnings })
}

fn absolute(dir: &Path) -> std::path::PathBuf {
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf())
}

/// Every relative `file` value made absolute against `dir`.
fn relocate(table: &mut Table, dir: &Path) {
    for e in &mut table.entries {
        match &mut e.item.value {
            Value::String(s) if e.key == "file" && Path::new(s.as_str()).is_relative() => *s = dir.join(&*s).to_string_lossy().into_owned(),
            Value::Table(t) => relocate(t, dir),
            Value::Array(items) => {
                for item in items {
                    if let Value::Table(t) = &mut item.value {
                        relocate(t, dir);
                    }
                }
            }
            _ => {}
        }
    }
}
