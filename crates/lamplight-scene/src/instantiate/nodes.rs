//! The node tree: groups and instances compose transforms and pass a default
//! material down; shapes and lights are made by their kinds in the registry;
//! meshes place mesh assets.
//!
//! Limits keep a hostile file from costing unbounded time or memory: nesting at
//! most [`MAX_NESTING`] deep, an instance may not (directly or not) place itself
//! (reported with the chain of names), and at most [`MAX_OBJECTS`] objects in
//! all, which also stops exponential instancing (a definition placing another
//! twice, 40 levels deep). Each mesh asset is loaded once and shared. Lights are
//! made after every shape, so that a light may name any shape as its own.

use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;
use std::sync::Arc;

use lamplight_core::lights::LightContext;
use lamplight_core::materials::{Material, Textures};
use lamplight_core::math::Mat4;
use lamplight_core::params::{unknown, unknown_among, Kind, ParamError, Params};
use lamplight_core::shapes::{placed, Shape, TriangleMesh};
use lamplight_core::SceneBuilder;

use super::mesh_animation::{self, MeshClip};
use super::mesh_keys::{inline, Shading, MESH_PARAMS};
use super::transform;
use crate::description::{Node, SceneDescription};
use crate::error::{LoadError, Location};
use crate::formats::native::Source;
use crate::{import, registry};

/// Deepest nesting of groups and instances.
pub const MAX_NESTING: usize = 64;
/// Most objects one scene may have.
pub const MAX_OBJECTS: usize = 1 << 22;

/// A loaded mesh asset: its parts (mesh, placement in the asset, imported material).
/// A glTF part's placements at the shutter's instants follow it, when its
/// own animation moves it ([`super::motion::Motion::keys`]).
pub(super) type Asset = Arc<Vec<Part>>;
/// A part of a mesh asset: its mesh, placement, imported material and
/// placements at the shutter's instants.
pub(super) type Part = (Arc<TriangleMesh>, Mat4, Option<usize>, Option<Arc<[Mat4]>>);

struct Ctx<'a> {
    desc: &'a SceneDescription,
    source: &'a Source,
    builder: &'a mut SceneBuilder,
    materials: BTreeMap<String, usize>,
    default_material: Option<usize>,
    assets: HashMap<String, Asset>,
    files: HashMap<(PathBuf, Shading, Option<String>, MeshClip), Asset>,
    /// Each mesh file decoded, read once per build however many clips pose it.
    imported: HashMap<PathBuf, import::Imported>,
    /// The scene's time in seconds, for glTF animations (`None`: no `[animation]`).
    seconds: Option<f64>,
    names: HashMap<String, Vec<usize>>,
    lights: Vec<(&'a Node, Mat4)>,
    stack: Vec<String>,
    /// The mesh files' warnings, `FILE: what`.
    warnings: Vec<String>,
    /// The shapes' transforms over the shutter, for motion blur.
    motion: Option<super::motion::Motion>,
    /// Shape and mesh nodes placed so far ([`super::motion::Motion::keys`]).
    leaf: usize,
}

