//! Keyframe interpolation as glTF 2.0 defines it (the specification's
//! "Animations" section and its Appendix C, "Animation Sampler Interpolation
//! Modes"): `step`, `linear` (spherical linear for rotations, by the shortest
//! path) and `cubicspline` (cubic Hermite with in- and out-tangents scaled by
//! the interval between the keys; rotations normalised after). Before the
//! first key and after the last the end value holds, as glTF says.
//!
//! Values are `[f64; 4]` of which a track uses its first 1 (a number), 3 (a
//! vector or colour) or all 4 (a quaternion `[x, y, z, w]`).

/// How values between keys are made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// Straight lines between keys; rotations by spherical linear interpolation.
    Linear,
    /// Each key's value holds until the next key.
    Step,
    /// Cubic Hermite spline through the keys with their in- and out-tangents.
    CubicSpline,
}

impl Interpolation {
    /// The names, as scene files write them; the first is the default.
    pub const NAMES: &'static [&'static str] = &["linear", "step", "cubicspline"];

    /// The interpolation called `name` (one of [`Interpolation::NAMES`]).
    pub fn from_name(name: &str) -> Option<Interpolation> {
        match name {
            "linear" => Some(Interpolation::Linear),
            "step" => Some(Interpolation::Step),
            "cubicspline" => Some(Interpolation::CubicSpline),
            _ => None,
        }
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Interpolation::Linear => "linear",
            Interpolation::Step => "step",
            Interpolation::CubicSpline => "cubicspline",
        }
    }
}

/// Where time `t` falls among the key times.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segment {
    /// On key `k` exactly, or held at it (before the first key, after the last).
    Key(usize),
    /// Between keys `k` and `k + 1`, the fraction `s` (0 < s < 1) of the way.
    Between {
        /// The key before.
        k: usize,
        /// How far from key `k` to key `k + 1`.
        s: f64,
    },
}

/// The segment of `t` among `times` (strictly increasing, at least one).
pub fn segment(times: &[f64], t: f64) -> Segment {
    let last = times.len() - 1;
    if t <= times[0] {
        return Segment::Key(0);
    }
    if t >= times[last] {
        return Segment::Key(last);
    }
    // The first key later than t: 1..=last.
    let next = times.partition_point(|&x| x <= t);
    let k = next - 1;
    if times[k] == t {
        return Segment::Key(k);
    }
    Segment::Between { k, s: (t - times[k]) / (times[next] - times[k]) }
}

/// `a + s (b - a)`, per component.
pub fn lerp(a: [f64; 4], b: [f64; 4], s: f64) -> [f64; 4] {
    std::array::from_fn(|i| a[i] + s * (b[i] - a[i]))
}

/// Spherical linear interpolation of unit quaternions `[x, y, z, w]` by the
/// shortest path (glTF's reference: `b` negated when `a . b < 0`); nearly
/// parallel ones are interpolated linearly and normalised, where `sin` of the
/// angle between them would lose its digits.
pub fn slerp(a: [f64; 4], b: [f64; 4], s: f64) -> [f64; 4] {
    let mut dot: f64 = (0..4).map(|i| a[i] * b[i]).sum();
    let mut b = b;
    if dot < 0.0 {
        b = b.map(|x| -x);
        dot = -dot;
    }
    if dot > 0.9995 {
        return normalized(lerp(a, b, s));
    }
    let theta = dot.min(1.0).acos();
    let sin = theta.sin();
    let (wa, wb) = (((1.0 - s) * theta).sin() / sin, (s * theta).sin() / sin);
    std::array::from_fn(|i| wa * a[i] + wb * b[i])
}

/// glTF's cubic spline between keys `k` (value `v0`, out-tangent `b0`) and
/// `k + 1` (value `v1`, in-tangent `a1`), `dt` apart, at fraction `s`:
/// `(2s^3 - 3s^2 + 1) v0 + dt (s^3 - 2s^2 + s) b0 + (-2s^3 + 3s^2) v1 + dt (s^3 - s^2) a1`.
pub fn hermite(v0: [f64; 4], b0: [f64; 4], v1: [f64; 4], a1: [f64; 4], s: f64, dt: f64) -> [f64; 4] {
    let (s2, s3) = (s * s, s * s * s);
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = dt * (s3 - 2.0 * s2 + s);
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = dt * (s3 - s2);
    std::array::from_fn(|i| h00 * v0[i] + h10 * b0[i] + h01 * v1[i] + h11 * a1[i])
}

