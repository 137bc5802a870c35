//! One triangle mesh prepared for batch ray casting: the Embree-style target.
//!
//! [`MeshAccel`] builds the `f32` ray-casting BVH ([`crate::accel::MeshBvh`]) over
//! a mesh given as positions and triangle indices. As a [`BatchTarget`] it is one
//! object (number 0) whose primitives are its triangles, answered in the units of
//! [`crate::batch`]: distance `t = s |d|`, triangle index in input order. `f64`
//! rays are rounded to `f32` first.
//!
//! The single-ray kernels [`MeshAccel::nearest_param`] and
//! [`MeshAccel::occluded_param`] work in the ray *parameter* `s` of
//! `origin + s dir` along the direction as given (Embree's `tfar`), without the
//! conversion to a distance; benchmarks use them to compare structures.
//!
//! Triangles are tested with the watertight `f32` kernel of
//! [`crate::accel::tri4`]: a ray through a shared edge or vertex of a closed mesh
//! always hits one of the triangles around it. The ray is tested as given (not
//! normalized first), so that rays exactly through vertices stay exact.

use super::{BatchRay, BatchTarget, Float, RayHit};
use crate::accel::{MeshBvh, MeshBvhStats, PACKET};
use crate::math::Vec3;
use crate::Error;

/// A triangle mesh prepared for batch ray casting.
#[derive(Clone, Debug)]
pub struct MeshAccel {
    bvh: MeshBvh,
    triangles: usize,
}

/// Memory of a built [`MeshAccel`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccelMemory {
    /// Triangles in the mesh.
    pub triangles: usize,
    /// Node and packet counts and bytes of the structure.
    pub bvh: MeshBvhStats,
    /// `bvh.bytes / triangles` (the structure holds its own copy of the vertices,
    /// so it needs nothing else to cast rays).
    pub bytes_per_triangle: f64,
}

impl MeshAccel {
    /// Builds the structure over the triangles `indices[i]` of `positions`.
    /// Triangle `i` keeps index `i` in the answers. Positions must be finite,
    /// indices in range and fewer than 2^28 triangles ([`Error::InvalidParameter`]
    /// otherwise); degenerate triangles are kept and never hit. Uses the current
    /// rayon pool (wrap in `ThreadPool::install` to choose the thread count).
    pub fn new(positions: &[[f32; 3]], indices: &[[u32; 3]]) -> Result<MeshAccel, Error> {
        if let Some(i) = positions.iter().position(|p| !p.iter().all(|v| v.is_finite())) {
            return Err(Error::invalid("positions", format!("vertex {i} is not finite: {:?}", positions[i])));
        }
        if let Some(i) = indices.iter().position(|t| t.iter().any(|&v| v as usize >= positions.len())) {
            return Err(Error::invalid("indices", format!("triangle {i} {:?} refers past the {} vertices", indices[i], positions.len())));
        }
        if indices.len() >= 1 << 28 {
            return Err(Error::invalid("indices", format!("{} triangles; at most 2^28 are supported", indices.len())));
        }
        Ok(MeshAccel { bvh: MeshBvh::build(positions, indices), triangles: indices.len() })
    }

    /// Like [`MeshAccel::new`] from `f64` positions (rounded to `f32`, which must
    /// stay finite).
    pub fn from_f64(positions: &[[f64; 3]], indices: &[[u32; 3]]) -> Result<MeshAccel, Error> {
        let p32: Vec<[f32; 3]> = positions.iter().map(|p| p.map(|v| v as f32)).collect();
        MeshAccel::new(&p32, indices)
    }

    /// Triangle count.
    pub fn triangles(&self) -> usize {
        self.triangles
    }

    /// Bytes of the built structure, in all and per triangle.
    pub fn memory(&self) -> AccelMemory {
        let bvh = self.bvh.stats();
        AccelMemory { triangles: self.triangles, bvh, bytes_per_triangle: bvh.bytes as f64 / self.triangles.max(1) as f64 }
    }

