//! Batch ray queries: the one API behind `lamplight raycast` and Python's
//! `Scene.intersect`, with one meaning for every number it returns.
//!
//! Ray `i` is `o_i + s d_i`, `s > 0`, for an origin `o_i` and a direction `d_i`
//! of any non-zero finite length. For its nearest hit, at the point `p_i`:
//!
//! - `t_i = |p_i - o_i| = s_hit |d_i|`, the **distance** from the origin to the
//!   hit, in scene units, whatever the length of `d_i`. For a unit `d_i` this is
//!   Embree's and pbrt's ray parameter `t` (within rounding, as both measure `t`
//!   along the direction as given); for a longer or shorter `d_i` it is not.
//!   `+inf` for a miss.
//! - `object_i`: the index of the object hit, objects numbered in scene order
//!   (a [`MeshAccel`] is one object, number 0); `-1` for a miss.
//! - `primitive_i`: the index of the triangle hit within that object's mesh, in
//!   the mesh's face order; `-1` for a miss and for shapes that are not triangle
//!   meshes (spheres, quadrics, boxes, single triangles...).
//! - `normal_i` (targets that have them, [`BatchTarget::NORMALS`]): the unit
//!   outward geometric normal at the hit, not turned towards the ray; zero for a
//!   miss.
//! - `error_i` (targets that have it, [`BatchTarget::ERRORS`]): a bound on
//!   `|t_i - t_exact|`, the rounding in the answered distance, including its
//!   rounding to the output type; `+inf` for a miss. It is how a caller learns
//!   that precision was lost: a ray from `z = 1e17` towards a unit sphere is
//!   answered `t = 1e17` with an error bound of about 1,400, larger than the sphere.
//!
//! A ray with a zero or non-finite direction, or a non-finite origin, misses.
//! Normals are always finite: far from the origin, where `f64` cannot resolve
//! the hit point, a shape computes them from the precise parts of its
//! intersection, and a hit it cannot resolve at all is a miss ([`scene`]).
//! [`occluded`] answers only whether a ray hits anything at a distance in
//! `(0, t_max)` (shadow rays), in the same units.
//!
//! Rays are split into chunks of [`CHUNK`] rays run on a rayon pool (camera
//! rays for a packet-walking target: bands of rows, read in pixel tiles, see
//! `batch/tiles.rs`); every ray is answered on its own from the same inputs, so the
//! answers do not depend on the thread count or the chunking, bit for bit.
//!
//! Two targets implement [`BatchTarget`]: a built [`crate::Scene`] (`f64`
//! geometry, [`scene`]) and [`MeshAccel`] (one triangle mesh in `f32`, the
//! Embree-style structure of [`mesh`]; `f64` rays are rounded to `f32` for it).

use rayon::prelude::*;

use crate::math::Vec3;
use crate::Error;

pub mod mesh;
pub mod scene;
mod tiles;

pub use mesh::{AccelMemory, MeshAccel};

/// Rays per work item: large enough to amortise scheduling, small enough to balance.
pub const CHUNK: usize = 1024;

/// Most worker threads a batch may ask for: far above any machine's cores; more
/// would only cost memory and scheduling, and huge counts make the pool fail.
pub const MAX_THREADS: usize = 1024;

/// One ray as a target sees it: `origin + s dir` in the caller's float type `T`,
/// with `|dir|^2` finite and positive and a finite origin (rays that are not are
/// answered as misses before a target is asked). Kept in `T` so that an `f32`
/// target given `f32` rays converts nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatchRay<T> {
    /// Start point `o`.
    pub origin: [T; 3],
    /// Direction `d` as given (not normalized).
    pub dir: [T; 3],
}

impl<T: Float> BatchRay<T> {
    /// The ray `origin + s dir`, or `None` when it misses everything by definition
    /// (non-finite origin, zero or non-finite direction or length).
    #[inline]
    pub fn new(origin: [T; 3], dir: [T; 3]) -> Option<BatchRay<T>> {
        T::usable_ray(origin, dir).then_some(BatchRay { origin, dir })
    }

