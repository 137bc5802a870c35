use super::signed::SignedTable;
use super::*;

const GAUSS: Filter = Filter::Gaussian { sigma: 0.5 };

/// The integral of `g` over `[a, b]` by the midpoint rule.
fn integral(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 20_000;
    let h = (b - a) / n as f64;
    (0..n).map(|i| g(a + (i as f64 + 0.5) * h) * h).sum()
}

#[test]
fn cumulative_weights_integrate_the_weights() {
    for f in [Filter::Box, Filter::Tent, GAUSS, Filter::Gaussian { sigma: 0.3 }] {
        let r = f.radius();
        assert_eq!(f.cumulative(-r), 0.0, "{f:?}");
        for x in [-0.9 * r, -0.3, 0.0, 0.2, 0.7 * r, r] {
            let exact = integral(|t| f.weight(t), -r, x);
            assert!((f.cumulative(x) - exact).abs() < 1e-6, "{f:?} at {x}: {} vs {exact}", f.cumulative(x));
        }
    }
    // Analytic totals: the box and the tent have area 1; the cut Gaussian
    // sqrt(pi/8) erf(2 sqrt 2) 2 - 4 exp(-8).
    assert_eq!(Filter::Tent.cumulative(1.0), 1.0);
    let gauss_total = (std::f64::consts::PI / 8.0).sqrt() * 2.0 * libm::erf(2.0 * std::f64::consts::SQRT_2) - 4.0 * (-8.0f64).exp();
    assert!((GAUSS.cumulative(2.0) - gauss_total).abs() < 1e-15);
    assert!((GAUSS.weight(0.0) - (1.0 - (-8.0f64).exp())).abs() < 1e-15);
    assert_eq!(GAUSS.weight(2.0), 0.0);
}

#[test]
fn offsets_follow_the_filter_restricted_to_the_bounds() {
    // The mean of x^2 (and of x) over stratified u equals that of the
    // weight restricted to [lo, hi], by quadrature.
    for f in [Filter::Tent, GAUSS] {
        let r = f.radius();
        for (lo, hi) in [(-f64::INFINITY, f64::INFINITY), (-0.5, f64::INFINITY), (-0.5, 0.5), (-1.5, 0.25)] {
            let (a, b) = (f64::max(lo, -r), f64::min(hi, r));
            let mass = integral(|t| f.weight(t), a, b);
            let mean = integral(|t| t * f.weight(t), a, b) / mass;
            let second = integral(|t| t * t * f.weight(t), a, b) / mass;
            let n = 20_000;
            let xs: Vec<(f64, f64)> = (0..n).map(|i| f.sample_axis((i as f64 + 0.5) / n as f64, lo, hi)).collect();
            assert!(xs.iter().all(|&(x, w)| x >= a && x <= b && w > 0.0 && w <= 4.0 / 3.0 + 1e-12), "{f:?} [{lo}, {hi}]");
            let m0 = xs.iter().map(|(_, w)| w).sum::<f64>() / n as f64;
            let m1 = xs.iter().map(|(x, w)| x * w).sum::<f64>() / n as f64;
            let m2 = xs.iter().map(|(x, w)| x * x * w).sum::<f64>() / n as f64;
            assert!((m0 - 1.0).abs() < 1e-4, "{f:?} [{lo}, {hi}]: weights average {m0}");
            assert!((m1 - mean).abs() < 1e-4 && (m2 - second).abs() < 1e-4, "{f:?} [{lo}, {hi}]: {m1} {m2} vs {mean} {second}");
        }
    }
}

#[test]
fn offsets_invert_the_cumulative_weight() {
    // The tent in closed form: u = 1/8 gives (x + 1)^2 / 2 = 1/8, x = -1/2.
    assert_eq!(Filter::Tent.sample((0.125, 0.875)), ((-0.5, 0.5), 1.0));
    // The Gaussian's filter part (u from 0.25 on, rescaled) is odd about the
    // centre, with its median at u = 0.625; its uniform part spans the support.
    let ((x, y), _) = GAUSS.sample((0.625, 0.91));
    assert!(x.abs() < 1e-12);
    let ((y2, _), _) = GAUSS.sample((0.34, 0.5));
    assert!((y + y2).abs() < 1e-9, "{y} {y2}");
    assert_eq!(GAUSS.sample_axis(0.125, -1.0, 3.0).0, 0.5, "halfway along [-1, 2]");
    // Restricted to [0, 2], the filter part's middle holds half the right half's weight.
    let (x, w) = GAUSS.sample_axis(0.625, 0.0, f64::INFINITY);
    assert!((GAUSS.cumulative(x) - 0.75 * GAUSS.cumulative(2.0)).abs() < 1e-12, "{x}");
    let density = GAUSS.weight(x) / (0.5 * GAUSS.cumulative(2.0));
    assert!((w - density / (0.75 * density + 0.25 / 2.0)).abs() < 1e-15);
}

