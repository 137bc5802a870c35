//! `<sensor>` with its `<film>`, `<rfilter>` and `<sampler>` to `[camera]` and
//! `[render]`.
//!
//! | Mitsuba | lamplight |
//! |---|---|
//! | `perspective` `fov`, `fov_axis` (`x`, `y`, `diagonal`, `smaller`, `larger`) | `perspective` `hfov` (axis x) or `vfov` (axis y; diagonal converted at the film's aspect) |
//! | a mirroring `to_world` (negative determinant) | the `window` camera with the mirrored `right` |
//! | `thinlens` `aperture_radius`, `focus_distance` | `thin_lens` `lens_radius`, `focal_distance` |
//! | `orthographic` | `orthographic`, `half_width` and `half_height` from `to_world`'s scale (`[-1, 1]` by `[-1/a, 1/a]`) |
//! | `principal_point_offset_x`, `_y` (in film widths and heights, `y` down) | `shift = [x W / L, -y H / L]`, `L = max(W, H)` (the window camera: its `window_center`) |
//! | `hdrfilm` `width`, `height` (768 x 576) | `width`, `height` |
//! | `hdrfilm` `crop_offset_x`, `crop_offset_y`, `crop_width`, `crop_height` | `crop = [x, y, width, height]` |
//! | `rfilter` `box`, `tent`, `gaussian` (stddev 0.5, the default), `mitchell` `B`, `C`, `catmullrom`, `lanczos` `lobes` (1 to 32) | `filter` `box`, `tent`, `gaussian`, `mitchell(B=b, C=c)`, `catmullrom`, `lanczos(lobes=n)` (others: warning, box) |
//! | `sampler` `sample_count` (4) | `spp` |
//!
//! Mitsuba's camera looks down its local `+z` with `+y` up and `+x` to the
//! left, so the image's right is `-to_world x`. With `fov_axis = "x"` the
//! horizontal field of view is kept when the width changes, as in Mitsuba.

use lamplight_core::film::{Filter, MAX_LOBES};
use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::params::{Loc, ParamError};

