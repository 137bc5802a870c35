//! The registry of kinds: every shape, light, material, texture and camera a
//! scene may name by `type`, each listed once, with its parameter table and
//! builder. Integrators are listed by the core's own registry
//! (`lamplight_core::integrators::INTEGRATORS`), which `[render] integrator`,
//! `--integrator` and Python's `integrator=` all read.
//!
//! A kind is one file (its struct, its `KIND` with the parameter table, its
//! tests) and one line here. The builder ([`crate::instantiate`]) finds kinds only
//! through these lists (`Kind::find`), the reference in `docs/scene-format.md` is generated
//! from them ([`reference()`]), and the error tests feed every kind a mistyped key.
//! Kinds that need this crate (an implicit surface's expression parser) live in
//! `instantiate/`; the structural node types (`group`, `instance`, `mesh`) are the
//! builder's own and are documented by [`STRUCTURAL`].

use lamplight_core::camera::{self, CameraKind};
use lamplight_core::lights::{self, LightKind};
use lamplight_core::materials::{self, MaterialKind, TextureKind};
use lamplight_core::params::{Param, ParamType as T};
use lamplight_core::shapes::{self, quadric::kinds as quadrics, ShapeKind};

use crate::instantiate::implicit;

/// Shape kinds.
pub static SHAPES: &[&ShapeKind] = &[
    &shapes::sphere::KIND,
    &quadrics::ELLIPSOID,
    &quadrics::CYLINDER,
    &quadrics::CONE,
    &quadrics::INFINITE_CYLINDER,
    &quadrics::INFINITE_CONE,
    &quadrics::PARABOLOID,
    &quadrics::HYPERBOLOID,
    &quadrics::QUADRIC,
    &shapes::plane::PLANE_KIND,
    &shapes::plane::RECTANGLE_KIND,
    &shapes::plane::DISK_KIND,
    &shapes::cuboid::KIND,
    &shapes::triangle::KIND,
    &shapes::torus::KIND,
    &implicit::KIND,
    &shapes::sdf_grid::KIND,
];

/// Light kinds.
pub static LIGHTS: &[&LightKind] = &[&lights::point::KIND, &lights::directional::KIND, &lights::spot::KIND, &lights::projector::KIND];

/// Material kinds; the first is the default `type`.
pub static MATERIALS: &[&MaterialKind] = &[
    &materials::phong::KIND,
    &materials::pbr::KIND,
    &materials::plastic::KIND,
    &materials::principled::KIND,
    &materials::principled_thin::KIND,
    &materials::thin_dielectric::KIND,
    &materials::blend::KIND,
];

/// Camera kinds; the first is the default `type`.
pub static CAMERAS: &[&CameraKind] = &[
    &camera::perspective::PERSPECTIVE_KIND,
    &camera::perspective::WINDOW_KIND,
    &camera::thin_lens::KIND,
    &camera::orthographic::KIND,
    &camera::spherical::KIND,
];

/// Texture kinds.
pub static TEXTURES: &[&TextureKind] = &[
    &materials::texture::CHECKER,
    &materials::uv_checker::KIND,
    &materials::image::KIND,
    &materials::combine::SCALE,
    &materials::combine::MIX,
    &materials::combine::VERTEX_COLOR,
    &materials::uv_set::KIND,
];

/// A node type the builder handles itself.
#[derive(Debug)]
pub struct Structural {
    /// The `type`.
    pub name: &'static str,
    /// One line for the reference.
    pub summary: &'static str,
    /// Its own keys.
    pub params: &'static [Param],
}

/// The structural node types.
pub static STRUCTURAL: &[Structural] = &[
    Structural {
        name: "group",
        summary: "everything in `children` moves with the group",
        params: &[
            Param::new("children", T::Array, "[]", "", "the nodes in the group"),
            Param::new("material", T::String, "inherited", "", "default material of everything below"),
        ],
    },
    Structural {
        name: "instance",
        summary: "places `[definitions.NAME]`",
        params: &[
            Param::new("of", T::String, "", "", "the definition's name"),
            Param::new("material", T::String, "inherited", "", "default material of everything below"),
        ],
    },
    Structural {
        name: "mesh",
        summary: "a triangle mesh asset",
        params: &[
            Param::new("mesh", T::String, "", "", "name of a `[meshes]` entry"),
            Param::new("material", T::String, "inherited, else the file's", "", "material name"),
            FLIP_NORMALS,
            Param::new(
                "part",
                T::Integer,
                "every part",
                "0 to parts - 1",
                "only this part of a mesh file: its placed meshes in file order (OBJ: one per group and material; glTF: one per primitive of each node, in node order)",
            ),
        ],
    },
];

/// The keys every shape node takes besides its kind's.
pub const SHAPE_COMMON: &[Param] = &[
    Param::new(
        "material",
        T::String,
        "inherited, else grey",
        "",
        "material name; default: the nearest enclosing group's or instance's, else a mid-grey diffuse material",
    ),
    FLIP_NORMALS,
];

/// `flip_normals`, taken by shapes and mesh nodes.
const FLIP_NORMALS: Param = Param::new(
    "flip_normals",
    T::Bool,
    "false",
    "",
    "turn the outward side inward (Mitsuba's flip_normals, pbrt's ReverseOrientation): one-sided materials scatter, and area lights emit, on the other side",
);

/// The keys every node of the tree takes.
pub const NODE_COMMON: &[Param] = &[
    Param::new("type", T::String, "", "", "what the node is"),
    Param::new("name", T::String, "none", "", "a name (shapes: referenced by a light's `own_object`)"),
    Param::new("translate", T::Vector, "none", "scene units", "translation"),
    Param::new(
        "rotate",
        T::Table,
        "none",
        "degrees",
        "`{ axis = VECTOR, degrees = N }`, `{ x = N, y = N, z = N }` or `[x, y, z]` (degrees about x, then y, then z), or `{ quaternion = [x, y, z, w] }` (glTF's order)",
    ),
    Param::new("scale", T::Color, "none", "non-zero", "a factor or `[sx, sy, sz]`"),
    Param::new("matrix", T::Matrix, "none", "affine", "4 rows of 4 numbers, last row `[0, 0, 0, 1]`; points are column vectors"),
    Param::new(
        "animate",
        T::Table,
        "none",
        "",
        "keyframes: `animate.KEY = { frames = [...], values = [...] }` for `translate`, `rotate`, `scale` or a key of the node's kind (see `animate.KEY`)",
    ),
];

/// The names of every node type, structural ones first (for messages).
pub fn node_types() -> Vec<&'static str> {
    let mut names: Vec<&str> = STRUCTURAL.iter().map(|s| s.name).collect();
    names.extend(LIGHTS.iter().map(|k| k.name));
    names.extend(SHAPES.iter().map(|k| k.name));
    names
}

mod reference;
pub use reference::reference;
