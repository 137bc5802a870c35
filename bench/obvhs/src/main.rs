//! obvhs against lamplight's own ray-casting BVH on the anchor ray sets.
//!
//!     cargo run --release -- --rays /tmp/anchor-rays [--meshes bunny,igea,igea-1m] [--runs 5]
//!         [--threads 1,2] [--structures lamplight,cwbvh-fast,cwbvh-medium,cwbvh-slow,bvh2-medium]
//!
//! For each mesh: builds every structure on a rayon pool of each thread count
//! (interleaved, median build time), then casts the `incoherent` and `primary`
//! (camera) ray sets for the nearest hit and the incoherent set for any-hit,
//! interleaving the structures run by run (A B C A B C ..., same rays), and prints
//! medians of wall-clock Mrays/s and Mrays per CPU-second (thread CPU time from
//! /proc/self/task/*/schedstat, which does not count time spent waiting for a
//! core). Answers are compared with lamplight's (hit/miss, `t`, triangle), node
//! visits per ray are counted for the CWBVH, and a watertightness probe counts
//! rays leaking through shared edges and vertices of a closed sheet.

mod accels;
mod probe;

use std::path::{Path, PathBuf};
use std::time::Instant;

use accels::{Accel, Kind};
use glam::Vec3A;
use lamplight_scene::npy;
use obvhs::ray::Ray;
use obvhs::rt_triangle::RtTriangle;

struct Args {
    rays: PathBuf,
    meshes: Vec<String>,
    runs: usize,
    threads: Vec<usize>,
    kinds: Vec<Kind>,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        rays: PathBuf::from(std::env::var("ANCHOR_RAYS").unwrap_or_else(|_| "/tmp/anchor-rays".into())),
        meshes: vec!["bunny".into(), "igea".into(), "igea-1m".into()],
        runs: 5,
        threads: vec![1, 2],
        kinds: ["lamplight", "cwbvh-fast", "cwbvh-medium", "cwbvh-slow", "bvh2-medium"].iter().map(|k| Kind::parse(k).unwrap()).collect(),
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().ok_or_else(|| format!("{flag} needs a value"))?;
        let list = || value.split(',').map(str::to_owned).collect::<Vec<_>>();
        match flag.as_str() {
            "--rays" => args.rays = PathBuf::from(&value),
            "--meshes" => args.meshes = list().into_iter().filter(|m| !m.is_empty()).collect(),
            "--runs" => args.runs = value.parse().map_err(|_| "--runs: a number")?,
            "--threads" => args.threads = list().iter().map(|t| t.parse().map_err(|_| "--threads: numbers")).collect::<Result<_, _>>()?,
            "--structures" => args.kinds = list().iter().map(|k| Kind::parse(k)).collect::<Result<_, _>>()?,
            _ => return Err(format!("unknown flag {flag}")),
        }
    }
    if args.kinds.first() != Some(&Kind::Lamplight) {
        return Err("--structures must start with lamplight (the reference for the answers)".into());
    }
    Ok(args)
}

/// CPU time of all threads of this process, in seconds.
fn cpu_seconds() -> f64 {
    let mut ns = 0u64;
    if let Ok(tasks) = std::fs::read_dir("/proc/self/task") {
        for task in tasks.flatten() {
            if let Ok(text) = std::fs::read_to_string(task.path().join("schedstat")) {
                ns += text.split_whitespace().next().and_then(|v| v.parse::<u64>().ok()).unwrap_or(0);
            }
        }
    }
    ns as f64 * 1e-9
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn load() -> String {
    std::fs::read_to_string("/proc/loadavg").map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" ")).unwrap_or_default()
}

/// Closest-hit answers of one structure.
struct Answers {
    t: Vec<f32>,
    prim: Vec<i64>,
}

