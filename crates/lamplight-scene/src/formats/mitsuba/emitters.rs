//! `<emitter>` to lights, emission and the sky.
//!
//! lamplight's path tracer reads a point or spot light's `intensity I` as the
//! radiant intensity `pi I` and a directional light's `radiance E` as the
//! irradiance `pi E` (so that the lecture's Whitted terms stay the same), so
//! Mitsuba's values are divided by `pi`:
//!
//! | Mitsuba | lamplight |
//! |---|---|
//! | `point` `intensity` (W/sr), `position` or `to_world` | `point_light` `intensity / pi` |
//! | `spot` `intensity`, `cutoff_angle` (20), `beam_width` (3/4 of the cutoff), `to_world` (shines along `+z`) | `spot_light` `intensity / pi`, `outer_angle`, `inner_angle`, `profile = "angle"` (linear in the angle, as Mitsuba's) |
//! | `directional` `irradiance`, `direction` or `to_world` | `directional_light` `radiance = irradiance / pi` |
//! | `area` `radiance` (inside a shape; a colour or a texture) | the shape's material's `emission` (a texture: its value at the hit's `uv`, and at each point that light sampling picks: [`area_radiance`]) |
//! | `constant` `radiance` | `background` |
//! | `envmap` `filename`, `scale`, `to_world` (a turn about `+y`) | `environment` `file`, `strength`, `rotate` (Mitsuba's `u` is lamplight's plus one half: a turn of 180 degrees), `filter = "bilinear"` (Mitsuba's lookup) |
//!
//! | `spot` `texture` | `spot_light` `texture`, `up = [0, -1, 0]` (so that the image's axes are Mitsuba's local x and y) |
//! | `projector` `irradiance`, `scale`, `fov`, `fov_axis`, `focal_length`, `to_world` (looks along `+z`) | `projector` `texture`, `strength = scale` (Mitsuba already lights a facing plane with `pi T`), `fov`, `fov_axis` (a focal length as a diagonal field of view), `up = [0, 1, 0]` |

use std::f64::consts::PI;

use lamplight_core::math::{Mat4, Rgb, Vec3};
use lamplight_core::params::{Item, Loc, ParamError};

use super::properties::Plugin;
use super::xml::El;
use super::{entry, matrix, num, table_of, text, textures, vec3, Ctx};

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// A colour parameter of an emitter (default `default`), checked non-negative.
fn radiant(p: &mut Plugin<'_>, key: &str, default: f64) -> Result<(Rgb, Loc), ParamError> {
    if let Some(o) = p.object(key) {
        return Err(err(&o.loc, format!("{}: {key}: a texture here is not supported, expected a colour", p.label)));
    }
    let (c, loc) = p.color(key)?.unwrap_or((Rgb::splat(default), p.el.loc.clone()));
    if c.min_element() < 0.0 {
        return Err(err(&loc, format!("{}: {key}: must be non-negative, got {c}", p.label)));
    }
    Ok((c, loc))
}