/// Adds every top-level node of `desc` to `builder` at the scene's time
/// `seconds` (its glTF meshes' animations: [`super::mesh_animation`]);
/// returns the warnings of the mesh files read, each file's once.
pub(super) fn add_all(
    desc: &SceneDescription,
    source: &Source,
    builder: &mut SceneBuilder,
    materials: BTreeMap<String, usize>,
    textures: &Textures<'_>,
    seconds: Option<f64>,
    shutter: &super::motion::Instants,
) -> Result<Vec<String>, LoadError> {
    let mut ctx = Ctx {
        desc,
        source,
        builder,
        materials,
        default_material: None,
        assets: HashMap::new(),
        files: HashMap::new(),
        imported: HashMap::new(),
        seconds,
        names: HashMap::new(),
        lights: Vec::new(),
        stack: Vec::new(),
        warnings: Vec::new(),
        motion: None,
        leaf: 0,
    };
    // Count first, so that exponential instancing fails at once instead of
    // after allocating millions of objects.
    let mut counts = HashMap::new();
    for node in &desc.objects {
        let planned = count(desc, node, &mut counts, 0);
        if planned > MAX_OBJECTS as u64 {
            let message = format!("{}: expands to more than {MAX_OBJECTS} objects (is a definition instanced exponentially?)", node.label);
            return Err(source.error(&node.params.loc, message));
        }
    }
    ctx.motion = super::motion::Motion::new(shutter).map_err(|e| source.param_error(e))?;
    for node in &desc.objects {
        ctx.node(node, Mat4::IDENTITY, None, 0)?;
    }
    for (node, world) in std::mem::take(&mut ctx.lights) {
        let kind = Kind::find(registry::LIGHTS, &node.kind).expect("only light kinds are deferred");
        let names = &ctx.names;
        let object = |name: &str| -> Result<usize, String> {
            match names.get(name).map(Vec::as_slice).unwrap_or_default() {
                [one] => Ok(*one),
                [] => Err(format!("\"{name}\" names no shape")),
                many => Err(format!("\"{name}\" names {} objects, expected one", many.len())),
            }
        };
        let p = Params::new(node.label.clone(), &node.params);
        let light = p.read(kind.params, &[], |p| (kind.build)(p, &LightContext { world, object: &object, textures: *textures }));
        let light = light.map_err(|e| source.param_error(e))?;
        ctx.builder.shared_light(light);
    }
    Ok(ctx.warnings)
}

impl<'a> Ctx<'a> {
    fn fail(&self, e: ParamError) -> LoadError {
        self.source.param_error(e)
    }

