//! An 8-wide bounding volume hierarchy with SIMD box tests.
//!
//! The BVH knows nothing of shapes: it is built from one [`Aabb`] per primitive and
//! traversed with a closure that intersects primitive `i` (the obvhs design). The
//! scene uses one over its objects, and every triangle mesh one over its triangles
//! (a two-level structure, so a mesh placed twice is stored once).
//!
//! Written by hand because it is the heart of the renderer's speed; see
//! `BENCHMARKS.md` for what each step gained.
//!
//! Build: a binary tree by binned SAH ([`super::sah`]), collapsed into nodes of
//! up to eight children by repeatedly opening the child with the largest surface
//! area (`bvh/collapse.rs`, in parallel near the root of a large tree). A node
//! stores its children's boxes as `f32` structure-of-arrays, so one ray is
//! tested against eight boxes in one AVX test on CPUs with AVX2 (detected at
//! run time; the whole traversal, with the closure inlined into it, is then
//! compiled for AVX2), two SSE tests elsewhere, with the same bits either way
//! ([`super::slab::test8`]). Eight children rather than four halve the levels a
//! ray descends through over a scene's objects: fewer box tests, pushes and pops
//! per ray (`BENCHMARKS.md`, issue 24).
//!
//! Exactness: geometry is `f64`, the boxes `f32`. Boxes are rounded outwards and
//! tested by [`super::slab`], which is conservative for `f64` rays (it may report a
//! box the ray misses, never miss one it enters).
//!
//! Traversal is ordered (nearest child first, by entry distance), with an explicit
//! stack; entries farther than the closest hit so far are skipped when popped.
//!
//! A handful of primitives (at most [`FLAT_MAX`], a Cornell box) are stored
//! flat instead: nodes of eight single-primitive leaves, all tested, the entered
//! ones visited nearest first, with no stack or per-level ordering. Measured with
//! callgrind: the Cornell box's 8 objects need 12 % fewer instructions flat than
//! as a tree, but luxo's 20 or so (quadrics in loose boxes) need 9 % more: the tree
//! skips boxes beyond the nearest hit before testing them; hence the small limit.

use std::mem::MaybeUninit;

use super::sah::{self, Costs};
use super::slab::{farthest_first, has_avx2, test8, SlabRay, WIDEN};
use super::Aabb;
use crate::math::Vec3;

mod collapse;
use collapse::Layout;

/// Marks a child reference as a leaf: low bits are the first index in `indices`.
const LEAF: u32 = 1 << 31;
/// Children per node.
const WIDTH: usize = 8;
/// Traversal stack size: `WIDTH - 1` pending siblings per level of a tree whose
/// depth the SAH build bounds by `SAH_DEPTH + 32`.
const STACK: usize = (WIDTH - 1) * (sah::SAH_DEPTH + 32) + WIDTH;
/// Most primitives stored flat (see the module documentation).
pub const FLAT_MAX: usize = 12;

/// Up to eight children: their boxes (structure of arrays) and references.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
struct Node {
    /// `[min_x, min_y, min_z, max_x, max_y, max_z]`, each for the eight children.
    planes: [[f32; WIDTH]; 6],
    /// Child node index, or `LEAF | first index` for a leaf.
    child: [u32; WIDTH],
    /// Primitive count of leaf children (0 for interior children).
    count: [u8; WIDTH],
    /// Bit `i` set when child `i` exists.
    valid: u8,
}

impl Node {
    /// No children.
    const EMPTY: Node = Node { planes: [[0.0; WIDTH]; 6], child: [0; WIDTH], count: [0; WIDTH], valid: 0 };

    /// Makes child `slot` valid with box `b`, rounded outwards to `f32`.
    fn set_box(&mut self, slot: usize, b: &Aabb) {
        let planes =
            [round_down(b.min.x), round_down(b.min.y), round_down(b.min.z), round_up(b.max.x), round_up(b.max.y), round_up(b.max.z)];
        for (row, value) in planes.into_iter().enumerate() {
            self.planes[row][slot] = value;
        }
        self.valid |= 1 << slot;
    }

    /// The entry distances of the children and the mask of those entered before `t_max`.
    #[inline(always)]
    fn test<const AVX2: bool>(&self, ray: &SlabRay, t_max: f32) -> ([f32; WIDTH], u32) {
        let (enter, mask) = test8::<AVX2>(ray, &self.planes, t_max);
        (enter, mask & self.valid as u32)
    }
}

