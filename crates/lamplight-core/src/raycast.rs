//! Batch ray casting against one triangle mesh: the Embree-style entry point.
//!
//! [`MeshAccel`] builds the `f32` ray-casting BVH ([`crate::accel::MeshBvh`]) over
//! a mesh given as positions and triangle indices, and answers batches of rays
//! `origin + t dir` (the direction need not be unit; `t` is measured along it):
//! [`MeshAccel::cast`] finds the nearest hit `t` in `(0, inf)` and the index of the
//! triangle hit, [`MeshAccel::occluded`] only whether there is one (shadow rays).
//! A batch is split into chunks run on a rayon pool of the requested size; every
//! ray is independent, so the answers do not depend on the thread count.
//!
//! Triangles are tested with the watertight `f32` kernel of
//! [`crate::accel::tri4`]: a ray through a shared edge or vertex of a closed mesh
//! always hits one of the triangles around it. A ray with a zero or non-finite
//! direction, or a non-finite origin, hits nothing.

use rayon::prelude::*;

use crate::accel::{MeshBvh, MeshBvhStats};
use crate::Error;

/// Rays per work item: large enough to amortise scheduling, small enough to balance.
const CHUNK: usize = 1024;

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
    /// Triangle `i` keeps index `i` in the answers. Positions must be finite and
    /// indices in range ([`Error::InvalidParameter`] otherwise); degenerate
    /// triangles are kept and never hit. Uses the current rayon pool (wrap in
    /// `ThreadPool::install` to choose the thread count).
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

    /// Nearest hit of one ray: `(t, triangle)` with `t` in `(0, t_max)`.
    #[inline]
    pub fn cast_one(&self, origin: [f32; 3], dir: [f32; 3], t_max: f32) -> Option<(f32, u32)> {
        self.bvh.closest(origin, dir, t_max)
    }

    /// Whether one ray hits anything with `t` in `(0, t_max)`.
    #[inline]
    pub fn occluded_one(&self, origin: [f32; 3], dir: [f32; 3], t_max: f32) -> bool {
        self.bvh.occluded(origin, dir, t_max)
    }

    /// Casts the rays `origins[i] + t directions[i]`: writes the nearest hit
    /// distance `t` (in units of the direction; `+inf` for a miss) to `t_out[i]`
    /// and, if given, the triangle index (`-1` for a miss) to `prim_out[i]`.
    /// `threads` is the worker count (0: rayon's default). All slices must have
    /// the same length.
    pub fn cast(
        &self,
        origins: &[[f32; 3]],
        directions: &[[f32; 3]],
        t_out: &mut [f32],
        prim_out: Option<&mut [i64]>,
        threads: usize,
    ) -> Result<(), Error> {
        check_lengths(origins, directions, t_out.len(), prim_out.as_ref().map(|p| p.len()))?;
        run(threads, || match prim_out {
            Some(prim) => {
                origins
                    .par_chunks(CHUNK)
                    .zip(directions.par_chunks(CHUNK))
                    .zip(t_out.par_chunks_mut(CHUNK))
                    .zip(prim.par_chunks_mut(CHUNK))
                    .for_each(|(((o, d), t), p)| {
                        for i in 0..o.len() {
                            (t[i], p[i]) = match self.bvh.closest(o[i], d[i], f32::INFINITY) {
                                Some((hit, tri)) => (hit, i64::from(tri)),
                                None => (f32::INFINITY, -1),
                            };
                        }
                    });
            }
            None => {
                origins.par_chunks(CHUNK).zip(directions.par_chunks(CHUNK)).zip(t_out.par_chunks_mut(CHUNK)).for_each(|((o, d), t)| {
                    for i in 0..o.len() {
                        t[i] = self.bvh.closest(o[i], d[i], f32::INFINITY).map_or(f32::INFINITY, |h| h.0);
                    }
                });
            }
        })
    }

    /// The any-hit query for a batch: `hit_out[i]` is true when ray `i` hits a
    /// triangle with `t` in `(0, t_max[i])` (`t_max` of `inf` for unbounded rays).
    pub fn occluded(
        &self,
        origins: &[[f32; 3]],
        directions: &[[f32; 3]],
        t_max: &[f32],
        hit_out: &mut [bool],
        threads: usize,
    ) -> Result<(), Error> {
        check_lengths(origins, directions, t_max.len(), Some(hit_out.len()))?;
        run(threads, || {
            origins
                .par_chunks(CHUNK)
                .zip(directions.par_chunks(CHUNK))
                .zip(t_max.par_chunks(CHUNK))
                .zip(hit_out.par_chunks_mut(CHUNK))
                .for_each(|(((o, d), tm), h)| {
                    for i in 0..o.len() {
                        h[i] = self.bvh.occluded(o[i], d[i], tm[i]);
                    }
                });
        })
    }
}

