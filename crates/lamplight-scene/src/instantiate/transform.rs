//! Node transforms: `translate`, `rotate`, `scale`, `matrix` to one matrix.
//!
//! A node's own matrix is `T R S X` (`X` the `matrix` key): a point is first
//! mapped by `matrix`, then scaled, rotated and translated; a child's world
//! matrix is its parent's times its own. Rotations about a coordinate axis use
//! glam's `from_rotation_{x,y,z}` so that `rotate = { y = 25 }` gives exactly the
//! matrix the built-in scenes compute.

use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::params::{Item, ParamResult, Params, Table, Value};

/// What `rotate` must be.
const ROTATE_FORMS: &str = "expected a table { axis = [x, y, z], degrees = N } or { x = N, y = N, z = N }, or [x, y, z] degrees";

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
    let item = p.item("rotate").expect("present");
    let xyz = |x: f64, y: f64, z: f64| {
        let mut m = Mat4::IDENTITY;
        // x first: the matrix applied first stands rightmost.
        for (deg, make) in [(z, Mat4::from_rotation_z as fn(f64) -> Mat4), (y, Mat4::from_rotation_y), (x, Mat4::from_rotation_x)] {
            if deg != 0.0 {
                m *= make(deg.to_radians());
            }
        }
        m
    };
    match &item.value {
        Value::Array(_) => {
            let one = lamplight_core::params::Table {
                entries: vec![lamplight_core::params::Entry { key: "rotate".into(), key_loc: item.loc.clone(), item: item.clone() }],
                loc: item.loc.clone(),
            };
            let mut q = Params::new(p.label().to_string(), &one);
            let v = q.vec3("rotate").map_err(|_| p.key_error("rotate", ROTATE_FORMS))?.expect("present");
            Ok(xyz(v.x, v.y, v.z))
        }
        Value::Table(_) => {
            let mut r = p.table("rotate")?.expect("present");
            r.check_keys(&ROTATE_KEYS, &[])?;
            let out = match (r.vec3("axis")?, r.number("degrees")?) {
                (Some(axis), Some(deg)) => {
                    if r.has("x") || r.has("y") || r.has("z") {
                        return Err(r.error("takes either axis and degrees or x, y, z, not both"));
                    }
                    let axis = axis.try_normalize().ok_or_else(|| r.key_error("axis", "must not be zero"))?;
                    axis_rotation(axis, deg.to_radians())
                }
                (None, None) => {
                    let (x, y, z) = (r.number_or("x", 0.0)?, r.number_or("y", 0.0)?, r.number_or("z", 0.0)?);
                    xyz(x, y, z)
                }
                _ => return Err(r.error("needs both axis and degrees")),
            };
            r.finish()?;
            Ok(out)
        }
        _ => Err(bad_rotate(p, item)),
    }
}

const ROTATE_KEYS: [lamplight_core::params::Param; 5] = {
    use lamplight_core::params::{Param, ParamType as T};
    [
        Param::new("axis", T::Vector, "", "", "rotation axis"),
        Param::new("degrees", T::Number, "", "degrees", "angle, counter-clockwise looking down the axis"),
        Param::new("x", T::Number, "0", "degrees", "about x"),
        Param::new("y", T::Number, "0", "degrees", "about y"),
        Param::new("z", T::Number, "0", "degrees", "about z"),
    ]
};

fn bad_rotate(p: &Params<'_>, item: &Item) -> lamplight_core::params::ParamError {
    p.key_error("rotate", format!("{ROTATE_FORMS}, got {}", item.value.describe()))
}

/// The rotation by `rad` about the unit `axis`; about a coordinate axis it is
/// glam's exact one (`from_axis_angle` rounds its off-axis terms).
pub(crate) fn axis_rotation(axis: Vec3, rad: f64) -> Mat4 {
    if axis == Vec3::X {
        Mat4::from_rotation_x(rad)
    } else if axis == Vec3::Y {
        Mat4::from_rotation_y(rad)
    } else if axis == Vec3::Z {
        Mat4::from_rotation_z(rad)
    } else {
        Mat4::from_axis_angle(axis, rad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_core::params::{Entry, Loc};

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
        assert_eq!(local("group", &word).unwrap_err().message, format!("group: rotate: {ROTATE_FORMS}, got a string \"left\""));
    }
}
