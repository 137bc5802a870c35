//! Colour sources evaluated at a hit point: constant or procedural checker.

use crate::math::{Rgb, Vec3};

/// A colour that may vary over space.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// The same colour everywhere.
    Constant(Rgb),
    /// A 3D checker of cubes of edge `size`: `even` where
    /// `floor((x+o.x)/size) + floor((y+o.y)/size) + floor((z+o.z)/size)` is even,
    /// `odd` elsewhere (POV-Ray's `checker`). The offset `o` keeps a planar floor
    /// away from a cube boundary, where rounding would make the pattern flicker.
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
}

impl Texture {
    /// The colour at world point `p`.
    #[inline]
    pub fn evaluate(&self, p: Vec3) -> Rgb {
        match self {
            Texture::Constant(c) => *c,
            Texture::Checker { size, even, odd, offset } => {
                let cell = ((p + *offset) / *size).floor();
                let parity = (cell.x + cell.y + cell.z).rem_euclid(2.0);
                if parity < 0.5 {
                    *even
                } else {
                    *odd
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_across_cells() {
        let t = Texture::Checker { size: 0.5, even: Rgb::ONE, odd: Rgb::ZERO, offset: Vec3::new(0.0, 0.25, 0.0) };
        assert_eq!(t.evaluate(Vec3::new(0.1, 0.0, 0.1)), Rgb::ONE);
        assert_eq!(t.evaluate(Vec3::new(0.6, 0.0, 0.1)), Rgb::ZERO);
        assert_eq!(t.evaluate(Vec3::new(-0.1, 0.0, 0.1)), Rgb::ZERO);
        assert_eq!(t.evaluate(Vec3::new(-0.1, -1e-17, -0.1)), Rgb::ONE, "rounding below the plane must not flip it");
    }
}