fn check_lengths(origins: &[[f32; 3]], directions: &[[f32; 3]], out: usize, second: Option<usize>) -> Result<(), Error> {
    let n = origins.len();
    if directions.len() != n || out != n || second.is_some_and(|m| m != n) {
        return Err(Error::invalid(
            "rays",
            format!("{n} origins, {} directions, {out} and {second:?} outputs: lengths must agree", directions.len()),
        ));
    }
    Ok(())
}

/// Runs `work` on a pool of `threads` workers (0: the current/global pool).
fn run(threads: usize, work: impl FnOnce() + Send) -> Result<(), Error> {
    if threads == 0 {
        work();
        return Ok(());
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| Error::Render(format!("thread pool: {e}")))?;
    pool.install(work);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tri4::{intersect_one, ShearRay};
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
        let ray = WatertightRay::new(&Ray { origin: to(o), dir: to(d) });
        f.iter()
            .filter_map(|t| intersect_triangle(&ray, to(v[t[0] as usize]), to(v[t[1] as usize]), to(v[t[2] as usize]), 0.0, f64::INFINITY))
            .map(|h| h.t)
            .fold(f64::INFINITY, f64::min)
    }

    fn check_batch(v: &[[f32; 3]], f: &[[u32; 3]], origins: &[[f32; 3]], dirs: &[[f32; 3]], all_hit: bool) {
        let accel = MeshAccel::new(v, f).unwrap();
        let mut t = vec![0.0; origins.len()];
        let mut prim = vec![0; origins.len()];
        accel.cast(origins, dirs, &mut t, Some(&mut prim), 2).unwrap();
        let mut occluded = vec![false; origins.len()];
        accel.occluded(origins, dirs, &vec![f32::INFINITY; origins.len()], &mut occluded, 1).unwrap();
        for i in 0..origins.len() {
            let want = brute(v, f, origins[i], dirs[i]);
            assert_eq!(want.is_some(), t[i].is_finite(), "ray {i}: hit/miss differs from brute force");
            assert_eq!(occluded[i], want.is_some(), "ray {i}: any-hit differs");
            if all_hit {
                assert!(want.is_some(), "ray {i} {:?} {:?} leaked through the closed mesh", origins[i], dirs[i]);
            }
            let Some((bt, _)) = want else {
                assert_eq!(prim[i], -1);
                continue;
            };
            assert!((t[i] - bt).abs() <= 1e-5 * bt, "ray {i}: t {} vs brute force {bt}", t[i]);
            let tri = f[prim[i] as usize].map(|k| v[k as usize]);
            let own = intersect_one(&ShearRay::new(origins[i], dirs[i]).unwrap(), tri, f32::INFINITY);
            assert_eq!(own, Some(t[i]), "ray {i}: the reported triangle gives the reported t");
            let exact = brute_f64(v, f, origins[i], dirs[i]);
            assert!((f64::from(t[i]) - exact).abs() <= 1e-5 * exact, "ray {i}: t {} vs f64 {exact}", t[i]);
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
        assert!(origins.iter().all(|o| accel.cast_one(*o, [0.0, 0.0, -2.0], f32::INFINITY).map(|h| h.0) == Some(1.5)));
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
        let (mut t1, mut t2) = (vec![0.0; 3000], vec![0.0; 3000]);
        accel.cast(&origins, &dirs, &mut t1, None, 1).unwrap();
        accel.cast(&origins, &dirs, &mut t2, None, 3).unwrap();
        assert_eq!(t1, t2);
        let mem = accel.memory();
        assert_eq!(mem.triangles, f.len());
        assert!(mem.bytes_per_triangle > 36.0 && mem.bytes_per_triangle < 100.0, "{mem:?}");
    }

    #[test]
    fn occlusion_respects_t_max_and_bad_input_is_rejected() {
        let (v, f) = sphere(1, [0.0; 3]);
        let accel = MeshAccel::new(&v, &f).unwrap();
        let mut hit = [false; 2];
        accel.occluded(&[[0.0, 0.0, -5.0]; 2], &[[0.0, 0.0, 1.0]; 2], &[2.5, 3.5], &mut hit, 1).unwrap();
        assert_eq!(hit, [false, true]);
        assert!(accel.cast_one([0.0; 3], [0.0; 3], f32::INFINITY).is_none(), "a zero direction hits nothing");
        let mut t = [0.0; 1];
        assert!(accel.cast(&[[0.0; 3]; 2], &[[1.0, 0.0, 0.0]; 2], &mut t, None, 1).is_err());
        assert!(MeshAccel::new(&[[0.0, 0.0, f32::NAN]], &[]).is_err());
        assert!(MeshAccel::new(&v, &[[0, 1, v.len() as u32]]).is_err());
        let empty = MeshAccel::new(&[], &[]).unwrap();
        assert!(empty.cast_one([0.0; 3], [1.0, 0.0, 0.0], f32::INFINITY).is_none());
        assert!(!empty.occluded_one([0.0; 3], [1.0, 0.0, 0.0], f32::INFINITY));
    }
}
