//! [`Node`]: one entry of the scene tree, a group, an instance, a shape or a light.
//!
//! A node is one flat table whose `type` says what it is; which of the keys below
//! a type takes is checked by the builder (so that a misplaced key is reported
//! with the list of keys that type does take, and a Python dict maps onto the same
//! struct). Transforms (`translate`, `rotate`, `scale`, `matrix`) are allowed on
//! groups and instances and apply to everything under them.

use serde::Deserialize;

use super::{Located, Triple};

/// One node of the scene tree; see the module documentation and `docs/scene-format.md`.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Node {
    /// What the node is: `group`, `instance`, a shape type or a light type.
    #[serde(rename = "type")]
    pub kind: String,
    /// Name (shapes: referenced by a light's `own_object`).
    pub name: Option<String>,
    /// Material name (shapes; on groups and instances the default for everything below).
    pub material: Option<String>,
    /// Translation.
    pub translate: Option<[f64; 3]>,
    /// Rotation.
    pub rotate: Option<Rotate>,
    /// Scale factor or per-axis factors.
    pub scale: Option<Triple>,
    /// A 4x4 affine matrix, rows (applied before the other transforms).
    pub matrix: Option<[[f64; 4]; 4]>,
    /// Children of a group.
    pub children: Option<Vec<Located<Node>>>,
    /// The definition an instance places.
    pub of: Option<String>,
    /// Centre (sphere, ellipsoid, disk, torus, hyperboloid).
    pub center: Option<[f64; 3]>,
    /// Radius (sphere, cylinder, cone, disk).
    pub radius: Option<f64>,
    /// Semi-axes (ellipsoid).
    pub radii: Option<[f64; 3]>,
    /// Start of the axis (cylinder).
    pub from: Option<[f64; 3]>,
    /// End of the axis (cylinder).
    pub to: Option<[f64; 3]>,
    /// Close the ends with disks (cylinder, cone).
    pub caps: Option<bool>,
    /// Apex (cone, paraboloid).
    pub apex: Option<[f64; 3]>,
    /// Centre of the base (cone).
    pub base: Option<[f64; 3]>,
    /// Axis direction (infinite cylinder and cone, paraboloid, hyperboloid, torus).
    pub axis: Option<[f64; 3]>,
    /// Focal length (paraboloid).
    pub focal_length: Option<f64>,
    /// Depth of the cup (paraboloid; none: infinite).
    pub depth: Option<f64>,
    /// Half opening angle, degrees (infinite cone).
    pub half_angle: Option<f64>,
    /// Radial semi-axis (hyperboloid).
    pub a: Option<f64>,
    /// Axial semi-axis (hyperboloid).
    pub c: Option<f64>,
    /// 1 or 2 sheets (hyperboloid).
    pub sheets: Option<u8>,
    /// A point (plane, infinite cylinder).
    pub point: Option<[f64; 3]>,
    /// Normal (plane, disk).
    pub normal: Option<[f64; 3]>,
    /// Corner (rectangle).
    pub corner: Option<[f64; 3]>,
    /// First edge (rectangle).
    pub edge_u: Option<[f64; 3]>,
    /// Second edge (rectangle).
    pub edge_v: Option<[f64; 3]>,
    /// Low corner (box, implicit bounds).
    pub min: Option<[f64; 3]>,
    /// High corner (box, implicit bounds).
    pub max: Option<[f64; 3]>,
    /// The three corners (triangle).
    pub vertices: Option<[[f64; 3]; 3]>,
    /// Mesh asset name (mesh).
    pub mesh: Option<String>,
    /// Ring radius (torus).
    pub major_radius: Option<f64>,
    /// Tube radius (torus).
    pub minor_radius: Option<f64>,
    /// `f(x, y, z)` (implicit).
    pub expression: Option<String>,
    /// Lipschitz bound of `f` (implicit).
    pub lipschitz: Option<f64>,
    /// Root tolerance, a distance (implicit).
    pub tolerance: Option<f64>,
    /// Sample cap per ray (implicit).
    pub max_steps: Option<u32>,
    /// Clip regions (quadrics).
    pub clip: Option<Vec<ClipDesc>>,
    /// 4x4 symmetric matrix, rows (quadric).
    pub coefficients: Option<[[f64; 4]; 4]>,
    /// Position (point light).
    pub position: Option<[f64; 3]>,
    /// Intensity (point light).
    pub intensity: Option<Triple>,
    /// `"inverse_square"` or `"none"` (point light).
    pub falloff: Option<String>,
    /// Direction the light travels (directional light).
    pub direction: Option<[f64; 3]>,
    /// Radiance (directional light).
    pub radiance: Option<Triple>,
    /// Name of the shape that must not shadow this light (point light).
    pub own_object: Option<String>,
}