/// How two structures' closest-hit answers differ.
struct Agreement {
    /// Rays one hits and the other misses.
    hit_miss: usize,
    /// Largest relative `t` difference where both hit.
    rel_max: f64,
    /// Rays where both hit and `t` differs by more than 1e-5 relative.
    over: usize,
    /// Rays where both hit different triangles.
    prim: usize,
    /// Rays that differ (hit/miss, or `t` by more than 1e-5) where the reference
    /// hit lies within 1e-4 of the origin (the incoherent sets start on the surface).
    near_origin: usize,
}

fn agreement(a: &Answers, reference: &Answers) -> Agreement {
    let mut out = Agreement { hit_miss: 0, rel_max: 0.0, over: 0, prim: 0, near_origin: 0 };
    for i in 0..a.t.len() {
        let (x, y) = (a.t[i], reference.t[i]);
        let differs = if x.is_finite() != y.is_finite() {
            out.hit_miss += 1;
            true
        } else if x.is_finite() {
            let rel = (f64::from(x) - f64::from(y)).abs() / f64::from(y).max(1e-30);
            out.rel_max = out.rel_max.max(rel);
            out.over += usize::from(rel > 1e-5);
            out.prim += usize::from(a.prim[i] != reference.prim[i]);
            rel > 1e-5
        } else {
            false
        };
        out.near_origin += usize::from(differs && y < 1e-4);
    }
    out
}

/// Per structure and thread count: median Mrays/s wall and per CPU-second.
type Speed = Vec<Vec<(f64, f64)>>;

