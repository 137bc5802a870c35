//! Which Mitsuba BSDFs are one-sided. Mitsuba's reflecting BSDFs (`diffuse`,
//! `conductor`, `roughconductor`, `plastic`, `roughplastic`) are black where
//! the ray meets the back of the surface (`cos_theta_i <= 0` in the shading
//! frame) and reflect no light arriving from behind; `twosided` makes them
//! reflect on both sides. The transmitting ones (`dielectric`,
//! `roughdielectric`, `thindielectric`) and `null` act on both sides. Their
//! materials get lamplight's `sided = "front"` ([`lamplight_core::materials::sided`]).
//!
//! | Mitsuba | `sided` |
//! |---|---|
//! | `diffuse`, `conductor`, `roughconductor`, `plastic`, `roughplastic` | `"front"` |
//! | `twosided`, `dielectric`, `roughdielectric`, `thindielectric`, `null`, `principled` (lamplight's `principled` tells its two sides apart itself, as Mitsuba's), `principledthin` | both (the default) |
//! | `mask`, `normalmap`, `bumpmap` | as the nested BSDF |
//! | `blendbsdf` | both: each nested BSDF (a `blend` component) is marked itself |

use lamplight_core::params::{Entry, ParamError};

use super::xml::El;
use super::{entry, text, Ctx};

/// Nesting deeper than this is refused (a `<ref>` cycle would never end).
const MAX_NESTING: usize = 64;

/// Whether the `<bsdf>` `el` is one of Mitsuba's one-sided BSDFs (module table).
pub fn one_sided<'a>(ctx: &Ctx<'a>, el: &'a El) -> Result<bool, ParamError> {
    one_sided_at(ctx, el, 0)
}

fn one_sided_at<'a>(ctx: &Ctx<'a>, el: &'a El, depth: usize) -> Result<bool, ParamError> {
    let el = ctx.deref(el)?;
    if depth > MAX_NESTING {
        return Err(ParamError { loc: el.loc.clone(), message: format!("bsdf: nested more than {MAX_NESTING} deep") });
    }
    let nested = || -> Result<Vec<bool>, ParamError> {
        let mut sides = Vec::new();
        for c in &el.children {
            let c = ctx.deref(c)?;
            if c.tag == "bsdf" {
                sides.push(one_sided_at(ctx, c, depth + 1)?);
            }
        }
        Ok(sides)
    };
    Ok(match el.get("type").unwrap_or("") {
        "diffuse" | "conductor" | "roughconductor" | "plastic" | "roughplastic" => true,
        "mask" | "normalmap" | "bumpmap" => nested()?.first().copied().unwrap_or(false),
        _ => false,
    })
}

/// `entries` of the material of `el`, with `sided = "front"` when `el` is one-sided.
pub fn mark<'a>(ctx: &Ctx<'a>, el: &'a El, mut entries: Vec<Entry>) -> Result<Vec<Entry>, ParamError> {
    entries.retain(|e| e.key != "sided");
    if one_sided(ctx, el)? {
        entries.push(entry("sided", text("front", &el.loc)));
    }
    Ok(entries)
}

/// `entries` made to scatter on both sides (a `twosided` around them): no
/// `sided`, in the material and in the components of a blend.
pub fn both_sides(mut entries: Vec<Entry>) -> Vec<Entry> {
    entries.retain(|e| e.key != "sided");
    for e in &mut entries {
        if let (true, lamplight_core::params::Value::Table(t)) = (e.key == "a" || e.key == "b", &mut e.item.value) {
            t.entries = both_sides(std::mem::take(&mut t.entries));
        }
    }
    entries
}
