//! Helpers shared by the importer tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use lamplight_scene::import::{self, Imported};
use lamplight_scene::LoadError;

/// `../shared/data` next to the repository, if present; prints why a test skips otherwise.
pub fn shared_data(test: &str) -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("SKIPPED {test}: shared test data not found at {} (see the issue: ../shared/data)", dir.display());
        None
    }
}

/// Writes `bytes` as `name` in `dir` and loads it.
pub fn write_and_load(dir: &Path, name: &str, bytes: &[u8]) -> Result<Imported, LoadError> {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    import::load(&path)
}

/// The error of loading `bytes` as `name`, as text with the temp dir stripped.
pub fn error_of(dir: &Path, name: &str, bytes: &[u8]) -> String {
    match write_and_load(dir, name, bytes) {
        Ok(imported) => panic!("{name} loaded but should fail: {} meshes, warnings {:?}", imported.meshes.len(), imported.warnings),
        Err(e) => e.to_string().replace(&format!("{}/", dir.display()), ""),
    }
}

/// Triangle count over every instance.
pub fn triangles(imported: &Imported) -> usize {
    imported.instances.iter().map(|i| imported.meshes[i.mesh].indices.len()).sum()
}
