//! The quadric kinds of the scene format: the named quadrics, their finite
//! segments and the general quadric, all taking `clip` regions.
//!
//! `clip` is an array of regions the visible surface must lie in:
//! `{ type = "half_space", point = P, normal = N }` keeps `N.(p - P) <= 0`;
//! `{ type = "inside", coefficients = [[...] x 4] }` keeps `[p, 1] G [p, 1]^T <= 0`.
//! A quadric under a transform maps its matrix and clips exactly
//! (`Q' = M^-T Q M^-1`).

use std::sync::Arc;

use super::{Clip, Quadric, Sheets};
use crate::math::{similarity_scale, Mat4, Vec3};
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};
use crate::shapes::{Disk, Shape, ShapeKind};

// Said in full here: the text is also Python's `kinds()` and the reference
// table, which sits below the section that explains `clip` (issue 27).
const CLIP: Param = Param::new(
    "clip",
    T::Array,
    "none",
    "",
    "regions the visible surface must lie in, all of them: `{ type = \"half_space\", point, normal }` keeps `normal.(p - point) <= 0`, `{ type = \"inside\", coefficients }` (a 4x4 quadric `G`) keeps `[p, 1] G [p, 1]^T <= 0`",
);

/// `ellipsoid`.
pub const ELLIPSOID: ShapeKind = Kind {
    name: "ellipsoid",
    summary: "an axis-aligned ellipsoid",
    params: &[
        Param::new("center", T::Point, "", "", "centre"),
        Param::new("radii", T::Vector, "", "scene units", "semi-axes [a, b, c]"),
        CLIP,
    ],
    build: |p, m| one(p, m, |p| Quadric::ellipsoid(p.required_vec3("center")?, p.required_vec3("radii")?).map_err(|e| p.core_error(e))),
};

/// `cylinder`: a finite tube, optionally capped.
pub const CYLINDER: ShapeKind = Kind {
    name: "cylinder",
    summary: "a finite open tube from `from` to `to`; `caps = true` adds end disks",
    params: &[
        Param::new("from", T::Point, "", "", "start of the axis"),
        Param::new("to", T::Point, "", "", "end of the axis"),
        Param::new("radius", T::Number, "", "scene units", "radius"),
        Param::new("caps", T::Bool, "false", "", "close the ends with disks"),
        CLIP,
    ],
    build: |p, m| {
        let (p0, p1, r) = (p.required_vec3("from")?, p.required_vec3("to")?, p.required_number("radius")?);
        let mut out = one(p, m, |p| Quadric::cylinder_segment(p0, p1, r).map_err(|e| p.core_error(e)))?;
        if p.boolean("caps")?.unwrap_or(false) {
            let axis = p1 - p0;
            out.push(disk(p, p0, -axis, r, m)?);
            out.push(disk(p, p1, axis, r, m)?);
        }
        Ok(out)
    },
};

/// `cone`: a finite cone, optionally capped.
pub const CONE: ShapeKind = Kind {
    name: "cone",
    summary: "a finite cone; `caps` adds the base disk",
    params: &[
        Param::new("apex", T::Point, "", "", "apex"),
        Param::new("base", T::Point, "", "", "centre of the base"),
        Param::new("radius", T::Number, "", "scene units", "radius at the base"),
        Param::new("caps", T::Bool, "false", "", "close the base with a disk"),
        CLIP,
    ],
    build: |p, m| {
        let (apex, base, r) = (p.required_vec3("apex")?, p.required_vec3("base")?, p.required_number("radius")?);
        let mut out = one(p, m, |p| Quadric::cone_segment(apex, base, r).map_err(|e| p.core_error(e)))?;
        if p.boolean("caps")?.unwrap_or(false) {
            out.push(disk(p, base, base - apex, r, m)?);
        }
        Ok(out)
    },
};

/// `infinite_cylinder`.
pub const INFINITE_CYLINDER: ShapeKind = Kind {
    name: "infinite_cylinder",
    summary: "an infinite cylinder",
    params: &[
        Param::new("point", T::Point, "", "", "a point on the axis"),
        Param::new("axis", T::Vector, "", "", "axis direction"),
        Param::new("radius", T::Number, "", "scene units", "radius"),
        CLIP,
    ],
    build: |p, m| {
        one(p, m, |p| {
            Quadric::cylinder(p.required_vec3("point")?, p.required_vec3("axis")?, p.required_number("radius")?)
                .map_err(|e| p.core_error(e))
        })
    },
};

/// `infinite_cone`.
pub const INFINITE_CONE: ShapeKind = Kind {
    name: "infinite_cone",
    summary: "an infinite double cone",
    params: &[
        Param::new("apex", T::Point, "", "", "apex"),
        Param::new("axis", T::Vector, "", "", "axis direction"),
        Param::new("half_angle", T::Number, "", "degrees", "half opening angle"),
        CLIP,
    ],
    build: |p, m| {
        one(p, m, |p| {
            let (apex, axis, angle) = (p.required_vec3("apex")?, p.required_vec3("axis")?, p.required_number("half_angle")?);
            Quadric::cone(apex, axis, angle.to_radians()).map_err(|e| p.core_error(e))
        })
    },
};

