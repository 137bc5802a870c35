//! `sdfgrid`: a signed distance sampled on a grid over the unit cube (Mitsuba 3's `sdfgrid`).
//!
//! Object space is `[0, 1]^3`, placed by the node's transform. Sample `(i, j, k)`
//! of an `nx x ny x nz` grid (each at least 2) sits at the voxel corner
//! `(i / (nx - 1), j / (ny - 1), k / (nz - 1))`, and the values are stored with
//! `x` fastest: `values[(k ny + j) nx + i]` (Mitsuba's `.vol` order). Inside a
//! voxel the distance is the trilinear interpolant of its eight corners: with
//! `q_a = p_a (n_a - 1)`, the voxel `c_a = min(floor(q_a), n_a - 2)` and
//! `w_a = q_a - c_a`,
//!
//! `f(p) = sum over corners e in {0, 1}^3 of f[c + e] prod_a (e_a w_a + (1 - e_a)(1 - w_a))`.
//!
//! The surface is `f = 0`, negative inside.
//!
//! # Ray tracing
//!
//! `f` is an implicit surface ([`super::Implicit`]), marched by sphere tracing
//! with a Lipschitz bound that holds for the data, not only for a true
//! distance: inside a voxel `df/dx_a` is a bilinear blend (non-negative weights
//! summing to 1) of the four edge differences along `a`, times `n_a - 1`, so
//! `|df/dx_a| <= L_a = (n_a - 1) max |f[e + 1_a] - f[e]|` over all edges along
//! `a`, and `|grad f| <= L = sqrt(L_x^2 + L_y^2 + L_z^2)`. A step of `|f| / L`
//! therefore never crosses the surface, and a grazing ray is not missed (only
//! a sliver thinner than the march's tolerance, `1e-6` of the cube's diagonal,
//! could be). Mitsuba solves the cubic that `f` is along the ray in each voxel
//! instead; both find the root of the same interpolant.
//!
//! # Normals
//!
//! The geometric normal is `grad f` of the voxel (Mitsuba's `analytic`). The
//! shading normal is that too with `normals = "analytic"`, or, by default
//! (`"smooth"`, Hansson-Söderlund, Evans and Akenine-Möller 2022, as Mitsuba),
//! a blend that is continuous across voxels: the eight voxels around the grid
//! vertex nearest to `p` each contribute the normalized gradient of finite
//! differences across their extent (`F_a(j + 1) - F_a(j)` times `n_a - 1`, where
//! `F_a(j)` is the bilinear interpolant of sample plane `j` along `a` at `p`'s
//! other two coordinates), weighted trilinearly by `p`'s position between the
//! voxels' centres. A voxel outside the grid has weight 0; a sample plane
//! outside it is clamped to the border, so a difference there is 0.

use std::sync::Arc;

use super::{placed, Implicit, ShapeKind};
use crate::accel::Aabb;
use crate::math::Vec3;
use crate::params::{fits_f32, Kind, Param, ParamError, ParamResult, ParamType as T, Params, Value};
use crate::Error;

/// Most samples a grid may hold (`2^22`, e.g. `160^3` or `256 x 128 x 128`):
/// checked from the resolution before any value is read. A scene's values
/// pass through its parameter tables (an entry each), so the bound keeps
/// those at a few hundred megabytes.
pub const MAX_SAMPLES: usize = 1 << 22;

/// The `normals` choices; the first is the default (Mitsuba's).
const NORMALS: [&str; 2] = ["smooth", "analytic"];

