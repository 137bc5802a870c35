//! The explanation as an indented tree for a reader: each ray with its hit, the
//! lecture's terms there and what the hit adds to the pixel; the children
//! indented below. Numbers have 4 decimals (the JSON has them in full).

use std::fmt::{self, Write};

use super::{HitInfo, NeeRecord, PathRecord, PixelExplanation, Record, Sampling};
use super::{LightOutcome, LightRecord, RayKind, RayNode, RayOutcome};
use crate::integrators::trace::{LightRef, PathEnd, ReflectionWeight, Unlit};
use crate::math::{Rgb, Vec3};

/// `(x, y, z)` with 4 decimals.
fn v(x: Vec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", x.x, x.y, x.z)
}

pub(super) fn write_pixel(f: &mut fmt::Formatter<'_>, p: &PixelExplanation) -> fmt::Result {
    writeln!(
        f,
        "pixel ({}, {}) of {}x{}, {} integrator, {} sample{} here, max depth {}, seed {}",
        p.x,
        p.y,
        p.width,
        p.height,
        p.integrator,
        p.spp,
        if p.spp == 1 { "" } else { "s" },
        p.max_depth,
        p.seed
    )?;
    let pixel = Vec3::new(p.pixel[0] as f64, p.pixel[1] as f64, p.pixel[2] as f64);
    writeln!(f, "pixel value (linear, before tone mapping): {}", v(pixel))?;
    match p.sampling {
        Sampling::Fixed => {}
        Sampling::Antialias { threshold, refined: true, samples } => {
            writeln!(f, "adaptive anti-aliasing: a neighbour's colour differs by more than {threshold}, so the pixel takes {samples} samples")?
        }
        Sampling::Antialias { threshold, refined: false, .. } => {
            writeln!(f, "adaptive anti-aliasing: no neighbour's colour differs by more than {threshold}, so the pixel takes one sample")?
        }
        Sampling::NoiseThreshold { threshold, min_samples, max_samples } => writeln!(
            f,
            "noise threshold {threshold}: {} of at most {max_samples} samples (a pixel stops, from {min_samples} samples on, once its error is below the threshold at two checks in a row)",
            p.spp
        )?,
    }
    for s in &p.samples {
        writeln!(f)?;
        let n = s.contributions.len();
        writeln!(f, "sample {}: radiance {} = the sum of its {n} contribution{}", s.index, v(s.radiance), if n == 1 { "" } else { "s" })?;
        match s.film_value {
            Some(l) if l != s.radiance => writeln!(f, "  the film keeps {} (clamped)", v(l))?,
            None => writeln!(f, "  the film drops it (not finite)")?,
            _ => {}
        }
        match &s.record {
            Record::RayTree(root) => write_ray(f, root, "")?,
            Record::Path(path) => write_path(f, path)?,
            Record::Nothing => writeln!(f, "  (this integrator records nothing)")?,
        }
    }
    if let Some(u) = &p.unrecorded {
        writeln!(f)?;
        let last = u.first + u.count - 1;
        match u.why {
            super::Unrecorded::PastCount => writeln!(
                f,
                "samples {} to {last}: traced, not recorded (an explanation records the first {} of a pixel; --sample K shows any one)",
                u.first,
                super::MAX_RECORDED_SAMPLES
            )?,
            super::Unrecorded::Memory { allowance } => writeln!(
                f,
                "samples {} to {last}: traced, not recorded: their records would pass the explanation's memory allowance of {:.1} MiB \
                 (a larger memory budget records more)",
                u.first,
                allowance as f64 / (1 << 20) as f64
            )?,
        }
        write!(f, "  {} samples, mean film value {}", u.count, v(u.mean))?;
        if u.dropped > 0 {
            write!(f, ", {} dropped by the film (not finite)", u.dropped)?;
        }
        match u.brightest {
            Some((k, l)) => writeln!(f, "; the brightest is sample {k}, film value {}", v(l))?,
            None => writeln!(f)?,
        }
    }
    if p.samples.len() > 1 || p.unrecorded.is_some() {
        writeln!(f)?;
        writeln!(f, "pixel = sum of the {} samples' film values / {} = {}", p.spp, p.spp, v(pixel))?;
    }
    Ok(())
}

fn hit_lines(h: &HitInfo) -> [String; 2] {
    let side = if h.front_face { "front face (outside, entering)" } else { "back face (inside, leaving): normals flipped to face the ray" };
    [
        format!(
            "hit object {}{} ({}), material {}{}, at t = {:.4}, point {}",
            h.object,
            h.object_name.as_ref().map_or(String::new(), |n| format!(" \"{n}\"")),
            h.object_kind,
            h.material,
            h.material_name.as_ref().map_or(String::new(), |n| format!(" \"{n}\"")),
            h.t,
            v(h.point)
        ),
        format!("normal: geometric {}, shading {}; {side}", v(h.geometric_normal), v(h.shading_normal)),
    ]
}