/// Times `query` on every structure, interleaved, `runs` times after a warm-up.
fn time_interleaved(
    pools: &[rayon::ThreadPool],
    accels: &[Accel],
    rays: usize,
    runs: usize,
    mut query: impl FnMut(&Accel) + Send,
) -> Speed {
    let mut out = vec![Vec::new(); accels.len()];
    for pool in pools {
        let mut wall = vec![Vec::new(); accels.len()];
        let mut cpu = vec![Vec::new(); accels.len()];
        for run in 0..=runs {
            for (k, accel) in accels.iter().enumerate() {
                let (c0, t0) = (cpu_seconds(), Instant::now());
                pool.install(|| query(accel));
                let (dt, dc) = (t0.elapsed().as_secs_f64(), cpu_seconds() - c0);
                if run > 0 {
                    wall[k].push(rays as f64 / dt * 1e-6);
                    cpu[k].push(rays as f64 / dc.max(1e-9) * 1e-6);
                }
            }
        }
        for k in 0..accels.len() {
            out[k].push((median(&mut wall[k]), median(&mut cpu[k])));
        }
    }
    out
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("model name")).map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned()))
        .unwrap_or_default();
    let features = if cfg!(target_feature = "avx512f") {
        "avx512"
    } else if cfg!(target_feature = "avx2") {
        "avx2"
    } else {
        "sse2 (default x86-64)"
    };
    println!(
        "# {cpu}, {} CPUs, built for {features}; load average at start {}",
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        load()
    );
    let pools: Vec<rayon::ThreadPool> =
        args.threads.iter().map(|&n| rayon::ThreadPoolBuilder::new().num_threads(n).build().expect("thread pool")).collect();

    watertight_probe(&args, &pools[0]);

    for mesh in &args.meshes {
        let f = |name: &str| args.rays.join(format!("{mesh}_{name}.npy"));
        let read = |p: &Path| npy::read_rows3_f32(p).unwrap_or_else(|e| panic!("{e}"));
        let positions = read(&f("vertices"));
        let indices = npy::read_rows3_u32(&f("indices")).unwrap_or_else(|e| panic!("{e}"));
        println!("\n## {mesh}: {} triangles (load {})", indices.len(), load());

        // Builds, interleaved; the structure cast below is the last one built on the first pool.
        let builds = args.runs.clamp(1, 3);
        let mut build_ms = vec![vec![Vec::new(); pools.len()]; args.kinds.len()];
        let mut accels: Vec<Option<Accel>> = args.kinds.iter().map(|_| None).collect();
        for _ in 0..builds {
            for (p, pool) in pools.iter().enumerate().rev() {
                for (k, &kind) in args.kinds.iter().enumerate() {
                    let (accel, took) = pool.install(|| Accel::build(kind, &positions, &indices));
                    build_ms[k][p].push(took.as_secs_f64() * 1e3);
                    if p == 0 {
                        accels[k] = Some(accel);
                    }
                }
            }
        }
        let accels: Vec<Accel> = accels.into_iter().map(Option::unwrap).collect();
        let build_ms: Vec<Vec<f64>> = build_ms.into_iter().map(|per| per.into_iter().map(|mut v| median(&mut v)).collect()).collect();

        let mut speeds: Vec<(&str, Speed)> = Vec::new();
        let mut notes = vec![String::new(); accels.len()];
        for set in ["incoherent", "primary"] {
            let origins = read(&f(&format!("{set}_origins")));
            let dirs = read(&f(&format!("{set}_directions")));
            let n = origins.len();
            // Answers (first pool), then timing.
            let answers: Vec<Answers> = accels
                .iter()
                .map(|a| {
                    let mut ans = Answers { t: vec![0.0; n], prim: vec![0; n] };
                    pools[0].install(|| a.cast(&origins, &dirs, &mut ans.t, &mut ans.prim));
                    ans
                })
                .collect();
            let hits = answers[0].t.iter().filter(|t| t.is_finite()).count();
            println!("{set}: {n} rays, {hits} hit (lamplight)");
            for (k, a) in answers.iter().enumerate().skip(1) {
                let Agreement { hit_miss, rel_max, over, prim, near_origin } = agreement(a, &answers[0]);
                println!(
                    "  {} vs lamplight: {hit_miss} hit/miss mismatches, t rel diff max {rel_max:.1e} ({over} > 1e-5), {prim} other triangle; \
                     {near_origin} of the differing rays have lamplight's hit within t < 1e-4",
                    args.kinds[k].name()
                );
                notes[k] += &format!("{set}: {hit_miss}, {rel_max:.1e} ({over}), {near_origin} at t < 1e-4; ");
            }
            for (k, a) in accels.iter().enumerate() {
                let sample: Vec<_> = (0..n).step_by(16).filter_map(|i| a.count_closest(origins[i], dirs[i])).collect();
                if !sample.is_empty() {
                    let per = |f: fn(&accels::Counts) -> u64| sample.iter().map(f).sum::<u64>() as f64 / sample.len() as f64;
                    println!(
                        "  {}: {:.1} node visits, {:.1} triangle tests per ray",
                        args.kinds[k].name(),
                        per(|c| c.nodes),
                        per(|c| c.tris)
                    );
                }
            }
            drop(answers);
            let (mut t, mut p) = (vec![0.0; n], vec![0; n]);
            let speed = time_interleaved(&pools, &accels, n, args.runs, |a| a.cast(&origins, &dirs, &mut t, &mut p));
            speeds.push((set, speed));
            if set == "incoherent" {
                let mut any = vec![vec![false; n]; accels.len()];
                for (k, a) in accels.iter().enumerate() {
                    pools[0].install(|| a.occluded(&origins, &dirs, &mut any[k]));
                }
                for k in 1..accels.len() {
                    let diff = any[k].iter().zip(&any[0]).filter(|(a, b)| a != b).count();
                    println!("  any-hit {} vs lamplight: {diff} mismatches", args.kinds[k].name());
                }
                let mut hit = vec![false; n];
                let speed = time_interleaved(&pools, &accels, n, args.runs, |a| a.occluded(&origins, &dirs, &mut hit));
                speeds.push(("any-hit", speed));
            }
        }
        print_table(mesh, indices.len(), &args, &accels, &build_ms, &speeds, &notes);
    }
    println!("\nload average at end {}", load());
}