    /// Whether the rays `ray(0..n)` mostly travel together: of up to
    /// [`COHERENCE_PAIRS`] neighbouring pairs spread over them, more than half have
    /// directions within about 8 degrees (cosine above 0.99) and origins within 1 %
    /// of the mesh's size (camera rays in pixel order, shadow rays towards one
    /// light). Such rays enter the same nodes, so walking them as packets shares
    /// each node's test, and even one at a time they find their nodes in cache;
    /// interleaving ([`MeshBvh::closest_batch`]) is faster for rays that scatter,
    /// whose walks wait on memory (`BENCHMARKS.md`, issue 24). Either way gives
    /// the same distances, so the guess costs speed at worst, never a result.
    fn coherent(&self, n: usize, ray: impl Fn(usize) -> Option<(Vec3, Vec3)>) -> bool {
        if n < 2 {
            return true;
        }
        let near = f64::from(self.bvh.diagonal()) * 0.01;
        let pairs = COHERENCE_PAIRS.min(n - 1);
        let together = (0..pairs)
            .filter(|k| {
                let i = k * (n - 1) / pairs;
                let (Some((oa, da)), Some((ob, db))) = (ray(i), ray(i + 1)) else { return false };
                let cos = da.dot(db);
                // cos > 0.99 |da| |db|, squared to spare the roots.
                cos > 0.0 && cos * cos > 0.9801 * da.length_squared() * db.length_squared() && oa.distance_squared(ob) <= near * near
            })
            .count();
        2 * together > pairs
    }

    /// Nearest hit of one ray `origin + s dir`: `(s, triangle)` with the
    /// parameter `s` in `(0, s_max)`, measured along `dir` as given (not a
    /// distance unless `dir` is unit). A zero or non-finite ray hits nothing.
    #[inline]
    pub fn nearest_param(&self, origin: [f32; 3], dir: [f32; 3], s_max: f32) -> Option<(f32, u32)> {
        self.bvh.closest(origin, dir, s_max)
    }

    /// Whether one ray `origin + s dir` hits anything with `s` in `(0, s_max)`.
    #[inline]
    pub fn occluded_param(&self, origin: [f32; 3], dir: [f32; 3], s_max: f32) -> bool {
        self.bvh.occluded(origin, dir, s_max)
    }
}

impl BatchTarget for MeshAccel {
    const NORMALS: bool = false;
    const PACKETS: bool = true;

    /// `t = s |d|` computed in `f64` from the kernel's `f32` parameter `s`.
    #[inline]
    fn nearest<T: Float>(&self, ray: &BatchRay<T>) -> Option<RayHit> {
        let (s, triangle) = self.bvh.closest(ray.origin.map(T::to_f32), ray.dir.map(T::to_f32), f32::INFINITY)?;
        Some(RayHit { t: f64::from(s) * ray.length(), object: 0, primitive: Some(triangle), normal: None, shape_error: 0.0 })
    }

    /// Asks the kernel for `s < t_max / |d|` (rounded to `f32`).
    #[inline]
    fn occluded<T: Float>(&self, ray: &BatchRay<T>, t_max: f64) -> bool {
        self.bvh.occluded(ray.origin.map(T::to_f32), ray.dir.map(T::to_f32), occlusion_limit(ray, t_max))
    }

