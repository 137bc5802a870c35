//! `lamplight raycast`: batch ray casting against one mesh, rays and answers as
//! NumPy `.npy` arrays ([`lamplight_scene::npy`]), through the batch API of
//! [`lamplight_core::batch`] that Python's `Scene.intersect` uses too.
//!
//! ```text
//! lamplight raycast (--mesh FILE | --vertices V.npy --indices I.npy)
//!                   --origins O.npy --directions D.npy -o T.npy [--prims P.npy]
//!                   [--objects OBJ.npy] [--threads N] [--any-hit] [--repeat K]
//! ```
//!
//! `O` and `D` are `(N, 3)` float32 (or float64, rounded) arrays; ray `i` is
//! `O[i] + s D[i]`, `s > 0`, and `D[i]` need not be unit. Answers, as
//! [`lamplight_core::batch`] defines them:
//!
//! - `T`, float32 `(N,)`: the **distance** from `O[i]` to the nearest hit,
//!   `s |D[i]|` (equal to Embree's `tfar` for unit directions), `+inf` for a miss;
//! - `P`, int64 `(N,)`: the index of the triangle hit, `-1` for a miss;
//! - `OBJ`, int64 `(N,)`: the object hit, always `0` here (the mesh is one
//!   object), `-1` for a miss: the same ids as `Scene.intersect` gives for a
//!   scene holding only this mesh.
//!
//! Triangles are numbered in the file's face order (`lamplight_scene::import::load_mesh`:
//! a multi-mesh file's instances merged in order, in world space). With
//! `--any-hit` only occlusion is asked: `T` is 0 for a ray that hits anything
//! and `+inf` for one that does not. Prints the build time, memory, casting time
//! and Mrays/s (casting only; with `--repeat K` the median of K casts). The
//! answers do not depend on `--threads`. Bad input exits with code 2.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use clap::Args;
use lamplight_core::batch::{self, Hits, MeshAccel, RaySlices};
use lamplight_scene::npy::{self, NpyError};

use lamplight_scene::request::{limits, Naming};

use crate::args::UsageError;

