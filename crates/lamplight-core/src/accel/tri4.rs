//! Four triangles tested against one ray at once, in `f32`: the leaf primitive of
//! the ray-casting BVH (`accel/mesh_bvh.rs`).
//!
//! The test is the watertight one of Woop, Benthin and Wald (2013), as in
//! [`crate::shapes::intersect_triangle`] but in single precision: vertices are
//! translated to the ray origin, permuted so that `z` is the direction's dominant
//! axis, and sheared so the direction becomes `(0, 0, 1)`; the 2D edge functions
//! `U = Cx By - Cy Bx`, `V = Ax Cy - Ay Cx`, `W = Bx Ay - By Ax` must share a sign,
//! and `t = (U Az + V Bz + W Cz) / (U + V + W)`. Because `Sz = 1 / d[kz]` is not
//! normalised away, `t` is the parameter along the given (not necessarily unit)
//! direction. A projected vertex depends only on the vertex and the ray, and
//! swapping an edge's vertices negates its edge function exactly, so two
//! triangles sharing an edge agree on the side the ray passes: no cracks. Where an
//! edge function rounds to zero it is recomputed in `f64`, where the product of two
//! `f32` values is exact and the difference has the right sign (the paper's
//! fallback).
//!
//! The packet is structure-of-arrays so the four tests are a few SSE instructions
//! (glam's `Vec4`). Unused lanes hold NaN vertices: every comparison with NaN is
//! false, so they never hit and never take the fallback.

use glam::{BVec4A, Vec3A, Vec4};

/// A ray prepared for the watertight test: axis permutation and shear.
#[derive(Clone, Copy, Debug)]
pub struct ShearRay {
    /// Permuted axes `[kx, ky, kz]`, `kz` the direction's largest component.
    pub k: [usize; 3],
    /// Origin components in permuted order.
    pub origin: [f32; 3],
    /// `(d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz])`.
    pub shear: [f32; 3],
}

impl ShearRay {
    /// Prepares the ray `origin + t dir`; `None` when `dir` is zero or not finite,
    /// or `origin` is not finite (such a ray hits nothing).
    #[inline(always)]
    pub fn new(origin: [f32; 3], dir: [f32; 3]) -> Option<ShearRay> {
        // Each array loaded whole, as the caller stored it (8 bytes, then 4):
        // six scalar tests were vectorized by some builds into a load of
        // components 1 and 2, which spans two of the caller's stores and cannot
        // be forwarded from them; it stalled the packet walk of camera rays by
        // 13 % (`BENCHMARKS.md`, session 20).
        if !(Vec3A::from_array(origin).is_finite() & Vec3A::from_array(dir).is_finite()) {
            return None;
        }
        // The axes are picked with arithmetic rather than branches: for scattered
        // rays which axis dominates, and its sign, are coin flips the core
        // mispredicts (5 % of the bunny's scattered casts, issue 24). Same
        // choice as the branches: the lowest axis of largest magnitude.
        let a = dir.map(f32::abs);
        let x_first = (a[0] >= a[1]) & (a[0] >= a[2]);
        let kz = usize::from(!x_first) * (1 + usize::from(a[1] < a[2]));
        if dir[kz] == 0.0 {
            return None;
        }
        // (kx, ky) cycle on from kz, swapped for a negative direction so that
        // the sheared frame keeps its handedness.
        const AXES: [[usize; 2]; 6] = [[1, 2], [2, 1], [2, 0], [0, 2], [0, 1], [1, 0]];
        let [kx, ky] = AXES[2 * kz + usize::from(dir[kz] < 0.0)];
        let shear = [dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]];
        Some(ShearRay { k: [kx, ky, kz], origin: [origin[kx], origin[ky], origin[kz]], shear })
    }
}

/// Edge function `a b - c d` of one lane, recomputed in `f64` (products exact).
#[cold]
pub(super) fn edge_exact(a: f32, b: f32, c: f32, d: f32) -> f32 {
    (f64::from(a) * f64::from(b) - f64::from(c) * f64::from(d)) as f32
}