/// The primitive test of a closest-hit walk: `visit(i, t_max)` tests primitive
/// `i` and returns the parameter of a hit closer than `t_max`. Closures are
/// visitors; a caller whose test must be compiled into the walk (the scene's
/// query) implements it with an `#[inline(always)]` method instead, since a
/// closure's body is inlined only where LLVM's cost model agrees, and a large
/// one called from the walk's two places was not (issue 24).
pub(crate) trait Visit {
    /// Tests primitive `prim` against `(t_min, t_max)` of the walk.
    fn visit(&mut self, prim: u32, t_max: f64) -> Option<f64>;
}

/// The primitive test of an any-hit walk: `occluded(i)` is true when primitive
/// `i` blocks the ray. Closures are such tests; the scene's shadow query
/// implements it with an `#[inline(always)]` method, as [`Visit`] explains.
pub(crate) trait Occlude {
    /// Whether primitive `prim` blocks the walk's ray.
    fn occluded(&mut self, prim: u32) -> bool;
}

impl<F: FnMut(u32) -> bool> Occlude for F {
    #[inline(always)]
    fn occluded(&mut self, prim: u32) -> bool {
        self(prim)
    }
}

impl<F: FnMut(u32, f64) -> Option<f64>> Visit for F {
    #[inline(always)]
    fn visit(&mut self, prim: u32, t_max: f64) -> Option<f64> {
        self(prim, t_max)
    }
}

/// A built hierarchy over primitives `0..n`.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    indices: Vec<u32>,
    bounds: Option<Aabb>,
    /// Every node holds only single-primitive leaves and all are tested.
    flat: bool,
}

/// Size figures of a built BVH.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BvhStats {
    /// Number of 8-wide nodes.
    pub nodes: usize,
    /// Number of leaves.
    pub leaves: usize,
    /// Deepest leaf (root node = 1).
    pub depth: usize,
    /// Bytes of nodes plus the primitive index array.
    pub bytes: usize,
}

/// `f32` below or equal to `x` (outward rounding of a box's minimum).
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f as f64 > x {
        f.next_down()
    } else {
        f
    }
}

/// `f32` above or equal to `x` (outward rounding of a box's maximum).
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x {
        f.next_up()
    } else {
        f
    }
}

