//! Packet traversal of the ray-casting BVH ([`super::MeshBvh`]) for coherent
//! rays: eight rays walk the tree together, one AVX lane each.
//!
//! Neighbouring camera rays (and shadow rays towards one light) enter nearly the
//! same nodes. Walked one at a time, each ray pays for every node on its own:
//! one eight-box test per node, the ordering of the children, the stack. Walked
//! as a packet, a node is fetched, tested and ordered once for all eight: each of
//! its boxes is tested against the eight rays in one AVX pass
//! ([`SlabPacket::test_box`]), and a child is entered with the mask of the rays
//! that enter it. Leaves are tested ray by ray with the single-ray triangle test,
//! only for the rays of the mask. This is the classic packet traversal (Wald et
//! al. 2001, "Interactive rendering with coherent ray tracing"), on an 8-wide tree.
//!
//! **The answers.** Each ray's box tests are bit for bit its own single-ray tests
//! (`slab.rs` tests it), and a ray takes part in a child exactly when its own walk
//! could: it enters the box before its own closest hit so far. Every triangle its
//! own walk would find is therefore tested for it, with the same arithmetic, and
//! the nearest distance is the same bits. Only which triangle is reported when two
//! are hit at the very same distance (a ray through a shared edge) can differ,
//! since the order of the tests differs; both are hits at that distance.
//!
//! Handing a ray over to its own single-ray walk once it is alone (or one of two)
//! in a subtree was tried and measured 3-5 % slower on the bunny and Igea camera
//! rays (issue 24, session 13): the packet's one-box tests are cheap, and the
//! hand-over's stack setup is not. So was a frustum test of inner nodes (one
//! conservative eight-box test for the whole packet from the ranges of the rays'
//! origins and inverse directions, each ray's own test only at leaves): 11 % slower
//! on the bunny, 1 % on Igea, as it lets rays through nodes they miss. Packets
//! of 16 rays (two AVX registers, a half skipped when none of its rays is left)
//! measured the same as 8, within 1 %.
//!
//! **Leaves.** A leaf reached by few of the packet's rays is tested ray by ray
//! (four triangles at once for one ray, [`super::tri4::Tri4`]). One reached by
//! [`LEAF_LANES_MIN`] rays or more, when all the packet's rays share the axis
//! permutation of the watertight test (camera rays nearly always do), is tested
//! a triangle at a time against all eight rays, one AVX lane each
//! ([`ShearLanes::intersect`]): the same operations in the same order as the
//! single-ray test, lane by lane, so the same bits, and the triangles in the
//! same order, so the same triangle on ties. On the bunny's camera rays a leaf
//! is reached by 4.7 rays of eight on average.
//!
//! Children are ordered by the nearest entry of any of their rays. Rays that
//! scatter would drag each other through nodes only some of them need; callers
//! use packets for coherent rays only (`batch/mesh.rs`).

use super::mesh_bvh::{MeshBvh, COUNT_SHIFT, FIRST_MASK, LEAF, STACK};
use super::tri4::{edge_exact, ShearRay, Tri4};

/// Rays per packet: one per AVX lane.
pub const PACKET: usize = 8;

/// Rays of a packet reaching a leaf from which the leaf is tested a triangle
/// at a time against all eight lanes rather than ray by ray. A one-triangle
/// eight-ray test costs a little more than a four-triangle one-ray test, and a
/// leaf holds 1.45 four-triangle groups on average (bunny, Igea); callgrind on
/// the bunny's camera rays: 3 needs 0.2 % fewer instructions than 4.
const LEAF_LANES_MIN: u32 = 3;

/// A packet's ray: origin, direction and limit of `o + t d`, `t` in `(0, t_max)`.
pub type PacketRay = ([f32; 3], [f32; 3], f32);

