//! A light buffer (Haines and Greenberg 1986): for a light that leaves one
//! point, a cube of direction cells around that point, each listing the objects
//! whose bounding boxes lie, seen from the point, in the cell's directions.
//!
//! A shadow ray towards the light can only be blocked by an object on its
//! segment, and every point of that segment lies, seen from the light, in the
//! direction the ray arrives from. So the ray needs to test only the objects of
//! one cell instead of walking the BVH: in the `spheres` scene about one ball
//! and the floor, against about 400 instructions of walk. The answer (is any
//! opaque object on the segment?) does not depend on the order objects are
//! tested in, so it is the same bit for bit; what has to hold is that the cell
//! lists every object the segment meets.
//!
//! **Why the lists are complete.** Cube face `f` (axis `a`, sign `s`) holds the
//! directions `d` with `s d_a >= |d_b|, |d_c|`, at face coordinates
//! `u = d_b / |d_a|`, `v = d_c / |d_a|` in `[-1, 1]`, cut into `N x N` cells.
//! - An object whose box comes within `near` of the light goes on a list every
//!   ray tests ([`LightBuffer::always`]), unless its surface stays `near` away
//!   from the light: a lamp shade around its bulb, whose box holds the bulb
//!   but whose surface covers only half the directions. Such a box is halved
//!   into eight parts that tile it (they share the midpoints), and again, up
//!   to [`REFINE_DEPTH`] times; a part the shape rules out
//!   ([`crate::shapes::Shape::may_meet`] false for the part grown by a
//!   millionth of the box, which covers the rounding of a reported hit) is
//!   dropped, and each kept part whose grown box is at least `near` from the
//!   light is listed as a box of its own, by the rule below. Every surface
//!   point the shape can report lies in a kept part, so the object is listed
//!   in every cell that holds one; a kept part within `near` at the last depth
//!   puts the object back on `always`. Parts larger than a quarter of their
//!   distance are halved further ([`SPLIT_RATIO`]).
//! - Any other box is cut to the part where `s (x_a - L_a) >= near / 2`, which
//!   holds every box point seen in the face's directions: such a point `q` has
//!   `|q - L| >= near` and a direction with `|d_a| >= 1/sqrt(3)` (less a tiny
//!   angle, below). Over that part, `u` and `v` are ratios with a positive
//!   denominator, so their extremes are at corners; the ranges, widened by
//!   [`PAD`], give the cells the object is listed in.
//! - A shadow ray `o + t w`, `0 < t < T`, is looked up by its direction `-w`.
//!   The light lies off the ray's line by `m` (the origin is pushed off the
//!   surface, and `w` is rounded), so a point `q` of the segment at distance
//!   `r >= near` from the light is seen at an angle of at most `m / r` from
//!   `-w`, provided the segment stops before it passes the light. The query
//!   checks both ([`LightBuffer::cell_of`]): `m <= near * ANGLE / 2` and
//!   `T <= (L - o).w + near / 2`; a ray that fails them walks the BVH. Then
//!   every segment point at least `near` from the light is seen within
//!   `0.51 ANGLE` of `-w`, lies in the cut box of `-w`'s face, and has face
//!   coordinates within `6 x 0.51 ANGLE` of `-w`'s (both directions have
//!   `|d_a| > 0.57`), inside [`PAD`] `= 4 ANGLE`.
//!
//! Written by hand: no crate builds one, and it is part of the tracer's heart.

use super::Aabb;
use crate::math::Vec3;

/// Cells per side of each cube face: a cell spans about 1.4 degrees. 128 lists
/// fewer objects per cell, but its 786 KB of spans per light measured slower
/// (spheres 400 against 395 ms) and took 1.9 ms instead of 0.5 to build.
const N: usize = 64;
/// Largest angle (radians) between a ray's lookup direction and the direction
/// of a point of its segment that the lists allow for.
const ANGLE: f64 = 1e-4;
/// Widening of each object's face-coordinate ranges (module doc).
const PAD: f64 = 4.0 * ANGLE;
/// `near` as a fraction of the scene's size: objects this close to the light
/// are tested by every ray.
const NEAR_FRACTION: f64 = 1e-3;
/// Most objects a buffer is built for; larger scenes keep the BVH walk.
const MAX_OBJECTS: usize = 4096;
/// Most list entries a buffer may hold: 8 per cell on average (768 KB). Cells
/// that list more objects than that are no faster than the BVH walk.
const MAX_ENTRIES: usize = 8 * 6 * N * N;
/// Most objects a cell lists: a ray through a longer list walks the BVH
/// instead, whose cost grows with the logarithm of the count, not the count.
const MAX_CELL: u32 = 32;
/// Most objects near the light, which every ray tests; more and the scene
/// keeps the walk for this light.
const MAX_ALWAYS: usize = 8;
/// A cell's span when its list is too long: rays through it walk the BVH.
const WALK: [u32; 2] = [u32::MAX, u32::MAX];

