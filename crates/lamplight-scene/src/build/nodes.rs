//! The node tree: groups and instances compose transforms and pass a default
//! material down; shapes, meshes and lights are added to the builder.
//!
//! Limits keep a hostile file from costing unbounded time or memory: nesting at
//! most [`MAX_NESTING`] deep, an instance may not (directly or not) place itself
//! (reported with the chain of names), and at most [`MAX_OBJECTS`] objects in
//! all, which also stops exponential instancing (a definition placing another
//! twice, 40 levels deep). Each mesh asset is loaded once and shared.

use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::path::PathBuf;
use std::sync::Arc;

use lamplight_core::lights::{DirectionalLight, Falloff, PointLight};
use lamplight_core::materials::Material;
use lamplight_core::math::Mat4;
use lamplight_core::shapes::{Shape, TriangleMesh};
use lamplight_core::SceneBuilder;

use super::shapes::{self, SHAPE_KEYS};
use super::transform::{self, finite};
use super::vec3;
use crate::description::{Located, MeshDesc, Node, SceneDescription};
use crate::error::{LoadError, Location};
use crate::formats::native::Source;
use crate::import;

/// Deepest nesting of groups and instances.
pub const MAX_NESTING: usize = 64;
/// Most objects one scene may have.
pub const MAX_OBJECTS: usize = 1 << 22;

const COMMON: &[&str] = &["name", "material"];
const TRANSFORM: &[&str] = &["translate", "rotate", "scale", "matrix"];

/// A loaded mesh asset: its parts (mesh, placement in the asset, imported material).
type Asset = Arc<Vec<(Arc<TriangleMesh>, Mat4, Option<usize>)>>;

struct Ctx<'a> {
    desc: &'a SceneDescription,
    source: &'a Source,
    builder: &'a mut SceneBuilder,
    materials: BTreeMap<String, usize>,
    default_material: Option<usize>,
    assets: HashMap<String, Asset>,
    files: HashMap<PathBuf, Asset>,
    names: HashMap<String, Vec<usize>>,
    lights: Vec<(PointLight, String, Option<Range<usize>>)>,
    stack: Vec<String>,
}

/// Adds every top-level node of `desc` to `builder`.
pub(super) fn add_all(
    desc: &SceneDescription,
    source: &Source,
    builder: &mut SceneBuilder,
    materials: BTreeMap<String, usize>,
) -> Result<(), LoadError> {
    let mut ctx = Ctx {
        desc,
        source,
        builder,
        materials,
        default_material: None,
        assets: HashMap::new(),
        files: HashMap::new(),
        names: HashMap::new(),
        lights: Vec::new(),
        stack: Vec::new(),
    };
    // Count first, so that exponential instancing fails at once instead of
    // after allocating millions of objects.
    let mut counts = HashMap::new();
    for node in &desc.objects {
        let planned = count(desc, &node.value, &mut counts, 0);
        if planned > MAX_OBJECTS as u64 {
            let message =
                format!("{}: expands to more than {MAX_OBJECTS} objects (is a definition instanced exponentially?)", node.value.kind);
            return Err(source.error(node.span.as_ref(), message));
        }
    }
    for node in &desc.objects {
        ctx.node(node, Mat4::IDENTITY, None, 0)?;
    }
    for (mut light, name, span) in std::mem::take(&mut ctx.lights) {
        let objects = ctx.names.get(&name).map(Vec::as_slice).unwrap_or_default();
        match objects {
            [one] => light.own_object = Some(*one),
            [] => return Err(source.error(span.as_ref(), format!("point_light: own_object \"{name}\" names no shape"))),
            _ => {
                return Err(source
                    .error(span.as_ref(), format!("point_light: own_object \"{name}\" names {} objects, expected one", objects.len())))
            }
        }
        ctx.builder.light(light);
    }
    Ok(())
}

