//! Mitsuba 3 XML scenes (`.xml`, versions 0.x, 2.x and 3.x) to the same
//! [`SceneDescription`] the TOML format makes, so that building, rendering and
//! errors are shared. The reader first makes the located table a TOML file
//! would give ([`read_table`]; `lamplight convert` writes it out as TOML), then
//! sorts it with [`SceneDescription::from_table`]. Every value keeps the place
//! of the XML attribute it came from.
//!
//! | Mitsuba | lamplight |
//! |---|---|
//! | `<sensor>` `perspective`, `thinlens`, `orthographic` ([`sensors`]) | `[camera]` `perspective` (or `window` when mirrored), `thin_lens`, `orthographic` |
//! | `<film>` `hdrfilm` width, height; `<rfilter>`; `<sampler>` `sample_count` | `[render]` width, height, `filter`, spp |
//! | `<integrator>` `path`, `direct`, `ptracer`, `volpath`, `volpathmis`, `moment` ([`integrators`]) | `integrator = "path"`, `max_depth` (same counting) |
//! | `<shape>` ([`shapes`]) | shape nodes, `[meshes]`, `[definitions]` |
//! | `<bsdf>` ([`bsdfs`]) | `[materials]` (`phong` read by the path tracer, `pbr`) |
//! | `<emitter>` ([`emitters`]) | lights, emission, `background`, `environment` |
//! | `<texture>` ([`textures`]) | texture tables |
//! | `<spectrum>` ([`spectra`]) | RGB as `scalar_rgb` computes it |
//!
//! What cannot be read the same is a warning at its place (then skipped) when
//! the rest of the image keeps its meaning, else an error.
//!
//! `docs/mitsuba.md` lists every plugin Mitsuba 3.9.1 ships with what this
//! reader does with it (read, read with a difference, skipped or refused);
//! the test `mitsuba_plugins` reads that list and holds the reader to it.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::params::{Entry, Item, Loc, ParamError, Table, Value};

use crate::description::SceneDescription;
use crate::error::LoadError;
use crate::formats::native::Source;

pub mod bsdfs;
mod cie_tables;
pub mod conductors;
pub mod emitters;
pub mod integrators;
pub mod properties;
mod rough;
pub mod sensors;
pub mod serialized;
pub mod shapes;
pub mod sided;
pub mod spectra;
pub mod textures;
pub mod transforms;
pub mod volume;
pub mod xml;

use properties::Plugin;
use xml::El;

/// Reads the Mitsuba scene at `path` with `-D name=value` pairs `defines`.
pub fn read(path: &Path, defines: &[(String, String)]) -> Result<(SceneDescription, Source), LoadError> {
    let (table, source) = read_table(path, defines)?;
    match SceneDescription::from_table(table) {
        Ok(d) => Ok((d, source)),
        Err(e) => Err(source.param_error(e)),
    }
}

/// Reads the Mitsuba scene at `path` to the table a TOML scene file would give.
pub fn read_table(path: &Path, defines: &[(String, String)]) -> Result<(Table, Source), LoadError> {
    let text = crate::formats::read_text(path, xml::MAX_FILE_BYTES)?;
    parse_table(path, text, defines)
}

/// Parses Mitsuba XML `text` (errors and relative files against `path`).
pub fn parse_table(path: &Path, text: String, defines: &[(String, String)]) -> Result<(Table, Source), LoadError> {
    if text.trim().is_empty() {
        return Err(LoadError::file(path, "is empty, expected a Mitsuba scene (<scene version=\"3.0.0\">)"));
    }
    let source = |text: Option<String>| Source { text, ..Source::without_text(path) };
    let doc = match xml::read(path, text, defines) {
        Ok(doc) => doc,
        Err((e, text)) => return Err(source(text).param_error(e)),
    };
    let mut ctx = Ctx::new(&doc);
    let result = ctx.scene(&doc.root);
    let mut src = source(Some(doc.text.clone()));
    let table = result.map_err(|e| src.param_error(e))?;
    let mut seen = std::collections::HashSet::new();
    for (loc, message) in ctx.warnings {
        let line = src.error(&loc, message).to_string();
        if seen.insert(line.clone()) {
            src.warnings.push(line);
        }
    }
    Ok((table, src))
}

