//! Real roots of a polynomial of degree at most 4 on an interval, by recursive
//! isolation with the derivative.
//!
//! The roots of `p'` split the interval into pieces on which `p` is monotone; each
//! piece holds at most one root, found by bisection with Newton steps when `p`
//! changes sign across it. The roots of `p'` are found the same way from `p''`,
//! down to a linear polynomial. A critical point where `|p|` is within the rounding
//! error of its evaluation is also reported as a root: that is a double root (a ray
//! tangent to the surface) which rounding may have lifted off zero, and reporting it
//! is what keeps grazing hits from being lost.
//!
//! Alongside the coefficients `a_i` the polynomial carries magnitudes `m_i >= |a_i|`:
//! the sums of the absolute values of the terms each coefficient was computed from.
//! `K eps sum m_i |u|^i` then bounds the error of evaluating `p(u)`, including the
//! cancellation inside the coefficients themselves.

/// Safety factor on the rounding error bound (covers the few roundings per
/// coefficient and per Horner step, `4 + 4 + 2` at most, with a margin).
const NOISE_FACTOR: f64 = 64.0;
/// Iteration cap of the bisection/Newton refinement: a hard bound on its cost. Newton
/// converges in a handful of steps, and 64 halvings shrink any bracket away from zero
/// to adjacent doubles, so the cap is reached only by brackets that reach down to 0.
const MAX_REFINE: usize = 200;

/// `sum a_i u^i` of degree `n` with error magnitudes (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(super) struct Poly {
    /// Coefficient of `u^i`.
    pub a: [f64; 5],
    /// Magnitude bound for `a[i]`, at least `|a[i]|`.
    pub m: [f64; 5],
    /// Degree, at most 4.
    pub n: usize,
}

impl Poly {
    /// `p(u)`.
    #[inline]
    pub(super) fn eval(&self, u: f64) -> f64 {
        self.a[..=self.n].iter().rev().fold(0.0, |acc, &c| acc * u + c)
    }

    /// `p(u)` and `p'(u)`.
    #[inline]
    fn eval_with_derivative(&self, u: f64) -> (f64, f64) {
        let (mut p, mut dp) = (0.0, 0.0);
        for &c in self.a[..=self.n].iter().rev() {
            dp = dp * u + p;
            p = p * u + c;
        }
        (p, dp)
    }

    /// Bound on the rounding error of `eval(u)`.
    #[inline]
    pub(super) fn noise(&self, u: f64) -> f64 {
        let au = u.abs();
        NOISE_FACTOR * f64::EPSILON * self.m[..=self.n].iter().rev().fold(0.0, |acc, &c| acc * au + c)
    }

    /// `p'`, with magnitudes carried along.
    pub(super) fn derivative(&self) -> Poly {
        let mut d = Poly { a: [0.0; 5], m: [0.0; 5], n: self.n.saturating_sub(1) };
        for i in 1..=self.n {
            d.a[i - 1] = self.a[i] * i as f64;
            d.m[i - 1] = self.m[i] * i as f64;
        }
        d
    }
}

/// Up to five sorted roots, on the stack: the root finder runs once per ray and
/// should not allocate.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Roots {
    values: [f64; 5],
    len: usize,
}

impl Roots {
    /// Appends `u` unless it repeats the last root.
    fn push(&mut self, u: f64) {
        if self.len < self.values.len() && (self.len == 0 || self.values[self.len - 1] != u) {
            self.values[self.len] = u;
            self.len += 1;
        }
    }

    /// The roots in increasing order.
    pub(super) fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }
}