/// The scalar test of one triangle, with the same operations in the same order
/// as the packet test (so the answers are bit-identical): the parameter of the
/// hit in `(0, t_max)`, if any. The brute-force reference of the tests.
pub fn intersect_one(ray: &ShearRay, tri: [[f32; 3]; 3], t_max: f32) -> Option<f32> {
    let [kx, ky, kz] = ray.k;
    let [sx, sy, sz] = ray.shear;
    let [ox, oy, oz] = ray.origin;
    let project = |p: [f32; 3]| {
        let (x, y, z) = (p[kx] - ox, p[ky] - oy, p[kz] - oz);
        (x - sx * z, y - sy * z, sz * z)
    };
    let (ax, ay, az) = project(tri[0]);
    let (bx, by, bz) = project(tri[1]);
    let (cx, cy, cz) = project(tri[2]);
    let edge = |a: f32, b: f32, c: f32, d: f32| {
        let e = a * b - c * d;
        if e == 0.0 {
            edge_exact(a, b, c, d)
        } else {
            e
        }
    };
    let u = edge(cx, by, cy, bx);
    let v = edge(ax, cy, ay, cx);
    let w = edge(bx, ay, by, ax);
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    let t = (u * az + v * bz + w * cz) / det;
    (det != 0.0 && t > 0.0 && t < t_max).then_some(t)
}

/// Up to four triangles, structure of arrays: `v[3 * vertex + axis]` holds that
/// coordinate of the four triangles' vertex `vertex`.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct Tri4 {
    pub(super) v: [[f32; 4]; 9],
    /// Triangle index of each lane (`u32::MAX` for an unused lane).
    pub prim: [u32; 4],
}

impl Tri4 {
    /// Packs up to four triangles (`tris.len() <= 4`) with their indices.
    pub fn new(tris: &[([[f32; 3]; 3], u32)]) -> Tri4 {
        debug_assert!(tris.len() <= 4);
        let mut packet = Tri4 { v: [[f32::NAN; 4]; 9], prim: [u32::MAX; 4] };
        for (lane, (tri, prim)) in tris.iter().enumerate() {
            for (vertex, point) in tri.iter().enumerate() {
                for (axis, value) in point.iter().enumerate() {
                    packet.v[3 * vertex + axis][lane] = *value;
                }
            }
            packet.prim[lane] = *prim;
        }
        packet
    }

