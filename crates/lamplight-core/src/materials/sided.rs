//! One-sided surfaces: a material that scatters light only on the front side
//! of its surface (where the shape's outward normal faces the ray), as every
//! Mitsuba BSDF except `twosided`, the dielectrics and `null` does. Seen from
//! the back such a surface is black (its emission, which has its own
//! `two_sided`, aside), and light arriving at the back is not reflected.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `sided` | string | `"both"` | `"both"`: the surface scatters on both sides; `"front"`: only on the front side, black from the back |
//!
//! The front side is the one the shape's normal points to (a sphere's outside,
//! a rectangle's or disk's `+normal` side, a mesh's counter-clockwise side or
//! its vertex normals' side; `flip_normals` turns it).

use crate::params::{Param, ParamResult, ParamType as T, Params};

/// The `sided` key the material kinds share.
pub const SIDED_PARAM: Param = Param::new(
    "sided",
    T::String,
    "\"both\"",
    "\"both\", \"front\"",
    "`front`: the surface scatters light only on its front (outward) side and is black from the back (Mitsuba's one-sided BSDFs)",
);

/// Reads [`SIDED_PARAM`]: whether the material is one-sided.
pub fn read(p: &mut Params<'_>) -> ParamResult<bool> {
    Ok(p.choice("sided", &["both", "front"])? == "front")
}