/// `lamplight raycast` flags.
#[derive(Debug, Args)]
#[command(after_help = "Units: ray i is O[i] + s D[i] with s > 0 and D[i] of any non-zero length; T[i] is the distance \
                        s |D[i]| to the nearest hit (Embree's t when D[i] is unit), +inf for a miss. The same numbers \
                        as Python's Scene.intersect.")]
pub struct RaycastArgs {
    /// Mesh file: .obj, .ply, .gltf or .glb (every mesh of the file merged in world space, in file order).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["vertices", "indices"])]
    pub mesh: Option<PathBuf>,
    /// Vertex positions, an (V, 3) float32/float64 .npy (with --indices, instead of --mesh).
    #[arg(long, value_name = "V.npy", requires = "indices")]
    pub vertices: Option<PathBuf>,
    /// Triangles, an (F, 3) integer .npy of vertex indices.
    #[arg(long, value_name = "I.npy", requires = "vertices")]
    pub indices: Option<PathBuf>,
    /// Ray origins, (N, 3) float32 or float64.
    #[arg(long, value_name = "O.npy")]
    pub origins: PathBuf,
    /// Ray directions, (N, 3) float32 or float64, any non-zero length.
    #[arg(long, value_name = "D.npy")]
    pub directions: PathBuf,
    /// Output: distance from the origin to the nearest hit, (N,) float32, +inf for a miss.
    #[arg(short, long, value_name = "T.npy")]
    pub output: PathBuf,
    /// Output: triangle indices, (N,) int64, -1 for a miss.
    #[arg(long, value_name = "P.npy")]
    pub prims: Option<PathBuf>,
    /// Output: object ids, (N,) int64: 0 (the mesh) for a hit, -1 for a miss.
    #[arg(long, value_name = "OBJ.npy")]
    pub objects: Option<PathBuf>,
    /// Worker threads for build and casting, at most 1024; 0 uses all cores. The answers do not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0, allow_negative_numbers = true, value_parser = crate::args::count::<usize>)]
    pub threads: usize,
    /// Only test occlusion (shadow rays): T is 0 for a hit, +inf for a miss.
    #[arg(long, conflicts_with_all = ["prims", "objects"])]
    pub any_hit: bool,
    /// Cast the batch K times and report the median time.
    #[arg(long, value_name = "K", default_value_t = 1, allow_negative_numbers = true, value_parser = crate::args::count::<u32>)]
    pub repeat: u32,
}

/// A reading error is the user's input (exit code 2); a writing error is not.
fn npy_error(e: NpyError) -> anyhow::Error {
    match e {
        NpyError::Read { .. } => UsageError(e.to_string()).into(),
        _ => e.into(),
    }
}

/// Fails before the work when an output's directory does not accept files.
fn check_writable(path: &Path) -> anyhow::Result<()> {
    lamplight_scene::atomic::check_writable(path).with_context(|| format!("cannot write {}", path.display()))
}

/// Reads the mesh and the rays, casts, writes the answers.
pub fn raycast_command(args: RaycastArgs) -> anyhow::Result<()> {
    limits::THREADS.check(args.threads as u64, Naming::Flags).map_err(UsageError)?;
    if args.repeat == 0 {
        return Err(UsageError("--repeat must be at least 1".into()).into());
    }
    let outputs: Vec<(&str, &Path)> = [("-o", Some(&args.output)), ("--prims", args.prims.as_ref()), ("--objects", args.objects.as_ref())]
        .into_iter()
        .filter_map(|(flag, path)| Some((flag, path?.as_path())))
        .collect();
    crate::args::distinct_outputs(&outputs)?;
    for path in [Some(&args.output), args.prims.as_ref(), args.objects.as_ref()].into_iter().flatten() {
        check_writable(path)?;
    }
    let (positions, indices) = load_mesh(&args)?;
    let origins = npy::read_rows3_f32(&args.origins).map_err(npy_error)?;
    let directions = npy::read_rows3_f32(&args.directions).map_err(npy_error)?;
    if origins.len() != directions.len() {
        let (o, d) = (args.origins.display(), args.directions.display());
        return Err(UsageError(format!(
            "{} origins but {} directions: {o} and {d} must have the same number of rows",
            origins.len(),
            directions.len()
        ))
        .into());
    }
    let rays = RaySlices::new(&origins, &directions)?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads).build().context("cannot start the thread pool")?;
    let threads = pool.current_num_threads();

    let start = Instant::now();
    let accel = pool.install(|| MeshAccel::new(&positions, &indices)).map_err(|e| UsageError(format!("bad mesh: {e}")))?;
    let build = start.elapsed();
    let mem = accel.memory();
    let mesh_bytes = positions.len() * 12 + indices.len() * 12;
    say(format_args!(
        "build: {:.1} ms, {} triangles, {} threads; structure {:.1} bytes/triangle ({:.1} MB), with the mesh arrays {:.1} bytes/triangle",
        build.as_secs_f64() * 1e3,
        mem.triangles,
        threads,
        mem.bytes_per_triangle,
        mem.bvh.bytes as f64 / 1e6,
        (mem.bvh.bytes + mesh_bytes) as f64 / mem.triangles.max(1) as f64
    ));

    let n = origins.len();
    let mut t = vec![0f32; n];
    let mut prims = args.prims.as_ref().map(|_| vec![0i64; n]);
    let mut objects = args.objects.as_ref().map(|_| vec![0i64; n]);
    let mut hits = vec![false; n];
    let (mut times, mut cpu_times) = (Vec::new(), Vec::new());
    for _ in 0..args.repeat {
        let cpu_start = cpu_seconds();
        let start = Instant::now();
        pool.install(|| {
            if args.any_hit {
                batch::occluded(&accel, &rays, None, &mut hits, 0)
            } else {
                let out = Hits { t: &mut t, object: objects.as_deref_mut(), primitive: prims.as_deref_mut(), normal: None, error: None };
                batch::cast(&accel, &rays, out, 0)
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
    say(format_args!(
        "cast: {n} rays{} in {:.1} ms ({}), {:.2} Mrays/s on {threads} threads",
        if args.any_hit { " (any hit)" } else { "" },
        median * 1e3,
        if times.len() > 1 { format!("median of {}", times.len()) } else { "one run".to_string() },
        n as f64 / median / 1e6
    ));
    if let Some(cpu) = cpu_times.get(cpu_times.len() / 2) {
        // CPU time is what to compare when other programs share the cores.
        say(format_args!("cpu: {:.1} ms of CPU time, {:.2} Mrays per CPU-second", cpu * 1e3, n as f64 / cpu / 1e6));
    }
    if args.any_hit {
        t = hits.iter().map(|&h| if h { 0.0 } else { f32::INFINITY }).collect();
    }
    npy::write_f32(&args.output, &t)?;
    for (path, ids) in [(&args.prims, &prims), (&args.objects, &objects)] {
        if let (Some(path), Some(ids)) = (path, ids) {
            npy::write_i64(path, ids)?;
        }
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
            let imported = lamplight_scene::import::load(path).map_err(|e| UsageError(e.to_string()))?;
            crate::print_warnings(&imported.warnings_of(path));
            let mesh = imported.into_mesh();
            Ok((mesh.positions.iter().map(|p| [p.x as f32, p.y as f32, p.z as f32]).collect(), mesh.indices))
        }
        (None, Some(v), Some(i)) => Ok((npy::read_rows3_f32(v).map_err(npy_error)?, npy::read_rows3_u32(i).map_err(npy_error)?)),
        _ => Err(UsageError("give --mesh FILE, or --vertices V.npy with --indices I.npy".into()).into()),
    }
}

/// Prints one line of figures to standard output. A reader that has gone
/// (`lamplight raycast ... | head -1`) no longer wants them, but the answers
/// still go to their files: the write's error is dropped, where `println!`
/// would panic.
fn say(line: std::fmt::Arguments) {
    use std::io::Write;
    let _ = writeln!(std::io::stdout().lock(), "{line}");
}