    /// `|d|`, the factor from the parameter `s` to the distance `t = s |d|`
    /// (bit for bit glam's `DVec3::length` of the `f64` direction). Computed
    /// when asked, not when the ray is made: most rays of a batch never need it
    /// (issue 24: a tenth of a camera ray's instructions went to making rays).
    #[inline]
    pub fn length(&self) -> f64 {
        let d = Vec3::from_array(self.dir.map(T::to_f64));
        d.dot(d).sqrt()
    }
}

/// The nearest hit of one ray, in the units of the module documentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Distance from the origin to the hit, `s |d|`.
    pub t: f64,
    /// Index of the object hit.
    pub object: usize,
    /// Index of the triangle hit in the object's mesh; `None` for other shapes.
    pub primitive: Option<u32>,
    /// Unit outward geometric normal; `None` when the target has none.
    pub normal: Option<[f64; 3]>,
    /// The shape's own absolute error bound of the hit point, for shapes whose
    /// root finding is iterative (0 for closed-form ones and for targets
    /// without [`BatchTarget::ERRORS`]).
    pub shape_error: f64,
}

/// Something a batch of rays can be cast against.
pub trait BatchTarget: Sync {
    /// Whether [`BatchTarget::nearest`] reports normals.
    const NORMALS: bool;

    /// Whether [`BatchTarget::t_error`] bounds the error of `t`.
    const ERRORS: bool = false;

    /// Whether [`BatchTarget::nearest_all`] walks neighbouring rays together,
    /// so that [`cast`] should hand it camera rays in pixel tiles (`batch/tiles.rs`).
    const PACKETS: bool = false;

    /// A bound on `|hit.t - t_exact|` in the target's own arithmetic (only asked
    /// when [`BatchTarget::ERRORS`]); the rounding to the output type is added
    /// by [`cast`].
    fn t_error<T: Float>(&self, _ray: &BatchRay<T>, _hit: &RayHit) -> f64 {
        f64::INFINITY
    }

    /// The nearest hit of `ray` with `s > 0`, or `None`.
    fn nearest<T: Float>(&self, ray: &BatchRay<T>) -> Option<RayHit>;

    /// Whether `ray` hits anything at a distance `t` in `(0, t_max)`.
    fn occluded<T: Float>(&self, ray: &BatchRay<T>, t_max: f64) -> bool;

    /// [`BatchTarget::nearest`] of rays `0..n`, ray `i` being `ray(i)` (`None`
    /// misses): `answer(i, hit)` receives each ray's answer once, in any order.
    /// A target may overlap the rays' work (the mesh does, [`MeshAccel`]); the
    /// answers must be those of `nearest`, bit for bit.
    #[inline]
    fn nearest_all<T: Float>(&self, n: usize, ray: impl Fn(usize) -> Option<BatchRay<T>>, mut answer: impl FnMut(usize, Option<RayHit>)) {
        for i in 0..n {
            answer(i, ray(i).and_then(|ray| self.nearest(&ray)));
        }
    }

    /// [`BatchTarget::occluded`] of rays `0..n`, ray `i` being `ray(i)` with its
    /// limit (`None` rays are not occluded), with the same freedom as
    /// [`BatchTarget::nearest_all`].
    #[inline]
    fn occluded_all<T: Float>(&self, n: usize, ray: impl Fn(usize) -> Option<(BatchRay<T>, f64)>, mut answer: impl FnMut(usize, bool)) {
        for i in 0..n {
            answer(i, ray(i).is_some_and(|(ray, t_max)| self.occluded(&ray, t_max)));
        }
    }
}

/// A batch of rays, read one at a time (so that callers can keep theirs in
/// place: slices here, strided numpy arrays in the Python module).
pub trait Rays: Sync {
    /// The float type the rays are stored in.
    type Scalar: Float;

    /// Number of rays.
    fn len(&self) -> usize;