impl MeshBvh {
    /// The nearest hits of eight rays, walked together: for each ray, what
    /// [`MeshBvh::closest`] answers (see the module documentation for ties). A ray
    /// with a zero or non-finite direction misses, as there.
    pub fn closest_packet(&self, rays: &[PacketRay; PACKET]) -> [Option<(f32, u32)>; PACKET] {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.closest_packet_avx2(rays) };
        }
        rays.map(|(o, d, t_max)| self.closest(o, d, t_max))
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn closest_packet_avx2(&self, rays: &[PacketRay; PACKET]) -> [Option<(f32, u32)>; PACKET] {
        use std::arch::x86_64::*;
        use std::mem::MaybeUninit;

        use super::slab::{farthest_first, SlabPacket, SlabRay, WIDEN};
        use crate::math::Vec3;

        let mut best = [None; PACKET];
        if self.nodes.is_empty() {
            return best;
        }
        // A loop rather than `rays.map(..)`: the closure of `map` was left out of
        // line by some builds, and each call then stalled on its arguments
        // (20 % of the packet walk's time on the bunny's camera rays).
        let mut shear = [None; PACKET];
        for (lane, &(o, d, _)) in rays.iter().enumerate() {
            shear[lane] = ShearRay::new(o, d);
        }
        let mut active = 0u32;
        for (lane, ray) in shear.iter().enumerate() {
            active |= u32::from(ray.is_some()) << lane;
        }
        if active == 0 {
            return best;
        }
        let lanes = ShearLanes::new(&shear);
        // Lanes without a ray get a harmless one; their bit is never set.
        let slabs = std::array::from_fn(|lane| {
            let (o, d, _) = rays[lane];
            let d = if active >> lane & 1 != 0 { d } else { [0.0, 0.0, 1.0] };
            SlabRay::new(Vec3::from(o.map(|v| if v.is_finite() { f64::from(v) } else { 0.0 })), Vec3::from(d.map(f64::from)), 0.0)
        });
        let packet = SlabPacket::new(&slabs);
        let mut t_max = rays.map(|(_, _, t)| t);
        let limits = |t_max: &[f32; PACKET]| _mm256_loadu_ps(t_max.as_ptr());
        // A stack entry: a child, the rays that entered it, and their entries.
        let mut stack = [const { MaybeUninit::<(u32, u32, __m256)>::uninit() }; STACK];
        let mut order = [(0f32, 0u32); 8];
        let mut top = 0usize;
        let (mut current, mut mask) = (0u32, active);
        loop {
            if current & LEAF != 0 {
                let first = (current & FIRST_MASK) as usize;
                let count = ((current & !LEAF) >> COUNT_SHIFT) as usize;
                if let Some(lanes) = lanes.as_ref().filter(|_| mask.count_ones() >= LEAF_LANES_MIN) {
                    lanes.intersect(&self.packets[first..first + count], mask, &mut t_max, &mut best);
                    // Fall through to the stack, as after the ray-by-ray test.
                } else {
                    let mut lanes = mask;
                    while lanes != 0 {
                        let lane = lanes.trailing_zeros() as usize;
                        lanes &= lanes - 1;
                        // SAFETY: lanes of `mask` are lanes of `active`, whose rays exist.
                        let ray = unsafe { shear[lane].as_ref().unwrap_unchecked() };
                        for tri in &self.packets[first..first + count] {
                            if let Some((t, prim)) = tri.intersect(ray, t_max[lane]) {
                                t_max[lane] = t;
                                best[lane] = Some((t, prim));
                            }
                        }
                    }
                }
            } else {
                let node = &self.nodes[current as usize];
                let limit = limits(&t_max);
                // The entered children: (nearest entry of their rays, slot), and each one's rays.
                // Only the slots of `entered` are written and read.
                let mut rays_of = [0u32; 8];
                let mut entries = [MaybeUninit::<__m256>::uninit(); 8];
                let mut entered = 0u32;
                let mut slots = u32::from(node.valid);
                while slots != 0 {
                    let slot = slots.trailing_zeros() as usize;
                    slots &= slots - 1;
                    let (enter, hit) = packet.test_box(&node.planes, slot, limit);
                    let hit = hit & mask;
                    if hit != 0 {
                        entered |= 1 << slot;
                        rays_of[slot] = hit;
                        entries[slot].write(enter);
                    }
                }
                if entered != 0 {
                    let slot = if entered & (entered - 1) == 0 {
                        entered.trailing_zeros() as usize
                    } else {
                        // Push the entered children farthest first (by the nearest
                        // entry of their rays); continue with the nearest.
                        let mut near = [f32::INFINITY; 8];
                        let mut each = entered;
                        while each != 0 {
                            let slot = each.trailing_zeros() as usize;
                            each &= each - 1;
                            // SAFETY: written above for every slot of `entered`.
                            near[slot] = nearest_of(unsafe { entries[slot].assume_init() }, rays_of[slot]);
                        }
                        let n = farthest_first(&near, entered, &mut order);
                        for &(_, slot) in &order[..n - 1] {
                            let slot = slot as usize;
                            // SAFETY: as above.
                            stack[top].write((node.child[slot], rays_of[slot], unsafe { entries[slot].assume_init() }));
                            top += 1;
                        }
                        order[n - 1].1 as usize
                    };
                    (current, mask) = (node.child[slot], rays_of[slot]);
                    continue;
                }
            }
            // The next child on the stack that one of its rays still needs: the
            // rays whose entry is not beyond their closest hit (as the single-ray
            // walk skips a child).
            loop {
                if top == 0 {
                    return best;
                }
                top -= 1;
                // SAFETY: entries below `top` were written by the pushes above.
                let (child, rays, enter) = unsafe { stack[top].assume_init() };
                let still = _mm256_cmp_ps::<_CMP_LE_OQ>(enter, _mm256_mul_ps(limits(&t_max), _mm256_set1_ps(1.0 + WIDEN)));
                let rays = rays & _mm256_movemask_ps(still) as u32;
                if rays != 0 {
                    (current, mask) = (child, rays);
                    break;
                }
            }
        }
    }
}

