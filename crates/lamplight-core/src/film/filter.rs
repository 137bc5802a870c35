//! Pixel reconstruction filters, applied by filter importance sampling: each
//! sample's film position is drawn from the filter's own distribution around the
//! pixel centre and the sample gets weight 1 (Ernst et al. 2006). The pixel value
//! is then a plain average of its own samples, a fixed-order sum that no other
//! pixel touches, so images stay identical for any thread count.

use std::f64::consts::PI;

/// A reconstruction filter.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Filter {
    /// The pixel square (width 1).
    #[default]
    Box,
    /// A Gaussian of standard deviation `sigma` pixels (Mitsuba's default is 0.5).
    Gaussian {
        /// Standard deviation in pixels.
        sigma: f64,
    },
}

impl Filter {
    /// The offset from the pixel centre for a uniform point `u` (Box-Muller for the Gaussian).
    pub fn sample(&self, u: (f64, f64)) -> (f64, f64) {
        match *self {
            Filter::Box => (u.0 - 0.5, u.1 - 0.5),
            Filter::Gaussian { sigma } => {
                let r = sigma * (-2.0 * (1.0 - u.0).ln()).sqrt();
                let phi = 2.0 * PI * u.1;
                (r * phi.cos(), r * phi.sin())
            }
        }
    }
}

impl std::str::FromStr for Filter {
    type Err = String;

    fn from_str(s: &str) -> Result<Filter, String> {
        match s {
            "box" => Ok(Filter::Box),
            "gaussian" => Ok(Filter::Gaussian { sigma: 0.5 }),
            _ => Err(format!("unknown filter '{s}' (box, gaussian)")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_samples_have_the_right_spread() {
        let f = Filter::Gaussian { sigma: 0.5 };
        let n = 200;
        let mut var = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (x, y) = f.sample(((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64));
                var += x * x + y * y;
            }
        }
        var /= (2 * n * n) as f64;
        assert!((var - 0.25).abs() < 0.01, "{var}");
        assert_eq!(Filter::Box.sample((0.0, 1.0)), (-0.5, 0.5));
    }
}
