//! What a scene argument names, decided once for every front end: the command
//! line's `SCENE`, `lamplight.Scene(...)` and `Scene.from_file` all read a
//! built-in name, a scene file or a mesh file by the same rule and refuse an
//! unknown file type with the same message.

use std::path::Path;

use super::{bad, RequestError};
use crate::formats::{self, Format};
use crate::import;

/// Whether `arg` is a built-in scene's name rather than a file: it has no path
/// separator and no extension (`luxo`, not `./luxo` or `luxo.toml`).
pub fn names_builtin(arg: &str) -> bool {
    let has_separator = arg.contains('/') || arg.contains(std::path::MAIN_SEPARATOR);
    let extension = Path::new(arg).extension().and_then(|e| e.to_str());
    !has_separator && extension.is_none()
}

/// What kind of file a scene file argument is.
#[derive(Clone, Copy)]
pub enum FileKind {
    /// A scene file in this format, read by [`crate::instantiate::SceneFile::read_format`].
    Scene(&'static Format),
    /// A mesh file for the importers ([`import::EXTENSIONS`]).
    Mesh,
}

/// The kind of the file `path` by its extension (any case), or the message for
/// an extension no format or importer reads.
pub fn file_kind(path: &Path) -> Result<FileKind, RequestError> {
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    if let Some(format) = formats::find(&extension) {
        return Ok(FileKind::Scene(format));
    }
    if import::EXTENSIONS.contains(&extension.as_str()) {
        return Ok(FileKind::Mesh);
    }
    Err(bad(format!(
        "{}: unknown scene file type, expected {} or a mesh file ({})",
        path.display(),
        formats::FORMATS.iter().map(|f| format!(".{}", f.extension)).collect::<Vec<_>>().join(", "),
        import::EXTENSIONS.iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", ")
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_without_separator_or_extension_is_a_builtin() {
        assert!(names_builtin("luxo") && names_builtin("no-such-scene"));
        assert!(!names_builtin("./luxo") && !names_builtin("luxo.toml") && !names_builtin("dir/luxo"));
    }

    #[test]
    fn files_are_told_apart_by_extension() {
        assert!(matches!(file_kind(Path::new("a/scene.TOML")), Ok(FileKind::Scene(f)) if f.extension == "toml"));
        assert!(matches!(file_kind(Path::new("scene.xml")), Ok(FileKind::Scene(f)) if f.extension == "xml"));
        assert!(matches!(file_kind(Path::new("bunny.ply")), Ok(FileKind::Mesh)));
        let err = file_kind(Path::new("scene.txt")).err().unwrap();
        assert_eq!(err.0, "scene.txt: unknown scene file type, expected .toml, .xml or a mesh file (.obj, .ply, .gltf, .glb)");
    }
}