/// The eight rays of a packet whose every usable ray has the same axis
/// permutation, lane by lane: origins in permuted order and shears, for
/// testing one triangle against the eight at once.
#[cfg(target_arch = "x86_64")]
struct ShearLanes {
    k: [usize; 3],
    origin: [std::arch::x86_64::__m256; 3],
    shear: [std::arch::x86_64::__m256; 3],
}

#[cfg(target_arch = "x86_64")]
impl ShearLanes {
    /// `None` when the usable rays do not share one permutation (or none is usable).
    #[target_feature(enable = "avx2")]
    fn new(rays: &[Option<ShearRay>; PACKET]) -> Option<ShearLanes> {
        use std::arch::x86_64::*;
        let k = rays.iter().flatten().next()?.k;
        if rays.iter().flatten().any(|r| r.k != k) {
            return None;
        }
        // Unusable lanes get zeros; their bits are never in a mask.
        let lane = |f: &dyn Fn(&ShearRay) -> f32| {
            let v = rays.each_ref().map(|r| r.as_ref().map_or(0.0, f));
            // SAFETY: eight f32s; unaligned load.
            unsafe { _mm256_loadu_ps(v.as_ptr()) }
        };
        Some(ShearLanes {
            k,
            origin: [lane(&|r| r.origin[0]), lane(&|r| r.origin[1]), lane(&|r| r.origin[2])],
            shear: [lane(&|r| r.shear[0]), lane(&|r| r.shear[1]), lane(&|r| r.shear[2])],
        })
    }

