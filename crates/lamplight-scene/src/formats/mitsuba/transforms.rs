//! `<transform>`: `translate`, `rotate`, `scale`, `matrix` and `lookat`
//! composed in Mitsuba's order: each operation applies after the ones above it,
//! `M = op_n ... op_2 op_1` (points are column vectors).
//!
//! - `translate`: `x`, `y`, `z` (0 when absent) or `value="x, y, z"`.
//! - `rotate`: an axis (`x`, `y`, `z` or `value`) and `angle` in degrees, counter-clockwise about the axis.
//! - `scale`: `value` (one number or three) or `x`, `y`, `z` (1 when absent).
//! - `matrix`: `value` of 16 numbers (rows of the 4x4) or 9 (a 3x3).
//! - `lookat`: `origin`, `target`, `up` ("x, y, z"); the matrix whose columns are
//!   `left = normalize(up x dir)`, `dir x left`, `dir = normalize(target - origin)` and `origin`.

use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::params::{Loc, ParamError};

use super::properties::{numbers, parse_float, vec3};
use super::xml::El;

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// The matrix of a `<transform>` element.
pub fn transform(el: &El) -> Result<Mat4, ParamError> {
    let mut m = Mat4::IDENTITY;
    for op in &el.children {
        m = operation(op)? * m;
    }
    if !m.is_finite() || m.determinant() == 0.0 {
        return Err(err(&el.loc, "transform: the matrix is singular, expected an invertible transform"));
    }
    Ok(m)
}

fn operation(op: &El) -> Result<Mat4, ParamError> {
    let value_loc = op.attr("value").map_or(op.loc.clone(), |a| a.loc.clone());
    let axis_or = |default: f64| -> Result<Vec3, ParamError> {
        if op.get("value").is_some() {
            return vec3(op, &value_loc);
        }
        let mut p = [default; 3];
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            if let Some(a) = op.attr(axis) {
                p[i] = parse_float(&a.value, &a.loc)?;
            }
        }
        Ok(Vec3::from_array(p))
    };
    match op.tag.as_str() {
        "translate" => Ok(Mat4::from_translation(axis_or(0.0)?)),
        "scale" => {
            let s = axis_or(1.0)?;
            if s.to_array().contains(&0.0) {
                return Err(err(&op.loc, "scale: must not be 0 (it would flatten the geometry)"));
            }
            Ok(Mat4::from_scale(s))
        }
        "rotate" => {
            let axis = axis_or(0.0)?;
            let angle = op.require("angle")?;
            let rad = parse_float(&angle.value, &angle.loc)?.to_radians();
            let unit = axis.try_normalize().ok_or_else(|| err(&op.loc, "rotate: the axis must not be zero"))?;
            Ok(crate::instantiate::transform::axis_rotation(unit, rad))
        }
        "matrix" => {
            let v = op.require("value")?;
            let n = numbers(&v.value, &v.loc)?;
            let rows: [[f64; 4]; 4] = match n.len() {
                16 => [[n[0], n[1], n[2], n[3]], [n[4], n[5], n[6], n[7]], [n[8], n[9], n[10], n[11]], [n[12], n[13], n[14], n[15]]],
                9 => [[n[0], n[1], n[2], 0.0], [n[3], n[4], n[5], 0.0], [n[6], n[7], n[8], 0.0], [0.0, 0.0, 0.0, 1.0]],
                k => return Err(err(&v.loc, format!("matrix: expected 16 or 9 numbers, got {k}"))),
            };
            if rows[3] != [0.0, 0.0, 0.0, 1.0] {
                return Err(err(&v.loc, "matrix: must be affine: its last row must be 0 0 0 1 (projective transforms are not supported)"));
            }
            Ok(Mat4::from_cols_array_2d(&rows).transpose())
        }
        "lookat" => {
            let point = |name: &str| -> Result<Vec3, ParamError> {
                let a = op.require(name)?;
                let n = numbers(&a.value, &a.loc)?;
                match n.as_slice() {
                    [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
                    _ => Err(err(&a.loc, format!("lookat: {name}: expected three numbers \"x, y, z\", got \"{}\"", a.value))),
                }
            };
            let origin = point("origin")?;
            let target = point("target")?;
            let up = if op.get("up").is_some() { point("up")? } else { Vec3::Y };
            look_at(origin, target, up).ok_or_else(|| err(&op.loc, "lookat: target equals origin, or up is parallel to the view direction"))
        }
        other => Err(err(
            &op.loc,
            lamplight_core::params::unknown("transform operation", other, &["translate", "rotate", "scale", "matrix", "lookat"]),
        )),
    }
}

/// Mitsuba's `look_at`: the camera-to-world matrix of a camera at `origin`
/// looking at `target`, its local `+z` forward, `+y` up and `+x` to the left.
pub fn look_at(origin: Vec3, target: Vec3, up: Vec3) -> Option<Mat4> {
    let dir = (target - origin).try_normalize()?;
    let left = up.cross(dir).try_normalize()?;
    let new_up = dir.cross(left);
    Some(Mat4::from_cols(left.extend(0.0), new_up.extend(0.0), dir.extend(0.0), origin.extend(1.0)))
}
