//! The only files the viewer reads or writes for the page: those inside the
//! scene's folder. A name from the page is relative, with no `..`, no root, no
//! drive and no backslash; the file it names, once every symbolic link is
//! resolved, must still lie inside the folder (a link out of it is refused).

use std::path::{Component, Path, PathBuf};

/// Why a name from the page was refused (the page shows it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refused(pub String);

fn refuse(name: &str, why: &str) -> Refused {
    Refused(format!("'{name}' is refused: {why}"))
}

/// Checks that `name` is a plain relative name: not empty, no NUL or
/// backslash, no root or prefix, and no `.` or `..` components.
fn plain(name: &str) -> Result<&Path, Refused> {
    if name.is_empty() {
        return Err(refuse(name, "the name is empty"));
    }
    if name.contains('\0') || name.contains('\\') {
        return Err(refuse(name, "names may not hold NUL or backslash characters"));
    }
    let path = Path::new(name);
    for component in path.components() {
        match component {
            Component::Normal(_) => {}
            Component::ParentDir => return Err(refuse(name, "'..' may not leave the scene's folder")),
            Component::RootDir | Component::Prefix(_) => {
                return Err(refuse(name, "absolute paths are outside the scene's folder"));
            }
            Component::CurDir => return Err(refuse(name, "names are relative to the scene's folder, without '.'")),
        }
    }
    Ok(path)
}

/// The canonical `root` (a folder that exists).
fn canonical_root(root: &Path) -> Result<PathBuf, Refused> {
    root.canonicalize().map_err(|e| Refused(format!("the scene's folder {} cannot be read: {e}", root.display())))
}

/// The existing regular file `name` inside `root`, canonical.
pub fn existing_file(root: &Path, name: &str) -> Result<PathBuf, Refused> {
    let relative = plain(name)?;
    let root = canonical_root(root)?;
    let path = root.join(relative).canonicalize().map_err(|_| refuse(name, "no such file in the scene's folder"))?;
    if !path.starts_with(&root) {
        return Err(refuse(name, "it links outside the scene's folder"));
    }
    if !path.is_file() {
        return Err(refuse(name, "not a regular file"));
    }
    Ok(path)
}

/// Where a file `name` may be written inside `root`: its folder exists inside
/// `root` (links resolved), and the name itself is not a link or a folder.
pub fn writable_file(root: &Path, name: &str) -> Result<PathBuf, Refused> {
    let relative = plain(name)?;
    let root = canonical_root(root)?;
    let file_name = relative.file_name().ok_or_else(|| refuse(name, "no file name"))?;
    let parent = root.join(relative.parent().unwrap_or(Path::new("")));
    let parent = parent.canonicalize().map_err(|_| refuse(name, "its folder does not exist in the scene's folder"))?;
    if !parent.starts_with(&root) {
        return Err(refuse(name, "it links outside the scene's folder"));
    }
    let path = parent.join(file_name);
    match std::fs::symlink_metadata(&path) {
        Ok(m) if m.file_type().is_symlink() => Err(refuse(name, "it is a symbolic link")),
        Ok(m) if !m.is_file() => Err(refuse(name, "not a regular file")),
        _ => Ok(path),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder() -> (tempfile::TempDir, PathBuf) {
        let outer = tempfile::tempdir().unwrap();
        let root = outer.path().join("scene");
        std::fs::create_dir_all(root.join("meshes")).unwrap();
        std::fs::write(root.join("scene.toml"), "x").unwrap();
        std::fs::write(root.join("meshes/a.obj"), "v 0 0 0").unwrap();
        std::fs::write(outer.path().join("secret.txt"), "secret").unwrap();
        (outer, root)
    }

    #[test]
    fn files_inside_the_folder_are_served() {
        let (_outer, root) = folder();
        assert!(existing_file(&root, "scene.toml").unwrap().ends_with("scene/scene.toml"));
        assert!(existing_file(&root, "meshes/a.obj").unwrap().ends_with("scene/meshes/a.obj"));
    }

    #[test]
    fn traversal_absolute_paths_and_links_out_are_refused() {
        let (outer, root) = folder();
        let err = |name: &str| existing_file(&root, name).unwrap_err().0;
        assert_eq!(err("../secret.txt"), "'../secret.txt' is refused: '..' may not leave the scene's folder");
        assert_eq!(err("meshes/../../secret.txt"), "'meshes/../../secret.txt' is refused: '..' may not leave the scene's folder");
        let absolute = outer.path().join("secret.txt").display().to_string();
        assert_eq!(err(&absolute), format!("'{absolute}' is refused: absolute paths are outside the scene's folder"));
        assert_eq!(err("..\\secret.txt"), "'..\\secret.txt' is refused: names may not hold NUL or backslash characters");
        assert_eq!(err("meshes"), "'meshes' is refused: not a regular file");
        assert_eq!(err("missing.toml"), "'missing.toml' is refused: no such file in the scene's folder");
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(outer.path().join("secret.txt"), root.join("link.txt")).unwrap();
            std::os::unix::fs::symlink(outer.path(), root.join("up")).unwrap();
            assert_eq!(err("link.txt"), "'link.txt' is refused: it links outside the scene's folder");
            assert_eq!(err("up/secret.txt"), "'up/secret.txt' is refused: it links outside the scene's folder");
            let werr = |name: &str| writable_file(&root, name).unwrap_err().0;
            assert_eq!(werr("link.txt"), "'link.txt' is refused: it is a symbolic link");
            assert_eq!(werr("up/out.png"), "'up/out.png' is refused: it links outside the scene's folder");
        }
    }

    #[test]
    fn writes_go_inside_the_folder_only() {
        let (_outer, root) = folder();
        assert!(writable_file(&root, "out.png").unwrap().ends_with("scene/out.png"));
        assert!(writable_file(&root, "meshes/out.exr").unwrap().ends_with("scene/meshes/out.exr"));
        assert_eq!(writable_file(&root, "../out.png").unwrap_err().0, "'../out.png' is refused: '..' may not leave the scene's folder");
        assert_eq!(
            writable_file(&root, "nowhere/out.png").unwrap_err().0,
            "'nowhere/out.png' is refused: its folder does not exist in the scene's folder"
        );
        assert_eq!(writable_file(&root, "meshes").unwrap_err().0, "'meshes' is refused: not a regular file");
    }
}
