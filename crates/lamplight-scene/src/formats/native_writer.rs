//! A located [`Table`] (what every format reads to) written as native TOML:
//! `lamplight convert` turns another renderer's scene into a lamplight file.
//!
//! Top-level values first, then `[render]` and `[camera]`, `[materials.NAME]`,
//! `[meshes.NAME]`, `[definitions.NAME]` and one `[[objects]]` per node; the
//! values inside are inline. Numbers are written in Rust's shortest form that
//! reads back to the same `f64`, so the TOML renders to the same bytes.

use std::fmt::Write;

use lamplight_core::params::{Item, Table, Value};

/// The tables written as `[NAME.KEY]` sections.
const NAMED: &[&str] = &["materials", "meshes", "definitions"];

/// `root` as a native scene file; `header` lines become comments on top.
pub fn write(root: &Table, header: &str) -> String {
    let mut out = String::new();
    for line in header.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let sections = |key: &str| matches!(key, "render" | "camera" | "objects") || NAMED.contains(&key);
    for e in root.entries.iter().filter(|e| !sections(&e.key)) {
        let _ = writeln!(out, "{} = {}", key(&e.key), value(&e.item));
    }
    for name in ["render", "camera"] {
        if let Some(Value::Table(t)) = root.get(name).map(|e| &e.item.value) {
            let _ = writeln!(out, "\n[{name}]");
            body(&mut out, t);
        }
    }
    for name in NAMED {
        if let Some(Value::Table(t)) = root.get(name).map(|e| &e.item.value) {
            for e in &t.entries {
                let _ = writeln!(out, "\n[{name}.{}]", key(&e.key));
                if let Value::Table(inner) = &e.item.value {
                    body(&mut out, inner);
                }
            }
        }
    }
    if let Some(Value::Array(items)) = root.get("objects").map(|e| &e.item.value) {
        for item in items {
            if let Value::Table(t) = &item.value {
                out.push_str("\n[[objects]]\n");
                body(&mut out, t);
            }
        }
    }
    out
}

fn body(out: &mut String, t: &Table) {
    for e in &t.entries {
        let _ = writeln!(out, "{} = {}", key(&e.key), value(&e.item));
    }
}

/// A key, bare when TOML allows, else quoted.
fn key(k: &str) -> String {
    if !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        k.to_string()
    } else {
        quote(k)
    }
}

fn quote(s: &str) -> String {
    let mut q = String::with_capacity(s.len() + 2);
    q.push('"');
    for c in s.chars() {
        match c {
            '"' => q.push_str("\\\""),
            '\\' => q.push_str("\\\\"),
            '\n' => q.push_str("\\n"),
            '\t' => q.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(q, "\\u{:04X}", c as u32);
            }
            c => q.push(c),
        }
    }
    q.push('"');
    q
}

/// One value, inline.
fn value(item: &Item) -> String {
    match &item.value {
        Value::Bool(b) => b.to_string(),
        Value::Integer(i) => i.to_string(),
        // `{:?}` is the shortest text that reads back to the same f64 ("1.0", "0.1", "1e-7").
        Value::Number(n) => format!("{n:?}"),
        Value::String(s) => quote(s),
        Value::Array(items) => format!("[{}]", items.iter().map(value).collect::<Vec<_>>().join(", ")),
        Value::Table(t) => {
            if t.entries.is_empty() {
                "{}".to_string()
            } else {
                format!(
                    "{{ {} }}",
                    t.entries.iter().map(|e| format!("{} = {}", key(&e.key), value(&e.item))).collect::<Vec<_>>().join(", ")
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_core::params::{Entry, Loc};

    fn item(value: Value) -> Item {
        Item { value, loc: Loc::Unknown }
    }

    #[test]
    fn values_read_back_the_same() {
        let t = Table {
            entries: vec![
                Entry { key: "a b".into(), key_loc: Loc::Unknown, item: item(Value::Number(0.1)) },
                Entry { key: "s".into(), key_loc: Loc::Unknown, item: item(Value::String("q\"\\\n".into())) },
                Entry {
                    key: "n".into(),
                    key_loc: Loc::Unknown,
                    item: item(Value::Array(vec![item(Value::Number(1e-7)), item(Value::Integer(-3))])),
                },
            ],
            loc: Loc::Unknown,
        };
        let text = write(&t, "made by a test");
        assert_eq!(text, "# made by a test\n\"a b\" = 0.1\ns = \"q\\\"\\\\\\n\"\nn = [1e-7, -3]\n");
        let back = toml::de::DeTable::parse(&text).unwrap().into_inner();
        assert_eq!(back.len(), 3, "every key reads back");
    }
}
