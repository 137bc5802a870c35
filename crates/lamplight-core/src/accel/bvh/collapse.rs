//! The binary SAH tree ([`super::sah`]) made into 8-wide nodes.
//!
//! A node takes up to eight descendants of a binary interior node: the child
//! with the largest surface area is opened (replaced by its two children)
//! until there are eight or only leaves are left. Nodes are laid out depth
//! first, each node's subtrees after it in slot order, and leaves' primitive
//! indices in the same order; so each subtree's nodes and indices are one
//! contiguous run.
//!
//! That makes the large subtrees independent: near the root of a big tree
//! (more than [`PARALLEL_MIN`] primitives, the top [`PARALLEL_LEVELS`]
//! levels) each interior child is laid out on its own thread from index 0,
//! and the runs are then appended in slot order with their node and index
//! references shifted: the very layout one thread makes. The binary tree is
//! freed the same way, in parallel. On a million triangles, laying out and
//! freeing the tree on one thread took a fifth of loading the mesh
//! (`BENCHMARKS.md`, session 27).

use rayon::prelude::*;

use super::super::sah::Tree;
use super::{Node, LEAF, WIDTH};

/// Primitives below which a tree is laid out on one thread.
const PARALLEL_MIN: usize = 1 << 16;
/// Levels of nodes whose interior children are laid out in parallel.
const PARALLEL_LEVELS: usize = 2;

/// Nodes and the leaves' primitive indices, laid out depth first.
#[derive(Default)]
pub(super) struct Layout {
    pub(super) nodes: Vec<Node>,
    pub(super) indices: Vec<u32>,
}

impl Layout {
    /// The layout of `tree` over `count` primitives, root node first; the tree
    /// is freed.
    pub(super) fn of(tree: Tree, count: usize) -> Layout {
        // A parallel layout reserves its exact node count itself.
        let parallel = count >= PARALLEL_MIN;
        let nodes = if parallel { Vec::new() } else { Vec::with_capacity(count / WIDTH + 1) };
        let mut layout = Layout { nodes, indices: Vec::with_capacity(count) };
        match &tree {
            Tree::Leaf { .. } => {
                // A single leaf still gets a root node, so traversal has one shape.
                layout.nodes.push(Node::EMPTY);
                layout.set_child(0, 0, &tree, 0);
            }
            Tree::Interior { .. } => {
                let levels = if parallel { PARALLEL_LEVELS } else { 0 };
                layout.collapse(&tree, levels);
            }
        }
        free(tree, if parallel { 6 } else { 0 });
        layout
    }

    /// Appends the node of interior `tree` and its subtrees; returns its index.
    /// Interior children of the top `levels` levels are laid out in parallel.
    fn collapse(&mut self, tree: &Tree, levels: usize) -> usize {
        let (kids, n) = open(tree);
        let kids = &kids[..n];
        let index = self.nodes.len();
        self.nodes.push(Node::EMPTY);
        if levels == 0 {
            for (slot, kid) in kids.iter().enumerate() {
                self.set_child(index, slot, kid, 0);
            }
            return index;
        }
        // Each interior child's run, made apart from index 0.
        let runs: Vec<Option<Layout>> = kids
            .par_iter()
            .map(|kid| {
                matches!(kid, Tree::Interior { .. }).then(|| {
                    let mut run = Layout::default();
                    run.collapse(kid, levels - 1);
                    run
                })
            })
            .collect();
        // Room for all of them at once, in huge pages: growing the vector by
        // doubling copied it and faulted its pages in a few at a time.
        let total = self.nodes.len() + runs.iter().flatten().map(|run| run.nodes.len()).sum::<usize>();
        if self.nodes.capacity() < total {
            let mut nodes = crate::pages::with_capacity(total);
            nodes.extend_from_slice(&self.nodes);
            self.nodes = nodes;
        }
        for (slot, (kid, run)) in kids.iter().zip(runs).enumerate() {
            match run {
                None => self.set_child(index, slot, kid, 0),
                Some(run) => {
                    self.nodes[index].set_box(slot, &kid.bounds());
                    let (node_base, index_base) = (self.nodes.len() as u32, self.indices.len() as u32);
                    self.nodes[index].child[slot] = node_base;
                    self.nodes.extend(run.nodes.into_iter().map(|mut node| {
                        for s in 0..WIDTH {
                            if node.valid & (1 << s) != 0 {
                                node.child[s] += if node.child[s] & LEAF != 0 { index_base } else { node_base };
                            }
                        }
                        node
                    }));
                    self.indices.extend_from_slice(&run.indices);
                }
            }
        }
        index
    }