fn write_ray(f: &mut fmt::Formatter<'_>, n: &RayNode, indent: &str) -> fmt::Result {
    let kind = match n.kind {
        RayKind::Camera => "camera ray",
        RayKind::Reflected => "reflected ray",
        RayKind::Refracted => "refracted ray",
    };
    let side = if n.inside { "inside" } else { "outside" };
    writeln!(f, "{indent}- {kind}, depth {}, {side}: origin {}, direction {}", n.depth, v(n.ray.origin), v(n.ray.dir))?;
    let inner = format!("{indent}    ");
    let i = inner.as_str();
    if n.kind != RayKind::Camera {
        writeln!(f, "{i}weight from above: {}", v(n.weight))?;
    }
    match &n.outcome {
        RayOutcome::Dropped => writeln!(f, "{i}not traced: its weight is at or below the scene's min_weight")?,
        RayOutcome::Miss { radiance, contribution } => {
            writeln!(f, "{i}misses everything: sky {}", v(*radiance))?;
            writeln!(f, "{i}contribution = weight x sky = {}", v(*contribution))?;
        }
        RayOutcome::Hit(s) => {
            for line in hit_lines(&s.hit) {
                writeln!(f, "{i}{line}")?;
            }
            writeln!(f, "{i}colour C = {}", v(s.color))?;
            if s.emission != Rgb::ZERO {
                writeln!(f, "{i}emission Ke = {}", v(s.emission))?;
            }
            writeln!(f, "{i}ambient ka*C*La = {}", v(s.ambient))?;
            write_lights(f, &s.lights, i)?;
            writeln!(f, "{i}direct light = {}", v(s.direct))?;
            writeln!(f, "{i}contribution = weight x direct = {}", v(s.contribution))?;
            match &s.reflection {
                Some((ReflectionWeight::Dielectric { fresnel }, w)) => {
                    writeln!(f, "{i}reflection: Fresnel F = {fresnel:.4}, weight {}", v(*w))?
                }
                Some((ReflectionWeight::Conductor, w)) => writeln!(f, "{i}reflection: conductor Fresnel, weight {}", v(*w))?,
                Some((ReflectionWeight::Constant, w)) => writeln!(f, "{i}reflection: constant weight {}", v(*w))?,
                None => {}
            }
            match &s.refraction {
                Some((_, None)) => writeln!(f, "{i}refraction: total internal reflection")?,
                Some((Some(fresnel), Some(w))) => writeln!(f, "{i}refraction: 1 - F = {:.4}, weight {}", 1.0 - fresnel, v(*w))?,
                Some((None, Some(w))) => writeln!(f, "{i}refraction: constant weight {}", v(*w))?,
                None => {}
            }
            if s.depth_cutoff {
                writeln!(f, "{i}depth limit reached: no reflected or refracted ray")?;
            }
        }
    }
    for child in &n.children {
        write_ray(f, child, i)?;
    }
    Ok(())
}

fn write_lights(f: &mut fmt::Formatter<'_>, lights: &[LightRecord], i: &str) -> fmt::Result {
    let mut k = 0;
    while k < lights.len() {
        let l = &lights[k];
        match l.light {
            LightRef::Delta(index) => {
                let lines = light_lines(&l.outcome);
                writeln!(f, "{i}light {index} ({}): {}", l.kind, lines[0])?;
                for line in &lines[1..] {
                    writeln!(f, "{i}{line}")?;
                }
                k += 1;
            }
            LightRef::Area { object, .. } => {
                // The points of one area light, summarised on one line.
                let end = lights[k..]
                    .iter()
                    .position(|m| !matches!(m.light, LightRef::Area { object: o, .. } if o == object))
                    .map_or(lights.len(), |p| k + p);
                let points = &lights[k..end];
                let (mut lit, mut blocked, mut sum, mut by) = (0, 0, Rgb::ZERO, Vec::new());
                for p in points {
                    if let LightOutcome::Lit { term, blockers } = &p.outcome {
                        if term.visible == Rgb::ZERO {
                            blocked += 1;
                        } else {
                            lit += 1;
                        }
                        sum += term.radiance;
                        for b in blockers {
                            if !by.contains(b) {
                                by.push(b.clone());
                            }
                        }
                    }
                }
                let unlit = points.len() - lit - blocked;
                let mut line = format!(
                    "{i}area light, object {object} ({}): {} points, {lit} lit, {blocked} shadowed, {unlit} below the surface or unreached",
                    l.kind,
                    points.len()
                );
                if !by.is_empty() {
                    let _ = write!(line, " (by {})", by.iter().map(|b| b.to_string()).collect::<Vec<_>>().join(", "));
                }
                writeln!(f, "{line}; adds {}", v(sum))?;
                k = end;
            }
        }
    }
    Ok(())
}

