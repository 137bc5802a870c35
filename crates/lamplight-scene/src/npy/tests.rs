//! The reader's errors, word for word, and round trips through the writer.

use std::fs;

use super::*;

/// A version 1.0 file with header dict `dict` and `data`.
fn npy(dict: &str, data: &[u8]) -> Vec<u8> {
    let header = format!("{dict}\n");
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

fn dict(descr: &str, fortran: bool, shape: &str) -> String {
    format!("{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}", if fortran { "True" } else { "False" })
}

fn f32s(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// Writes `bytes` to `name` in `dir` and reads it back as `(N, 3)` floats.
fn floats(dir: &Path, name: &str, bytes: &[u8]) -> Result<Vec<[f32; 3]>, String> {
    let path = dir.join(name);
    fs::write(&path, bytes).unwrap();
    read_rows3_f32(&path).map_err(|e| e.to_string().replace(&format!("{}: ", path.display()), ""))
}

#[test]
fn reads_c_and_fortran_order_and_both_float_types() {
    let dir = tempfile::tempdir().unwrap();
    let rows = vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]];
    assert_eq!(floats(dir.path(), "c.npy", &npy(&dict("<f4", false, "(2, 3)"), &f32s(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]))), Ok(rows.clone()));
    // Fortran order stores the columns one after another.
    assert_eq!(floats(dir.path(), "f.npy", &npy(&dict("<f4", true, "(2, 3)"), &f32s(&[1.0, 4.0, 2.0, 5.0, 3.0, 6.0]))), Ok(rows.clone()));
    let f64s: Vec<u8> = [1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0].iter().flat_map(|x| x.to_le_bytes()).collect();
    assert_eq!(floats(dir.path(), "d.npy", &npy(&dict("<f8", false, "(2, 3)"), &f64s)), Ok(rows));
    assert_eq!(floats(dir.path(), "e.npy", &npy(&dict("<f4", false, "(0, 3)"), &[])), Ok(vec![]));
    // Version 2.0: a u32 header length.
    let header = format!("{}\n", dict("<f4", false, "(1, 3)"));
    let mut v2 = b"\x93NUMPY\x02\x00".to_vec();
    v2.extend_from_slice(&(header.len() as u32).to_le_bytes());
    v2.extend_from_slice(header.as_bytes());
    v2.extend_from_slice(&f32s(&[7.0, 8.0, 9.0]));
    assert_eq!(floats(dir.path(), "v2.npy", &v2), Ok(vec![[7.0, 8.0, 9.0]]));
}

#[test]
fn bad_files_give_one_line_saying_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let six = f32s(&[0.0; 6]);
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (b"not numpy".to_vec(), "not a .npy file (no \\x93NUMPY magic)"),
        (b"\x93NUMPY\x04\x00\x10\x00".to_vec(), "unsupported .npy version 4.0 (expected 1.0, 2.0 or 3.0)"),
        (b"\x93NUMPY\x02\x00\x10\x00".to_vec(), "truncated header length"),
        (b"\x93NUMPY\x01\x00\xff\x00{'descr'".to_vec(), "truncated header: 255 bytes announced, 8 present"),
        (npy(&dict("<c8", false, "(2, 3)"), &six), "dtype '<c8': expected one of '<f4', '<f8', '<i4', '<u4', '<i8', '<u8' (little-endian)"),
        (npy(&dict(">f4", false, "(2, 3)"), &six), "dtype '>f4': expected one of '<f4', '<f8', '<i4', '<u4', '<i8', '<u8' (little-endian)"),
        (npy(&dict("<i4", false, "(2, 3)"), &six), "dtype '<i4': expected float32 or float64 ('<f4', '<f8')"),
        (npy(&dict("<f4", false, "(3, 2)"), &six), "shape (3, 2): expected (N, 3)"),
        (npy(&dict("<f4", false, "(6,)"), &six), "shape (6,): expected (N, 3)"),
        (npy(&dict("<f4", false, "(3, 3)"), &six), "shape (3, 3) of '<f4' needs 36 bytes of data; the file has 24"),
        (npy(&dict("<f4", false, "(1, 3)"), &six), "shape (1, 3) of '<f4' needs 12 bytes of data; the file has 24"),
        // 12 (2^62 + 1) wraps to 12 in 64 bits: one row's worth, were it not checked.
        (
            npy(&dict("<f4", false, "(4611686018427387905, 3)"), &f32s(&[0.0; 3])),
            "shape (4611686018427387905, 3) of '<f4' needs over 2^64 bytes; the file has 12 bytes of data",
        ),
        (npy("{'descr': '<f4', 'shape': (1, 3)}", &six), "bad header: 'descr', 'fortran_order' and 'shape' are all required"),
        (npy(&dict("<f4", false, "(-2, 3)"), &six), "bad header: expected a non-negative integer at byte 51"),
    ];
    for (i, (bytes, want)) in cases.iter().enumerate() {
        assert_eq!(floats(dir.path(), &format!("{i}.npy"), bytes).unwrap_err(), *want, "case {i}");
    }
    let path = dir.path().join("neg.npy");
    fs::write(&path, npy(&dict("<i8", false, "(1, 3)"), &[0i64, 1, -1].iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>())).unwrap();
    assert_eq!(read_rows3_u32(&path).unwrap_err().to_string(), format!("{}: row 0: index -1 is not in 0..2^32", path.display()));
    fs::write(&path, npy(&dict("<f4", false, "(2, 3)"), &six)).unwrap();
    let want = format!("{}: dtype '<f4': expected integers ('<i4', '<u4', '<i8', '<u8')", path.display());
    assert_eq!(read_rows3_u32(&path).unwrap_err().to_string(), want);
}

