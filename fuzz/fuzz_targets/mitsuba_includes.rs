//! The Mitsuba reader's substitution and include logic under amplification:
//! the input is split at NUL bytes into a main scene and up to three files it
//! may include (`a.xml`, `b.xml`, `c.xml`, written into a folder of this
//! process's own), and reading must end in `Ok` or one error within the
//! scene's budgets (`MAX_INCLUDES`, `MAX_XML_BYTES`, `MAX_VALUE_BYTES`,
//! `MAX_SUBSTITUTED_BYTES`). Run under `-rss_limit_mb` (fuzz/README.md) so that
//! an input that grows past them is a finding, not only a crash. Dictionary:
//! `fuzz/mitsuba_includes.dict`.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use lamplight_scene::formats::mitsuba;
use libfuzzer_sys::fuzz_target;

/// An empty folder of this process's own, made once.
fn folder() -> &'static PathBuf {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("lamplight-fuzz-includes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        dir
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let mut parts = text.split('\0');
    let main = parts.next().unwrap_or_default().to_string();
    let dir = folder();
    for name in ["a.xml", "b.xml", "c.xml"] {
        let part = parts.next().unwrap_or_default();
        if std::fs::write(dir.join(name), part).is_err() {
            return;
        }
    }
    let _ = mitsuba::parse_table(&dir.join("main.xml"), main, &[("x".into(), "ab".into())]);
});