/// The light's line and, when its shadow ray was traced, two more for its terms.
fn light_lines(o: &LightOutcome) -> Vec<String> {
    match o {
        LightOutcome::Unlit(Unlit::NotReached) => vec!["sends nothing here".into()],
        LightOutcome::Unlit(Unlit::Below(cos)) => vec![format!("below the surface (L.N = {cos:.4}): nothing")],
        LightOutcome::Unlit(Unlit::Negligible) => vec!["negligible highlight: nothing, no shadow ray".into()],
        LightOutcome::Lit { term: t, blockers } => {
            let shadow = if t.visible == Rgb::ONE {
                "shadow ray clear".to_string()
            } else if t.visible == Rgb::ZERO {
                format!("shadow ray BLOCKED by {}", blockers.last().map_or("?".into(), |b| b.to_string()))
            } else {
                let by: Vec<String> = blockers.iter().map(|b| b.to_string()).collect();
                format!("shadow ray dimmed to {} by {}", v(t.visible), by.join(", "))
            };
            vec![
                format!("L.N = {:.4}, H.N = {:.4}, Lin = {}", t.cos_light, t.cos_half, v(t.lin)),
                format!("  kd C (L.N)+ = {}, ks ((H.N)+)^shine = {}", v(t.diffuse), v(t.specular)),
                format!("  {shadow}: adds Lin x (diffuse + specular) = {}", v(t.radiance)),
            ]
        }
    }
}

fn write_path(f: &mut fmt::Formatter<'_>, p: &PathRecord) -> fmt::Result {
    for x in &p.vertices {
        let kind = if x.depth == 1 { "camera ray" } else { "bounce" };
        writeln!(f, "  - {kind} {}: origin {}, direction {}, throughput {}", x.depth, v(x.ray.origin), v(x.ray.dir), v(x.beta))?;
        let i = "      ";
        match &x.hit {
            Some(h) => {
                for line in hit_lines(h) {
                    writeln!(f, "{i}{line}")?;
                }
            }
            None => writeln!(f, "{i}misses everything")?,
        }
        if let Some((le, w, c)) = x.emitted {
            writeln!(f, "{i}emission Le = {}, MIS weight {w:.4}: contribution throughput x Le x w = {}", v(le), v(c))?;
        }
        match &x.nee {
            None => {}
            Some(NeeRecord::Miss(why)) => writeln!(f, "{i}light sample: nothing ({why:?})")?,
            Some(NeeRecord::Sample { light, pick_probability, wi, li, light_pdf, f: fv, cos, bsdf_pdf, mis_weight, value, .. }) => {
                writeln!(f, "{i}light sample: {light} (picked with p = {pick_probability:.4}) towards {}, Li = {}", v(*wi), v(*li))?;
                let pdf = light_pdf.map_or("a delta light (no MIS)".to_string(), |p| format!("light pdf {p:.4}, BSDF pdf {bsdf_pdf:.4}"));
                writeln!(f, "{i}  f = {}, |cos| = {cos:.4}, {pdf}, MIS weight {mis_weight:.4}", v(*fv))?;
                writeln!(f, "{i}  value f Li |cos| w / (p pdf) = {}", v(*value))?;
            }
        }
        if let Some(c) = x.nee_contribution {
            writeln!(f, "{i}contribution throughput x light sample = {}", v(c))?;
        }
        if let Some((s, wi, beta)) = &x.bsdf {
            let pdf = if s.delta { "delta lobe".to_string() } else { format!("pdf {:.4}", s.pdf) };
            writeln!(f, "{i}BSDF sample: direction {}, f|cos|/pdf = {}, {pdf}; throughput now {}", v(*wi), v(s.weight), v(*beta))?;
        }
        if let Some((survive, beta)) = x.survived {
            writeln!(f, "{i}Russian roulette: survived with p = {survive:.4}, throughput now {}", v(beta))?;
        }
    }
    let end = match p.end {
        Some(PathEnd::Escaped) => "it left the scene".to_string(),
        Some(PathEnd::MaxDepth) => "the depth limit".to_string(),
        Some(PathEnd::BlackBsdf) => "the surface scatters nothing".to_string(),
        Some(PathEnd::NoSample) => "the BSDF sample failed".to_string(),
        Some(PathEnd::WrongSide) => "the sample went below the geometric surface".to_string(),
        Some(PathEnd::Roulette { survive, u }) => format!("Russian roulette (u = {u:.4} >= survival {survive:.4})"),
        None => "?".to_string(),
    };
    writeln!(f, "  path ends: {end}")
}