#[test]
fn the_gaussians_inverse_is_exact_to_1e_12() {
    for f in [GAUSS, Filter::Gaussian { sigma: 0.3 }, Filter::Gaussian { sigma: 1.7 }] {
        let r = f.radius();
        for (lo, hi) in [(-r, r), (-0.2, r), (0.7 * r, r), (-r, -0.9 * r)] {
            let (wa, wb) = (f.cumulative(lo), f.cumulative(hi));
            for i in 0..=1000 {
                let w = wa + (wb - wa) * i as f64 / 1000.0;
                let x = f.inverse_cumulative(w, lo, hi);
                assert!((lo..=hi).contains(&x) && (f.cumulative(x) - w).abs() < 1e-12, "{f:?} [{lo}, {hi}] w {w}: x {x}");
            }
        }
    }
}

#[test]
fn the_box_keeps_its_offsets() {
    // A pixel centre is at least 1/2 from the image's edge, so the box is never cut.
    for u in [0.0, 0.1, 0.37, 0.5, 0.999] {
        assert_eq!(Filter::Box.sample_in((u, u), (-0.5, -7.5), (0.5, 2.5)), ((u - 0.5, u - 0.5), 1.0));
    }
    assert_eq!(Filter::Box.sample((0.0, 1.0)), ((-0.5, 0.5), 1.0));
    // Bounds that miss the support give the pixel square.
    assert_eq!(GAUSS.sample_in((0.25, 0.75), (3.0, -1.0), (4.0, 1.0)).0 .0, -0.25);
}

#[test]
fn the_gaussians_constants_are_its_cut() {
    assert_eq!(GAUSSIAN_BIAS, (-8.0f64).exp());
    assert!((ERF_AT_CUT - libm::erf(2.0 * std::f64::consts::SQRT_2)).abs() <= f64::EPSILON);
}

const MITCHELL: Filter = Filter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 };
const LANCZOS: Filter = Filter::Lanczos { lobes: 3 };
const SIGNED: [Filter; 5] = [MITCHELL, Filter::CatmullRom, LANCZOS, Filter::Lanczos { lobes: 2 }, Filter::Mitchell { b: 0.8, c: 0.1 }];

