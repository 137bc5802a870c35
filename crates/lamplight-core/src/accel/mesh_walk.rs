//! Traversal of the ray-casting BVH ([`super::MeshBvh`]): one ray at a time, or
//! several rays interleaved so that their memory waits overlap.
//!
//! A ray's walk is a chain of dependent loads: which node comes next is known
//! only once the current one is tested. On a mesh larger than the caches (a
//! million triangles is 59 MB of nodes and packets) each step waits on memory,
//! and one ray's walk leaves the core idle most of the time. A batch of rays has
//! no such dependency between its rays, so [`MeshBvh::closest_batch`] keeps
//! [`LANES`] walks in flight: each step of a walk tests one node or one leaf,
//! decides the next one, *prefetches* it and moves on to the next walk. By the
//! time a walk's turn comes again its node has arrived. This is the "asynchronous
//! memory access chaining" of database hash joins (Kocberber et al. 2015) applied
//! to BVH traversal; it is not a packet traversal, every ray walks its own path.
//!
//! The answers are those of the single-ray walk bit for bit: a step does exactly
//! what one iteration of the single-ray loop does, and each walk keeps its own
//! closest hit and stack (the tests compare the two on random rays). The order
//! in which the rays of a batch finish differs, which nothing observes. The
//! single-ray loops are written out rather than built from the steps: kept in
//! registers, they are 12 % faster on coherent rays than the step run to the end
//! (measured on the bunny's camera rays, issue 24).
//!
//! Closest hit, here: ordered traversal (nearest child first, by entry distance;
//! popped entries beyond the closest hit are skipped). Any hit: `any_hit.rs`,
//! sharing this module's walk state, setup and prefetching.

use std::mem::MaybeUninit;

use super::mesh_bvh::{MeshBvh, Node, COUNT_SHIFT, FIRST_MASK, LEAF, MAX_LEAF, STACK, WIDTH};
use super::slab::{farthest_first, test8, SlabRay, WIDEN};
use super::tri4::{ShearRay, Tri4};
use crate::math::Vec3;

mod any_hit;

/// Walks in flight in a batch query. Measured on the bunny and Igea-1M
/// (`BENCHMARKS.md`, issue 24): once a step stopped clamping its prefetches
/// (session 35), 12 walks beat 8 on Igea-1M's scattered rays by 8 % (any hit
/// 7 %), whose nodes wait on main memory, and the bunny's by 1 %; 16 gained
/// nothing more, 6 lost 9 % on Igea-1M.
pub const LANES: usize = 12;

/// One ray's walk, less its stack.
#[derive(Clone, Copy)]
struct Walk {
    shear: ShearRay,
    slab: SlabRay,
    /// The closest hit so far (the query's limit before any).
    t_max: f32,
    best: Option<(f32, u32)>,
    /// The reference (node, or `LEAF | ...`) this walk tests next.
    current: u32,
    /// Entries on this walk's stack.
    top: usize,
    /// The ray's index in the batch.
    ray: usize,
}

type Stack<T> = [MaybeUninit<T>; STACK];

/// The packet range `(first, count)` of a leaf reference.
#[inline(always)]
fn leaf_range(reference: u32) -> (usize, usize) {
    ((reference & FIRST_MASK) as usize, ((reference & !LEAF) >> COUNT_SHIFT) as usize)
}

/// The entry distances of a node's eight children, and the mask of those entered.
#[inline(always)]
fn test_node<const AVX2: bool>(ray: &SlabRay, node: &Node, t_max: f32) -> ([f32; WIDTH], u32) {
    let (enter, mask) = test8::<AVX2>(ray, &node.planes, t_max);
    (enter, mask & node.valid as u32)
}

/// The most bytes [`prefetch`] covers: a leaf of [`MAX_LEAF`] triangles (two
/// packets, unaligned to a line) or a node.
const PREFETCH_SPAN: usize = 5 * 64;
const _: () = assert!(MAX_LEAF.div_ceil(4) * size_of::<Tri4>() <= PREFETCH_SPAN && size_of::<Node>() <= PREFETCH_SPAN);