/// The direction cells around one point and the objects listed in each.
#[derive(Clone, Debug)]
pub struct LightBuffer {
    /// The point the light leaves from.
    centre: Vec3,
    /// Objects whose boxes come closer than this are on [`LightBuffer::always`].
    near: f64,
    /// Objects every ray tests.
    always: Vec<u32>,
    /// Each cell's list: its start and end in `items` (`6 N^2` cells).
    spans: Vec<[u32; 2]>,
    /// The cells' lists, one after the other.
    items: Vec<u32>,
}

/// The axis and sign of cube face `f`, and its two other axes.
fn face_axes(f: usize) -> (usize, f64, usize, usize) {
    let a = f / 2;
    let sign = if f.is_multiple_of(2) { 1.0 } else { -1.0 };
    (a, sign, (a + 1) % 3, (a + 2) % 3)
}

/// The cell along one face coordinate that holds `u` in `[-1, 1]` (clamped to
/// the face, NaN to cell 0; truncation floors the clamped value without a libm
/// call). Clamped as floats first, so the conversion needs none of the range
/// checks of a saturating `as usize` (15 instructions a call, 1 % of a Whitted
/// render's instructions; BENCHMARKS.md).
#[inline(always)]
fn cell_index(u: f64) -> usize {
    // `max` turns NaN into 0.
    let x = ((u + 1.0) * (0.5 * N as f64)).max(0.0).min((N - 1) as f64);
    // SAFETY: `x` is finite and in `[0, N - 1]`, inside `i32`'s range.
    unsafe { x.to_int_unchecked::<i32>() as usize }
}

/// The cells `[lo, hi]` along one face coordinate whose span meets `[u0, u1]`.
fn cell_range(u0: f64, u1: f64) -> Option<(usize, usize)> {
    let (u0, u1) = (u0 - PAD, u1 + PAD);
    if u1 < -1.0 || u0 > 1.0 {
        return None;
    }
    Some((cell_index(u0), cell_index(u1)))
}

/// The distance from `p` to the box `b` (0 inside).
fn distance(p: Vec3, b: &Aabb) -> f64 {
    (p.clamp(b.min, b.max) - p).length()
}

/// The cells of face `f` (ranges along its `u` and `v` axes) that hold the
/// directions from `centre` to the points of box `b` at least `near / 2` out
/// along the face's axis, widened by [`PAD`]; `None` when there are none.
fn face_block(centre: Vec3, near: f64, b: &Aabb, f: usize) -> Option<((usize, usize), (usize, usize))> {
    let (a, sign, ub, vb) = face_axes(f);
    // The box's extent along the face axis, seen from the centre.
    let (lo, hi) = (sign * (b.min[a] - centre[a]), sign * (b.max[a] - centre[a]));
    let (x0, x1) = (lo.min(hi).max(0.5 * near), lo.max(hi));
    if x1 < x0 {
        return None;
    }
    let ratio_range = |axis: usize| {
        let (y0, y1) = (b.min[axis] - centre[axis], b.max[axis] - centre[axis]);
        let r = [y0 / x0, y0 / x1, y1 / x0, y1 / x1];
        (r.iter().copied().fold(f64::INFINITY, f64::min), r.iter().copied().fold(f64::NEG_INFINITY, f64::max))
    };
    let (u0, u1) = ratio_range(ub);
    let (v0, v1) = ratio_range(vb);
    Some((cell_range(u0, u1)?, cell_range(v0, v1)?))
}

