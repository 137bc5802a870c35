//! The ray-casting BVH over one triangle mesh, in `f32`: 8-wide nodes whose leaves
//! hold the triangles themselves, four to a SIMD packet ([`Tri4`]), in leaf order.
//!
//! Unlike the renderer's [`super::Bvh`] (boxes over arbitrary `f64` shapes, tested
//! through a closure), everything a ray touches here is stored inline and in the
//! order traversal reads it: a node's eight child boxes (structure of arrays;
//! measured 10-15% faster than 4-wide), then the packets of a leaf, contiguous.
//! That is what makes batch ray casting fast; see `BENCHMARKS.md` ("Batch ray
//! casting vs Embree").
//!
//! The eight boxes are one AVX test on CPUs with AVX2 (detected at run time; the
//! whole traversal is then compiled for AVX2, 7-14 % more rays per second) and
//! two SSE tests elsewhere. Both give the same bits, so the answers do not depend
//! on the CPU (`slab.rs` tests it).
//!
//! Build: top-down binned SAH on the triangles' `f32` boxes, in place on one index
//! array (subtrees over 4096 triangles on other threads, rayon). This is not the
//! renderer's builder (`sah.rs`): the leaf cost and the precision differ, see
//! [`super`] for why there are two. A leaf of `n`
//! triangles costs `ceil(n / 4)` packet tests, so the SAH cost of a split is
//! `C_node + (A_l ceil(n_l/4) + A_r ceil(n_r/4)) / A`, against `ceil(n / 4)` for a
//! leaf; leaves hold at most [`MAX_LEAF`] triangles. Below depth [`SAH_DEPTH`]
//! splits are at the median, which bounds the depth whatever the input. The binary
//! tree is then collapsed into 8-wide nodes by repeatedly opening the child of
//! largest surface area.
//!
//! Box test: [`super::slab`], shared with the scene's BVH (an `f32` ray converts
//! to `f64` exactly), conservative so that no box a triangle hit lies in is
//! missed. Traversal, one ray at a time or several interleaved: `mesh_walk.rs`.

use glam::Vec3A;

use super::tri4::Tri4;

/// Marks a child reference as a leaf.
pub(super) const LEAF: u32 = 1 << 31;
/// A leaf reference holds its packet count in bits 28..31 ...
pub(super) const COUNT_SHIFT: u32 = 28;
/// ... and its first packet in bits 0..28.
pub(super) const FIRST_MASK: u32 = (1 << COUNT_SHIFT) - 1;
/// SAH bins per axis.
const BINS: usize = 16;
/// Largest leaf, in triangles (two packets).
pub const MAX_LEAF: usize = 8;
/// Cost of a binary node relative to one packet test.
const NODE_COST: f32 = 1.0;
/// Subtrees larger than this are built on another thread.
const PARALLEL: usize = 4096;
/// Depth below which splits follow the SAH (median splits deeper).
const SAH_DEPTH: usize = 48;
/// Children per node.
pub(super) const WIDTH: usize = 8;
/// Traversal stack: `WIDTH - 1` siblings per level of a tree at most
/// `SAH_DEPTH + 32` deep.
pub(super) const STACK: usize = (WIDTH - 1) * (SAH_DEPTH + 32) + WIDTH;

/// Eight child boxes (rows min x, y, z, max x, y, z) and references. An unused
/// slot has its bit clear in `valid` (and an empty box, `min = +inf`, `max = -inf`).
///
/// Aligned to a cache line, so that a node is exactly four lines: traversal of
/// incoherent rays waits mostly on node loads.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct Node {
    pub(super) planes: [[f32; WIDTH]; 6],
    /// Node index, or `LEAF | count << COUNT_SHIFT | first packet`.
    pub(super) child: [u32; WIDTH],
    /// Bit `i` set when child `i` exists (fits in the padding of the fourth line).
    pub(super) valid: u8,
}

const EMPTY_NODE: Node = Node {
    planes: [
        [f32::INFINITY; WIDTH],
        [f32::INFINITY; WIDTH],
        [f32::INFINITY; WIDTH],
        [f32::NEG_INFINITY; WIDTH],
        [f32::NEG_INFINITY; WIDTH],
        [f32::NEG_INFINITY; WIDTH],
    ],
    child: [0; WIDTH],
    valid: 0,
};

/// A triangle during the build: its box and index.
#[derive(Clone, Copy)]
struct Ref {
    lo: Vec3A,
    hi: Vec3A,
    index: u32,
}

/// The binary tree of the build; leaves are ranges of the reordered `Ref`s.
enum Bin {
    Leaf { lo: Vec3A, hi: Vec3A, start: usize, end: usize },
    Inner { lo: Vec3A, hi: Vec3A, kids: Box<[Bin; 2]> },
}