    /// Coherent rays (camera rays in pixel order, see `MeshAccel::coherent`) eight to a packet
    /// ([`MeshBvh::closest_packet`]), others interleaved ([`MeshBvh::closest_batch`]):
    /// the distances of [`MeshAccel::nearest`] one by one, bit for bit, and its
    /// triangles but for two hit at the very same distance (a ray through a shared
    /// edge), where a packet may report the other one.
    fn nearest_all<T: Float>(&self, n: usize, ray: impl Fn(usize) -> Option<BatchRay<T>>, mut answer: impl FnMut(usize, Option<RayHit>)) {
        let hit = |ray: &BatchRay<T>, (s, triangle): (f32, u32)| RayHit {
            t: f64::from(s) * ray.length(),
            object: 0,
            primitive: Some(triangle),
            normal: None,
            shape_error: 0.0,
        };
        if self.coherent(n, |i| ray(i).map(|r| vectors(&r))) {
            // Eight neighbours at a time, walked together ([`MeshBvh::closest_packet`]).
            // Plain loops into plain arrays: building the packet with
            // `array::from_fn` and `map` over `Option<BatchRay>`s left a copying
            // call out of line (issue 24: a fifth of a camera ray's instructions
            // on Igea-1M were this wrapper's). A lane without a usable ray gets
            // `UNUSABLE`, which the packet answers as a miss.
            for start in (0..n).step_by(PACKET) {
                let lanes = PACKET.min(n - start);
                let mut packet = [UNUSABLE; PACKET];
                let mut usable = [None; PACKET];
                for k in 0..lanes {
                    if let Some(r) = ray(start + k) {
                        packet[k] = (r.origin.map(T::to_f32), r.dir.map(T::to_f32), f32::INFINITY);
                        usable[k] = Some(r);
                    }
                }
                let answers = self.bvh.closest_packet(&packet);
                for k in 0..lanes {
                    answer(start + k, usable[k].as_ref().zip(answers[k]).map(|(ray, found)| hit(ray, found)));
                }
            }
            return;
        }
        self.bvh.closest_batch(
            n,
            |i| ray(i).map_or(UNUSABLE, |r| (r.origin.map(T::to_f32), r.dir.map(T::to_f32), f32::INFINITY)),
            |i, found| answer(i, found.and_then(|found| Some(hit(&ray(i)?, found)))),
        );
    }

    /// The rays interleaved ([`MeshBvh::occluded_batch`]) unless they are
    /// coherent, answers as [`MeshAccel::occluded`]'s.
    fn occluded_all<T: Float>(&self, n: usize, ray: impl Fn(usize) -> Option<(BatchRay<T>, f64)>, mut answer: impl FnMut(usize, bool)) {
        if self.coherent(n, |i| ray(i).map(|(r, _)| vectors(&r))) {
            for i in 0..n {
                answer(i, ray(i).is_some_and(|(ray, t_max)| self.occluded(&ray, t_max)));
            }
            return;
        }
        self.bvh.occluded_batch(
            n,
            |i| ray(i).map_or(UNUSABLE, |(r, t_max)| (r.origin.map(T::to_f32), r.dir.map(T::to_f32), occlusion_limit(&r, t_max))),
            answer,
        );
    }
}

/// Neighbouring ray pairs [`MeshAccel::coherent`] looks at: enough to tell camera
/// rays from scattered ones, few enough to cost nothing next to 1024 walks.
const COHERENCE_PAIRS: usize = 32;

/// What the kernels are given for a ray that [`BatchRay::new`] refused: a zero
/// direction, which [`crate::accel::MeshBvh`] answers as a miss without a walk.
const UNUSABLE: ([f32; 3], [f32; 3], f32) = ([0.0; 3], [0.0; 3], f32::INFINITY);

/// A ray's origin and direction in `f64`.
#[inline]
fn vectors<T: Float>(ray: &BatchRay<T>) -> (Vec3, Vec3) {
    (Vec3::from_array(ray.origin.map(T::to_f64)), Vec3::from_array(ray.dir.map(T::to_f64)))
}

