//! Rays that leave an object's surface back into it: a refracted ray that
//! enters a glass ball, a ray reflected inside it. Such a ray's nearest hit
//! is found among the object and its few neighbours instead of by the BVH
//! walk.
//!
//! In the POV-Ray `spheres` scene 44 % of the secondary rays start inside a
//! glass ball and end on its far side, and each walked the tree (about 660
//! instructions; issue 24). Testing the ball, the floor it stands on and
//! the infinite objects costs about a quarter of that.
//!
//! **The same answer as the walk, bit for bit.** Let the ray start on or
//! near object `S` (the object whose surface it leaves) and let `S` report
//! a hit at `t_S`. If the ray's origin and its point at `t_S` both lie in
//! `B`, `S`'s box grown by a margin, then so does its whole segment up to
//! `t_S` (a box is convex), and any object hit at `t <= t_S` is hit at a
//! point of `B`: its own box meets `B`. Those objects, the neighbours, are
//! listed for `S` when the scene is built (boxes grown by the margin on both
//! sides, which covers the rounding of a reported hit point). So the nearest
//! hit among `S`, the unbounded objects and `S`'s neighbours is the nearest
//! of all, with the shape's own report: every object's test must ignore
//! `t_max` ([`crate::shapes::Shape::hit_ignores_t_max`]), as for the eye's
//! buffer. Where two objects are hit at exactly the nearest distance, the
//! walk's order decides: such a ray is handed to the walk, as is a ray whose
//! `S` reports no hit (a ray leaving `S` outwards), or whose points fall
//! outside `B`.
//!
//! Written by hand, as the eye's buffer: it is part of the tracer's heart.

use super::{Hit, PrimRef, Scene};
use crate::accel::Aabb;
use crate::math::{max_abs, Vec3};
use crate::ray::Ray;
use crate::shapes::{Shape, SurfaceHit};

/// Most neighbours an object may have for its rays to take the short way:
/// more, and the walk is as quick.
const MAX_NEIGHBOURS: usize = 8;
/// Box overlap tests the build may make per object before it gives up (a
/// scene of long boxes that all overlap along `x`).
const WORK_PER_OBJECT: usize = 64;
/// Most objects the lists are built for: beyond, a scene is mostly instances
/// or meshes, whose secondary rays are not worth a build of this size.
const MAX_OBJECTS: usize = 1 << 16;
/// The margin boxes grow by, relative to the size and place of the box: far
/// above the rounding of a hit point (about `1e-16` of its coordinates), far
/// below any gap between objects that matters.
const MARGIN: f64 = 1e-9;

/// One object's short way: its place among the BVH's objects, its grown box
/// and its neighbours (`list[start..start + count]`).
#[derive(Clone, Copy, Debug)]
struct Entry {
    prim: u32,
    bounds: Aabb,
    start: u32,
    count: u32,
}

/// Per object of a scene, its neighbours (module doc).
#[derive(Clone, Debug, Default)]
pub(super) struct Neighbours {
    /// Per object (by its index in the scene), its entry in `entries`, or `u32::MAX`.
    of_object: Vec<u32>,
    entries: Vec<Entry>,
    /// The neighbours, as indices of the BVH's objects.
    list: Vec<u32>,
}

