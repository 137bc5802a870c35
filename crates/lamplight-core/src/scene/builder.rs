//! [`SceneBuilder`]: objects, materials and lights collected, checked, and
//! built into a [`Scene`] with its BVH and the path tracer's prebuilt BSDFs.

use std::sync::Arc;

use super::{set_name, surface_bsdf, Names, Object, PrimRef, Scene, SceneSettings};
use crate::accel::{Aabb, Bvh, Costs, EyeBuffer, LightBuffer, ObjectLanes, FLAT_MAX};
use crate::camera::Camera;
use crate::lights::Light;
use crate::materials::Material;
use crate::math::{Rgb, Vec3};
use crate::shapes::Shape;
use crate::Error;

/// Collects objects, materials and lights, then builds a [`Scene`].
#[derive(Debug)]
pub struct SceneBuilder {
    objects: Vec<Object>,
    materials: Vec<Material>,
    lights: Vec<Arc<dyn Light>>,
    /// The camera, the ambient and background light, the sky and the
    /// recursion's limits ([`SceneSettings::new`] gives the defaults).
    pub settings: SceneSettings,
    /// Per material: a blend's components, added as materials of their own.
    blend_parts: Vec<Option<[usize; 2]>>,
    names: Names,
}

impl SceneBuilder {
    /// An empty scene seen by `camera`.
    pub fn new(camera: impl Camera + 'static) -> SceneBuilder {
        SceneBuilder::with_camera(Arc::new(camera))
    }

    /// An empty scene seen by a camera that may be shared.
    pub fn with_camera(camera: Arc<dyn Camera>) -> SceneBuilder {
        SceneBuilder {
            objects: Vec::new(),
            materials: Vec::new(),
            lights: Vec::new(),
            settings: SceneSettings::new(camera),
            blend_parts: Vec::new(),
            names: Names::default(),
        }
    }

    /// Gives object `object` the name `name` (shown by [`crate::explain`]).
    pub fn name_object(&mut self, object: usize, name: &str) {
        set_name(&mut self.names.objects, object, name);
    }

    /// Gives material `material` the name `name` (shown by [`crate::explain`]).
    pub fn name_material(&mut self, material: usize, name: &str) {
        set_name(&mut self.names.materials, material, name);
    }

    /// Material `index` as added ([`SceneBuilder::material`]), if there is one.
    pub fn material_at(&self, index: usize) -> Option<&Material> {
        self.materials.get(index)
    }

    /// Adds a material after checking its numbers; returns its index. A
    /// blend's components are added first, as materials of their own, which
    /// [`Scene::shade`] picks from per hit.
    pub fn material(&mut self, material: Material) -> Result<usize, Error> {
        material.validate()?;
        let parts = match &material.blend {
            Some(blend) => {
                let max = crate::materials::blend::MAX_DEPTH;
                if blend.depth() > max {
                    return Err(Error::invalid("blend", format!("blends nested more than {max} deep")));
                }
                Some([self.material(blend.a.clone())?, self.material(blend.b.clone())?])
            }
            None => None,
        };
        self.materials.push(material);
        self.blend_parts.push(parts);
        Ok(self.materials.len() - 1)
    }

    /// Places `shape` with material `material`; returns the object's index.
    pub fn object(&mut self, shape: impl Shape + 'static, material: usize) -> Result<usize, Error> {
        self.shared_object(Arc::new(shape), material)
    }

    /// Places an already shared shape (instancing: the geometry is not copied).
    pub fn shared_object(&mut self, shape: Arc<dyn Shape>, material: usize) -> Result<usize, Error> {
        if material >= self.materials.len() {
            return Err(Error::invalid("material", format!("index {material} does not exist")));
        }
        self.objects.push(Object { shape, material, reversed: false });
        Ok(self.objects.len() - 1)
    }

    /// Turns object `object`'s outward side inward ([`Object::reversed`]).
    pub fn reverse_orientation(&mut self, object: usize) {
        if let Some(o) = self.objects.get_mut(object) {
            o.reversed = !o.reversed;
        }
    }

    /// Adds a light.
    pub fn light(&mut self, light: impl Light + 'static) {
        self.lights.push(Arc::new(light));
    }

    /// Adds an already shared light.
    pub fn shared_light(&mut self, light: Arc<dyn Light>) {
        self.lights.push(light);
    }

    /// Number of objects placed so far (the index the next object gets).
    pub fn object_count(&self) -> usize {
        self.objects.len()
    }