fn print_table(mesh: &str, tris: usize, args: &Args, accels: &[Accel], build_ms: &[Vec<f64>], speeds: &[(&str, Speed)], notes: &[String]) {
    println!("\n{mesh} ({tris} triangles), Mrays/s wall (per CPU-second), median of {} runs:\n", args.runs);
    let mut head = "| structure | build ms ".to_owned() + &args.threads.iter().map(|t| format!("{t}t")).collect::<Vec<_>>().join(" / ");
    head += " | bytes/tri (nodes only) |";
    for (set, _) in speeds {
        for t in &args.threads {
            head += &format!(" {set} {t}t |");
        }
    }
    head += " vs lamplight: hit/miss mismatches, t rel max (> 1e-5) |";
    println!("{head}");
    println!("{}", "|---".repeat(head.matches('|').count() - 1) + "|");
    for (k, accel) in accels.iter().enumerate() {
        let (bytes, nodes) = accel.bytes();
        let mut row = format!(
            "| {} | {} | {:.1} ({:.1}) |",
            args.kinds[k].name(),
            build_ms[k].iter().map(|ms| format!("{ms:.0}")).collect::<Vec<_>>().join(" / "),
            bytes as f64 / tris as f64,
            nodes as f64 / tris as f64
        );
        for (_, speed) in speeds {
            for &(wall, cpu) in &speed[k] {
                row += &format!(" {wall:.2} ({cpu:.2}) |");
            }
        }
        row += &format!(" {} |", if k == 0 { "reference" } else { notes[k].trim_end_matches("; ") });
        println!("{row}");
    }
}

/// Counts rays that leak through the closed sheet of [`probe`] for every structure.
fn watertight_probe(args: &Args, pool: &rayon::ThreadPool) {
    let (positions, indices) = probe::sheet();
    let (origins, dirs) = probe::rays(&positions, 400_000);
    let n = origins.len();
    print!("watertightness probe ({n} rays at shared vertices and edges of a {}-triangle sheet): leaks", indices.len());
    for &kind in &args.kinds {
        let accel = pool.install(|| Accel::build(kind, &positions, &indices).0);
        let (mut t, mut p) = (vec![0.0; n], vec![0; n]);
        pool.install(|| accel.cast(&origins, &dirs, &mut t, &mut p));
        let leaks: Vec<usize> = (0..n).filter(|&i| !t[i].is_finite()).collect();
        print!("; {} {}", kind.name(), leaks.len());
        if !leaks.is_empty() {
            // By target (ray i aims at a vertex when i % 4 == 0, else at a point on the
            // x, y or diagonal edge) and side (front when i % 8 < 4), in % of such rays.
            let mut by = [[0usize; 2]; 4];
            for &i in &leaks {
                by[i % 4][usize::from(i % 8 >= 4)] += 1;
            }
            let pct = |c: usize| 100.0 * c as f64 / (n / 8) as f64;
            let part = |k: usize| format!("{:.1}/{:.1}", pct(by[k][0]), pct(by[k][1]));
            print!(" [% front/back: vertex {}, x edge {}, y edge {}, diagonal {}]", part(0), part(1), part(2), part(3));
        }
        if kind != Kind::Lamplight && !leaks.is_empty() {
            // Whether the triangle test itself leaks: every triangle against each leaking ray.
            let tris: Vec<RtTriangle> = indices
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|k| Vec3A::from_array(positions[k as usize]));
                    RtTriangle::new(a, b, c)
                })
                .collect();
            let brute = leaks
                .iter()
                .filter(|&&i| {
                    let ray = Ray::new(Vec3A::from_array(origins[i]), Vec3A::from_array(dirs[i]), 0.0, f32::INFINITY);
                    tris.iter().all(|tri| !tri.intersect(&ray).is_finite())
                })
                .count();
            print!(" ({brute} of them also missed by RtTriangle::intersect against every triangle)");
        }
    }
    println!();
}