impl Bvh {
    /// Builds the hierarchy over `bounds[i]` for primitive `i`, costed for
    /// triangles ([`Costs::TRIANGLES`]). Every box must be finite (unbounded shapes
    /// are kept outside the BVH by the scene). Empty input gives an empty BVH whose
    /// traversal finds nothing.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        Bvh::build_with(bounds, Costs::TRIANGLES)
    }

    /// [`Bvh::build`] with the SAH weighing primitive tests by `costs`.
    pub fn build_with(bounds: &[Aabb], costs: Costs) -> Bvh {
        assert!(bounds.len() < LEAF as usize, "too many primitives for one BVH");
        if bounds.is_empty() {
            return Bvh::default();
        }
        if bounds.len() <= FLAT_MAX {
            return Bvh::flat(bounds);
        }
        let tree = sah::build(bounds, costs);
        let root = tree.bounds();
        let Layout { nodes, indices } = Layout::of(tree, bounds.len());
        Bvh { nodes, indices, bounds: Some(root), flat: false }
    }

    /// Up to [`FLAT_MAX`] primitives, eight per node, each its own leaf.
    fn flat(bounds: &[Aabb]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(bounds.len().div_ceil(WIDTH)),
            indices: (0..bounds.len() as u32).collect(),
            bounds: Some(bounds.iter().fold(Aabb::EMPTY, |all, b| all.union(*b))),
            flat: true,
        };
        for (i, b) in bounds.iter().enumerate() {
            let (node, slot) = (i / WIDTH, i % WIDTH);
            if slot == 0 {
                bvh.nodes.push(Node::EMPTY);
            }
            bvh.nodes[node].set_box(slot, b);
            bvh.nodes[node].child[slot] = LEAF | i as u32;
            bvh.nodes[node].count[slot] = 1;
        }
        bvh
    }

    /// Bounds of everything in the hierarchy ([`Aabb::EMPTY`] if nothing).
    pub fn bounds(&self) -> Aabb {
        self.bounds.unwrap_or(Aabb::EMPTY)
    }

    /// Node count, leaves, depth and memory.
    pub fn stats(&self) -> BvhStats {
        let (mut leaves, mut depth) = (0, 0);
        // A flat hierarchy's nodes are side by side, each a root.
        let roots = if self.flat { self.nodes.len() } else { 1 };
        let mut stack: Vec<(usize, usize)> = (0..roots).map(|i| (i, 1)).collect();
        while let Some((i, d)) = stack.pop() {
            let Some(node) = self.nodes.get(i) else { break };
            for slot in 0..WIDTH {
                if node.valid & (1 << slot) == 0 {
                    continue;
                }
                if node.child[slot] & LEAF != 0 {
                    leaves += 1;
                    depth = depth.max(d);
                } else {
                    stack.push((node.child[slot] as usize, d + 1));
                }
            }
        }
        BvhStats { nodes: self.nodes.len(), leaves, depth, bytes: self.nodes.len() * std::mem::size_of::<Node>() + self.indices.len() * 4 }
    }

    /// [`Bvh::traverse`] of a flat hierarchy: every box tested, the entered ones
    /// sorted by entry distance and visited until one lies beyond the closest hit.
    #[inline(always)]
    fn traverse_flat<const AVX2: bool>(&self, ray: &SlabRay, mut t_max: f64, mut intersect: impl Visit) -> f64 {
        // Uninitialized, as the walk's stack: zero-filling it was the query's
        // single hottest instruction in a path-traced Cornell box (issue 24).
        let mut entered = [const { MaybeUninit::<(f32, u32)>::uninit() }; FLAT_MAX];
        let mut n = 0;
        for node in &self.nodes {
            let (enter, mut mask) = node.test::<AVX2>(ray, t_max as f32);
            while mask != 0 {
                let slot = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                // Insertion by entry distance, nearest first.
                let t = enter[slot];
                let mut j = n;
                while j > 0 {
                    // SAFETY: entries below `n` are written.
                    let before = unsafe { entered[j - 1].assume_init() };
                    if before.0 <= t {
                        break;
                    }
                    entered[j].write(before);
                    j -= 1;
                }
                entered[j].write((t, node.child[slot] & !LEAF));
                n += 1;
            }
        }
        for entry in &entered[..n] {
            // SAFETY: entries below `n` are written.
            let (enter, first) = unsafe { entry.assume_init() };
            if f64::from(enter) * (1.0 - f64::from(WIDEN)) > t_max {
                break;
            }
            if let Some(t) = intersect.visit(self.indices[first as usize], t_max) {
                t_max = t_max.min(t);
            }
        }
        t_max
    }

    /// Visits, nearest first, every primitive whose leaf box the ray enters within
    /// `(t_min, t_max)`. `intersect(i, t_max)` tests primitive `i` and returns the
    /// parameter of a hit closer than `t_max`, which then becomes the new `t_max`.
    /// Returns the final `t_max` (unchanged if nothing was hit).
    #[inline]
    pub fn traverse(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, intersect: impl FnMut(u32, f64) -> Option<f64>) -> f64 {
        if self.nodes.is_empty() {
            return t_max;
        }
        #[cfg(target_arch = "x86_64")]
        if has_avx2() {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.traverse_avx2(origin, dir, t_min, t_max, intersect) };
        }
        self.traverse_with::<false>(origin, dir, t_min, t_max, intersect)
    }

    /// [`Bvh::traverse`] compiled for AVX2, the closure inlined into it.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn traverse_avx2(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, intersect: impl FnMut(u32, f64) -> Option<f64>) -> f64 {
        self.traverse_with::<true>(origin, dir, t_min, t_max, intersect)
    }

    /// [`Bvh::traverse`] for a caller that has chosen the box test itself: the
    /// scene's queries, compiled whole for AVX2 so that this walk is inlined
    /// into them (`Scene::first_intersect`). `AVX2` must be set only on CPUs
    /// that have it.
    #[inline(always)]
    pub(crate) fn traverse_in<const AVX2: bool>(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, intersect: impl Visit) -> f64 {
        if self.nodes.is_empty() {
            return t_max;
        }
        self.traverse_with::<AVX2>(origin, dir, t_min, t_max, intersect)
    }

    #[inline(always)]
    fn traverse_with<const AVX2: bool>(&self, origin: Vec3, dir: Vec3, t_min: f64, mut t_max: f64, mut intersect: impl Visit) -> f64 {
        let ray = SlabRay::new(origin, dir, t_min);
        if self.flat {
            return self.traverse_flat::<AVX2>(&ray, t_max, intersect);
        }
        // Uninitialized: zero-filling the stack cost more than a short traversal.
        let mut stack = [const { MaybeUninit::<(u32, f32, u8)>::uninit() }; STACK];
        let mut order = [(0f32, 0u32); WIDTH];
        let mut top = 0usize;
        let mut current = 0u32; // a node index, or LEAF | first with `leaf_count`
        let mut leaf_count = 0u8;
        loop {
            if current & LEAF != 0 {
                let first = (current & !LEAF) as usize;
                for &prim in &self.indices[first..first + leaf_count as usize] {
                    if let Some(t) = intersect.visit(prim, t_max) {
                        t_max = t_max.min(t);
                    }
                }
            } else {
                let node = &self.nodes[current as usize];
                let (enter, mask) = node.test::<AVX2>(&ray, t_max as f32);
                if mask != 0 && mask & (mask - 1) == 0 {
                    // One child entered (the usual case): nothing to order.
                    let slot = mask.trailing_zeros() as usize;
                    current = node.child[slot];
                    leaf_count = node.count[slot];
                    continue;
                }
                let second = mask & mask.wrapping_sub(1);
                if mask != 0 && second & (second - 1) == 0 {
                    // Two children entered: push the farther, continue with the nearer
                    // (farthest_first's order, ties to the higher slot, without its loop).
                    let (a, b) = (mask.trailing_zeros() as usize, second.trailing_zeros() as usize);
                    let (far, near) = if enter[a] < enter[b] { (b, a) } else { (a, b) };
                    stack[top].write((node.child[far], enter[far], node.count[far]));
                    top += 1;
                    current = node.child[near];
                    leaf_count = node.count[near];
                    continue;
                }
                if mask != 0 {
                    // Push the entered children farthest first, then continue with the nearest.
                    let n = farthest_first(&enter, mask, &mut order);
                    for &(t, slot) in &order[..n - 1] {
                        stack[top].write((node.child[slot as usize], t, node.count[slot as usize]));
                        top += 1;
                    }
                    let nearest = order[n - 1].1 as usize;
                    current = node.child[nearest];
                    leaf_count = node.count[nearest];
                    continue;
                }
            }
            // Pop the next entry that may still hold something nearer than t_max.
            loop {
                if top == 0 {
                    return t_max;
                }
                top -= 1;
                // SAFETY: entries below `top` were written by the pushes above.
                let (child, enter, count) = unsafe { stack[top].assume_init() };
                if f64::from(enter) * (1.0 - f64::from(WIDEN)) <= t_max {
                    current = child;
                    leaf_count = count;
                    break;
                }
            }
        }
    }

    /// True as soon as `occluded(i)` is true for a primitive whose leaf box the ray
    /// enters within `(t_min, t_max)`: the any-hit query for shadow rays.
    #[inline]
    pub fn any(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, occluded: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        #[cfg(target_arch = "x86_64")]
        if has_avx2() {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.any_avx2(origin, dir, t_min, t_max, occluded) };
        }
        self.any_with::<false>(origin, dir, t_min, t_max, occluded)
    }

    /// [`Bvh::any`] compiled for AVX2, the closure inlined into it.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn any_avx2(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, occluded: impl FnMut(u32) -> bool) -> bool {
        self.any_with::<true>(origin, dir, t_min, t_max, occluded)
    }

    /// [`Bvh::any`] for a caller that has chosen the box test itself (see
    /// [`Bvh::traverse_in`]).
    #[inline(always)]
    pub(crate) fn any_in<const AVX2: bool>(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, occluded: impl Occlude) -> bool {
        !self.nodes.is_empty() && self.any_with::<AVX2>(origin, dir, t_min, t_max, occluded)
    }

    #[inline(always)]
    fn any_with<const AVX2: bool>(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, mut occluded: impl Occlude) -> bool {
        let ray = SlabRay::new(origin, dir, t_min);
        let t_max32 = t_max as f32;
        if self.flat {
            for node in &self.nodes {
                let (_, mut mask) = node.test::<AVX2>(&ray, t_max32);
                while mask != 0 {
                    let slot = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    if occluded.occluded(self.indices[(node.child[slot] & !LEAF) as usize]) {
                        return true;
                    }
                }
            }
            return false;
        }
        let mut stack = [const { MaybeUninit::<u32>::uninit() }; STACK];
        stack[0].write(0); // the root node
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            // SAFETY: entries below `top` were written before.
            let node = &self.nodes[unsafe { stack[top].assume_init() } as usize];
            let (_, mut mask) = node.test::<AVX2>(&ray, t_max32);
            while mask != 0 {
                let slot = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let child = node.child[slot];
                if child & LEAF != 0 {
                    let first = (child & !LEAF) as usize;
                    for &p in &self.indices[first..first + node.count[slot] as usize] {
                        if occluded.occluded(p) {
                            return true;
                        }
                    }
                } else {
                    stack[top].write(child);
                    top += 1;
                }
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers for tests (splitmix64).
    fn rand(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Boxes as "primitives" hit at their slab entry: the BVH must find exactly the
    /// nearest one that brute force finds.
    #[test]
    fn traversal_matches_brute_force() {
        let mut s = 7u64;
        let boxes: Vec<Aabb> = (0..2000)
            .map(|_| {
                let c = Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 100.0;
                Aabb::new(c, c + Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 3.0)
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        let stats = bvh.stats();
        assert!(stats.depth < 40, "depth {}", stats.depth);
        for _ in 0..500 {
            let o = Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 120.0 - 10.0;
            let d = (Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) - 0.5).normalize();
            let test =
                |i: u32, t_max: f64| boxes[i as usize].hit(&crate::ray::Ray::new(o, d), 0.0, t_max).map(|(t, _)| t).filter(|&t| t < t_max);
            let brute = (0..boxes.len() as u32).filter_map(|i| test(i, f64::INFINITY)).fold(f64::INFINITY, f64::min);
            let found = bvh.traverse(o, d, 0.0, f64::INFINITY, test);
            assert_eq!(found, brute);
            assert_eq!(bvh.any(o, d, 0.0, f64::INFINITY, |i| test(i, f64::INFINITY).is_some()), brute.is_finite());
            // Both box tests visit the same primitives in the same order.
            let visits = |avx2: bool| {
                let mut seen = Vec::new();
                let mut record = |i: u32, t_max: f64| {
                    seen.push(i);
                    test(i, t_max)
                };
                let t = if avx2 {
                    bvh.traverse_with::<true>(o, d, 0.0, f64::INFINITY, &mut record)
                } else {
                    bvh.traverse_with::<false>(o, d, 0.0, f64::INFINITY, &mut record)
                };
                (t, seen)
            };
            if has_avx2() {
                assert_eq!(visits(true), visits(false));
            }
        }
    }

    #[test]
    fn flat_hierarchies_match_brute_force() {
        let mut s = 11u64;
        for n in [1, 3, 4, 5, 9, FLAT_MAX] {
            let boxes: Vec<Aabb> = (0..n)
                .map(|_| {
                    let c = Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 10.0;
                    Aabb::new(c, c + Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 4.0)
                })
                .collect();
            let bvh = Bvh::build(&boxes);
            assert!(bvh.flat);
            assert_eq!(bvh.stats().leaves, n);
            let mut visited = 0;
            for _ in 0..2000 {
                let o = Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) * 16.0 - 3.0;
                let d = (Vec3::new(rand(&mut s), rand(&mut s), rand(&mut s)) - 0.5).normalize();
                let test = |i: u32, t_max: f64| {
                    boxes[i as usize].hit(&crate::ray::Ray::new(o, d), 0.0, t_max).map(|(t, _)| t).filter(|&t| t < t_max)
                };
                let brute = (0..n as u32).filter_map(|i| test(i, f64::INFINITY)).fold(f64::INFINITY, f64::min);
                let found = bvh.traverse(o, d, 0.0, f64::INFINITY, |i, t_max| {
                    visited += 1;
                    test(i, t_max)
                });
                assert_eq!(found, brute);
                assert_eq!(bvh.any(o, d, 0.0, f64::INFINITY, |i| test(i, f64::INFINITY).is_some()), brute.is_finite());
            }
            // Boxes beyond the nearest hit are skipped: fewer visits than n per ray.
            assert!(visited < 2000 * n.max(2) - 1000, "{n} boxes: {visited} visits");
        }
        assert!(!Bvh::build(&vec![Aabb::new(Vec3::ZERO, Vec3::ONE); FLAT_MAX + 1]).flat);
    }

    #[test]
    fn coincident_and_empty_inputs() {
        let same = vec![Aabb::new(Vec3::ZERO, Vec3::ONE); 10_000];
        let bvh = Bvh::build(&same);
        assert!(bvh.stats().depth < 64);
        let mut count = 0;
        bvh.traverse(Vec3::new(0.5, 0.5, -1.0), Vec3::Z, 0.0, f64::INFINITY, |_, _| {
            count += 1;
            None
        });
        assert_eq!(count, 10_000, "every primitive visited once");
        let empty = Bvh::build(&[]);
        assert_eq!(empty.traverse(Vec3::ZERO, Vec3::Z, 0.0, 5.0, |_, _| Some(1.0)), 5.0);
    }
}
