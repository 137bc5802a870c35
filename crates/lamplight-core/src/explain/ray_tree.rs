//! [`RayTree`]: the recorder of a Whitted sample, and the tree it builds.
//!
//! The tracer runs its recursion as a depth-first work list; the recorder keeps
//! a mirror of that list (each traced branch pushed, each ray taken off popped),
//! so every event lands on the node of the ray being traced. Children are the
//! reflected ray, then the refracted one, the order the tracer makes them.

use super::HitInfo;
use crate::integrators::trace::{LightRef, LightTerm, ReflectionWeight, Unlit, WhittedTrace};
use crate::math::Rgb;
use crate::ray::{offset_origin, Ray};
use crate::scene::{Hit, Scene};

/// What made a ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayKind {
    /// The camera.
    Camera,
    /// Mirror reflection at its parent's hit.
    Reflected,
    /// Refraction at its parent's hit.
    Refracted,
}

/// One ray of the tree with what it met and the rays it spawned.
#[derive(Clone, Debug, PartialEq)]
pub struct RayNode {
    /// What made it.
    pub kind: RayKind,
    /// Origin and unit direction.
    pub ray: Ray,
    /// Depth (camera ray = 1).
    pub depth: u32,
    /// The product of the weights above it: what its radiance is multiplied by in the pixel.
    pub weight: Rgb,
    /// It travels inside an object (a refracted ray that entered, ...).
    pub inside: bool,
    /// What it met.
    pub outcome: RayOutcome,
    /// The reflected and refracted rays, in the tracer's order.
    pub children: Vec<RayNode>,
}

/// What a ray met.
#[derive(Clone, Debug, PartialEq)]
pub enum RayOutcome {
    /// Not traced: its weight fell to or below the scene's `min_weight`.
    Dropped,
    /// It left the scene and sees the sky `radiance`; adds `contribution = weight * radiance`.
    Miss {
        /// Background or environment radiance.
        radiance: Rgb,
        /// What it adds to the pixel.
        contribution: Rgb,
    },
    /// It hit a surface.
    Hit(Box<ShadingRecord>),
}

/// A hit and the lecture's terms there.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadingRecord {
    /// The hit.
    pub hit: HitInfo,
    /// Surface colour `C` at the point.
    pub color: Rgb,
    /// Emission `Ke` towards the ray.
    pub emission: Rgb,
    /// `ka C La`.
    pub ambient: Rgb,
    /// Each light (each point of each area light), in the tracer's order.
    pub lights: Vec<LightRecord>,
    /// The direct light: `Ke + ka C La + sum of the lights' terms`.
    pub direct: Rgb,
    /// `weight * direct`: what the hit adds to the pixel.
    pub contribution: Rgb,
    /// Reflection: how the weight was found and the local weight.
    pub reflection: Option<(ReflectionWeight, Rgb)>,
    /// Refraction: Fresnel `F` (for Fresnel glass) and the local weight (`1 - F`; `None`: total internal reflection).
    pub refraction: Option<(Option<f64>, Option<Rgb>)>,
    /// The depth limit stopped the recursion here.
    pub depth_cutoff: bool,
}

/// One light at one hit.
#[derive(Clone, Debug, PartialEq)]
pub struct LightRecord {
    /// Which light.
    pub light: LightRef,
    /// Its kind (`PointLight`, ...; area lights: the emitter's shape).
    pub kind: String,
    /// What it gave.
    pub outcome: LightOutcome,
}

/// What a light gave at a hit.
#[derive(Clone, Debug, PartialEq)]
pub enum LightOutcome {
    /// Nothing, without a shadow ray.
    Unlit(Unlit),
    /// Its terms and shadow ray; `blockers` are the objects that dimmed or
    /// stopped the shadow ray, nearest first (empty when clear).
    Lit {
        /// The terms (boxed: an unlit light is a few bytes).
        term: Box<LightTerm>,
        /// Objects on the shadow ray that are not clear, up to the first opaque one.
        blockers: Vec<ObjectRef>,
    },
}

/// A scene object as the explanation names it: index, the scene file's name, kind.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectRef {
    /// Index in the scene.
    pub object: usize,
    /// Its name in the scene file, if any.
    pub name: Option<String>,
    /// Its shape's kind.
    pub kind: String,
}

