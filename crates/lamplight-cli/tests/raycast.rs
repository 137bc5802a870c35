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

/// Reads the data of a 1-D .npy written by the program (with the one reader).
fn read_data(path: &Path) -> Vec<u8> {
    let array = lamplight_scene::npy::read(path).unwrap();
    assert_eq!(array.shape.len(), 1, "{}", path.display());
    let bytes = std::fs::read(path).unwrap();
    let item = array.dtype.size();
    bytes[bytes.len() - array.shape[0] * item..].to_vec()
}

fn i64s(bytes: &[u8]) -> Vec<i64> {
    bytes.chunks(8).map(|c| i64::from_le_bytes(c.try_into().unwrap())).collect()
}

#[test]
fn casts_rays_against_a_two_triangle_square() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    // The unit square in z = 0 as two triangles; rays down from z = 2 with a
    // direction of length 2 (parameter 1, distance t = 2), one through the shared
    // diagonal, one missing.
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
    let out = run(&["--prims", p("p.npy").to_str().unwrap(), "--objects", p("obj.npy").to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("build:") && stdout.contains("Mrays/s"), "{stdout}");
    assert_eq!(read_data(&p("t.npy")), f32s(&[2.0, 2.0, f32::INFINITY]), "distances, not parameters");
    let prims = i64s(&read_data(&p("p.npy")));
    assert_eq!(prims[0], 0);
    assert!(prims[1] == 0 || prims[1] == 1, "the diagonal belongs to one of the two");
    assert_eq!(prims[2], -1);
    assert_eq!(i64s(&read_data(&p("obj.npy"))), [0, 0, -1]);
    let entries: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    assert!(entries.iter().all(|name| !name.ends_with(".tmp")), "{entries:?}");

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
    assert_eq!(read_data(&p("t2.npy")), f32s(&[2.0, 2.0, f32::INFINITY]));

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

/// A reader of the figures that has gone (`lamplight raycast ... | head -1`):
/// no panic, exit 0, and the distances still written. Standard output is a
/// pipe whose reading end is closed before the program starts.
#[test]
fn a_closed_standard_output_still_writes_the_answers() {
    let dir = tempfile::tempdir().unwrap();
    let origins = dir.path().join("o.npy");
    write_npy(&origins, "<f4", "(1, 3)", &f32s(&[0.2, 0.2, 1.0]));
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let p = |name: &str| dir.path().join(name);
    write_npy(&p("v.npy"), "<f4", "(3, 3)", &f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]));
    write_npy(&p("i.npy"), "<i4", "(1, 3)", &[0i32, 1, 2].iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>());
    write_npy(&p("d.npy"), "<f4", "(1, 3)", &f32s(&[0.0, 0.0, -1.0]));
    let out = Command::new(env!("CARGO_BIN_EXE_lamplight"))
        .arg("raycast")
        .args(["--vertices", p("v.npy").to_str().unwrap(), "--indices", p("i.npy").to_str().unwrap()])
        .args(["--origins", origins.to_str().unwrap(), "--directions", p("d.npy").to_str().unwrap()])
        .args(["-o", p("t.npy").to_str().unwrap()])
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(read_data(&p("t.npy")), f32s(&[1.0]));
}

/// Runs `lamplight raycast` on the square with `origins` as the origins file.
fn raycast_with_origins(dir: &Path, origins: &Path, extra: &[&str]) -> std::process::Output {
    let p = |name: &str| dir.join(name);
    write_npy(&p("v.npy"), "<f4", "(3, 3)", &f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]));
    write_npy(&p("i.npy"), "<i4", "(1, 3)", &[0i32, 1, 2].iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>());
    write_npy(&p("d.npy"), "<f4", "(1, 3)", &f32s(&[0.0, 0.0, -1.0]));
    Command::new(env!("CARGO_BIN_EXE_lamplight"))
        .arg("raycast")
        .args(["--vertices", p("v.npy").to_str().unwrap(), "--indices", p("i.npy").to_str().unwrap()])
        .args(["--origins", origins.to_str().unwrap(), "--directions", p("d.npy").to_str().unwrap()])
        .args(["-o", p("t.npy").to_str().unwrap()])
        .args(extra)
        .output()
        .unwrap()
}

/// Exit code 2 and exactly one line `lamplight: error: MESSAGE`.
fn assert_usage_error(out: &std::process::Output, message: &str) {
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(String::from_utf8_lossy(&out.stderr), format!("lamplight: error: {message}\n"));
}

#[test]
fn hostile_arrays_are_clean_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("o.npy");
    let shown = o.display().to_string();
    // 12 (2^62 + 1) bytes wraps to 12 in 64 bits: one row, were it not checked.
    write_npy(&o, "<f4", "(4611686018427387905, 3)", &f32s(&[0.2, 0.2, 1.0]));
    let want = format!("{shown}: shape (4611686018427387905, 3) of '<f4' needs over 2^64 bytes; the file has 12 bytes of data");
    assert_usage_error(&raycast_with_origins(dir.path(), &o, &[]), &want);
    write_npy(&o, "<f4", "(2, 3)", &f32s(&[0.2, 0.2, 1.0]));
    let want = format!("{shown}: shape (2, 3) of '<f4' needs 24 bytes of data; the file has 12");
    assert_usage_error(&raycast_with_origins(dir.path(), &o, &[]), &want);
    write_npy(&o, "<u1", "(1, 3)", &[0, 0, 1]);
    let want = format!("{shown}: dtype '<u1': expected one of '<f4', '<f8', '<i4', '<u4', '<i8', '<u8' (little-endian)");
    assert_usage_error(&raycast_with_origins(dir.path(), &o, &[]), &want);
    write_npy(&o, "<f4", "(3,)", &f32s(&[0.2, 0.2, 1.0]));
    assert_usage_error(&raycast_with_origins(dir.path(), &o, &[]), &format!("{shown}: shape (3,): expected (N, 3)"));
    // A good file at the thread limit: t is the distance 1.5 along the unit direction.
    write_npy(&o, "<f4", "(1, 3)", &f32s(&[0.25, 0.25, 1.5]));
    let out = raycast_with_origins(dir.path(), &o, &["--threads", "1024"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(read_data(&dir.path().join("t.npy")), f32s(&[1.5]));
    let out = raycast_with_origins(dir.path(), &o, &["--threads", "1025"]);
    assert_usage_error(&out, "--threads must be at most 1024 (0 uses all cores), got 1025");
    if Path::new("/dev/zero").exists() {
        let out = raycast_with_origins(dir.path(), Path::new("/dev/zero"), &[]);
        assert_usage_error(&out, "/dev/zero: is a device, expected a regular .npy file");
    }
}

#[test]
fn a_fifo_as_input_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo.npy");
    match Command::new("mkfifo").arg(&fifo).status() {
        Ok(status) if status.success() => {}
        _ => {
            eprintln!("skipped: mkfifo is not available");
            return;
        }
    }
    // No writer ever opens the FIFO: a reader that opened it would wait forever.
    let start = std::time::Instant::now();
    let out = raycast_with_origins(dir.path(), &fifo, &[]);
    assert_usage_error(&out, &format!("{}: is a FIFO, expected a regular .npy file", fifo.display()));
    assert!(start.elapsed().as_secs() < 30);
}

#[test]
fn help_states_the_units() {
    let out = Command::new(env!("CARGO_BIN_EXE_lamplight")).args(["raycast", "--help"]).output().unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains("T[i] is the distance s |D[i]| to the nearest hit"), "{help}");
    assert!(help.contains("--objects <OBJ.npy>") && help.contains("at most 1024"), "{help}");
}
