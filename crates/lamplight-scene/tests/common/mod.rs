//! Helpers shared by the importer tests.
#![allow(dead_code)]

pub mod mitsuba_xml;

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

/// A path in a folder that does not exist, so that referenced files are never found.
pub fn fake_path(name: &str) -> PathBuf {
    Path::new("/nonexistent-lamplight-fuzz").join(name)
}

/// Random byte edits: (position, new byte), positions taken modulo the file length.
pub fn edits() -> impl proptest::strategy::Strategy<Value = Vec<(usize, u8)>> {
    proptest::collection::vec((proptest::prelude::any::<usize>(), proptest::prelude::any::<u8>()), 1..8)
}

/// `base` with `edits` applied, and cut short when `cut` says so (one time in four).
pub fn mutate(base: &[u8], edits: &[(usize, u8)], cut: usize) -> Vec<u8> {
    let mut out = base.to_vec();
    for &(at, byte) in edits {
        let i = at % out.len();
        out[i] = byte;
    }
    if cut & 3 == 0 {
        out.truncate(cut / 4 % (base.len() + 1));
    }
    out
}

/// Root-mean-square difference of two images of one size, over pixels and channels.
pub fn rmse(a: &lamplight_core::film::Image, b: &lamplight_core::film::Image) -> f64 {
    let sum: f64 = a.pixels.iter().zip(&b.pixels).flat_map(|(p, q)| (0..3).map(move |c| (p[c] as f64 - q[c] as f64).powi(2))).sum();
    (sum / (3 * a.pixels.len()) as f64).sqrt()
}
