//! Helpers shared by the tests of Mitsuba's BSDFs: a scene of one sphere with a
//! given BSDF, read as a user's file is, and the exact error of a bad one.

use lamplight_core::Scene;
use lamplight_scene::formats::mitsuba;
use lamplight_scene::request::SceneRequest;

/// A scene of a camera and one sphere with the BSDF `bsdf`.
pub fn one_sphere(bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
    <shape type="sphere">{bsdf}</shape>
</scene>
"#
    )
}

/// The built scene of `text` (an XML scene, written to `s.xml` in a fresh
/// folder) and the reader's warnings, the folder left out of them.
pub fn read(text: &str) -> (Scene, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.xml");
    std::fs::write(&path, text).unwrap();
    let (_, source) = mitsuba::read(&path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let scene = SceneRequest::resolve_with(path.to_str().unwrap(), &[]).unwrap().build().unwrap_or_else(|e| panic!("{e}"));
    let warnings = source.warnings.iter().map(|w| w.replace(&format!("{}/", dir.path().display()), "")).collect();
    (scene, warnings)
}

/// The error of reading and building `text` as `s.xml`, the folder left out.
pub fn error(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.xml");
    std::fs::write(&path, text).unwrap();
    match SceneRequest::resolve_with(path.to_str().unwrap(), &[]).and_then(|r| r.build()) {
        Ok(_) => panic!("read but should fail:\n{text}"),
        Err(e) => e.to_string().replace(&format!("{}/", dir.path().display()), ""),
    }
}

/// What reading and building `text` as `s.xml` gives, with `files` (name,
/// bytes) written beside it: the reader's warnings, or the error; the folder
/// left out of both.
pub fn outcome(text: &str, files: &[(&str, Vec<u8>)]) -> Result<Vec<String>, String> {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    let path = dir.path().join("s.xml");
    std::fs::write(&path, text).unwrap();
    let strip = |s: &str| s.replace(&format!("{}/", dir.path().display()), "");
    let built = SceneRequest::resolve_with(path.to_str().unwrap(), &[]).and_then(|r| r.build());
    match (built, mitsuba::read(&path, &[])) {
        (Ok(_), Ok((_, source))) => Ok(source.warnings.iter().map(|w| strip(w)).collect()),
        (Err(e), _) => Err(strip(&e.to_string())),
        (Ok(_), Err(e)) => Err(strip(&e.to_string())),
    }
}
