//! `docs/scene-format.md` holds the registry's reference tables word for word:
//! a kind or parameter added to the registry without the docs fails here.
//! `LAMPLIGHT_BLESS=1 cargo test -p lamplight-scene --test all reference::` rewrites
//! the generated part after a deliberate change.

use std::path::Path;

const BEGIN: &str = "<!-- BEGIN reference generated from the registry (crates/lamplight-scene/src/registry.rs); do not edit by hand -->\n";
const END: &str = "<!-- END generated reference -->";

#[test]
fn scene_format_reference_matches_the_registry() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let (Some(start), Some(end)) = (doc.find(BEGIN), doc.find(END)) else {
        panic!("{} lacks the generated reference markers", path.display());
    };
    let generated = lamplight_scene::registry::reference();
    let current = &doc[start + BEGIN.len()..end];
    if current != generated {
        if std::env::var_os("LAMPLIGHT_BLESS").is_some() {
            let updated = format!("{}{BEGIN}{generated}{}", &doc[..start], &doc[end..]);
            std::fs::write(&path, updated).unwrap();
            return;
        }
        let first = current.lines().zip(generated.lines()).position(|(a, b)| a != b).unwrap_or(0);
        panic!(
            "docs/scene-format.md differs from the registry at generated line {}:\n  doc:      {:?}\n  registry: {:?}\n(rerun with LAMPLIGHT_BLESS=1 to rewrite it)",
            first + 1,
            current.lines().nth(first),
            generated.lines().nth(first)
        );
    }
}

/// The rows of the generated reference, each with its section's title:
/// `(section, key, default, meaning)`.
fn rows(reference: &str) -> Vec<(String, String, String, String)> {
    let mut section = String::new();
    let mut out = Vec::new();
    for line in reference.lines() {
        if let Some(title) = line.strip_prefix("#### ") {
            section = title.to_string();
        } else if let Some(row) = line.strip_prefix("| `") {
            let cells: Vec<&str> = row.split(" | ").collect();
            let key = cells[0].trim_end_matches('`').to_string();
            out.push((section.clone(), key, cells[2].to_string(), cells[4].trim_end_matches(" |").to_string()));
        }
    }
    out
}

/// Issue 27: the spot light's `look_at` was "required" beside `direction`'s
/// "one of direction, look_at". Each key such a default names has that default too.
#[test]
fn keys_that_are_alternatives_are_not_also_required() {
    let rows = rows(&lamplight_scene::registry::reference());
    let mut checked = 0;
    for (section, key, default, _) in &rows {
        let Some(names) = default.strip_prefix("one of ") else { continue };
        for other in names.split(", ") {
            let found = rows.iter().find(|(s, k, _, _)| s == section && k == other);
            let (_, _, other_default, _) = found.unwrap_or_else(|| panic!("{section}: `{key}` names `{other}`, which it lacks"));
            assert_eq!(other_default, default, "{section}: `{other}` beside `{key}`");
            checked += 1;
        }
    }
    assert!(checked >= 4, "the spot and projector lights' direction and look_at: {checked}");
}

/// Issue 27: the `clip` rows said "see below" of text that is above them. A row
/// may say "see below" only of a key that has its own section below it; the
/// rest say what they mean in place (the same text is Python's `kinds()`).
#[test]
fn a_row_that_says_see_below_has_its_section_below() {
    let reference = lamplight_scene::registry::reference();
    let mut checked = 0;
    for (at, line) in reference.lines().enumerate() {
        let Some(row) = line.strip_prefix("| `") else { continue };
        if !row.contains("see below") {
            continue;
        }
        let key = row.split('`').next().unwrap_or_default();
        let below: Vec<&str> = reference.lines().skip(at + 1).collect();
        let heading = [format!("#### `{key}`"), format!("#### `[{key}]`")];
        assert!(below.iter().any(|l| heading.contains(&l.to_string())), "`{key}` says \"see below\" but has no section below: {line}");
        checked += 1;
    }
    assert!(checked >= 1, "the top level's `environment` and `[render]` rows");
}