/// The kernel's parameter limit for a distance limit `t_max`: `t_max / |d|`, rounded to `f32`.
#[inline]
fn occlusion_limit<T: Float>(ray: &BatchRay<T>, t_max: f64) -> f32 {
    (t_max / ray.length()) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tri4::{intersect_one, ShearRay};
    use crate::batch::{self, Hits, RaySlices};
    use crate::math::Vec3;
    use crate::ray::Ray;
    use crate::sampling::Rng;
    use crate::shapes::{intersect_triangle, WatertightRay};

    /// A closed sphere: an octahedron subdivided `levels` times, vertices shared
    /// (edge midpoints looked up), projected onto the sphere of radius 2 about `c`.
    fn sphere(levels: usize, c: [f32; 3]) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let mut v: Vec<[f64; 3]> =
            vec![[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
        let mut f: Vec<[u32; 3]> = vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
        for _ in 0..levels {
            let mut mid = std::collections::HashMap::new();
            let mut next = Vec::new();
            for t in &f {
                let mut m = [0u32; 3];
                for e in 0..3 {
                    let (a, b) = (t[e].min(t[(e + 1) % 3]), t[e].max(t[(e + 1) % 3]));
                    m[e] = *mid.entry((a, b)).or_insert_with(|| {
                        let (p, q) = (v[a as usize], v[b as usize]);
                        v.push([(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, (p[2] + q[2]) / 2.0]);
                        v.len() as u32 - 1
                    });
                }
                next.extend([[t[0], m[0], m[2]], [m[0], t[1], m[1]], [m[2], m[1], t[2]], [m[0], m[1], m[2]]]);
            }
            f = next;
        }
        let v = v
            .iter()
            .map(|p| Vec3::from_array(*p).normalize() * 2.0)
            .map(|p| [p.x as f32 + c[0], p.y as f32 + c[1], p.z as f32 + c[2]])
            .collect();
        (v, f)
    }

    /// Every ray against every triangle with the scalar kernel.
    fn brute(v: &[[f32; 3]], f: &[[u32; 3]], o: [f32; 3], d: [f32; 3]) -> Option<(f32, u32)> {
        let ray = ShearRay::new(o, d)?;
        let mut best: Option<(f32, u32)> = None;
        for (i, t) in f.iter().enumerate() {
            if let Some(hit) = intersect_one(&ray, t.map(|k| v[k as usize]), best.map_or(f32::INFINITY, |b| b.0)) {
                best = Some((hit, i as u32));
            }
        }
        best
    }

    /// The `f64` kernel's nearest distance, for the precision check.
    fn brute_f64(v: &[[f32; 3]], f: &[[u32; 3]], o: [f32; 3], d: [f32; 3]) -> f64 {
        let to = |p: [f32; 3]| Vec3::new(p[0].into(), p[1].into(), p[2].into());
        let ray = WatertightRay::new(&Ray::unit(to(o), to(d)));
        f.iter()
            .filter_map(|t| intersect_triangle(&ray, to(v[t[0] as usize]), to(v[t[1] as usize]), to(v[t[2] as usize]), 0.0, f64::INFINITY))
            .map(|h| h.t)
            .fold(f64::INFINITY, f64::min)
    }

    /// `|d|` in `f64`, the batch API's factor from parameter to distance.
    fn length(d: [f32; 3]) -> f64 {
        Vec3::new(d[0].into(), d[1].into(), d[2].into()).length()
    }

    /// Casts through the batch API: distances, objects, triangles.
    fn cast(accel: &MeshAccel, origins: &[[f32; 3]], dirs: &[[f32; 3]], threads: usize) -> (Vec<f32>, Vec<i64>, Vec<i64>) {
        let n = origins.len();
        let (mut t, mut object, mut prim) = (vec![0.0; n], vec![0; n], vec![0; n]);
        let out = Hits { t: &mut t, object: Some(&mut object), primitive: Some(&mut prim), normal: None, error: None };
        batch::cast(accel, &RaySlices::new(origins, dirs).unwrap(), out, threads).unwrap();
        (t, object, prim)
    }

    fn check_batch(v: &[[f32; 3]], f: &[[u32; 3]], origins: &[[f32; 3]], dirs: &[[f32; 3]], all_hit: bool) {
        let accel = MeshAccel::new(v, f).unwrap();
        let (t, object, prim) = cast(&accel, origins, dirs, 2);
        let mut occluded = vec![false; origins.len()];
        batch::occluded(&accel, &RaySlices::new(origins, dirs).unwrap(), None, &mut occluded, 1).unwrap();
        for i in 0..origins.len() {
            let want = brute(v, f, origins[i], dirs[i]);
            assert_eq!(want.is_some(), t[i].is_finite(), "ray {i}: hit/miss differs from brute force");
            assert_eq!(occluded[i], want.is_some(), "ray {i}: any-hit differs");
            if all_hit {
                assert!(want.is_some(), "ray {i} {:?} {:?} leaked through the closed mesh", origins[i], dirs[i]);
            }
            let Some((bs, _)) = want else {
                assert_eq!((object[i], prim[i]), (-1, -1));
                continue;
            };
            assert_eq!(object[i], 0, "ray {i}: the mesh is object 0");
            // The batch answer is the kernel's parameter times |d|, rounded once. Its
            // triangle may differ from the single-ray walk's where two are hit at the
            // same parameter (rays through vertices; packets test in another order):
            // the reported one must give that parameter, checked below.
            let (s, _) = accel.nearest_param(origins[i], dirs[i], f32::INFINITY).unwrap();
            assert_eq!(t[i], (f64::from(s) * length(dirs[i])) as f32, "ray {i}");
            assert!((s - bs).abs() <= 1e-5 * bs, "ray {i}: s {s} vs brute force {bs}");
            let tri = f[prim[i] as usize].map(|k| v[k as usize]);
            let own = intersect_one(&ShearRay::new(origins[i], dirs[i]).unwrap(), tri, f32::INFINITY);
            assert_eq!(own, Some(s), "ray {i}: the reported triangle gives the reported parameter");
            let exact = brute_f64(v, f, origins[i], dirs[i]);
            assert!((f64::from(s) - exact).abs() <= 1e-5 * exact, "ray {i}: s {s} vs f64 {exact}");
        }
    }

    #[test]
    fn closed_sphere_from_inside_through_vertices_edges_and_at_random() {
        let c = [0.25, -0.5, 1.0];
        let (v, f) = sphere(4, c);
        let mut dirs: Vec<[f32; 3]> = Vec::new();
        // Through every vertex and every edge midpoint (f32-exact when the edge is axis-symmetric).
        for p in &v {
            dirs.push([p[0] - c[0], p[1] - c[1], p[2] - c[2]]);
        }
        for t in &f {
            for e in 0..3 {
                let (p, q) = (v[t[e] as usize], v[t[(e + 1) % 3] as usize]);
                dirs.push(std::array::from_fn(|k| (p[k] + q[k]) / 2.0 - c[k]));
            }
        }
        let mut rng = Rng::for_sample(11, 0, 0);
        for _ in 0..2000 {
            let s = 0.1 + 3.0 * rng.uniform();
            dirs.push(std::array::from_fn(|_| (rng.uniform() as f32 - 0.5) * s as f32));
        }
        // Axis directions pass exactly through the octahedron's vertices.
        dirs.extend([[1.0, 0.0, 0.0], [0.0, -3.0, 0.0], [0.0, 0.0, 0.5], [1.0, 1.0, 0.0], [0.0, 1.0, -1.0], [1.0, 1.0, 1.0]]);
        let origins = vec![c; dirs.len()];
        check_batch(&v, &f, &origins, &dirs, true);
    }

    #[test]
    fn grid_rays_exactly_through_edges_and_vertices_never_leak() {
        // A 8x8 grid in z = 0 split along diagonals; vertical rays through every
        // vertex, edge midpoint and diagonal point hit, and exactly at t = 3 / 2.
        let n = 8u32;
        let v: Vec<[f32; 3]> = (0..=n).flat_map(|y| (0..=n).map(move |x| [x as f32, y as f32, 0.0])).collect();
        let id = |x: u32, y: u32| y * (n + 1) + x;
        let f: Vec<[u32; 3]> = (0..n)
            .flat_map(|y| {
                (0..n).flat_map(move |x| [[id(x, y), id(x + 1, y), id(x + 1, y + 1)], [id(x, y), id(x + 1, y + 1), id(x, y + 1)]])
            })
            .collect();
        let mut origins = Vec::new();
        for y in 0..=2 * n {
            for x in 0..=2 * n {
                origins.push([x as f32 / 2.0, y as f32 / 2.0, 3.0]);
            }
        }
        let dirs = vec![[0.0, 0.0, -2.0]; origins.len()];
        check_batch(&v, &f, &origins, &dirs, true);
        let accel = MeshAccel::new(&v, &f).unwrap();
        assert!(origins.iter().all(|o| accel.nearest_param(*o, [0.0, 0.0, -2.0], f32::INFINITY).map(|h| h.0) == Some(1.5)));
    }

    #[test]
    fn random_rays_outside_and_inside_match_brute_force() {
        let (mut v, mut f) = sphere(3, [0.0; 3]);
        let (v2, f2) = sphere(2, [3.0, 1.0, 0.5]);
        let base = v.len() as u32;
        v.extend(v2);
        f.extend(f2.iter().map(|t| t.map(|k| k + base)));
        let mut rng = Rng::for_sample(5, 0, 0);
        let mut r = |s: f64| (rng.uniform() * 2.0 - 1.0) as f32 * s as f32;
        let origins: Vec<[f32; 3]> = (0..3000).map(|_| [r(6.0), r(6.0), r(6.0)]).collect();
        let dirs: Vec<[f32; 3]> = (0..3000).map(|_| [r(2.0), r(2.0), r(2.0)]).collect();
        check_batch(&v, &f, &origins, &dirs, false);
        // The answers do not depend on the thread count.
        let accel = MeshAccel::new(&v, &f).unwrap();
        let one = cast(&accel, &origins, &dirs, 1);
        assert_eq!(one, cast(&accel, &origins, &dirs, 3));
        assert_eq!(one, cast(&accel, &origins, &dirs, 0));
        let mem = accel.memory();
        assert_eq!(mem.triangles, f.len());
        assert!(mem.bytes_per_triangle > 36.0 && mem.bytes_per_triangle < 100.0, "{mem:?}");
    }

    #[test]
    fn camera_rays_go_as_packets_scattered_rays_interleaved_with_the_same_answers() {
        let (v, f) = sphere(3, [0.0; 3]);
        let accel = MeshAccel::new(&v, &f).unwrap();
        // A 40x42 camera looking at the sphere, rays in pixel order: `cast` hands
        // them over in 2x4 tiles, the last band of rows two rows high.
        let camera: Vec<[f32; 3]> = (0..1680).map(|i| [(i % 40) as f32 / 20.0 - 1.0, (i / 40) as f32 / 20.0 - 1.0, 4.0]).collect();
        let eye = vec![[0.0f32, 0.0, -5.0]; camera.len()];
        assert_eq!(super::super::tiles::row_width(&RaySlices::new(&eye, &camera).unwrap()), Some(40), "camera rays go in tiles");
        let mut rng = Rng::for_sample(9, 0, 0);
        let mut r = |s: f64| (rng.uniform() * 2.0 - 1.0) as f32 * s as f32;
        let origins: Vec<[f32; 3]> = (0..1600).map(|_| [r(3.0), r(3.0), r(3.0)]).collect();
        let mut dirs: Vec<[f32; 3]> = (0..1600).map(|_| [r(1.0), r(1.0), r(1.0)]).collect();
        dirs[17] = [0.0; 3];
        dirs[901] = [f32::INFINITY, 0.0, 0.0];
        let vectors_of = |o: &[[f32; 3]], d: &[[f32; 3]]| {
            let (o, d) = (o.to_vec(), d.to_vec());
            move |i: usize| BatchRay::new(o[i], d[i]).map(|r| vectors(&r))
        };
        assert!(accel.coherent(camera.len(), vectors_of(&eye, &camera)), "camera rays are coherent");
        assert!(!accel.coherent(dirs.len(), vectors_of(&origins, &dirs)), "scattered rays are not");
        let mut ties = 0;
        for (o, d) in [(&eye, &camera), (&origins, &dirs)] {
            let (t, _, prim) = cast(&accel, o, d, 2);
            let limits: Vec<f64> = (0..o.len()).map(|i| [2.5, 4.0, f64::INFINITY][i % 3]).collect();
            let mut hit = vec![false; o.len()];
            batch::occluded(&accel, &RaySlices::new(o, d).unwrap(), Some(&limits), &mut hit, 2).unwrap();
            for i in 0..o.len() {
                let ray = BatchRay::new(o[i], d[i]);
                let one = ray.and_then(|ray| accel.nearest(&ray));
                assert_eq!(t[i].to_bits(), one.map_or(f32::INFINITY, |h| h.t as f32).to_bits(), "ray {i}");
                let own = one.and_then(|h| h.primitive).map_or(-1, i64::from);
                if prim[i] != own {
                    // A tie (a camera ray through a shared edge): the triangle reported
                    // is hit at the very same distance.
                    let tri = f[prim[i] as usize].map(|k| v[k as usize]);
                    let s = intersect_one(&ShearRay::new(o[i], d[i]).unwrap(), tri, f32::INFINITY).expect("the other triangle is hit");
                    assert_eq!((f64::from(s) * length(d[i])) as f32, t[i], "ray {i}: a tie at one distance");
                    ties += 1;
                }
                assert_eq!(hit[i], ray.is_some_and(|ray| accel.occluded(&ray, limits[i])), "ray {i}");
            }
            assert!(hit.iter().any(|&h| h) && hit.iter().any(|&h| !h));
        }
        assert!(ties < 40, "{ties} ties");
        // The tiles depend on the rays alone: the same bytes, ties included, on any thread count.
        let two = cast(&accel, &eye, &camera, 2);
        for threads in [1, 3] {
            let other = cast(&accel, &eye, &camera, threads);
            assert_eq!(two.0.iter().map(|t| t.to_bits()).collect::<Vec<_>>(), other.0.iter().map(|t| t.to_bits()).collect::<Vec<_>>());
            assert_eq!(two.2, other.2, "{threads} threads");
        }
    }

    #[test]
    fn occlusion_respects_t_max_and_bad_input_is_rejected() {
        let (v, f) = sphere(1, [0.0; 3]);
        let accel = MeshAccel::new(&v, &f).unwrap();
        let mut hit = [false; 2];
        // The sphere of radius 2 is 3 away; t_max is a distance, so a direction
        // of length 2 changes nothing.
        let rays = RaySlices::new(&[[0.0, 0.0, -5.0]; 2], &[[0.0, 0.0, 2.0]; 2]).unwrap();
        batch::occluded(&accel, &rays, Some(&[2.5, 3.5]), &mut hit, 1).unwrap();
        assert_eq!(hit, [false, true]);
        assert!(accel.nearest_param([0.0; 3], [0.0; 3], f32::INFINITY).is_none(), "a zero direction hits nothing");
        let mut t = [0.0; 1];
        let two = RaySlices::new(&[[0.0f32; 3]; 2], &[[1.0, 0.0, 0.0]; 2]).unwrap();
        let err = batch::cast(&accel, &two, Hits { t: &mut t, object: None, primitive: None, normal: None, error: None }, 1).unwrap_err();
        assert_eq!(err.to_string(), "invalid t: 1 outputs for 2 rays: lengths must agree");
        let mut normal = [[0.0f32; 3]; 2];
        let mut t = [0.0; 2];
        let err = batch::cast(&accel, &two, Hits { t: &mut t, object: None, primitive: None, normal: Some(&mut normal), error: None }, 1)
            .unwrap_err();
        assert_eq!(err.to_string(), "invalid normal: this target does not report normals");
        assert!(MeshAccel::new(&[[0.0, 0.0, f32::NAN]], &[]).is_err());
        assert!(MeshAccel::new(&v, &[[0, 1, v.len() as u32]]).is_err());
        let empty = MeshAccel::new(&[], &[]).unwrap();
        assert!(empty.nearest_param([0.0; 3], [1.0, 0.0, 0.0], f32::INFINITY).is_none());
        assert!(!empty.occluded_param([0.0; 3], [1.0, 0.0, 0.0], f32::INFINITY));
    }
}
