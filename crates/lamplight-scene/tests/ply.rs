//! PLY importer: files the tests write (ASCII, binary little and big endian,
//! with and without normals, polygons, strips), the shared real meshes, and a
//! table of malformed files with the exact error each gives.

use crate::common;

use common::{error_of, shared_data, write_and_load};
use lamplight_core::math::Vec3;
use lamplight_scene::import;

const SQUARE_ASCII: &str = "ply\r\nformat ascii 1.0\ncomment a unit square and a triangle\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n4 0 1 2 3\n3 0 1 4\n";

#[test]
fn ascii_quads_are_fan_triangulated_in_file_order() {
    let dir = tempfile::tempdir().unwrap();
    let imported = write_and_load(dir.path(), "square.ply", SQUARE_ASCII.as_bytes()).unwrap();
    assert_eq!(imported.meshes.len(), 1);
    let mesh = &imported.meshes[0];
    assert_eq!(mesh.positions[4], Vec3::new(0.5, 0.5, 1.0));
    assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]]);
    assert_eq!(mesh.normals, None);
    assert_eq!(mesh.name.as_deref(), Some("square"));
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
}

/// A binary PLY of two triangles, optionally with normals and an ignored `red` property.
fn binary(big_endian: bool, normals: bool) -> Vec<u8> {
    let mut header = format!("ply\nformat binary_{}_endian 1.0\nelement vertex 4\n", if big_endian { "big" } else { "little" });
    header += "property float x\nproperty float y\nproperty double z\n";
    if normals {
        header += "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n";
    }
    header += "element face 2\nproperty list uchar uint vertex_indices\nend_header\n";
    let mut out = header.into_bytes();
    let f32b = |v: f32| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
    let f64b = |v: f64| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
    let u32b = |v: u32| if big_endian { v.to_be_bytes() } else { v.to_le_bytes() };
    for (i, p) in [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0, 0.0, -4.5]].iter().enumerate() {
        out.extend(f32b(p[0] as f32));
        out.extend(f32b(p[1] as f32));
        out.extend(f64b(p[2]));
        if normals {
            out.extend(f32b(0.0));
            out.extend(f32b(0.0));
            out.extend(f32b(1.0 + i as f32));
            out.push(255);
        }
    }
    for face in [[0u32, 1, 2], [0, 2, 3]] {
        out.push(3);
        for i in face {
            out.extend(u32b(i));
        }
    }
    out
}

#[test]
fn binary_little_and_big_endian_with_and_without_normals() {
    let dir = tempfile::tempdir().unwrap();
    for big in [false, true] {
        for normals in [false, true] {
            let imported = write_and_load(dir.path(), "two.ply", &binary(big, normals)).unwrap();
            let mesh = &imported.meshes[0];
            assert_eq!(mesh.positions, vec![Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 3.0, 0.0), Vec3::new(0.0, 0.0, -4.5)]);
            assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3]], "big endian {big}");
            if normals {
                assert_eq!(mesh.normals.as_ref().unwrap()[3], Vec3::new(0.0, 0.0, 4.0));
                assert_eq!(imported.warnings, vec!["PLY vertex properties ignored: red".to_string()]);
            } else {
                assert_eq!(mesh.normals, None);
            }
        }
    }
}

