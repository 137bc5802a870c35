//! The microfacet roughness of Mitsuba's rough BSDFs (`roughconductor`,
//! `roughdielectric`, `roughplastic`): `alpha`, or `alpha_u` and `alpha_v`,
//! and `distribution`, as lamplight's `roughness` (or `roughness_u`,
//! `roughness_v`) and `distribution`.
//!
//! | Mitsuba | lamplight |
//! |---|---|
//! | `alpha` (0.1): a number or a texture | `roughness` (a texture is a scalar texture slot, evaluated at each hit as Mitsuba's `eval_1`; its values are clamped to 0 to 1) |
//! | `alpha_u`, `alpha_v` (both, never with `alpha`) | `roughness_u` along the shading frame's `dp/du`, `roughness_v` across; equal numbers are `roughness` |
//! | `distribution` (`beckmann`, `ggx`) | `distribution` |
//! | `sample_visible` | read; only the noise depends on it |
//!
//! `roughplastic` takes a number only (lamplight tabulates its coating for one
//! `alpha`): a texture there is an error.

use lamplight_core::params::{Entry, Item, Loc, ParamError, Value};

use super::properties::Plugin;
use super::textures::{number, number_or_texture};
use super::{entry, num, text, Ctx};

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// The `roughness` (or `roughness_u`, `roughness_v`) and `distribution` entries
/// of a rough BSDF: `alpha`, or with `anisotropic` (`roughconductor`,
/// `roughdielectric`) the pair `alpha_u`, `alpha_v`, and
/// `distribution` (Mitsuba's default `beckmann`). `textured` (the same two)
/// lets each be a texture, read per hit as Mitsuba's `eval_1` reads it.
pub fn rough<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, anisotropic: bool, textured: bool) -> Result<Vec<Entry>, ParamError> {
    let (name, dloc) = p.string("distribution")?.unwrap_or(("beckmann".into(), p.el.loc.clone()));
    if name != "ggx" && name != "beckmann" {
        return Err(err(&dloc, format!("{}: distribution: expected beckmann or ggx, got \"{name}\"", p.label)));
    }
    let mut e = alpha(ctx, p, anisotropic, textured)?;
    e.push(entry("distribution", text(&name, &dloc)));
    Ok(e)
}

/// The roughness of a rough BSDF as Mitsuba's `MicrofacetDistribution` reads
/// it: `alpha` (0.1), or `alpha_u` and `alpha_v` together and never with
/// `alpha` (Mitsuba's rule). An isotropic pair is lamplight's `roughness`, an
/// anisotropic one `roughness_u` (along `dp/du`) and `roughness_v`. Where
/// `textured`, each may be a texture (lamplight's scalar texture slot, evaluated
/// at each hit; Mitsuba's `eval_1`, [`super::textures::scalar_texture`]); elsewhere a texture is
/// an error (Mitsuba's `roughplastic` tabulates its coating for one `alpha`).
fn alpha<'a>(ctx: &mut Ctx<'a>, p: &mut Plugin<'a>, anisotropic: bool, textured: bool) -> Result<Vec<Entry>, ParamError> {
    // Only the sampling changes with it, not the image.
    let _ = p.boolean("sample_visible")?;
    let mut read = |p: &mut Plugin<'a>, key: &str| -> Result<Item, ParamError> {
        if textured && p.object(key).is_some() {
            if let Some(item) = number_or_texture(ctx, p, key)? {
                return Ok(item);
            }
        }
        let (a, loc) = number(p, key, 0.1)?;
        if (0.0..=1.0).contains(&a) {
            Ok(num(a, &loc))
        } else {
            Err(err(&loc, format!("{}: {key}: must be between 0 and 1, got {a}", p.label)))
        }
    };
    if anisotropic && (p.has("alpha_u") || p.has("alpha_v")) {
        if p.has("alpha") {
            return Err(err(&p.el.loc, format!("{}: give either alpha or alpha_u and alpha_v, not both (as Mitsuba)", p.label)));
        }
        if !(p.has("alpha_u") && p.has("alpha_v")) {
            return Err(err(&p.el.loc, format!("{}: give both alpha_u and alpha_v (as Mitsuba)", p.label)));
        }
        let u = read(p, "alpha_u")?;
        let v = read(p, "alpha_v")?;
        if let (Value::Number(a), Value::Number(b)) = (&u.value, &v.value) {
            if a == b {
                return Ok(vec![entry("roughness", u)]);
            }
        }
        return Ok(vec![entry("roughness_u", u), entry("roughness_v", v)]);
    }
    Ok(vec![entry("roughness", read(p, "alpha")?)])
}