/// Halvings of an object's box when it surrounds a light (module doc).
const REFINE_DEPTH: u32 = 6;
/// A part is halved again while its size times this exceeds its distance from the light.
/// At 640x360 `luxo`'s shade is then tested by 23 thousand shadow rays instead
/// of 139 thousand, and the render takes 474.5 million instructions instead of
/// 511.5; 1 gave 51 thousand tests (486.8 M), 8 gave 17 thousand but took 2 ms
/// to build (477.1 M), and 16 ran into [`MAX_PARTS`] (514 M).
const SPLIT_RATIO: f64 = 4.0;
/// Most parts of one box looked at; beyond, the object is tested by every ray.
const MAX_PARTS: usize = 20_000;

/// The cells (a flag per cell, `6 N^2`) that may hold the surface of an object
/// whose box `b` comes within `near` of `centre`, from parts of the box, each
/// grown by a millionth of its size and kept where `meets` says the surface
/// may reach it. A part within `near` of the light is halved (up to
/// [`REFINE_DEPTH`] times); so is one large for its distance
/// ([`SPLIT_RATIO`]), for a tighter list. `None` when the surface may come
/// within `near` of the light, or the box takes more than [`MAX_PARTS`] parts.
fn surface_cells(centre: Vec3, near: f64, b: &Aabb, meets: impl Fn(&Aabb) -> bool) -> Option<Vec<bool>> {
    let size = b.extent().max_element() + 1e-3 * b.min.abs().max(b.max.abs()).max_element();
    let grow = |part: &Aabb| Aabb::new(part.min - Vec3::splat(1e-6 * size), part.max + Vec3::splat(1e-6 * size));
    // First only the parts near the light, a few per level: most shapes that
    // surround a light (a room) reach it, and answer here.
    let mut stack = vec![(*b, 0)];
    while let Some((part, depth)) = stack.pop() {
        let grown = grow(&part);
        if distance(centre, &grown) < near && meets(&grown) {
            if depth == REFINE_DEPTH {
                return None;
            }
            stack.extend(halves(&part).map(|h| (h, depth + 1)));
        }
    }
    let (mut stack, mut leaves, mut looked) = (vec![(*b, 0)], Vec::new(), 0);
    while let Some((part, depth)) = stack.pop() {
        looked += 1;
        if looked > MAX_PARTS {
            return None;
        }
        let grown = grow(&part);
        if !meets(&grown) {
            continue;
        }
        let away = distance(centre, &grown);
        if away < near || (depth < REFINE_DEPTH && SPLIT_RATIO * grown.extent().max_element() > away) {
            stack.extend(halves(&part).map(|h| (h, depth + 1)));
        } else {
            leaves.push(grown);
        }
    }
    let mut cells = vec![false; 6 * N * N];
    for leaf in &leaves {
        for f in 0..6 {
            let Some(((i0, i1), (j0, j1))) = face_block(centre, near, leaf, f) else { continue };
            for j in j0..=j1 {
                cells[(f * N + j) * N + i0..=(f * N + j) * N + i1].fill(true);
            }
        }
    }
    Some(cells)
}

/// The eight halves of `part`, which tile it exactly: they share the midpoints.
fn halves(part: &Aabb) -> impl Iterator<Item = Aabb> + '_ {
    let mid = (part.min + part.max) * 0.5;
    (0..8).map(move |k| {
        let pick = |bit: usize, axis: usize| if k & bit == 0 { (part.min[axis], mid[axis]) } else { (mid[axis], part.max[axis]) };
        let ((x0, x1), (y0, y1), (z0, z1)) = (pick(1, 0), pick(2, 1), pick(4, 2));
        Aabb { min: Vec3::new(x0, y0, z0), max: Vec3::new(x1, y1, z1) }
    })
}

/// The runs of flagged cells in each row of each face: `(face, row, (first, last))`.
fn row_runs(cells: &[bool]) -> impl Iterator<Item = (usize, usize, (usize, usize))> + '_ {
    cells.chunks(N).enumerate().flat_map(|(row, flags)| {
        let (f, j) = (row / N, row % N);
        let mut i = 0;
        std::iter::from_fn(move || {
            let start = i + flags[i..].iter().position(|&x| x)?;
            let end = start + flags[start..].iter().position(|&x| !x).unwrap_or(N - start);
            i = end;
            Some((f, j, (start, end - 1)))
        })
    })
}