impl Neighbours {
    /// The lists for the BVH's objects `bounded` with boxes `boxes`, in a
    /// scene of `objects` objects; empty where some object's test depends on
    /// `t_max` (`shape_of` gives each object's shape) or the scene has more
    /// than [`MAX_OBJECTS`] bounded objects. A flat scene (the
    /// business card's five objects) gains too: without lists its Whitted
    /// render took 3.5 % longer.
    pub(super) fn build<'a>(
        objects: usize,
        bounded: &[PrimRef],
        boxes: &[Aabb],
        unbounded: &[PrimRef],
        shape_of: impl Fn(usize) -> &'a dyn Shape,
    ) -> Neighbours {
        let every = bounded.iter().chain(unbounded);
        if bounded.is_empty() || bounded.len() > MAX_OBJECTS || !every.clone().all(|p| shape_of(p.object as usize).hit_ignores_t_max()) {
            return Neighbours::default();
        }
        let grown: Vec<Aabb> = boxes.iter().map(|b| grow(*b)).collect();
        // A box near the largest floats grows past them: it could not be
        // swept, and every object must be in the sweep to be listed.
        if !grown.iter().all(Aabb::is_finite) {
            return Neighbours::default();
        }
        let mut order: Vec<usize> = (0..bounded.len()).collect();
        order.sort_by(|&a, &b| grown[a].min.x.total_cmp(&grown[b].min.x));
        // Sweep along x: each box meets only those that start before it ends.
        let mut near: Vec<Vec<u32>> = vec![Vec::new(); bounded.len()];
        let mut work = 0;
        for (k, &a) in order.iter().enumerate() {
            for &b in &order[k + 1..] {
                if grown[b].min.x > grown[a].max.x {
                    break;
                }
                work += 1;
                if work > WORK_PER_OBJECT * bounded.len() {
                    return Neighbours::default();
                }
                if !grown[a].intersection(grown[b]).is_empty() {
                    near[a].push(b as u32);
                    near[b].push(a as u32);
                }
            }
        }
        let mut n = Neighbours { of_object: vec![u32::MAX; objects], ..Neighbours::default() };
        for &i in &order {
            if near[i].len() > MAX_NEIGHBOURS {
                continue;
            }
            n.of_object[bounded[i].object as usize] = n.entries.len() as u32;
            n.entries.push(Entry { prim: i as u32, bounds: grown[i], start: n.list.len() as u32, count: near[i].len() as u32 });
            n.list.extend_from_slice(&near[i]);
        }
        n
    }
}

/// `b` grown by [`MARGIN`] of its size and of its coordinates' magnitude.
fn grow(b: Aabb) -> Aabb {
    let m = MARGIN * (max_abs(b.extent()) + max_abs(b.min).max(max_abs(b.max)));
    Aabb { min: b.min - Vec3::splat(m), max: b.max + Vec3::splat(m) }
}

impl Scene {
    /// The object whose surface a ray spawned at `hit` along `dir` leaves into
    /// its inside (against the shape's outward normal), for
    /// [`Scene::first_intersect_leaving`]; `usize::MAX` for a ray that leaves
    /// it outwards, which would meet the object again only where it is not
    /// convex: testing it first would mostly be wasted (a mirror ball's
    /// reflections, a glass ellipsoid's in `luxo`, measured +2 % there).
    #[inline(always)]
    pub fn leaving_into(&self, hit: &Hit, dir: Vec3) -> usize {
        // The geometric normal faces the ray that hit; the shape's outward
        // normal is it, or its opposite where the ray met the inside.
        let met_outside = hit.front_face != self.objects[hit.object].reversed;
        if (dir.dot(hit.geometric_normal) < 0.0) == met_outside {
            hit.object
        } else {
            usize::MAX
        }
    }

    /// [`Scene::first_intersect`] over `(0, inf)` of a ray that leaves the
    /// surface of object `from`: among the object and its neighbours where
    /// that gives the walk's answer, else by the walk (module doc).
    #[inline(always)]
    pub fn first_intersect_leaving(&self, ray: &Ray, from: usize) -> Option<Hit> {
        match self.nearest_near(ray, from) {
            Some((object, h)) => Some(self.hit_record(ray, object, h)),
            None => self.first_intersect(ray, f64::INFINITY),
        }
    }