    /// The leaf's triangles against the rays of `mask`, in the order of the
    /// ray-by-ray test: each lane's `t_max` and `best` move to a triangle hit
    /// strictly nearer, as `Tri4::intersect` moves them, and each lane's
    /// arithmetic is `Tri4`'s (and `intersect_one`'s), so the answers are the
    /// same bits.
    #[target_feature(enable = "avx2")]
    fn intersect(&self, tris: &[Tri4], mask: u32, t_max: &mut [f32; PACKET], best: &mut [Option<(f32, u32)>; PACKET]) {
        use std::arch::x86_64::*;
        let [kx, ky, kz] = self.k;
        let [ox, oy, oz] = self.origin;
        let [sx, sy, sz] = self.shear;
        // SAFETY (loads and stores below): eight f32s each; unaligned.
        let mut limit = unsafe { _mm256_loadu_ps(t_max.as_ptr()) };
        let mut prims = _mm256_setzero_si256();
        let mut found = 0u32;
        let zero = _mm256_setzero_ps();
        for tri in tris {
            for j in 0..4 {
                if tri.prim[j] == u32::MAX {
                    continue;
                }
                let project = |vertex: usize| {
                    let base = 3 * vertex;
                    let x = _mm256_sub_ps(_mm256_set1_ps(tri.v[base + kx][j]), ox);
                    let y = _mm256_sub_ps(_mm256_set1_ps(tri.v[base + ky][j]), oy);
                    let z = _mm256_sub_ps(_mm256_set1_ps(tri.v[base + kz][j]), oz);
                    (_mm256_sub_ps(x, _mm256_mul_ps(sx, z)), _mm256_sub_ps(y, _mm256_mul_ps(sy, z)), _mm256_mul_ps(sz, z))
                };
                let (ax, ay, az) = project(0);
                let (bx, by, bz) = project(1);
                let (cx, cy, cz) = project(2);
                let edge = |a: __m256, b: __m256, c: __m256, d: __m256| _mm256_sub_ps(_mm256_mul_ps(a, b), _mm256_mul_ps(c, d));
                let (mut u, mut v, mut w) = (edge(cx, by, cy, bx), edge(ax, cy, ay, cx), edge(bx, ay, by, ax));
                let is_zero = |e: __m256| _mm256_cmp_ps::<_CMP_EQ_OQ>(e, zero);
                if _mm256_movemask_ps(_mm256_or_ps(_mm256_or_ps(is_zero(u), is_zero(v)), is_zero(w))) as u32 & mask != 0 {
                    // The `f64` fallback for the lanes whose edge function rounded to zero.
                    let arr = |x: __m256| {
                        let mut a = [0f32; 8];
                        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), x) };
                        a
                    };
                    let (ax, ay, bx, by, cx, cy) = (arr(ax), arr(ay), arr(bx), arr(by), arr(cx), arr(cy));
                    let (mut ua, mut va, mut wa) = (arr(u), arr(v), arr(w));
                    for lane in 0..PACKET {
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
                    unsafe {
                        (u, v, w) = (_mm256_loadu_ps(ua.as_ptr()), _mm256_loadu_ps(va.as_ptr()), _mm256_loadu_ps(wa.as_ptr()));
                    }
                }
                // Outside: one edge function below zero and one above (zero counts
                // as either side). A NaN lane may pass as inside here, where the
                // ray-by-ray test calls it outside; its `t` is NaN and fails below.
                let low = _mm256_min_ps(_mm256_min_ps(u, v), w);
                let high = _mm256_max_ps(_mm256_max_ps(u, v), w);
                let outside = _mm256_and_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(low, zero), _mm256_cmp_ps::<_CMP_GT_OQ>(high, zero));
                let inside = !(_mm256_movemask_ps(outside) as u32) & mask;
                if inside == 0 {
                    continue;
                }
                let det = _mm256_add_ps(_mm256_add_ps(u, v), w);
                let num = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(u, az), _mm256_mul_ps(v, bz)), _mm256_mul_ps(w, cz));
                let t = _mm256_div_ps(num, det);
                let valid = _mm256_andnot_ps(outside, _mm256_cmp_ps::<_CMP_NEQ_UQ>(det, zero));
                let valid =
                    _mm256_and_ps(valid, _mm256_and_ps(_mm256_cmp_ps::<_CMP_GT_OQ>(t, zero), _mm256_cmp_ps::<_CMP_LT_OQ>(t, limit)));
                let hit = _mm256_movemask_ps(valid) as u32 & mask;
                if hit != 0 {
                    let chosen = lane_mask(hit);
                    limit = _mm256_blendv_ps(limit, t, chosen);
                    prims = _mm256_castps_si256(_mm256_blendv_ps(
                        _mm256_castsi256_ps(prims),
                        _mm256_castsi256_ps(_mm256_set1_epi32(tri.prim[j] as i32)),
                        chosen,
                    ));
                    found |= hit;
                }
            }
        }
        if found == 0 {
            return;
        }
        let mut prim = [0u32; PACKET];
        unsafe {
            _mm256_storeu_ps(t_max.as_mut_ptr(), limit);
            _mm256_storeu_si256(prim.as_mut_ptr().cast(), prims);
        }
        while found != 0 {
            let lane = found.trailing_zeros() as usize;
            found &= found - 1;
            best[lane] = Some((t_max[lane], prim[lane]));
        }
    }
}

/// All bits set in the lanes of `mask`, as a float vector for blends.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn lane_mask(mask: u32) -> std::arch::x86_64::__m256 {
    use std::arch::x86_64::*;
    let bits = _mm256_set_epi32(1 << 7, 1 << 6, 1 << 5, 1 << 4, 1 << 3, 1 << 2, 1 << 1, 1);
    _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(mask as i32), bits), bits))
}

