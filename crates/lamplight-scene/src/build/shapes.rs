//! Shape nodes to core shapes, one `match` arm per type, under a world matrix.
//!
//! With the identity matrix each shape is made exactly as the built-in scenes
//! make it. Under a transform: points and edges of planes, rectangles, disks and
//! triangles are mapped (a disk and a sphere keep their kind under a similarity,
//! otherwise become an [`Instance`]); a box is one [`Cuboid`] carrying the matrix
//! (any affine one, shear included); quadrics use [`Quadric::transformed`]; tori
//! and implicit surfaces become an [`Instance`].

use std::sync::Arc;

use lamplight_core::accel::Aabb;
use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::shapes::*;

use super::transform::{finite, similarity_scale};
use super::vec3;
use crate::description::{ClipDesc, Node};
use crate::expr::Expr;

/// The keys each shape type takes besides `type`, `name` and `material`.
pub const SHAPE_KEYS: &[(&str, &[&str])] = &[
    ("sphere", &["center", "radius"]),
    ("ellipsoid", &["center", "radii", "clip"]),
    ("cylinder", &["from", "to", "radius", "caps", "clip"]),
    ("cone", &["apex", "base", "radius", "caps", "clip"]),
    ("infinite_cylinder", &["point", "axis", "radius", "clip"]),
    ("infinite_cone", &["apex", "axis", "half_angle", "clip"]),
    ("paraboloid", &["apex", "axis", "focal_length", "depth", "clip"]),
    ("hyperboloid", &["center", "axis", "a", "c", "sheets", "clip"]),
    ("quadric", &["coefficients", "clip"]),
    ("plane", &["point", "normal"]),
    ("rectangle", &["corner", "edge_u", "edge_v"]),
    ("disk", &["center", "normal", "radius"]),
    ("box", &["min", "max"]),
    ("triangle", &["vertices"]),
    ("torus", &["center", "axis", "major_radius", "minor_radius"]),
    ("implicit", &["expression", "min", "max", "lipschitz", "tolerance", "max_steps"]),
    ("mesh", &["mesh"]),
];

fn req<T>(value: Option<T>, key: &str) -> Result<T, String> {
    value.ok_or_else(|| format!("needs `{key}`"))
}

fn point(value: Option<[f64; 3]>, key: &str) -> Result<Vec3, String> {
    let v = req(value, key)?;
    finite(key, &v)?;
    Ok(vec3(v))
}

fn number(value: Option<f64>, key: &str) -> Result<f64, String> {
    let v = req(value, key)?;
    finite(key, &[v])?;
    Ok(v)
}

fn core(e: lamplight_core::Error) -> String {
    e.to_string()
}

/// The shapes node `n` (of an analytic type) makes under world matrix `m`.
pub fn make(n: &Node, m: &Mat4) -> Result<Vec<Arc<dyn Shape>>, String> {
    let identity = *m == Mat4::IDENTITY;
    let mut out: Vec<Arc<dyn Shape>> = Vec::new();
    match n.kind.as_str() {
        "sphere" => {
            let (c, r) = (point(n.center, "center")?, number(n.radius, "radius")?);
            if identity {
                out.push(Arc::new(Sphere::new(c, r).map_err(core)?));
            } else if let Some(s) = similarity_scale(m) {
                out.push(Arc::new(Sphere::new(m.transform_point3(c), r * s).map_err(core)?));
            } else {
                out.push(Arc::new(Quadric::ellipsoid(c, Vec3::splat(r)).and_then(|q| q.transformed(*m)).map_err(core)?));
            }
        }
        "ellipsoid" | "infinite_cylinder" | "infinite_cone" | "paraboloid" | "hyperboloid" | "quadric" => {
            out.push(Arc::new(placed(clipped(quadric(n)?, n)?, m)?));
        }
        "cylinder" => {
            let (p0, p1, r) = (point(n.from, "from")?, point(n.to, "to")?, number(n.radius, "radius")?);
            out.push(Arc::new(placed(clipped(Quadric::cylinder_segment(p0, p1, r).map_err(core)?, n)?, m)?));
            if n.caps.unwrap_or(false) {
                let axis = p1 - p0;
                out.push(disk(p0, -axis, r, m)?);
                out.push(disk(p1, axis, r, m)?);
            }
        }
        "cone" => {
            let (apex, base, r) = (point(n.apex, "apex")?, point(n.base, "base")?, number(n.radius, "radius")?);
            out.push(Arc::new(placed(clipped(Quadric::cone_segment(apex, base, r).map_err(core)?, n)?, m)?));
            if n.caps.unwrap_or(false) {
                out.push(disk(base, base - apex, r, m)?);
            }
        }
        "plane" => {
            let (p, normal) = (point(n.point, "point")?, point(n.normal, "normal")?);
            let normal = if identity { normal } else { m.inverse().transpose().transform_vector3(normal) };
            out.push(Arc::new(Plane::new(m.transform_point3(p), normal).map_err(core)?));
        }
        "rectangle" => {
            let (c, u, v) = (point(n.corner, "corner")?, point(n.edge_u, "edge_u")?, point(n.edge_v, "edge_v")?);
            out.push(Arc::new(Rectangle::new(m.transform_point3(c), m.transform_vector3(u), m.transform_vector3(v)).map_err(core)?));
        }
        "disk" => out.push(disk(point(n.center, "center")?, point(n.normal, "normal")?, number(n.radius, "radius")?, m)?),
        "box" => {
            let (lo, hi) = (point(n.min, "min")?, point(n.max, "max")?);
            if !(lo.cmplt(hi).all()) {
                return Err(format!("min {lo} must be below max {hi} on every axis"));
            }
            out.push(Arc::new(Cuboid::new(lo, hi, *m).map_err(core)?));
        }
        "triangle" => {
            let v = req(n.vertices, "vertices")?;
            for p in &v {
                finite("vertices", p)?;
            }
            let [a, b, c] = v.map(|p| m.transform_point3(vec3(p)));
            out.push(Arc::new(Triangle::new(a, b, c).map_err(core)?));
        }
        "torus" => {
            let (c, axis) = (point(n.center, "center")?, point(n.axis, "axis")?);
            let torus =
                Torus::new(c, axis, number(n.major_radius, "major_radius")?, number(n.minor_radius, "minor_radius")?).map_err(core)?;
            out.push(instance(Arc::new(torus), m)?);
        }
        "implicit" => out.push(instance(Arc::new(implicit(n)?), m)?),
        other => return Err(format!("is not an analytic shape type: {other}")),
    }
    Ok(out)
}

