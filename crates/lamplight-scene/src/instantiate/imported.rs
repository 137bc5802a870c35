//! A scene from an imported mesh file (OBJ, PLY, glTF): its meshes, placed as
//! the file places them, seen by the file's first camera or else by the
//! viewer's camera framing everything ([`super::viewer`]), and lit by the file's
//! lights, the viewer's lights and studio ([`super::studio`]), or both.
//! Emitting meshes (MTL `Ke`, glTF `emissiveFactor`) are lights of the file
//! too: they are the path tracer's area lights.
//!
//! A file without lights of its own gets the viewer's. A file with lights
//! keeps them alone when they reach at least [`viewer::MIN_LIT_SHARE`] of
//! what the camera sees of the model, as a probe of 16 x 16 camera rays at
//! [`viewer::PROBE_SIZE`] finds ([`lamplight_core::scene::lit_share`]); below
//! that (a jack-o'-lantern whose only light is inside it) the viewer's
//! lights are kept with them, and a note says so. [`MeshOptions::auto_lights`]
//! decides otherwise ([`AutoLights`]).

use std::path::Path;
use std::sync::Arc;

use lamplight_core::camera::{Camera, Fov, Orthographic, Perspective};
use lamplight_core::materials::Material;
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::shapes::TriangleMesh;
use lamplight_core::{Scene, SceneBuilder};

pub use super::viewer::AutoLights;
use super::{studio, viewer, Built};
use crate::error::LoadError;
use crate::import::{self, Imported, ImportedProjection};

/// Ambient radiance of an imported scene with lights of its own (its files carry none).
pub const AMBIENT: f64 = 0.1;

/// The choices a front end makes for a mesh file rendered directly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct MeshOptions {
    /// Meshes without normals get angle-weighted vertex normals (`--smooth`,
    /// Mitsuba's default for OBJ and PLY); else they are flat (glTF's rule,
    /// and Blender's import).
    pub smooth: bool,
    /// Whether a file with lights of its own keeps the viewer's lights too.
    pub auto_lights: AutoLights,
    /// The glTF animation that plays, an index into the file's `animations`
    /// (`--animation`, resolved by [`import::gltf_choice::resolve`]); `None`:
    /// the first, with a note when the file has several.
    pub animation: Option<usize>,
}

/// Reads the mesh file at `path` and builds a scene (for any image size).
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    load_with_warnings(path).map(|built| built.scene)
}

/// [`load`], keeping the importer's warnings, each as `PATH: what`.
pub fn load_with_warnings(path: &Path) -> Result<Built, LoadError> {
    load_with(path, MeshOptions::default())
}

/// [`load_with_warnings`] with the front end's `options`; the warnings end
/// with the note on the lights, if any ([`build_with`]). An animated glTF
/// file is built at its first frame.
pub fn load_with(path: &Path, options: MeshOptions) -> Result<Built, LoadError> {
    load_frame(path, options, None)
}

/// [`load_with`] at frame `frame` of the file's animation (`None`: its first
/// frame, 0; a glTF file's animation [`MeshOptions::animation`] at 24 fps:
/// [`import::gltf_animation`]). A file without animations is the same at every frame.
pub fn load_frame(path: &Path, options: MeshOptions, frame: Option<i64>) -> Result<Built, LoadError> {
    let mut imported = import::load(path)?;
    let framing = animation_sphere(path, &mut imported, options.animation.unwrap_or(0))?;
    imported.pose_clip_frame(path, options.animation.unwrap_or(0), frame.unwrap_or(0))?;
    if options.animation.is_none() {
        imported.warnings.extend(imported.several_animations_note());
    }
    let (scene, note) = build_framed(path, &imported, options, framing)?;
    let mut warnings = imported.warnings_of(path);
    warnings.extend(note);
    Ok(Built { scene, warnings })
}