    /// Stores `tree` as child `slot` of node `node`, recursing into interior trees.
    fn set_child(&mut self, node: usize, slot: usize, tree: &Tree, levels: usize) {
        self.nodes[node].set_box(slot, &tree.bounds());
        match tree {
            Tree::Leaf { prims, .. } => {
                self.nodes[node].child[slot] = LEAF | self.indices.len() as u32;
                self.nodes[node].count[slot] = prims.len() as u8;
                self.indices.extend_from_slice(prims);
            }
            Tree::Interior { .. } => {
                let index = self.collapse(tree, levels);
                self.nodes[node].child[slot] = index as u32;
            }
        }
    }
}

/// Up to eight descendants of interior `tree` and their number: its two
/// children, then the widest interior one (by surface area; the last of
/// equals) opened in turn, the opened one's place taken by the last (a
/// `swap_remove`) and its children appended.
fn open(tree: &Tree) -> ([&Tree; WIDTH], usize) {
    let Tree::Interior { children, .. } = tree else { unreachable!("collapse is called on interior trees") };
    let mut kids = [&children.0; WIDTH];
    let mut area = [0.0; WIDTH];
    kids[1] = &children.1;
    let mut n = 2;
    for (a, kid) in area.iter_mut().zip(&kids[..n]) {
        *a = kid.bounds().surface_area();
    }
    while n < WIDTH {
        let mut widest = None;
        for i in 0..n {
            if matches!(kids[i], Tree::Interior { .. }) && widest.is_none_or(|w: usize| area[i].total_cmp(&area[w]).is_ge()) {
                widest = Some(i);
            }
        }
        let Some(i) = widest else { break };
        let Tree::Interior { children, .. } = kids[i] else { unreachable!() };
        kids[i] = kids[n - 1];
        area[i] = area[n - 1];
        kids[n - 1] = &children.0;
        kids[n] = &children.1;
        area[n - 1] = children.0.bounds().surface_area();
        area[n] = children.1.bounds().surface_area();
        n += 1;
    }
    (kids, n)
}

/// Frees `tree`, its top `levels` levels' halves on two threads.
fn free(tree: Tree, levels: usize) {
    match tree {
        Tree::Interior { children, .. } if levels > 0 => {
            let (a, b) = *children;
            rayon::join(|| free(a, levels - 1), || free(b, levels - 1));
        }
        tree => drop(tree),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::sah::{self, Costs};
    use crate::accel::Aabb;
    use crate::math::Vec3;

    /// A node as comparable data: its planes (as bits), children, counts and mask.
    type NodeData = (Vec<u32>, [u32; WIDTH], [u8; WIDTH], u8);

    /// A layout as comparable data: its nodes and its primitive indices.
    fn flat(layout: &Layout) -> (Vec<NodeData>, Vec<u32>) {
        let nodes =
            layout.nodes.iter().map(|n| (n.planes.iter().flatten().map(|p| p.to_bits()).collect(), n.child, n.count, n.valid)).collect();
        (nodes, layout.indices.clone())
    }

    fn boxes(n: usize) -> Vec<Aabb> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| {
                let c = Vec3::new(next() * 200.0 - 100.0, next() * 50.0, next() * 10.0);
                let h = Vec3::new(next(), next(), next()) * 0.5;
                Aabb::new(c - h, c + h)
            })
            .collect()
    }

    #[test]
    fn the_parallel_layout_is_the_one_thread_layout() {
        let bounds = boxes(PARALLEL_MIN + 12_345);
        for costs in [Costs::TRIANGLES, Costs::OBJECTS] {
            let tree = sah::build(&bounds, costs);
            let mut one = Layout::default();
            one.collapse(&tree, 0);
            let mut parallel = Layout::default();
            parallel.collapse(&tree, PARALLEL_LEVELS + 1);
            let (one, parallel) = (flat(&one), flat(&parallel));
            assert!(one.0.len() > 10_000 && one.1.len() == bounds.len());
            assert!(one == parallel, "the parallel layout differs");
        }
    }
}
