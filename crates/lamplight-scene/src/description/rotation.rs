//! A `rotate` value, read in one place for node transforms
//! ([`crate::instantiate`]) and for keyframed rotations ([`super::animation`]).
//!
//! Four forms are accepted: `{ axis = [x, y, z], degrees = N }`, `{ x = N, y =
//! N, z = N }` or `[x, y, z]` (degrees about x, then y, then z), and `{
//! quaternion = [x, y, z, w] }` (glTF's order; normalised). Each becomes a
//! [`Rotation`], which gives the matrix the transform uses (about a coordinate
//! axis exactly glam's `from_rotation_{x,y,z}`, so `rotate = { y = 25 }` gives
//! the matrix the built-in scenes compute) or the unit quaternion that
//! keyframes interpolate.

use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::params::{Entry, Item, Param, ParamError, ParamResult, ParamType as T, Params, Table, Value};

/// What `rotate` must be.
pub const ROTATE_FORMS: &str =
    "expected a table { axis = [x, y, z], degrees = N }, { x = N, y = N, z = N } or { quaternion = [x, y, z, w] }, or [x, y, z] degrees";

/// The keys of a `rotate` table.
pub const ROTATE_KEYS: [Param; 6] = [
    Param::new("axis", T::Vector, "", "", "rotation axis"),
    Param::new("degrees", T::Number, "", "degrees", "angle, counter-clockwise looking down the axis"),
    Param::new("x", T::Number, "0", "degrees", "about x"),
    Param::new("y", T::Number, "0", "degrees", "about y"),
    Param::new("z", T::Number, "0", "degrees", "about z"),
    Param::new("quaternion", T::Array, "", "[x, y, z, w]", "a unit quaternion (normalised), glTF's order"),
];

/// A rotation as the scene gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rotation {
    /// Degrees about x, then y, then z.
    Euler(Vec3),
    /// A unit axis and an angle in radians.
    AxisAngle(Vec3, f64),
    /// A unit quaternion.
    Quaternion(glam::DQuat),
}

impl Rotation {
    /// The rotation matrix; about a coordinate axis exactly glam's (see the module docs).
    pub fn matrix(self) -> Mat4 {
        match self {
            Rotation::Euler(v) => {
                let mut m = Mat4::IDENTITY;
                // x first: the matrix applied first stands rightmost.
                for (deg, make) in
                    [(v.z, Mat4::from_rotation_z as fn(f64) -> Mat4), (v.y, Mat4::from_rotation_y), (v.x, Mat4::from_rotation_x)]
                {
                    if deg != 0.0 {
                        m *= make(deg.to_radians());
                    }
                }
                m
            }
            Rotation::AxisAngle(axis, rad) => axis_rotation(axis, rad),
            Rotation::Quaternion(q) => Mat4::from_quat(q),
        }
    }

    /// The unit quaternion.
    pub fn quaternion(self) -> glam::DQuat {
        use glam::DQuat;
        match self {
            Rotation::Euler(v) => {
                DQuat::from_rotation_z(v.z.to_radians())
                    * DQuat::from_rotation_y(v.y.to_radians())
                    * DQuat::from_rotation_x(v.x.to_radians())
            }
            Rotation::AxisAngle(axis, rad) => DQuat::from_axis_angle(axis, rad),
            Rotation::Quaternion(q) => q,
        }
    }
}

/// The rotation `item` (the value of `key`, read for `p`) gives.
pub fn read(p: &mut Params<'_>, key: &str) -> ParamResult<Rotation> {
    let item = p.item(key).ok_or_else(|| p.error(format!("needs `{key}`")))?;
    match &item.value {
        Value::Array(_) => {
            let one =
                Table { entries: vec![Entry { key: key.into(), key_loc: item.loc.clone(), item: item.clone() }], loc: item.loc.clone() };
            let mut q = Params::new(p.label().to_string(), &one);
            let v = q.vec3(key).map_err(|_| bad(p, key, item))?.expect("present");
            Ok(Rotation::Euler(v))
        }
        Value::Table(_) => {
            let mut r = p.table(key)?.expect("present");
            r.check_keys(&ROTATE_KEYS, &[])?;
            let given = |r: &Params<'_>, keys: &[&str]| keys.iter().any(|k| r.has(k));
            let out = if r.has("quaternion") {
                if given(&r, &["axis", "degrees", "x", "y", "z"]) {
                    return Err(r.error("takes a quaternion alone, not with axis, degrees or x, y, z"));
                }
                Rotation::Quaternion(quaternion(&mut r)?)
            } else {
                match (r.vec3("axis")?, r.number("degrees")?) {
                    (Some(axis), Some(deg)) => {
                        if given(&r, &["x", "y", "z"]) {
                            return Err(r.error("takes either axis and degrees or x, y, z, not both"));
                        }
                        let axis = axis.try_normalize().ok_or_else(|| r.key_error("axis", "must not be zero"))?;
                        Rotation::AxisAngle(axis, deg.to_radians())
                    }
                    (None, None) => Rotation::Euler(Vec3::new(r.number_or("x", 0.0)?, r.number_or("y", 0.0)?, r.number_or("z", 0.0)?)),
                    _ => return Err(r.error("needs both axis and degrees")),
                }
            };
            r.finish()?;
            Ok(out)
        }
        _ => Err(bad(p, key, item)),
    }
}

