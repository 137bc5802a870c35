//! The any-hit walks of the ray-casting BVH (shadow rays and visibility): one
//! ray at a time, or [`super::LANES`] scattered rays interleaved, as the
//! closest-hit walks of the parent module. The entered children of a node are
//! pushed, leaves as well as nodes, in slot order, each prefetched; the query
//! stops at the first hit, which order does not change.

use super::{leaf_range, test_node, Stack, Walk, LANES};
use crate::accel::mesh_bvh::{MeshBvh, LEAF, STACK};
use crate::accel::slab::SlabRay;
use crate::accel::tri4::ShearRay;
use crate::math::Vec3;
use std::mem::MaybeUninit;

impl MeshBvh {
    /// As [`MeshBvh::fetch_closest`], for an any-hit walk on `stack`.
    #[inline(always)]
    fn fetch_any(
        &self,
        next: &mut usize,
        n: usize,
        ray: &impl Fn(usize) -> ([f32; 3], [f32; 3], f32),
        answer: &mut impl FnMut(usize, bool),
        stack: &mut Stack<u32>,
    ) -> Option<Walk> {
        while *next < n {
            let index = *next;
            *next += 1;
            let (o, d, t_max) = ray(index);
            match self.start_any(index, o, d, t_max, stack) {
                Some(walk) => return Some(walk),
                None => answer(index, false),
            }
        }
        None
    }

    /// Starts the any-hit walk of a ray; `None` when it hits nothing by definition.
    #[inline(always)]
    fn start_any(&self, index: usize, o: [f32; 3], d: [f32; 3], t_max: f32, stack: &mut Stack<u32>) -> Option<Walk> {
        let mut walk = self.start(index, o, d, t_max)?;
        stack[0].write(0);
        walk.top = 1;
        Some(walk)
    }

    /// One step of an any-hit walk: pops one reference and tests it (a leaf's
    /// packets, or a node, whose entered children are pushed and prefetched when
    /// `PREFETCH`). `Some(answer)` when the walk is over.
    #[inline(always)]
    fn step_any<const AVX2: bool, const PREFETCH: bool>(&self, walk: &mut Walk, stack: &mut Stack<u32>) -> Option<bool> {
        if walk.top == 0 {
            return Some(false);
        }
        walk.top -= 1;
        // SAFETY: entries below `top` were written before.
        let reference = unsafe { stack[walk.top].assume_init() };
        if reference & LEAF != 0 {
            let (first, count) = leaf_range(reference);
            if self.packets[first..first + count].iter().any(|p| p.occludes(&walk.shear, walk.t_max)) {
                return Some(true);
            }
            return None;
        }
        let node = &self.nodes[reference as usize];
        let (_, mut mask) = test_node::<AVX2>(&walk.slab, node, walk.t_max);
        while mask != 0 {
            let slot = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let child = node.child[slot];
            stack[walk.top].write(child);
            walk.top += 1;
            if PREFETCH {
                self.prefetch_reference(child);
            }
        }
        None
    }

    /// Whether `o + t d` hits any triangle with `t` in `(0, t_max)` (stops at the first).
    #[inline]
    pub fn occluded(&self, o: [f32; 3], d: [f32; 3], t_max: f32) -> bool {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.occluded_avx2(o, d, t_max) };
        }
        self.occluded_any::<false>(o, d, t_max)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn occluded_avx2(&self, o: [f32; 3], d: [f32; 3], t_max: f32) -> bool {
        self.occluded_any::<true>(o, d, t_max)
    }

    #[inline(always)]
    fn occluded_any<const AVX2: bool>(&self, o: [f32; 3], d: [f32; 3], t_max: f32) -> bool {
        let Some(shear) = ShearRay::new(o, d) else { return false };
        if self.nodes.is_empty() {
            return false;
        }
        let ray = SlabRay::new(Vec3::from(o.map(f64::from)), Vec3::from(d.map(f64::from)), 0.0);
        let mut stack = [const { MaybeUninit::<u32>::uninit() }; STACK];
        stack[0].write(0);
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            // SAFETY: entries below `top` were written before.
            let node = &self.nodes[unsafe { stack[top].assume_init() } as usize];
            let (_, mut mask) = test_node::<AVX2>(&ray, node, t_max);
            while mask != 0 {
                let slot = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let child = node.child[slot];
                if child & LEAF != 0 {
                    let (first, count) = leaf_range(child);
                    if self.packets[first..first + count].iter().any(|p| p.occludes(&shear, t_max)) {
                        return true;
                    }
                } else {
                    stack[top].write(child);
                    top += 1;
                }
            }
        }
        false
    }

    /// Whether each of `n` rays `ray(i) = (o, d, t_max)` hits anything:
    /// `answer(i, hit)` receives [`MeshBvh::occluded`]'s answer for ray `i`, with
    /// the rays interleaved as in [`MeshBvh::closest_batch`].
    #[inline]
    pub fn occluded_batch(&self, n: usize, ray: impl Fn(usize) -> ([f32; 3], [f32; 3], f32), answer: impl FnMut(usize, bool)) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.occluded_batch_avx2(n, ray, answer) };
        }
        self.occluded_batch_any::<false>(n, ray, answer)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn occluded_batch_avx2(&self, n: usize, ray: impl Fn(usize) -> ([f32; 3], [f32; 3], f32), answer: impl FnMut(usize, bool)) {
        self.occluded_batch_any::<true>(n, ray, answer)
    }

    #[inline(always)]
    fn occluded_batch_any<const AVX2: bool>(
        &self,
        n: usize,
        ray: impl Fn(usize) -> ([f32; 3], [f32; 3], f32),
        mut answer: impl FnMut(usize, bool),
    ) {
        let mut walks = [const { MaybeUninit::<Walk>::uninit() }; LANES];
        let mut stacks = [const { [const { MaybeUninit::<u32>::uninit() }; STACK] }; LANES];
        let mut next = 0;
        let mut active = 0;
        while active < LANES {
            let Some(walk) = self.fetch_any(&mut next, n, &ray, &mut answer, &mut stacks[active]) else { break };
            walks[active].write(walk);
            active += 1;
        }
        while active > 0 {
            let mut lane = 0;
            while lane < active {
                // SAFETY: lanes below `active` hold walks written above.
                let walk = unsafe { walks[lane].assume_init_mut() };
                let Some(hit) = self.step_any::<AVX2, true>(walk, &mut stacks[lane]) else {
                    lane += 1;
                    continue;
                };
                answer(walk.ray, hit);
                if let Some(fresh) = self.fetch_any(&mut next, n, &ray, &mut answer, &mut stacks[lane]) {
                    *walk = fresh;
                    lane += 1;
                } else {
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
