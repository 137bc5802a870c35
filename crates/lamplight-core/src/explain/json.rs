//! The explanation as JSON: the same tree as the text, every number in full
//! precision (vectors and colours as `[x, y, z]`; an infinite distance, a
//! directional light's, as `null`, which JSON has no number for).

use serde_json::{json, Value};

use super::{HitInfo, NeeRecord, PathRecord, PixelExplanation, Record, SampleExplanation, SampleSummary, Sampling};
use super::{LightOutcome, LightRecord, RayKind, RayNode, RayOutcome};
use crate::integrators::trace::{LightRef, PathEnd, ReflectionWeight, Unlit};
use crate::math::Vec3;

fn v(x: Vec3) -> Value {
    json!([x.x, x.y, x.z])
}

/// The whole explanation.
pub(super) fn pixel(p: &PixelExplanation) -> Value {
    json!({
        "integrator": p.integrator,
        "pixel": [p.x, p.y],
        "width": p.width,
        "height": p.height,
        "spp": p.spp,
        "seed": p.seed,
        "max_depth": p.max_depth,
        "value": p.pixel,
        "sampling": sampling(&p.sampling),
        "samples": p.samples.iter().map(sample).collect::<Vec<_>>(),
        "unrecorded": p.unrecorded.as_ref().map(unrecorded),
    })
}

/// The samples past the recorded ones, summarised.
fn unrecorded(u: &SampleSummary) -> Value {
    json!({
        "first": u.first,
        "count": u.count,
        "why": match u.why {
            super::Unrecorded::PastCount => json!("count"),
            super::Unrecorded::Memory { allowance } => json!({ "memory_allowance": allowance }),
        },
        "dropped": u.dropped,
        "film_sum": v(u.film_sum),
        "mean": v(u.mean),
        "brightest": u.brightest.map(|(k, l)| json!({ "index": k, "film_value": v(l) })),
    })
}

fn sampling(s: &Sampling) -> Value {
    match *s {
        Sampling::Fixed => json!("fixed"),
        Sampling::Antialias { threshold, refined, samples } => {
            json!({ "antialias": { "threshold": threshold, "refined": refined, "samples": samples } })
        }
        Sampling::NoiseThreshold { threshold, min_samples, max_samples } => {
            json!({ "noise_threshold": { "threshold": threshold, "min_samples": min_samples, "max_samples": max_samples } })
        }
    }
}

fn sample(s: &SampleExplanation) -> Value {
    let mut out = json!({
        "index": s.index,
        "radiance": v(s.radiance),
        "film_value": s.film_value.map(v),
        "contributions": s.contributions.iter().map(|c| v(*c)).collect::<Vec<_>>(),
    });
    match &s.record {
        Record::RayTree(root) => out["ray"] = ray(root),
        Record::Path(path) => out["path"] = path_json(path),
        Record::Nothing => {}
    }
    out
}

fn hit(h: &HitInfo) -> Value {
    json!({
        "t": h.t,
        "point": v(h.point),
        "object": h.object,
        "object_name": h.object_name,
        "object_kind": h.object_kind,
        "material": h.material,
        "material_name": h.material_name,
        "geometric_normal": v(h.geometric_normal),
        "shading_normal": v(h.shading_normal),
        "front_face": h.front_face,
        "normal_flipped": h.flipped,
    })
}

fn ray(n: &RayNode) -> Value {
    let kind = match n.kind {
        RayKind::Camera => "camera",
        RayKind::Reflected => "reflected",
        RayKind::Refracted => "refracted",
    };
    let mut out = json!({
        "kind": kind,
        "origin": v(n.ray.origin),
        "direction": v(n.ray.dir),
        "depth": n.depth,
        "weight": v(n.weight),
        "inside": n.inside,
    });
    match &n.outcome {
        RayOutcome::Dropped => out["dropped"] = json!("weight at or below the scene's min_weight"),
        RayOutcome::Miss { radiance, contribution } => {
            out["miss"] = json!({ "sky": v(*radiance) });
            out["contribution"] = v(*contribution);
        }
        RayOutcome::Hit(s) => {
            out["hit"] = hit(&s.hit);
            out["terms"] = json!({
                "color": v(s.color),
                "emission": v(s.emission),
                "ambient": v(s.ambient),
                "lights": s.lights.iter().map(light).collect::<Vec<_>>(),
                "direct": v(s.direct),
            });
            out["contribution"] = v(s.contribution);
            if let Some((how, w)) = &s.reflection {
                out["reflection"] = match how {
                    ReflectionWeight::Constant => json!({ "how": "constant", "weight": v(*w) }),
                    ReflectionWeight::Dielectric { fresnel } => json!({ "how": "fresnel", "F": fresnel, "weight": v(*w) }),
                    ReflectionWeight::Conductor => json!({ "how": "conductor", "weight": v(*w) }),
                };
            }
            if let Some((fresnel, w)) = &s.refraction {
                out["refraction"] = json!({
                    "F": fresnel,
                    "one_minus_F": fresnel.map(|f| 1.0 - f),
                    "weight": w.map(v),
                    "total_internal_reflection": w.is_none(),
                });
            }
            if s.depth_cutoff {
                out["depth_cutoff"] = json!(true);
            }
        }
    }
    out["children"] = Value::Array(n.children.iter().map(ray).collect());
    out
}

