//! Node transforms: `translate`, `rotate`, `scale`, `matrix` to one matrix.
//!
//! A node's own matrix is `T R S X` (`X` the `matrix` key): a point is first
//! mapped by `matrix`, then scaled, rotated and translated; a child's world
//! matrix is its parent's times its own. Rotations about a coordinate axis use
//! glam's `from_rotation_{x,y,z}` so that `rotate = { y = 25 }` gives exactly the
//! matrix the built-in scenes compute.

use lamplight_core::math::{Mat4, Vec3};

use crate::description::{Node, Rotate};

/// The node's own transform, or a message naming the bad key.
pub fn local(node: &Node) -> Result<Mat4, String> {
    let mut m = Mat4::IDENTITY;
    if let Some(t) = node.translate {
        finite("translate", &t)?;
        m = Mat4::from_translation(Vec3::from_array(t));
    }
    if let Some(r) = &node.rotate {
        m *= rotation(r)?;
    }
    if let Some(s) = node.scale {
        finite("scale", &s.0)?;
        if s.0.contains(&0.0) {
            return Err("scale must not be 0 (it would flatten the geometry)".into());
        }
        m *= Mat4::from_scale(Vec3::from_array(s.0));
    }
    if let Some(rows) = node.matrix {
        for row in &rows {
            finite("matrix", row)?;
        }
        if rows[3] != [0.0, 0.0, 0.0, 1.0] {
            return Err("matrix must be affine: its last row must be [0, 0, 0, 1]".into());
        }
        let x = Mat4::from_cols_array_2d(&rows).transpose();
        if x.determinant() == 0.0 {
            return Err("matrix is singular".into());
        }
        m *= x;
    }
    Ok(m)
}

fn rotation(r: &Rotate) -> Result<Mat4, String> {
    match (r.axis, r.degrees) {
        (Some(axis), Some(deg)) => {
            if r.x.is_some() || r.y.is_some() || r.z.is_some() {
                return Err("rotate takes either axis and degrees or x, y, z, not both".into());
            }
            finite("rotate axis", &axis)?;
            finite("rotate degrees", &[deg])?;
            let axis = Vec3::from_array(axis).try_normalize().ok_or("rotate axis must not be zero")?;
            let rad = deg.to_radians();
            Ok(if axis == Vec3::X {
                Mat4::from_rotation_x(rad)
            } else if axis == Vec3::Y {
                Mat4::from_rotation_y(rad)
            } else if axis == Vec3::Z {
                Mat4::from_rotation_z(rad)
            } else {
                Mat4::from_axis_angle(axis, rad)
            })
        }
        (None, None) => {
            let (x, y, z) = (r.x.unwrap_or(0.0), r.y.unwrap_or(0.0), r.z.unwrap_or(0.0));
            finite("rotate", &[x, y, z])?;
            let mut m = Mat4::IDENTITY;
            // x first: the matrix applied first stands rightmost.
            for (deg, make) in [(z, Mat4::from_rotation_z as fn(f64) -> Mat4), (y, Mat4::from_rotation_y), (x, Mat4::from_rotation_x)] {
                if deg != 0.0 {
                    m *= make(deg.to_radians());
                }
            }
            Ok(m)
        }
        _ => Err("rotate needs both axis and degrees".into()),
    }
}

/// Fails with "KEY must be finite" when a number is NaN or infinite.
pub fn finite(key: &str, values: &[f64]) -> Result<(), String> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(format!("{key} must be finite numbers, got {values:?}"))
    }
}

/// The uniform scale of `m`'s linear part when it is a similarity (rotation times
/// one scale factor), else `None`.
pub fn similarity_scale(m: &Mat4) -> Option<f64> {
    let cols = [m.x_axis.truncate(), m.y_axis.truncate(), m.z_axis.truncate()];
    let s = cols[0].length();
    let tol = 1e-12 * s;
    let same_length = cols.iter().all(|c| (c.length() - s).abs() <= tol);
    let orthogonal =
        cols[0].dot(cols[1]).abs() <= tol * s && cols[1].dot(cols[2]).abs() <= tol * s && cols[0].dot(cols[2]).abs() <= tol * s;
    (same_length && orthogonal && s > 0.0).then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::Triple;

    #[test]
    fn order_is_translate_rotate_scale_matrix() {
        let node = Node {
            translate: Some([1.0, 0.0, 0.0]),
            rotate: Some(Rotate { z: Some(90.0), ..Rotate::default() }),
            scale: Some(Triple([2.0, 2.0, 2.0])),
            ..Node::default()
        };
        let m = local(&node).unwrap();
        // (1,0,0) -> scaled (2,0,0) -> rotated (0,2,0) -> translated (1,2,0).
        assert!((m.transform_point3(Vec3::X) - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-15);
        assert_eq!(similarity_scale(&m), Some(2.0));
        let y25 =
            Node { rotate: Some(Rotate { axis: Some([0.0, 1.0, 0.0]), degrees: Some(25.0), ..Rotate::default() }), ..Node::default() };
        assert_eq!(local(&y25).unwrap(), Mat4::from_rotation_y(25f64.to_radians()));
        let squash = Node { scale: Some(Triple([1.0, 2.0, 1.0])), ..Node::default() };
        assert_eq!(similarity_scale(&local(&squash).unwrap()), None);
    }

    #[test]
    fn bad_transforms_are_messages() {
        let nan = Node { translate: Some([f64::NAN, 0.0, 0.0]), ..Node::default() };
        assert!(local(&nan).unwrap_err().starts_with("translate must be finite"));
        let zero = Node { scale: Some(Triple([0.0; 3])), ..Node::default() };
        assert!(local(&zero).is_err());
        let half = Node { rotate: Some(Rotate { degrees: Some(3.0), ..Rotate::default() }), ..Node::default() };
        assert_eq!(local(&half).unwrap_err(), "rotate needs both axis and degrees");
    }
}