use super::properties::Plugin;
use super::xml::El;
use super::{entry, int, num, table_of, text, vec3, Ctx};

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// Reads a `<sensor>`.
pub fn read<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<(), ParamError> {
    let mut p = Plugin::new(el)?;
    let (width, height) = film(ctx, &p)?;
    let shift = principal_point(&mut p, width, height)?;
    if let (Some((_, sloc)), "thinlens") = (&shift, p.kind.as_str()) {
        ctx.warn(
            sloc,
            "sensor \"thinlens\": principal_point_offset is read as a lens shift (Mitsuba 3.9's thinlens rejects it as unreferenced)",
        );
    }
    sampler(ctx, &p)?;
    let aspect = width as f64 / height as f64;
    let (m, mloc) = p.transform("to_world")?.unwrap_or((Mat4::IDENTITY, el.loc.clone()));
    let eye = m.transform_point3(Vec3::ZERO);
    let forward = m.transform_vector3(Vec3::Z);
    let up = m.transform_vector3(Vec3::Y).normalize_or_zero();
    let right = -m.transform_vector3(Vec3::X).normalize_or_zero();
    let mirrored = m.determinant() < 0.0;
    for key in ["near_clip", "far_clip"] {
        if let Some((_, loc)) = p.number(key)? {
            ctx.warn(&loc, format!("{}: {key} is not supported (lamplight does not clip), ignored", p.label));
        }
    }
    let loc = el.loc.clone();
    let camera = match p.kind.as_str() {
        "perspective" | "thinlens" => {
            let (tx, ty, fov, floc) = field_of_view(&mut p, aspect)?;
            let lens = if p.kind == "thinlens" {
                let (r, rloc) = p.number_or("aperture_radius", 0.03)?;
                let (f, dloc) = p.number("focus_distance")?.ok_or_else(|| err(&loc, "sensor \"thinlens\": needs focus_distance"))?;
                Some((num(r, &rloc), num(f * forward.length(), &dloc)))
            } else {
                None
            };
            if mirrored {
                if lens.is_some() {
                    return Err(err(&mloc, "sensor \"thinlens\": a mirroring to_world is not supported"));
                }
                let f = forward.normalize();
                // The shift in units of the larger side is 2 [x W / L, -y H / L] of
                // the half-width and half-height vectors: 2 [x, -y] of `right`, `up`.
                let [sx, sy] = shift.as_ref().map_or([0.0; 2], |s| s.0);
                let larger = aspect.max(1.0);
                let center = eye + f + right * (tx * 2.0 * sx * larger / aspect) + up * (ty * 2.0 * sy * larger);
                table_of(
                    vec![
                        ("type", text("window", &loc)),
                        ("eye", vec3(eye, &mloc)),
                        ("window_center", vec3(center, &mloc)),
                        ("right", vec3(right * tx, &floc)),
                        ("up", vec3(up * ty, &floc)),
                    ],
                    &loc,
                )
            } else {
                let mut pairs = vec![
                    ("type", text(if lens.is_some() { "thin_lens" } else { "perspective" }, &loc)),
                    ("eye", vec3(eye, &mloc)),
                    ("look_at", vec3(eye + forward, &mloc)),
                    ("up", vec3(up, &mloc)),
                    (fov.0, num(fov.1, &floc)),
                ];
                if let Some((r, f)) = lens {
                    pairs.push(("lens_radius", r));
                    pairs.push(("focal_distance", f));
                }
                if let Some(([sx, sy], sloc)) = &shift {
                    pairs.push(("shift", super::pair(*sx, *sy, sloc)));
                }
                table_of(pairs, &loc)
            }
        }
        "orthographic" => {
            if let Some((_, sloc)) = &shift {
                return Err(err(sloc, "sensor \"orthographic\": principal_point_offset is not supported, expected 0"));
            }
            if mirrored {
                return Err(err(&mloc, "sensor \"orthographic\": a mirroring to_world is not supported"));
            }
            let half_w = m.transform_vector3(Vec3::X).length();
            let half_h = m.transform_vector3(Vec3::Y).length() / aspect;
            table_of(
                vec![
                    ("type", text("orthographic", &loc)),
                    ("eye", vec3(eye, &mloc)),
                    ("look_at", vec3(eye + forward, &mloc)),
                    ("up", vec3(up, &mloc)),
                    ("half_width", num(half_w, &mloc)),
                    ("half_height", num(half_h, &mloc)),
                ],
                &loc,
            )
        }
        other => {
            return Err(err(
                &p.el.require("type")?.loc,
                format!(
                    "sensor: {}",
                    lamplight_core::params::unknown_among(
                        "sensor type",
                        other,
                        &["perspective", "thinlens", "orthographic"],
                        "lamplight reads"
                    )
                ),
            ))
        }
    };
    ctx.camera = Some(camera);
    for o in p.objects.clone() {
        if !matches!(o.tag.as_str(), "film" | "sampler") {
            ctx.warn(&o.loc, format!("{}: nested <{}> is not supported, ignored", p.label, o.tag));
        }
    }
    ctx.finish(p);
    Ok(())
}

/// `principal_point_offset_x` and `_y` as lamplight's lens shift `[sx, sy]`
/// (units of the larger side, `y` up), with where the first of them is
/// written; `None` when both are absent or 0. Mitsuba moves the view right by
/// `x` film widths and down by `y` film heights (checked against Mitsuba 3.9:
/// `x = 0.25` turns the centre ray to a quarter of the width right of the axis).
fn principal_point(p: &mut Plugin<'_>, width: u32, height: u32) -> Result<Option<([f64; 2], Loc)>, ParamError> {
    let mut offset = [0.0; 2];
    let mut at = None;
    for (k, key) in ["principal_point_offset_x", "principal_point_offset_y"].into_iter().enumerate() {
        if let Some((v, loc)) = p.number(key)? {
            if !(v.is_finite() && v.abs() <= lamplight_core::camera::perspective::MAX_SHIFT) {
                return Err(err(&loc, format!("{}: {key}: expected a finite number of at most 100 in magnitude, got {v}", p.label)));
            }
            offset[k] = v;
            at.get_or_insert(loc);
        }
    }
    if offset == [0.0; 2] {
        return Ok(None);
    }
    let larger = width.max(height) as f64;
    Ok(at.map(|loc| ([offset[0] * width as f64 / larger, -offset[1] * height as f64 / larger], loc)))
}