/// `sdfgrid`.
pub const KIND: ShapeKind = Kind {
    name: "sdfgrid",
    summary: "a signed distance sampled on a grid over the unit cube `[0, 1]^3` (Mitsuba's `sdfgrid`), trilinearly interpolated",
    params: &[
        Param::new("resolution", T::Array, "", "each 2 or more, at most 2^22 samples", "`[nx, ny, nz]`, samples per axis"),
        Param::new("values", T::Array, "", "object units", "the `nx ny nz` signed distances, `x` fastest, negative inside"),
        Param::new(
            "normals",
            T::String,
            "\"smooth\"",
            "",
            "shading normals: `\"smooth\"` (blended across voxels) or `\"analytic\"` (the gradient)",
        ),
    ],
    build: |p, m| {
        let resolution = resolution(p)?;
        let values = values(p, resolution.iter().product())?;
        let smooth = p.choice("normals", &NORMALS)? == "smooth";
        let grid = SdfGrid::new(resolution, values).map_err(|e| p.core_error(e))?;
        Ok(vec![placed(Arc::new(grid.into_shape(smooth)), m).map_err(|e| p.core_error(e))?])
    },
};

/// `resolution`: three whole numbers of at least 2 whose product is at most [`MAX_SAMPLES`].
fn resolution(p: &mut Params<'_>) -> ParamResult<[usize; 3]> {
    let Some(item) = p.item("resolution") else { return Err(p.error("needs `resolution` ([nx, ny, nz])")) };
    let expected = |got: String| p.key_error("resolution", format!("expected [nx, ny, nz] of whole numbers of at least 2, got {got}"));
    let Value::Array(items) = &item.value else { return Err(expected(item.value.describe())) };
    let n: Vec<i64> = items.iter().filter_map(|i| if let Value::Integer(n) = i.value { Some(n) } else { None }).collect();
    if n.len() != 3 || items.len() != 3 || n.iter().any(|&n| n < 2) {
        return Err(expected(item.value.describe()));
    }
    // Multiplied in u128: three i64 cannot overflow it.
    let count = n.iter().map(|&n| n as u128).product::<u128>();
    if count > MAX_SAMPLES as u128 {
        return Err(p.key_error("resolution", format!("{} x {} x {} = {count} samples, expected at most {MAX_SAMPLES}", n[0], n[1], n[2])));
    }
    Ok([n[0] as usize, n[1] as usize, n[2] as usize])
}

/// `values`: `count` finite numbers that fit an `f32` (the grid's storage, as Mitsuba's).
fn values(p: &mut Params<'_>, count: usize) -> ParamResult<Vec<f32>> {
    let label = p.label().to_string();
    let Some(item) = p.item("values") else { return Err(p.error("needs `values` (nx ny nz numbers)")) };
    let Value::Array(items) = &item.value else {
        return Err(p.key_error("values", format!("expected an array of numbers, got {}", item.value.describe())));
    };
    if items.len() != count {
        return Err(p.key_error("values", format!("has {} numbers, expected nx ny nz = {count}", items.len())));
    }
    items
        .iter()
        .enumerate()
        .map(|(i, v)| match v.value {
            Value::Number(x) if x.is_finite() && fits_f32(x) => Ok(x as f32),
            Value::Integer(n) => Ok(n as f32),
            ref other => {
                let got = match other {
                    Value::Number(x) if x.abs() >= 1e15 => format!("{x:e}"),
                    Value::Number(x) => format!("{x}"),
                    _ => other.describe(),
                };
                Err(ParamError { loc: v.loc.clone(), message: format!("{label}: values[{i}]: expected a finite number, got {got}") })
            }
        })
        .collect()
}

/// A grid of signed distances over `[0, 1]^3` (see the module doc).
#[derive(Clone, Debug)]
pub struct SdfGrid {
    /// Samples per axis, `n_a >= 2`.
    n: [usize; 3],
    /// `n_x n_y n_z` values, `x` fastest.
    values: Vec<f32>,
}