/// What the viewer's camera of an animated file frames: the corners of each
/// placed mesh's bounds at every frame of animation `clip` (at most 257
/// frames, evenly spaced), so that the camera and its lights hold still and
/// see everything the animation reaches (`lamplight convert` writes the same
/// camera); `None` for a file without animations. `imported` is left as it was read.
pub fn animation_sphere(path: &Path, imported: &mut Imported, clip: usize) -> Result<Option<viewer::Sphere>, LoadError> {
    let Some(frames) = imported.clip_frames(clip) else { return Ok(None) };
    let bounds: Vec<Option<(Vec3, Vec3)>> = imported
        .meshes
        .iter()
        .map(|m| {
            let first = *m.positions.first()?;
            Some(m.positions.iter().fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))))
        })
        .collect();
    let (instances, cameras, lights) = (imported.instances.clone(), imported.cameras.clone(), imported.lights.clone());
    let step = (frames.end / 256).max(1);
    let mut corners = Vec::new();
    for frame in (0..=frames.end).step_by(step as usize).chain([frames.end]) {
        imported.instances.clone_from(&instances);
        imported.pose_clip_frame(path, clip, frame)?;
        for placed in &imported.instances {
            let Some(Some((lo, hi))) = bounds.get(placed.mesh) else { continue };
            for i in 0..8 {
                let corner = Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                );
                corners.push(placed.transform.transform_point3(corner));
            }
        }
    }
    (imported.instances, imported.cameras, imported.lights) = (instances, cameras, lights);
    Ok(viewer::bounding_sphere(corners.into_iter()))
}

/// Builds a scene from what an importer read from `path`.
pub fn build(path: &Path, imported: &Imported) -> Result<Scene, LoadError> {
    build_with(path, imported, MeshOptions::default()).map(|(scene, _)| scene)
}

/// [`build`] with `options`, and a note when the viewer's lights were kept
/// beside the file's because these reach too little of the view (module doc).
pub fn build_with(path: &Path, imported: &Imported, options: MeshOptions) -> Result<(Scene, Option<String>), LoadError> {
    build_framed(path, imported, options, None)
}

/// [`build_with`], the viewer's camera framing `framing` when given ([`animation_sphere`]).
fn build_framed(
    path: &Path,
    imported: &Imported,
    options: MeshOptions,
    framing: Option<viewer::Sphere>,
) -> Result<(Scene, Option<String>), LoadError> {
    let parts = Parts::new(path, imported, options.smooth, framing)?;
    let decided = decide(&parts, options.auto_lights)?;
    let scene = match decided.own {
        Some(scene) if !decided.viewer_lights => scene,
        _ => parts.assemble(decided.viewer_lights)?,
    };
    Ok((scene, decided.note))
}

/// Whether the scene [`build_with`] makes of `imported` has the viewer's
/// lights, and its note (for `lamplight convert`, which writes them out).
pub fn viewer_lights(path: &Path, imported: &Imported, auto_lights: AutoLights) -> Result<(bool, Option<String>), LoadError> {
    let parts = Parts::new(path, imported, false, None)?;
    let decided = decide(&parts, auto_lights)?;
    Ok((decided.viewer_lights, decided.note))
}

/// What [`decide`] found: whether the viewer's lights are added, the scene
/// lit by the file alone when it was built to probe, and the note.
struct Decided {
    viewer_lights: bool,
    own: Option<Scene>,
    note: Option<String>,
}

/// The module doc's rule.
fn decide(parts: &Parts<'_>, auto_lights: AutoLights) -> Result<Decided, LoadError> {
    let plain = |viewer_lights| Ok(Decided { viewer_lights, own: None, note: None });
    if !has_own_lights(parts.imported) {
        return plain(true);
    }
    match auto_lights {
        AutoLights::On => plain(true),
        AutoLights::Off => plain(false),
        AutoLights::Auto => {
            let own = parts.assemble(false)?;
            let (w, h) = viewer::PROBE_SIZE;
            let share = lamplight_core::scene::lit_share(&own, parts.camera.as_ref(), w, h).unwrap_or(1.0);
            if share >= viewer::MIN_LIT_SHARE {
                return Ok(Decided { viewer_lights: false, own: Some(own), note: None });
            }
            let note = format!(
                "{}: the file's own lights reach {:.0} % of what the camera sees (less than {:.0} %), so the automatic lights \
                 (studio, key, fill and rim) are kept with them; --keep-auto-lights off (Python keep_auto_lights=False) leaves them out",
                parts.path.display(),
                100.0 * share,
                100.0 * viewer::MIN_LIT_SHARE
            );
            Ok(Decided { viewer_lights: true, own: Some(own), note: Some(note) })
        }
    }
}

