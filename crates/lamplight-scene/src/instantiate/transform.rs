//! Node transforms: `translate`, `rotate`, `scale`, `matrix` to one matrix.
//!
//! A node's own matrix is `T R S X` (`X` the `matrix` key): a point is first
//! mapped by `matrix`, then scaled, rotated and translated; a child's world
//! matrix is its parent's times its own. Rotations about a coordinate axis use
//! glam's `from_rotation_{x,y,z}` so that `rotate = { y = 25 }` gives exactly the
//! matrix the built-in scenes compute.

use lamplight_core::math::Mat4;
use lamplight_core::params::{ParamResult, Params, Table};

/// The node's own transform from its transform keys (read for `label`).
pub fn local(label: &str, table: &Table) -> ParamResult<Mat4> {
    let mut p = Params::new(label, table);
    let mut m = Mat4::IDENTITY;
    if let Some(t) = p.vec3("translate")? {
        m = Mat4::from_translation(t);
    }
    if p.has("rotate") {
        m *= rotation(&mut p)?;
    }
    if let Some(s) = p.color("scale")? {
        if s.to_array().contains(&0.0) {
            return Err(p.key_error("scale", "must not be 0 (it would flatten the geometry)"));
        }
        m *= Mat4::from_scale(s);
    }
    if let Some(x) = p.matrix("matrix")? {
        if x.row(3) != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) {
            return Err(p.key_error("matrix", "must be affine: its last row must be [0, 0, 0, 1]"));
        }
        if x.determinant() == 0.0 {
            return Err(p.key_error("matrix", "is singular"));
        }
        m *= x;
    }
    p.finish()?;
    Ok(m)
}

fn rotation(p: &mut Params<'_>) -> ParamResult<Mat4> {
    crate::description::rotation::read(p, "rotate").map(|r| r.matrix())
}

pub(crate) use crate::description::rotation::axis_rotation;

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_core::math::Vec3;
    use lamplight_core::params::{Entry, Item, Loc, Value};

    fn table(entries: Vec<(&str, Value)>) -> Table {
        Table {
            entries: entries
                .into_iter()
                .map(|(k, v)| Entry { key: k.into(), key_loc: Loc::Unknown, item: Item { value: v, loc: Loc::Unknown } })
                .collect(),
            loc: Loc::Unknown,
        }
    }

    fn nums(v: &[f64]) -> Value {
        Value::Array(v.iter().map(|x| Item { value: Value::Number(*x), loc: Loc::Unknown }).collect())
    }

    #[test]
    fn order_is_translate_rotate_scale_matrix() {
        let t = table(vec![
            ("translate", nums(&[1.0, 0.0, 0.0])),
            ("rotate", Value::Table(table(vec![("z", Value::Number(90.0))]))),
            ("scale", Value::Number(2.0)),
        ]);
        let m = local("group", &t).unwrap();
        // (1,0,0) -> scaled (2,0,0) -> rotated (0,2,0) -> translated (1,2,0).
        assert!((m.transform_point3(Vec3::X) - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-15);
        let y25 = table(vec![("rotate", Value::Table(table(vec![("axis", nums(&[0.0, 1.0, 0.0])), ("degrees", Value::Number(25.0))])))]);
        assert_eq!(local("group", &y25).unwrap(), Mat4::from_rotation_y(25f64.to_radians()));
        let array = table(vec![("rotate", nums(&[0.0, 25.0, 0.0]))]);
        assert_eq!(local("group", &array).unwrap(), Mat4::from_rotation_y(25f64.to_radians()));
    }

    #[test]
    fn bad_transforms_are_messages() {
        let nan = table(vec![("translate", nums(&[f64::NAN, 0.0, 0.0]))]);
        assert_eq!(local("group", &nan).unwrap_err().message, "group: translate: must be finite numbers, got [NaN, 0, 0]");
        let zero = table(vec![("scale", Value::Number(0.0))]);
        assert_eq!(local("group", &zero).unwrap_err().message, "group: scale: must not be 0 (it would flatten the geometry)");
        let half = table(vec![("rotate", Value::Table(table(vec![("degrees", Value::Number(3.0))])))]);
        assert_eq!(local("group", &half).unwrap_err().message, "group: rotate: needs both axis and degrees");
        let word = table(vec![("rotate", Value::String("left".into()))]);
        assert_eq!(
            local("group", &word).unwrap_err().message,
            format!("group: rotate: {}, got a string \"left\"", crate::description::rotation::ROTATE_FORMS)
        );
    }
}
