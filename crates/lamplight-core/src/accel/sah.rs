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
    // Two arrays of 80 bytes a primitive, written at once: in huge pages.
    let mut prims: Vec<BuildPrim> = crate::pages::with_capacity(bounds.len());
    prims.extend(bounds.iter().enumerate().map(|(i, b)| BuildPrim { bounds: *b, centroid: b.centroid(), index: i as u32 }));
    let mut scratch = crate::pages::with_capacity(prims.len());
    scratch.extend_from_slice(&prims);
    let span = prims.iter().fold(Span::EMPTY, Span::add);
    build_node(&mut prims, &mut scratch, span, 0, costs)
}

/// The bounds of a node's primitives and of their centroids, each folded in
/// the primitives' order.
#[derive(Clone, Copy)]
struct Span {
    bounds: Aabb,
    centroids: Aabb,
}

impl Span {
    const EMPTY: Span = Span { bounds: Aabb::EMPTY, centroids: Aabb::EMPTY };

    #[inline(always)]
    fn add(self, p: &BuildPrim) -> Span {
        Span { bounds: self.bounds.union(p.bounds), centroids: self.centroids.grow(p.centroid) }
    }
}

fn leaf(prims: &[BuildPrim], bounds: Aabb) -> Tree {
    Tree::Leaf { bounds, prims: prims.iter().map(|p| p.index).collect() }
}

/// Copies `prims` into `into`, those `goes_left` accepts first, each side in
/// its order; returns how many went left and each side's [`Span`]. One test
/// per primitive: the right ones fill `into` from its end backwards and are
/// then turned around. The spans are folded here, in each side's order, so the
/// children need not read their primitives twice more for them: the same
/// values as the children's own folds.
#[inline(always)]
fn stable_partition(prims: &[BuildPrim], into: &mut [BuildPrim], goes_left: impl Fn(&BuildPrim) -> bool) -> (usize, Span, Span) {
    let (mut l, mut r) = (0, into.len());
    let (mut left, mut right) = (Span::EMPTY, Span::EMPTY);
    for p in prims {
        if goes_left(p) {
            into[l] = *p;
            l += 1;
            left = left.add(p);
        } else {
            r -= 1;
            into[r] = *p;
            right = right.add(p);
        }
    }
    into[l..].reverse();
    (l, left, right)
}

/// The bin of a centroid coordinate `value`: `floor((value - min) scale)`,
/// clamped to the bins (a NaN to the first). The same answer as
/// `(x as usize).min(BINS - 1)` for every `x`, but the clamp is two plain
/// comparisons and the conversion one instruction: the saturating `as` took a
/// sixth of the build's time on a million triangles.
#[inline(always)]
fn bin_of(value: f64, min: f64, scale: f64) -> usize {
    let x = (value - min) * scale;
    let x = if x > 0.0 { x } else { 0.0 };
    let x = if x < (BINS - 1) as f64 { x } else { (BINS - 1) as f64 };
    // SAFETY: `x` is in `[0, BINS - 1]`, so its integer part fits an `i32`.
    unsafe { x.to_int_unchecked::<i32>() as usize }
}

/// One node and, recursively, its subtrees: [`build_node_in`], compiled for
/// AVX2 where the CPU has it. The arithmetic is the same IEEE operations either
/// way, so the tree is too; the NaN-aware `f64::min` and `max` of the box
/// unions, which baseline x86-64 makes of five SSE2 instructions each, take
/// three there (`vminsd`, `vcmpunordsd`, `vblendvpd`): a million-triangle
/// build is 12-20 % faster (`BENCHMARKS.md`, issue 24).
fn build_node(prims: &mut [BuildPrim], scratch: &mut [BuildPrim], span: Span, depth: usize, costs: Costs) -> Tree {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2.
        return unsafe { build_node_avx2(prims, scratch, span, depth, costs) };
    }
    build_node_in(prims, scratch, span, depth, costs, build_node)
}

/// [`build_node_in`] compiled for AVX2; its subtrees go through [`build_node`] again.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn build_node_avx2(prims: &mut [BuildPrim], scratch: &mut [BuildPrim], span: Span, depth: usize, costs: Costs) -> Tree {
    build_node_in(prims, scratch, span, depth, costs, build_node)
}

/// A node's builder, which [`build_node_in`] calls for its subtrees.
type BuildNode = fn(&mut [BuildPrim], &mut [BuildPrim], Span, usize, Costs) -> Tree;

