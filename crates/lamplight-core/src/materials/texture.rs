//! Colour sources evaluated at a shading point: constant, the 3D checker here,
//! and the kinds of their own files (image, UV checker, mix, scale, vertex colour).
//!
//! A texturable parameter takes a colour (a constant) or a texture table
//! `{ type = KIND, ... }` of a registered [`TextureKind`]; [`Textures::read`]
//! tells them apart. Textures that read surface coordinates
//! ([`Texture::needs_coords`]) make the integrators ask the shape for them.

use std::sync::Arc;

use super::image::{ImageLoader, ImageTexture};
use super::uv_transform::UvTransform;
use crate::math::{Rgb, Vec3};
use crate::params::{unknown_kind, Item, Kind, Param, ParamResult, ParamType as T, Params, Value};

/// Builds a texture kind's texture from its parameters; textures nested in its
/// parameters are read through the same [`Textures`].
pub type TextureBuild = fn(&mut Params<'_>, &Textures<'_>) -> ParamResult<Texture>;
/// A texture kind of the scene format.
pub type TextureKind = Kind<TextureBuild>;

/// `checker`: the 3D checker.
pub const CHECKER: TextureKind = Kind {
    name: "checker",
    summary: "a 3D checker of cubes (POV-Ray's `checker`)",
    params: &[
        Param::new("size", T::Number, "", "scene units, > 0", "cube edge length"),
        Param::new("even", T::Color, "", "", "colour of cells whose index sum is even"),
        Param::new("odd", T::Color, "", "", "colour of the other cells"),
        Param::new("offset", T::Vector, "[0, 0, 0]", "scene units", "added to the point before the cells are counted"),
    ],
    build: |p, _| {
        let size = p.required_number("size")?;
        let even = p.color("even")?.ok_or_else(|| p.error("needs `even` (a colour)"))?;
        let odd = p.color("odd")?.ok_or_else(|| p.error("needs `odd` (a colour)"))?;
        let offset = p.vec3("offset")?.unwrap_or(Vec3::ZERO);
        Ok(Texture::Checker { size, even, odd, offset })
    },
};

/// The texture kinds a scene may use, for reading texturable parameters.
#[derive(Clone, Copy)]
pub struct Textures<'a> {
    /// The registered kinds.
    pub kinds: &'a [&'a TextureKind],
    /// Reads image files (`None` where there is no scene file to read them beside).
    pub images: Option<&'a dyn ImageLoader>,
    /// Reads the materials a `blend` mixes (`None` where there are no others to name).
    pub materials: Option<&'a dyn super::blend::Components>,
}

impl std::fmt::Debug for Textures<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Textures")
            .field("kinds", &self.kinds.len())
            .field("images", &self.images.is_some())
            .field("materials", &self.materials.is_some())
            .finish()
    }
}

impl Textures<'_> {
    /// The texture of parameter `key`: a colour is a [`Texture::Constant`], a table
    /// is built by the kind its `type` names.
    pub fn read(&self, p: &mut Params<'_>, key: &str) -> ParamResult<Option<Texture>> {
        match p.item(key) {
            None => Ok(None),
            Some(Item { value: Value::Table(_), .. }) => {
                let mut table = p.table(key)?.expect("the key holds a table");
                let Some(kind_name) = table.string("type")? else {
                    let names: Vec<&str> = self.kinds.iter().map(|k| k.name).collect();
                    return Err(table.error(format!("needs `type` (a texture: {})", names.join(", "))));
                };
                let Some(kind) = Kind::find(self.kinds, kind_name) else {
                    return Err(table.key_error("type", unknown_kind("texture", kind_name, self.kinds)));
                };
                table.read(kind.params, &["type"], |t| (kind.build)(t, self)).map(Some)
            }
            Some(_) => Ok(p.color(key)?.map(Texture::Constant)),
        }
    }

    /// A scalar parameter `key`: a number is a constant (of every channel), a
    /// table a texture whose first channel is read.
    pub fn read_scalar(&self, p: &mut Params<'_>, key: &str) -> ParamResult<Option<Texture>> {
        match p.item(key) {
            Some(Item { value: Value::Table(_), .. }) => self.read(p, key),
            Some(_) => Ok(p.number(key)?.map(|x| Texture::Constant(Rgb::splat(x)))),
            None => Ok(None),
        }
    }
}

/// The cells of [`Texture::UvChecker`].
#[derive(Clone, Debug, PartialEq)]
pub struct UvChecker {
    /// `(u, v)` to cell coordinates.
    pub transform: UvTransform,
    /// Colour of even cells.
    pub even: Rgb,
    /// Colour of odd cells.
    pub odd: Rgb,
}