fn quadric(n: &Node) -> Result<Quadric, String> {
    match n.kind.as_str() {
        "ellipsoid" => Quadric::ellipsoid(point(n.center, "center")?, point(n.radii, "radii")?),
        "infinite_cylinder" => Quadric::cylinder(point(n.point, "point")?, point(n.axis, "axis")?, number(n.radius, "radius")?),
        "infinite_cone" => Quadric::cone(point(n.apex, "apex")?, point(n.axis, "axis")?, number(n.half_angle, "half_angle")?.to_radians()),
        "paraboloid" => {
            let (apex, axis, f) = (point(n.apex, "apex")?, point(n.axis, "axis")?, number(n.focal_length, "focal_length")?);
            match n.depth {
                Some(depth) => Quadric::paraboloid_cup(apex, axis, f, depth),
                None => Quadric::paraboloid(apex, axis, f),
            }
        }
        "hyperboloid" => {
            let sheets = match n.sheets.unwrap_or(1) {
                1 => Sheets::One,
                2 => Sheets::Two,
                s => return Err(format!("sheets must be 1 or 2, got {s}")),
            };
            Quadric::hyperboloid(point(n.center, "center")?, point(n.axis, "axis")?, number(n.a, "a")?, number(n.c, "c")?, sheets)
        }
        _ => Quadric::new(matrix(req(n.coefficients, "coefficients")?, "coefficients")?),
    }
    .map_err(core)
}

fn matrix(rows: [[f64; 4]; 4], key: &str) -> Result<Mat4, String> {
    for row in &rows {
        finite(key, row)?;
    }
    Ok(Mat4::from_cols_array_2d(&rows).transpose())
}

fn clipped(mut q: Quadric, n: &Node) -> Result<Quadric, String> {
    for clip in n.clip.iter().flatten() {
        let clip = match clip {
            ClipDesc::HalfSpace { point, normal } => {
                finite("clip point", point)?;
                finite("clip normal", normal)?;
                Clip::half_space(vec3(*point), vec3(*normal))
            }
            ClipDesc::Inside { coefficients } => Clip::inside_matrix(matrix(*coefficients, "clip coefficients")?),
        };
        q = q.with_clip(clip.map_err(core)?);
    }
    Ok(q)
}

fn placed(q: Quadric, m: &Mat4) -> Result<Quadric, String> {
    if *m == Mat4::IDENTITY {
        Ok(q)
    } else {
        q.transformed(*m).map_err(core)
    }
}

fn disk(center: Vec3, normal: Vec3, radius: f64, m: &Mat4) -> Result<Arc<dyn Shape>, String> {
    if *m == Mat4::IDENTITY {
        return Ok(Arc::new(Disk::new(center, normal, radius).map_err(core)?));
    }
    match similarity_scale(m) {
        Some(s) => Ok(Arc::new(Disk::new(m.transform_point3(center), m.transform_vector3(normal), radius * s).map_err(core)?)),
        None => instance(Arc::new(Disk::new(center, normal, radius).map_err(core)?), m),
    }
}

/// `shape` under `m`: itself for the identity, else an [`Instance`].
pub fn instance(shape: Arc<dyn Shape>, m: &Mat4) -> Result<Arc<dyn Shape>, String> {
    if *m == Mat4::IDENTITY {
        Ok(shape)
    } else {
        Ok(Arc::new(Instance::new(shape, *m).map_err(core)?))
    }
}

fn implicit(n: &Node) -> Result<Implicit, String> {
    let text = req(n.expression.as_deref(), "expression")?;
    let expr = Expr::compile(text).map_err(|e| format!("expression, at character {}: {}", e.offset + 1, e.message))?;
    let bounds = Aabb::new(point(n.min, "min")?, point(n.max, "max")?);
    let f: ImplicitFn = Arc::new(move |p: Vec3| expr.eval(p.x, p.y, p.z));
    let mut shape = Implicit::new(f, bounds, number(n.lipschitz, "lipschitz")?).map_err(core)?;
    if let Some(t) = n.tolerance {
        shape = shape.with_tolerance(t).map_err(core)?;
    }
    if let Some(steps) = n.max_steps {
        shape = shape.with_max_steps(steps.min(1 << 20) as usize);
    }
    Ok(shape)
}
