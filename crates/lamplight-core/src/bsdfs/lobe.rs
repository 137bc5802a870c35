//! What every lobe does, stated once: the [`Scatter`] trait each lobe type
//! implements in its own file, and the `lobes!` registry that makes [`Lobe`]
//! and its dispatch from one line per lobe (in `bsdfs/mod.rs`). A new lobe is
//! its file with `impl Scatter` and one registry line; no match arm elsewhere
//! names it.
//!
//! The dispatch is a plain `match` over the enum, as written out by hand
//! before: each arm calls the lobe's own method, and an arm of a delta lobe in
//! [`Lobe::add_f`] and [`Lobe::add_pdf`] is empty (`Scatter::DELTA` is a
//! constant), so the path tracer's inner loop is the same code.

use super::Lobe;
use crate::math::{Rgb, Vec3};

/// A direction sampled from one lobe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sampled {
    /// A direction of a lobe with a value and a density: the BSDF weighs it
    /// with the mixture of all its non-delta lobes.
    Smooth(Vec3),
    /// A direction of a delta lobe, with its weight `f cos / pdf` (including
    /// the lobe's own branch probability) and the relative index `n_t / n_i`
    /// it crossed (1 for a reflection).
    Delta {
        /// Incident direction, local frame.
        wi: Vec3,
        /// `f cos / pdf` of the branch taken.
        weight: Rgb,
        /// Relative index of a refraction, 1 for a reflection.
        eta: f64,
    },
}

/// One scattering lobe: the physics of one file of `bsdfs/`, in the local
/// shading frame (`z` the normal on the side the ray arrived from).
pub trait Scatter: Copy + Into<Lobe> {
    /// True for a lobe that scatters into single directions only: it has no
    /// value or density a light sample could meet, and [`Scatter::sample`]
    /// returns [`Sampled::Delta`].
    const DELTA: bool;

    /// Per-channel upper bound of the reflectance (albedo) over all angles.
    fn bound(&self) -> Rgb;

    /// The lobe scaled by `s` (each channel at most 1), so that a BSDF's lobes
    /// reflect at most what arrives. The default keeps the lobe as it is: a
    /// lobe whose bound is at most 1 and whose material uses it alone is never
    /// scaled.
    fn scaled(self, _s: Rgb) -> Lobe {
        self.into()
    }

    /// The value `f(wo, wi)` of a non-delta lobe (0 for a delta lobe).
    fn f(&self, _wo: Vec3, _wi: Vec3) -> Rgb {
        Rgb::ZERO
    }

    /// The solid-angle density with which [`Scatter::sample`] returns `wi` (0 for a delta lobe).
    fn pdf(&self, _wo: Vec3, _wi: Vec3) -> f64 {
        0.0
    }

    /// A direction for outgoing `wo` (`wo.z > 0`): `u_choice` in `[0, 1)` picks
    /// among the lobe's branches (reflect or refract, coat or base), `u` the
    /// direction. `None` when sampling failed.
    fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled>;

    /// The relative index `n_t / n_i` along a direction `wi` this non-delta
    /// lobe sampled: 1 unless the lobe refracts into `wi`.
    fn eta_towards(&self, _wi: Vec3) -> f64 {
        1.0
    }

    /// True when the lobe is anisotropic: its local `x` axis must be the
    /// surface's tangent `dp/du` ([`super::Frame::from_tangent`]), not any
    /// direction around the normal.
    fn needs_tangent(&self) -> bool {
        false
    }
}

/// The registry: `lobes! { /// doc \n Variant(Type), ... }` makes the enum
/// [`Lobe`] with one variant per lobe type, `From<Type> for Lobe`, and the
/// methods that dispatch to each type's [`Scatter`] implementation.
macro_rules! lobes {
    ($($(#[$doc:meta])* $variant:ident($ty:ty),)*) => {
        /// One lobe of a [`Bsdf`]: one variant per lobe type of `bsdfs/`, each
        /// implementing [`Scatter`] in its own file.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum Lobe {
            $($(#[$doc])* $variant($ty),)*
        }

        $(
            impl From<$ty> for Lobe {
                #[inline]
                fn from(lobe: $ty) -> Lobe {
                    Lobe::$variant(lobe)
                }
            }
        )*

        impl Lobe {
            /// True for lobes that scatter into single directions ([`Scatter::DELTA`]).
            #[inline]
            pub fn is_delta(&self) -> bool {
                match self {
                    $(Lobe::$variant(_) => <$ty as Scatter>::DELTA,)*
                }
            }

            /// Per-channel upper bound of the reflectance (albedo) over all angles.
            #[inline]
            pub fn bound(&self) -> Rgb {
                match self {
                    $(Lobe::$variant(lobe) => Scatter::bound(lobe),)*
                }
            }

            /// The lobe scaled by `s` ([`Scatter::scaled`]).
            fn scaled(self, s: Rgb) -> Lobe {
                match self {
                    $(Lobe::$variant(lobe) => Scatter::scaled(lobe, s),)*
                }
            }

            /// Adds the value of a non-delta lobe to `sum` (a delta lobe adds nothing).
            #[inline(always)]
            fn add_f(&self, sum: &mut Rgb, wo: Vec3, wi: Vec3) {
                match self {
                    $(Lobe::$variant(lobe) => {
                        if !<$ty as Scatter>::DELTA {
                            *sum += Scatter::f(lobe, wo, wi);
                        }
                    })*
                }
            }

            /// Adds `p` times the density of a non-delta lobe to `pdf` (a delta lobe adds nothing).
            #[inline(always)]
            fn add_pdf(&self, pdf: &mut f64, p: f64, wo: Vec3, wi: Vec3) {
                match self {
                    $(Lobe::$variant(lobe) => {
                        if !<$ty as Scatter>::DELTA {
                            *pdf += p * Scatter::pdf(lobe, wo, wi);
                        }
                    })*
                }
            }

            /// A direction from this lobe ([`Scatter::sample`]).
            #[inline(always)]
            fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
                match self {
                    $(Lobe::$variant(lobe) => Scatter::sample(lobe, wo, u_choice, u),)*
                }
            }

            /// Whether the lobe's local `x` must be the surface's tangent ([`Scatter::needs_tangent`]).
            #[inline]
            fn needs_tangent(&self) -> bool {
                match self {
                    $(Lobe::$variant(lobe) => Scatter::needs_tangent(lobe),)*
                }
            }

            /// The relative index along a sampled `wi` ([`Scatter::eta_towards`]).
            #[inline]
            fn eta_towards(&self, wi: Vec3) -> f64 {
                match self {
                    $(Lobe::$variant(lobe) => Scatter::eta_towards(lobe, wi),)*
                }
            }
        }
    };
}
pub(super) use lobes;