impl ObjectRef {
    /// Object `object` of `scene`.
    pub fn new(scene: &Scene, object: usize) -> ObjectRef {
        let name = scene.object_name(object).map(str::to_string);
        ObjectRef { object, name, kind: super::kind_name(&*scene.objects[object].shape) }
    }
}

impl std::fmt::Display for ObjectRef {
    /// `object 95 (Sphere)`, `object 0 "s0" (Sphere)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "object {}", self.object)?;
        if let Some(name) = &self.name {
            write!(f, " {name:?}")?;
        }
        write!(f, " ({})", self.kind)
    }
}

/// The recorder of a Whitted sample: nodes in the order made, linked by index.
#[derive(Debug, Default)]
pub struct RayTree {
    nodes: Vec<Flat>,
    /// Mirror of the tracer's work list.
    stack: Vec<usize>,
    current: usize,
    /// Branch kinds the current hit announced, not yet made.
    announced: Vec<RayKind>,
    light: Option<LightRef>,
    contributions: Vec<Rgb>,
}

#[derive(Debug)]
struct Flat {
    node: RayNode,
    children: Vec<usize>,
}

impl RayTree {
    /// The tree and the contributions in the tracer's order; `None` if nothing was recorded.
    pub fn finish(mut self) -> Option<(RayNode, Vec<Rgb>)> {
        if self.nodes.is_empty() {
            return None;
        }
        // Children are made after their parents: build from the last node back.
        let mut built: Vec<Option<RayNode>> = vec![None; self.nodes.len()];
        for i in (0..self.nodes.len()).rev() {
            let Flat { node, children } = std::mem::replace(
                &mut self.nodes[i],
                Flat {
                    node: RayNode {
                        kind: RayKind::Camera,
                        ray: Ray::unit(Default::default(), Default::default()),
                        depth: 0,
                        weight: Rgb::ZERO,
                        inside: false,
                        outcome: RayOutcome::Dropped,
                        children: Vec::new(),
                    },
                    children: Vec::new(),
                },
            );
            let mut node = node;
            node.children = children.iter().map(|&c| built[c].take().expect("a child is built before its parent")).collect();
            built[i] = Some(node);
        }
        Some((built[0].take().expect("the root"), self.contributions))
    }

    fn shading(&mut self) -> &mut ShadingRecord {
        match &mut self.nodes[self.current].node.outcome {
            RayOutcome::Hit(s) => s,
            _ => panic!("a shading event without a hit"),
        }
    }

    fn push_light(&mut self, kind: String, outcome: LightOutcome) {
        let light = self.light.take().expect("a light event follows `light`");
        self.shading().lights.push(LightRecord { light, kind, outcome });
    }
}

/// The objects a shadow ray from `ray.origin` over `length` crosses that are
/// not clear (`shadow_transmittance` below 1), nearest first, up to the first
/// opaque one; it ends where it first meets `own` (as [`Scene::transmittance`]).
fn blockers(scene: &Scene, ray: &Ray, length: f64, own: Option<usize>) -> Vec<ObjectRef> {
    let mut found = Vec::new();
    let mut origin = ray.origin;
    let mut remaining = length;
    for _ in 0..64 {
        let Some(h) = scene.first_intersect(&ray.spawn(origin, ray.dir), remaining) else { break };
        if Some(h.object) == own {
            break;
        }
        let transmittance = scene.materials[h.material].shadow_transmittance;
        if transmittance != Rgb::ONE {
            found.push(ObjectRef::new(scene, h.object));
        }
        if transmittance == Rgb::ZERO {
            break;
        }
        let next = offset_origin(h.point, h.geometric_normal, ray.dir, h.t, h.error);
        remaining -= (next - origin).length();
        origin = next;
        if remaining <= 0.0 {
            break;
        }
    }
    found
}

