//! Arbitrary bytes as the `.mtl` file of a fixed OBJ: loading must return `Ok`
//! or one `LoadError`, never panic, hang or allocate without bound. The `obj`
//! target cannot reach the MTL reader (its folder does not exist, so every
//! `mtllib` is reported missing); this one writes the bytes where the OBJ's
//! `mtllib` finds them. Textures the MTL names are looked for in that folder,
//! which holds nothing else.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

/// An empty folder of this process's own, made once.
fn folder() -> &'static PathBuf {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("lamplight-fuzz-mtl-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        dir
    })
}

const OBJ: &[u8] = b"mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1 3 2\n";

fuzz_target!(|data: &[u8]| {
    let dir = folder();
    if std::fs::write(dir.join("fuzz.mtl"), data).is_err() {
        return;
    }
    let _ = lamplight_scene::import::load_bytes(&dir.join("input.obj"), OBJ);
});
