//! `[materials.NAME]` through the material kinds of the registry.

use std::collections::BTreeMap;

use lamplight_core::materials::Textures;
use lamplight_core::params::{unknown_kind, Kind, Params};
use lamplight_core::SceneBuilder;

use crate::description::SceneDescription;
use crate::error::LoadError;
use crate::formats::native::Source;
use crate::registry;

/// Adds every material of `desc` to `builder`; returns their indices by name.
pub(super) fn add_all(
    desc: &SceneDescription,
    source: &Source,
    builder: &mut SceneBuilder,
    textures: &Textures<'_>,
) -> Result<BTreeMap<String, usize>, LoadError> {
    let mut out = BTreeMap::new();
    for named in &desc.materials {
        let node = &named.value;
        let Some(kind) = Kind::find(registry::MATERIALS, &node.kind) else {
            let message = format!("{}: {}", node.label, unknown_kind("material type", &node.kind, registry::MATERIALS));
            return Err(source.error(&node.kind_loc, message));
        };
        let p = Params::new(node.label.clone(), &node.params);
        let material = p.read(kind.params, &[], |p| (kind.build)(p, textures)).map_err(|e| source.param_error(e))?;
        let index = builder.material(material).map_err(|e| source.error(&node.params.loc, format!("{}: {e}", node.label)))?;
        out.insert(named.name.clone(), index);
    }
    Ok(out)
}