fn light(l: &LightRecord) -> Value {
    let mut out = match l.light {
        LightRef::Delta(i) => json!({ "light": i }),
        LightRef::Area { object, sample } => json!({ "area_light_object": object, "point": sample }),
    };
    out["kind"] = json!(l.kind);
    match &l.outcome {
        LightOutcome::Unlit(why) => {
            out["unlit"] = match why {
                Unlit::NotReached => json!("the light sends nothing here"),
                Unlit::Below(cos) => json!(format!("below the surface (L.N = {cos})")),
                Unlit::Negligible => json!("negligible (kd C (L.N) + ks (H.N)^n below 1e-12)"),
            };
            out["radiance"] = json!([0.0, 0.0, 0.0]);
        }
        LightOutcome::Lit { term: t, blockers } => {
            out["L"] = v(t.wi);
            out["distance"] = json!(t.distance);
            out["Lin"] = v(t.lin);
            out["L.N"] = json!(t.cos_light);
            out["H.N"] = json!(t.cos_half);
            out["diffuse"] = v(t.diffuse);
            out["specular"] = v(t.specular);
            out["shadow_ray"] = json!({
                "origin": v(t.shadow.origin),
                "direction": v(t.shadow.dir),
                "length": t.shadow_length,
                "transmittance": v(t.visible),
                "blocked": t.visible == crate::math::Rgb::ZERO,
                "blocked_by": blockers.iter().map(|b| json!({ "object": b.object, "name": b.name, "kind": b.kind })).collect::<Vec<_>>(),
            });
            out["radiance"] = v(t.radiance);
        }
    }
    out
}

fn path_json(p: &PathRecord) -> Value {
    let end = p.end.map(|e| match e {
        PathEnd::Escaped => json!("escaped"),
        PathEnd::MaxDepth => json!("max_depth"),
        PathEnd::BlackBsdf => json!("the surface scatters nothing"),
        PathEnd::NoSample => json!("the BSDF sample failed"),
        PathEnd::WrongSide => json!("the sample is below the geometric surface"),
        PathEnd::Roulette { survive, u } => json!({ "russian_roulette": { "survive": survive, "u": u } }),
    });
    let vertices: Vec<Value> = p
        .vertices
        .iter()
        .map(|x| {
            let mut out = json!({
                "depth": x.depth,
                "origin": v(x.ray.origin),
                "direction": v(x.ray.dir),
                "throughput": v(x.beta),
                "hit": x.hit.as_ref().map(hit),
            });
            if let Some((le, w, c)) = x.emitted {
                out["emitted"] = json!({ "Le": v(le), "mis_weight": w, "contribution": v(c) });
            }
            match &x.nee {
                None => {}
                Some(NeeRecord::Miss(why)) => out["light_sample"] = json!({ "none": format!("{why:?}") }),
                Some(NeeRecord::Sample { light, pick_probability, wi, distance, li, light_pdf, f, cos, bsdf_pdf, mis_weight, value }) => {
                    out["light_sample"] = json!({
                        "light": light, "pick_probability": pick_probability, "wi": v(*wi), "distance": distance,
                        "Li": v(*li), "light_pdf": light_pdf, "f": v(*f), "cos": cos, "bsdf_pdf": bsdf_pdf,
                        "mis_weight": mis_weight, "value": v(*value),
                    })
                }
            }
            if let Some(c) = x.nee_contribution {
                out["light_sample_contribution"] = v(c);
            }
            if let Some((s, wi, beta)) = &x.bsdf {
                out["bsdf_sample"] = json!({
                    "wi": v(*wi), "weight": v(s.weight), "pdf": s.pdf, "delta": s.delta, "eta": s.eta, "throughput_after": v(*beta),
                });
            }
            if let Some((survive, beta)) = x.survived {
                out["russian_roulette"] = json!({ "survive": survive, "throughput_after": v(beta) });
            }
            out
        })
        .collect();
    json!({ "vertices": vertices, "end": end })
}