/// Splits `prims`, whose [`Span`] is `span`, by the SAH, or makes them a leaf;
/// the subtrees are built by `recurse`.
#[inline(always)]
fn build_node_in(prims: &mut [BuildPrim], scratch: &mut [BuildPrim], span: Span, depth: usize, costs: Costs, recurse: BuildNode) -> Tree {
    let Span { bounds, centroids: centroid_bounds } = span;
    let n = prims.len();
    if n <= costs.min_leaf {
        return leaf(prims, bounds);
    }
    let extent = centroid_bounds.extent();
    let parent_area = bounds.surface_area().max(f64::MIN_POSITIVE);

    // The cheapest split so far: (cost, axis, bins left of the split), kept as
    // plain values chosen without a branch (which split wins next is what the
    // core cannot predict).
    let (mut found, mut best_cost, mut best_axis, mut best_split) = (false, 0.0, 0, 0);
    if depth < SAH_DEPTH {
        // The three axes' bins in one pass: their unions are three independent
        // chains where one axis at a time was one, each waiting for the last
        // store to its bin. Each bin folds its primitives in their order, as one
        // axis at a time did. An axis of no extent bins nonsense, never read.
        let scale = [0, 1, 2].map(|axis| BINS as f64 / extent[axis]);
        let mut bins = [([Aabb::EMPTY; BINS], [0usize; BINS]); 3];
        for p in prims.iter() {
            for (axis, (bin_bounds, bin_counts)) in bins.iter_mut().enumerate() {
                let b = bin_of(p.centroid[axis], centroid_bounds.min[axis], scale[axis]);
                bin_bounds[b] = bin_bounds[b].union(p.bounds);
                bin_counts[b] += 1;
            }
        }
        for (axis, (bin_bounds, bin_counts)) in bins.iter().enumerate() {
            if extent[axis] <= 0.0 {
                continue;
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
                let take = !found | (cost < best_cost);
                found |= take;
                best_cost = if take { cost } else { best_cost };
                best_axis = if take { axis } else { best_axis };
                best_split = if take { split } else { best_split };
            }
        }
    }

    let best = found.then_some((best_cost, best_axis, best_split));

    // The children's primitives, and the scratch each works with.
    let (left, right, left_scratch, right_scratch, left_span, right_span) = match best {
        Some((cost, axis, split)) if cost < n as f64 || n > MAX_LEAF => {
            let (scale, min) = (BINS as f64 / extent[axis], centroid_bounds.min[axis]);
            let (k, left_span, right_span) = stable_partition(prims, scratch, |p| bin_of(p.centroid[axis], min, scale) < split);
            let (left, right) = scratch.split_at_mut(k);
            let (left_scratch, right_scratch) = prims.split_at_mut(k);
            (left, right, left_scratch, right_scratch, left_span, right_span)
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
            let (left_span, right_span) = (left.iter().fold(Span::EMPTY, Span::add), right.iter().fold(Span::EMPTY, Span::add));
            (left, right, left_scratch, right_scratch, left_span, right_span)
        }
    };
    let (left_tree, right_tree) = if n > PARALLEL_THRESHOLD {
        rayon::join(
            || recurse(left, left_scratch, left_span, depth + 1, costs),
            || recurse(right, right_scratch, right_span, depth + 1, costs),
        )
    } else {
        (recurse(left, left_scratch, left_span, depth + 1, costs), recurse(right, right_scratch, right_span, depth + 1, costs))
    };
    Tree::Interior { bounds, children: Box::new((left_tree, right_tree)) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree as plain data: each node's bounds (as bits) and each leaf's primitives.
    fn flatten(tree: &Tree, out: &mut Vec<(Vec<u64>, Vec<u32>)>) {
        let bits = |b: Aabb| b.min.to_array().into_iter().chain(b.max.to_array()).map(f64::to_bits).collect::<Vec<_>>();
        match tree {
            Tree::Leaf { bounds, prims } => out.push((bits(*bounds), prims.clone())),
            Tree::Interior { bounds, children } => {
                out.push((bits(*bounds), Vec::new()));
                flatten(&children.0, out);
                flatten(&children.1, out);
            }
        }
    }

    /// [`build_node`] compiled for baseline x86-64 all the way down.
    fn build_node_baseline(prims: &mut [BuildPrim], scratch: &mut [BuildPrim], span: Span, depth: usize, costs: Costs) -> Tree {
        build_node_in(prims, scratch, span, depth, costs, build_node_baseline)
    }

    #[test]
    fn bins_are_the_saturating_cast_clamped() {
        let last = (BINS - 1) as f64;
        for x in [f64::NAN, f64::NEG_INFINITY, -1e300, -1.0, -0.0, 0.0, 0.5, 1.0, 14.999, last, last + 0.5, 16.0, 1e300, f64::INFINITY] {
            assert_eq!(bin_of(x, 0.0, 1.0), (x as usize).min(BINS - 1), "{x}");
        }
        // Below the minimum, and a scale that overflows.
        assert_eq!(bin_of(1.0, 2.0, 1.0), 0);
        assert_eq!(bin_of(1.0, 0.5, f64::INFINITY), BINS - 1);
        assert_eq!(bin_of(0.5, 0.5, f64::INFINITY), 0);
    }

    #[test]
    fn the_avx2_build_makes_the_baseline_tree() {
        // Scattered boxes of all sizes, some sharing a centroid, some touching zero.
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let bounds: Vec<Aabb> = (0..20_000)
            .map(|i| {
                let c = if i % 7 == 0 { Vec3::ZERO } else { Vec3::new(next() * 100.0 - 50.0, next() * 2.0, next() * 0.01) };
                let h = Vec3::new(next(), next() * 10.0, 0.0);
                Aabb::new(c - h, c + h)
            })
            .collect();
        for costs in [Costs::TRIANGLES, Costs::OBJECTS] {
            let mut prims: Vec<BuildPrim> =
                bounds.iter().enumerate().map(|(i, b)| BuildPrim { bounds: *b, centroid: b.centroid(), index: i as u32 }).collect();
            let mut scratch = prims.clone();
            let (mut baseline, mut dispatched) = (Vec::new(), Vec::new());
            let span = prims.iter().fold(Span::EMPTY, Span::add);
            flatten(&build_node_baseline(&mut prims, &mut scratch, span, 0, costs), &mut baseline);
            flatten(&build(&bounds, costs), &mut dispatched);
            assert!(baseline.len() > 1000);
            assert!(baseline == dispatched, "the two compilations built different trees");
        }
    }
}
