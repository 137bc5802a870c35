//! Arbitrary bytes to the native scene parser and builder: loading must return
//! `Ok` or one `LoadError`, never panic, hang or allocate without bound.
#![no_main]

use std::path::Path;

use lamplight_scene::instantiate::SceneFile;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(file) = SceneFile::parse(Path::new("fuzz.toml"), text) {
        if file.settings().is_ok() {
            let _ = file.build();
        }
    }
});
