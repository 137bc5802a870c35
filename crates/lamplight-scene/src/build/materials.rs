//! `[materials.NAME]` through the material kinds of the registry.

use std::collections::BTreeMap;

use lamplight_core::materials::Textures;
use lamplight_core::params::Params;
use lamplight_core::SceneBuilder;

use crate::description::SceneDescription;
use crate::error::LoadError;
use crate::formats::native::Source;
use crate::registry;

/// Adds every material of `desc` to `builder`; returns their indices by name.
pub(super) fn add_all(desc: &SceneDescription, source: &Source, builder: &mut SceneBuilder) -> Result<BTreeMap<String, usize>, LoadError> {
    let textures = Textures { kinds: registry::TEXTURES };
    let mut out = BTreeMap::new();
    for named in &desc.materials {
        let node = &named.value;
        let mut p = Params::new(node.label.clone(), &node.params);
        let Some(kind) = registry::material(&node.kind) else {
            let names: Vec<&str> = registry::MATERIALS.iter().map(|k| k.name).collect();
            let hint = lamplight_core::params::suggestion(&node.kind, names.iter().copied())
                .map(|s| format!("did you mean '{s}'? "))
                .unwrap_or_default();
            let message = format!("{}: unknown material type \"{}\" ({hint}material types: {})", node.label, node.kind, names.join(", "));
            return Err(source.error(&node.kind_loc, message));
        };
        let made = p.check_keys(kind.params, &[]).and_then(|()| (kind.build)(&mut p, &textures)).and_then(|m| p.finish().map(|()| m));
        let material = made.map_err(|e| source.param_error(e))?;
        let index = builder.material(material).map_err(|e| source.error(&node.params.loc, format!("{}: {e}", node.label)))?;
        out.insert(named.name.clone(), index);
    }
    Ok(out)
}