#[test]
fn signed_weights_are_mitsubas_formulas() {
    // Mitchell-Netravali, B = C = 1/3: (6 - 2B) / 6 = 8/9 at 0; at 1 both
    // pieces give (12 - 9B - 6C - 18 + 12B + 6C + 6 - 2B) / 6 = B / 6 = 1/18;
    // at 1.5 ((-7/3) 27/8 + 12 (9/4) - 20 (3/2) + 32/3) / 6 = -5/144.
    let close = |a: f64, b: f64| (a - b).abs() < 1e-14;
    assert!(close(MITCHELL.weight(0.0), 8.0 / 9.0));
    assert!(close(MITCHELL.weight(1.0), 1.0 / 18.0) && (MITCHELL.weight(1.0 - 1e-12) - 1.0 / 18.0).abs() < 1e-11);
    assert!(close(MITCHELL.weight(-1.5), -5.0 / 144.0) && close(MITCHELL.weight(1.5), -5.0 / 144.0));
    assert_eq!((MITCHELL.weight(2.0), MITCHELL.weight(-2.5)), (0.0, 0.0));
    // Another B, C: at 0.5, (12 - 9B - 6C) / 8 + (-18 + 12B + 6C) / 4 + 6 - 2B, over 6.
    let (b, c) = (0.8, 0.1);
    let f = Filter::Mitchell { b, c };
    let at_half = ((12.0 - 9.0 * b - 6.0 * c) / 8.0 + (-18.0 + 12.0 * b + 6.0 * c) / 4.0 + 6.0 - 2.0 * b) / 6.0;
    assert!(close(f.weight(0.5), at_half));
    // Catmull-Rom (B = 0, C = 1/2): 1 at 0, 0 at 1, (9/8 - 15/4 + 6) / 6 = 9/16
    // at 1/2, (-3 (27/8) + 15 (9/4) - 24 (3/2) + 12) / 6 = -1/16 at 3/2.
    let cr = Filter::CatmullRom;
    assert!(close(cr.weight(0.0), 1.0) && close(cr.weight(1.0), 0.0));
    assert!(close(cr.weight(0.5), 9.0 / 16.0) && close(cr.weight(-1.5), -1.0 / 16.0));
    // Lanczos, 3 lobes: sin(pi x) sin(pi x / 3) / (pi^2 x^2 / 3): 1 at 0,
    // 6 / pi^2 at 1/2, -4 / (3 pi^2) at 3/2, 0 at the whole pixels and beyond 3.
    let pi2 = std::f64::consts::PI * std::f64::consts::PI;
    assert_eq!(LANCZOS.weight(0.0), 1.0);
    assert!(close(LANCZOS.weight(0.5), 6.0 / pi2) && close(LANCZOS.weight(-1.5), -4.0 / (3.0 * pi2)));
    assert!(LANCZOS.weight(1.0).abs() < 1e-15 && LANCZOS.weight(2.0).abs() < 1e-15);
    assert!((LANCZOS.weight(1e-6) - 1.0).abs() < 1e-11 && LANCZOS.weight(3.5) == 0.0);
    // Two lobes at 1/2: sin(pi/2) sin(pi/4) / (pi^2 / 8).
    assert!(close(Filter::Lanczos { lobes: 2 }.weight(0.5), std::f64::consts::FRAC_1_SQRT_2 * 8.0 / pi2));
}

#[test]
fn signed_filters_are_normalised_as_mitsubas() {
    // The Mitchell-Netravali family has area 1 for every B, C (0.5 + (C/2 - B/4) / 6
    // below 1 on each side, (B/4 - C/2) / 6 between 1 and 2); the sinc's area
    // is left to quadrature: Mitsuba divides by the sum of weights, so the
    // area scales nothing.
    for f in [MITCHELL, Filter::CatmullRom, Filter::Mitchell { b: 0.8, c: 0.1 }] {
        assert!((f.cumulative(2.0) - 1.0).abs() < 1e-13, "{f:?}: {}", f.cumulative(2.0));
        assert!((f.cumulative(0.0) - 0.5).abs() < 1e-13 && (f.cumulative(1.0) - (1.0 - f.cumulative(-1.0))).abs() < 1e-13);
    }
    for f in SIGNED {
        let r = f.radius();
        assert_eq!(f.cumulative(-r), 0.0);
        for x in [-0.9 * r, -1.3, -0.3, 0.0, 0.2, 1.0, 1.7, r] {
            let exact = integral(|t| f.weight(t), -r, x);
            assert!((f.cumulative(x) - exact).abs() < 1e-8, "{f:?} at {x}: {} vs {exact}", f.cumulative(x));
        }
        let table = SignedTable::new(f);
        for x in [-0.77 * r, -0.5, 0.013, 0.5, 1.5, r] {
            assert!((table.signed_at(x) - f.cumulative(x)).abs() < 1e-13, "{f:?} at {x}");
        }
    }
}