    /// The nearest hit among object `from`, the unbounded objects and
    /// `from`'s neighbours, or `None` where the walk must answer (`from`
    /// itself reports no hit, or the answer is not known to be the walk's).
    #[inline(always)]
    fn nearest_near(&self, ray: &Ray, from: usize) -> Option<(usize, SurfaceHit)> {
        let index = *self.neighbours.of_object.get(from)?;
        let entry = self.neighbours.entries.get(index as usize)?;
        if !entry.bounds.contains(ray.origin) {
            return None;
        }
        let prim = &self.bounded[entry.prim as usize];
        let own = self.hit_object(prim, ray, f64::INFINITY)?;
        if !entry.bounds.contains(ray.at(own.t)) {
            return None;
        }
        let mut best = (prim.object as usize, own);
        let mut closest = own.t;
        // Each object is asked up to the float past `closest`, so that a hit
        // at exactly `closest` shows: a tie, left to the walk.
        let mut limit = closest.next_up();
        let mut tie = false;
        let start = entry.start as usize;
        let neighbours = self.neighbours.list[start..start + entry.count as usize].iter().map(|&i| &self.bounded[i as usize]);
        for other in self.unbounded.iter().chain(neighbours) {
            let Some(h) = self.hit_object(other, ray, limit) else { continue };
            if h.t < closest {
                closest = h.t;
                limit = h.t.next_up();
                best = (other.object as usize, h);
                tie = false;
            } else {
                tie = true;
            }
        }
        (!tie).then_some(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::materials::Material;
    use crate::math::Mat4;
    use crate::sampling::Rng;
    use crate::scene::SceneBuilder;
    use crate::shapes::{Cuboid, Plane, Quadric, Rectangle, Sphere};

    fn reflect(d: Vec3, n: Vec3) -> Vec3 {
        d - n * (2.0 * d.dot(n))
    }

    /// Snell's law for unit `d` through unit `n` facing it, `eta = n_i / n_t`.
    fn refract(d: Vec3, n: Vec3, eta: f64) -> Option<Vec3> {
        let c = -d.dot(n);
        let k = 1.0 - eta * eta * (1.0 - c * c);
        (k >= 0.0).then(|| (d * eta + n * (eta * c - k.sqrt())).normalize())
    }

    /// Balls on a floor (touching it), boxes, ellipsoids, a ball inside a
    /// ball, a ball placed twice (exact ties), a cluster of overlapping balls
    /// (too many neighbours) and an infinite plane behind them all.
    fn scene() -> Scene {
        let mut rng = Rng::for_sample(11, 0, 0);
        let mut rand = move || rng.uniform();
        let camera = Perspective::look_at(Vec3::new(0.0, 3.0, 12.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(50.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let m = b.material(Material::default()).unwrap();
        b.object(Rectangle::horizontal(0.0, -8.0, 8.0, -8.0, 8.0).unwrap(), m).unwrap();
        b.object(Plane::new(Vec3::new(0.0, 0.0, -20.0), Vec3::Z).unwrap(), m).unwrap();
        for k in 0..24 {
            let c = Vec3::new(rand() * 12.0 - 6.0, 0.0, rand() * 12.0 - 6.0);
            let r = 0.2 + rand() * 0.5;
            match k % 3 {
                0 => b.object(Sphere::new(c + Vec3::Y * r, r).unwrap(), m).unwrap(),
                1 => b.object(Cuboid::new(c, c + Vec3::splat(2.0 * r), Mat4::from_rotation_y(rand())).unwrap(), m).unwrap(),
                _ => b.object(Quadric::ellipsoid(c + Vec3::Y * (r + 0.5), Vec3::new(r, 0.5, 0.7 * r)).unwrap(), m).unwrap(),
            };
        }
        let twice = Sphere::new(Vec3::new(0.0, 2.0, 0.0), 0.8).unwrap();
        b.object(twice, m).unwrap();
        b.object(twice, m).unwrap();
        b.object(Sphere::new(Vec3::new(3.0, 3.0, 1.0), 1.0).unwrap(), m).unwrap();
        b.object(Sphere::new(Vec3::new(3.2, 3.1, 1.0), 0.4).unwrap(), m).unwrap();
        for k in 0..12 {
            b.object(Sphere::new(Vec3::new(-3.0 + 0.05 * k as f64, 4.0, 0.0), 0.5).unwrap(), m).unwrap();
        }
        b.build().unwrap()
    }

    /// Rays leaving the surfaces of every kind of object, into them (refracted
    /// and reflected inside) and out of them, get the walk's answer bit for
    /// bit, ties included; the short way answers most rays that go in.
    #[test]
    fn rays_leaving_a_surface_get_the_walks_answer() {
        let scene = scene();
        let mut rng = Rng::for_sample(12, 0, 0);
        let mut rand = move || rng.uniform();
        let eye = Vec3::new(0.0, 3.0, 12.0);
        let (mut inward, mut short, mut ties) = (0, 0, 0);
        for k in 0..20_000 {
            let target = if k % 5 == 0 {
                Vec3::new(rand() - 0.5, 2.0 + rand() - 0.5, rand() - 0.5)
            } else {
                Vec3::new(rand() * 12.0 - 6.0, rand() * 4.0, rand() * 12.0 - 6.0)
            };
            let Some(hit) = scene.first_intersect(&Ray::unit(eye, (target - eye).normalize()), f64::INFINITY) else { continue };
            let d = (target - eye).normalize();
            let eta = [1.5, 1.0 / 1.5, 1.0][k % 3];
            let dirs = [refract(d, hit.geometric_normal, eta), Some(reflect(d, hit.geometric_normal))];
            for dir in dirs.into_iter().flatten() {
                let origin = crate::ray::offset_origin(hit.point, hit.geometric_normal, dir, hit.t, hit.error);
                let ray = hit.spawn(origin, dir);
                let walk = scene.first_intersect_in::<false>(&ray, f64::INFINITY);
                // Hit from outside (the eye is outside every object but the
                // floor's half-space): refracted rays go in, reflected ones out.
                let went_in = dir.dot(hit.geometric_normal) < 0.0;
                assert_eq!(scene.leaving_into(&hit, dir), if went_in { hit.object } else { usize::MAX });
                assert_eq!(scene.first_intersect_leaving(&ray, hit.object), walk, "ray {ray:?} from object {}", hit.object);
                // Into a listed object (a ball, a box, an ellipsoid, not the floor).
                let listed = scene.neighbours.of_object[hit.object] != u32::MAX;
                if dir.dot(hit.geometric_normal) < 0.0 && listed && hit.object != 0 {
                    // The ball placed twice (objects 26 and 27) ties everywhere.
                    let twin = hit.object == 26 || hit.object == 27;
                    match scene.nearest_near(&ray, hit.object) {
                        Some(_) => assert!(!twin, "a tie answered the short way: {ray:?}"),
                        None if twin => ties += 1,
                        None => {}
                    }
                    if !twin {
                        inward += 1;
                        short += usize::from(scene.nearest_near(&ray, hit.object).is_some());
                    }
                } else {
                    assert!(scene.nearest_near(&ray, hit.object).is_none() || listed);
                }
            }
        }
        assert!(inward > 1_000, "only {inward} rays went into a listed object");
        assert!(short > inward * 9 / 10, "the short way answered {short} of {inward} rays that went into a listed object");
        assert!(ties > 20, "only {ties} rays into listed objects were handed to the walk: the ball placed twice was not met");
    }

    /// No lists where an object's test depends on `t_max`, and none for an
    /// object with more than eight neighbours.
    #[test]
    fn lists_only_where_the_short_way_holds() {
        let scene = scene();
        let crowded = scene.objects.len() - 6;
        assert_eq!(scene.neighbours.of_object[crowded], u32::MAX, "a ball among eleven overlapping ones");
        assert_ne!(scene.neighbours.of_object[2], u32::MAX, "the first ball on the floor");
        let balls = |count: usize, marching: bool| {
            let mut b = SceneBuilder::new(Perspective::look_at(Vec3::Z, Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(50.0)).unwrap());
            let m = b.material(Material::default()).unwrap();
            for k in 0..count {
                b.object(Sphere::new(Vec3::new(3.0 * k as f64, 0.0, 0.0), 1.0).unwrap(), m).unwrap();
            }
            if marching {
                let f: crate::shapes::ImplicitFn = std::sync::Arc::new(|p: Vec3| p.length() - 0.5);
                let ball = crate::shapes::Implicit::new(f, Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0)), 1.0).unwrap();
                b.object(ball, m).unwrap();
            }
            b.build().unwrap().neighbours
        };
        assert_eq!(balls(20, false).entries.len(), 20);
        assert!(balls(20, true).entries.is_empty(), "a surface found by marching");
        assert_eq!(balls(3, false).entries.len(), 3, "a flat scene has lists too");
        // A box whose margin overflows: no lists rather than one left out of them.
        let mut b = SceneBuilder::new(Perspective::look_at(Vec3::Z, Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(50.0)).unwrap());
        let m = b.material(Material::default()).unwrap();
        b.object(Sphere::new(Vec3::ZERO, 1.0).unwrap(), m).unwrap();
        b.object(Sphere::new(Vec3::new(1.79769313486e308, 0.0, 0.0), 1e296).unwrap(), m).unwrap();
        let scene = b.build().unwrap();
        assert!(scene.objects[1].shape.bounds().is_finite(), "the test needs a finite box");
        assert!(scene.neighbours.entries.is_empty(), "a box at the largest floats");
    }
}