/// `paraboloid`.
pub const PARABOLOID: ShapeKind = Kind {
    name: "paraboloid",
    summary: "`|P-A|^2 - ((P-A).a)^2 = 4 f (P-A).a`, cut at `0 <= (P-A).a <= depth`",
    params: &[
        Param::new("apex", T::Point, "", "", "apex"),
        Param::new("axis", T::Vector, "", "", "axis direction, into the bowl"),
        Param::new("focal_length", T::Number, "", "scene units", "focal length f"),
        Param::new("depth", T::Number, "none: infinite", "scene units", "depth of the cup"),
        CLIP,
    ],
    build: |p, m| {
        one(p, m, |p| {
            let (apex, axis, f) = (p.required_vec3("apex")?, p.required_vec3("axis")?, p.required_number("focal_length")?);
            match p.number("depth")? {
                Some(depth) => Quadric::paraboloid_cup(apex, axis, f, depth),
                None => Quadric::paraboloid(apex, axis, f),
            }
            .map_err(|e| p.core_error(e))
        })
    },
};

/// `hyperboloid`.
pub const HYPERBOLOID: ShapeKind = Kind {
    name: "hyperboloid",
    summary: "a hyperboloid of one or two sheets",
    params: &[
        Param::new("center", T::Point, "", "", "centre"),
        Param::new("axis", T::Vector, "", "", "axis direction"),
        Param::new("a", T::Number, "", "scene units", "radial semi-axis"),
        Param::new("c", T::Number, "", "scene units", "axial semi-axis"),
        Param::new("sheets", T::Integer, "1", "1 or 2", "number of sheets"),
        CLIP,
    ],
    build: |p, m| {
        one(p, m, |p| {
            let sheets = match p.integer("sheets", 1..=2)?.unwrap_or(1) {
                1 => Sheets::One,
                _ => Sheets::Two,
            };
            let (c, axis) = (p.required_vec3("center")?, p.required_vec3("axis")?);
            Quadric::hyperboloid(c, axis, p.required_number("a")?, p.required_number("c")?, sheets).map_err(|e| p.core_error(e))
        })
    },
};

/// `quadric`: any symmetric 4x4 matrix.
pub const QUADRIC: ShapeKind = Kind {
    name: "quadric",
    summary: "`[p, 1] Q [p, 1]^T = 0`, symmetrized",
    params: &[Param::new("coefficients", T::Matrix, "", "", "the 4x4 matrix Q, rows"), CLIP],
    build: |p, m| {
        one(p, m, |p| {
            let q = p.matrix("coefficients")?.ok_or_else(|| p.error("needs `coefficients` (4 rows of 4 numbers)"))?;
            Quadric::new(q).map_err(|e| p.core_error(e))
        })
    },
};

/// The quadric `make` builds, clipped and placed.
fn one(p: &mut Params<'_>, m: &Mat4, make: impl FnOnce(&mut Params<'_>) -> ParamResult<Quadric>) -> ParamResult<Vec<Arc<dyn Shape>>> {
    let mut q = make(p)?;
    for mut clip in p.tables("clip")? {
        let region = match clip.required_choice("type", &["half_space", "inside"])? {
            "half_space" => Clip::half_space(clip.required_vec3("point")?, clip.required_vec3("normal")?),
            _ => {
                let g = clip.matrix("coefficients")?.ok_or_else(|| clip.error("needs `coefficients` (4 rows of 4 numbers)"))?;
                Clip::inside_matrix(g)
            }
        };
        let region = region.map_err(|e| clip.core_error(e))?;
        clip.finish()?;
        q = q.with_clip(region);
    }
    if *m != Mat4::IDENTITY {
        q = q.transformed(*m).map_err(|e| p.core_error(e))?;
    }
    Ok(vec![Arc::new(q)])
}

/// An end disk of a cylinder or cone: a disk under a similarity, else an instance.
fn disk(p: &Params<'_>, center: Vec3, normal: Vec3, radius: f64, m: &Mat4) -> ParamResult<Arc<dyn Shape>> {
    let made: Result<Arc<dyn Shape>, crate::Error> = if *m == Mat4::IDENTITY {
        Disk::new(center, normal, radius).map(|d| Arc::new(d) as Arc<dyn Shape>)
    } else {
        match similarity_scale(m) {
            Some(s) => {
                Disk::new(m.transform_point3(center), m.transform_vector3(normal), radius * s).map(|d| Arc::new(d) as Arc<dyn Shape>)
            }
            None => Disk::new(center, normal, radius).and_then(|d| crate::shapes::placed(Arc::new(d), m)),
        }
    };
    made.map_err(|e| p.core_error(e))
}