/// What a texture is evaluated at: the point, and its surface coordinates when
/// a texture reads them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint {
    /// World position.
    pub p: Vec3,
    /// Surface coordinates ([`crate::shapes::SurfaceCoords`]; 0 when not asked).
    pub uv: [f64; 2],
    /// Change of `uv` from one pixel to the next in x (0: no footprint known).
    pub duv_dx: [f64; 2],
    /// Change of `uv` from one pixel to the next in y.
    pub duv_dy: [f64; 2],
    /// A mesh's interpolated vertex colour.
    pub color: Option<Rgb>,
    /// The second texture coordinates (glTF `TEXCOORD_1`) and their changes
    /// from pixel to pixel in x and y, where the shape has them. (An option, so
    /// that a point without them costs one byte to make, not six numbers.)
    pub second: Option<[[f64; 2]; 3]>,
}

impl ShadingPoint {
    /// The point `p` with no surface coordinates.
    #[inline]
    pub fn at(p: Vec3) -> ShadingPoint {
        ShadingPoint { p, uv: [0.0; 2], duv_dx: [0.0; 2], duv_dy: [0.0; 2], color: None, second: None }
    }

    /// The point `p` with the surface coordinates `c` (no footprint).
    #[inline]
    pub fn with_coords(p: Vec3, c: &crate::shapes::SurfaceCoords) -> ShadingPoint {
        let second = c.uv1.map(|s| [s.uv, [0.0; 2], [0.0; 2]]);
        ShadingPoint { uv: c.uv, color: c.color, second, ..ShadingPoint::at(p) }
    }

    /// The same point seen through its second texture coordinates; itself
    /// where it has none.
    #[inline]
    pub fn second_uv(&self) -> ShadingPoint {
        match self.second {
            Some([uv, duv_dx, duv_dy]) => ShadingPoint { uv, duv_dx, duv_dy, ..*self },
            None => *self,
        }
    }
}

/// A colour that may vary over space.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// The same colour everywhere.
    Constant(Rgb),
    /// A 3D checker of cubes of edge `size`: `even` where
    /// `floor((x+o.x)/size) + floor((y+o.y)/size) + floor((z+o.z)/size)` is even,
    /// `odd` elsewhere (POV-Ray's `checker`). A point within rounding error of a
    /// cell boundary counts as on it ([`cell_parity`]), so a floor at `y = 0`
    /// shows clean squares without an offset; `o` shifts the pattern.
    Checker {
        /// Cube edge length.
        size: f64,
        /// Colour of even cells.
        even: Rgb,
        /// Colour of odd cells.
        odd: Rgb,
        /// Added to the point before the cells are counted.
        offset: Vec3,
    },
    /// A checker in texture space: `even` where `floor(s) + floor(t)` is even
    /// for `(s, t) = T(u, v)` ([`super::uv_checker`]).
    /// (Shared, so that the enum stays the size it had with the 3D checker.)
    UvChecker(Arc<UvChecker>),
    /// An image ([`super::image`]).
    Image(Arc<ImageTexture>),
    /// The product of two textures, channel by channel ([`super::combine`]).
    Scale(Arc<[Texture; 2]>),
    /// `(1 - t) a + t b` of textures `[a, b, t]` ([`super::combine`]).
    Mix(Arc<[Texture; 3]>),
    /// A mesh's vertex colour, 1 where the shape has none ([`super::combine`]).
    VertexColor,
    /// A texture read at the second texture coordinates ([`super::uv_set`]).
    SecondUv(Arc<Texture>),
}

impl Texture {
    /// The colour at the point `p` where the texture is a constant or the 3D
    /// checker, `None` for the others: [`Texture::evaluate`]'s first two cases,
    /// small enough to compile into a render loop (the Whitted tracer's floor;
    /// `evaluate`, recursive, stays a call).
    #[inline(always)]
    pub fn of_point(&self, p: Vec3) -> Option<Rgb> {
        match self {
            Texture::Constant(c) => Some(*c),
            Texture::Checker { size, even, odd, offset } => Some(checker(p, *size, *even, *odd, *offset)),
            _ => None,
        }
    }

