//! `[materials.NAME]` through the material kinds of the registry.

use std::cell::RefCell;
use std::collections::BTreeMap;

use lamplight_core::materials::blend::{Components, MAX_DEPTH};
use lamplight_core::materials::{ImageLoader, Material, Textures};
use lamplight_core::params::{unknown_kind, Item, Kind, ParamResult, Params, Table, Value};
use lamplight_core::SceneBuilder;

use crate::description::{Node, SceneDescription};
use crate::error::LoadError;
use crate::formats::native::Source;
use crate::registry;

/// Adds every material of `desc` to `builder`; returns their indices by name.
pub(super) fn add_all(
    desc: &SceneDescription,
    source: &Source,
    builder: &mut SceneBuilder,
    images: &dyn ImageLoader,
) -> Result<BTreeMap<String, usize>, LoadError> {
    let scope = Scope { desc, open: RefCell::new(Vec::new()) };
    let textures = Textures { kinds: registry::TEXTURES, images: Some(images), materials: Some(&scope) };
    let mut out = BTreeMap::new();
    for named in &desc.materials {
        let node = &named.value;
        if Kind::find(registry::MATERIALS, &node.kind).is_none() {
            let message = format!("{}: {}", node.label, unknown_kind("material type", &node.kind, registry::MATERIALS));
            return Err(source.error(&node.kind_loc, message));
        }
        scope.open.borrow_mut().push(Some(named.name.clone()));
        let material = build(node, &textures);
        scope.open.borrow_mut().pop();
        let material = material.map_err(|e| source.param_error(e))?;
        let index = builder.material(material).map_err(|e| source.error(&node.params.loc, format!("{}: {e}", node.label)))?;
        out.insert(named.name.clone(), index);
    }
    Ok(out)
}

/// The material of `node` through its kind (which the caller has checked exists).
fn build(node: &Node, textures: &Textures<'_>) -> ParamResult<Material> {
    let Some(kind) = Kind::find(registry::MATERIALS, &node.kind) else {
        return Err(lamplight_core::params::ParamError {
            loc: node.kind_loc.clone(),
            message: format!("{}: {}", node.label, unknown_kind("material type", &node.kind, registry::MATERIALS)),
        });
    };
    let p = Params::new(node.label.clone(), &node.params);
    p.read(kind.params, &[], |p| (kind.build)(p, textures))
}

/// The components a `blend` names or holds: the scene's named materials, built
/// again where they are used (materials are values), and the materials being
/// built now (`open`: a name, or `None` for a table written in place), which a
/// component may not name again (a cycle) and whose number bounds the nesting.
struct Scope<'a> {
    desc: &'a SceneDescription,
    open: RefCell<Vec<Option<String>>>,
}

impl Components for Scope<'_> {
    fn component(&self, p: &mut Params<'_>, key: &str, textures: &Textures<'_>) -> ParamResult<Option<Material>> {
        let label = format!("{}: {key}", p.label());
        let (node, name) = match p.item(key) {
            None => return Ok(None),
            Some(Item { value: Value::String(name), .. }) => {
                let Some(named) = self.desc.material(name) else {
                    let known: Vec<&str> = self.desc.materials.iter().map(|m| m.name.as_str()).collect();
                    return Err(p.key_error(key, lamplight_core::params::unknown("material", name, &known)));
                };
                let open = self.open.borrow();
                if open.iter().any(|o| o.as_deref() == Some(name.as_str())) {
                    let chain: Vec<&str> = open.iter().flatten().map(String::as_str).chain([name.as_str()]).collect();
                    return Err(p.key_error(key, format!("the blend contains itself ({})", chain.join(" -> "))));
                }
                (named.value.clone(), Some(name.clone()))
            }
            Some(Item { value: Value::Table(t), loc }) => {
                let mut t: Table = t.clone();
                if t.loc == lamplight_core::params::Loc::Unknown {
                    t.loc = loc.clone();
                }
                (Node::from_table(t, &label, Some("phong"), false)?, None)
            }
            Some(item) => {
                let got = item.value.describe();
                return Err(p.key_error(key, format!("expected a material name or a material table, got {got}")));
            }
        };
        if self.open.borrow().len() > MAX_DEPTH {
            return Err(p.key_error(key, format!("materials nested more than {MAX_DEPTH} deep")));
        }
        let node = Node {
            label: match &name {
                Some(n) => format!("material \"{n}\""),
                None => label,
            },
            ..node
        };
        self.open.borrow_mut().push(name);
        let built = build(&node, textures);
        self.open.borrow_mut().pop();
        built.map(Some)
    }
}
