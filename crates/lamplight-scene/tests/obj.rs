//! OBJ + MTL importer: files the tests write (quads, negative indices,
//! normals, materials), the shared bunny and Cornell box, and a table of
//! malformed files with the exact error each gives.

use crate::common;

use common::{error_of, shared_data, triangles, write_and_load};
use lamplight_core::materials::{Reflection, Refraction};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_scene::import;

const MTL: &str = "# two materials\nnewmtl red\nKa 0.1 0 0\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 50\nillum 2\n\nnewmtl mirror\nKd 0 0 0\nKs 0.9 0.9 0.9\nillum 3\nmap_Kd wood.png\n";

const OBJ: &str = "mtllib scene.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nusemtl red\nf 1//1 2//1 3//1 4//1\no tri\nv 0 0 1\nv 1 0 1\nv 0 1 1\nusemtl mirror\nf -3 -2 -1\ns off\n";

#[test]
fn quads_negative_indices_and_materials() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.mtl"), MTL).unwrap();
    let imported = write_and_load(dir.path(), "scene.obj", OBJ.as_bytes()).unwrap();
    assert_eq!(imported.meshes.len(), 2);
    let quad = &imported.meshes[0];
    assert_eq!(quad.name.as_deref(), Some("quad"));
    assert_eq!(quad.indices, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(quad.normals.as_ref().map(|n| n[2]), Some(Vec3::Z));
    let tri = &imported.meshes[1];
    assert_eq!(tri.positions, vec![Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0)]);
    assert_eq!(tri.indices, vec![[0, 1, 2]]);
    assert_eq!(tri.normals, None);
    let red = imported.instances[0].material.as_ref().unwrap();
    assert_eq!((red.kd, red.ka, red.ks, red.shininess), (Rgb::new(0.8, 0.1, 0.1), Rgb::new(0.1, 0.0, 0.0), Rgb::splat(0.5), 50.0));
    let mirror = imported.instances[1].material.as_ref().unwrap();
    assert_eq!(mirror.reflection, Reflection::Constant(Rgb::splat(0.9)));
    assert_eq!(mirror.refraction, Refraction::None);
    // The map names a file that is not there: the material is kept without it.
    assert_eq!(imported.warnings.len(), 1, "{:?}", imported.warnings);
    assert!(
        imported.warnings[0]
            .starts_with(&format!("{}:13:1: MTL map_Kd ignored: cannot read texture", dir.path().join("scene.mtl").display()))
            && imported.warnings[0].ends_with("wood.png': no such file"),
        "{:?}",
        imported.warnings
    );
    // Merged in file order.
    let merged = imported.into_mesh();
    assert_eq!(merged.indices, vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]]);
    assert_eq!(merged.normals, None);
}

#[test]
fn malformed_files_give_one_exact_error() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.mtl"), "newmtl a\nKd 0.5 x 0.5\n").unwrap();
    let cases: &[(&str, &str, &str)] = &[
        ("empty", "", "bad.obj: the file is empty"),
        ("nan", "v 0 0 0\nv 1 NaN 0\n", "bad.obj:2:5: expected a finite number (y), found NaN"),
        ("short vertex", "v 0 0\n", "bad.obj:1:6: expected a number (z), found the end of the line"),
        ("word", "v 0 0 zero\n", "bad.obj:1:7: expected a number (z), found `zero`"),
        (
            "index out of range",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
            "bad.obj:4:7: face corner `4`: vertex index 4 out of range (3 vertices defined so far)",
        ),
        (
            "zero index",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
            "bad.obj:4:3: face corner `0`: vertex index 0 out of range (3 vertices defined so far)",
        ),
        (
            "bad normal",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2 3\n",
            "bad.obj:4:3: face corner `1//1`: normal index 1 out of range (0 normals defined so far)",
        ),
        ("two corners", "v 0 0 0\nf 1 1\n", "bad.obj:2:1: a face needs at least 3 vertices, found 2"),
        ("mtl that is a folder", "mtllib sub\n", "bad.obj:1:8: cannot read material library `sub`: is a directory, expected a file"),
        ("bad mtl", "mtllib bad.mtl\n", "bad.mtl:2:8: expected a number (Kd colour), found `x`"),
    ];
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    for (what, text, expected) in cases {
        let got = error_of(dir.path(), "bad.obj", text.as_bytes());
        assert_eq!(got.replace(&format!("{}/", dir.path().display()), ""), *expected, "case: {what}");
    }
}

#[test]
fn a_missing_material_library_is_a_warning_and_the_default_material() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    let imported = write_and_load(dir.path(), "model.obj", obj.as_bytes()).unwrap();
    assert_eq!(triangles(&imported), 1);
    assert!(imported.instances.iter().all(|i| i.material.is_none()), "the default material");
    let obj_path = dir.path().join("model.obj");
    assert_eq!(
        imported.warnings,
        [format!(
            "{}:1:8: material library `{}` not found: its materials are the default material",
            obj_path.display(),
            dir.path().join("gone.mtl").display()
        )],
        "one warning, not one per usemtl"
    );
}

#[test]
fn shared_obj_meshes_load_with_the_readme_counts() {
    let Some(data) = shared_data("shared_obj_meshes_load_with_the_readme_counts") else { return };
    let bunny = import::load_mesh(&data.join("meshes/stanford-bunny.obj")).unwrap();
    assert_eq!((bunny.positions.len(), bunny.indices.len()), (35_947, 69_451));
    let cornell = import::load(&data.join("meshes/cornell-box/CornellBox-Original.obj")).unwrap();
    assert_eq!(triangles(&cornell), 46);
    assert!(cornell.instances.iter().all(|i| i.material.is_some()));
    let light = cornell.instances.iter().filter_map(|i| i.material.as_ref()).find(|m| m.emission != Rgb::ZERO);
    assert!(light.is_some(), "the Cornell box's light has Ke > 0");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 256, rng_seed: proptest::test_runner::RngSeed::Fixed(0x1a3f), ..Default::default() })]

    /// Random bytes give meshes or a `LoadError`, never a panic.
    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..512)) {
        let _ = import::load_bytes(&common::fake_path("x.obj"), &bytes);
    }

    /// Mutations of a valid OBJ (without its `mtllib` line, which would fail at once) never panic.
    #[test]
    fn mutated_files_never_panic(edits in common::edits(), cut in proptest::prelude::any::<usize>()) {
        let base = OBJ.replace("mtllib scene.mtl\n", "").replace("usemtl", "g");
        let _ = import::load_bytes(&common::fake_path("x.obj"), &common::mutate(base.as_bytes(), &edits, cut));
    }
}