    fn node(&mut self, n: &'a Node, parent: Mat4, material: Option<usize>, depth: usize) -> Result<(), LoadError> {
        let at_node = |m: String| ParamError { loc: n.params.loc.clone(), message: format!("{}: {m}", n.label) };
        if depth >= MAX_NESTING {
            return Err(self.fail(at_node(format!("nodes are nested more than {MAX_NESTING} deep"))));
        }
        let m = parent * transform::local(&n.label, &n.transform).map_err(|e| self.fail(e))?;
        if n.children.is_some() && n.kind != "group" {
            return Err(self.fail(at_node("takes no `children` (only a group does)".into())));
        }
        if Kind::find(registry::LIGHTS, &n.kind).is_some() {
            self.lights.push((n, m));
            return Ok(());
        }
        let mut p = Params::new(n.label.clone(), &n.params);
        match n.kind.as_str() {
            "group" | "instance" | "mesh" => {
                let own = registry::STRUCTURAL.iter().find(|s| s.name == n.kind).expect("structural").params;
                p.check_keys(own, &[]).map_err(|e| self.fail(e))?;
            }
            kind => match Kind::find(registry::SHAPES, kind) {
                Some(k) => {
                    let common: Vec<&str> = registry::SHAPE_COMMON.iter().map(|c| c.name).collect();
                    p.check_keys(k.params, &common).map_err(|e| self.fail(e))?
                }
                None => return Err(self.fail(unknown_type(n))),
            },
        }
        let material = match p.string("material").map_err(|e| self.fail(e))? {
            Some(name) => Some(self.material(name).map_err(|m| self.fail(p.key_error("material", m)))?),
            None => material,
        };
        let reversed = match n.kind.as_str() {
            "group" | "instance" => false,
            _ => p.boolean("flip_normals").map_err(|e| self.fail(e))?.unwrap_or(false),
        };
        match n.kind.as_str() {
            "group" => {
                for child in n.children.iter().flatten() {
                    self.node(child, m, material, depth + 1)?;
                }
            }
            "instance" => {
                let of = p.required_string("of").map_err(|e| self.fail(e))?;
                let Some(def) = self.desc.definition(of) else {
                    let known: Vec<_> = self.desc.definitions.iter().map(|d| d.name.as_str()).collect();
                    return Err(self.fail(p.key_error("of", unknown("definition", of, &known))));
                };
                if self.stack.iter().any(|s| s == of) {
                    let chain: Vec<_> = self.stack.iter().map(String::as_str).chain([of]).collect();
                    return Err(self.fail(p.error(format!("cyclic instance: {}", chain.join(" -> ")))));
                }
                self.stack.push(of.to_string());
                self.node(&def.value, m, material, depth + 1)?;
                self.stack.pop();
            }
            "mesh" => {
                let name = p.required_string("mesh").map_err(|e| self.fail(e))?;
                let asset = self.asset(name).map_err(|e| match e {
                    Ok(message) => self.fail(p.key_error("mesh", message)),
                    Err(load) => load,
                })?;
                let parts = asset.len();
                let part = p.integer("part", 0..=i64::MAX).map_err(|e| self.fail(e))?;
                if let Some(k) = part.filter(|&k| k as usize >= parts) {
                    let message = format!("part {k} does not exist: mesh \"{name}\" has {parts} part{}", if parts == 1 { "" } else { "s" });
                    return Err(self.fail(p.key_error("part", message)));
                }
                let chosen = asset.iter().enumerate().filter(|(i, _)| part.is_none_or(|k| k as usize == *i));
                let leaf = self.next_leaf();
                // A part its glTF animation hides at this frame ([`mesh_animation::HIDDEN`]).
                for (_, (mesh, placement, imported, placements)) in chosen.filter(|(_, part)| part.1 != mesh_animation::HIDDEN) {
                    let keys = self.motion.as_ref().and_then(|motion| motion.keys(leaf, &m, placement, placements.as_deref()));
                    let material = match (material, *imported) {
                        (Some(m), _) | (None, Some(m)) => m,
                        (None, None) => self.default_material().map_err(|e| self.fail(p.error(e)))?,
                    };
                    let shape = placed(mesh.clone(), &(m * *placement)).map_err(|e| self.fail(p.core_error(e)))?;
                    let shape = self.moved(shape, material, keys.as_ref()).map_err(|e| self.fail(p.core_error(e)))?;
                    self.place(shape, material, reversed, n).map_err(|e| self.fail(p.error(e)))?;
                }
            }
            kind => {
                let k = Kind::find(registry::SHAPES, kind).expect("checked above");
                let made = (k.build)(&mut p, &m).map_err(|e| self.fail(e))?;
                let material = match material {
                    Some(m) => m,
                    None => self.default_material().map_err(|e| self.fail(p.error(e)))?,
                };
                let leaf = self.next_leaf();
                let keys = self.motion.as_ref().and_then(|motion| motion.keys(leaf, &m, &Mat4::IDENTITY, None));
                for shape in made {
                    let shape = self.moved(shape, material, keys.as_ref()).map_err(|e| self.fail(p.core_error(e)))?;
                    self.place(shape, material, reversed, n).map_err(|e| self.fail(p.error(e)))?;
                }
            }
        }
        p.finish().map_err(|e| self.fail(e))
    }

    /// The number of the next shape or mesh node in build order, which
    /// motion blur's keys are read by ([`super::motion::Motion::keys`]).
    fn next_leaf(&mut self) -> usize {
        self.leaf += 1;
        self.leaf - 1
    }

    /// `shape` moving by `keys`; an emitting one stays where it is at the frame.
    fn moved(
        &self,
        shape: Arc<dyn Shape>,
        material: usize,
        keys: Option<&Vec<(f64, Mat4)>>,
    ) -> Result<Arc<dyn Shape>, lamplight_core::Error> {
        let emits = self.builder.material_at(material).is_some_and(Material::emits);
        super::motion::wrap(shape, keys.filter(|_| !emits))
    }

    fn place(&mut self, shape: Arc<dyn Shape>, material: usize, reversed: bool, n: &Node) -> Result<(), String> {
        if self.builder.object_count() >= MAX_OBJECTS {
            return Err(format!("the scene has more than {MAX_OBJECTS} objects (is a definition instanced exponentially?)"));
        }
        let index = self.builder.shared_object(shape, material).map_err(|e| e.to_string())?;
        if reversed {
            self.builder.reverse_orientation(index);
        }
        if let Some(name) = &n.name {
            self.names.entry(name.clone()).or_default().push(index);
            self.builder.name_object(index, name);
        }
        Ok(())
    }