/// `tan(hfov / 2)`, `tan(vfov / 2)`, the kept key and degrees, and where the field of view is written.
type FieldOfView = (f64, f64, (&'static str, f64), Loc);

/// `tan` of half the horizontal and vertical fields of view, the camera key
/// that keeps the field of view (`hfov` for axis x, else `vfov`) with its
/// degrees, and where it is written.
fn field_of_view(p: &mut Plugin<'_>, aspect: f64) -> Result<FieldOfView, ParamError> {
    let (fov, floc) = match (p.number("fov")?, p.string("focal_length")?) {
        (Some(f), _) => f,
        (None, Some((mm, loc))) => (focal_length_fov(&mm, &loc, &p.label)?, loc),
        (None, None) => (2.0 * (43.266615f64 / 100.0).atan().to_degrees(), p.el.loc.clone()),
    };
    let diagonal_default = !p.has("fov");
    if !(fov > 0.0 && fov < 180.0) {
        return Err(err(&floc, format!("{}: fov: must be between 0 and 180 degrees, got {fov}", p.label)));
    }
    let axis = match p.string("fov_axis")? {
        None if diagonal_default => "diagonal".to_string(),
        None => "x".to_string(),
        Some((a, loc)) => match a.as_str() {
            "x" | "y" | "diagonal" => a,
            "smaller" => if aspect > 1.0 { "y" } else { "x" }.to_string(),
            "larger" => if aspect > 1.0 { "x" } else { "y" }.to_string(),
            _ => return Err(err(&loc, format!("{}: fov_axis: expected x, y, diagonal, smaller or larger, got \"{a}\"", p.label))),
        },
    };
    let t = (fov.to_radians() / 2.0).tan();
    let (tx, ty) = match axis.as_str() {
        "x" => (t, t / aspect),
        "y" => (t * aspect, t),
        _ => {
            let d = (1.0 + aspect * aspect).sqrt();
            (t * aspect / d, t / d)
        }
    };
    let kept = match axis.as_str() {
        "x" => ("hfov", fov),
        "y" => ("vfov", fov),
        _ => ("vfov", 2.0 * ty.atan().to_degrees()),
    };
    Ok((tx, ty, kept, floc))
}

/// The diagonal field of view in degrees of a 35 mm `focal_length` such as
/// `"50mm"`: a 35 mm film's diagonal is 43.27 mm (Mitsuba's conversion).
pub(super) fn focal_length_fov(mm: &str, loc: &Loc, label: &str) -> Result<f64, ParamError> {
    let v: f64 = mm
        .trim_end_matches("mm")
        .trim()
        .parse()
        .map_err(|_| err(loc, format!("{label}: focal_length: expected such as \"50mm\", got \"{mm}\"")))?;
    Ok(2.0 * (43.266615 / (2.0 * v)).atan().to_degrees())
}

/// The film's size and filter into `[render]`.
fn film(ctx: &mut Ctx<'_>, sensor: &Plugin<'_>) -> Result<(u32, u32), ParamError> {
    let Some(el) = sensor.objects.iter().copied().find(|o| o.tag == "film") else {
        ctx.render.push(entry("width", int(768, &sensor.el.loc)));
        ctx.render.push(entry("height", int(576, &sensor.el.loc)));
        ctx.render.push(entry("filter", text("gaussian", &sensor.el.loc)));
        return Ok((768, 576));
    };
    let el = ctx.deref(el)?;
    let mut p = Plugin::new(el)?;
    if !matches!(p.kind.as_str(), "hdrfilm" | "specfilm") {
        ctx.warn(&el.loc, format!("{}: read as hdrfilm (size and filter only)", p.label));
    }
    let mut side = |p: &mut Plugin<'_>, key: &str, default: i64| -> Result<i64, ParamError> {
        let (v, loc) = p.integer(key)?.unwrap_or((default, el.loc.clone()));
        if !(1..=1 << 16).contains(&v) {
            return Err(err(&loc, format!("{}: {key}: must be between 1 and 65536, got {v}", p.label)));
        }
        ctx.render.push(entry(key, int(v, &loc)));
        Ok(v)
    };
    let width = side(&mut p, "width", 768)?;
    let height = side(&mut p, "height", 576)?;
    crop(ctx, &mut p, width, height)?;
    for key in ["file_format", "pixel_format", "component_format", "banner", "high_quality_edges", "sample_border"] {
        let _ = p.take(key);
    }
    let filter = match p.objects.iter().copied().find(|o| o.tag == "rfilter") {
        None => "gaussian".to_string(),
        Some(f) => {
            let f = ctx.deref(f)?;
            let mut fp = Plugin::new(f)?;
            let filter = match fp.kind.as_str() {
                "box" => Filter::Box,
                "tent" => {
                    if let Some((r, loc)) = fp.number("radius")? {
                        if r != 1.0 {
                            ctx.warn(&loc, format!("rfilter \"tent\": radius {r} is read as 1 (lamplight's tent)"));
                        }
                    }
                    Filter::Tent
                }
                "gaussian" => {
                    if let Some((s, loc)) = fp.number("stddev")? {
                        if s != 0.5 {
                            ctx.warn(&loc, format!("rfilter \"gaussian\": stddev {s} is read as 0.5 (lamplight's gaussian)"));
                        }
                    }
                    Filter::Gaussian { sigma: 0.5 }
                }
                "mitchell" => {
                    let b = fp.number("B")?.map_or(1.0 / 3.0, |(b, _)| b);
                    let c = fp.number("C")?.map_or(1.0 / 3.0, |(c, _)| c);
                    Filter::Mitchell { b, c }
                }
                "catmullrom" => Filter::CatmullRom,
                "lanczos" => {
                    let lobes = match fp.integer("lobes")? {
                        None => 3,
                        Some((n, loc)) => match u32::try_from(n) {
                            Ok(n) if (1..=MAX_LOBES).contains(&n) => n,
                            _ => return Err(err(&loc, format!("rfilter \"lanczos\": lobes must be between 1 and {MAX_LOBES}, got {n}"))),
                        },
                    };
                    Filter::Lanczos { lobes }
                }
                other => {
                    ctx.warn(&f.loc, format!("rfilter \"{other}\": not supported, the box filter is used"));
                    Filter::Box
                }
            };
            ctx.finish(fp);
            filter.to_string()
        }
    };
    ctx.render.push(entry("filter", text(&filter, &el.loc)));
    ctx.finish(p);
    Ok((width as u32, height as u32))
}

/// The film's crop window into `[render] crop`: `crop_offset_x`, `_y` (0) and
/// `crop_width`, `crop_height` (the rest of the film), inside the film.
fn crop(ctx: &mut Ctx<'_>, p: &mut Plugin<'_>, width: i64, height: i64) -> Result<(), ParamError> {
    let mut read = |key: &str| p.integer(key);
    let (x, y) = (read("crop_offset_x")?, read("crop_offset_y")?);
    let (w, h) = (read("crop_width")?, read("crop_height")?);
    let Some(loc) = [&x, &y, &w, &h].into_iter().flatten().map(|(_, l)| l.clone()).next() else { return Ok(()) };
    let bad = |(v, loc): &(i64, Loc), message: String| if *v < 0 { Err(err(loc, message)) } else { Ok(()) };
    for (v, key) in [(&x, "crop_offset_x"), (&y, "crop_offset_y")] {
        if let Some(v) = v {
            bad(v, format!("{}: {key}: must be at least 0, got {}", p.label, v.0))?;
        }
    }
    let (x0, y0) = (x.as_ref().map_or(0, |v| v.0), y.as_ref().map_or(0, |v| v.0));
    let cw = w.as_ref().map_or(width - x0, |v| v.0);
    let ch = h.as_ref().map_or(height - y0, |v| v.0);
    for (v, side, key, full, offset) in [(cw, &w, "crop_width", width, x0), (ch, &h, "crop_height", height, y0)] {
        if v < 1 || offset + v > full {
            let at = side.as_ref().map_or(&loc, |s| &s.1);
            return Err(err(
                at,
                format!("{}: {key}: the crop window ({x0}, {y0}) + {cw} x {ch} must have a size >= 1 and lie inside the {width} x {height} film", p.label),
            ));
        }
    }
    let item = |v: i64| int(v, &loc);
    let value = lamplight_core::params::Value::Array(vec![item(x0), item(y0), item(cw), item(ch)]);
    ctx.render.push(entry("crop", lamplight_core::params::Item { value, loc: loc.clone() }));
    Ok(())
}

/// `sample_count` into `spp`.
fn sampler(ctx: &mut Ctx<'_>, sensor: &Plugin<'_>) -> Result<(), ParamError> {
    let Some(el) = sensor.objects.iter().copied().find(|o| o.tag == "sampler") else {
        ctx.render.push(entry("spp", int(4, &sensor.el.loc)));
        return Ok(());
    };
    let el = ctx.deref(el)?;
    let mut p = Plugin::new(el)?;
    let (spp, loc) = p.integer("sample_count")?.unwrap_or((4, el.loc.clone()));
    ctx.render.push(entry("spp", int(spp, &loc)));
    // The sampler's pattern and seed change the noise, not the expected image.
    for key in ["seed", "jitter", "scramble_type", "dimension"] {
        let _ = p.take(key);
    }
    ctx.finish(p);
    Ok(())
}
