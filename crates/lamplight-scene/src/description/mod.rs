//! The scene description: plain data between a scene source (a TOML file, a
//! Python dict, later other renderers' formats) and [`crate::instantiate`].
//!
//! Every format first produces a generic [`Table`] tree whose values and keys
//! carry their place ([`Loc`]); [`SceneDescription::from_table`] then sorts the
//! top level into its parts and each entity into a [`Node`]: `{type, name,
//! transform, children, params}`. What a kind's `params` mean is not known
//! here: the kind reads them (see [`crate::registry`]), so a new kind needs no
//! change to this module.

use lamplight_core::params::{Entry, Item, Loc, ParamError, Table, Value};

pub mod animation;
mod node;
pub mod rotation;

pub use animation::Animation;
pub use node::{Named, Node, TRANSFORM_KEYS};

/// A whole scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneDescription {
    /// Top-level values (`ambient`, `background`), read as the `scene` kind.
    pub globals: Table,
    /// `[render]`: image size, sampling and integrator.
    pub render: Option<Table>,
    /// `[camera]`.
    pub camera: Option<Node>,
    /// `[materials.NAME]`, in source order.
    pub materials: Vec<Named<Node>>,
    /// `[meshes.NAME]`, in source order.
    pub meshes: Vec<Named<Table>>,
    /// `[definitions.NAME]`: node trees placed by `instance` nodes.
    pub definitions: Vec<Named<Node>>,
    /// `[[objects]]`: the scene's top-level nodes, in order.
    pub objects: Vec<Node>,
    /// `[animation]`: the frame range and rate, when the scene is animated
    /// (its nodes' `animate` tables say what moves; [`SceneDescription::at_frame`]).
    pub animation: Option<Animation>,
}

/// The top-level keys, in the order the reference lists them.
pub const TOP_LEVEL_KEYS: &[&str] =
    &["ambient", "background", "environment", "render", "animation", "camera", "materials", "meshes", "definitions", "objects"];

impl SceneDescription {
    /// Sorts a parsed top-level table into a description. The `scene` label
    /// starts messages about the top level.
    pub fn from_table(mut root: Table) -> Result<SceneDescription, ParamError> {
        if let Some(entry) = root.entries.iter().find(|e| !TOP_LEVEL_KEYS.contains(&e.key.as_str())) {
            let hint = match lamplight_core::params::suggestion(&entry.key, TOP_LEVEL_KEYS.iter().copied()) {
                Some(s) => format!(" (did you mean '{s}'?)"),
                None => format!(" (the top level takes: {})", TOP_LEVEL_KEYS.join(", ")),
            };
            return Err(ParamError { loc: entry.key_loc.clone(), message: format!("scene: unknown key '{}'{hint}", entry.key) });
        }
        let mut desc = SceneDescription::default();
        if let Some(e) = root.remove("render") {
            desc.render = Some(into_table(e, "render")?);
        }
        if let Some(e) = root.remove("animation") {
            desc.animation = Some(Animation::read(&into_table(e, "animation")?)?);
        }
        if let Some(e) = root.remove("camera") {
            desc.camera = Some(Node::from_table(into_table(e, "camera")?, "camera", Some("perspective"), false)?);
        }
        if let Some(e) = root.remove("materials") {
            for m in into_table(e, "materials")?.entries {
                let label = format!("material \"{}\"", m.key);
                let table = into_table_at(m.item, &label)?;
                desc.materials.push(Named { name: m.key, loc: m.key_loc, value: Node::from_table(table, &label, Some("phong"), false)? });
            }
        }
        if let Some(e) = root.remove("meshes") {
            for m in into_table(e, "meshes")?.entries {
                let table = into_table_at(m.item, &format!("mesh \"{}\"", m.key))?;
                desc.meshes.push(Named { name: m.key, loc: m.key_loc, value: table });
            }
        }
        if let Some(e) = root.remove("definitions") {
            for d in into_table(e, "definitions")?.entries {
                let label = format!("definition \"{}\"", d.key);
                let table = into_table_at(d.item, &label)?;
                desc.definitions.push(Named { name: d.key, loc: d.key_loc, value: Node::from_table(table, &label, None, true)? });
            }
        }
        if let Some(e) = root.remove("objects") {
            desc.objects = node::node_list(e.item, "objects")?;
        }
        desc.globals = root;
        desc.check_animation()?;
        Ok(desc)
    }

    /// The material called `name`.
    pub fn material(&self, name: &str) -> Option<&Named<Node>> {
        self.materials.iter().find(|m| m.name == name)
    }

    /// The mesh asset called `name`.
    pub fn mesh(&self, name: &str) -> Option<&Named<Table>> {
        self.meshes.iter().find(|m| m.name == name)
    }

    /// The definition called `name`.
    pub fn definition(&self, name: &str) -> Option<&Named<Node>> {
        self.definitions.iter().find(|d| d.name == name)
    }
}

fn into_table(entry: Entry, what: &str) -> Result<Table, ParamError> {
    into_table_at(entry.item, what)
}

pub(crate) fn into_table_at(item: Item, what: &str) -> Result<Table, ParamError> {
    match item.value {
        Value::Table(mut t) => {
            if t.loc == Loc::Unknown {
                t.loc = item.loc;
            }
            Ok(t)
        }
        other => Err(ParamError { loc: item.loc, message: format!("{what}: expected a table, got {}", other.describe()) }),
    }
}