    fn material(&self, name: &str) -> Result<usize, String> {
        self.materials.get(name).copied().ok_or_else(|| {
            let known: Vec<_> = self.materials.keys().map(String::as_str).collect();
            unknown("material", name, &known)
        })
    }

    fn default_material(&mut self) -> Result<usize, String> {
        if let Some(m) = self.default_material {
            return Ok(m);
        }
        let m = self.builder.material(Material::default()).map_err(|e| e.to_string())?;
        self.default_material = Some(m);
        Ok(m)
    }

    /// The mesh asset `name`, loaded once. `Err(Ok(message))` is an error at the
    /// node, `Err(Err(load_error))` one reported as it is (in the mesh file itself).
    fn asset(&mut self, name: &str) -> Result<Asset, Result<String, LoadError>> {
        if let Some(asset) = self.assets.get(name) {
            return Ok(asset.clone());
        }
        let Some(desc) = self.desc.mesh(name) else {
            let known: Vec<_> = self.desc.meshes.iter().map(|m| m.name.as_str()).collect();
            return Err(Ok(unknown_among("mesh", name, &known, "meshes")));
        };
        let label = format!("mesh \"{name}\"");
        let mut p = Params::new(label, &desc.value);
        p.check_keys(MESH_PARAMS, &[]).map_err(|e| Err(self.fail(e)))?;
        let at = |m: String| self.source.error(&desc.value.loc, format!("mesh \"{name}\": {m}"));
        let asset = match (p.has("file"), p.has("positions")) {
            (true, false) if !p.has("indices") && !p.has("normals") => {
                let shading = Shading::read(&mut p).map_err(|e| Err(self.fail(e)))?;
                let color = p.string("color").map_err(|e| Err(self.fail(e)))?.map(str::to_string);
                let clip = mesh_animation::read(&mut p).map_err(|e| Err(self.fail(e)))?;
                let file = p.required_string("file").map_err(|e| Err(self.fail(e)))?;
                // Problems with the file as a whole are reported at the `file` key;
                // those at a place inside the mesh file, at that place.
                let file_loc = desc.value.get("file").map(|e| e.item.loc.clone()).unwrap_or_default();
                let at_file = |m: String| self.source.error(&file_loc, format!("mesh \"{name}\": {m}"));
                self.file_asset(file, shading, color, clip).map_err(|e| match e {
                    Ok(m) => Err(at_file(m)),
                    Err(load) if load.location == Location::File => Err(at_file(load.to_string())),
                    Err(load) => Err(load),
                })?
            }
            (false, true) => inline(&mut p).map_err(|e| Err(self.fail(e)))?,
            _ => return Err(Err(at("needs either `file` or `positions` and `indices`".into()))),
        };
        p.finish().map_err(|e| Err(self.fail(e)))?;
        self.assets.insert(name.to_string(), asset.clone());
        Ok(asset)
    }