    /// The colour at the shading point.
    #[inline]
    pub fn evaluate(&self, at: &ShadingPoint) -> Rgb {
        match self {
            Texture::Constant(c) => *c,
            Texture::Checker { size, even, odd, offset } => checker(at.p, *size, *even, *odd, *offset),
            Texture::UvChecker(c) => {
                let [s, t] = c.transform.apply(at.uv);
                if (s.floor() + t.floor()).rem_euclid(2.0) == 0.0 {
                    c.even
                } else {
                    c.odd
                }
            }
            Texture::Image(image) => image.evaluate(at),
            Texture::Scale(f) => f[0].evaluate(at) * f[1].evaluate(at),
            Texture::Mix(f) => {
                let t = f[2].evaluate(at);
                f[0].evaluate(at) * (Rgb::ONE - t) + f[1].evaluate(at) * t
            }
            Texture::VertexColor => at.color.unwrap_or(Rgb::ONE),
            Texture::SecondUv(t) => t.evaluate(&at.second_uv()),
        }
    }

    /// Whether the texture reads surface coordinates or vertex data (everything
    /// but constants and the 3D checker).
    pub fn needs_coords(&self) -> bool {
        match self {
            Texture::Constant(_) | Texture::Checker { .. } => false,
            Texture::Scale(f) => f.iter().any(Texture::needs_coords),
            Texture::Mix(f) => f.iter().any(Texture::needs_coords),
            _ => true,
        }
    }

    /// Whether a lookup reads the footprint (a trilinear image somewhere inside).
    pub fn uses_footprint(&self) -> bool {
        match self {
            Texture::Image(i) => i.filter == super::image::Filter::Trilinear,
            Texture::Scale(f) => f.iter().any(Texture::uses_footprint),
            Texture::Mix(f) => f.iter().any(Texture::uses_footprint),
            Texture::SecondUv(t) => t.uses_footprint(),
            _ => false,
        }
    }

    /// The constant colour, if the texture is one.
    pub fn constant(&self) -> Option<Rgb> {
        match self {
            Texture::Constant(c) => Some(*c),
            _ => None,
        }
    }
}

/// Distance in cells below a cell boundary within which a point counts as on
/// it, plus [`CELL_SNAP_RELATIVE`] of the coordinate: far above the rounding of
/// a hit point (about 1e-16 of its distance from the origin and from the ray's
/// origin, so up to 10^7 cells away), far below anything a pixel resolves.
pub const CELL_SNAP: f64 = 1e-9;

/// The part of the snap distance that grows with the cell coordinate `|v|`.
pub const CELL_SNAP_RELATIVE: f64 = 1e-12;

/// The 3D checker's colour at `p`: `even` where the cell `floor((p + offset) / size)`
/// has an even coordinate sum ([`cell_parity`]), else `odd`.
#[inline(always)]
fn checker(p: Vec3, size: f64, even: Rgb, odd: Rgb, offset: Vec3) -> Rgb {
    // Selected lane by lane: picking one of the two by a branch copied it
    // through memory in pieces that the Whitted tracer's next wide load of
    // the colour spanned, a store-forwarding stall on every floor hit of
    // `luxo` (issue 24).
    Rgb::select(glam::BVec3::splat(cell_parity((p + offset) / size) == 0), even, odd)
}

