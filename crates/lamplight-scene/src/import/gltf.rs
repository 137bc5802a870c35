//! glTF 2.0 reader: `.gltf` (JSON with external or `data:` base64 buffers) and
//! `.glb` (binary container).
//!
//! Reads the default scene's node tree (or the first scene, or with no scenes
//! every root node) with `matrix` or TRS transforms, triangle primitives (mode
//! 4, indexed or not) as meshes, perspective and orthographic cameras and
//! `KHR_lights_punctual` lights; materials map as in [`super::gltf_material`]. The
//! camera looks down its node's -Z with +Y up; a directional light and a spot
//! light shine along -Z, the spot light with the spec's cone profile
//! ([`SpotProfile::Gltf`]). An orthographic camera's `xmag` and `ymag` are the
//! half-width and half-height of its view; an image of another aspect widens the
//! view rather than crop or stretch it (the glTF 2.0 specification's rule for
//! orthographic projections: no cropping, no non-uniform scaling). A light's
//! intensity (candela for point and spot lights, lux for directional ones) is
//! divided by `pi` ([`lamplight_core::lights::DELTA_SCALE`]): a white diffuse
//! surface 1 m from a 1 cd light, facing it, then shows the `1 / pi` nit the
//! glTF specification's units give, under both integrators.
//!
//! The `gltf` crate parses and validates the JSON (`Gltf::from_slice`, so a bad
//! reference names its JSON path), but the buffers and accessors are read here:
//! the crate's `import` would report a missing `.bin` without its JSON path,
//! and its accessor iterators assume valid lengths (`count - 1` underflows,
//! `debug_assert`s on strides), while every range here is checked against the
//! buffer first. Animations are read by [`super::gltf_animation`]. Unsupported parts (other primitive modes, textures, skins, morph targets, sparse accessors'
//! meshes are errors) are reported once each as warnings.

use std::collections::HashMap;
use std::path::Path;

use base64::engine::{general_purpose::GeneralPurpose, DecodePaddingMode, GeneralPurposeConfig};
use base64::Engine;
use gltf::accessor::{DataType, Dimensions};
use gltf::khr_lights_punctual::Kind;
use lamplight_core::materials::Material;
use lamplight_core::math::{Mat4, Rgb, Vec3};
use lamplight_core::shapes::VertexAttributes;

use super::gltf_images::GltfImages;
use super::{gltf_material, Imported, ImportedCamera, ImportedLight, ImportedMesh, ImportedProjection, MeshData, Warnings};
use crate::error::LoadError;