impl Ctx<'_> {
    fn node(&mut self, located: &Located<Node>, parent: Mat4, material: Option<usize>, depth: usize) -> Result<(), LoadError> {
        let n = &located.value;
        let span = located.span.as_ref();
        let err = |m: String| self.source.error(span, format!("{}: {m}", n.kind));
        self.check_keys(n).map_err(err)?;
        if depth >= MAX_NESTING {
            return Err(err(format!("nodes are nested more than {MAX_NESTING} deep")));
        }
        let material = match &n.material {
            Some(name) => Some(self.material(name).map_err(err)?),
            None => material,
        };
        match n.kind.as_str() {
            "group" | "instance" => {
                let m = parent * transform::local(n).map_err(err)?;
                if n.kind == "group" {
                    for child in n.children.iter().flatten() {
                        self.node(child, m, material, depth + 1)?;
                    }
                    return Ok(());
                }
                let of = n.of.as_ref().ok_or_else(|| err("needs `of`, the name of a definition".into()))?;
                let Some(def) = self.desc.definitions.get(of) else {
                    let known: Vec<_> = self.desc.definitions.keys().map(String::as_str).collect();
                    return Err(err(format!("unknown definition \"{of}\" (definitions: {})", list(&known))));
                };
                if self.stack.contains(of) {
                    let chain: Vec<_> = self.stack.iter().chain([of]).map(String::as_str).collect();
                    return Err(err(format!("cyclic instance: {}", chain.join(" -> "))));
                }
                self.stack.push(of.clone());
                self.node(def, m, material, depth + 1)?;
                self.stack.pop();
                Ok(())
            }
            "point_light" => {
                let position = vec3(req_finite(n.position, "position").map_err(err)?);
                let intensity = n.intensity.ok_or_else(|| err("needs `intensity`".into()))?;
                let mut light = PointLight::new(parent.transform_point3(position), vec3(intensity.0)).map_err(|e| err(e.to_string()))?;
                light.falloff = match n.falloff.as_deref().unwrap_or("inverse_square") {
                    "inverse_square" => Falloff::InverseSquare,
                    "none" => Falloff::None,
                    other => return Err(err(format!("unknown falloff \"{other}\", expected \"inverse_square\" or \"none\""))),
                };
                match &n.own_object {
                    Some(name) => self.lights.push((light, name.clone(), located.span.clone())),
                    None => self.builder.light(light),
                }
                Ok(())
            }
            "directional_light" => {
                let direction = parent.transform_vector3(vec3(req_finite(n.direction, "direction").map_err(err)?));
                let radiance = n.radiance.ok_or_else(|| err("needs `radiance`".into()))?;
                let light = DirectionalLight::new(direction, vec3(radiance.0)).map_err(|e| err(e.to_string()))?;
                self.builder.light(light);
                Ok(())
            }
            "mesh" => {
                let name = n.mesh.as_ref().ok_or_else(|| err("needs `mesh`, the name of a [meshes] entry".into()))?;
                let asset = self.asset(name).map_err(|e| match e {
                    Ok(message) => err(message),
                    Err(load) => load,
                })?;
                for (mesh, placement, imported) in asset.iter() {
                    let shape = shapes::instance(mesh.clone(), &(parent * *placement)).map_err(err)?;
                    let material = match (material, *imported) {
                        (Some(m), _) | (None, Some(m)) => m,
                        (None, None) => self.default_material().map_err(err)?,
                    };
                    self.place(shape, material, n).map_err(err)?;
                }
                Ok(())
            }
            _ => {
                let made = shapes::make(n, &parent).map_err(err)?;
                let material = match material {
                    Some(m) => m,
                    None => self.default_material().map_err(err)?,
                };
                for shape in made {
                    self.place(shape, material, n).map_err(err)?;
                }
                Ok(())
            }
        }
    }

    fn place(&mut self, shape: Arc<dyn Shape>, material: usize, n: &Node) -> Result<(), String> {
        if self.builder.object_count() >= MAX_OBJECTS {
            return Err(format!("the scene has more than {MAX_OBJECTS} objects (is a definition instanced exponentially?)"));
        }
        let index = self.builder.shared_object(shape, material).map_err(|e| e.to_string())?;
        if let Some(name) = &n.name {
            self.names.entry(name.clone()).or_default().push(index);
        }
        Ok(())
    }

    fn check_keys(&self, n: &Node) -> Result<(), String> {
        let own: &[&str] = match n.kind.as_str() {
            "group" => &["children"],
            "instance" => &["of"],
            "point_light" => &["position", "intensity", "falloff", "own_object"],
            "directional_light" => &["direction", "radiance"],
            kind => match SHAPE_KEYS.iter().find(|(k, _)| *k == kind) {
                Some((_, keys)) => keys,
                None => {
                    let mut kinds = vec!["group", "instance", "point_light", "directional_light"];
                    kinds.extend(SHAPE_KEYS.iter().map(|(k, _)| *k));
                    return Err(format!("unknown node type (expected one of: {})", kinds.join(", ")));
                }
            },
        };
        let transform: &[&str] = if matches!(n.kind.as_str(), "group" | "instance") { TRANSFORM } else { &[] };
        let common: &[&str] = if n.kind.ends_with("_light") { &[] } else { COMMON };
        let valid: Vec<&str> = common.iter().chain(transform).chain(own).copied().collect();
        for key in n.present_keys() {
            if !valid.contains(&key) {
                return Err(format!("unknown key `{key}` for this type (valid keys: type, {})", valid.join(", ")));
            }
        }
        Ok(())
    }

    fn material(&self, name: &str) -> Result<usize, String> {
        self.materials.get(name).copied().ok_or_else(|| {
            let known: Vec<_> = self.materials.keys().map(String::as_str).collect();
            format!("unknown material \"{name}\" (materials: {})", list(&known))
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
        let Some(desc) = self.desc.meshes.get(name) else {
            let known: Vec<_> = self.desc.meshes.keys().map(String::as_str).collect();
            return Err(Ok(format!("unknown mesh \"{name}\" (meshes: {})", list(&known))));
        };
        let at = |m: String| self.source.error(desc.span.as_ref(), format!("mesh \"{name}\": {m}"));
        let asset = match (&desc.value.file, &desc.value.positions) {
            (Some(file), None) if desc.value.indices.is_none() && desc.value.normals.is_none() => {
                self.file_asset(file).map_err(|e| match e {
                    Ok(m) => Err(at(m)),
                    Err(load) => Err(load),
                })?
            }
            (None, Some(_)) => inline(&desc.value).map_err(|m| Err(at(m)))?,
            _ => return Err(Err(at("needs either `file` or `positions` and `indices`".into()))),
        };
        self.assets.insert(name.to_string(), asset.clone());
        Ok(asset)
    }

    fn file_asset(&mut self, file: &str) -> Result<Asset, Result<String, LoadError>> {
        let dir = self.source.path.parent().map(|p| p.to_path_buf()).unwrap_or_default();
        let path = dir.join(file);
        let meta = std::fs::metadata(&path).map_err(|_| Ok(format!("file \"{file}\" not found (looked for {})", path.display())))?;
        if meta.is_dir() {
            return Err(Ok(format!("file \"{file}\" is a directory, expected a mesh file")));
        }
        if !meta.is_file() {
            // A device or a pipe (/dev/zero) could be read forever.
            return Err(Ok(format!("file \"{file}\" is not a regular file")));
        }
        let key = path.canonicalize().unwrap_or(path.clone());
        if let Some(asset) = self.files.get(&key) {
            return Ok(asset.clone());
        }
        let imported = import::load(&path).map_err(Err)?;
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
                    let mesh = TriangleMesh::new(data.positions.clone(), data.indices.clone(), data.normals.clone())
                        .map_err(|e| Err(LoadError { path: path.clone(), location: Location::File, message: e.to_string() }))?;
                    meshes.entry(placed.mesh).or_insert(Arc::new(mesh)).clone()
                }
            };
            let material = match &placed.material {
                Some(m) => Some(self.builder.material(m.clone()).map_err(|e| Ok(format!("file \"{file}\": {e}")))?),
                None => None,
            };
            parts.push((mesh, placed.transform, material));
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
        "group" => node.children.iter().flatten().fold(0u64, |sum, c| sum.saturating_add(count(desc, &c.value, memo, depth + 1))),
        "instance" => {
            let Some(name) = &node.of else { return 0 };
            if let Some(n) = memo.get(name) {
                return *n;
            }
            let n = match desc.definitions.get(name) {
                Some(def) => {
                    memo.insert(name.clone(), 0); // a cycle back here counts 0
                    count(desc, &def.value, memo, depth + 1)
                }
                None => 0,
            };
            memo.insert(name.clone(), n);
            n
        }
        "cylinder" => 3,
        _ => 1,
    }
}

fn inline(desc: &MeshDesc) -> Result<Asset, String> {
    let positions = desc.positions.clone().unwrap_or_default();
    let indices = desc.indices.clone().ok_or("inline mesh needs `indices`")?;
    for p in &positions {
        finite("positions", p)?;
    }
    let normals = match &desc.normals {
        Some(n) => {
            for v in n {
                finite("normals", v)?;
            }
            Some(n.iter().map(|v| vec3(*v)).collect())
        }
        None => None,
    };
    let mesh = TriangleMesh::new(positions.into_iter().map(vec3).collect(), indices, normals).map_err(|e| e.to_string())?;
    Ok(Arc::new(vec![(Arc::new(mesh), Mat4::IDENTITY, None)]))
}

fn req_finite(v: Option<[f64; 3]>, key: &str) -> Result<[f64; 3], String> {
    let v = v.ok_or_else(|| format!("needs `{key}`"))?;
    finite(key, &v)?;
    Ok(v)
}

fn list(names: &[&str]) -> String {
    if names.is_empty() {
        "none defined".to_string()
    } else {
        names.join(", ")
    }
}