    /// Builds the BVH and returns the finished scene.
    pub fn build(self) -> Result<Scene, Error> {
        self.settings.validate()?;
        let mut bounded = Vec::new();
        let mut unbounded = Vec::new();
        let mut boxes = Vec::new();
        for (i, object) in self.objects.iter().enumerate() {
            let b = object.shape.bounds();
            let material = &self.materials[object.material];
            let prim = PrimRef {
                object: i as u32,
                opaque: material.shadow_transmittance == Rgb::ZERO,
                masked: material.alpha.is_some(),
                inlined: Arc::clone(&object.shape).inlined(),
            };
            if b.is_finite() {
                bounded.push(prim);
                boxes.push(b);
            } else if b.is_empty() {
                continue; // nothing to hit
            } else {
                unbounded.push(prim);
            }
        }
        let any_partial_shadow = self.materials.iter().any(|m| m.shadow_transmittance != Rgb::ZERO && m.shadow_transmittance != Rgb::ONE);
        // Partly transparent shadows multiply every crossing, in the walk's order.
        let light_buffers =
            if any_partial_shadow { vec![None; self.lights.len()] } else { light_buffers(&self.lights, &self.objects, &boxes, &bounded) };
        let eye_buffer = eye_buffer(&*self.settings.camera, &self.objects, &boxes, &bounded);
        let lanes = object_lanes(&self.objects, &bounded, &unbounded);
        let neighbours = super::leaving::Neighbours::build(self.objects.len(), &bounded, &boxes, &unbounded, |i| &*self.objects[i].shape);
        let bsdfs = self
            .materials
            .iter()
            .map(|m| m.is_constant().then(|| [surface_bsdf(m, Vec3::ZERO, false), surface_bsdf(m, Vec3::ZERO, true)]))
            .collect();
        let uses_footprints = self.materials.iter().any(Material::uses_footprint);
        let moves = self.objects.iter().any(|o| o.shape.moves());
        let turns_normals = self.materials.iter().any(|m| m.normal_map.is_some() || m.bump.is_some());
        let plain = self
            .materials
            .iter()
            .map(|m| {
                m.normal_map.is_none()
                    && m.bump.is_none()
                    && m.textures.is_none()
                    && m.pbr.is_none()
                    && m.blend.is_none()
                    && !m.color.needs_coords()
            })
            .collect();
        Ok(Scene {
            plain,
            uses_footprints,
            moves,
            turns_normals,
            bsdfs,
            bvh: Bvh::build_with(&boxes, Costs::OBJECTS),
            bounded,
            unbounded,
            any_partial_shadow,
            light_buffers,
            eye: eye_buffer.as_ref().map_or(Vec3::NAN, EyeBuffer::eye),
            eye_buffer,
            neighbours,
            lanes,
            objects: self.objects,
            materials: self.materials,
            point_lights: self.lights.iter().map(|l| l.point_light().cloned()).collect(),
            lights: self.lights,
            settings: self.settings,
            blend_parts: self.blend_parts,
            names: self.names,
        })
    }
}

/// The objects' tests in lanes ([`ObjectLanes`]) where the scene is at most
/// [`FLAT_MAX`] bounded objects, every one of a kind the lanes test
/// ([`Shape::lane`]) and none with holes cut by its material; `None` otherwise.
fn object_lanes(objects: &[Object], bounded: &[PrimRef], unbounded: &[PrimRef]) -> Option<ObjectLanes> {
    if !unbounded.is_empty() || bounded.len() > FLAT_MAX {
        return None;
    }
    let list = bounded
        .iter()
        .map(|p| (!p.masked).then(|| objects[p.object as usize].shape.lane()).flatten().map(|shape| (shape, p.opaque, p.object)))
        .collect::<Option<Vec<_>>>()?;
    ObjectLanes::build(&list)
}

/// The eye's buffer ([`EyeBuffer`]) where every ray of the camera leaves one
/// point (a pinhole) and every bounded object's test ignores `t_max`
/// ([`Shape::hit_ignores_t_max`]); `None` otherwise, or where the buffer
/// would be too large. A scene of at most [`FLAT_MAX`] objects keeps its flat
/// walk, which tests all their boxes at once and the entered ones nearest
/// first: in the Cornell box the lists' walls, ordered by where their boxes
/// begin, made the path-traced render 2-4 % slower (business-card 2 %).
fn eye_buffer(camera: &dyn Camera, objects: &[Object], boxes: &[Aabb], bounded: &[PrimRef]) -> Option<EyeBuffer> {
    if bounded.len() <= FLAT_MAX
        || camera.uses_lens_sample()
        || !bounded.iter().all(|p| objects[p.object as usize].shape.hit_ignores_t_max())
    {
        return None;
    }
    // The centre and the corners of a small image: one origin for all, or no buffer.
    let origin = |x: f64, y: f64| camera.ray(x, y, 64, 64, (0.5, 0.5)).origin;
    let eye = origin(32.0, 32.0);
    if !eye.is_finite() || [(0.0, 0.0), (64.0, 0.0), (0.0, 64.0), (64.0, 64.0)].iter().any(|&(x, y)| origin(x, y) != eye) {
        return None;
    }
    EyeBuffer::build(eye, boxes, |i, region| objects[bounded[i].object as usize].shape.may_meet(region), scene_scale(boxes))
}

/// The largest coordinate magnitude of the boxes `boxes`: the scene's extent,
/// which the buffers' `near` distance scales with.
fn scene_scale(boxes: &[Aabb]) -> f64 {
    boxes.iter().map(|b| b.min.abs().max(b.max.abs()).max_element()).fold(0.0, f64::max)
}

/// Lights with a buffer of their own; shadow rays towards later lights walk the BVH.
const MAX_LIGHT_BUFFERS: usize = 16;

/// The light buffer of each of the first [`MAX_LIGHT_BUFFERS`] lights that leave
/// one point, over the bounded objects `bounded` with boxes `boxes`, listing
/// those that can block a shadow ray, sized by the scene's extent (the light
/// buffer's `near` distance scales with it).
fn light_buffers(lights: &[Arc<dyn Light>], objects: &[Object], boxes: &[Aabb], bounded: &[PrimRef]) -> Vec<Option<LightBuffer>> {
    let scale = scene_scale(boxes);
    lights
        .iter()
        .enumerate()
        .map(|(i, light)| {
            let centre = light.point_source().filter(|_| i < MAX_LIGHT_BUFFERS)?;
            LightBuffer::build(
                centre,
                boxes,
                |i| bounded[i].opaque,
                |i, region| objects[bounded[i].object as usize].shape.may_meet(region),
                scale,
            )
        })
        .collect()
}