/// The smallest lane of `enter` among the lanes of `mask` (`+inf` for none).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn nearest_of(enter: std::arch::x86_64::__m256, mask: u32) -> f32 {
    use std::arch::x86_64::*;
    let bits = _mm256_set_epi32(1 << 7, 1 << 6, 1 << 5, 1 << 4, 1 << 3, 1 << 2, 1 << 1, 1);
    let chosen = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(mask as i32), bits), bits);
    let v = _mm256_blendv_ps(_mm256_set1_ps(f32::INFINITY), enter, _mm256_castsi256_ps(chosen));
    let v = _mm_min_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps::<1>(v));
    let v = _mm_min_ps(v, _mm_movehl_ps(v, v));
    let v = _mm_min_ss(v, _mm_shuffle_ps::<0b01>(v, v));
    _mm_cvtss_f32(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    /// A wavy height field of `n x n` cells (two triangles each) over [-1, 1]^2,
    /// seen by a 64 x 64 camera from above, rays in pixel order: packets of
    /// neighbouring rays, some crossing the field's silhouette, some missing it.
    fn field_and_camera(n: u32) -> (MeshBvh, Vec<PacketRay>) {
        let h = |x: f32, y: f32| 0.2 * (3.0 * x).sin() * (2.0 * y).cos();
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (2.0 * i as f32 / n as f32 - 1.0, 2.0 * j as f32 / n as f32 - 1.0);
                positions.push([x, y, h(x, y)]);
            }
        }
        let mut indices = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let a = j * (n + 1) + i;
                indices.push([a, a + 1, a + n + 2]);
                indices.push([a, a + n + 2, a + n + 1]);
            }
        }
        let bvh = MeshBvh::build(&positions, &indices);
        let mut rng = Rng::for_sample(11, 0, 0);
        let rays = (0..64 * 64)
            .map(|p| {
                let (x, y) = ((p % 64) as f32 / 32.0 - 1.0, (p / 64) as f32 / 32.0 - 1.0);
                let d = [1.4 * x + 0.001 * rng.uniform() as f32, 1.4 * y, -2.0];
                let t_max = if p % 7 == 0 { 0.8 } else { f32::INFINITY };
                ([0.1, 0.0, 2.0], if p % 97 == 5 { [0.0; 3] } else { d }, t_max)
            })
            .collect();
        (bvh, rays)
    }

    #[test]
    fn packets_find_each_rays_own_nearest_distance_bit_for_bit() {
        let (bvh, rays) = field_and_camera(40);
        let (mut hits, mut same_triangle) = (0, 0);
        for (k, chunk) in rays.chunks(PACKET).enumerate() {
            let packet: [PacketRay; PACKET] = chunk.try_into().unwrap();
            let answers = bvh.closest_packet(&packet);
            for (lane, (&(o, d, t_max), answer)) in packet.iter().zip(answers).enumerate() {
                let own = bvh.closest(o, d, t_max);
                assert_eq!(answer.map(|a| a.0.to_bits()), own.map(|a| a.0.to_bits()), "packet {k} lane {lane}");
                hits += usize::from(own.is_some());
                same_triangle += usize::from(answer == own);
            }
        }
        assert!(hits > 1000 && hits < rays.len() - 500, "rays both hit and miss: {hits}");
        // Ties at one distance are rare: a different triangle only on shared edges.
        assert!(same_triangle >= rays.len() - 8, "{same_triangle} of {} rays report their own triangle", rays.len());
    }

    #[test]
    fn packets_of_scattered_unusable_and_empty_rays() {
        let (bvh, _) = field_and_camera(8);
        let mut rng = Rng::for_sample(12, 0, 0);
        let mut r = move || (rng.uniform() * 2.0 - 1.0) as f32;
        for _ in 0..200 {
            let packet: [PacketRay; PACKET] = std::array::from_fn(|lane| match lane {
                3 => ([0.0; 3], [f32::NAN, 0.0, 1.0], f32::INFINITY),
                6 => ([f32::INFINITY, 0.0, 0.0], [0.0, 0.0, -1.0], f32::INFINITY),
                _ => ([2.0 * r(), 2.0 * r(), 2.0 * r()], [r(), r(), r()], f32::INFINITY),
            });
            let answers = bvh.closest_packet(&packet);
            for (lane, &(o, d, t_max)) in packet.iter().enumerate() {
                assert_eq!(answers[lane].map(|a| a.0.to_bits()), bvh.closest(o, d, t_max).map(|a| a.0.to_bits()), "lane {lane}");
            }
            assert_eq!((answers[3], answers[6]), (None, None));
        }
        let empty = MeshBvh::build(&[], &[]);
        assert_eq!(empty.closest_packet(&[([0.0; 3], [0.0, 0.0, 1.0], f32::INFINITY); PACKET]), [None; PACKET]);
    }

    /// One triangle against eight lanes answers, lane by lane, what the
    /// ray-by-ray four-triangle test answers: the same distance bits and the
    /// same triangle, ties included. Triangles on an integer grid and rays
    /// through grid points make edge functions round to exactly zero (the
    /// `f64` fallback) and distances tie between neighbours; some triangles
    /// are degenerate, some groups have unused lanes.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn eight_lanes_per_triangle_answer_as_the_ray_by_ray_test() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            eprintln!("skipped: the eight-lane leaf test needs AVX2");
            return;
        }
        let mut rng = Rng::for_sample(13, 0, 0);
        let mut uniform = move || rng.uniform();
        let (mut hits, mut ties) = (0, 0);
        for round in 0..3000 {
            // Whole coordinates in even rounds (exact products: ties between
            // neighbours), arbitrary ones in odd rounds.
            let mut coordinate = |n: f64| if round % 2 == 0 { (uniform() * n).floor() as f32 } else { (uniform() * n) as f32 };
            let groups: Vec<Tri4> = (0..1 + round % 3)
                .map(|g| {
                    let tris: Vec<([[f32; 3]; 3], u32)> = (0..1 + (round + g) % 4)
                        .map(|j| {
                            let mut tri = [
                                [coordinate(4.0), coordinate(4.0), coordinate(3.0) - 4.0],
                                [coordinate(4.0), coordinate(4.0), -2.0],
                                [coordinate(4.0), coordinate(4.0), -3.0],
                            ];
                            if round % 17 == 0 {
                                tri[2] = tri[0]; // degenerate
                            }
                            (tri, (10 * g + j) as u32)
                        })
                        .collect();
                    Tri4::new(&tris)
                })
                .collect();
            let first = groups[0].v;
            // Eight rays looking down -z (one permutation): even lanes through a
            // point rounded onto an edge of the first triangle (where edge
            // functions round to zero and the `f64` fallback decides), odd lanes
            // through grid points or half-way between them.
            let rays: [Option<ShearRay>; PACKET] = std::array::from_fn(|lane| {
                let o = if lane % 2 == 0 {
                    let (a, b) = (lane / 2 % 3, (lane / 2 + 1) % 3);
                    let s = uniform() as f32;
                    let along = |axis: usize| first[3 * a + axis][0] + s * (first[3 * b + axis][0] - first[3 * a + axis][0]);
                    [along(0), along(1), 2.0]
                } else {
                    [(uniform() * 8.0).floor() as f32 * 0.5, (uniform() * 8.0).floor() as f32 * 0.5, 2.0]
                };
                let tilt = |u: f64| ((u * 3.0).floor() as f32 - 1.0) * 0.25;
                ShearRay::new(o, if lane % 4 == 0 { [0.0, 0.0, -1.0] } else { [tilt(uniform()), tilt(uniform()), -1.0] })
            });
            let lanes = unsafe { ShearLanes::new(&rays) }.expect("one permutation");
            let limit = if round % 5 == 0 { 4.5 } else { f32::INFINITY };
            let (mut t_max, mut best) = ([limit; PACKET], [None; PACKET]);
            unsafe { lanes.intersect(&groups, 0xff, &mut t_max, &mut best) };
            for (lane, ray) in rays.iter().enumerate() {
                let ray = ray.as_ref().unwrap();
                let (mut own_t, mut own) = (limit, None);
                for tri in &groups {
                    if let Some((t, prim)) = tri.intersect(ray, own_t) {
                        own_t = t;
                        own = Some((t, prim));
                    }
                }
                assert_eq!(best[lane].map(|(t, p)| (t.to_bits(), p)), own.map(|(t, p)| (t.to_bits(), p)), "round {round} lane {lane}");
                hits += usize::from(own.is_some());
                ties += usize::from(own.is_some_and(|(t, _)| t.fract() == 0.0));
            }
        }
        assert!(hits > 4000, "{hits} hits");
        assert!(ties > 100, "{ties} hits at whole distances");
    }
}