/// Every key a node may have, in the order of [`Node::present_keys`].
pub const NODE_KEYS: &[&str] = &[
    "type",
    "name",
    "material",
    "translate",
    "rotate",
    "scale",
    "matrix",
    "children",
    "of",
    "center",
    "radius",
    "radii",
    "from",
    "to",
    "caps",
    "apex",
    "base",
    "axis",
    "focal_length",
    "depth",
    "half_angle",
    "a",
    "c",
    "sheets",
    "point",
    "normal",
    "corner",
    "edge_u",
    "edge_v",
    "min",
    "max",
    "vertices",
    "mesh",
    "major_radius",
    "minor_radius",
    "expression",
    "lipschitz",
    "tolerance",
    "max_steps",
    "clip",
    "coefficients",
    "position",
    "intensity",
    "falloff",
    "direction",
    "radiance",
    "own_object",
];

impl Node {
    /// The keys this node has (besides `type`), in [`NODE_KEYS`] order.
    pub fn present_keys(&self) -> Vec<&'static str> {
        let flags = [
            true,
            self.name.is_some(),
            self.material.is_some(),
            self.translate.is_some(),
            self.rotate.is_some(),
            self.scale.is_some(),
            self.matrix.is_some(),
            self.children.is_some(),
            self.of.is_some(),
            self.center.is_some(),
            self.radius.is_some(),
            self.radii.is_some(),
            self.from.is_some(),
            self.to.is_some(),
            self.caps.is_some(),
            self.apex.is_some(),
            self.base.is_some(),
            self.axis.is_some(),
            self.focal_length.is_some(),
            self.depth.is_some(),
            self.half_angle.is_some(),
            self.a.is_some(),
            self.c.is_some(),
            self.sheets.is_some(),
            self.point.is_some(),
            self.normal.is_some(),
            self.corner.is_some(),
            self.edge_u.is_some(),
            self.edge_v.is_some(),
            self.min.is_some(),
            self.max.is_some(),
            self.vertices.is_some(),
            self.mesh.is_some(),
            self.major_radius.is_some(),
            self.minor_radius.is_some(),
            self.expression.is_some(),
            self.lipschitz.is_some(),
            self.tolerance.is_some(),
            self.max_steps.is_some(),
            self.clip.is_some(),
            self.coefficients.is_some(),
            self.position.is_some(),
            self.intensity.is_some(),
            self.falloff.is_some(),
            self.direction.is_some(),
            self.radiance.is_some(),
            self.own_object.is_some(),
        ];
        NODE_KEYS.iter().zip(flags).skip(1).filter(|(_, f)| *f).map(|(k, _)| *k).collect()
    }
}

/// `rotate = { axis = [x, y, z], degrees = a }` or `rotate = { x = a, y = b, z = c }`
/// (degrees about the coordinate axes, applied x first, then y, then z).
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Rotate {
    /// Rotation axis (axis-angle form).
    pub axis: Option<[f64; 3]>,
    /// Angle in degrees, counter-clockwise looking down the axis (axis-angle form).
    pub degrees: Option<f64>,
    /// Degrees about x.
    pub x: Option<f64>,
    /// Degrees about y.
    pub y: Option<f64>,
    /// Degrees about z.
    pub z: Option<f64>,
}

/// One clip region of a quadric.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ClipDesc {
    /// Keeps `normal . (p - point) <= 0`.
    HalfSpace {
        /// A point on the plane.
        point: [f64; 3],
        /// Points out of the kept side.
        normal: [f64; 3],
    },
    /// Keeps `[p, 1] M [p, 1]^T <= 0`.
    Inside {
        /// 4x4 matrix, rows.
        coefficients: [[f64; 4]; 4],
    },
}