impl WhittedTrace for RayTree {
    fn ray(&mut self, ray: &Ray, weight: Rgb, depth: u32) {
        if self.nodes.is_empty() {
            let node = RayNode {
                kind: RayKind::Camera,
                ray: *ray,
                depth,
                weight,
                inside: false,
                outcome: RayOutcome::Dropped,
                children: Vec::new(),
            };
            self.nodes.push(Flat { node, children: Vec::new() });
            self.current = 0;
            return;
        }
        self.current = self.stack.pop().expect("the tracer takes off only rays it put on");
        debug_assert_eq!((self.nodes[self.current].node.ray, self.nodes[self.current].node.depth), (*ray, depth));
    }

    fn miss(&mut self, radiance: Rgb, contribution: Rgb) {
        self.nodes[self.current].node.outcome = RayOutcome::Miss { radiance, contribution };
        self.contributions.push(contribution);
    }

    fn hit(&mut self, scene: &Scene, hit: &Hit) {
        self.nodes[self.current].node.outcome = RayOutcome::Hit(Box::new(ShadingRecord {
            hit: HitInfo::new(scene, hit),
            color: Rgb::ZERO,
            emission: Rgb::ZERO,
            ambient: Rgb::ZERO,
            lights: Vec::new(),
            direct: Rgb::ZERO,
            contribution: Rgb::ZERO,
            reflection: None,
            refraction: None,
            depth_cutoff: false,
        }));
        self.announced.clear();
    }

    fn surface(&mut self, color: Rgb, emission: Rgb, ambient: Rgb) {
        let s = self.shading();
        (s.color, s.emission, s.ambient) = (color, emission, ambient);
    }

    fn light(&mut self, light: LightRef) {
        self.light = Some(light);
    }

    fn unlit(&mut self, why: Unlit) {
        self.push_light(String::new(), LightOutcome::Unlit(why));
    }

    fn lit(&mut self, scene: &Scene, term: &LightTerm) {
        let blockers = if term.visible == Rgb::ONE { Vec::new() } else { blockers(scene, &term.shadow, term.shadow_length, term.own) };
        self.push_light(String::new(), LightOutcome::Lit { term: Box::new(*term), blockers });
    }

    fn direct(&mut self, direct: Rgb, contribution: Rgb) {
        let s = self.shading();
        (s.direct, s.contribution) = (direct, contribution);
        self.contributions.push(contribution);
    }

    fn depth_cutoff(&mut self) {
        self.shading().depth_cutoff = true;
    }

    fn reflection(&mut self, how: ReflectionWeight, weight: Rgb) {
        self.shading().reflection = Some((how, weight));
        self.announced.push(RayKind::Reflected);
    }

    fn refraction(&mut self, fresnel: Option<f64>, weight: Option<Rgb>) {
        self.shading().refraction = Some((fresnel, weight));
        // The tracer makes no ray of weight 0.
        if weight.is_some_and(|w| w != Rgb::ZERO) {
            self.announced.push(RayKind::Refracted);
        }
    }

    fn branch(&mut self, ray: &Ray, weight: Rgb, depth: u32, traced: bool) {
        let kind = self.announced.remove(0);
        let parent = self.current;
        let front_face = match &self.nodes[parent].node.outcome {
            RayOutcome::Hit(s) => s.hit.front_face,
            _ => unreachable!("branches leave hits"),
        };
        // A reflected ray stays on the side it came from; a refracted one crosses.
        let inside = match kind {
            RayKind::Refracted => front_face,
            _ => !front_face,
        };
        let outcome = RayOutcome::Dropped;
        let node = RayNode { kind, ray: *ray, depth, weight, inside, outcome, children: Vec::new() };
        self.nodes.push(Flat { node, children: Vec::new() });
        let id = self.nodes.len() - 1;
        self.nodes[parent].children.push(id);
        if traced {
            self.stack.push(id);
        }
    }
}

impl RayNode {
    /// Fills in the kinds of the lights of this node and those below (the
    /// events name lights by index; their kinds come from `scene`).
    pub(crate) fn name_lights(&mut self, scene: &Scene) {
        if let RayOutcome::Hit(s) = &mut self.outcome {
            for record in &mut s.lights {
                record.kind = match record.light {
                    LightRef::Delta(i) => super::kind_name(&*scene.lights[i]),
                    LightRef::Area { object, .. } => format!("emitting {}", super::kind_name(&*scene.objects[object].shape)),
                };
            }
        }
        self.children.iter_mut().for_each(|c| c.name_lights(scene));
    }
}