#[test]
fn signed_sampling_gives_the_filter_weighted_mean() {
    // For a constant image the mean weight is 1, for a ramp g the mean of
    // g(x) times the weight the f-weighted mean of g over the interval
    // (by quadrature), on each axis and in 2D, to 1e-4 at 200 000 (1D) and
    // 1e-3 at 40 000 (2D) stratified samples (the Lanczos sinc's 1D mean is
    // off by 1.2e-4 at 20 000: stratification, not bias).
    let g = |x: f64| 0.3 + 0.7 * x;
    for f in SIGNED {
        let sampler = FilterSampler::new(f);
        let table = sampler.table.as_ref().unwrap();
        let r = f.radius();
        for (lo, hi) in [(-f64::INFINITY, f64::INFINITY), (-0.5, f64::INFINITY), (-0.5, 0.5), (-1.5, 0.6), (-r, 1.25)] {
            let (a, b) = (f64::max(lo, -r), f64::min(hi, r));
            let mass = integral(|t| f.weight(t), a, b);
            let ramp = integral(|t| g(t) * f.weight(t), a, b) / mass;
            let bound = 4.0 * integral(|t| f.weight(t).abs(), a, b) / mass;
            let n = 200_000;
            let xs: Vec<(f64, f64)> = (0..n).map(|i| table.sample_axis((i as f64 + 0.5) / n as f64, lo, hi)).collect();
            assert!(xs.iter().all(|&(x, w)| x >= a && x <= b && w.abs() <= bound), "{f:?} [{lo}, {hi}]");
            let m0 = xs.iter().map(|(_, w)| w).sum::<f64>() / n as f64;
            let m1 = xs.iter().map(|(x, w)| g(*x) * w).sum::<f64>() / n as f64;
            assert!((m0 - 1.0).abs() < 1e-4, "{f:?} [{lo}, {hi}]: weights average {m0}");
            assert!((m1 - ramp).abs() < 1e-4, "{f:?} [{lo}, {hi}]: {m1} vs {ramp}");
            // 2D: a Fibonacci-like lattice of 40 000 points (both projections
            // well stratified), the ramp g(x) + g(y) / 2.
            let (mut w2, mut g2) = (0.0, 0.0);
            for i in 0..40_000 {
                let t = i as f64 + 0.5;
                let u = (t / 40_000.0, (t * 0.618_033_988_749_894_8).fract());
                let ((x, y), w) = sampler.sample_in(u, (lo, -f64::INFINITY), (hi, 0.5));
                assert!(w.is_finite());
                w2 += w;
                g2 += w * (g(x) + 0.5 * g(y));
            }
            let ramp_y = integral(|t| g(t) * f.weight(t), -r, 0.5) / integral(|t| f.weight(t), -r, 0.5);
            assert!((w2 / 40_000.0 - 1.0).abs() < 1e-3, "{f:?} [{lo}, {hi}] 2D: {}", w2 / 40_000.0);
            assert!((g2 / 40_000.0 - ramp - 0.5 * ramp_y).abs() < 1e-3, "{f:?} [{lo}, {hi}] 2D ramp: {}", g2 / 40_000.0);
        }
    }
}

#[test]
fn signed_sampling_stays_finite() {
    // Outside the bounds: the pixel square. A filter whose weight over the
    // interval is not positive (B = 0, C = 8: a negative lobe of area 1.3
    // beyond 1 pixel) falls back to it too, every weight finite.
    let table = SignedTable::new(LANCZOS);
    assert_eq!(table.sample_axis(0.25, 4.0, 5.0), (-0.25, 1.0));
    let wild = SignedTable::new(Filter::Mitchell { b: 0.0, c: 8.0 });
    assert!(wild.signed_at(2.0) - wild.signed_at(0.9) < 0.0);
    assert_eq!(wild.sample_axis(0.75, 0.9, f64::INFINITY), (0.25, 1.0));
    for i in 0..1000 {
        let u = (i as f64 + 0.5) / 1000.0;
        for (lo, hi) in [(-9.0, 9.0), (-0.5, 2.0), (-0.5, 0.5), (0.0, 0.01), (1.999, 2.5)] {
            for t in [&table, &wild] {
                let (x, w) = t.sample_axis(u, lo, hi);
                assert!(x.is_finite() && w.is_finite(), "{:?} [{lo}, {hi}] u {u}: {x} {w}", t.filter);
            }
        }
    }
}

#[test]
fn the_sampler_keeps_the_unsigned_filters() {
    for f in [Filter::Box, Filter::Tent, GAUSS] {
        let sampler = FilterSampler::new(f);
        assert!(sampler.table.is_none() && sampler.filter() == f);
        for (u, lo, hi) in [((0.1, 0.8), (-0.5, -1.0), (2.0, 0.7)), ((0.5, 0.33), (-9.0, -9.0), (9.0, 9.0))] {
            assert_eq!(sampler.sample_in(u, lo, hi), f.sample_in(u, lo, hi));
        }
    }
    // Filter::sample_in of a signed filter is its sampler's.
    assert_eq!(
        LANCZOS.sample_in((0.3, 0.6), (-1.0, -2.0), (4.0, 0.5)),
        FilterSampler::new(LANCZOS).sample_in((0.3, 0.6), (-1.0, -2.0), (4.0, 0.5))
    );
}

