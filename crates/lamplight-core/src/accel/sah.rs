//! Top-down binned SAH construction of a binary tree (Wald 2007), the first stage
//! of the BVH build; [`super::bvh`] then collapses it into 8-wide nodes. This is
//! the builder of both levels of the renderer's BVH: the scene's objects
//! ([`Costs::OBJECTS`]) and each triangle mesh's triangles ([`Costs::TRIANGLES`]).
//! The batch ray-casting BVH (`mesh_bvh.rs`) has its own; the module
//! documentation of [`super`] says why.
//!
//! Each split tries [`BINS`] bins per axis over the centroid bounds and keeps the
//! cheapest by the surface area heuristic, cost
//! `C_trav + (A_left n_left + A_right n_right) / A_parent`, against the leaf cost
//! `n` (costs in units of one primitive test; [`Costs`] sets `C_trav` and the
//! smallest leaf). Subtrees with many primitives are built in parallel (rayon).

use super::Aabb;
use crate::math::Vec3;

/// Number of SAH bins per axis.
pub const BINS: usize = 16;
/// Largest leaf: above this a node is always split.
pub const MAX_LEAF: usize = 8;

/// What the SAH weighs: the cost of descending into a node against testing primitives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Costs {
    /// Cost of one traversal step relative to one primitive test.
    pub traversal: f64,
    /// Primitives at or below which a node always becomes a leaf.
    pub min_leaf: usize,
}

impl Costs {
    /// Triangles: a primitive test costs about one 4-wide box test, pairs share a leaf.
    pub const TRIANGLES: Costs = Costs { traversal: 1.0, min_leaf: 2 };
    /// A scene's objects (spheres, quadrics, rectangles, meshes behind their own
    /// BVH): each test costs several 4-wide box tests, so splitting down to single
    /// objects pays (fewer instructions per render than [`Costs::TRIANGLES`] on
    /// the built-in scenes; `BENCHMARKS.md`).
    pub const OBJECTS: Costs = Costs { traversal: 0.5, min_leaf: 1 };
}
/// Subtrees larger than this are built on another thread.
const PARALLEL_THRESHOLD: usize = 4096;
/// Below this depth splits follow the SAH; deeper ones split at the median by
/// count, so the tree depth stays below `SAH_DEPTH + log2(n)` whatever the input
/// (the traversal stacks are sized for it).
pub const SAH_DEPTH: usize = 32;

/// A binary tree over primitive indices.
pub enum Tree {
    /// Up to [`MAX_LEAF`] primitives.
    Leaf {
        /// Bounds of the primitives.
        bounds: Aabb,
        /// Their indices.
        prims: Vec<u32>,
    },
    /// Two subtrees.
    Interior {
        /// Bounds of both.
        bounds: Aabb,
        /// The subtrees.
        children: Box<(Tree, Tree)>,
    },
}

impl Tree {
    /// Bounds of the subtree.
    pub fn bounds(&self) -> Aabb {
        match self {
            Tree::Leaf { bounds, .. } | Tree::Interior { bounds, .. } => *bounds,
        }
    }
}

#[derive(Clone, Copy)]
struct BuildPrim {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

/// Builds the tree over `bounds[i]` for primitive `i`; `bounds` must not be empty.
///
/// The primitives live in one array and a scratch array of the same length:
/// a split copies its node's primitives into the scratch, the left ones first,
/// each side in its order (a stable partition), and the children work on those
/// halves with the node's own as their scratch. A new pair of vectors per node
/// and its allocations were a fifth of loading a million-triangle mesh; the
/// order, and so the tree, is the one they gave.
pub fn build(bounds: &[Aabb], costs: Costs) -> Tree {
    let mut prims: Vec<BuildPrim> =
        bounds.iter().enumerate().map(|(i, b)| BuildPrim { bounds: *b, centroid: b.centroid(), index: i as u32 }).collect();
    let mut scratch = prims.clone();
    build_node(&mut prims, &mut scratch, 0, costs)
}

fn leaf(prims: &[BuildPrim], bounds: Aabb) -> Tree {
    Tree::Leaf { bounds, prims: prims.iter().map(|p| p.index).collect() }
}

/// Copies `prims` into `into`, those `goes_left` accepts first, each side in
/// its order; returns how many went left. One test per primitive: the right
/// ones fill `into` from its end backwards and are then turned around.
fn stable_partition(prims: &[BuildPrim], into: &mut [BuildPrim], goes_left: impl Fn(&BuildPrim) -> bool) -> usize {
    let (mut l, mut r) = (0, into.len());
    for p in prims {
        if goes_left(p) {
            into[l] = *p;
            l += 1;
        } else {
            r -= 1;
            into[r] = *p;
        }
    }
    into[l..].reverse();
    l
}

fn bin_of(value: f64, min: f64, scale: f64) -> usize {
    (((value - min) * scale) as usize).min(BINS - 1)
}

fn build_node(prims: &mut [BuildPrim], scratch: &mut [BuildPrim], depth: usize, costs: Costs) -> Tree {
    let bounds = prims.iter().fold(Aabb::EMPTY, |b, p| b.union(p.bounds));
    let n = prims.len();
    if n <= costs.min_leaf {
        return leaf(prims, bounds);
    }
    let centroid_bounds = prims.iter().fold(Aabb::EMPTY, |b, p| b.grow(p.centroid));
    let extent = centroid_bounds.extent();
    let parent_area = bounds.surface_area().max(f64::MIN_POSITIVE);

    let mut best: Option<(f64, usize, usize)> = None; // (cost, axis, bins left of the split)
    if depth < SAH_DEPTH {
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f64 / extent[axis];
            let mut bin_bounds = [Aabb::EMPTY; BINS];
            let mut bin_counts = [0usize; BINS];
            for p in prims.iter() {
                let b = bin_of(p.centroid[axis], centroid_bounds.min[axis], scale);
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
                    costs.traversal + (acc_box.surface_area() * acc_n as f64 + right_area[split] * right_count[split] as f64) / parent_area;
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, split));
                }
            }
        }
    }

    // The children's primitives, and the scratch each works with.
    let (left, right, left_scratch, right_scratch) = match best {
        Some((cost, axis, split)) if cost < n as f64 || n > MAX_LEAF => {
            let (scale, min) = (BINS as f64 / extent[axis], centroid_bounds.min[axis]);
            let k = stable_partition(prims, scratch, |p| bin_of(p.centroid[axis], min, scale) < split);
            let (left, right) = scratch.split_at_mut(k);
            let (left_scratch, right_scratch) = prims.split_at_mut(k);
            (left, right, left_scratch, right_scratch)
        }
        Some(_) => return leaf(prims, bounds),
        None if n <= MAX_LEAF => return leaf(prims, bounds),
        None => {
            // Coincident centroids, or too deep for the SAH: split at the median by
            // count along the widest centroid axis, so the tree stays balanced.
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            prims.sort_unstable_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
            let (left, right) = prims.split_at_mut(n / 2);
            let (left_scratch, right_scratch) = scratch.split_at_mut(n / 2);
            (left, right, left_scratch, right_scratch)
        }
    };
    let (left_tree, right_tree) = if n > PARALLEL_THRESHOLD {
        rayon::join(|| build_node(left, left_scratch, depth + 1, costs), || build_node(right, right_scratch, depth + 1, costs))
    } else {
        (build_node(left, left_scratch, depth + 1, costs), build_node(right, right_scratch, depth + 1, costs))
    };
    Tree::Interior { bounds, children: Box::new((left_tree, right_tree)) }
}