#[test]
fn tristrips_restart_at_minus_one_and_keep_the_winding() {
    let dir = tempfile::tempdir().unwrap();
    let text = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 2 0\n1 2 0\n8 0 1 2 3 -1 2 3 4\n";
    let mesh = import::load_mesh(&{
        let p = dir.path().join("strip.ply");
        std::fs::write(&p, text).unwrap();
        p
    })
    .unwrap();
    assert_eq!(mesh.indices, vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
}

#[test]
fn elements_without_properties_cost_nothing_whatever_their_count() {
    let dir = tempfile::tempdir().unwrap();
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement empty 1000000000000\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let imported = write_and_load(dir.path(), "empty.ply", text.as_bytes()).unwrap();
    assert_eq!(imported.meshes[0].indices, vec![[0, 1, 2]]);
    assert_eq!(imported.warnings, vec!["PLY element `empty` (1000000000000 items) ignored".to_string()]);
}

/// Vertices of `float x, y, z` and faces of `list uchar int vertex_indices`
/// (`uint` when `unsigned`), the layout read in bulk, with these positions
/// and faces (each a list of any length). `general`: the same mesh as
/// `double`s and `list int int`, which only the general reader reads.
fn bulk_layout(big_endian: bool, unsigned: bool, general: bool, positions: &[[f32; 3]], faces: &[&[i32]]) -> Vec<u8> {
    let (real, count, index) = match (general, unsigned) {
        (true, _) => ("double", "int", "int"),
        (false, false) => ("float", "uchar", "int"),
        (false, true) => ("float", "uchar", "uint"),
    };
    let mut out = format!(
        "ply\nformat binary_{}_endian 1.0\nelement vertex {}\nproperty {real} x\nproperty {real} y\nproperty {real} z\n\
         element face {}\nproperty list {count} {index} vertex_indices\nend_header\n",
        if big_endian { "big" } else { "little" },
        positions.len(),
        faces.len(),
    )
    .into_bytes();
    let bytes = |b: &[u8], out: &mut Vec<u8>| {
        out.extend(b.iter().rev().take(if big_endian { b.len() } else { 0 }).chain(b.iter().take(if big_endian { 0 } else { b.len() })))
    };
    for p in positions {
        for v in p {
            match general {
                true => bytes(&f64::from(*v).to_le_bytes(), &mut out),
                false => bytes(&v.to_le_bytes(), &mut out),
            }
        }
    }
    for face in faces {
        match general {
            true => bytes(&(face.len() as i32).to_le_bytes(), &mut out),
            false => out.push(face.len() as u8),
        }
        for i in *face {
            bytes(&i.to_le_bytes(), &mut out);
        }
    }
    out
}

#[test]
fn the_bulk_layout_reads_as_the_general_reader_does() {
    let dir = tempfile::tempdir().unwrap();
    let positions = [[0.0, 0.0, 0.0], [1.5, -0.0, 2.25], [0.1, 1e-30, -3.0e7], [f32::MAX, -1.0, 0.5]];
    let triangles: [&[i32]; 3] = [&[0, 1, 2], &[2, 1, 3], &[3, 0, 2]];
    // Triangles are read in bulk; with a quad among them (the general reader's
    // fan) the whole element goes to the general reader.
    let with_quad: [&[i32]; 3] = [&[0, 1, 2], &[0, 1, 2, 3], &[3, 0, 2]];
    for faces in [&triangles[..], &with_quad[..]] {
        for big in [false, true] {
            let general = write_and_load(dir.path(), "general.ply", &bulk_layout(big, false, true, &positions, faces)).unwrap();
            let want = &general.meshes[0];
            assert_eq!(want.positions[3], Vec3::new(f64::from(f32::MAX), -1.0, 0.5));
            for unsigned in [false, true] {
                let bulk = write_and_load(dir.path(), "bulk.ply", &bulk_layout(big, unsigned, false, &positions, faces)).unwrap();
                let got = &bulk.meshes[0];
                let bits = |m: &import::MeshData| m.positions.iter().flat_map(|p| p.to_array().map(f64::to_bits)).collect::<Vec<_>>();
                assert_eq!(bits(got), bits(want), "positions, big endian {big}, uint {unsigned}");
                assert_eq!(got.indices, want.indices);
                assert_eq!((got.normals.is_none(), got.attributes.uvs.is_none(), got.named.is_empty()), (true, true, true));
                assert_eq!(bulk.warnings, general.warnings);
            }
        }
    }
    // What the bulk read leaves to the general reader gives its exact errors.
    let header = |file: &[u8]| file.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let nan = bulk_layout(false, false, false, &[[0.0; 3], [1.0, f32::NAN, 0.0], [0.0; 3]], &[&[0, 1, 2]]);
    assert_eq!(
        error_of(dir.path(), "nan.ply", &nan),
        format!("nan.ply: at byte {}: vertex 1: `y` is NaN, expected a finite number", header(&nan) + 12 + 4)
    );
    let out_of_range = bulk_layout(false, false, false, &[[0.0; 3]; 3], &[&[0, 1, 3]]);
    assert_eq!(
        error_of(dir.path(), "range.ply", &out_of_range),
        format!("range.ply: at byte {}: face 0: vertex index 3 out of range (the file has 3 vertices)", header(&out_of_range) + 36 + 1 + 8)
    );
    let negative = bulk_layout(true, false, false, &[[0.0; 3]; 3], &[&[0, -1, 2]]);
    assert_eq!(
        error_of(dir.path(), "negative.ply", &negative),
        format!("negative.ply: at byte {}: face 0: vertex index -1 out of range (the file has 3 vertices)", header(&negative) + 36 + 1 + 4)
    );
}

#[test]
fn malformed_files_give_one_exact_error() {
    let dir = tempfile::tempdir().unwrap();
    let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty", Vec::new(), "bad.ply: the file is empty"),
        ("not ply", b"solid cube\n".to_vec(), "bad.ply:1:1: expected the magic line `ply` (not a PLY file)"),
        ("no end", b"ply\nformat ascii 1.0\nelement vertex 0\n".to_vec(), "bad.ply:3:1: the PLY header ends without an `end_header` line"),
        (
            "bad format",
            b"ply\nformat utf8 1.0\nend_header\n".to_vec(),
            "bad.ply:2:8: expected `ascii`, `binary_little_endian` or `binary_big_endian`, found `utf8`",
        ),
        (
            "bad type",
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n".to_vec(),
            "bad.ply:4:10: expected a PLY type (char, uchar, short, ushort, int, uint, float, double), found `real`",
        ),
        (
            "10^12 vertices",
            b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0".to_vec(),
            "bad.ply:3:16: element `vertex` claims 1000000000000 items, which need at least 12000000000000 bytes, but only 4 bytes follow the header",
        ),
        (
            "index out of range",
            format!("{head}0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").into_bytes(),
            "bad.ply:13:7: face 0: vertex index 3 out of range (the file has 3 vertices)",
        ),
        ("nan", format!("{head}0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n").into_bytes(), "bad.ply:11:3: vertex 1: `y` is NaN, expected a finite number"),
        (
            "not a number",
            format!("{head}0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n").into_bytes(),
            "bad.ply:12:3: expected property `y` of vertex 2 (a float), found `one`",
        ),
        (
            "ascii truncated",
            format!("{head}0 0 0\n1 0 0\n0 1 0\n3 0 1").into_bytes(),
            "bad.ply:13:6: file ends where a vertex index of face 0 (a int) was expected",
        ),
        (
            "no x",
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nend_header\n1\n".to_vec(),
            "bad.ply:3:1: element `vertex` has no scalar property `x`",
        ),
        (
            "faces first",
            b"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec(),
            "bad.ply:3:1: element `face` comes before element `vertex`; the vertices must come first",
        ),
    ];
    for (what, bytes, expected) in cases {
        assert_eq!(error_of(dir.path(), "bad.ply", &bytes), expected, "case: {what}");
    }
}