impl SdfGrid {
    /// The grid of `n[0] x n[1] x n[2]` `values` (`x` fastest): each `n_a` at
    /// least 2, as many values, all finite, and at least one voxel whose
    /// corners have both signs (or a zero), where the surface is.
    pub fn new(n: [usize; 3], values: Vec<f32>) -> Result<SdfGrid, Error> {
        let count = n.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
        if n.iter().any(|&n| n < 2) || count.is_none_or(|c| c > MAX_SAMPLES) {
            let reason = format!("must be at least 2 per axis and at most {MAX_SAMPLES} samples, got {n:?}");
            return Err(Error::invalid("resolution", reason));
        }
        if count != Some(values.len()) {
            return Err(Error::invalid("values", format!("has {} numbers, expected {}", values.len(), count.unwrap_or(0))));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::invalid("values", format!("values[{i}] is {}, expected a finite number", values[i])));
        }
        let grid = SdfGrid { n, values };
        if !grid.voxels().any(|c| {
            let f = grid.corners(c);
            f.iter().any(|&v| v <= 0.0) && f.iter().any(|&v| v >= 0.0)
        }) {
            return Err(Error::invalid("values", "hold no surface: no voxel has corners of both signs"));
        }
        Ok(grid)
    }

    /// The lower corner of every voxel.
    fn voxels(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        let [nx, ny, nz] = self.n;
        (0..nz - 1).flat_map(move |k| (0..ny - 1).flat_map(move |j| (0..nx - 1).map(move |i| [i, j, k])))
    }

    /// The sample at `idx`, each index clamped into the grid.
    fn sample(&self, idx: [i64; 3]) -> f64 {
        let at = |a: usize| idx[a].clamp(0, self.n[a] as i64 - 1) as usize;
        f64::from(self.values[(at(2) * self.n[1] + at(1)) * self.n[0] + at(0)])
    }

    /// The eight corner values of voxel `c`, indexed `x + 2 y + 4 z`.
    fn corners(&self, c: [usize; 3]) -> [f64; 8] {
        std::array::from_fn(|e| self.sample([(c[0] + (e & 1)) as i64, (c[1] + ((e >> 1) & 1)) as i64, (c[2] + (e >> 2)) as i64]))
    }

    /// `n_a - 1` per axis: object units to grid units.
    fn scale(&self) -> [f64; 3] {
        self.n.map(|n| (n - 1) as f64)
    }

    /// The grid position `q` of `p` (clamped into the grid), the voxel that
    /// holds it and the position `w` in that voxel.
    fn locate(&self, p: Vec3) -> ([f64; 3], [usize; 3], [f64; 3]) {
        let scale = self.scale();
        let q: [f64; 3] = std::array::from_fn(|a| (p[a] * scale[a]).clamp(0.0, scale[a]));
        let c: [usize; 3] = std::array::from_fn(|a| (q[a].floor() as usize).min(self.n[a] - 2));
        (q, c, std::array::from_fn(|a| q[a] - c[a] as f64))
    }

    /// `f(p)`, the trilinear interpolant.
    pub fn value(&self, p: Vec3) -> f64 {
        let (_, c, w) = self.locate(p);
        let f = self.corners(c);
        let face = |z: usize| bilerp([f[4 * z], f[4 * z + 1], f[4 * z + 2], f[4 * z + 3]], w[0], w[1]);
        lerp(face(0), face(1), w[2])
    }

    /// `grad f(p)` in object units: per axis the bilinear blend of the voxel's
    /// four edge differences along it, times `n_a - 1`.
    pub fn gradient(&self, p: Vec3) -> Vec3 {
        let (_, c, w) = self.locate(p);
        let (f, s) = (self.corners(c), self.scale());
        let dx = bilerp([f[1] - f[0], f[3] - f[2], f[5] - f[4], f[7] - f[6]], w[1], w[2]);
        let dy = bilerp([f[2] - f[0], f[3] - f[1], f[6] - f[4], f[7] - f[5]], w[0], w[2]);
        let dz = bilerp([f[4] - f[0], f[5] - f[1], f[6] - f[2], f[7] - f[3]], w[0], w[1]);
        Vec3::new(dx * s[0], dy * s[1], dz * s[2])
    }

    /// The smooth shading normal's direction at `p` (module doc; not normalized).
    pub fn smooth_normal(&self, p: Vec3) -> Vec3 {
        let (q, cell, w) = self.locate(p);
        let s = self.scale();
        // `v`: the lower corner of the eight voxels around the nearest grid vertex;
        // `t`: `p`'s position between their centres.
        let v: [i64; 3] = std::array::from_fn(|a| q[a].round() as i64 - 1);
        let t: [f64; 3] = std::array::from_fn(|a| if v[a] < 0 { 1.0 } else { q[a] - v[a] as f64 - 0.5 });
        // `F_a(j)`: sample plane `j` along `a`, interpolated at p's other two coordinates.
        let plane = |a: usize, j: i64| {
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            let f: [f64; 4] = std::array::from_fn(|e| {
                let mut idx = [0i64; 3];
                (idx[a], idx[b], idx[c]) = (j, (cell[b] + (e & 1)) as i64, (cell[c] + (e >> 1)) as i64);
                self.sample(idx)
            });
            bilerp(f, w[b], w[c])
        };
        // The differences of the lower (`low`) and upper (`high`) voxel along each axis.
        let (mut low, mut high) = ([0.0; 3], [0.0; 3]);
        for a in 0..3 {
            let j = cell[a] as i64;
            let (f0, f1) = (plane(a, j), plane(a, j + 1));
            (low[a], high[a]) = if j != v[a] { (f0 - plane(a, j - 1), f1 - f0) } else { (f1 - f0, plane(a, j + 2) - f1) };
            (low[a], high[a]) = (low[a] * s[a], high[a] * s[a]);
        }
        let mut sum = Vec3::ZERO;
        for e in 0..8 {
            let upper = [e & 1 != 0, e & 2 != 0, e & 4 != 0];
            if (0..3).any(|a| !upper[a] && v[a] < 0) {
                continue;
            }
            let d = Vec3::from_array(std::array::from_fn(|a| if upper[a] { high[a] } else { low[a] }));
            let weight: f64 = (0..3).map(|a| if upper[a] { t[a] } else { 1.0 - t[a] }).product();
            sum += d.try_normalize().unwrap_or(Vec3::ZERO) * weight;
        }
        sum
    }

    /// The Lipschitz bound `L` of the module doc.
    pub fn lipschitz(&self) -> f64 {
        let s = self.scale();
        let mut steepest = [0.0f64; 3];
        for c in self.voxels() {
            let f = self.corners(c);
            for e in 0..8 {
                for (a, steep) in steepest.iter_mut().enumerate() {
                    if e & (1 << a) == 0 {
                        *steep = steep.max((f[e | (1 << a)] - f[e]).abs() * s[a]);
                    }
                }
            }
        }
        Vec3::from_array(steepest).length()
    }

    /// The surface to trace: an [`Implicit`] over the unit cube, shaded with
    /// the smooth normals when `smooth`.
    pub fn into_shape(self, smooth: bool) -> Implicit {
        // A constant-free grid has L > 0; a grid whose surface is all zeros
        // (L = 0) is still traced, with any positive bound.
        let lipschitz = self.lipschitz().max(f64::MIN_POSITIVE);
        let grid = Arc::new(self);
        let (f, g) = (grid.clone(), grid.clone());
        let shape = Implicit::new(Arc::new(move |p| f.value(p)), Aabb::new(Vec3::ZERO, Vec3::ONE), lipschitz)
            .expect("the unit cube and a positive bound")
            .with_gradient(Arc::new(move |p| g.gradient(p)));
        if smooth {
            shape.with_shading_normals(Arc::new(move |p| grid.smooth_normal(p)))
        } else {
            shape
        }
    }
}

fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + (b - a) * t
}

/// The bilinear interpolant of `f` (indexed `u + 2 v`) at `(u, v)`.
fn bilerp(f: [f64; 4], u: f64, v: f64) -> f64 {
    lerp(lerp(f[0], f[1], u), lerp(f[2], f[3], u), v)
}

#[cfg(test)]
mod tests;