#[test]
fn only_regular_files_within_the_limit_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.npy");
    fs::write(&path, npy(&dict("<f4", false, "(2, 3)"), &f32s(&[0.0; 6]))).unwrap();
    let len = fs::metadata(&path).unwrap().len();
    assert!(read_limited(&path, len).is_ok());
    let err = read_limited(&path, len - 1).unwrap_err().to_string();
    assert_eq!(err, format!("{}: {len} bytes, more than the {} allowed for a .npy file", path.display(), len - 1));
    let err = read(dir.path()).unwrap_err().to_string();
    assert_eq!(err, format!("{}: is a directory, expected a regular .npy file", dir.path().display()));
    let missing = dir.path().join("missing.npy");
    assert_eq!(read(&missing).unwrap_err().to_string(), format!("{}: cannot read: no such file or directory", missing.display()));
    #[cfg(unix)]
    {
        let zero = Path::new("/dev/zero");
        if zero.exists() {
            assert_eq!(read(zero).unwrap_err().to_string(), "/dev/zero: is a device, expected a regular .npy file");
        }
    }
}

#[test]
fn a_fifo_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("rays.npy");
    match std::process::Command::new("mkfifo").arg(&fifo).status() {
        Ok(status) if status.success() => {}
        _ => {
            eprintln!("skipped: mkfifo is not available");
            return;
        }
    }
    // With no writer, opening the FIFO would block: the answer must come anyway.
    let (send, receive) = std::sync::mpsc::channel();
    let path = fifo.clone();
    std::thread::spawn(move || send.send(read(&path).map(|_| ()).map_err(|e| e.to_string())));
    let answer = receive.recv_timeout(std::time::Duration::from_secs(10)).expect("reading a FIFO returned within 10 s");
    assert_eq!(answer, Err(format!("{}: is a FIFO, expected a regular .npy file", fifo.display())));
}

#[test]
fn written_files_are_aligned_and_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.npy");
    write_f32(&path, &[1.5, f32::INFINITY]).unwrap();
    let bytes = fs::read(&path).unwrap();
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + header_len) % 64, 0);
    let d = dict("<f4", false, "(2,)");
    assert_eq!(&bytes[10..10 + header_len], format!("{d}{}\n", " ".repeat((64 - (11 + d.len()) % 64) % 64)).as_bytes());
    let back = read(&path).unwrap();
    assert_eq!((back.dtype, back.shape.clone(), back.fortran_order), (Dtype::F32, vec![2], false));
    assert_eq!(&bytes[10 + header_len..], f32s(&[1.5, f32::INFINITY]));
    write_i64(&path, &[-1, 7]).unwrap();
    assert_eq!(read(&path).unwrap().dtype, Dtype::I64);
    let rows = [[1.0, -2.0, 3.5], [0.0, 1e-30, f32::MAX]];
    write_rows3_f32(&path, &rows).unwrap();
    assert_eq!(read_rows3_f32(&path).unwrap(), rows);
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary file is left");
    let blocked = path.join("under-a-file.npy");
    let err = write_f32(&blocked, &[1.0]).unwrap_err().to_string();
    assert_eq!(err, format!("cannot write {}: not a directory", blocked.display()));
}