#[test]
fn names_parse() {
    assert_eq!("tent".parse::<Filter>(), Ok(Filter::Tent));
    assert_eq!("gaussian".parse::<Filter>(), Ok(GAUSS));
    assert_eq!("mitchell".parse::<Filter>(), Ok(MITCHELL));
    assert_eq!("catmullrom".parse::<Filter>(), Ok(Filter::CatmullRom));
    assert_eq!("lanczos".parse::<Filter>(), Ok(LANCZOS));
    assert_eq!("mitchell(B=0.5, C=0.25)".parse::<Filter>(), Ok(Filter::Mitchell { b: 0.5, c: 0.25 }));
    assert_eq!("mitchell(C=0)".parse::<Filter>(), Ok(Filter::Mitchell { b: 1.0 / 3.0, c: 0.0 }));
    assert_eq!("lanczos(lobes=2)".parse::<Filter>(), Ok(Filter::Lanczos { lobes: 2 }));
    for f in [
        Filter::Box,
        Filter::Tent,
        GAUSS,
        MITCHELL,
        Filter::CatmullRom,
        LANCZOS,
        Filter::Mitchell { b: 0.1, c: 0.45 },
        Filter::Lanczos { lobes: 5 },
    ] {
        assert_eq!(f.to_string().parse::<Filter>(), Ok(f), "{f}");
    }
    assert_eq!(Filter::Lanczos { lobes: 5 }.to_string(), "lanczos(lobes=5)");
    assert_eq!(
        "sinc".parse::<Filter>(),
        Err("unknown filter \"sinc\" (filters: box, tent, gaussian, mitchell, catmullrom, lanczos)".into())
    );
    assert_eq!(
        "lanczos(lobes=0)".parse::<Filter>(),
        Err("filter \"lanczos(lobes=0)\": lobes must be a whole number from 1 to 32, got 0".into())
    );
    assert_eq!("mitchell(B=nan)".parse::<Filter>(), Err("filter \"mitchell(B=nan)\": B must be a finite number, got \"nan\"".into()));
    assert_eq!("tent(radius=2)".parse::<Filter>(), Err("filter \"tent(radius=2)\": \"tent\" takes no parameters".into()));
    assert_eq!(
        "lanczos(taps=2)".parse::<Filter>(),
        Err("filter \"lanczos(taps=2)\": unknown parameter \"taps\" (\"lanczos\" takes lobes)".into())
    );
    // A near miss gets the same "did you mean" as every other unknown name.
    assert_eq!(
        "lanczos(lobe=2)".parse::<Filter>(),
        Err("filter \"lanczos(lobe=2)\": unknown parameter \"lobe\" (did you mean 'lobes'? \"lanczos\" takes lobes)".into())
    );
}

/// The box's inlined axis ([`box_axis`]) is the general route's arithmetic:
/// `W` at both bounds, `W^-1` of the interpolated weight, clamped, for
/// interior pixels (bounds past the support), border pixels (a bound inside
/// it) and pixels outside the bounds, bit for bit.
#[test]
fn the_inlined_box_is_the_general_route_bit_for_bit() {
    let b = Filter::Box;
    let general = |u: f64, lo: f64, hi: f64| -> f64 {
        let (a, c) = (lo.max(-0.5), hi.min(0.5));
        if !(a < c) {
            return u - 0.5;
        }
        let (wa, wc) = (b.cumulative(a), b.cumulative(c));
        b.inverse_cumulative(wa + u * (wc - wa), a, c)
    };
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let bounds = [f64::NEG_INFINITY, -3.0, -0.5, -0.4999999999999999, -0.3, 0.0, 0.1, 0.5, 2.0, f64::INFINITY];
    for &lo in &bounds {
        for &hi in &bounds {
            for _ in 0..200 {
                let u = next();
                assert_eq!(box_axis(u, lo, hi).0.to_bits(), general(u, lo, hi).to_bits(), "u {u} lo {lo} hi {hi}");
                assert_eq!(box_axis(u, lo, hi).1, 1.0);
            }
            for u in [0.0, 0.5, 1.0 - f64::EPSILON / 2.0] {
                assert_eq!(box_axis(u, lo, hi).0.to_bits(), general(u, lo, hi).to_bits(), "u {u} lo {lo} hi {hi}");
            }
        }
    }
}
