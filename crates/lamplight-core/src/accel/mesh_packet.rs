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
//! Children are ordered by the nearest entry of any of their rays. Rays that
//! scatter would drag each other through nodes only some of them need; callers
//! use packets for coherent rays only (`batch/mesh.rs`).

use super::mesh_bvh::{MeshBvh, COUNT_SHIFT, FIRST_MASK, LEAF, STACK};
use super::tri4::ShearRay;

/// Rays per packet: one per AVX lane.
pub const PACKET: usize = 8;

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
        let shear = rays.map(|(o, d, _)| ShearRay::new(o, d));
        let mut active = 0u32;
        for (lane, ray) in shear.iter().enumerate() {
            active |= u32::from(ray.is_some()) << lane;
        }
        if active == 0 {
            return best;
        }
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
        let mut top = 0usize;
        let (mut current, mut mask) = (0u32, active);
        loop {
            if current & LEAF != 0 {
                let first = (current & FIRST_MASK) as usize;
                let count = ((current & !LEAF) >> COUNT_SHIFT) as usize;
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
                        let (order, n) = farthest_first(&near, entered);
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
}