    /// Lanes hit in `(0, t_max)` and their parameters.
    #[inline(always)]
    fn hits(&self, ray: &ShearRay, t_max: f32) -> (BVec4A, Vec4) {
        let [kx, ky, kz] = ray.k;
        let (ox, oy, oz) = (Vec4::splat(ray.origin[0]), Vec4::splat(ray.origin[1]), Vec4::splat(ray.origin[2]));
        let (sx, sy, sz) = (Vec4::splat(ray.shear[0]), Vec4::splat(ray.shear[1]), Vec4::splat(ray.shear[2]));
        let project = |vertex: usize| {
            let base = 3 * vertex;
            let x = Vec4::from_array(self.v[base + kx]) - ox;
            let y = Vec4::from_array(self.v[base + ky]) - oy;
            let z = Vec4::from_array(self.v[base + kz]) - oz;
            (x - sx * z, y - sy * z, sz * z)
        };
        let (ax, ay, az) = project(0);
        let (bx, by, bz) = project(1);
        let (cx, cy, cz) = project(2);
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        let zero = Vec4::ZERO;
        if (u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero)).any() {
            let (mut ua, mut va, mut wa) = (u.to_array(), v.to_array(), w.to_array());
            let (ax, ay, bx, by, cx, cy) = (ax.to_array(), ay.to_array(), bx.to_array(), by.to_array(), cx.to_array(), cy.to_array());
            // Each edge function on its own, so that its value depends only on its
            // two vertices (the neighbour sharing the edge computes its negation).
            for lane in 0..4 {
                if ua[lane] == 0.0 {
                    ua[lane] = edge_exact(cx[lane], by[lane], cy[lane], bx[lane]);
                }
                if va[lane] == 0.0 {
                    va[lane] = edge_exact(ax[lane], cy[lane], ay[lane], cx[lane]);
                }
                if wa[lane] == 0.0 {
                    wa[lane] = edge_exact(bx[lane], ay[lane], by[lane], ax[lane]);
                }
            }
            (u, v, w) = (Vec4::from_array(ua), Vec4::from_array(va), Vec4::from_array(wa));
        }
        // Inside: the three edge functions share a sign (zero counts as either).
        // A NaN lane (padding, or an overflowed product) is in neither set; its `t`
        // would be NaN and fail below anyway, so leaving it out changes nothing.
        let all_ge = u.cmpge(zero) & v.cmpge(zero) & w.cmpge(zero);
        let all_le = u.cmple(zero) & v.cmple(zero) & w.cmple(zero);
        let inside = all_ge | all_le;
        // Most packets a walk opens miss in every lane: stop before the division.
        if !inside.any() {
            return (inside, zero);
        }
        let det = u + v + w;
        let t = (u * az + v * bz + w * cz) / det;
        let valid = inside & det.cmpne(zero) & t.cmpgt(zero) & t.cmplt(Vec4::splat(t_max));
        (valid, t)
    }

    /// The nearest hit in `(0, t_max)`: its parameter and triangle index.
    #[inline(always)]
    pub fn intersect(&self, ray: &ShearRay, t_max: f32) -> Option<(f32, u32)> {
        let (valid, t) = self.hits(ray, t_max);
        let mut mask = valid.bitmask();
        if mask == 0 {
            return None;
        }
        let t = t.to_array();
        let mut best = (f32::INFINITY, u32::MAX);
        while mask != 0 {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            if t[lane] < best.0 {
                best = (t[lane], self.prim[lane]);
            }
        }
        Some(best)
    }

    /// Whether any lane is hit in `(0, t_max)`.
    #[inline(always)]
    pub fn occludes(&self, ray: &ShearRay, t_max: f32) -> bool {
        self.hits(ray, t_max).0.any()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    /// The axes as Woop et al. pick them, written with branches.
    fn axes_by_branches(dir: [f32; 3]) -> [usize; 3] {
        let a = dir.map(f32::abs);
        let kz = if a[0] >= a[1] && a[0] >= a[2] {
            0
        } else if a[1] >= a[2] {
            1
        } else {
            2
        };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        [kx, ky, kz]
    }

    #[test]
    fn axes_are_the_lowest_dominant_one_and_its_cycle() {
        // Every sign and every order of magnitudes, ties included (0.5 twice or
        // three times), and negative zeros.
        let values = [-2.0f32, -0.5, -0.0, 0.0, 0.5, 2.0];
        let mut checked = 0;
        for x in values {
            for y in values {
                for z in values {
                    let dir = [x, y, z];
                    let Some(ray) = ShearRay::new([1.0, 2.0, 3.0], dir) else {
                        assert!(dir.iter().all(|&c| c == 0.0), "{dir:?} refused");
                        continue;
                    };
                    let k = axes_by_branches(dir);
                    assert_eq!(ray.k, k, "{dir:?}");
                    assert_eq!(ray.origin, k.map(|axis| [1.0, 2.0, 3.0][axis]), "{dir:?}");
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 6 * 6 * 6 - 8);
    }

    #[test]
    fn parameter_is_along_the_unnormalised_direction() {
        let ray = ShearRay::new([0.25, 0.25, 4.0], [0.0, 0.0, -2.0]).unwrap();
        assert_eq!(intersect_one(&ray, TRI, f32::INFINITY), Some(2.0));
        let packet = Tri4::new(&[(TRI, 7)]);
        assert_eq!(packet.intersect(&ray, f32::INFINITY), Some((2.0, 7)));
        assert_eq!(packet.intersect(&ray, 2.0), None, "the interval is open");
        assert!(!packet.occludes(&ray, 1.5));
    }

    #[test]
    fn nearest_lane_wins_and_padding_never_hits() {
        let lift = |z: f32| TRI.map(|p| [p[0], p[1], z]);
        let packet = Tri4::new(&[(lift(1.0), 3), (lift(-1.0), 4), (lift(2.0), 5)]);
        let ray = ShearRay::new([0.1, 0.1, 0.0], [0.0, 0.0, 1.0]).unwrap();
        assert_eq!(packet.intersect(&ray, f32::INFINITY), Some((1.0, 3)));
        let down = ShearRay::new([0.1, 0.1, 0.0], [0.0, 0.0, -0.5]).unwrap();
        assert_eq!(packet.intersect(&down, f32::INFINITY), Some((2.0, 4)));
        let miss = ShearRay::new([5.0, 5.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
        assert_eq!(packet.intersect(&miss, f32::INFINITY), None);
    }

    #[test]
    fn shared_edge_and_vertex_are_hit_once_at_least() {
        // Two triangles sharing the diagonal of the unit square; rays exactly
        // through the diagonal and through the shared vertices.
        let a = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]];
        let b = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        for p in [[0.5f32, 0.5], [0.25, 0.25], [0.0, 0.0], [1.0, 1.0], [0.3, 0.3]] {
            let ray = ShearRay::new([p[0], p[1], 1.0], [0.0, 0.0, -1.0]).unwrap();
            let hits = [a, b].iter().filter(|t| intersect_one(&ray, **t, f32::INFINITY).is_some()).count();
            assert!(hits >= 1, "ray through {p:?} leaked");
        }
    }

    /// Each lane of a packet answers as the scalar test does, bit for bit, over
    /// random triangles (some degenerate, some with huge coordinates whose edge
    /// products overflow) and rays aimed at them, including the packets whose
    /// every lane misses and stops before the division.
    #[test]
    fn packet_lanes_match_the_scalar_test() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut hits = 0;
        for round in 0..20_000 {
            let scale = match round % 5 {
                0 => 1e-3,
                1 => 1e19,
                _ => 1.0,
            };
            let mut tris = [[[0.0f32; 3]; 3]; 4];
            for tri in &mut tris {
                for p in tri.iter_mut() {
                    *p = [next() - 0.5, next() - 0.5, next() - 0.5].map(|c| c * scale);
                }
            }
            if round % 7 == 0 {
                tris[1][2] = tris[1][0]; // a degenerate triangle
            }
            let lanes = 1 + round % 4;
            let packet = Tri4::new(&tris[..lanes].iter().enumerate().map(|(i, t)| (*t, i as u32)).collect::<Vec<_>>());
            let target = [next() - 0.5, next() - 0.5, next() - 0.5].map(|c| c * scale);
            let origin = [next() - 0.5, next() - 0.5, 2.0 + next()].map(|c| c * scale);
            let dir = [0, 1, 2].map(|k| target[k] - origin[k]);
            let Some(ray) = ShearRay::new(origin, dir) else { continue };
            let t_max = if round % 3 == 0 { 0.9 + 0.2 * next() } else { f32::INFINITY };
            let (valid, t) = packet.hits(&ray, t_max);
            let (mask, t) = (valid.bitmask(), t.to_array());
            for lane in 0..4 {
                let scalar = if lane < lanes { intersect_one(&ray, tris[lane], t_max) } else { None };
                let packed = (mask >> lane & 1 == 1).then(|| t[lane]);
                assert_eq!(packed.map(f32::to_bits), scalar.map(f32::to_bits), "round {round}, lane {lane}");
                hits += scalar.is_some() as usize;
            }
        }
        assert!(hits > 1000, "the rays must hit often enough to test the hits ({hits})");
    }

    #[test]
    fn degenerate_rays_are_rejected() {
        assert!(ShearRay::new([0.0; 3], [0.0; 3]).is_none());
        assert!(ShearRay::new([f32::NAN, 0.0, 0.0], [0.0, 0.0, 1.0]).is_none());
        assert!(ShearRay::new([0.0; 3], [f32::INFINITY, 0.0, 1.0]).is_none());
    }
}
