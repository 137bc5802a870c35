//! A bounding volume hierarchy built with the binned surface area heuristic.
//!
//! The BVH knows nothing of shapes: it is built from one [`Aabb`] per primitive and
//! traversed with a closure that intersects primitive `i` (the obvhs design). The
//! scene uses one over its objects, and every triangle mesh one over its triangles
//! (a two-level structure, so a mesh placed twice is stored once).
//!
//! Written by hand because it is the heart of the renderer's speed and must work on
//! `f64` boxes of any shape type; see `BENCHMARKS.md` for what it costs.
//!
//! Build: top-down, binned SAH (Wald 2007) with [`BINS`] bins per axis on the
//! centroid bounds, cost `C_trav + sum(A_child / A_parent * n_child)`; subtrees
//! with many primitives are built in parallel (rayon). Nodes are stored depth
//! first: the left child directly follows its parent, the right child's index is
//! stored. Traversal is ordered (near child first, by the ray's sign on the split
//! axis) with an explicit stack, and shrinks `t_max` as hits are found.

use super::Aabb;
use crate::math::Vec3;

/// Number of SAH bins per axis.
pub const BINS: usize = 16;
/// Primitives at or below which a node always becomes a leaf.
const MIN_LEAF: usize = 2;
/// Largest leaf made when the SAH cannot separate primitives (coincident centroids).
const MAX_LEAF: usize = 8;
/// Cost of one box test relative to one primitive test.
const TRAVERSAL_COST: f64 = 1.0;
/// Subtrees larger than this are built on another thread.
const PARALLEL_THRESHOLD: usize = 4096;

/// One node: a leaf holds `count > 0` primitives starting at `offset` in the index
/// array; an interior node (`count == 0`) has its left child next and its right
/// child at `offset`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    offset: u32,
    count: u16,
    axis: u8,
}

/// A built hierarchy over primitives `0..n`.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    indices: Vec<u32>,
}

/// Size figures of a built BVH.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BvhStats {
    /// Number of nodes.
    pub nodes: usize,
    /// Number of leaves.
    pub leaves: usize,
    /// Deepest leaf (root = 1).
    pub depth: usize,
    /// Bytes of nodes plus the primitive index array.
    pub bytes: usize,
}

enum Tree {
    Leaf { bounds: Aabb, prims: Vec<u32> },
    Interior { bounds: Aabb, axis: u8, children: Box<(Tree, Tree)> },
}

struct BuildPrim {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

impl Bvh {
    /// Builds the hierarchy over `bounds[i]` for primitive `i`. Every box must be
    /// finite (unbounded shapes are kept outside the BVH by the scene). Panics never:
    /// empty input gives an empty BVH whose traversal finds nothing.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        assert!(bounds.len() < u32::MAX as usize, "too many primitives for one BVH");
        if bounds.is_empty() {
            return Bvh::default();
        }
        let prims: Vec<BuildPrim> =
            bounds.iter().enumerate().map(|(i, b)| BuildPrim { bounds: *b, centroid: b.centroid(), index: i as u32 }).collect();
        let tree = build_tree(prims);
        let mut bvh = Bvh { nodes: Vec::with_capacity(2 * bounds.len() / MIN_LEAF + 1), indices: Vec::with_capacity(bounds.len()) };
        bvh.flatten(tree);
        bvh
    }

    fn flatten(&mut self, tree: Tree) -> usize {
        let at = self.nodes.len();
        match tree {
            Tree::Leaf { bounds, prims } => {
                self.nodes.push(Node { bounds, offset: self.indices.len() as u32, count: prims.len() as u16, axis: 0 });
                self.indices.extend_from_slice(&prims);
            }
            Tree::Interior { bounds, axis, children } => {
                self.nodes.push(Node { bounds, offset: 0, count: 0, axis });
                let (left, right) = *children;
                self.flatten(left);
                let right_at = self.flatten(right);
                self.nodes[at].offset = right_at as u32;
            }
        }
        at
    }

    /// Bounds of everything in the hierarchy ([`Aabb::EMPTY`] if nothing).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// Node count, leaves, depth and memory.
    pub fn stats(&self) -> BvhStats {
        let mut leaves = 0;
        let mut depth = 0;
        let mut stack = vec![(0usize, 1usize)];
        while let Some((i, d)) = stack.pop() {
            let Some(node) = self.nodes.get(i) else { break };
            if node.count > 0 {
                leaves += 1;
                depth = depth.max(d);
            } else {
                stack.push((i + 1, d + 1));
                stack.push((node.offset as usize, d + 1));
            }
        }
        BvhStats { nodes: self.nodes.len(), leaves, depth, bytes: self.nodes.len() * std::mem::size_of::<Node>() + self.indices.len() * 4 }
    }