impl LightBuffer {
    /// The buffer around `centre` for the objects with boxes `boxes` (numbered
    /// as the slice) that `listed` accepts (those that can block a shadow ray),
    /// in a scene whose extent (largest coordinate magnitude) is `scale`; `None`
    /// for more than `MAX_OBJECTS` (4,096) boxes or lists too long. `meets(i,
    /// region)` is false only where object `i` has no surface point in the box
    /// `region` ([`crate::shapes::Shape::may_meet`]); `|_, _| true` is safe.
    pub fn build(
        centre: Vec3,
        boxes: &[Aabb],
        listed: impl Fn(usize) -> bool,
        meets: impl Fn(usize, &Aabb) -> bool,
        scale: f64,
    ) -> Option<LightBuffer> {
        if boxes.len() > MAX_OBJECTS || !centre.is_finite() || !scale.is_finite() {
            return None;
        }
        let near = NEAR_FRACTION * scale.max(centre.abs().max_element());
        if !(near > 0.0) {
            return None;
        }
        let mut always = Vec::new();
        // Each listed object's block of cells per face, `(object, face, [i0, i1], [j0, j1])`.
        let mut blocks = Vec::new();
        let mut entries = 0usize;
        for (i, b) in boxes.iter().enumerate().filter(|&(i, _)| listed(i)) {
            let finite = b.min.is_finite() && b.max.is_finite();
            let near_light = finite && distance(centre, b) < near;
            if near_light {
                // The box surrounds the light; the surface itself may not.
                if let Some(cells) = surface_cells(centre, near, b, |part| meets(i, part)) {
                    for (f, j, (i0, i1)) in row_runs(&cells) {
                        entries += i1 - i0 + 1;
                        blocks.push((i as u32, f, (i0, i1), (j, j)));
                    }
                    if entries > MAX_ENTRIES {
                        return None;
                    }
                    continue;
                }
            }
            if !finite || near_light {
                always.push(i as u32);
                if always.len() > MAX_ALWAYS {
                    return None;
                }
                continue;
            }
            for f in 0..6 {
                let Some(((i0, i1), (j0, j1))) = face_block(centre, near, b, f) else { continue };
                entries += (i1 - i0 + 1) * (j1 - j0 + 1);
                if entries > MAX_ENTRIES {
                    return None;
                }
                blocks.push((i as u32, f, (i0, i1), (j0, j1)));
            }
        }
        // Counted, then filled: each cell's objects in object order.
        let mut count = vec![0u32; 6 * N * N];
        let cells_of = |&(_, f, (i0, i1), (j0, j1)): &(u32, usize, (usize, usize), (usize, usize))| {
            (j0..=j1).flat_map(move |j| ((f * N + j) * N + i0)..=((f * N + j) * N + i1))
        };
        for block in &blocks {
            for cell in cells_of(block) {
                count[cell] += 1;
            }
        }
        let mut spans = Vec::with_capacity(6 * N * N);
        let mut next = 0u32;
        for &n in &count {
            if n > MAX_CELL {
                spans.push(WALK);
            } else {
                spans.push([next, next]);
                next += n;
            }
        }
        let mut items = vec![0u32; next as usize];
        for block in &blocks {
            for cell in cells_of(block) {
                if spans[cell] != WALK {
                    let end = &mut spans[cell][1];
                    items[*end as usize] = block.0;
                    *end += 1;
                }
            }
        }
        Some(LightBuffer { centre, near, always, spans, items })
    }

    /// The objects every ray tests: those whose boxes come within `near` of the light.
    #[inline]
    pub fn always(&self) -> &[u32] {
        &self.always
    }

    /// The objects a shadow ray from `origin` along the unit `dir`, over
    /// `(0, length)`, may meet besides [`LightBuffer::always`]; `None` when the
    /// segment does not end at the light closely enough for the lists to be
    /// complete (module doc), and the caller must walk the BVH.
    #[inline(always)]
    pub fn cell_of(&self, origin: Vec3, dir: Vec3, length: f64) -> Option<&[u32]> {
        let to_light = self.centre - origin;
        // The light's distance from the ray's line, squared, and how far along it lies.
        let along = to_light.dot(dir);
        let off = to_light.cross(dir).length_squared();
        let allowed = 0.5 * self.near * ANGLE;
        if !(off <= allowed * allowed && length <= along + 0.5 * self.near) {
            return None;
        }
        self.list_towards(-dir)
    }

