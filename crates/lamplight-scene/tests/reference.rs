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