/// The materials of the primitives under `roots`, each once, in the order
/// first met (nodes met twice, which the walk below refuses, are not followed
/// again here).
fn used_materials<'a>(document: &'a gltf::Document, roots: &[gltf::Node<'a>]) -> Vec<gltf::Material<'a>> {
    let (mut seen, mut taken) = (vec![false; document.nodes().len()], vec![false; document.materials().len()]);
    let mut stack: Vec<gltf::Node> = roots.iter().rev().cloned().collect();
    let mut materials = Vec::new();
    while let Some(node) = stack.pop() {
        if std::mem::replace(&mut seen[node.index()], true) {
            continue;
        }
        for p in node.mesh().iter().flat_map(|m| m.primitives()) {
            if let Some(i) = p.material().index().filter(|&i| !std::mem::replace(&mut taken[i], true)) {
                materials.extend(document.materials().nth(i));
            }
        }
        stack.extend(node.children().collect::<Vec<_>>().into_iter().rev());
    }
    materials
}

/// Reads a `.gltf` or `.glb` file's bytes; external buffers are read relative to `path`.
pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Imported, LoadError> {
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| gltf_error(path, bytes, e))?;
    let root = document.into_json();
    check_position_accessors(path, &root)?;
    super::gltf_images::check_sources(path, &root)?;
    let document = gltf::Document::from_json(root).map_err(|e| gltf_error(path, bytes, e))?;
    let buffers = load_buffers(path, &document, blob)?;
    let mut reader = Reader {
        path,
        buffers,
        warnings: Warnings::default(),
        primitives: HashMap::new(),
        materials: HashMap::new(),
        images: GltfImages::new(path),
    };
    let mut out = Imported::default();
    if document.extensions_used().any(|e| e == "KHR_materials_volume") {
        reader.warnings.once("glTF KHR_materials_volume ignored: transmission is thin-walled (no refraction, no absorption)".to_string());
    }
    let scene_count = document.scenes().len();
    let whole_file = scene_count == 0;
    let roots: Vec<gltf::Node> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => {
            if scene_count > 1 {
                reader.warnings.once(format!("glTF file has {scene_count} scenes: only scene {} is read", scene.index()));
            }
            scene.nodes().collect()
        }
        None => {
            let mut is_child = vec![false; document.nodes().len()];
            for node in document.nodes() {
                for child in node.children() {
                    is_child[child.index()] = true;
                }
            }
            document.nodes().filter(|n| !is_child[n.index()]).collect()
        }
    };
    reader.images.decode_ahead(&document, &used_materials(&document, &roots), &reader.buffers);
    // Depth-first, children in file order, with an explicit stack so deep trees cannot overflow it.
    let mut seen = vec![false; document.nodes().len()];
    // Each node's place in the tree is kept for the animations (`gltf_animation`).
    let mut tree = super::gltf_animation::TreeRecorder::default();
    let mut stack: Vec<(gltf::Node, Mat4, String, Option<usize>)> =
        roots.into_iter().rev().map(|n| (n.clone(), Mat4::IDENTITY, "scene.nodes".to_string(), None)).collect();
    while let Some((node, parent, via, parent_place)) = stack.pop() {
        let i = node.index();
        if std::mem::replace(&mut seen[i], true) {
            return Err(LoadError::json(
                path,
                via,
                format!("node {i} is reached twice (a cycle or a shared child): glTF nodes must form trees"),
            ));
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        let world = parent * local;
        if !world.is_finite() {
            return Err(LoadError::json(path, format!("nodes[{i}]"), "the transform is not finite"));
        }
        let place = tree.add(&node, parent_place, local);
        let before = (out.instances.len(), out.cameras.len(), out.lights.len());
        reader.node(&node, world, &mut out)?;
        tree.placed(place, before, &out);
        let children: Vec<gltf::Node> = node.children().collect();
        for (j, child) in children.into_iter().enumerate().rev() {
            stack.push((child, world, format!("nodes[{i}].children[{j}]"), Some(place)));
        }
    }
    // Without a scene every node is a root or below one, unless it sits on a cycle.
    if let Some(i) = seen.iter().position(|s| !s).filter(|_| whole_file) {
        return Err(LoadError::json(
            path,
            format!("nodes[{i}]"),
            format!("node {i} lies on a cycle of children: glTF nodes must form trees"),
        ));
    }
    let mut warnings = std::mem::take(&mut reader.warnings);
    let values = |acc: &gltf::Accessor, dims, types: &[DataType]| reader.values(acc, dims, types);
    out.animations = super::gltf_animation::read(path, &document, tree, &values, &mut warnings)?;
    out.warnings = warnings.into_vec();
    out.images = reader.images.into_sources();
    Ok(out)
}

/// gltf-json 1.4.1's validation indexes `accessors[POSITION]` without a bounds
/// check (found by the `gltf` fuzz target: a file whose POSITION names a missing
/// accessor panicked), so that one reference is checked before validating.
fn check_position_accessors(path: &Path, root: &gltf::json::Root) -> Result<(), LoadError> {
    let positions = gltf::json::validation::Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let Some(index) = primitive.attributes.get(&positions) else { continue };
            if index.value() >= root.accessors.len() {
                let at = format!("meshes[{m}].primitives[{p}].attributes.POSITION");
                return Err(LoadError::json(
                    path,
                    at,
                    format!("accessor {} does not exist ({} accessors)", index.value(), root.accessors.len()),
                ));
            }
        }
    }
    Ok(())
}

/// A triangle primitive read: its index into `Imported::meshes`, its material and the material's name.
type Primitive = (usize, Option<Material>, Option<String>);

/// State while walking the nodes: buffers, caches, warnings.
struct Reader<'p> {
    path: &'p Path,
    buffers: Vec<Vec<u8>>,
    warnings: Warnings,
    /// glTF mesh index -> (index into `Imported::meshes`, material) per triangle primitive.
    primitives: HashMap<usize, Vec<Primitive>>,
    /// (glTF material index, whether the primitive has vertex colours) -> material.
    materials: HashMap<(usize, bool), Material>,
    images: GltfImages<'p>,
}