/// Asks for the cache lines of the [`PREFETCH_SPAN`] bytes from `start` (no
/// effect on the answers; a no-op off x86-64): six hints, at steps of at most a
/// line from the first byte to the last, so every line of the span gets one.
/// A fixed count, because a loop over a node's or a leaf's own lines would end
/// on a count the core mispredicts (leaves and nodes take turns). The span is
/// not clamped to the object's own bytes either: a node's hints reach two lines
/// past it and a one-packet leaf's up to three, and that costs less than the
/// six comparisons that kept them inside (bunny's scattered rays +5.8 %
/// closest and +10 % any-hit, Igea-1M +3.7 % and +2.2 %; issue 24).
#[inline(always)]
fn prefetch(start: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        for offset in [0, 64, 128, 192, 256, PREFETCH_SPAN - 1] {
            let at = start.wrapping_add(offset);
            // SAFETY: prefetching is a hint; it never faults, whatever the address.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(at as *const i8) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = start;
}

impl MeshBvh {
    /// Prefetches what `reference` points at: a node, or a leaf's packets. The
    /// two addresses are both computed and one picked, without a branch.
    #[inline(always)]
    fn prefetch_reference(&self, reference: u32) {
        let leaf = reference & LEAF != 0;
        let (first, _) = leaf_range(reference);
        let packets = self.packets.as_ptr().wrapping_add(first) as usize;
        let node = self.nodes.as_ptr().wrapping_add(reference as usize) as usize;
        prefetch(std::hint::select_unpredictable(leaf, packets, node));
    }

    /// The walk of the next ray from `*next` on that needs one, answering those
    /// that need none. A method rather than a closure: a closure is compiled
    /// for the features of the function that defines it, so the batch's
    /// generic body would set up every ray in baseline code, out of line
    /// (15 % of the bunny's incoherent casts, issue 24); a method inlines
    /// into the AVX2 compilation.
    #[inline(always)]
    fn fetch_closest(
        &self,
        next: &mut usize,
        n: usize,
        ray: &impl Fn(usize) -> ([f32; 3], [f32; 3], f32),
        answer: &mut impl FnMut(usize, Option<(f32, u32)>),
    ) -> Option<Walk> {
        while *next < n {
            let index = *next;
            *next += 1;
            let (o, d, t_max) = ray(index);
            match self.start(index, o, d, t_max) {
                Some(walk) => return Some(walk),
                None => answer(index, None),
            }
        }
        None
    }

    /// Starts the closest-hit walk of ray `index`; `None` when it hits nothing
    /// by definition (see [`ShearRay::new`]) or the mesh is empty.
    #[inline(always)]
    fn start(&self, index: usize, o: [f32; 3], d: [f32; 3], t_max: f32) -> Option<Walk> {
        let shear = ShearRay::new(o, d)?;
        if self.nodes.is_empty() {
            return None;
        }
        let slab = SlabRay::new(Vec3::from(o.map(f64::from)), Vec3::from(d.map(f64::from)), 0.0);
        Some(Walk { shear, slab, t_max, best: None, current: 0, top: 0, ray: index })
    }

    /// One step of a closest-hit walk: tests `walk.current` (a node or a leaf)
    /// and moves to the next reference, prefetching it when `PREFETCH`. False
    /// when the walk is over (`walk.best` is then the answer).
    ///
    /// A node's entered children all go on the stack, nearest on top, and the
    /// walk continues with what it pops. Whether a node has none, one or two
    /// children entered (92 % of the bunny's scattered node visits: 30 %, 42 %
    /// and 20 %) is then data for the same instructions, not a branch the core
    /// must guess. The order is [`farthest_first`]'s, ties included, and the pop's
    /// test only skips a child whose entry lies beyond the closest hit, which
    /// cannot hold a nearer one: the answers are the single-ray walk's bits.
    #[inline(always)]
    fn step_closest<const AVX2: bool, const PREFETCH: bool>(
        &self,
        walk: &mut Walk,
        stack: &mut Stack<(u32, f32)>,
        order: &mut [(f32, u32); WIDTH],
    ) -> bool {
        let current = walk.current;
        if current & LEAF != 0 {
            let (first, count) = leaf_range(current);
            for packet in &self.packets[first..first + count] {
                if let Some((t, prim)) = packet.intersect(&walk.shear, walk.t_max) {
                    walk.t_max = t;
                    walk.best = Some((t, prim));
                }
            }
        } else {
            let node = &self.nodes[current as usize];
            let (enter, mask) = test_node::<AVX2>(&walk.slab, node, walk.t_max);
            let n = mask.count_ones() as usize;
            if n <= 2 {
                // Slots a < b (b meaningless unless two are entered). Of two, the
                // farther goes below, the lower slot on a tie (as farthest_first).
                let a = mask.trailing_zeros() as usize % WIDTH;
                let b = (mask & mask.wrapping_sub(1)).trailing_zeros() as usize % WIDTH;
                let below = std::hint::select_unpredictable((n == 2) & (enter[a] < enter[b]), b, a);
                let above = a ^ b ^ below;
                stack[walk.top].write((node.child[below], enter[below]));
                stack[walk.top + 1].write((node.child[above], enter[above]));
                walk.top += n;
            } else {
                let n = farthest_first(&enter, mask, order);
                for &(t, slot) in &order[..n] {
                    stack[walk.top].write((node.child[slot as usize], t));
                    walk.top += 1;
                }
            }
        }
        while walk.top > 0 {
            walk.top -= 1;
            // SAFETY: entries below `top` were written by the pushes above.
            let (child, enter) = unsafe { stack[walk.top].assume_init() };
            if enter <= walk.t_max * (1.0 + WIDEN) {
                walk.current = child;
                if PREFETCH {
                    self.prefetch_reference(child);
                }
                return true;
            }
        }
        false
    }

    /// The nearest hit of `o + t d` with `t` in `(0, t_max)`: parameter and triangle.
    #[inline]
    pub fn closest(&self, o: [f32; 3], d: [f32; 3], t_max: f32) -> Option<(f32, u32)> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.closest_avx2(o, d, t_max) };
        }
        self.closest_any::<false>(o, d, t_max)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn closest_avx2(&self, o: [f32; 3], d: [f32; 3], t_max: f32) -> Option<(f32, u32)> {
        self.closest_any::<true>(o, d, t_max)
    }

    #[inline(always)]
    fn closest_any<const AVX2: bool>(&self, o: [f32; 3], d: [f32; 3], mut t_max: f32) -> Option<(f32, u32)> {
        let shear = ShearRay::new(o, d)?;
        if self.nodes.is_empty() {
            return None;
        }
        let ray = SlabRay::new(Vec3::from(o.map(f64::from)), Vec3::from(d.map(f64::from)), 0.0);
        let mut best = None;
        let mut stack = [const { MaybeUninit::<(u32, f32)>::uninit() }; STACK];
        let mut order = [(0f32, 0u32); WIDTH];
        let mut top = 0usize;
        let mut current = 0u32;
        loop {
            if current & LEAF != 0 {
                let (first, count) = leaf_range(current);
                for packet in &self.packets[first..first + count] {
                    if let Some((t, prim)) = packet.intersect(&shear, t_max) {
                        t_max = t;
                        best = Some((t, prim));
                    }
                }
            } else {
                let node = &self.nodes[current as usize];
                let (enter, mask) = test_node::<AVX2>(&ray, node, t_max);
                if mask != 0 && mask & (mask - 1) == 0 {
                    // One child entered: nothing to order.
                    current = node.child[mask.trailing_zeros() as usize];
                    continue;
                }
                if mask != 0 {
                    // Push the entered children farthest first; continue with the nearest.
                    let n = farthest_first(&enter, mask, &mut order);
                    for &(t, slot) in &order[..n - 1] {
                        stack[top].write((node.child[slot as usize], t));
                        top += 1;
                    }
                    current = node.child[order[n - 1].1 as usize];
                    continue;
                }
            }
            loop {
                if top == 0 {
                    return best;
                }
                top -= 1;
                // SAFETY: entries below `top` were written by the pushes above.
                let (child, enter) = unsafe { stack[top].assume_init() };
                if enter <= t_max * (1.0 + WIDEN) {
                    current = child;
                    break;
                }
            }
        }
    }

    /// The nearest hits of `n` rays, ray `i` being `ray(i) = (o, d, t_max)`:
    /// `answer(i, hit)` receives what [`MeshBvh::closest`] answers for it, bit for
    /// bit, in an order that interleaves the rays (see the module documentation).
    #[inline]
    pub fn closest_batch(&self, n: usize, ray: impl Fn(usize) -> ([f32; 3], [f32; 3], f32), answer: impl FnMut(usize, Option<(f32, u32)>)) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.closest_batch_avx2(n, ray, answer) };
        }
        self.closest_batch_any::<false>(n, ray, answer)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn closest_batch_avx2(
        &self,
        n: usize,
        ray: impl Fn(usize) -> ([f32; 3], [f32; 3], f32),
        answer: impl FnMut(usize, Option<(f32, u32)>),
    ) {
        self.closest_batch_any::<true>(n, ray, answer)
    }

    #[inline(always)]
    fn closest_batch_any<const AVX2: bool>(
        &self,
        n: usize,
        ray: impl Fn(usize) -> ([f32; 3], [f32; 3], f32),
        mut answer: impl FnMut(usize, Option<(f32, u32)>),
    ) {
        let mut walks = [const { MaybeUninit::<Walk>::uninit() }; LANES];
        let mut stacks = [const { [const { MaybeUninit::<(u32, f32)>::uninit() }; STACK] }; LANES];
        let mut order = [(0f32, 0u32); WIDTH];
        let mut next = 0;
        let mut active = 0;
        while active < LANES {
            let Some(walk) = self.fetch_closest(&mut next, n, &ray, &mut answer) else { break };
            walks[active].write(walk);
            active += 1;
        }
        while active > 0 {
            let mut lane = 0;
            while lane < active {
                // SAFETY: lanes below `active` hold walks written above.
                let walk = unsafe { walks[lane].assume_init_mut() };
                if self.step_closest::<AVX2, true>(walk, &mut stacks[lane], &mut order) {
                    lane += 1;
                    continue;
                }
                answer(walk.ray, walk.best);
                if let Some(fresh) = self.fetch_closest(&mut next, n, &ray, &mut answer) {
                    *walk = fresh;
                    lane += 1;
                } else {
                    // No rays left: the last walk takes this lane (its stack too).
                    active -= 1;
                    if lane < active {
                        // SAFETY: lane `active` holds a walk (it was below the old `active`).
                        walks[lane].write(unsafe { walks[active].assume_init_read() });
                        let top = unsafe { walks[lane].assume_init_ref() }.top;
                        let (low, high) = stacks.split_at_mut(active);
                        low[lane][..top].copy_from_slice(&high[0][..top]);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    /// A ray and its limit, as the batch queries take them.
    type Query = ([f32; 3], [f32; 3], f32);

    /// `n` random triangles in the cube [-1, 1]^3, small enough that rays pass
    /// between them, and the rays: scattered origins and directions, with some
    /// that hit nothing by definition (zero or non-finite directions).
    fn soup(n: usize, rays: usize, seed: u64) -> (MeshBvh, Vec<Query>) {
        let mut rng = Rng::for_sample(seed, 0, 0);
        let mut r = move || (rng.uniform() * 2.0 - 1.0) as f32;
        let mut positions = Vec::new();
        for _ in 0..n {
            let c = [r(), r(), r()];
            for _ in 0..3 {
                positions.push([c[0] + 0.1 * r(), c[1] + 0.1 * r(), c[2] + 0.1 * r()]);
            }
        }
        let indices: Vec<[u32; 3]> = (0..n as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        let bvh = MeshBvh::build(&positions, &indices);
        let rays = (0..rays)
            .map(|i| {
                let o = [2.0 * r(), 2.0 * r(), 2.0 * r()];
                let d = match i % 17 {
                    3 => [0.0; 3],
                    11 => [f32::NAN, 1.0, 0.0],
                    _ => [r(), r(), r()],
                };
                // Some limits cut walks short, most are open.
                let t_max = if i % 5 == 0 { 0.5 + r().abs() } else { f32::INFINITY };
                (o, d, t_max)
            })
            .collect();
        (bvh, rays)
    }

    /// The interleaved queries answer each ray once, with the single-ray answer bit for bit.
    fn check(bvh: &MeshBvh, rays: &[Query]) {
        let mut closest = vec![None; rays.len()];
        let mut seen = vec![0; rays.len()];
        bvh.closest_batch(
            rays.len(),
            |i| rays[i],
            |i, hit| {
                closest[i] = hit.map(|(t, prim)| (t.to_bits(), prim));
                seen[i] += 1;
            },
        );
        let mut occluded = vec![None; rays.len()];
        bvh.occluded_batch(
            rays.len(),
            |i| rays[i],
            |i, hit| {
                assert!(occluded[i].replace(hit).is_none(), "ray {i} answered twice");
            },
        );
        assert!(seen.iter().all(|&k| k == 1), "every ray answered exactly once: {seen:?}");
        for (i, &(o, d, t_max)) in rays.iter().enumerate() {
            assert_eq!(closest[i], bvh.closest(o, d, t_max).map(|(t, prim)| (t.to_bits(), prim)), "closest, ray {i}");
            assert_eq!(occluded[i], Some(bvh.occluded(o, d, t_max)), "occluded, ray {i}");
        }
    }

    #[test]
    fn interleaved_walks_answer_as_single_rays_bit_for_bit() {
        let (bvh, rays) = soup(3000, 2000, 7);
        let hits = rays.iter().filter(|&&(o, d, t)| bvh.closest(o, d, t).is_some()).count();
        assert!(hits > 200 && hits < 1800, "the rays both hit and miss: {hits} of 2000");
        check(&bvh, &rays);
        // Fewer rays than lanes, one ray, none.
        for n in [LANES - 1, 1, 0] {
            check(&bvh, &rays[..n]);
        }
    }

    #[test]
    fn interleaved_walks_on_an_empty_and_a_one_triangle_mesh() {
        let empty = MeshBvh::build(&[], &[]);
        let rays = [([0.0, 0.0, -1.0], [0.0, 0.0, 1.0], f32::INFINITY); 20];
        bvh_answers(&empty, &rays, None, false);
        let one = MeshBvh::build(&[[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
        bvh_answers(&one, &rays, Some((1.0, 0)), true);
        check(&one, &rays);
    }

    /// Every ray of the batch gets `closest` and `occluded`.
    fn bvh_answers(bvh: &MeshBvh, rays: &[Query], closest: Option<(f32, u32)>, occluded: bool) {
        bvh.closest_batch(rays.len(), |i| rays[i], |_, hit| assert_eq!(hit, closest));
        bvh.occluded_batch(rays.len(), |i| rays[i], |_, hit| assert_eq!(hit, occluded));
    }
}