/// `quaternion = [x, y, z, w]`: four finite numbers, not all zero, normalised.
fn quaternion(r: &mut Params<'_>) -> ParamResult<glam::DQuat> {
    let item = r.item("quaternion").expect("present");
    let q = numbers4(&item.value)
        .ok_or_else(|| r.key_error("quaternion", format!("expected [x, y, z, w], four numbers, got {}", item.value.describe())))?;
    let q = glam::DQuat::from_array(q);
    if !q.is_finite() || q.length_squared() == 0.0 {
        return Err(r.key_error("quaternion", "must be finite numbers, not all zero"));
    }
    Ok(q.normalize())
}

/// Four numbers, when `value` is an array of four.
pub(crate) fn numbers4(value: &Value) -> Option<[f64; 4]> {
    match value {
        Value::Array(items) if items.len() == 4 => {
            let mut out = [0.0; 4];
            for (o, i) in out.iter_mut().zip(items) {
                *o = match i.value {
                    Value::Number(x) => x,
                    Value::Integer(n) => n as f64,
                    _ => return None,
                };
            }
            Some(out)
        }
        _ => None,
    }
}

fn bad(p: &Params<'_>, key: &str, item: &Item) -> ParamError {
    p.key_error(key, format!("{ROTATE_FORMS}, got {}", item.value.describe()))
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
    use lamplight_core::params::Loc;

    fn rotate(value: Value) -> ParamResult<Rotation> {
        let t = Table {
            entries: vec![Entry { key: "rotate".into(), key_loc: Loc::Unknown, item: Item { value, loc: Loc::Unknown } }],
            loc: Loc::Unknown,
        };
        read(&mut Params::new("group", &t), "rotate")
    }

    fn nums(v: &[f64]) -> Value {
        Value::Array(v.iter().map(|x| Item { value: Value::Number(*x), loc: Loc::Unknown }).collect())
    }

    fn table(entries: Vec<(&str, Value)>) -> Value {
        Value::Table(Table {
            entries: entries
                .into_iter()
                .map(|(k, v)| Entry { key: k.into(), key_loc: Loc::Unknown, item: Item { value: v, loc: Loc::Unknown } })
                .collect(),
            loc: Loc::Unknown,
        })
    }

    #[test]
    fn every_form_gives_the_same_rotation_as_matrix_and_quaternion() {
        let forms = [
            rotate(nums(&[30.0, 40.0, 50.0])).unwrap(),
            rotate(table(vec![("x", Value::Number(30.0)), ("y", Value::Number(40.0)), ("z", Value::Number(50.0))])).unwrap(),
        ];
        let p = Vec3::new(0.3, -1.2, 2.0);
        for r in forms {
            let by_matrix = r.matrix().transform_point3(p);
            let by_quaternion = r.quaternion() * p;
            assert!((by_matrix - by_quaternion).length() < 1e-12, "{by_matrix} vs {by_quaternion}");
        }
        // 90 degrees about y as a quaternion: (0, sin 45, 0, cos 45), normalised from any length.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q = rotate(table(vec![("quaternion", nums(&[0.0, 2.0, 0.0, 2.0]))])).unwrap();
        let Rotation::Quaternion(unit) = q else { panic!("{q:?}") };
        assert!((unit.to_array()[1] - h).abs() < 1e-15 && (unit.to_array()[3] - h).abs() < 1e-15, "{unit:?}");
        assert!((q.matrix().transform_point3(Vec3::X) - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-15);
    }

    #[test]
    fn bad_quaternions_are_messages() {
        let zero = rotate(table(vec![("quaternion", nums(&[0.0, 0.0, 0.0, 0.0]))])).unwrap_err();
        assert_eq!(zero.message, "group: rotate: quaternion: must be finite numbers, not all zero");
        let three = rotate(table(vec![("quaternion", nums(&[0.0, 0.0, 1.0]))])).unwrap_err();
        assert_eq!(three.message, "group: rotate: quaternion: expected [x, y, z, w], four numbers, got an array of 3");
        let both = rotate(table(vec![("quaternion", nums(&[0.0, 0.0, 0.0, 1.0])), ("y", Value::Number(3.0))])).unwrap_err();
        assert_eq!(both.message, "group: rotate: takes a quaternion alone, not with axis, degrees or x, y, z");
    }
}