/// `(floor(x) + floor(y) + floor(z)) mod 2` for the checker's cell coordinates,
/// where a coordinate within `CELL_SNAP + CELL_SNAP_RELATIVE |v|` below an integer
/// counts as that integer. A surface lying in a cell boundary (a floor at
/// `y = 0`) is hit at `y = +-1e-17` as rounding falls; without this its pixels
/// would take either cell's colour at random (POV-Ray adds a small tolerance to
/// its `checker` for the same reason).
///
/// In integers where they fit (the usual case): `floor` and `rem_euclid` are libm
/// calls on baseline x86-64 and cost more than the rest of the lookup. Beyond
/// 2^50 every `f64` is an integer and the float formula is exact.
#[inline]
pub fn cell_parity(cell: Vec3) -> u8 {
    const FITS: f64 = (1u64 << 50) as f64;
    if cell.x.abs() < FITS && cell.y.abs() < FITS && cell.z.abs() < FITS {
        // Truncation, minus one for negative non-integers, is floor; a value just
        // below the next integer is taken as that integer.
        let floor = |v: f64| {
            let t = v as i64;
            let below = t - ((t as f64) > v) as i64;
            let next = below + 1;
            if next as f64 - v <= CELL_SNAP + CELL_SNAP_RELATIVE * v.abs() {
                next
            } else {
                below
            }
        };
        ((floor(cell.x) + floor(cell.y) + floor(cell.z)) & 1) as u8
    } else {
        let c = cell.floor();
        (c.x + c.y + c.z).rem_euclid(2.0) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `of_point` answers for a constant and the 3D checker exactly as
    /// `evaluate` does, and leaves every other texture to it.
    #[test]
    fn of_point_is_evaluate_for_the_colours_of_a_point() {
        let checker =
            Texture::Checker { size: 0.7, even: Rgb::splat(0.75), odd: Rgb::new(0.1, 0.2, 0.3), offset: Vec3::new(0.0, 0.5, 0.25) };
        let constant = Texture::Constant(Rgb::new(0.4, 0.5, 0.6));
        let mut rng = crate::sampling::Rng::for_sample(21, 0, 0);
        let (mut even, mut odd) = (0, 0);
        for _ in 0..2000 {
            let p = Vec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5) * 20.0;
            for t in [&checker, &constant] {
                assert_eq!(t.of_point(p), Some(t.evaluate(&ShadingPoint::at(p))), "{t:?} at {p}");
            }
            match checker.of_point(p) {
                Some(c) if c == Rgb::splat(0.75) => even += 1,
                _ => odd += 1,
            }
        }
        assert!(even > 800 && odd > 800, "{even} even and {odd} odd cells");
        assert_eq!(Texture::VertexColor.of_point(Vec3::ZERO), None);
    }

    #[test]
    fn cell_parity_equals_the_float_formula_away_from_boundaries() {
        let float = |c: Vec3| {
            let f = c.floor();
            (f.x + f.y + f.z).rem_euclid(2.0) as u8
        };
        let values = [-3.5, -2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.999, 7.0, 1e9 + 0.5, -1e9 - 0.5, 3e15, -3e15, 1e300];
        for &x in &values {
            for &y in &values {
                for &z in &[-0.25, 0.0, 2.5] {
                    let c = Vec3::new(x, y, z);
                    assert_eq!(cell_parity(c), float(c), "{c}");
                }
            }
        }
    }

    #[test]
    fn checker_alternates_across_cells() {
        let t = Texture::Checker { size: 0.5, even: Rgb::ONE, odd: Rgb::ZERO, offset: Vec3::new(0.0, 0.25, 0.0) };
        assert_eq!(t.evaluate(&ShadingPoint::at(Vec3::new(0.1, 0.0, 0.1))), Rgb::ONE);
        assert_eq!(t.evaluate(&ShadingPoint::at(Vec3::new(0.6, 0.0, 0.1))), Rgb::ZERO);
        assert_eq!(t.evaluate(&ShadingPoint::at(Vec3::new(-0.1, 0.0, 0.1))), Rgb::ZERO);
        assert_eq!(t.evaluate(&ShadingPoint::at(Vec3::new(-0.1, -1e-17, -0.1))), Rgb::ONE, "rounding below the plane must not flip it");
    }

    #[test]
    fn a_floor_in_a_cell_boundary_shows_one_colour_per_square() {
        // No offset: the floor y = 0 is a boundary; its hits land a rounding
        // error above or below it, and both sides must give the same square.
        let t = Texture::Checker { size: 1.0, even: Rgb::ONE, odd: Rgb::ZERO, offset: Vec3::ZERO };
        for (x, z) in [(0.5, 0.5), (1.5, 0.5), (-0.5, 0.5), (-0.5, -0.5), (1e5 + 0.5, -3e5 + 0.5)] {
            let colours: Vec<Rgb> =
                [-1e-17, -1e-12, -1e-10, 0.0, 1e-17, 1e-12].iter().map(|&y| t.evaluate(&ShadingPoint::at(Vec3::new(x, y, z)))).collect();
            assert!(colours.iter().all(|c| *c == colours[0]), "({x}, {z}): {colours:?}");
        }
        // Cells still alternate, and a point a visible distance below the floor is in the cell below.
        assert_ne!(t.evaluate(&ShadingPoint::at(Vec3::new(0.5, 0.0, 0.5))), t.evaluate(&ShadingPoint::at(Vec3::new(1.5, 0.0, 0.5))));
        assert_ne!(t.evaluate(&ShadingPoint::at(Vec3::new(0.5, 0.0, 0.5))), t.evaluate(&ShadingPoint::at(Vec3::new(0.5, -1e-6, 0.5))));
        // Far from the origin the tolerance scales with the coordinate.
        let far = 1e6;
        assert_eq!(cell_parity(Vec3::new(far - 1e-7, 0.5, 0.5)), cell_parity(Vec3::new(far + 1e-7, 0.5, 0.5)));
        assert_ne!(cell_parity(Vec3::new(far - 1e-4, 0.5, 0.5)), cell_parity(Vec3::new(far + 1e-4, 0.5, 0.5)));
    }
}