/// What every build of one file shares: its meshes and the camera.
struct Parts<'a> {
    path: &'a Path,
    imported: &'a Imported,
    meshes: Vec<Arc<TriangleMesh>>,
    eye: Vec3,
    target: Vec3,
    camera: Arc<dyn Camera>,
}

impl<'a> Parts<'a> {
    fn new(path: &'a Path, imported: &'a Imported, smooth: bool, framing: Option<viewer::Sphere>) -> Result<Parts<'a>, LoadError> {
        let fail = |e: lamplight_core::Error| LoadError::file(path, e.to_string());
        let mut meshes = Vec::with_capacity(imported.meshes.len());
        for data in &imported.meshes {
            // An index out of range is the mesh's error, reported by `to_mesh`.
            let in_range = || data.indices.iter().flatten().all(|&i| (i as usize) < data.positions.len());
            let mesh = if smooth && data.normals.is_none() && in_range() {
                let normals = TriangleMesh::angle_weighted_normals(&data.positions, &data.indices);
                data.to_mesh_with(Some(normals))
            } else {
                data.to_mesh()
            };
            meshes.push(Arc::new(mesh.map_err(fail)?));
        }
        for placed in &imported.instances {
            if imported.meshes.get(placed.mesh).is_none() {
                return Err(LoadError::file(path, format!("instance of missing mesh {}", placed.mesh)));
            }
        }
        let sphere = framing.or_else(|| world_sphere(imported)).ok_or_else(|| LoadError::file(path, "has no geometry to render"))?;
        let (eye, target, camera): (Vec3, Vec3, Arc<dyn Camera>) = match imported.cameras.first() {
            Some(c) => match c.projection {
                ImportedProjection::Perspective { vfov_deg } => {
                    (c.eye, c.target, Arc::new(Perspective::look_at(c.eye, c.target, c.up, Fov::VerticalDeg(vfov_deg)).map_err(fail)?))
                }
                ImportedProjection::Orthographic { xmag, ymag } => {
                    (c.eye, c.target, Arc::new(Orthographic::look_at(c.eye, c.target, c.up, xmag, ymag).map_err(fail)?))
                }
            },
            None => {
                let (eye, camera) = viewer::camera(sphere).map_err(fail)?;
                (eye, sphere.center, Arc::new(camera))
            }
        };
        Ok(Parts { path, imported, meshes, eye, target, camera })
    }

    /// The scene: the file's objects and lights, with the viewer's lights and
    /// studio when `viewer_lights`.
    fn assemble(&self, viewer_lights: bool) -> Result<Scene, LoadError> {
        let fail = |e: lamplight_core::Error| LoadError::file(self.path, e.to_string());
        let imported = self.imported;
        let mut builder = SceneBuilder::with_camera(self.camera.clone());
        builder.settings.ambient = Rgb::splat(AMBIENT);
        let default_material = builder.material(Material::default()).map_err(fail)?;
        for placed in &imported.instances {
            let material = match &placed.material {
                Some(m) => builder.material(m.clone()).map_err(fail)?,
                None => default_material,
            };
            // The file's names, for `explain` (as a converted scene file keeps them).
            if let Some(name) = placed.material_name.as_deref().filter(|n| placed.material.is_some() && !n.trim().is_empty()) {
                builder.name_material(material, name);
            }
            let shape = lamplight_core::shapes::placed(self.meshes[placed.mesh].clone(), &placed.transform).map_err(fail)?;
            let object = builder.shared_object(shape, material).map_err(fail)?;
            if let Some(name) = imported.meshes[placed.mesh].name.as_deref().filter(|n| !n.trim().is_empty()) {
                builder.name_object(object, name);
            }
        }
        if viewer_lights {
            builder.settings.ambient = Rgb::splat(viewer::AMBIENT);
            builder.settings.background = Rgb::splat(studio::FLOOR);
            builder.settings.environment = Some(Arc::new(studio::environment(self.eye, self.target).map_err(fail)?));
            for light in viewer::lights(self.eye, self.target).map_err(fail)? {
                builder.light(light);
            }
        }
        for light in &imported.lights {
            builder.shared_light(light.build().map_err(fail)?);
        }
        builder.build().map_err(fail)
    }
}

