//! Issue 30 ("Budgets and doors"), the amplification half: each small input
//! that grows (doubling `$name`s, include fan-out, a mesh or image whose header
//! declares far more than the file holds, a zlib bomb) and each special file
//! named as a mesh, with the one line it must print, exit code 2, and a bound
//! on the time it takes. Inputs are made here; nothing is read from outside.
//! See: issue 30 in the project's tracker.

use std::fs;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Runs `lamplight ARGS` in `dir`; fails the test past 5 seconds.
fn lamplight(dir: &Path, args: &[&str]) -> Output {
    let start = Instant::now();
    let out =
        Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs");
    assert!(start.elapsed() < Duration::from_secs(5), "lamplight {args:?} took {:?}", start.elapsed());
    out
}

/// Runs each case; collects every mismatch of exit code or of the whole stderr.
fn check(dir: &Path, cases: &[(Vec<&str>, String)]) {
    let mut failures = Vec::new();
    for (args, message) in cases {
        let out = lamplight(dir, args);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let expected = format!("lamplight: error: {message}\n");
        if out.status.code() != Some(2) || err != expected {
            let args: Vec<String> = args.iter().map(|a| if a.len() > 80 { format!("{}...", &a[..80]) } else { a.to_string() }).collect();
            failures.push(format!("lamplight {args:?}\n  expected (2): {expected}  got ({:?}):      {err}", out.status.code()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

const SENSOR: &str = "<sensor type=\"perspective\"/>";

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>\n")
}

fn render(file: &str) -> Vec<&str> {
    vec!["render", file, "-q", "--width", "8", "--height", "8", "-o", "out.png"]
}

#[test]
fn substitution_is_bounded_per_value_and_per_scene() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 32 chained defaults, each twice the last: 2^33 bytes unbounded.
    let mut lines = vec!["<default name=\"a0\" value=\"xx\"/>".to_string()];
    lines.extend((1..=32).map(|i| format!("<default name=\"a{i}\" value=\"$a{}$a{}\"/>", i - 1, i - 1)));
    lines.push(SENSOR.to_string());
    fs::write(d.join("double.xml"), scene(&lines.join("\n"))).unwrap();
    // A 130 KB -D value (an argument may have at most 128 KiB) named 200,000 times: 26 GB unbounded.
    let refs = "<float name=\"x\" value=\"$big\"/>\n".repeat(200_000);
    fs::write(d.join("many.xml"), scene(&format!("{SENSOR}\n<bsdf type=\"diffuse\" id=\"b\">\n{refs}</bsdf>"))).unwrap();
    let big = format!("big={}", "7".repeat(130_000));
    let mut many = render("many.xml");
    many.extend(["-D", &big]);
    check(
        d,
        &[
            (
                render("double.xml"),
                "double.xml:22:28: substituting the $names would make this value 2097152 bytes long, expected at most 1048576 (1 MiB)"
                    .into(),
            ),
            (
                many,
                "many.xml:133:24: substituting the $names would make the scene's values more than 16777216 bytes together \
                 (a long value named many times), expected at most 16 MiB"
                    .into(),
            ),
        ],
    );
}

#[test]
fn includes_are_bounded_in_number_and_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Eleven files, each including the next four times: 4^10 includes.
    for i in 0..10 {
        let body = format!("<include filename=\"f{}.xml\"/>\n", i + 1).repeat(4);
        fs::write(d.join(format!("f{i}.xml")), scene(&body)).unwrap();
    }
    fs::write(d.join("f10.xml"), scene("<bsdf type=\"diffuse\"/>")).unwrap();
    fs::write(d.join("fan.xml"), scene(&format!("<include filename=\"f0.xml\"/>\n{SENSOR}"))).unwrap();
    // One 15 MiB file (under the 16 MiB a file may have) included 300 times.
    let mut large = fs::File::create(d.join("large.xml")).unwrap();
    write!(large, "<scene version=\"3.0.0\"><!--{}--></scene>", " ".repeat(15 << 20)).unwrap();
    drop(large);
    fs::write(d.join("wide.xml"), scene(&format!("{SENSOR}\n{}", "<include filename=\"large.xml\"/>\n".repeat(300)))).unwrap();
    check(
        d,
        &[
            (
                render("fan.xml"),
                "fan.xml: f8.xml:5:20: include: more than 1024 includes in one scene (each time a file is included counts), expected at most 1024"
                    .into(),
            ),
            (
                render("wide.xml"),
                "wide.xml:7:20: include: \"large.xml\" (15728678 bytes) would make the scene read more than 67108864 bytes of XML \
                 (the main file and each included file, each time it is included), expected at most 64 MiB"
                    .into(),
            ),
        ],
    );
}

/// Mitsuba 3.9.1 resolves an `<include>` beside the file that includes it
/// first (checked with `mi.load_file` on this layout: it loads `sub/b.xml`'s
/// sphere, not `b.xml`'s cube), while other file names stay relative to the
/// scene's folder.
#[test]
fn a_nested_include_is_found_beside_the_file_that_includes_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::create_dir(d.join("sub")).unwrap();
    fs::write(d.join("main.xml"), scene(&format!("{SENSOR}\n<include filename=\"sub/a.xml\"/>"))).unwrap();
    fs::write(d.join("sub/a.xml"), scene("<include filename=\"b.xml\"/>")).unwrap();
    fs::write(d.join("sub/b.xml"), scene("<shape type=\"sphere\"><float name=\"radius\" value=\"-1\"/></shape>")).unwrap();
    fs::write(d.join("b.xml"), scene("<shape type=\"cube\"/>")).unwrap();
    let out = lamplight(d, &render("main.xml"));
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    // The sphere of sub/b.xml was read: its bad radius is the error.
    assert!(err.starts_with("lamplight: error: main.xml: ") && err.contains("sub/b.xml:2:") && err.contains("radius"), "{err}");
    assert_eq!(out.status.code(), Some(2));
}

/// A `.serialized` shape: `vertices` and `triangles` declared, then `body`
/// bytes of zeros, all zlib-compressed.
fn serialized(vertices: u64, triangles: u64, body: u64) -> Vec<u8> {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    z.write_all(&0u32.to_le_bytes()).unwrap();
    z.write_all(b"m\0").unwrap();
    z.write_all(&vertices.to_le_bytes()).unwrap();
    z.write_all(&triangles.to_le_bytes()).unwrap();
    let zeros = vec![0u8; 1 << 20];
    let mut left = body;
    while left > 0 {
        let n = left.min(zeros.len() as u64) as usize;
        z.write_all(&zeros[..n]).unwrap();
        left -= n as u64;
    }
    let mut file = vec![0x1C, 0x04, 4, 0];
    file.extend(z.finish().unwrap());
    file.extend(0u64.to_le_bytes());
    file.extend(1u32.to_le_bytes());
    file
}

/// An 8192x8192 RGBA16 PNG of zeros (about 520 KB) padded to 680 KB by a
/// comment, so that it passes the pixels-per-byte check as the did.
fn large_png() -> Vec<u8> {
    fn chunk(out: &mut Vec<u8>, kind: &[u8], data: &[u8]) {
        out.extend((data.len() as u32).to_be_bytes());
        let mut crc = flate2::Crc::new();
        crc.update(kind);
        crc.update(data);
        out.extend(kind);
        out.extend(data);
        out.extend(crc.sum().to_be_bytes());
    }
    let (w, h) = (8192u32, 8192u32);
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    let row = vec![0u8; 1 + w as usize * 8];
    for _ in 0..h {
        z.write_all(&row).unwrap();
    }
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = w.to_be_bytes().to_vec();
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([16, 6, 0, 0, 0]);
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(&mut out, b"tEXt", &[b"Comment\0".as_slice(), &[b'x'; 160_000]].concat());
    chunk(&mut out, b"IDAT", &z.finish().unwrap());
    chunk(&mut out, b"IEND", &[]);
    out
}

#[test]
fn declared_sizes_are_checked_against_the_memory_budget_before_allocating() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let n = 1u64 << 24;
    // Refused from the declared counts, before the data would be inflated: the
    // issue's 587 KB file of zeros behind the same header goes the same way.
    fs::write(d.join("big.serialized"), serialized(n, n, 0)).unwrap();
    // The 48 bytes declared and 64 MiB more: inflating stops at 49.
    fs::write(d.join("bomb.serialized"), serialized(3, 1, 48 + (64 << 20))).unwrap();
    for name in ["big", "bomb"] {
        let shape = format!("<shape type=\"serialized\"><string name=\"filename\" value=\"{name}.serialized\"/></shape>");
        fs::write(d.join(format!("{name}.xml")), scene(&format!("{SENSOR}\n{shape}"))).unwrap();
    }
    fs::write(d.join("big.png"), large_png()).unwrap();
    let texture =
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[materials.a]\ncolor = { type = \"image\", file = \"big.png\" }\n\
                   [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"a\"\n";
    fs::write(d.join("tex.toml"), texture).unwrap();
    // A 1024x1024 gradient EXR: float texels are counted from its header too.
    let mut gradient = lamplight_core::film::Image::new(1024, 1024);
    for (i, p) in gradient.pixels.iter_mut().enumerate() {
        *p = [(i % 1024) as f32 / 1024.0, (i / 1024) as f32 / 1024.0, 0.5];
    }
    lamplight_scene::image_io::write_image_as(&d.join("big.exr"), &gradient, Default::default()).unwrap();
    fs::write(d.join("exr.toml"), texture.replace("big.png", "big.exr")).unwrap();
    fs::write(d.join("tex-budget.toml"), format!("[render]\nmemory_budget = \"600M\"\n{texture}")).unwrap();
    // The same EXR as an environment map: its f64 pixels, sampling distribution
    // and decoding buffers, 80 bytes a pixel, from the header.
    let sky = "environment = { file = \"big.exr\" }\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
               [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n";
    fs::write(d.join("sky.toml"), sky).unwrap();
    let big_sky = |shown: &str| format!("environment map '{shown}' (1024x1024 pixels) needs 80.0 MiB of memory");
    let budget = |file: &'static str, size: &'static str| [render(file), vec!["--memory-budget", size]].concat();
    let raise = "raise it with --memory-budget (or [render] memory_budget in a TOML scene)";
    // 16-bit texels are kept as 16-bit (512 MiB), with a third more for the MIP levels.
    let big_png = "texture 'big.png' (8192x8192 pixels) needs 682.7 MiB of memory";
    check(
        d,
        &[
            (
                budget("big.xml", "4G"),
                format!(
                    "big.xml:3:1: shape \"serialized\": \"big.serialized\": a mesh of 16777216 vertices and 16777216 triangles needs \
                     11.5 GiB of memory, and 36 bytes of the memory budget of 4.0 GiB is in use; {raise}"
                ),
            ),
            (
                render("bomb.xml"),
                "bomb.xml:3:1: shape \"serialized\": the compressed mesh data holds more than the 48 bytes its header declares \
                 (3 vertices, 1 triangles)"
                    .into(),
            ),
            (
                budget("tex.toml", "512M"),
                format!("tex.toml:6:34: material \"a\": color: file: {big_png}, more than the memory budget of 512.0 MiB; {raise}"),
            ),
            (
                budget("exr.toml", "32M"),
                format!(
                    "exr.toml:6:34: material \"a\": color: file: texture 'big.exr' (1024x1024 pixels) needs 33.3 MiB of memory, \
                     more than the memory budget of 32.0 MiB; {raise}"
                ),
            ),
            (
                budget("sky.toml", "32M"),
                format!(
                    "sky.toml:1:24: scene: environment: file: {}, more than the memory budget of 32.0 MiB; {raise}",
                    big_sky("big.exr")
                ),
            ),
            (
                [render("spheres"), vec!["--environment", "big.exr", "--memory-budget", "32M"]].concat(),
                // The film of 8x8 pixels came first.
                format!("{}, and 6.0 KiB of the memory budget of 32.0 MiB is in use; {raise}", big_sky("big.exr")),
            ),
            (
                render("tex-budget.toml"),
                format!("tex-budget.toml:8:34: material \"a\": color: file: {big_png}, more than the memory budget of 600.0 MiB; {raise}"),
            ),
            (
                budget("tex.toml", "1M"),
                "invalid value '1M' for '--memory-budget <SIZE>': must be at least 16.0 MiB (16M), got \"1M\"".into(),
            ),
            (
                vec!["render", "spheres", "-q", "--width", "4096", "--height", "4096", "--memory-budget", "256M"],
                format!("the film of 4096x4096 pixels needs 1.5 GiB of memory, more than the memory budget of 256.0 MiB; {raise}"),
            ),
        ],
    );
    assert!(!d.join("out.png").exists(), "nothing rendered");
}

/// Two glass shells around the camera, depth 20: one sample's Whitted tree is
/// about 36,000 rays (22 MB recorded, 650 MB as one JSON string), where the
/// recorder may hold 8 MiB of the budget's 256 MiB share (the rest for the
/// JSON form) or less when less is left.
#[test]
fn the_explain_recorder_draws_on_the_memory_budget() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let glass = "kd = [0, 0, 0]\nka = [0, 0, 0]\nreflection = { type = \"dielectric\", ior = 1.5 }\nrefraction = { type = \"fresnel\", ior = 1.5 }\n";
    let shells: String = [10, 20]
        .iter()
        .map(|r| format!("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = {r}\nmaterial = \"glass\"\n"))
        .collect();
    let toml =
        format!("[render]\nmax_depth = 20\n[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\nvfov = 40\n[materials.glass]\n{glass}{shells}");
    fs::write(d.join("deep.toml"), toml).unwrap();
    let explain =
        |extra: &[&'static str]| [vec!["explain", "deep.toml", "--pixel", "4,4", "--width", "8", "--height", "8"], extra.to_vec()].concat();
    let summarised = |args: Vec<&str>, allowance: u64| {
        let out = lamplight(d, &args);
        assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
        let tree: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(tree["samples"].as_array().unwrap().len(), 0, "the one sample's tree does not fit");
        let u = &tree["unrecorded"];
        assert_eq!((u["first"].as_u64(), u["count"].as_u64()), (Some(0), Some(1)));
        assert_eq!(u["why"]["memory_allowance"].as_u64(), Some(allowance));
    };
    summarised(explain(&["--json"]), 8 << 20);
    // A 16 MiB budget leaves the recorder a 32nd of what the film (96 bytes a
    // pixel) and the BVH (256 bytes an object) have not taken.
    let used = 8 * 8 * 96 + 2 * 256;
    summarised(explain(&["--json", "--memory-budget", "16M"]), ((16u64 << 20) - used) / 32);
    let mut text = lamplight(d, &explain(&[]));
    assert_eq!(text.status.code(), Some(0));
    text.stdout.retain(|&b| b != b'\n');
    assert!(String::from_utf8_lossy(&text.stdout).contains(
        "samples 0 to 0: traced, not recorded: their records would pass the explanation's memory allowance of 8.0 MiB \
         (a larger memory budget records more)"
    ));
    check(
        d,
        &[(
            explain(&["--sample", "0"]),
            "--sample 0's record needs more than the 256.0 MiB of the memory budget the explain recorder may take (8.0 MiB for \
             the record, the rest for its JSON form); raise it with --memory-budget"
                .into(),
        )],
    );
}

#[cfg(unix)]
#[test]
fn a_file_that_is_not_a_regular_file_is_named_for_what_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::create_dir(d.join("dir.obj")).unwrap();
    let fifo = Command::new("mkfifo").arg(d.join("fifo.obj")).status().is_ok_and(|s| s.success());
    let mut cases = Vec::new();
    let mut files = vec![("dir", "dir.obj"), ("zero", "/dev/zero"), ("passwd", "/etc/passwd")];
    if fifo {
        files.push(("fifo", "fifo.obj"));
    }
    for (name, file) in &files {
        let xml = scene(&format!("{SENSOR}\n<shape type=\"obj\"><string name=\"filename\" value=\"{file}\"/></shape>"));
        fs::write(d.join(format!("{name}.xml")), xml).unwrap();
        let toml = format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[meshes.m]\nfile = \"{file}\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n");
        fs::write(d.join(format!("{name}.toml")), toml).unwrap();
    }
    let at = "3:50";
    let no_extension = "has no file extension, expected a mesh file named for its format (.obj, .ply, .gltf, .glb)";
    cases.push((render("dir.xml"), format!("dir.xml:{at}: \"dir.obj\" is a directory, expected a file")));
    cases.push((render("zero.xml"), format!("zero.xml:{at}: \"/dev/zero\" is a device, not a regular file (expected a file)")));
    cases.push((render("passwd.xml"), format!("passwd.xml:{at}: mesh \"mesh_1\": /etc/passwd: {no_extension}")));
    cases.push((render("dir.toml"), "dir.toml:6:8: mesh \"m\": file \"dir.obj\" is a directory, expected a mesh file".into()));
    cases.push((
        render("zero.toml"),
        "zero.toml:6:8: mesh \"m\": file \"/dev/zero\" is a device, not a regular file (expected a mesh file)".into(),
    ));
    cases.push((render("passwd.toml"), format!("passwd.toml:6:8: mesh \"m\": /etc/passwd: {no_extension}")));
    if fifo {
        // Returns at once: the FIFO is never opened.
        cases.push((render("fifo.xml"), format!("fifo.xml:{at}: \"fifo.obj\" is a FIFO, not a regular file (expected a file)")));
        cases.push((
            render("fifo.toml"),
            "fifo.toml:6:8: mesh \"m\": file \"fifo.obj\" is a FIFO, not a regular file (expected a mesh file)".into(),
        ));
    }
    check(d, &cases);
}