    /// Whether there are no rays.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Origin and direction of ray `i < len()`.
    fn get(&self, i: usize) -> ([Self::Scalar; 3], [Self::Scalar; 3]);
}

/// A float type rays are read in and answers written in (`f32` or `f64`);
/// conversions round to nearest.
pub trait Float: Copy + Send + Sync + std::fmt::Debug + PartialEq + 'static {
    /// The machine epsilon (the gap from 1 to the next number): a rounding to
    /// this type changes `x` by at most `EPSILON |x| / 2`.
    const EPSILON: f64;
    /// `x` rounded to this type.
    fn from_f64(x: f64) -> Self;
    /// `self` as `f64` (exact).
    fn to_f64(self) -> f64;
    /// `self` rounded to `f32` (exact for `f32`).
    fn to_f32(self) -> f32;
    /// Whether `origin + s dir` is a ray at all: a finite origin, and a
    /// direction whose `f64` length `|d|` is finite and positive.
    #[inline]
    fn usable_ray(origin: [Self; 3], dir: [Self; 3]) -> bool {
        let d = Vec3::from_array(dir.map(Self::to_f64));
        let length_sq = d.dot(d);
        // `d . d` is finite and positive exactly when `|d|` is, which also rules
        // out non-finite components (NaN or inf make the sum NaN or inf). The
        // checks are `&`, not `&&`: no branches (iterator chains here cost more
        // than a tenth of a ray's time on a small mesh).
        let o = origin.map(Self::to_f64);
        length_sq.is_finite() & (length_sq > 0.0) & o[0].is_finite() & o[1].is_finite() & o[2].is_finite()
    }
}

impl Float for f32 {
    const EPSILON: f64 = f32::EPSILON as f64;
    #[inline]
    fn from_f64(x: f64) -> f32 {
        x as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline]
    fn to_f32(self) -> f32 {
        self
    }
    /// The same answer as the `f64` test, in `f32`: a finite `f32`'s square is
    /// finite in `f64` (below 1.2e77), and a non-zero one's is positive (at
    /// least 2e-90), so `|d|` is finite and positive exactly when every
    /// component is finite and one is not zero.
    #[inline]
    fn usable_ray(origin: [f32; 3], dir: [f32; 3]) -> bool {
        let finite = origin[0].is_finite()
            & origin[1].is_finite()
            & origin[2].is_finite()
            & dir[0].is_finite()
            & dir[1].is_finite()
            & dir[2].is_finite();
        finite & ((dir[0] != 0.0) | (dir[1] != 0.0) | (dir[2] != 0.0))
    }
}

impl Float for f64 {
    const EPSILON: f64 = f64::EPSILON;
    #[inline]
    fn from_f64(x: f64) -> f64 {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn to_f32(self) -> f32 {
        self as f32
    }
}

/// Rays from two slices of `[x, y, z]` rows, `origins[i] + s directions[i]`.
#[derive(Clone, Copy, Debug)]
pub struct RaySlices<'a, T> {
    origins: &'a [[T; 3]],
    directions: &'a [[T; 3]],
}

impl<'a, T: Float> RaySlices<'a, T> {
    /// The rays; [`Error::InvalidParameter`] when the lengths differ.
    pub fn new(origins: &'a [[T; 3]], directions: &'a [[T; 3]]) -> Result<RaySlices<'a, T>, Error> {
        if origins.len() != directions.len() {
            return Err(Error::invalid("rays", format!("{} origins but {} directions", origins.len(), directions.len())));
        }
        Ok(RaySlices { origins, directions })
    }
}

impl<T: Float> Rays for RaySlices<'_, T> {
    type Scalar = T;

    fn len(&self) -> usize {
        self.origins.len()
    }

    #[inline]
    fn get(&self, i: usize) -> ([T; 3], [T; 3]) {
        (self.origins[i], self.directions[i])
    }
}