/// Reads a top-level `<emitter>`.
pub fn read<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<(), ParamError> {
    let mut p = Plugin::new(el)?;
    let loc = el.loc.clone();
    let to_world = p.transform("to_world")?;
    let mut node: Vec<(&str, Item)> = Vec::new();
    match p.kind.as_str() {
        "point" => {
            let (i, iloc) = radiant(&mut p, "intensity", 1.0)?;
            let (pos, ploc) = p.vec3("position")?.unwrap_or((Vec3::ZERO, loc.clone()));
            node.push(("type", text("point_light", &loc)));
            node.push(("position", vec3(pos, &ploc)));
            node.push(("intensity", vec3(i / PI, &iloc)));
        }
        "spot" => {
            let (i, iloc) = radiant(&mut p, "intensity", 1.0)?;
            let texture = match p.object("texture") {
                None => None,
                Some(o) => {
                    if to_world.as_ref().is_some_and(|(m, _)| mirrors(m)) {
                        return Err(err(&o.loc, "emitter \"spot\": a projected texture under a mirroring to_world is not supported"));
                    }
                    Some(textures::colour_or_texture(ctx, &mut p, "texture", Rgb::ONE)?)
                }
            };
            let (cutoff, cloc) = p.number_or("cutoff_angle", 20.0)?;
            let (beam, bloc) = p.number_or("beam_width", cutoff * 0.75)?;
            if !(cutoff > 0.0 && cutoff <= 90.0 && beam >= 0.0 && beam <= cutoff) {
                return Err(err(
                    &cloc,
                    format!("emitter \"spot\": expected 0 <= beam_width <= cutoff_angle <= 90, got {beam} and {cutoff}"),
                ));
            }
            node.push(("type", text("spot_light", &loc)));
            node.push(("position", vec3(Vec3::ZERO, &loc)));
            node.push(("direction", vec3(Vec3::Z, &loc)));
            node.push(("intensity", vec3(i / PI, &iloc)));
            node.push(("outer_angle", num(cutoff, &cloc)));
            node.push(("inner_angle", num(beam, &bloc)));
            node.push(("profile", text("angle", &loc)));
            if let Some(texture) = texture {
                // Mitsuba's image runs along its local x and y; lamplight's
                // `right = axis x up` is local x when `up` is local -y.
                node.push(("texture", texture));
                node.push(("up", vec3(-Vec3::Y, &loc)));
            }
        }
        "projector" => {
            if !p.has("irradiance") {
                return Err(err(&loc, "emitter \"projector\": needs irradiance (a texture)"));
            }
            if let Some((_, mloc)) = to_world.as_ref().filter(|(m, _)| mirrors(m)) {
                return Err(err(mloc, "emitter \"projector\": a mirroring to_world is not supported"));
            }
            let texture = textures::colour_or_texture(ctx, &mut p, "irradiance", Rgb::ONE)?;
            let (scale, sloc) = p.number_or("scale", 1.0)?;
            node.push(("type", text("projector", &loc)));
            node.push(("direction", vec3(Vec3::Z, &loc)));
            node.push(("up", vec3(Vec3::Y, &loc)));
            node.push(("texture", texture));
            // Mitsuba lights a facing plane one unit ahead with pi T: lamplight's
            // reading of a delta light's T, so no division by pi here.
            node.push(("strength", num(scale, &sloc)));
            let (fov, axis, floc) = projector_fov(&mut p)?;
            node.push(("fov", num(fov, &floc)));
            node.push(("fov_axis", text(axis, &floc)));
        }
        "directional" => {
            let (e, eloc) = radiant(&mut p, "irradiance", 1.0)?;
            let (d, dloc) = p.vec3("direction")?.unwrap_or((Vec3::Z, loc.clone()));
            node.push(("type", text("directional_light", &loc)));
            node.push(("direction", vec3(d, &dloc)));
            node.push(("radiance", vec3(e / PI, &eloc)));
        }
        "constant" => {
            let (c, cloc) = radiant(&mut p, "radiance", 1.0)?;
            ctx.globals.retain(|e| e.key != "background" && e.key != "environment");
            ctx.globals.push(entry("background", vec3(c, &cloc)));
            ctx.finish(p);
            return Ok(());
        }
        "envmap" => {
            let (f, floc) = p.string("filename")?.ok_or_else(|| err(&loc, "emitter \"envmap\": needs filename"))?;
            let file = ctx.file(&f, &floc)?;
            let (scale, sloc) = p.number_or("scale", 1.0)?;
            let degrees = match &to_world {
                None => 0.0,
                Some((m, mloc)) => y_turn(m).ok_or_else(|| {
                    err(mloc, "emitter \"envmap\": to_world must be a turn about +y (lamplight turns maps about +y only)")
                })?,
            };
            let env = table_of(
                vec![
                    ("file", text(&file, &floc)),
                    ("strength", num(scale, &sloc)),
                    ("rotate", num(degrees + 180.0, &loc)),
                    ("filter", text("bilinear", &loc)),
                ],
                &loc,
            );
            ctx.globals.retain(|e| e.key != "background" && e.key != "environment");
            ctx.globals.push(entry("environment", env));
            ctx.finish(p);
            return Ok(());
        }
        "area" => return Err(err(&loc, "emitter \"area\": must sit inside a <shape>")),
        other => return Err(err(&p.el.require("type")?.loc, format!("emitter \"{other}\": not supported (the scene would lose a light)"))),
    }
    if let Some((m, mloc)) = to_world {
        if m != Mat4::IDENTITY {
            node.push(("matrix", matrix(&m, &mloc)));
        }
    }
    let _ = p.number("sampling_weight")?;
    ctx.finish(p);
    ctx.objects.push(table_of(node, &loc));
    Ok(())
}