#[test]
fn truncated_binary_names_the_byte_offset() {
    let dir = tempfile::tempdir().unwrap();
    let full = binary(false, false);
    // Cut inside the last face's indices: the header is the text before the 4*16 vertex bytes and 2*13 face bytes.
    let body_start = full.len() - 4 * 16 - 2 * 13;
    let cut = &full[..full.len() - 2];
    let last_face = body_start + 4 * 16 + 13;
    assert_eq!(
        error_of(dir.path(), "cut.ply", cut),
        format!("cut.ply: at byte {last_face}: face 1: list `vertex_indices` claims 3 items but the file ends before them")
    );
    // A scalar cut short: the header's minimum (empty lists) fits, the lists' items use up the bytes.
    let mut text = b"ply\nformat binary_big_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement extra 2\nproperty list uchar uchar a\nproperty double b\nend_header\n".to_vec();
    let at = text.len() + 13;
    text.extend([3, 1, 2, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 3, 4, 5]);
    assert_eq!(
        error_of(dir.path(), "short.ply", &text),
        format!("short.ply: at byte {at}: file ends in the middle of property `b` of extra 1: expected 8 bytes, 5 left")
    );
    // A list claiming more items than the file holds is refused before reading them.
    let mut long = full.clone();
    long[body_start + 4 * 16 + 13] = 200;
    assert_eq!(
        error_of(dir.path(), "long.ply", &long),
        format!(
            "long.ply: at byte {}: face 1: list `vertex_indices` claims 200 items but the file ends before them",
            body_start + 4 * 16 + 13
        )
    );
}

#[test]
fn missing_files_and_directories_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("none.ply");
    assert_eq!(import::load(&missing).unwrap_err().to_string(), format!("{}: file not found", missing.display()));
    let sub = dir.path().join("folder.ply");
    std::fs::create_dir(&sub).unwrap();
    assert_eq!(import::load(&sub).unwrap_err().to_string(), format!("{}: is a directory, expected a file", sub.display()));
    if cfg!(unix) {
        // Devices would never end: the guard is checked through a link to /dev/zero named like a mesh.
        let link = dir.path().join("zero.ply");
        if std::os::unix::fs::symlink("/dev/zero", &link).is_ok() {
            assert_eq!(import::load(&link).unwrap_err().to_string(), format!("{}: is a device, expected a mesh file", link.display()));
        }
    }
}

#[test]
fn shared_igea_meshes_load_with_the_readme_counts() {
    let Some(data) = shared_data("shared_igea_meshes_load_with_the_readme_counts") else { return };
    let igea = import::load_mesh(&data.join("meshes/igea.ply")).unwrap();
    assert_eq!((igea.positions.len(), igea.indices.len()), (134_345, 268_686));
    let big = import::load_mesh(&data.join("meshes/igea-1m.ply")).unwrap();
    assert_eq!((big.positions.len(), big.indices.len()), (537_374, 1_074_744));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 256, rng_seed: proptest::test_runner::RngSeed::Fixed(0x1a3f), ..Default::default() })]

    /// Random bytes after a PLY header give a mesh or a `LoadError`, never a panic.
    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..512), header in 0usize..3) {
        let mut file = [b"".as_slice(), b"ply\nformat ascii 1.0\n", b"ply\nformat binary_little_endian 1.0\n"][header].to_vec();
        file.extend(&bytes);
        let _ = import::load_bytes(&common::fake_path("x.ply"), &file);
    }

    /// Mutations of valid ASCII and binary files give a mesh or a `LoadError`, never a panic.
    #[test]
    fn mutated_files_never_panic(edits in common::edits(), cut in proptest::prelude::any::<usize>()) {
        for base in [SQUARE_ASCII.as_bytes().to_vec(), binary(false, true), binary(true, false)] {
            let _ = import::load_bytes(&common::fake_path("x.ply"), &common::mutate(&base, &edits, cut));
        }
    }
}
