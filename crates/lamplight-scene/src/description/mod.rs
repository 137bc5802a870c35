//! The scene description: plain data that a scene file (or, later, a Python
//! dict) deserializes into, and that [`crate::build`] turns into a core scene.
//!
//! The types mirror the file format documented in `docs/scene-format.md` key by
//! key. Every optional key is an `Option` so that defaults live in one place (the
//! builder) and command-line flags can tell "not given" from "given". Tables
//! that the builder may still reject keep their source position ([`Located`]).
//! Unknown keys are errors (`deny_unknown_fields`).

use std::collections::BTreeMap;

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;

mod located;
mod node;

pub use located::Located;
pub use node::{ClipDesc, Node, Rotate, NODE_KEYS};

/// A whole scene file.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneDescription {
    /// Ambient radiance `La` (default 0).
    pub ambient: Option<Triple>,
    /// Radiance of rays that hit nothing (default 0).
    pub background: Option<Triple>,
    /// Image and integrator settings.
    pub render: Option<Located<RenderSettings>>,
    /// The camera (required).
    pub camera: Option<Located<CameraDesc>>,
    /// Materials by name.
    #[serde(default)]
    pub materials: BTreeMap<String, Located<MaterialDesc>>,
    /// Mesh assets by name: loaded once, placed by `mesh` nodes.
    #[serde(default)]
    pub meshes: BTreeMap<String, Located<MeshDesc>>,
    /// Named node trees, placed by `instance` nodes.
    #[serde(default)]
    pub definitions: BTreeMap<String, Located<Node>>,
    /// The scene's top-level nodes, in order.
    #[serde(default)]
    pub objects: Vec<Located<Node>>,
}

/// `[render]`: image size, sampling and integrator.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RenderSettings {
    /// Image width in pixels (default 640).
    pub width: Option<u32>,
    /// Image height in pixels (default 360).
    pub height: Option<u32>,
    /// Samples per pixel (default 1).
    pub spp: Option<u32>,
    /// Depth limit, camera ray = 1 (default 5).
    pub max_depth: Option<u32>,
    /// Secondary rays of weight at or below this are not traced (default 0).
    pub min_weight: Option<f64>,
    /// Seed of the per-sample random numbers (default 0).
    pub seed: Option<u64>,
    /// Integrator name (default `"whitted"`).
    pub integrator: Option<String>,
}

/// `[camera]`: either `eye` + `look_at` + `up` + `vfov`/`hfov`, or the raw window
/// form `eye` + `window_center` + `right` + `up` (+ `pixel_offset`, `fit`).
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Eye position.
    pub eye: Option<[f64; 3]>,
    /// Point looked at (look-at form).
    pub look_at: Option<[f64; 3]>,
    /// Sky direction (look-at form, default +y) or the window's half-height vector (window form).
    pub up: Option<[f64; 3]>,
    /// Full vertical field of view, degrees.
    pub vfov: Option<f64>,
    /// Full horizontal field of view, degrees.
    pub hfov: Option<f64>,
    /// Centre of the image window (window form).
    pub window_center: Option<[f64; 3]>,
    /// Half-width vector of the window (window form).
    pub right: Option<[f64; 3]>,
    /// Where in a pixel its sample goes, 0..1 (default 0.5).
    pub pixel_offset: Option<f64>,
    /// Window form: `"none"` (vectors as written), `"width"` (written for a square
    /// image; `up` is divided by the aspect) or `"height"` (`right` multiplied by it).
    pub fit: Option<String>,
}

/// A material: the lecture's Phong/Blinn terms, mirror and refraction.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesc {
    /// Surface colour (default 0.5).
    pub color: Option<Triple>,
    /// A 3D checker instead of `color`.
    pub checker: Option<CheckerDesc>,
    /// Ambient factor (default 0.1).
    pub ka: Option<Triple>,
    /// Diffuse factor (default 0.9).
    pub kd: Option<Triple>,
    /// Specular (Blinn) factor (default 0).
    pub ks: Option<Triple>,
    /// Blinn exponent (default 1).
    pub shininess: Option<f64>,
    /// Emitted radiance (default 0).
    pub emission: Option<Triple>,
    /// Mirror reflection (default none).
    pub reflection: Option<ReflectionDesc>,
    /// Refraction (default none).
    pub refraction: Option<RefractionDesc>,
    /// Fraction of light a shadow ray keeps crossing this surface (default 0).
    pub shadow_transmittance: Option<Triple>,
    /// GGX roughness of Fresnel glass and conductors in the path tracer (default 0: smooth).
    pub roughness: Option<f64>,
}

/// `checker = { size, even, odd, offset }`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CheckerDesc {
    /// Cube edge length.
    pub size: f64,
    /// Colour of even cells.
    pub even: Triple,
    /// Colour of odd cells.
    pub odd: Triple,
    /// Added to the point before the cells are counted (default 0).
    pub offset: Option<[f64; 3]>,
}

/// `reflection = { type = "constant" | "dielectric" | "conductor", ... }`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ReflectionDesc {
    /// A constant weight.
    Constant {
        /// Weight per channel.
        weight: Triple,
    },
    /// Dielectric Fresnel reflectance rescaled to `min + (max - min) F`.
    Dielectric {
        /// Index of refraction.
        ior: f64,
        /// Reflectance at `F = 0` (default 0).
        min: Option<f64>,
        /// Reflectance at `F = 1` (default 1).
        max: Option<f64>,
    },
    /// Conductor Fresnel reflectance: a named metal or `eta` and `k`.
    Conductor {
        /// `"gold"`, `"silver"`, `"copper"` or `"aluminium"`.
        metal: Option<String>,
        /// Real part of the index.
        eta: Option<Triple>,
        /// Extinction coefficient.
        k: Option<Triple>,
    },
}

/// `refraction = { type = "fresnel" | "constant", ior, weight }`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum RefractionDesc {
    /// Weight `1 - F`.
    Fresnel {
        /// Index of refraction inside.
        ior: f64,
    },
    /// A constant weight.
    Constant {
        /// Index of refraction inside.
        ior: f64,
        /// Weight per channel.
        weight: Triple,
    },
}

/// `[meshes.NAME]`: a mesh file (relative to the scene file) or inline data.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MeshDesc {
    /// OBJ, PLY or glTF file, relative to the scene file.
    pub file: Option<String>,
    /// Inline vertex positions.
    pub positions: Option<Vec<[f64; 3]>>,
    /// Inline triangles (vertex indices from 0).
    pub indices: Option<Vec<[u32; 3]>>,
    /// Inline per-vertex normals.
    pub normals: Option<Vec<[f64; 3]>>,
}

/// A number or an `[a, b, c]` array (a number `v` means `[v, v, v]`): colours,
/// weights and scale factors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triple(pub [f64; 3]);

impl<'de> Deserialize<'de> for Triple {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Triple, D::Error> {
        struct TripleVisitor;
        impl<'de> Visitor<'de> for TripleVisitor {
            type Value = Triple;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a number or an array of 3 numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Triple, E> {
                Ok(Triple([v; 3]))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Triple, E> {
                Ok(Triple([v as f64; 3]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Triple, E> {
                Ok(Triple([v as f64; 3]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Triple, A::Error> {
                <[f64; 3]>::deserialize(de::value::SeqAccessDeserializer::new(seq)).map(Triple)
            }
        }
        deserializer.deserialize_any(TripleVisitor)
    }
}
