//! Every reader (scene TOML, `.npy`, environment maps in EXR and HDR, meshes in
//! OBJ, PLY, glTF and GLB) against what a careless or hostile user may hand it:
//! a header that states a random size (up to `u64::MAX`), an empty file, a
//! directory, a FIFO, links to `/dev/zero`, `/dev/null`, a directory or nothing,
//! and sparse files beyond every size cap. The outcome is bounded: a result or
//! one line of error naming the file, never a panic, a block on the FIFO, an
//! endless read or an allocation the file does not justify. The seed is fixed.
//! See: issue 12 ("Panics, hangs and unbounded memory").

use std::fs;
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

/// The readers, by the extension that selects them.
const READERS: &[&str] = &["toml", "npy", "exr", "hdr", "obj", "ply", "gltf", "glb"];

/// Reads `path` with the reader its extension names; `Err` is the message.
fn read(path: &Path) -> Result<(), String> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or_default();
    match ext {
        "toml" => lamplight_scene::instantiate::SceneFile::read(path).and_then(|f| f.settings().map(drop)).map_err(|e| e.to_string()),
        "npy" => lamplight_scene::npy::read(path).and_then(|a| a.rows3_f32().map(drop)).map_err(|e| e.to_string()),
        "exr" | "hdr" => lamplight_scene::env_map::read_environment(path).map(drop).map_err(|e| e.to_string()),
        _ => lamplight_scene::import::load(path).map(drop).map_err(|e| e.to_string()),
    }
}

/// A small file of format `ext` whose header states `size` (rows, pixels,
/// vertices, accessor counts, image sides), followed by far fewer bytes.
fn header(ext: &str, size: u64) -> Vec<u8> {
    match ext {
        "toml" => {
            format!("[render]\nwidth = {size}\nheight = {size}\nspp = {size}\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n")
                .into_bytes()
        }
        "npy" => {
            let mut text = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({size}, 3), }}");
            while (10 + text.len() + 1) % 64 != 0 {
                text.push(' ');
            }
            text.push('\n');
            let mut out = b"\x93NUMPY\x01\x00".to_vec();
            out.extend_from_slice(&(text.len() as u16).to_le_bytes());
            out.extend_from_slice(text.as_bytes());
            out.extend_from_slice(&[0; 36]);
            out
        }
        "hdr" => {
            let side = size.min(u32::MAX as u64);
            let mut out = format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {side} +X {side}\n").into_bytes();
            out.extend_from_slice(&[2, 2, 0, 8, 128, 128, 128, 130]);
            out
        }
        "exr" => {
            // A real 2x2 EXR whose data and display windows are rewritten to end at `size`.
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("t.exr");
            let image = lamplight_core::film::Image { width: 2, height: 2, pixels: vec![[1.0; 3]; 4] };
            lamplight_scene::image_io::write_image(&path, &image).unwrap();
            let mut bytes = fs::read(&path).unwrap();
            let end = (size.min(i32::MAX as u64) as i32).to_le_bytes();
            for name in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
                if let Some(at) = bytes.windows(name.len()).position(|w| w == name) {
                    // Name, 4-byte size, then xMin, yMin, xMax, yMax.
                    let values = at + name.len() + 4;
                    bytes[values + 8..values + 12].copy_from_slice(&end);
                    bytes[values + 12..values + 16].copy_from_slice(&end);
                }
            }
            bytes
        }
        "obj" => format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {size}\n").into_bytes(),
        "ply" => format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {size}\nproperty float x\nproperty float y\nproperty float z\n\
             element face {size}\nproperty list uchar int vertex_indices\nend_header\n\0\0\0\0"
        )
        .into_bytes(),
        "gltf" | "glb" => {
            let json = format!(
                "{{\"asset\":{{\"version\":\"2.0\"}},\"buffers\":[{{\"byteLength\":{size},\"uri\":\"data:application/octet-stream;base64,AAAA\"}}],\
                 \"bufferViews\":[{{\"buffer\":0,\"byteLength\":{size}}}],\
                 \"accessors\":[{{\"bufferView\":0,\"componentType\":5126,\"count\":{size},\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,1]}}],\
                 \"meshes\":[{{\"primitives\":[{{\"attributes\":{{\"POSITION\":0}}}}]}}],\"nodes\":[{{\"mesh\":0}}],\"scenes\":[{{\"nodes\":[0]}}]}}"
            );
            if ext == "gltf" {
                return json.into_bytes();
            }
            let mut chunk = json.into_bytes();
            while chunk.len() % 4 != 0 {
                chunk.push(b' ');
            }
            let mut out = b"glTF".to_vec();
            out.extend_from_slice(&2u32.to_le_bytes());
            out.extend_from_slice(&(12 + 8 + chunk.len() as u32).to_le_bytes());
            out.extend_from_slice(&(chunk.len() as u32).to_le_bytes());
            out.extend_from_slice(b"JSON");
            out.extend_from_slice(&chunk);
            out
        }
        _ => unreachable!(),
    }
}