/// Every real root of `p` in `[lo, hi]`, in increasing order (tangent roots within
/// rounding included). The leading coefficient must be non-zero.
pub(super) fn roots_in(p: &Poly, lo: f64, hi: f64) -> Roots {
    let mut out = Roots::default();
    if lo.is_nan() || hi.is_nan() || lo > hi || p.n == 0 {
        return out;
    }
    if p.n == 1 {
        let u = -p.a[0] / p.a[1];
        if u >= lo && u <= hi {
            out.push(u);
        }
        return out;
    }
    // Monotone pieces between the critical points: at most one root each.
    let critical = roots_in(&p.derivative(), lo, hi);
    let critical = critical.as_slice();
    let mut x0 = lo;
    let mut v0 = p.eval(lo);
    if v0 == 0.0 {
        out.push(lo);
    }
    for (k, x1) in critical.iter().copied().chain(std::iter::once(hi)).enumerate() {
        let v1 = p.eval(x1);
        if v1 == 0.0 {
            out.push(x1);
        } else if v0 != 0.0 && (v0 < 0.0) != (v1 < 0.0) {
            out.push(refine(p, x0, x1, v0));
        } else if k < critical.len() && v1.abs() <= p.noise(x1) {
            // A critical point that touches zero within rounding: a double root.
            out.push(x1);
        }
        x0 = x1;
        v0 = v1;
    }
    out
}

/// The root of `p` in `[a, b]`, where `p` is monotone and `p(a) = va` differs in
/// sign from `p(b)`: Newton steps, replaced by bisection whenever they leave the
/// bracket, until the bracket or the step reaches the spacing of doubles.
fn refine(p: &Poly, mut a: f64, mut b: f64, va: f64) -> f64 {
    let negative_at_a = va < 0.0;
    let mut x = 0.5 * (a + b);
    for _ in 0..MAX_REFINE {
        let (v, dv) = p.eval_with_derivative(x);
        if v == 0.0 {
            return x;
        }
        if (v < 0.0) == negative_at_a {
            a = x;
        } else {
            b = x;
        }
        let newton = x - v / dv;
        let next = if newton > a && newton < b { newton } else { 0.5 * (a + b) };
        if !(a < next && next < b) {
            break; // a and b are adjacent doubles
        }
        let converged = (next - x).abs() <= f64::EPSILON * x.abs();
        x = next;
        if converged {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `prod (u - r_i)` with exact-ish magnitudes.
    fn from_roots(roots: &[f64]) -> Poly {
        let mut a = [0.0; 5];
        a[0] = 1.0;
        for (k, &r) in roots.iter().enumerate() {
            for i in (0..=k + 1).rev() {
                a[i] = if i > 0 { a[i - 1] } else { 0.0 } - r * a[i];
            }
        }
        Poly { a, m: a.map(f64::abs), n: roots.len() }
    }

    #[test]
    fn finds_all_simple_roots_in_order() {
        let p = from_roots(&[-1.5, 0.25, 0.5, 3.0]);
        let r = roots_in(&p, -10.0, 10.0).as_slice().to_vec();
        assert_eq!(r.len(), 4, "{r:?}");
        for (got, want) in r.iter().zip([-1.5, 0.25, 0.5, 3.0]) {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
        assert_eq!(roots_in(&p, 0.3, 2.0).as_slice().len(), 1);
        assert!(roots_in(&p, 4.0, 10.0).as_slice().is_empty());
    }

    #[test]
    fn close_and_double_roots_are_found() {
        let r = roots_in(&from_roots(&[1.0, 1.0 + 1e-7, 2.0, 5.0]), 0.0, 10.0).as_slice().to_vec();
        assert_eq!(r.len(), 4, "{r:?}");
        // Rounding the coefficients (~1e-16 of 30) moves roots where |p'| ~ 4e-7 by ~1e-8.
        assert!((r[0] - 1.0).abs() < 2e-8 && (r[1] - 1.0 - 1e-7).abs() < 2e-8, "{r:?}");
        // A double root: no sign change, found as a critical point touching zero.
        let r = roots_in(&from_roots(&[0.7, 0.7, -3.0, 4.0]), 0.0, 10.0).as_slice().to_vec();
        assert!(!r.is_empty() && (r[0] - 0.7).abs() < 1e-7, "{r:?}");
        // An extremum clearly off zero is not a root.
        let mut lifted = from_roots(&[0.7, 0.7, -3.0, 4.0]);
        lifted.a[0] -= 1e-6; // the double root is a maximum: push it below zero
        assert!(roots_in(&lifted, 0.0, 3.0).as_slice().is_empty());
    }
}
