//! The structures under test behind one interface: lamplight's `MeshAccel`, and
//! obvhs's compressed wide BVH8 (`CwBvh`) and binary BVH (`Bvh2`), both built with
//! its PLOC builder, with triangles copied into leaf order as `RtTriangle` (the
//! layout obvhs's docs name as the fastest for CPU intersection; Möller-Trumbore).

use std::time::{Duration, Instant};

use glam::{UVec2, Vec3A};
use lamplight_core::batch::MeshAccel;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::bvh2::node::Bvh2Node;
use obvhs::bvh2::Bvh2;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray, RayHit};
use obvhs::rt_triangle::RtTriangle;
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use rayon::prelude::*;

/// One of obvhs's build presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// `BvhBuildParams::fast_build()`.
    Fast,
    /// `BvhBuildParams::medium_build()` (the docs' example; "around the same build time as Embree but with faster traversal").
    Medium,
    /// `BvhBuildParams::slow_build()` (spatial pre-splits, wider PLOC search, more reinsertion).
    Slow,
}

impl Preset {
    fn params(self) -> BvhBuildParams {
        match self {
            Preset::Fast => BvhBuildParams::fast_build(),
            Preset::Medium => BvhBuildParams::medium_build(),
            Preset::Slow => BvhBuildParams::slow_build(),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Preset::Fast => "fast",
            Preset::Medium => "medium",
            Preset::Slow => "slow",
        }
    }
}

/// What to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// lamplight's `MeshAccel`.
    Lamplight,
    /// obvhs `CwBvh` with the given preset.
    CwBvh(Preset),
    /// obvhs `Bvh2` with the given preset.
    Bvh2(Preset),
}

impl Kind {
    /// Parses `lamplight`, `cwbvh-fast|medium|slow`, `bvh2-fast|medium|slow`.
    pub fn parse(s: &str) -> Result<Kind, String> {
        let preset = |p: &str| match p {
            "fast" => Ok(Preset::Fast),
            "medium" => Ok(Preset::Medium),
            "slow" => Ok(Preset::Slow),
            _ => Err(format!("unknown preset {p}")),
        };
        match s.split_once('-') {
            None if s == "lamplight" => Ok(Kind::Lamplight),
            Some(("cwbvh", p)) => Ok(Kind::CwBvh(preset(p)?)),
            Some(("bvh2", p)) => Ok(Kind::Bvh2(preset(p)?)),
            _ => Err(format!("unknown structure {s}")),
        }
    }

    /// Name as in the table.
    pub fn name(self) -> String {
        match self {
            Kind::Lamplight => "lamplight MeshAccel".into(),
            Kind::CwBvh(p) => format!("obvhs CwBvh {}", p.name()),
            Kind::Bvh2(p) => format!("obvhs Bvh2 {}", p.name()),
        }
    }
}

/// A built structure.
pub enum Accel {
    /// lamplight.
    Lamplight(MeshAccel),
    /// obvhs CWBVH; triangles in `primitive_indices` order.
    Cw(CwBvh, Vec<RtTriangle>),
    /// obvhs BVH2; triangles in `primitive_indices` order.
    B2(Bvh2, Vec<RtTriangle>),
}

/// Traversal counters of one ray.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counts {
    /// Nodes whose children's boxes were tested.
    pub nodes: u64,
    /// Triangle tests.
    pub tris: u64,
}

impl Accel {
    /// Builds `kind` over the mesh on the current rayon pool; returns it with the
    /// wall time from the indexed mesh to a structure ready to cast.
    pub fn build(kind: Kind, positions: &[[f32; 3]], indices: &[[u32; 3]]) -> (Accel, Duration) {
        let start = Instant::now();
        let gather = || -> Vec<Triangle> {
            indices
                .iter()
                .map(|t| {
                    let [v0, v1, v2] = t.map(|k| Vec3A::from_array(positions[k as usize]));
                    Triangle { v0, v1, v2 }
                })
                .collect()
        };
        let accel = match kind {
            Kind::Lamplight => Accel::Lamplight(MeshAccel::new(positions, indices).expect("valid mesh")),
            Kind::CwBvh(p) => {
                let tris = gather();
                let bvh = build_cwbvh_from_tris(&tris, p.params(), &mut Duration::default());
                let leaf = bvh.primitive_indices.iter().map(|&i| RtTriangle::from(&tris[i as usize])).collect();
                Accel::Cw(bvh, leaf)
            }
            Kind::Bvh2(p) => {
                let tris = gather();
                let bvh = build_bvh2_from_tris(&tris, p.params(), &mut Duration::default());
                let leaf = bvh.primitive_indices.iter().map(|&i| RtTriangle::from(&tris[i as usize])).collect();
                Accel::B2(bvh, leaf)
            }
        };
        (accel, start.elapsed())
    }

