//! Arbitrary bytes to the Mitsuba XML reader and builder: reading must return
//! `Ok` or one `LoadError`, never panic, hang or allocate without bound.
#![no_main]

use std::path::Path;

use lamplight_scene::instantiate::SceneFile;
use lamplight_scene::formats::mitsuba;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    // Files it names are looked for in a folder that does not exist.
    let path = Path::new("/nonexistent-lamplight-fuzz/fuzz.xml");
    let Ok((table, source)) = mitsuba::parse_table(path, text.to_string(), &[("spp".into(), "1".into())]) else { return };
    if let Ok(description) = lamplight_scene::description::SceneDescription::from_table(table) {
        let file = SceneFile { description, source };
        if file.settings().is_ok() {
            let _ = file.build();
        }
    }
});