/// The bounding sphere of every placed vertex, in world space (what the
/// viewer's camera frames).
pub fn world_sphere(imported: &Imported) -> Option<viewer::Sphere> {
    let world_points = imported
        .instances
        .iter()
        .filter_map(|placed| Some((placed, imported.meshes.get(placed.mesh)?)))
        .flat_map(|(placed, mesh)| mesh.positions.iter().map(move |p| placed.transform.transform_point3(*p)));
    viewer::bounding_sphere(world_points)
}

/// Whether the file lights itself: lights of its own, or an emitting mesh
/// (else the viewer's lights and surround are added).
pub fn has_own_lights(imported: &Imported) -> bool {
    let emits = imported.instances.iter().any(|p| p.material.as_ref().is_some_and(|m| m.emission.max_element() > 0.0));
    !imported.lights.is_empty() || emits
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::{ImportedMesh, MeshData};
    use lamplight_core::math::Mat4;

    #[test]
    fn default_camera_frames_the_model_and_lights_are_added() {
        let mesh = MeshData {
            name: None,
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            normals: None,
            ..MeshData::default()
        };
        let imported = Imported {
            meshes: vec![mesh],
            instances: vec![ImportedMesh { mesh: 0, transform: Mat4::from_translation(Vec3::Z), material: None, material_name: None }],
            ..Imported::default()
        };
        let scene = build(Path::new("t.obj"), &imported).unwrap();
        assert_eq!(scene.objects.len(), 1);
        assert_eq!(scene.lights.len(), 3, "key, fill and rim");
        assert_eq!((scene.settings.background, scene.settings.ambient), (Rgb::splat(studio::FLOOR), Rgb::splat(viewer::AMBIENT)));
        assert!(scene.settings.environment.is_some(), "the studio");
        let ray = scene.settings.camera.ray(0.5, 0.5, 1, 1, (0.5, 0.5));
        let centre = Vec3::new(0.5, 0.5, 1.0);
        assert!((ray.dir - (centre - ray.origin).normalize()).length() < 1e-12, "looks at the centre");
        let empty = Imported::default();
        assert_eq!(build(Path::new("e.obj"), &empty).unwrap_err().to_string(), "e.obj: has no geometry to render");
    }

    #[test]
    fn the_files_object_and_material_names_reach_the_scene() {
        let mesh = |name: Option<&str>| MeshData {
            name: name.map(str::to_string),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            ..MeshData::default()
        };
        let red = Material { kd: Rgb::new(0.8, 0.1, 0.1), ..Material::default() };
        let imported = Imported {
            meshes: vec![mesh(Some("lamp")), mesh(None)],
            instances: vec![
                ImportedMesh { mesh: 0, transform: Mat4::IDENTITY, material: Some(red), material_name: Some("glass red".into()) },
                ImportedMesh { mesh: 1, transform: Mat4::IDENTITY, material: None, material_name: None },
            ],
            ..Imported::default()
        };
        let scene = build(Path::new("t.gltf"), &imported).unwrap();
        assert_eq!((scene.object_name(0), scene.object_name(1)), (Some("lamp"), None));
        let materials = (scene.objects[0].material, scene.objects[1].material);
        assert_eq!((scene.material_name(materials.0), scene.material_name(materials.1)), (Some("glass red"), None));
    }
}