    /// Bytes needed to cast rays: nodes, triangle copies and the index map back to
    /// input triangles; and the nodes alone.
    pub fn bytes(&self) -> (usize, usize) {
        match self {
            Accel::Lamplight(a) => {
                let m = a.memory().bvh;
                (m.bytes, m.nodes * 256)
            }
            Accel::Cw(b, t) => {
                let nodes = b.nodes.len() * size_of::<CwBvhNode>();
                (nodes + b.primitive_indices.len() * 4 + t.len() * size_of::<RtTriangle>(), nodes)
            }
            Accel::B2(b, t) => {
                let nodes = b.nodes.len() * size_of::<Bvh2Node>();
                (nodes + b.primitive_indices.len() * 4 + t.len() * size_of::<RtTriangle>(), nodes)
            }
        }
    }

    /// Casts the batch on the current rayon pool (chunks of 1024 rays, as
    /// `lamplight_core::batch::cast`): nearest ray parameter `t` along the
    /// direction as given (`inf` for a miss; every structure here in the same
    /// unit) and input triangle index (`-1`). Each arm is monomorphised, so the per-ray query inlines.
    pub fn cast(&self, origins: &[[f32; 3]], dirs: &[[f32; 3]], t_out: &mut [f32], prim_out: &mut [i64]) {
        match self {
            Accel::Lamplight(a) => closest_batch(origins, dirs, t_out, prim_out, |o, d| a.nearest_param(o, d, f32::INFINITY)),
            Accel::Cw(b, t) => closest_batch(origins, dirs, t_out, prim_out, |o, d| {
                let mut hit = RayHit::none();
                b.ray_traverse(ray(o, d), &mut hit, |r, id| t[id].intersect(r))
                    .then(|| (hit.t, b.primitive_indices[hit.primitive_id as usize]))
            }),
            Accel::B2(b, t) => closest_batch(origins, dirs, t_out, prim_out, |o, d| {
                let mut hit = RayHit::none();
                b.ray_traverse(ray(o, d), &mut hit, |r, id| t[id].intersect(r))
                    .then(|| (hit.t, b.primitive_indices[hit.primitive_id as usize]))
            }),
        }
    }

    /// The any-hit query for the batch (stops at the first hit), current rayon pool.
    pub fn occluded(&self, origins: &[[f32; 3]], dirs: &[[f32; 3]], hit_out: &mut [bool]) {
        match self {
            Accel::Lamplight(a) => occluded_batch(origins, dirs, hit_out, |o, d| a.occluded_param(o, d, f32::INFINITY)),
            Accel::Cw(b, t) => occluded_batch(origins, dirs, hit_out, |o, d| !b.ray_traverse_miss(ray(o, d), |r, id| t[id].intersect(r))),
            Accel::B2(b, t) => occluded_batch(origins, dirs, hit_out, |o, d| !b.ray_traverse_miss(ray(o, d), |r, id| t[id].intersect(r))),
        }
    }

    /// Node visits and triangle tests of a closest-hit query (CWBVH only: obvhs's
    /// `traverse!` macro lets the node test be wrapped; lamplight's traversal has
    /// no counters).
    pub fn count_closest(&self, o: [f32; 3], d: [f32; 3]) -> Option<Counts> {
        let Accel::Cw(bvh, tris) = self else { return None };
        let mut counts = Counts::default();
        let mut traverse_ray = ray(o, d);
        let mut state = bvh.new_traversal(traverse_ray.direction);
        let mut node;
        obvhs::traverse!(
            bvh,
            node,
            state,
            {
                counts.nodes += 1;
                node.intersect_ray(&traverse_ray, state.oct_inv4)
            },
            {
                counts.tris += 1;
                let t = tris[state.primitive_id as usize].intersect(&traverse_ray);
                if t < traverse_ray.tmax {
                    traverse_ray.tmax = t;
                }
            }
        );
        let _: UVec2 = state.current_group;
        Some(counts)
    }
}

/// Rays per rayon work item, as in `lamplight_core::batch::cast`.
const CHUNK: usize = 1024;

fn closest_batch(
    origins: &[[f32; 3]],
    dirs: &[[f32; 3]],
    t_out: &mut [f32],
    prim_out: &mut [i64],
    query: impl Fn([f32; 3], [f32; 3]) -> Option<(f32, u32)> + Sync,
) {
    origins.par_chunks(CHUNK).zip(dirs.par_chunks(CHUNK)).zip(t_out.par_chunks_mut(CHUNK)).zip(prim_out.par_chunks_mut(CHUNK)).for_each(
        |(((o, d), t), p)| {
            for i in 0..o.len() {
                (t[i], p[i]) = match query(o[i], d[i]) {
                    Some((hit, tri)) => (hit, i64::from(tri)),
                    None => (f32::INFINITY, -1),
                };
            }
        },
    );
}

fn occluded_batch(origins: &[[f32; 3]], dirs: &[[f32; 3]], hit_out: &mut [bool], query: impl Fn([f32; 3], [f32; 3]) -> bool + Sync) {
    origins.par_chunks(CHUNK).zip(dirs.par_chunks(CHUNK)).zip(hit_out.par_chunks_mut(CHUNK)).for_each(|((o, d), h)| {
        for i in 0..o.len() {
            h[i] = query(o[i], d[i]);
        }
    });
}

fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
    Ray::new(Vec3A::from_array(o), Vec3A::from_array(d), 0.0, f32::INFINITY)
}