    fn file_asset(
        &mut self,
        file: &str,
        shading: Shading,
        color: Option<String>,
        clip: MeshClip,
    ) -> Result<Asset, Result<String, LoadError>> {
        if file.is_empty() {
            return Err(Ok("file: the path is empty, expected a mesh file".to_string()));
        }
        let dir = self.source.dir();
        let path = dir.join(file);
        match crate::input::check_regular(&path) {
            Ok(_) => {}
            Err(crate::input::Refusal::NotFound) => return Err(Ok(format!("file \"{file}\" not found (looked for {})", path.display()))),
            // A device or a pipe (/dev/zero) could be read forever: named for what it is.
            Err(r) => return Err(Ok(format!("file \"{file}\" {}", r.describe("a mesh file")))),
        }
        let canonical = path.canonicalize().unwrap_or(path.clone());
        let key = (canonical.clone(), shading, color.clone(), clip);
        if let Some(asset) = self.files.get(&key) {
            return Ok(asset.clone());
        }
        if !self.imported.contains_key(&canonical) {
            let imported = import::load(&path).map_err(Err)?;
            self.warnings.extend(imported.warnings_of(&path));
            self.imported.insert(canonical.clone(), imported);
        }
        let mut imported = self.imported[&canonical].clone();
        let note = mesh_animation::pose(&mut imported, &path, file, &key.3, self.seconds).map_err(Ok)?;
        if let Some(note) = note.filter(|n| !self.warnings.contains(n)) {
            self.warnings.push(note);
        }
        let mut parts = Vec::new();
        let mut meshes: HashMap<usize, Arc<TriangleMesh>> = HashMap::new();
        for placed in &imported.instances {
            let Some(data) = imported.meshes.get(placed.mesh) else {
                return Err(Err(LoadError {
                    path: path.clone(),
                    location: Location::File,
                    message: format!("instance of missing mesh {}", placed.mesh),
                }));
            };
            let mesh = match meshes.get(&placed.mesh) {
                Some(mesh) => mesh.clone(),
                None => {
                    let normals = shading.normals(&data.positions, &data.indices, data.normals.clone());
                    let attributes = match &color {
                        Some(name) => data.with_color_attribute(name).map_err(|m| Ok(format!("file \"{file}\" {m}")))?,
                        None => data.attributes.clone(),
                    };
                    let mesh = TriangleMesh::new(data.positions.clone(), data.indices.clone(), normals)
                        .and_then(|m| m.with_attributes(attributes))
                        .map_err(|e| Err(LoadError { path: path.clone(), location: Location::File, message: e.to_string() }))?;
                    meshes.entry(placed.mesh).or_insert(Arc::new(mesh)).clone()
                }
            };
            let material = match &placed.material {
                Some(m) => Some(self.builder.material(m.clone()).map_err(|e| Ok(format!("file \"{file}\": {e}")))?),
                None => None,
            };
            parts.push((mesh, placed.transform, material, None));
        }
        if let (Some(motion), Some(seconds)) = (&self.motion, self.seconds) {
            super::motion::pose_parts(motion, seconds, &self.imported[&canonical], &mut parts, &path, file, &key.3).map_err(Ok)?;
        }
        let asset: Asset = Arc::new(parts);
        self.files.insert(key, asset.clone());
        Ok(asset)
    }
}

/// An upper bound of the objects `node` adds (saturating; definitions memoized;
/// cycles and over-deep nesting count 0 here and are reported by the traversal).
fn count(desc: &SceneDescription, node: &Node, memo: &mut HashMap<String, u64>, depth: usize) -> u64 {
    if depth > MAX_NESTING {
        return 0;
    }
    match node.kind.as_str() {
        "group" => node.children.iter().flatten().fold(0u64, |sum, c| sum.saturating_add(count(desc, c, memo, depth + 1))),
        "instance" => {
            let Some(name) = node.params.get("of").and_then(|e| match &e.item.value {
                lamplight_core::params::Value::String(s) => Some(s.clone()),
                _ => None,
            }) else {
                return 0;
            };
            if let Some(n) = memo.get(&name) {
                return *n;
            }
            let n = match desc.definition(&name) {
                Some(def) => {
                    memo.insert(name.clone(), 0); // a cycle back here counts 0
                    count(desc, &def.value, memo, depth + 1)
                }
                None => 0,
            };
            memo.insert(name, n);
            n
        }
        _ => 1,
    }
}

fn unknown_type(n: &Node) -> ParamError {
    let types = registry::node_types();
    let hint = match lamplight_core::params::suggestion(&n.kind, types.iter().copied()) {
        Some(s) => format!("did you mean '{s}'?"),
        None => format!("node types: {}", types.join(", ")),
    };
    ParamError { loc: n.kind_loc.clone(), message: format!("{}: unknown node type ({hint})", n.kind) }
}