    /// Visits, nearest first, every primitive whose leaf box the ray enters within
    /// `(t_min, t_max)`. `intersect(i, t_max)` tests primitive `i` and returns the
    /// parameter of a hit closer than `t_max`, which then becomes the new `t_max`.
    /// Returns the final `t_max` (unchanged if nothing was hit).
    #[inline]
    pub fn traverse(&self, origin: Vec3, dir: Vec3, t_min: f64, mut t_max: f64, mut intersect: impl FnMut(u32, f64) -> Option<f64>) -> f64 {
        if self.nodes.is_empty() {
            return t_max;
        }
        let inv_dir = dir.recip();
        let negative = [dir.x < 0.0, dir.y < 0.0, dir.z < 0.0];
        let mut stack = [0u32; 64];
        let mut top = 0usize;
        let mut current = 0usize;
        loop {
            let node = &self.nodes[current];
            if node.bounds.hit_interval(origin, inv_dir, t_min, t_max).is_some() {
                if node.count > 0 {
                    let start = node.offset as usize;
                    for &prim in &self.indices[start..start + node.count as usize] {
                        if let Some(t) = intersect(prim, t_max) {
                            t_max = t_max.min(t);
                        }
                    }
                } else {
                    let (near, far) = if negative[node.axis as usize] {
                        (node.offset as usize, current + 1)
                    } else {
                        (current + 1, node.offset as usize)
                    };
                    stack[top] = far as u32;
                    top += 1;
                    current = near;
                    continue;
                }
            }
            if top == 0 {
                return t_max;
            }
            top -= 1;
            current = stack[top] as usize;
        }
    }

    /// True as soon as `occluded(i)` is true for a primitive whose leaf box the ray
    /// enters within `(t_min, t_max)`: the any-hit query for shadow rays.
    #[inline]
    pub fn any(&self, origin: Vec3, dir: Vec3, t_min: f64, t_max: f64, mut occluded: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv_dir = dir.recip();
        let mut stack = [0u32; 64];
        let mut top = 0usize;
        let mut current = 0usize;
        loop {
            let node = &self.nodes[current];
            if node.bounds.hit_interval(origin, inv_dir, t_min, t_max).is_some() {
                if node.count > 0 {
                    let start = node.offset as usize;
                    if self.indices[start..start + node.count as usize].iter().any(|&p| occluded(p)) {
                        return true;
                    }
                } else {
                    stack[top] = node.offset;
                    top += 1;
                    current += 1;
                    continue;
                }
            }
            if top == 0 {
                return false;
            }
            top -= 1;
            current = stack[top] as usize;
        }
    }
}

fn leaf(prims: Vec<BuildPrim>, bounds: Aabb) -> Tree {
    Tree::Leaf { bounds, prims: prims.into_iter().map(|p| p.index).collect() }
}

/// Recursive binned-SAH build. Depth stays below the traversal stack size because
/// a split that the SAH cannot make falls back to a median split by count.
fn build_tree(mut prims: Vec<BuildPrim>) -> Tree {
    let bounds = prims.iter().fold(Aabb::EMPTY, |b, p| b.union(p.bounds));
    let n = prims.len();
    if n <= MIN_LEAF {
        return leaf(prims, bounds);
    }
    let centroid_bounds = prims.iter().fold(Aabb::EMPTY, |b, p| b.grow(p.centroid));
    let extent = centroid_bounds.extent();
    let leaf_cost = n as f64;
    let parent_area = bounds.surface_area().max(f64::MIN_POSITIVE);

    // Best SAH split over all three axes.
    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins left of split)
    for axis in 0..3 {
        if !(extent[axis] > 0.0) {
            continue;
        }
        let scale = BINS as f64 / extent[axis];
        let mut bin_bounds = [Aabb::EMPTY; BINS];
        let mut bin_counts = [0usize; BINS];
        for p in &prims {
            let b = (((p.centroid[axis] - centroid_bounds.min[axis]) * scale) as usize).min(BINS - 1);
            bin_bounds[b] = bin_bounds[b].union(p.bounds);
            bin_counts[b] += 1;
        }
        let mut right_area = [0.0; BINS];
        let mut right_count = [0usize; BINS];
        let (mut acc_box, mut acc_n) = (Aabb::EMPTY, 0);
        for b in (1..BINS).rev() {
            acc_box = acc_box.union(bin_bounds[b]);
            acc_n += bin_counts[b];
            right_area[b] = acc_box.surface_area();
            right_count[b] = acc_n;
        }
        let (mut acc_box, mut acc_n) = (Aabb::EMPTY, 0);
        for split in 1..BINS {
            acc_box = acc_box.union(bin_bounds[split - 1]);
            acc_n += bin_counts[split - 1];
            if acc_n == 0 || right_count[split] == 0 {
                continue;
            }
            let cost =
                TRAVERSAL_COST + (acc_box.surface_area() * acc_n as f64 + right_area[split] * right_count[split] as f64) / parent_area;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, split));
            }
        }
    }

    let (left, right, axis) = match best {
        Some((cost, axis, split)) if cost < leaf_cost || n > MAX_LEAF => {
            let scale = BINS as f64 / extent[axis];
            let min = centroid_bounds.min[axis];
            let (left, right): (Vec<_>, Vec<_>) =
                prims.into_iter().partition(|p| ((((p.centroid[axis] - min) * scale) as usize).min(BINS - 1)) < split);
            (left, right, axis)
        }
        Some(_) => return leaf(prims, bounds),
        None if n <= MAX_LEAF => return leaf(prims, bounds),
        None => {
            // All centroids coincide: split by count so the tree stays balanced.
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let right = prims.split_off(n / 2);
            (prims, right, axis)
        }
    };
    let (left_tree, right_tree) =
        if n > PARALLEL_THRESHOLD { rayon::join(|| build_tree(left), || build_tree(right)) } else { (build_tree(left), build_tree(right)) };
    Tree::Interior { bounds, axis: axis as u8, children: Box::new((left_tree, right_tree)) }
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
        }
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