/// What sits at the path the reader is given.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// A file whose header states a size.
    Header(u64),
    /// A zero-byte file.
    Empty,
    /// A directory.
    Directory,
    /// A named pipe: opening it for reading would block until a writer comes.
    Fifo,
    /// A symbolic link to this path.
    Link(&'static str),
    /// A sparse file of this many bytes (beyond every cap, or small).
    Sparse(u64),
}

fn kind() -> impl Strategy<Value = Kind> {
    let size = prop_oneof![
        0..64u64,
        any::<u32>().prop_map(u64::from),
        any::<u64>(),
        Just(u64::MAX),
        Just(4_611_686_018_427_387_905),
        Just(1 << 32),
    ];
    prop_oneof![
        4 => size.prop_map(Kind::Header),
        1 => Just(Kind::Empty),
        1 => Just(Kind::Directory),
        1 => Just(Kind::Fifo),
        1 => prop_oneof![Just("/dev/zero"), Just("/dev/null"), Just("/"), Just("/nonexistent-lamplight-target")].prop_map(Kind::Link),
        1 => prop_oneof![1..65_536u64, (1u64 << 31)..(1u64 << 40)].prop_map(Kind::Sparse),
    ]
}

/// Makes `kind` at `dir/input.EXT`; `None` when this system cannot (no mkfifo).
fn make(dir: &Path, ext: &str, kind: Kind) -> Option<PathBuf> {
    let path = dir.join(format!("input.{ext}"));
    match kind {
        Kind::Header(size) => fs::write(&path, header(ext, size)).unwrap(),
        Kind::Empty => fs::write(&path, b"").unwrap(),
        Kind::Directory => fs::create_dir(&path).unwrap(),
        Kind::Fifo => {
            let made = std::process::Command::new("mkfifo").arg(&path).status();
            if !made.is_ok_and(|s| s.success()) {
                return None;
            }
        }
        Kind::Link(target) => {
            #[cfg(unix)]
            std::os::unix::fs::symlink(target, &path).unwrap();
            #[cfg(not(unix))]
            return None;
        }
        Kind::Sparse(len) => fs::File::create(&path).unwrap().set_len(len).unwrap(),
    }
    Some(path)
}

proptest! {
    #![proptest_config(Config { cases: 256, rng_seed: RngSeed::Fixed(12), failure_persistence: None, ..Config::default() })]

    #[test]
    fn every_reader_refuses_special_files_and_lying_headers(reader in 0..READERS.len(), kind in kind()) {
        let ext = READERS[reader];
        let dir = tempfile::tempdir().unwrap();
        let Some(path) = make(dir.path(), ext, kind) else { return Ok(()) };
        let outcome = read(&path);
        match (kind, &outcome) {
            // A header may describe a file that is fine (a few rows, a small image).
            (Kind::Header(_), Ok(())) => {}
            (Kind::Sparse(len), Ok(())) => prop_assert!(len < 65_536, "{ext}: {len} bytes of zeros read as valid"),
            (_, Ok(())) => prop_assert!(false, "{ext}: {kind:?} was accepted"),
            (_, Err(message)) => {
                prop_assert!(message.contains("input."), "{ext}: {kind:?}: the message names no file: {message}");
                prop_assert!(!message.contains('\n'), "{ext}: {kind:?}: one line: {message}");
            }
        }
    }
}