/// Whether the linear part of `m` mirrors (a negative determinant).
fn mirrors(m: &Mat4) -> bool {
    m.x_axis.truncate().cross(m.y_axis.truncate()).dot(m.z_axis.truncate()) < 0.0
}

/// A projector's field of view in degrees and its axis (Mitsuba's rule: `fov`
/// along `fov_axis`, default x; else a 35 mm `focal_length`, default 50 mm,
/// across the diagonal), and where it is written.
fn projector_fov(p: &mut Plugin<'_>) -> Result<(f64, &'static str, Loc), ParamError> {
    let (fov, axis, loc) = match p.number("fov")? {
        Some((fov, loc)) => {
            let axis = match p.string("fov_axis")? {
                None => "x",
                Some((a, aloc)) => match a.as_str() {
                    "x" => "x",
                    "y" => "y",
                    "diagonal" => "diagonal",
                    "smaller" => "smaller",
                    "larger" => "larger",
                    _ => return Err(err(&aloc, format!("{}: fov_axis: expected x, y, diagonal, smaller or larger, got \"{a}\"", p.label))),
                },
            };
            (fov, axis, loc)
        }
        None => {
            let (mm, loc) = p.string("focal_length")?.unwrap_or_else(|| ("50mm".to_string(), p.el.loc.clone()));
            (super::sensors::focal_length_fov(&mm, &loc, &p.label)?, "diagonal", loc)
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(err(&loc, format!("{}: fov: must be between 0 and 180 degrees, got {fov}", p.label)));
    }
    Ok((fov, axis, loc))
}

/// The emitted radiance of an `area` emitter nested in a shape.
pub fn area_radiance<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<(Item, Loc), ParamError> {
    let mut p = Plugin::new(el)?;
    if p.kind != "area" {
        return Err(err(&el.loc, format!("{}: inside a shape only \"area\" emitters are supported", p.label)));
    }
    // A texture is the material's textured `emission`: its value at the hit's
    // uv where rays meet the surface, and the area light built from the
    // material evaluates it at each sampled point (lamplight_core's AreaLight),
    // so light sampling and BSDF sampling see the same emitter, as in Mitsuba.
    let radiance = match p.object("radiance") {
        Some(o) => {
            let t = ctx.deref(o)?;
            if t.tag != "texture" {
                return Err(err(&o.loc, format!("{}: radiance: expected a colour or a <texture>, got <{}>", p.label, t.tag)));
            }
            (textures::texture(ctx, t)?, o.loc.clone())
        }
        None => {
            let (c, loc) = radiant(&mut p, "radiance", 1.0)?;
            (vec3(c, &loc), loc)
        }
    };
    let _ = p.number("sampling_weight")?;
    ctx.finish(p);
    Ok(radiance)
}

/// The angle in degrees of `m` when it is a turn about `+y` (and a translation, ignored).
fn y_turn(m: &Mat4) -> Option<f64> {
    let z = m.transform_vector3(Vec3::Z);
    let degrees = z.x.atan2(z.z).to_degrees();
    let turn = Mat4::from_rotation_y(degrees.to_radians());
    let close = (0..3).all(|c| (m.col(c).truncate() - turn.col(c).truncate()).abs().max_element() < 1e-6);
    close.then_some(degrees)
}
