//! `lamplight raycast` end to end: small .npy files in, answers out, bad input exits 2.

use std::path::Path;
use std::process::Command;

/// A C-ordered little-endian .npy of `shape` holding `data` (already bytes).
fn write_npy(path: &Path, descr: &str, shape: &str, data: &[u8]) {
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    std::fs::write(path, out).unwrap();
}

fn f32s(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// Reads the data of a 1-D .npy written by the program.
fn read_data(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[10 + header_len..].to_vec()
}

#[test]
fn casts_rays_against_a_two_triangle_square() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    // The unit square in z = 0 as two triangles; rays down from z = 2 with a
    // direction of length 2 (t = 1), one through the shared diagonal, one missing.
    write_npy(&p("v.npy"), "<f4", "(4, 3)", &f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]));
    write_npy(&p("i.npy"), "<i8", "(2, 3)", &[0i64, 1, 2, 0, 2, 3].iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>());
    write_npy(&p("o.npy"), "<f4", "(3, 3)", &f32s(&[0.8, 0.2, 2.0, 0.5, 0.5, 2.0, 3.0, 3.0, 2.0]));
    write_npy(&p("d.npy"), "<f4", "(3, 3)", &f32s(&[0.0, 0.0, -2.0, 0.0, 0.0, -2.0, 0.0, 0.0, -2.0]));
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_lamplight"))
            .arg("raycast")
            .args(["--vertices", p("v.npy").to_str().unwrap(), "--indices", p("i.npy").to_str().unwrap()])
            .args(["--origins", p("o.npy").to_str().unwrap(), "--directions", p("d.npy").to_str().unwrap()])
            .args(["-o", p("t.npy").to_str().unwrap(), "--threads", "2"])
            .args(extra)
            .output()
            .unwrap()
    };
    let out = run(&["--prims", p("p.npy").to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("build:") && stdout.contains("Mrays/s"), "{stdout}");
    assert_eq!(read_data(&p("t.npy")), f32s(&[1.0, 1.0, f32::INFINITY]));
    let prims: Vec<i64> = read_data(&p("p.npy")).chunks(8).map(|c| i64::from_le_bytes(c.try_into().unwrap())).collect();
    assert_eq!(prims[0], 0);
    assert!(prims[1] == 0 || prims[1] == 1, "the diagonal belongs to one of the two");
    assert_eq!(prims[2], -1);

    // The same square as a PLY file through --mesh: the same answers.
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
               element face 2\nproperty list uchar int vertex_indices\nend_header\n\
               0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    std::fs::write(p("square.ply"), ply).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_lamplight"))
        .args(["raycast", "--mesh", p("square.ply").to_str().unwrap()])
        .args(["--origins", p("o.npy").to_str().unwrap(), "--directions", p("d.npy").to_str().unwrap()])
        .args(["-o", p("t2.npy").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(read_data(&p("t2.npy")), f32s(&[1.0, 1.0, f32::INFINITY]));

    let out = run(&["--any-hit"]);
    assert!(out.status.success());
    assert_eq!(read_data(&p("t.npy")), f32s(&[0.0, 0.0, f32::INFINITY]));

    // Bad inputs: wrong shape, wrong dtype, mismatched lengths, missing file.
    write_npy(&p("o.npy"), "<f4", "(9,)", &f32s(&[0.0; 9]));
    assert_eq!(run(&[]).status.code(), Some(2));
    write_npy(&p("o.npy"), "<i4", "(3, 3)", &[0u8; 36]);
    assert_eq!(run(&[]).status.code(), Some(2));
    write_npy(&p("o.npy"), "<f4", "(2, 3)", &f32s(&[0.0; 6]));
    let out = run(&[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("2 origins but 3 directions"));
    std::fs::remove_file(p("o.npy")).unwrap();
    assert_eq!(run(&[]).status.code(), Some(2));
}
