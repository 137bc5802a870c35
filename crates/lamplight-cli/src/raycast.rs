//! `lamplight raycast`: batch ray casting against one mesh, rays and answers as
//! NumPy `.npy` arrays ([`crate::npy`]).
//!
//! ```text
//! lamplight raycast (--mesh FILE | --vertices V.npy --indices I.npy)
//!                   --origins O.npy --directions D.npy -o T.npy [--prims P.npy]
//!                   [--threads N] [--any-hit] [--repeat K]
//! ```
//!
//! `O` and `D` are `(N, 3)` float32 (or float64) arrays; `T` gets the nearest hit
//! distance along each (not necessarily unit) direction, `+inf` for a miss, and
//! `P` the int64 triangle index, `-1` for a miss. Triangles are numbered in the
//! file's face order (`lamplight_scene::import::load_mesh`: a multi-mesh file's
//! instances merged in order, in world space).
//! With `--any-hit` only occlusion is asked: `T` is 0 for a ray that hits anything
//! and `+inf` for one that does not. Prints the build time, memory, casting time
//! and Mrays/s (casting only; with `--repeat K` the median of K casts).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use clap::Args;
use lamplight_core::raycast::MeshAccel;

use crate::args::UsageError;
use crate::npy;

/// `lamplight raycast` flags.
#[derive(Debug, Args)]
pub struct RaycastArgs {
    /// Mesh file (any format `lamplight_scene::import` reads).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["vertices", "indices"])]
    pub mesh: Option<PathBuf>,
    /// Vertex positions, an (V, 3) float32/float64 .npy (with --indices, instead of --mesh).
    #[arg(long, value_name = "V.npy", requires = "indices")]
    pub vertices: Option<PathBuf>,
    /// Triangles, an (F, 3) integer .npy of vertex indices.
    #[arg(long, value_name = "I.npy", requires = "vertices")]
    pub indices: Option<PathBuf>,
    /// Ray origins, (N, 3) float32.
    #[arg(long, value_name = "O.npy")]
    pub origins: PathBuf,
    /// Ray directions, (N, 3) float32 (need not be unit length).
    #[arg(long, value_name = "D.npy")]
    pub directions: PathBuf,
    /// Output: hit distances, (N,) float32, +inf for a miss.
    #[arg(short, long, value_name = "T.npy")]
    pub output: PathBuf,
    /// Output: triangle indices, (N,) int64, -1 for a miss.
    #[arg(long, value_name = "P.npy")]
    pub prims: Option<PathBuf>,
    /// Worker threads for build and casting (default: all cores).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: usize,
    /// Only test occlusion (shadow rays): T is 0 for a hit, +inf for a miss.
    #[arg(long, conflicts_with = "prims")]
    pub any_hit: bool,
    /// Cast the batch K times and report the median time.
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub repeat: u32,
}

/// Reads the mesh and the rays, casts, writes the answers.
pub fn raycast_command(args: RaycastArgs) -> anyhow::Result<()> {
    let (positions, indices) = load_mesh(&args)?;
    let origins = npy::read_rows3(&args.origins)?.to_f32(&args.origins)?;
    let directions = npy::read_rows3(&args.directions)?.to_f32(&args.directions)?;
    if origins.len() != directions.len() {
        return Err(UsageError(format!("{} origins but {} directions", origins.len(), directions.len())).into());
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads).build().context("cannot start the thread pool")?;
    let threads = pool.current_num_threads();

    let start = Instant::now();
    let accel = pool.install(|| MeshAccel::new(&positions, &indices)).map_err(|e| UsageError(format!("bad mesh: {e}")))?;
    let build = start.elapsed();
    let mem = accel.memory();
    let mesh_bytes = positions.len() * 12 + indices.len() * 12;
    println!(
        "build: {:.1} ms, {} triangles, {} threads; structure {:.1} bytes/triangle ({:.1} MB), with the mesh arrays {:.1} bytes/triangle",
        build.as_secs_f64() * 1e3,
        mem.triangles,
        threads,
        mem.bytes_per_triangle,
        mem.bvh.bytes as f64 / 1e6,
        (mem.bvh.bytes + mesh_bytes) as f64 / mem.triangles.max(1) as f64
    );

    let n = origins.len();
    let mut t = vec![0f32; n];
    let mut prims = args.prims.as_ref().map(|_| vec![0i64; n]);
    let mut hits = vec![false; n];
    let unbounded = if args.any_hit { vec![f32::INFINITY; n] } else { Vec::new() };
    let (mut times, mut cpu_times) = (Vec::new(), Vec::new());
    for _ in 0..args.repeat {
        let cpu_start = cpu_seconds();
        let start = Instant::now();
        pool.install(|| {
            if args.any_hit {
                accel.occluded(&origins, &directions, &unbounded, &mut hits, 0)
            } else {
                accel.cast(&origins, &directions, &mut t, prims.as_deref_mut(), 0)
            }
        })?;
        times.push(start.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (cpu_start, cpu_seconds()) {
            cpu_times.push(b - a);
        }
    }
    times.sort_by(f64::total_cmp);
    cpu_times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    println!(
        "cast: {n} rays{} in {:.1} ms ({}), {:.2} Mrays/s on {threads} threads",
        if args.any_hit { " (any hit)" } else { "" },
        median * 1e3,
        if times.len() > 1 { format!("median of {}", times.len()) } else { "one run".to_string() },
        n as f64 / median / 1e6
    );
    if let Some(cpu) = cpu_times.get(cpu_times.len() / 2) {
        // CPU time is what to compare when other programs share the cores.
        println!("cpu: {:.1} ms of CPU time, {:.2} Mrays per CPU-second", cpu * 1e3, n as f64 / cpu / 1e6);
    }
    if args.any_hit {
        t = hits.iter().map(|&h| if h { 0.0 } else { f32::INFINITY }).collect();
    }
    npy::write_f32(&args.output, &t)?;
    if let (Some(path), Some(prims)) = (&args.prims, &prims) {
        npy::write_i64(path, prims)?;
    }
    Ok(())
}

/// CPU time of this process so far (Linux: the sum over its threads of
/// `/proc/self/task/*/schedstat`, nanoseconds on the CPU); `None` elsewhere.
fn cpu_seconds() -> Option<f64> {
    let mut total = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let stat = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        total += stat.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total as f64 * 1e-9)
}

/// Vertex positions and triangles.
type Mesh = (Vec<[f32; 3]>, Vec<[u32; 3]>);

/// Positions and triangles from `--mesh` or `--vertices`/`--indices`.
fn load_mesh(args: &RaycastArgs) -> anyhow::Result<Mesh> {
    match (&args.mesh, &args.vertices, &args.indices) {
        (Some(path), _, _) => {
            let mesh = lamplight_scene::import::load_mesh(path).map_err(|e| UsageError(e.to_string()))?;
            Ok((mesh.positions.iter().map(|p| [p.x as f32, p.y as f32, p.z as f32]).collect(), mesh.indices))
        }
        (None, Some(v), Some(i)) => Ok((npy::read_rows3(v)?.to_f32(v)?, npy::read_rows3(i)?.to_u32(i)?)),
        _ => Err(UsageError("give --mesh FILE, or --vertices V.npy with --indices I.npy".into()).into()),
    }
}
