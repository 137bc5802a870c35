//! The scene file's `environment`: light from every direction, infinitely far,
//! as Mitsuba's `constant` and `envmap` emitters and pbrt's `infinite` light.
//!
//! ```toml
//! environment = { file = "sky.hdr", strength = 2, rotate = 90 }
//! # looked up bilinearly, as Mitsuba's envmap: filter = "bilinear"
//! # or: environment = { color = [0.4, 0.5, 0.7] }
//! # or the studio a bare model is lit by: environment = { preset = "studio", rotate = 35 }
//! ```
//!
//! Under path tracing it lights every surface and is seen by every ray that
//! leaves the scene, in place of `background`; under Whitted, rays that leave
//! the scene see it. `--environment FILE` (Python `environment=`) replaces it,
//! looked up bilinearly (`crate::env_map::load_bilinear_map`).

use std::path::Path;
use std::sync::Arc;

use lamplight_core::lights::Environment;
use lamplight_core::math::Rgb;
use lamplight_core::params::{Param, ParamResult, ParamType as T, Params};

/// The `environment` table's keys.
pub const ENVIRONMENT_PARAMS: &[Param] = &[
    Param::new("color", T::Color, "none", "radiance", "a uniform sky of this radiance (one of `color`, `file`, `preset`)"),
    Param::new(
        "file",
        T::String,
        "none",
        "",
        "an equirectangular `.exr` or `.hdr` map: an absolute path, or one relative to the scene file's folder",
    ),
    Param::new(
        "preset",
        T::String,
        "none",
        "\"studio\"",
        "a sky made in code: `studio`, the neutral studio a bare model is lit by (a grey floor, a brighter sky, a soft box overhead and strip lights at the sides of a camera on `+z`; `docs/examples.md`)",
    ),
    Param::new("strength", T::Number, "1", ">= 0", "multiplies the radiance"),
    Param::new("rotate", T::Number, "0", "degrees", "turns the map about +y, counter-clockwise seen from above"),
    Param::new(
        "filter",
        T::String,
        "\"nearest\"",
        "\"nearest\", \"bilinear\"",
        "how the map is looked up: the nearest pixel, or bilinearly between pixels as Mitsuba's `envmap` (first row at the zenith, last at the nadir); a map given by `--environment` (Python `environment=`) is always looked up bilinearly",
    ),
];

/// Reads the `environment` table `p` into the scene's environment; a map file
/// is found relative to `dir`.
pub fn read(mut p: Params<'_>, dir: &Path) -> ParamResult<Arc<Environment>> {
    p.check_keys(ENVIRONMENT_PARAMS, &[])?;
    let strength = p.number_or("strength", 1.0)?;
    if !(strength.is_finite() && strength >= 0.0) {
        return Err(p.key_error("strength", format!("must be a non-negative number, got {strength}")));
    }
    let rotate = p.number_or("rotate", 0.0)?;
    let bilinear = p.choice("filter", &["nearest", "bilinear"])? == "bilinear";
    let preset = p.string("preset")?;
    if let Some(name) = preset {
        if p.color("color")?.is_some() || p.string("file")?.is_some() {
            return Err(p.error("takes one of `color`, `file` and `preset`"));
        }
        if name != "studio" {
            return Err(p.key_error("preset", format!("must be \"studio\", got {name:?}")));
        }
        let map = super::studio::map(rotate).map_err(|e| p.key_error("preset", e))?;
        let map = if strength == 1.0 { map } else { map.scaled(Rgb::splat(strength)).map_err(|e| p.key_error("strength", e))? };
        p.finish()?;
        return Ok(Arc::new(Environment::Map(map)));
    }
    let environment = match (p.color("color")?, p.string("file")?) {
        (Some(color), None) => {
            if color.min_element() < 0.0 {
                return Err(p.key_error("color", format!("must be non-negative, got {color}")));
            }
            Environment::Constant(color * strength)
        }
        (None, Some(file)) => {
            if file.is_empty() {
                return Err(p.key_error("file", "the path is empty, expected an .exr or .hdr file"));
            }
            let map = crate::env_map::load_map(&dir.join(file)).map_err(|m| p.key_error("file", m))?;
            let map = if strength == 1.0 { map } else { map.scaled(Rgb::splat(strength)).map_err(|e| p.key_error("strength", e))? };
            let map = if bilinear { map.bilinear().map_err(|e| p.key_error("filter", e))? } else { map };
            Environment::Map(map.with_rotation(rotate))
        }
        _ => return Err(p.error("takes either `color` or `file`")),
    };
    p.finish()?;
    Ok(Arc::new(environment))
}