    /// The objects a ray leaving the centre itself along `dir` may meet besides
    /// [`LightBuffer::always`]; `None` where the cell's list was too long. Every
    /// point of such a ray is seen from the centre exactly in the direction
    /// `dir`, so the lists are complete for it (module doc, with `m = 0`, and a
    /// ray that cannot pass the point it leaves): the eye's buffer
    /// (`eye_buffer.rs`) is looked up so.
    #[inline(always)]
    pub fn cell_from_centre(&self, dir: Vec3) -> Option<&[u32]> {
        self.list_towards(dir)
    }

    /// The point the cells are seen from.
    pub fn centre(&self) -> Vec3 {
        self.centre
    }

    /// Orders every cell's list by `key` of its objects, nearest first (ties
    /// by object number), for a caller that may stop partway along a list.
    pub fn sort_lists_by(&mut self, key: impl Fn(u32) -> f64) {
        for &[start, end] in &self.spans {
            if let Some(list) = self.items.get_mut(start as usize..end as usize) {
                list.sort_by(|&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)));
            }
        }
        self.always.sort_by(|&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)));
    }

    /// The list of cell `cell` (as [`LightBuffer::cells_from_centre`]
    /// numbers it); `None` where it was too long.
    #[inline(always)]
    pub(crate) fn list_of_cell(&self, cell: u32) -> Option<&[u32]> {
        let [start, end] = *self.spans.get(cell as usize)?;
        self.items.get(start as usize..end as usize)
    }

    /// The list of the cell that holds direction `e` seen from the centre.
    #[inline(always)]
    fn list_towards(&self, e: Vec3) -> Option<&[u32]> {
        // The face of `e` (axis a, then the axes a + 1 and a + 2 as u and v).
        let m = e.abs();
        let (major, u, v, face) = if m.x >= m.y && m.x >= m.z {
            (e.x, e.y, e.z, 0)
        } else if m.y >= m.z {
            (e.y, e.z, e.x, 2)
        } else {
            (e.z, e.x, e.y, 4)
        };
        let face = face + usize::from(major < 0.0);
        // A reciprocal: its rounding, like the divisions', is far inside `PAD`.
        let inv = 1.0 / major.abs();
        let cell = (face * N + cell_index(v * inv)) * N + cell_index(u * inv);
        let [start, end] = self.spans[cell];
        // A list too long (`WALK`) ends outside `items`: no cell.
        self.items.get(start as usize..end as usize)
    }
}