impl Reader<'_> {
    fn node(&mut self, node: &gltf::Node, world: Mat4, out: &mut Imported) -> Result<(), LoadError> {
        if node.skin().is_some() {
            self.warnings.once("glTF skins ignored: meshes are read in their bind pose".to_string());
        }
        if let Some(mesh) = node.mesh() {
            if !self.primitives.contains_key(&mesh.index()) {
                let list = self.mesh(&mesh, out)?;
                self.primitives.insert(mesh.index(), list);
            }
            for (m, material, name) in &self.primitives[&mesh.index()] {
                out.instances.push(ImportedMesh { mesh: *m, transform: world, material: material.clone(), material_name: name.clone() });
            }
        }
        let origin = world.transform_point3(Vec3::ZERO);
        let forward = world.transform_vector3(-Vec3::Z);
        if let Some(camera) = node.camera() {
            let projection = match camera.projection() {
                gltf::camera::Projection::Perspective(p) => {
                    let vfov_deg = f64::from(p.yfov()).to_degrees();
                    if !(vfov_deg > 0.0 && vfov_deg < 180.0) || forward.length_squared() == 0.0 {
                        return Err(LoadError::json(
                            self.path,
                            format!("cameras[{}].perspective.yfov", camera.index()),
                            "expected a field of view in (0, pi)",
                        ));
                    }
                    ImportedProjection::Perspective { vfov_deg }
                }
                gltf::camera::Projection::Orthographic(o) => {
                    let (xmag, ymag) = (f64::from(o.xmag()), f64::from(o.ymag()));
                    for (key, mag) in [("xmag", xmag), ("ymag", ymag)] {
                        if !(mag.is_finite() && mag > 0.0) || forward.length_squared() == 0.0 {
                            return Err(LoadError::json(
                                self.path,
                                format!("cameras[{}].orthographic.{key}", camera.index()),
                                "expected a positive half-extent",
                            ));
                        }
                    }
                    ImportedProjection::Orthographic { xmag, ymag }
                }
            };
            out.cameras.push(ImportedCamera { eye: origin, target: origin + forward, up: world.transform_vector3(Vec3::Y), projection });
        }
        if let Some(light) = node.light() {
            let at = format!("extensions.KHR_lights_punctual.lights[{}]", light.index());
            let power =
                Rgb::from_array(light.color().map(f64::from)) * (f64::from(light.intensity()) / lamplight_core::lights::DELTA_SCALE);
            if light.range().is_some() {
                self.warnings.once("glTF light range ignored: point and spot lights fall off with the squared distance".to_string());
            }
            let made = match light.kind() {
                Kind::Directional => ImportedLight::Directional { direction: forward, radiance: power },
                Kind::Point => ImportedLight::Point { position: origin, intensity: power },
                Kind::Spot { inner_cone_angle, outer_cone_angle } => ImportedLight::Spot {
                    position: origin,
                    direction: forward,
                    intensity: power,
                    inner_deg: f64::from(inner_cone_angle).to_degrees(),
                    outer_deg: f64::from(outer_cone_angle).to_degrees(),
                },
            };
            // Built once here, so that a bad light is an error at its place in the file.
            made.build().map_err(|e| LoadError::json(self.path, at.clone(), e.to_string()))?;
            out.lights.push(made);
        }
        Ok(())
    }

    /// Reads a mesh's triangle primitives into `out.meshes`.
    fn mesh(&mut self, mesh: &gltf::Mesh, out: &mut Imported) -> Result<Vec<Primitive>, LoadError> {
        let mut list = Vec::new();
        for p in mesh.primitives() {
            let at = format!("meshes[{}].primitives[{}]", mesh.index(), p.index());
            if p.mode() != gltf::mesh::Mode::Triangles {
                self.warnings.once(format!("glTF primitives of mode {:?} ignored: only triangles (mode 4) are read", p.mode()));
                continue;
            }
            if p.morph_targets().next().is_some() {
                self.warnings.once("glTF morph targets ignored".to_string());
            }
            for (semantic, _) in p.attributes() {
                use gltf::Semantic as S;
                if !matches!(semantic, S::Positions | S::Normals | S::TexCoords(0) | S::TexCoords(1) | S::Colors(0) | S::Tangents) {
                    self.warnings.once(format!("glTF vertex attribute {semantic:?} ignored"));
                }
            }
            let Some(positions) = p.get(&gltf::Semantic::Positions) else {
                return Err(LoadError::json(self.path, format!("{at}.attributes"), "expected a POSITION attribute"));
            };
            let positions = self.vec3s(&positions)?;
            let normals = match p.get(&gltf::Semantic::Normals) {
                Some(acc) => {
                    let normals = self.vec3s(&acc)?;
                    if normals.len() != positions.len() {
                        let msg = format!("NORMAL has {} items but POSITION has {}", normals.len(), positions.len());
                        return Err(LoadError::json(self.path, format!("{at}.attributes.NORMAL"), msg));
                    }
                    Some(normals)
                }
                None => None,
            };
            let attributes = self.vertex_attributes(&p, &at, positions.len())?;
            let indices: Vec<u32> = match p.indices() {
                Some(acc) => {
                    let values = self.values(&acc, Dimensions::Scalar, &[DataType::U8, DataType::U16, DataType::U32])?;
                    let mut out = Vec::with_capacity(values.len());
                    for (k, v) in values.into_iter().enumerate() {
                        if v >= positions.len() as f64 {
                            let msg = format!("index {v} of triangle {} out of range: POSITION has {} vertices", k / 3, positions.len());
                            return Err(LoadError::json(self.path, format!("accessors[{}]", acc.index()), msg));
                        }
                        out.push(v as u32);
                    }
                    out
                }
                None => (0..positions.len() as u32).collect(),
            };
            let leftover = indices.len() % 3;
            if leftover > 0 {
                self.warnings.once(format!("glTF {at}: {leftover} trailing indices do not make a triangle and are ignored"));
            }
            let name = match (mesh.name(), mesh.primitives().len()) {
                (Some(n), 1) => Some(n.to_string()),
                (Some(n), _) => Some(format!("{n}.{}", p.index())),
                (None, _) => None,
            };
            let triangles = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
            let attributes_have_colors = attributes.colors.is_some();
            let mut data = MeshData { name, positions, indices: triangles, normals, attributes, named: Vec::new() };
            let material = match p.material().index() {
                Some(m) => {
                    let key = (m, attributes_have_colors);
                    if !self.materials.contains_key(&key) {
                        let (buffers, images) = (&self.buffers, &mut self.images);
                        let mut load = |image: &gltf::Image, srgb: bool| images.load(image, buffers, srgb);
                        let material = gltf_material::map(&p.material(), key.1, &mut load, &mut self.warnings)?;
                        self.materials.insert(key, material);
                    }
                    Some(self.materials[&key].clone())
                }
                None => None,
            };
            // A normal map needs tangents: the file's, else MikkTSpace's.
            if material.as_ref().is_some_and(|m| m.normal_map.is_some()) && !super::tangents::generate(&mut data) {
                self.warnings.once("glTF normalTexture on a primitive without TEXCOORD_0: its tangents follow the faces".to_string());
            }
            out.meshes.push(data);
            let material_name = material.as_ref().and(p.material().name()).map(str::to_string);
            list.push((out.meshes.len() - 1, material, material_name));
        }
        Ok(list)
    }

    /// `TEXCOORD_0` and `TEXCOORD_1` (their `v` flipped: glTF's `v = 0` is the image's top row,
    /// lamplight's the bottom), `COLOR_0` (rgb; alpha is not used) and `TANGENT`.
    fn vertex_attributes(&self, p: &gltf::Primitive, at: &str, count: usize) -> Result<VertexAttributes, LoadError> {
        use gltf::Semantic as S;
        let mut out = VertexAttributes::default();
        if let Some(acc) = p.get(&S::TexCoords(0)) {
            let (v, _) = self.normalized(&acc, &[Dimensions::Vec2], &format!("{at}.attributes.TEXCOORD_0"), count)?;
            out.uvs = Some(v.chunks_exact(2).map(|c| [c[0], 1.0 - c[1]]).collect());
        }
        if let Some(acc) = p.get(&S::TexCoords(1)) {
            let (v, _) = self.normalized(&acc, &[Dimensions::Vec2], &format!("{at}.attributes.TEXCOORD_1"), count)?;
            out.uvs1 = Some(v.chunks_exact(2).map(|c| [c[0], 1.0 - c[1]]).collect());
        }
        if let Some(acc) = p.get(&S::Colors(0)) {
            let (v, n) = self.normalized(&acc, &[Dimensions::Vec3, Dimensions::Vec4], &format!("{at}.attributes.COLOR_0"), count)?;
            out.colors = Some(v.chunks_exact(n).map(|c| Rgb::new(c[0], c[1], c[2])).collect());
        }
        if let Some(acc) = p.get(&S::Tangents) {
            let (v, _) = self.normalized(&acc, &[Dimensions::Vec4], &format!("{at}.attributes.TANGENT"), count)?;
            out.tangents = Some(v.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect());
        }
        Ok(out)
    }

    /// A float or normalized-integer accessor (glTF 2.0 section 3.7.2.1: `c / 255`
    /// for `u8`, `c / 65535` for `u16`, `max(c / 127, -1)` for `i8`, and so on) of
    /// one of `dims`, with one item per vertex; the values and components per item.
    fn normalized(&self, acc: &gltf::Accessor, dims: &[Dimensions], at: &str, count: usize) -> Result<(Vec<f64>, usize), LoadError> {
        let err = |msg: String| Err(LoadError::json(self.path, at.to_string(), msg));
        if !dims.contains(&acc.dimensions()) {
            return err(format!("expected {dims:?}, found {:?}", acc.dimensions()));
        }
        let ty = acc.data_type();
        if ty != DataType::F32 && !acc.normalized() {
            return err(format!("expected floats or normalized integers, found {ty:?} that are not normalized"));
        }
        let scale = match ty {
            DataType::I8 => 127.0,
            DataType::U8 => 255.0,
            DataType::I16 => 32767.0,
            DataType::U16 => 65535.0,
            DataType::U32 => 4294967295.0,
            DataType::F32 => 1.0,
        };
        let mut values = self.values(acc, acc.dimensions(), &[ty])?;
        let n = acc.dimensions().multiplicity();
        if values.len() != count * n {
            return err(format!("has {} items but POSITION has {count}", values.len() / n));
        }
        for (k, v) in values.iter_mut().enumerate() {
            *v /= scale;
            if matches!(ty, DataType::I8 | DataType::I16) {
                *v = v.max(-1.0);
            }
            if !v.is_finite() {
                return err(format!("item {} is not finite", k / n));
            }
        }
        Ok((values, n))
    }

    /// A VEC3 float accessor as finite vectors.
    fn vec3s(&self, acc: &gltf::Accessor) -> Result<Vec<Vec3>, LoadError> {
        let values = self.values(acc, Dimensions::Vec3, &[DataType::F32])?;
        let mut out = Vec::with_capacity(values.len() / 3);
        for (k, v) in values.chunks_exact(3).enumerate() {
            let v = Vec3::new(v[0], v[1], v[2]);
            if !v.is_finite() {
                return Err(LoadError::json(
                    self.path,
                    format!("accessors[{}]", acc.index()),
                    format!("item {k} is {v}, expected finite numbers"),
                ));
            }
            out.push(v);
        }
        Ok(out)
    }

    /// Every component of an accessor, in order, after checking its type and that
    /// its bytes lie inside its buffer view and the view inside its buffer.
    fn values(&self, acc: &gltf::Accessor, dims: Dimensions, types: &[DataType]) -> Result<Vec<f64>, LoadError> {
        let at = format!("accessors[{}]", acc.index());
        let err = |where_: String, msg: String| Err(LoadError::json(self.path, where_, msg));
        if acc.sparse().is_some() {
            return err(format!("{at}.sparse"), "sparse accessors are not supported".into());
        }
        if acc.dimensions() != dims || !types.contains(&acc.data_type()) {
            return err(at, format!("expected {dims:?} of {types:?}, found {:?} of {:?}", acc.dimensions(), acc.data_type()));
        }
        let Some(view) = acc.view() else {
            return err(format!("{at}.bufferView"), "accessors without a buffer view (all zeros) are not supported".into());
        };
        let count = acc.count() as u64;
        if count == 0 {
            return Ok(Vec::new());
        }
        let component = acc.data_type().size() as u64;
        let n = dims.multiplicity() as u64;
        let item = component * n;
        let stride = view.stride().map_or(item, |s| s as u64);
        if stride < item {
            return err(format!("bufferViews[{}].byteStride", view.index()), format!("stride {stride} is less than the item size {item}"));
        }
        let buffer = &self.buffers[view.buffer().index()];
        let view_start = view.offset() as u64;
        let view_end = view_start + view.length() as u64;
        if view_end > buffer.len() as u64 {
            let msg = format!("bytes {view_start}..{view_end} lie outside buffer {} ({} bytes)", view.buffer().index(), buffer.len());
            return err(format!("bufferViews[{}]", view.index()), msg);
        }
        let start = acc.offset() as u64;
        let end = u128::from(start) + u128::from(stride) * u128::from(count - 1) + u128::from(item);
        if end > u128::from(view.length() as u64) {
            let msg = format!("needs bytes {start}..{end} of bufferView {}, which has {} bytes", view.index(), view.length());
            return err(at, msg);
        }
        let mut out = Vec::with_capacity((count * n) as usize);
        for k in 0..count {
            let base = (view_start + start + k * stride) as usize;
            for c in 0..n as usize {
                let at = base + c * component as usize;
                let b = &buffer[at..at + component as usize];
                out.push(match acc.data_type() {
                    DataType::I8 => f64::from(b[0] as i8),
                    DataType::U8 => f64::from(b[0]),
                    DataType::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
                    DataType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                    DataType::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    DataType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                });
            }
        }
        Ok(out)
    }
}