/// Where [`cast`] writes its answers: one entry per ray in each slice given.
#[derive(Debug)]
pub struct Hits<'a, T> {
    /// Distances (`+inf` for a miss).
    pub t: &'a mut [T],
    /// Object indices (`-1` for a miss).
    pub object: Option<&'a mut [i64]>,
    /// Triangle indices within the object (`-1` for a miss or a non-mesh shape).
    pub primitive: Option<&'a mut [i64]>,
    /// Unit outward normals (zero for a miss); only for targets with normals.
    pub normal: Option<&'a mut [[T; 3]]>,
    /// Bounds on the error of each `t` (`+inf` for a miss); only for targets
    /// with [`BatchTarget::ERRORS`].
    pub error: Option<&'a mut [T]>,
}

impl<'a, T> Hits<'a, T> {
    /// Only the distances; the other outputs are added by setting their fields.
    pub fn distances(t: &'a mut [T]) -> Hits<'a, T> {
        Hits { t, object: None, primitive: None, normal: None, error: None }
    }
}

/// One chunk of the outputs, with the index of its first ray.
struct Part<'a, T> {
    start: usize,
    t: &'a mut [T],
    object: Option<&'a mut [i64]>,
    primitive: Option<&'a mut [i64]>,
    normal: Option<&'a mut [[T; 3]]>,
    error: Option<&'a mut [T]>,
}

/// Casts every ray of `rays` against `target` and writes the nearest hits to
/// `out` (see the module documentation for the units). `threads` is the worker
/// count, 1 to [`MAX_THREADS`], or 0 for the current rayon pool. Fails, writing
/// nothing, when an output's length is not the ray count, when normals or errors
/// are asked of a target without them, or when the pool cannot start.
pub fn cast<B: BatchTarget, R: Rays, T: Float>(target: &B, rays: &R, out: Hits<'_, T>, threads: usize) -> Result<(), Error> {
    let n = rays.len();
    let lengths = [
        Some(out.t.len()),
        out.object.as_ref().map(|s| s.len()),
        out.primitive.as_ref().map(|s| s.len()),
        out.normal.as_ref().map(|s| s.len()),
        out.error.as_ref().map(|s| s.len()),
    ];
    for (name, len) in ["t", "object", "primitive", "normal", "error"].iter().zip(lengths) {
        if len.is_some_and(|len| len != n) {
            return Err(Error::invalid(*name, format!("{} outputs for {n} rays: lengths must agree", len.unwrap_or(0))));
        }
    }
    if out.normal.is_some() && !B::NORMALS {
        return Err(Error::invalid("normal", "this target does not report normals"));
    }
    if out.error.is_some() && !B::ERRORS {
        return Err(Error::invalid("error", "this target does not bound its errors"));
    }
    // Camera rays for a packet walker: bands of whole rows, each read in tiles.
    let grid = if B::PACKETS { tiles::row_width(rays) } else { None };
    let chunk = grid.map_or(CHUNK, |width| width * tiles::TILE_ROWS);
    let mut object = out.object.map(|s| s.chunks_mut(chunk));
    let mut primitive = out.primitive.map(|s| s.chunks_mut(chunk));
    let mut normal = out.normal.map(|s| s.chunks_mut(chunk));
    let mut error = out.error.map(|s| s.chunks_mut(chunk));
    let parts: Vec<Part<'_, T>> = out
        .t
        .chunks_mut(chunk)
        .enumerate()
        .map(|(k, t)| Part {
            start: k * chunk,
            t,
            object: object.as_mut().and_then(Iterator::next),
            primitive: primitive.as_mut().and_then(Iterator::next),
            normal: normal.as_mut().and_then(Iterator::next),
            error: error.as_mut().and_then(Iterator::next),
        })
        .collect();
    run(threads, || {
        parts.into_par_iter().for_each(|part| {
            // The `j`-th ray the target is given: the band's rays in tile order,
            // or in order. One compilation of the part's loop per order, so that
            // no ray pays for choosing it (a full band's order is a few shifts).
            match grid.map(|width| (width, part.t.len() / width)) {
                None => cast_part(target, rays, part, |j| j),
                Some((width, tiles::TILE_ROWS)) => cast_part(target, rays, part, move |j| tiles::full_band_order(j, width)),
                Some((width, rows)) => cast_part(target, rays, part, move |j| tiles::tile_order(j, width, rows)),
            }
        })
    })
}