impl Bin {
    fn area(&self) -> f32 {
        let (Bin::Leaf { lo, hi, .. } | Bin::Inner { lo, hi, .. }) = self;
        half_area(*lo, *hi)
    }
}

fn half_area(lo: Vec3A, hi: Vec3A) -> f32 {
    let d = (hi - lo).max(Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// Packets needed for `n` triangles.
fn packets(n: usize) -> f32 {
    n.div_ceil(4) as f32
}

fn build_range(refs: &mut [Ref], offset: usize, depth: usize) -> Bin {
    let n = refs.len();
    let (mut lo, mut hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
    let (mut clo, mut chi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
    for r in refs.iter() {
        (lo, hi) = (lo.min(r.lo), hi.max(r.hi));
        let c = r.lo + r.hi;
        (clo, chi) = (clo.min(c), chi.max(c));
    }
    let leaf = Bin::Leaf { lo, hi, start: offset, end: offset + n };
    if n == 1 {
        return leaf;
    }
    let extent = chi - clo;
    let mut best: Option<(f32, usize, usize)> = None; // cost, axis, first right bin
    if depth < SAH_DEPTH {
        let parent = half_area(lo, hi).max(f32::MIN_POSITIVE);
        for axis in 0..3 {
            if !(extent[axis] > 0.0) {
                continue;
            }
            let scale = BINS as f32 / extent[axis];
            let mut bin_lo = [Vec3A::INFINITY; BINS];
            let mut bin_hi = [Vec3A::NEG_INFINITY; BINS];
            let mut count = [0usize; BINS];
            for r in refs.iter() {
                let b = bin_of(r, axis, clo[axis], scale);
                (bin_lo[b], bin_hi[b]) = (bin_lo[b].min(r.lo), bin_hi[b].max(r.hi));
                count[b] += 1;
            }
            let mut right_cost = [0.0f32; BINS];
            let (mut acc_lo, mut acc_hi, mut acc_n) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0);
            for b in (1..BINS).rev() {
                (acc_lo, acc_hi, acc_n) = (acc_lo.min(bin_lo[b]), acc_hi.max(bin_hi[b]), acc_n + count[b]);
                right_cost[b] = if acc_n == 0 { f32::NAN } else { half_area(acc_lo, acc_hi) * packets(acc_n) };
            }
            let (mut acc_lo, mut acc_hi, mut acc_n) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0);
            for split in 1..BINS {
                (acc_lo, acc_hi, acc_n) = (acc_lo.min(bin_lo[split - 1]), acc_hi.max(bin_hi[split - 1]), acc_n + count[split - 1]);
                if acc_n == 0 || acc_n == n {
                    continue;
                }
                let cost = NODE_COST + (half_area(acc_lo, acc_hi) * packets(acc_n) + right_cost[split]) / parent;
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, split));
                }
            }
        }
    }
    let mid = match best {
        Some((cost, axis, split)) if cost < packets(n) || n > MAX_LEAF => {
            let scale = BINS as f32 / extent[axis];
            partition(refs, |r| bin_of(r, axis, clo[axis], scale) < split)
        }
        _ if n <= MAX_LEAF => return leaf,
        _ => {
            // Coincident centroids or too deep for the SAH: median by count along
            // the widest centroid axis keeps the tree balanced.
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let mid = n / 2;
            refs.select_nth_unstable_by(mid, |a, b| (a.lo[axis] + a.hi[axis]).total_cmp(&(b.lo[axis] + b.hi[axis])));
            mid
        }
    };
    let (left, right) = refs.split_at_mut(mid);
    let kids = if n > PARALLEL {
        rayon::join(|| build_range(left, offset, depth + 1), || build_range(right, offset + mid, depth + 1))
    } else {
        (build_range(left, offset, depth + 1), build_range(right, offset + mid, depth + 1))
    };
    Bin::Inner { lo, hi, kids: Box::new([kids.0, kids.1]) }
}

#[inline]
fn bin_of(r: &Ref, axis: usize, min: f32, scale: f32) -> usize {
    (((r.lo[axis] + r.hi[axis] - min) * scale) as usize).min(BINS - 1)
}

/// Moves the refs satisfying `left` to the front; returns how many there are.
fn partition(refs: &mut [Ref], left: impl Fn(&Ref) -> bool) -> usize {
    let mut first = 0;
    for i in 0..refs.len() {
        if left(&refs[i]) {
            refs.swap(first, i);
            first += 1;
        }
    }
    first
}

/// A built hierarchy over a triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct MeshBvh {
    pub(super) nodes: Vec<Node>,
    pub(super) packets: Vec<Tri4>,
}

/// Size figures of a [`MeshBvh`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshBvhStats {
    /// 8-wide nodes.
    pub nodes: usize,
    /// Triangle packets (four triangles each, some lanes unused).
    pub packets: usize,
    /// Bytes of nodes and packets together.
    pub bytes: usize,
}