/// Standard base64 that accepts data URIs with or without padding.
pub(super) fn base64_engine() -> GeneralPurpose {
    GeneralPurpose::new(&base64::alphabet::STANDARD, GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent))
}

/// The bytes of every buffer: the GLB chunk, a `data:` URI, or a file beside `path`.
fn load_buffers(path: &Path, document: &gltf::Document, mut blob: Option<Vec<u8>>) -> Result<Vec<Vec<u8>>, LoadError> {
    let engine = base64_engine();
    let mut out = Vec::new();
    for buffer in document.buffers() {
        let at = format!("buffers[{}]", buffer.index());
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or_else(|| LoadError::json(path, &at, "refers to the GLB binary chunk, but the file has none"))?
            }
            gltf::buffer::Source::Uri(uri) => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    let Some((_, encoded)) = rest.split_once(";base64,") else {
                        return Err(LoadError::json(path, format!("{at}.uri"), "expected a base64 data URI (`data:...;base64,...`)"));
                    };
                    engine.decode(encoded).map_err(|e| LoadError::json(path, format!("{at}.uri"), format!("invalid base64: {e}")))?
                } else if uri.contains("://") {
                    return Err(LoadError::json(
                        path,
                        format!("{at}.uri"),
                        format!("cannot fetch `{uri}`: only files beside the glTF are read"),
                    ));
                } else {
                    let file = path.parent().unwrap_or(Path::new("")).join(uri);
                    super::read_file(&file).map_err(|e| {
                        LoadError::json(path, format!("{at}.uri"), format!("cannot read buffer `{}`: {}", file.display(), e.message))
                    })?
                }
            }
        };
        if data.len() < buffer.length() {
            return Err(LoadError::json(
                path,
                format!("{at}.byteLength"),
                format!("claims {} bytes but the data has {}", buffer.length(), data.len()),
            ));
        }
        out.push(data);
    }
    Ok(out)
}

/// A `gltf` crate error as a [`LoadError`] with a JSON path or text position.
fn gltf_error(path: &Path, bytes: &[u8], e: gltf::Error) -> LoadError {
    match e {
        gltf::Error::Validation(errors) => {
            let more = if errors.len() > 1 { format!(" (and {} more problems)", errors.len() - 1) } else { String::new() };
            match errors.into_iter().next() {
                Some((json_path, problem)) => LoadError::json(path, json_path.to_string(), format!("{problem}{more}")),
                None => LoadError::file(path, "invalid glTF"),
            }
        }
        gltf::Error::Deserialize(e) if !bytes.starts_with(b"glTF") => {
            LoadError::at(path, e.line().max(1), e.column().max(1), format!("invalid glTF JSON: {e}"))
        }
        gltf::Error::Deserialize(e) => {
            LoadError::file(path, format!("invalid JSON chunk in GLB (line {}, column {}): {e}", e.line(), e.column()))
        }
        gltf::Error::Binary(e) => LoadError::file(path, format!("invalid GLB container: {e}")),
        other => LoadError::file(path, format!("invalid glTF: {other}")),
    }
}
