//! [`Node`]: one entity of a scene, `{type, name, transform, children, params}`.

use lamplight_core::params::{Item, Loc, ParamError, Table, Value};

use super::into_table_at;

/// The keys that place a node; they apply to everything under it.
pub const TRANSFORM_KEYS: &[&str] = &["translate", "rotate", "scale", "matrix"];

/// A value with the name it is filed under (`[materials.NAME]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Named<T> {
    /// The name.
    pub name: String,
    /// Where the name is written.
    pub loc: Loc,
    /// The value.
    pub value: T,
}

/// One entity: what it is, its name, its placement, its children and the
/// parameters its kind reads.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// The `type` (a registered kind, `group`, `instance` or `mesh`).
    pub kind: String,
    /// Where `type` is written (the table, when it was defaulted).
    pub kind_loc: Loc,
    /// The label messages about this node start with (usually `kind`).
    pub label: String,
    /// `name`, if given.
    pub name: Option<String>,
    /// The transform keys (`translate`, `rotate`, `scale`, `matrix`), unread.
    pub transform: Table,
    /// `children`, if given.
    pub children: Option<Vec<Node>>,
    /// Everything else, with the node table's place as its own.
    pub params: Table,
}

impl Node {
    /// A node from its table. `what` names it in messages before its type is
    /// known; `default_kind` is used when `type` is absent (else `type` is
    /// required); `tree` says whether it sits in the node tree (and so takes a
    /// transform and children).
    pub fn from_table(mut table: Table, what: &str, default_kind: Option<&str>, tree: bool) -> Result<Node, ParamError> {
        let loc = table.loc.clone();
        let (kind, kind_loc) = match table.remove("type") {
            Some(e) => match e.item.value {
                Value::String(s) => (s, e.item.loc),
                other => {
                    return Err(ParamError {
                        loc: e.item.loc,
                        message: format!("{what}: type: expected a string, got {}", other.describe()),
                    })
                }
            },
            None => match default_kind {
                Some(k) => (k.to_string(), loc.clone()),
                None => return Err(ParamError { loc, message: format!("{what}: needs `type` (a string naming what the node is)") }),
            },
        };
        let label = if tree { kind.clone() } else { what.to_string() };
        let mut name = None;
        let mut transform = Table { entries: Vec::new(), loc: loc.clone() };
        let mut children = None;
        if tree {
            if let Some(e) = table.remove("name") {
                match e.item.value {
                    Value::String(s) => name = Some(s),
                    other => {
                        return Err(ParamError {
                            loc: e.item.loc,
                            message: format!("{label}: name: expected a string, got {}", other.describe()),
                        })
                    }
                }
            }
            for key in TRANSFORM_KEYS {
                if let Some(e) = table.remove(key) {
                    transform.entries.push(e);
                }
            }
            if let Some(e) = table.remove("children") {
                children = Some(node_list(e.item, &format!("{label}: children"))?);
            }
        }
        Ok(Node { kind, kind_loc, label, name, transform, children, params: table })
    }
}

/// An array of node tables (`objects`, a group's `children`).
pub(crate) fn node_list(item: Item, what: &str) -> Result<Vec<Node>, ParamError> {
    let Value::Array(items) = item.value else {
        return Err(ParamError {
            loc: item.loc,
            message: format!("{what}: expected an array of node tables, got {}", item.value.describe()),
        });
    };
    items
        .into_iter()
        .enumerate()
        .map(|(i, item)| {
            let what = format!("{what}[{i}]");
            Node::from_table(into_table_at(item, &what)?, &what, None, true)
        })
        .collect()
}
