//! `implicit`: a surface `f(x, y, z) = 0` given as an expression (it needs this
//! crate's expression parser, [`crate::expr`], so its kind lives here).
//!
//! `expression` is `f` in `x`, `y`, `z` with `+ - * / ^`, parentheses, `pi`,
//! `e`, and `sin cos tan sqrt abs exp ln min max pow`; `f < 0` is the inside.
//! `lipschitz` bounds `|f(a) - f(b)| / |a - b|` inside the box: the ray
//! marcher's steps of `|f| / lipschitz` then never cross the surface.

use std::sync::Arc;

use lamplight_core::accel::Aabb;
use lamplight_core::math::Vec3;
use lamplight_core::params::{Kind, Param, ParamType as T};
use lamplight_core::shapes::{placed, Implicit, ImplicitFn, ShapeKind};

use crate::expr::Expr;

/// Most steps of the ray march a file may ask for: with a loose Lipschitz bound
/// every ray takes them all, so this bounds the work per ray (65,536 steps of an
/// interpreted expression cost a few milliseconds; 2^32 cost minutes per pixel).
pub const MAX_STEPS: i64 = 1 << 16;

/// `implicit`.
pub const KIND: ShapeKind = Kind {
    name: "implicit",
    summary: "the surface `f(x, y, z) = 0` inside the box `[min, max]`",
    params: &[
        Param::new("expression", T::String, "", "", "`f(x, y, z)`, negative inside"),
        Param::new("min", T::Point, "", "", "low corner of the bounding box"),
        Param::new("max", T::Point, "", "", "high corner of the bounding box"),
        Param::new("lipschitz", T::Number, "", "> 0", "bound of |grad f| inside the box"),
        Param::new("tolerance", T::Number, "1e-6 of the box diagonal", "scene units", "root tolerance"),
        Param::new("max_steps", T::Integer, "4096", "1 to 2^16", "march steps per ray"),
    ],
    build: |p, m| {
        let text = p.required_string("expression")?;
        let expr = Expr::compile(text).map_err(|e| p.key_error("expression", format!("at character {}: {}", e.offset + 1, e.message)))?;
        let (lo, hi) = (p.required_vec3("min")?, p.required_vec3("max")?);
        if lo.cmpge(hi).any() {
            // As `box` says it: the box would be empty or inside out.
            return Err(p.key_error("max", format!("min {lo} must be below max {hi} on every axis")));
        }
        let bounds = Aabb::new(lo, hi);
        let f: ImplicitFn = Arc::new(move |q: Vec3| expr.eval(q.x, q.y, q.z));
        let mut shape = Implicit::new(f, bounds, p.required_number("lipschitz")?).map_err(|e| p.core_error(e))?;
        if let Some(t) = p.number("tolerance")? {
            shape = shape.with_tolerance(t).map_err(|e| p.core_error(e))?;
        }
        if let Some(steps) = p.integer("max_steps", 1..=MAX_STEPS)? {
            shape = shape.with_max_steps(steps as usize);
        }
        Ok(vec![placed(Arc::new(shape), m).map_err(|e| p.core_error(e))?])
    },
};