/// Casts the rays of one part, the target's `j`-th being the part's `index(j)`-th.
#[inline(always)]
fn cast_part<B: BatchTarget, R: Rays, T: Float>(target: &B, rays: &R, mut part: Part<'_, T>, index: impl Fn(usize) -> usize + Copy) {
    let start = part.start;
    let ray = |j: usize| {
        let (o, d) = rays.get(start + index(j));
        BatchRay::new(o, d)
    };
    target.nearest_all(part.t.len(), ray, |given, hit| {
        let j = index(given);
        part.t[j] = T::from_f64(hit.map_or(f64::INFINITY, |h| h.t));
        if let Some(object) = part.object.as_deref_mut() {
            object[j] = hit.map_or(-1, |h| h.object as i64);
        }
        if let Some(primitive) = part.primitive.as_deref_mut() {
            primitive[j] = hit.and_then(|h| h.primitive).map_or(-1, i64::from);
        }
        // The constants first: `cast` refuses these outputs from targets without
        // them, and a target's answer loop then compiles without their code
        // (small enough to inline into the mesh's packet loop).
        if let Some(normal) = part.normal.as_deref_mut().filter(|_| B::NORMALS) {
            normal[j] = hit.and_then(|h| h.normal).unwrap_or([0.0; 3]).map(T::from_f64);
        }
        if let Some(error) = part.error.as_deref_mut().filter(|_| B::ERRORS) {
            // A hit comes only from a usable ray, so `ray(given)` is `Some` with it.
            error[j] = T::from_f64(match (ray(given), hit) {
                (Some(ray), Some(hit)) => answer_error::<T>(target.t_error(&ray, &hit), hit.t),
                _ => f64::INFINITY,
            });
        }
    });
}

/// `target_error` plus the rounding of `t` to `T` (half an ulp, here a whole
/// `EPSILON t` so that the bound's own rounding to `T` cannot undercut it).
fn answer_error<T: Float>(target_error: f64, t: f64) -> f64 {
    target_error + T::EPSILON * t.abs()
}

/// The any-hit query: `hit_out[i]` is true when ray `i` hits something at a
/// distance in `(0, t_max[i])` (`t_max` `None`: unbounded rays). Threads and
/// failures as in [`cast`].
pub fn occluded<B: BatchTarget, R: Rays>(
    target: &B,
    rays: &R,
    t_max: Option<&[f64]>,
    hit_out: &mut [bool],
    threads: usize,
) -> Result<(), Error> {
    let n = rays.len();
    if hit_out.len() != n || t_max.is_some_and(|t| t.len() != n) {
        return Err(Error::invalid(
            "occluded",
            format!("{n} rays, {} outputs and {:?} t_max: lengths must agree", hit_out.len(), t_max.map(<[f64]>::len)),
        ));
    }
    run(threads, || {
        hit_out.par_chunks_mut(CHUNK).enumerate().for_each(|(k, hits)| {
            let start = k * CHUNK;
            let ray = |j: usize| {
                let (o, d) = rays.get(start + j);
                BatchRay::new(o, d).map(|ray| (ray, t_max.map_or(f64::INFINITY, |t| t[start + j])))
            };
            target.occluded_all(hits.len(), ray, |j, hit| hits[j] = hit);
        })
    })
}

/// Runs `work` on a pool of `threads` workers (0: the current pool).
fn run(threads: usize, work: impl FnOnce() + Send) -> Result<(), Error> {
    if threads > MAX_THREADS {
        return Err(Error::invalid("threads", format!("{threads}: at most {MAX_THREADS} (0 uses the current pool)")));
    }
    if threads == 0 {
        work();
        return Ok(());
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| Error::Render(format!("thread pool: {e}")))?;
    pool.install(work);
    Ok(())
}

#[cfg(test)]
mod tests;