impl MeshBvh {
    /// Builds the hierarchy over triangles `indices[i]` of `positions` (indices
    /// must be in range and positions finite; the caller checks).
    pub fn build(positions: &[[f32; 3]], indices: &[[u32; 3]]) -> MeshBvh {
        if indices.is_empty() {
            return MeshBvh::default();
        }
        let tri = |i: usize| indices[i].map(|v| positions[v as usize]);
        let mut refs: Vec<Ref> = (0..indices.len())
            .map(|i| {
                let [a, b, c] = tri(i).map(Vec3A::from_array);
                Ref { lo: a.min(b).min(c), hi: a.max(b).max(c), index: i as u32 }
            })
            .collect();
        let root = build_range(&mut refs, 0, 0);
        let mut bvh = MeshBvh { nodes: Vec::with_capacity(indices.len() / 6 + 1), packets: Vec::with_capacity(indices.len() / 3 + 1) };
        let mut emit = Emitter { bvh: &mut bvh, refs: &refs, tri: &tri };
        match root {
            Bin::Leaf { .. } => {
                emit.bvh.nodes.push(EMPTY_NODE);
                emit.set_child(0, 0, &root);
            }
            Bin::Inner { .. } => {
                emit.collapse(&root);
            }
        }
        bvh
    }

    /// The length of the diagonal of the mesh's bounding box (0 when empty).
    pub fn diagonal(&self) -> f32 {
        let Some(root) = self.nodes.first() else { return 0.0 };
        let (mut lo, mut hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        for slot in (0..WIDTH).filter(|slot| root.valid & 1 << slot != 0) {
            let corner = |row: usize| Vec3A::new(root.planes[row][slot], root.planes[row + 1][slot], root.planes[row + 2][slot]);
            (lo, hi) = (lo.min(corner(0)), hi.max(corner(3)));
        }
        (hi - lo).length()
    }

    /// Node and packet counts and bytes.
    pub fn stats(&self) -> MeshBvhStats {
        MeshBvhStats {
            nodes: self.nodes.len(),
            packets: self.packets.len(),
            bytes: self.nodes.len() * size_of::<Node>() + self.packets.len() * size_of::<Tri4>(),
        }
    }
}

/// Writes the collapsed 8-wide nodes and the leaf packets.
struct Emitter<'a, F: Fn(usize) -> [[f32; 3]; 3]> {
    bvh: &'a mut MeshBvh,
    refs: &'a [Ref],
    tri: &'a F,
}

impl<F: Fn(usize) -> [[f32; 3]; 3]> Emitter<'_, F> {
    fn collapse(&mut self, tree: &Bin) -> u32 {
        let Bin::Inner { kids, .. } = tree else { unreachable!("collapse is called on inner nodes") };
        let mut open: Vec<&Bin> = vec![&kids[0], &kids[1]];
        while open.len() < WIDTH {
            let widest = open
                .iter()
                .enumerate()
                .filter(|(_, t)| matches!(t, Bin::Inner { .. }))
                .max_by(|a, b| a.1.area().total_cmp(&b.1.area()))
                .map(|(i, _)| i);
            let Some(i) = widest else { break };
            let Bin::Inner { kids, .. } = open.swap_remove(i) else { unreachable!() };
            open.push(&kids[0]);
            open.push(&kids[1]);
        }
        let index = self.bvh.nodes.len();
        self.bvh.nodes.push(EMPTY_NODE);
        for (slot, kid) in open.into_iter().enumerate() {
            self.set_child(index, slot, kid);
        }
        index as u32
    }

    fn set_child(&mut self, node: usize, slot: usize, tree: &Bin) {
        let (Bin::Leaf { lo, hi, .. } | Bin::Inner { lo, hi, .. }) = tree;
        for axis in 0..3 {
            self.bvh.nodes[node].planes[axis][slot] = lo[axis];
            self.bvh.nodes[node].planes[axis + 3][slot] = hi[axis];
        }
        let child = match tree {
            Bin::Leaf { start, end, .. } => {
                let first = self.bvh.packets.len();
                assert!(first <= FIRST_MASK as usize, "too many triangles for one BVH");
                for group in self.refs[*start..*end].chunks(4) {
                    let tris: Vec<_> = group.iter().map(|r| ((self.tri)(r.index as usize), r.index)).collect();
                    self.bvh.packets.push(Tri4::new(&tris));
                }
                LEAF | (((self.bvh.packets.len() - first) as u32) << COUNT_SHIFT) | first as u32
            }
            Bin::Inner { .. } => self.collapse(tree),
        };
        self.bvh.nodes[node].child[slot] = child;
        self.bvh.nodes[node].valid |= 1 << slot;
    }
}