/// What reading a scene collects.
pub struct Ctx<'a> {
    /// Elements by `id`.
    pub ids: HashMap<String, &'a El>,
    /// Folders searched for files.
    pub search_paths: &'a [PathBuf],
    /// Warnings: place and message.
    pub warnings: Vec<(Loc, String)>,
    /// `materials` entries.
    pub materials: Vec<Entry>,
    /// BSDF ids already made materials.
    pub material_ids: HashMap<String, String>,
    /// `meshes` entries.
    pub meshes: Vec<Entry>,
    /// `definitions` entries.
    pub definitions: Vec<Entry>,
    /// `objects`.
    pub objects: Vec<Item>,
    /// Top-level values (`background`, `environment`).
    pub globals: Vec<Entry>,
    /// `[render]` entries.
    pub render: Vec<Entry>,
    /// `[camera]`.
    pub camera: Option<Item>,
    /// Every `mesh_attribute` read so far: its `name` and place.
    pub attribute_reads: Vec<(String, Loc)>,
    /// The attributes each material reads ([`bsdfs::material_name`]), for the
    /// meshes it is placed on ([`shapes`]).
    pub material_attributes: HashMap<String, Vec<(String, Loc)>>,
    counter: usize,
}

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

impl<'a> Ctx<'a> {
    fn new(doc: &'a xml::Document) -> Ctx<'a> {
        Ctx {
            ids: HashMap::new(),
            search_paths: &doc.search_paths,
            warnings: Vec::new(),
            materials: Vec::new(),
            material_ids: HashMap::new(),
            meshes: Vec::new(),
            definitions: Vec::new(),
            objects: Vec::new(),
            globals: Vec::new(),
            render: Vec::new(),
            camera: None,
            attribute_reads: Vec::new(),
            material_attributes: HashMap::new(),
            counter: 0,
        }
    }

    fn collect_ids(&mut self, el: &'a El) -> Result<(), ParamError> {
        for c in &el.children {
            if c.tag != "ref" {
                if let Some(id) = c.attr("id") {
                    if self.ids.insert(id.value.clone(), c).is_some() {
                        return Err(err(&id.loc, format!("id \"{}\" is given to two objects", id.value)));
                    }
                }
            }
            self.collect_ids(c)?;
        }
        Ok(())
    }

    fn scene(&mut self, root: &'a El) -> Result<Table, ParamError> {
        self.collect_ids(root)?;
        let mut sensor_seen = false;
        for el in &root.children {
            match el.tag.as_str() {
                "integrator" => integrators::read(self, el)?,
                "sensor" if sensor_seen => self.warn(&el.loc, "sensor: only the first <sensor> is rendered, this one is ignored"),
                "sensor" => {
                    sensor_seen = true;
                    sensors::read(self, el)?
                }
                "shape" => {
                    let mut out = Vec::new();
                    shapes::read(self, el, &mut out)?;
                    self.objects.extend(out);
                }
                "emitter" => emitters::read(self, el)?,
                "bsdf" => {
                    if el.get("id").is_some() {
                        bsdfs::material_name(self, el)?;
                    } else {
                        self.warn(&el.loc, "bsdf: a top-level <bsdf> without an id is never used, ignored");
                    }
                }
                "texture" | "spectrum" | "rgb" => {}
                other => self.warn(&el.loc, format!("<{other}>: not supported, ignored")),
            }
        }
        if self.camera.is_none() {
            return Err(err(&root.loc, "scene: has no <sensor>, expected one (lamplight renders one camera)"));
        }
        let mut entries = std::mem::take(&mut self.globals);
        // Mitsuba's BSDFs see a hit's side by its shading normal (a coarse mesh's
        // vertex normals can turn a face seen from the front into a back face).
        self.render.push(entry("sides", text("shading", &root.loc)));
        entries.push(entry("render", table(std::mem::take(&mut self.render), root.loc.clone())));
        entries.push(entry("camera", self.camera.take().expect("checked")));
        let named = |list: Vec<Entry>| table(list, root.loc.clone());
        if !self.materials.is_empty() {
            entries.push(entry("materials", named(std::mem::take(&mut self.materials))));
        }
        if !self.meshes.is_empty() {
            entries.push(entry("meshes", named(std::mem::take(&mut self.meshes))));
        }
        if !self.definitions.is_empty() {
            entries.push(entry("definitions", named(std::mem::take(&mut self.definitions))));
        }
        entries.push(entry("objects", Item { value: Value::Array(std::mem::take(&mut self.objects)), loc: root.loc.clone() }));
        Ok(Table { entries, loc: root.loc.clone() })
    }

    /// A warning at `loc`.
    pub fn warn(&mut self, loc: &Loc, message: impl Into<String>) {
        self.warnings.push((loc.clone(), message.into()));
    }

    /// Reports what `plugin` left unread.
    pub fn finish(&mut self, plugin: Plugin<'_>) {
        self.warnings.extend(plugin.finish());
    }

    /// A new name `prefix_N`.
    pub fn fresh(&mut self, prefix: &str) -> String {
        self.counter += 1;
        format!("{prefix}_{}", self.counter)
    }

    /// `el`, or the element a `<ref id>` names.
    pub fn deref(&self, el: &'a El) -> Result<&'a El, ParamError> {
        if el.tag != "ref" {
            return Ok(el);
        }
        let id = el.require("id")?;
        self.ids.get(&id.value).copied().ok_or_else(|| err(&id.loc, format!("ref: no object has id \"{}\"", id.value)))
    }

    /// The file `name` (a `filename` value at `loc`) as the scene should name it:
    /// found in the scene's folder or a `<path>` folder.
    pub fn file(&self, name: &str, loc: &Loc) -> Result<String, ParamError> {
        let found = xml::resolve(self.search_paths, name).ok_or_else(|| err(loc, format!("no such file \"{name}\"")))?;
        crate::input::check_regular(&found).map_err(|r| err(loc, format!("\"{name}\" {}", r.describe("a file"))))?;
        let base = &self.search_paths[0];
        Ok(match found.strip_prefix(base) {
            Ok(rel) if !base.as_os_str().is_empty() || found.is_relative() => rel.to_string_lossy().into_owned(),
            _ => found.to_string_lossy().into_owned(),
        })
    }

    /// The full path of a file [`Ctx::file`] named.
    pub fn full_path(&self, name: &str) -> PathBuf {
        let p = Path::new(name);
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.search_paths[0].join(p)
        }
    }
}

/// An entry whose key sits at its value's place.
pub fn entry(key: &str, item: Item) -> Entry {
    Entry { key: key.to_string(), key_loc: item.loc.clone(), item }
}

/// A number.
pub fn num(v: f64, loc: &Loc) -> Item {
    Item { value: Value::Number(v), loc: loc.clone() }
}

/// An integer.
pub fn int(v: i64, loc: &Loc) -> Item {
    Item { value: Value::Integer(v), loc: loc.clone() }
}

/// A boolean.
pub fn boolean(v: bool, loc: &Loc) -> Item {
    Item { value: Value::Bool(v), loc: loc.clone() }
}

/// A string.
pub fn text(v: &str, loc: &Loc) -> Item {
    Item { value: Value::String(v.to_string()), loc: loc.clone() }
}

/// `[x, y, z]` (points, vectors and colours).
pub fn vec3(v: Vec3, loc: &Loc) -> Item {
    Item { value: Value::Array(v.to_array().iter().map(|&c| num(c, loc)).collect()), loc: loc.clone() }
}

/// `[a, b]`.
pub fn pair(a: f64, b: f64, loc: &Loc) -> Item {
    Item { value: Value::Array(vec![num(a, loc), num(b, loc)]), loc: loc.clone() }
}

/// Four rows of four numbers.
pub fn matrix(m: &Mat4, loc: &Loc) -> Item {
    let rows = (0..4).map(|r| Item { value: Value::Array(m.row(r).to_array().iter().map(|&c| num(c, loc)).collect()), loc: loc.clone() });
    Item { value: Value::Array(rows.collect()), loc: loc.clone() }
}

/// A table of `entries`.
pub fn table(entries: Vec<Entry>, loc: Loc) -> Item {
    Item { value: Value::Table(Table { entries, loc: loc.clone() }), loc }
}

/// A table from `(key, item)` pairs.
pub fn table_of(pairs: Vec<(&str, Item)>, loc: &Loc) -> Item {
    table(pairs.into_iter().map(|(k, v)| entry(k, v)).collect(), loc.clone())
}