#[cfg(target_arch = "x86_64")]
mod lanes;

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    #[test]
    fn cell_index_floors_and_clamps_as_the_saturating_cast() {
        let definition = |u: f64| (((u + 1.0) * (0.5 * N as f64)) as usize).min(N - 1);
        let mut values = vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -2.0, -1.0, 0.0, -0.0, 1.0, 2.0, 1e300, -1e300];
        for k in 0..=N {
            let edge = 2.0 * k as f64 / N as f64 - 1.0;
            values.extend([edge, edge.next_up(), edge.next_down()]);
        }
        values.extend((0..10_000).map(|i| -1.2 + 2.4 * i as f64 / 9_999.0));
        for u in values {
            assert_eq!(cell_index(u), definition(u), "{u}");
        }
    }
    use crate::sampling::Rng;

    /// `count` boxes centred in the cube of side `10 scale` around the origin,
    /// from `rand`: every `flat_every`-th has no height (a floor), and their
    /// half sizes reach `largest` times `scale` (a box may hold the centre).
    pub(in crate::accel) fn random_boxes(
        rand: &mut impl FnMut() -> f64,
        count: usize,
        scale: f64,
        flat_every: usize,
        largest: f64,
    ) -> Vec<Aabb> {
        (0..count)
            .map(|k| {
                let c = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 10.0 * scale;
                let size = Vec3::new(rand(), if k % flat_every == 0 { 0.0 } else { rand() }, rand()) * scale * [0.1, 1.0, largest][k % 3];
                Aabb { min: c - size, max: c + size }
            })
            .collect()
    }

    /// Boxes of many sizes around a light; points sampled inside each box and
    /// looked up from the light, along rays that start beyond the point (and
    /// off the exact line by up to the allowed distance), find the box listed.
    #[test]
    fn every_box_a_segment_meets_is_listed() {
        let mut rng = Rng::for_sample(5, 0, 0);
        let mut rand = move || rng.uniform();
        for trial in 0..40 {
            let scale = [1e-3, 1.0, 1e5][trial % 3];
            let centre = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 4.0 * scale;
            // Some flat boxes (a floor) and some that surround the light.
            let boxes = random_boxes(&mut rand, 60, scale, 7, 6.0);
            let buffer = LightBuffer::build(centre, &boxes, |_| true, |_, _| true, 10.0 * scale).expect("small enough");
            for (k, b) in boxes.iter().enumerate() {
                for _ in 0..40 {
                    let q = b.min + (b.max - b.min) * Vec3::new(rand(), rand(), rand());
                    let away = q - centre;
                    if away.length() == 0.0 {
                        continue;
                    }
                    // A ray from beyond q towards the light, its origin then
                    // pushed off the line by up to the allowed distance.
                    let start = q + away.normalize() * (rand() * 3.0 * scale);
                    let dir = (centre - start).normalize();
                    let nudge = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * (buffer.near * ANGLE * 0.5);
                    let origin = start + nudge;
                    let length = (centre - origin).dot(dir);
                    let cell = buffer.cell_of(origin, dir, length).expect("a ray within the allowed distance gets a cell");
                    let listed = buffer.always().contains(&(k as u32)) || cell.contains(&(k as u32));
                    assert!(listed, "box {k} {b:?} not listed for point {q:?} seen from {centre:?}");
                }
            }
        }
    }

    /// A ray that passes the light, or whose line misses it by more than the
    /// allowed distance, gets no cell.
    #[test]
    fn rays_that_do_not_end_at_the_light_walk() {
        let boxes = [Aabb { min: Vec3::splat(1.0), max: Vec3::splat(2.0) }];
        let buffer = LightBuffer::build(Vec3::ZERO, &boxes, |_| true, |_, _| true, 10.0).unwrap();
        let origin = Vec3::new(5.0, 0.0, 0.0);
        assert!(buffer.cell_of(origin, -Vec3::X, 5.0).is_some());
        assert!(buffer.cell_of(origin, -Vec3::X, 6.0).is_none(), "the segment goes past the light");
        let aside = Vec3::new(5.0, 1e-3, 0.0);
        assert!(buffer.cell_of(aside, -Vec3::X, 5.0).is_none(), "the line misses the light by 1e-3");
    }

    /// Scenes beyond the object limit, or with many objects around the light,
    /// keep the walk; so do rays through a cell that would list too many.
    #[test]
    fn crowded_scenes_and_cells_walk() {
        let boxes = vec![Aabb { min: Vec3::splat(1.0), max: Vec3::splat(2.0) }; MAX_OBJECTS + 1];
        assert!(LightBuffer::build(Vec3::ZERO, &boxes, |_| true, |_, _| true, 10.0).is_none());
        let around = vec![Aabb { min: Vec3::splat(-1.0), max: Vec3::splat(1.0) }; MAX_ALWAYS + 1];
        assert!(LightBuffer::build(Vec3::ZERO, &around, |_| true, |_, _| true, 10.0).is_none());
        // 40 small boxes in a row along +x, one behind the other as seen from the light.
        let row: Vec<Aabb> =
            (0..40).map(|k| Aabb { min: Vec3::new(2.0 + k as f64, -0.1, -0.1), max: Vec3::new(2.5 + k as f64, 0.1, 0.1) }).collect();
        let buffer = LightBuffer::build(Vec3::ZERO, &row, |_| true, |_, _| true, 50.0).unwrap();
        assert!(buffer.cell_of(Vec3::new(60.0, 0.0, 0.0), -Vec3::X, 60.0).is_none(), "40 objects in one cell: walk");
        assert_eq!(buffer.cell_of(Vec3::new(0.0, 60.0, 0.0), -Vec3::Y, 60.0), Some(&[][..]), "nothing above the light");
    }
}