/// `q / |q|` (a zero quaternion stays zero; keys are checked non-zero).
pub fn normalized(q: [f64; 4]) -> [f64; 4] {
    let len = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len == 0.0 {
        q
    } else {
        q.map(|x| x / len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 4], b: [f64; 4]) -> bool {
        (0..4).all(|i| (a[i] - b[i]).abs() < 1e-12)
    }

    #[test]
    fn segments_hold_at_the_ends_and_find_the_keys() {
        let times = [1.0, 5.0, 9.0];
        assert_eq!(segment(&times, -3.0), Segment::Key(0));
        assert_eq!(segment(&times, 1.0), Segment::Key(0));
        assert_eq!(segment(&times, 2.0), Segment::Between { k: 0, s: 0.25 });
        assert_eq!(segment(&times, 5.0), Segment::Key(1));
        assert_eq!(segment(&times, 8.0), Segment::Between { k: 1, s: 0.75 });
        assert_eq!(segment(&times, 9.0), Segment::Key(2));
        assert_eq!(segment(&times, 100.0), Segment::Key(2));
        assert_eq!(segment(&[4.0], 0.0), Segment::Key(0));
        assert_eq!(segment(&[4.0], 7.0), Segment::Key(0));
    }

    #[test]
    fn slerp_of_a_quarter_turn_passes_through_45_degrees() {
        // 0 and 90 degrees about y; halfway is 45 degrees: (0, sin 22.5, 0, cos 22.5).
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q = slerp([0.0, 0.0, 0.0, 1.0], [0.0, h, 0.0, h], 0.5);
        let (s, c) = (22.5f64.to_radians().sin(), 22.5f64.to_radians().cos());
        assert!(close(q, [0.0, s, 0.0, c]), "{q:?}");
        assert!(close(q, [0.0, 0.382_683_432_365_089_8, 0.0, 0.923_879_532_511_286_7]), "{q:?}");
        // A third of the way: 30 degrees.
        let q = slerp([0.0, 0.0, 0.0, 1.0], [0.0, h, 0.0, h], 1.0 / 3.0);
        assert!(close(q, [0.0, 15f64.to_radians().sin(), 0.0, 15f64.to_radians().cos()]), "{q:?}");
    }

    #[test]
    fn slerp_takes_the_shortest_path() {
        // 350 degrees about z is -10 degrees: halfway from 0 is -5 degrees, not 175.
        let half = 350f64.to_radians() / 2.0;
        let q350 = [0.0, 0.0, half.sin(), half.cos()];
        let q = slerp([0.0, 0.0, 0.0, 1.0], q350, 0.5);
        let expected = [0.0, 0.0, (-2.5f64).to_radians().sin(), (-2.5f64).to_radians().cos()];
        assert!(close(q, expected) || close(q.map(|x| -x), expected), "{q:?}");
    }

    #[test]
    fn hermite_with_tangents_against_hand_computed_numbers() {
        // v0 = 0, v1 = 10, out-tangent 2 per unit, in-tangent -4 per unit, keys 2 apart, s = 0.5:
        // h00 = 0.5, h10 = 2 * 0.125 = 0.25, h01 = 0.5, h11 = 2 * -0.125 = -0.25
        // p = 0 + 0.25 * 2 + 0.5 * 10 - 0.25 * -4 = 0.5 + 5 + 1 = 6.5.
        let p = hermite([0.0; 4], [2.0; 4], [10.0; 4], [-4.0; 4], 0.5, 2.0);
        assert_eq!(p[0], 6.5);
        // s = 0.25: h00 = 0.84375, h10 = 2 * 0.140625, h01 = 0.15625, h11 = 2 * -0.046875
        // p = 0.5625 + 1.5625 + 0.375 = 2.5.
        let p = hermite([0.0; 4], [2.0; 4], [10.0; 4], [-4.0; 4], 0.25, 2.0);
        assert_eq!(p[0], 2.5);
        // At the keys: the values themselves.
        assert_eq!(hermite([3.0; 4], [7.0; 4], [5.0; 4], [9.0; 4], 0.0, 4.0)[0], 3.0);
        assert_eq!(hermite([3.0; 4], [7.0; 4], [5.0; 4], [9.0; 4], 1.0, 4.0)[0], 5.0);
    }

    #[test]
    fn linear_is_a_straight_line() {
        assert_eq!(lerp([0.0, 2.0, -4.0, 0.0], [10.0, 2.0, 4.0, 0.0], 0.25), [2.5, 2.0, -2.0, 0.0]);
    }
}
