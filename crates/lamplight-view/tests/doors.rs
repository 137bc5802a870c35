//! The viewer's doors from outside (issue 30): foreign `Host` and `Origin`
//! headers are refused, no file of the scene's folder is served, an oversized
//! WebSocket message is closed with 1009, saves go into the save folder only,
//! and an explanation of a million samples records 64.
//! See: docs/view.md, "Security".

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::{Duration, Instant};

use lamplight_scene::request::Request;
use lamplight_view::{ViewOptions, Viewer};

fn start(scene: &str, save_dir: Option<&Path>) -> Viewer {
    let request = Request { width: Some(32), ..Request::default() };
    let listen = Some("127.0.0.1:0".parse().unwrap());
    Viewer::start(ViewOptions { scene: scene.into(), listen, request, save_dir: save_dir.map(Path::to_path_buf) }).unwrap()
}

/// Sends `head` (a request line and headers, without the blank line) and
/// returns the connection and the response's head.
pub fn ask(viewer: &Viewer, head: &str) -> (TcpStream, String) {
    let mut stream = TcpStream::connect(viewer.address).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    write!(stream, "{head}\r\n\r\n").unwrap();
    let mut bytes = Vec::new();
    let mut byte = [0u8; 1];
    while !bytes.ends_with(b"\r\n\r\n") && stream.read(&mut byte).unwrap_or(0) == 1 {
        bytes.push(byte[0]);
    }
    (stream, String::from_utf8_lossy(&bytes).into_owned())
}

pub fn status(head: &str) -> u16 {
    head.split(' ').nth(1).and_then(|s| s.parse().ok()).unwrap_or(0)
}

pub const UPGRADE: &str =
    "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==";

#[test]
fn foreign_hosts_and_origins_are_refused() {
    let viewer = start("business-card", None);
    let (t, port) = (viewer.app.token.clone(), viewer.address.port());
    let get = |target: &str, host: &str, extra: &str| {
        let extra = if extra.is_empty() { String::new() } else { format!("\r\n{extra}") };
        status(&ask(&viewer, &format!("GET {target} HTTP/1.1\r\nHost: {host}\r\nConnection: close{extra}")).1)
    };
    // DNS rebinding: the token is right, the name is not this server's.
    assert_eq!(get(&format!("/?token={t}"), &format!("evil.example:{port}"), ""), 403);
    assert_eq!(get("/favicon.ico", &format!("evil.example:{port}"), ""), 403);
    for host in [format!("localhost:{port}"), format!("127.0.0.1:{port}"), format!("[::1]:{port}")] {
        assert_eq!(get(&format!("/?token={t}"), &host, ""), 200, "{host}");
    }
    let (_, head) = ask(&viewer, &format!("GET /?token={t} HTTP/1.1\r\nHost: evil.example:{port}\r\nConnection: close"));
    assert!(head.starts_with("HTTP/1.1 403"), "{head}");
    // A WebSocket from another page, with the token: refused; from its own page: accepted.
    let ws = |origin: &str| {
        status(&ask(&viewer, &format!("GET /ws?token={t} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n{UPGRADE}\r\nOrigin: {origin}")).1)
    };
    assert_eq!(ws("http://evil.example"), 403);
    assert_eq!(ws("null"), 403);
    assert_eq!(ws(&format!("http://localhost:{port}")), 403, "another name of the server is another origin");
    assert_eq!(ws(&format!("http://127.0.0.1:{port}")), 101);
    // Issue 27: the favicon, which browsers ask for without the token, is not a 403.
    assert_eq!(get("/favicon.ico", &format!("127.0.0.1:{port}"), ""), 204);
}

#[test]
fn no_file_of_the_scene_s_folder_is_served() {
    let outer = tempfile::tempdir().unwrap();
    let luxo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/luxo.toml");
    std::fs::copy(luxo, outer.path().join("luxo.toml")).unwrap();
    std::fs::write(outer.path().join(".env"), "SECRET=1").unwrap();
    let viewer = start(&outer.path().join("luxo.toml").display().to_string(), None);
    let t = viewer.app.token.clone();
    // The page fetches nothing from the scene's folder: the scene file, its
    // dotfiles, anything, is "not found".
    for name in ["luxo.toml", ".env", "x/../.env"] {
        let (_, head) = ask(&viewer, &format!("GET /files/{name}?token={t} HTTP/1.1\r\nHost: {}\r\nConnection: close", viewer.address));
        assert_eq!(status(&head), 404, "{name}: {head}");
    }
}

/// Reads one WebSocket frame from the server (unmasked): its opcode and payload.
pub fn frame(stream: &mut TcpStream) -> (u8, Vec<u8>) {
    let mut head = [0u8; 2];
    stream.read_exact(&mut head).unwrap();
    let mut len = (head[1] & 0x7f) as usize;
    if len == 126 {
        let mut l = [0u8; 2];
        stream.read_exact(&mut l).unwrap();
        len = u16::from_be_bytes(l) as usize;
    } else if len == 127 {
        let mut l = [0u8; 8];
        stream.read_exact(&mut l).unwrap();
        len = u64::from_be_bytes(l) as usize;
    }
    let mut payload = vec![0u8; len];
    stream.read_exact(&mut payload).unwrap();
    (head[0] & 0x0f, payload)
}

#[test]
fn an_oversized_message_is_closed_with_1009() {
    let viewer = start("business-card", None);
    let t = viewer.app.token.clone();
    let (mut stream, head) = ask(&viewer, &format!("GET /ws?token={t} HTTP/1.1\r\nHost: {}\r\n{UPGRADE}", viewer.address));
    assert_eq!(status(&head), 101, "{head}");
    // One masked text frame of 70,000 bytes (the limit is 65,536).
    let n = 70_000u64;
    let mut message = vec![0x81, 0x80 | 127];
    message.extend_from_slice(&n.to_be_bytes());
    message.extend_from_slice(&[0, 0, 0, 0]);
    message.extend(std::iter::repeat_n(b' ', n as usize));
    stream.write_all(&message).unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let (opcode, payload) = frame(&mut stream);
        if opcode == 0x8 {
            assert_eq!(u16::from_be_bytes([payload[0], payload[1]]), 1009, "{payload:?}");
            assert_eq!(&payload[2..], b"a message is at most 65536 bytes");
            break;
        }
        assert!(Instant::now() < deadline, "no close frame");
    }
}

/// Sends `message` to the page's handler; returns the first answer.
fn answer(viewer: &Viewer, message: serde_json::Value) -> serde_json::Value {
    let runtime = tokio::runtime::Builder::new_multi_thread().worker_threads(1).enable_all().build().unwrap();
    let (tx, mut rx) = tokio::sync::mpsc::channel(4);
    let explainer = lamplight_view::explainer::Explainer::default();
    runtime.block_on(async {
        if let Some(reply) = lamplight_view::messages::handle(&viewer.app, &message.to_string(), &tx, &explainer) {
            return serde_json::from_str(&reply).unwrap();
        }
        let reply = tokio::time::timeout(Duration::from_secs(60), rx.recv()).await.unwrap().unwrap();
        serde_json::from_str(&reply).unwrap()
    })
}

fn wait_for_frame(viewer: &Viewer) {
    let start = Instant::now();
    while viewer.app.latest_frame().is_none() {
        assert!(start.elapsed() < Duration::from_secs(30));
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[test]
fn saves_go_into_the_save_folder_and_replace_only_the_viewer_s_files() {
    let home = tempfile::tempdir().unwrap();
    std::fs::create_dir(home.path().join(".cargo")).unwrap();
    std::fs::write(home.path().join(".cargo/config.toml"), "[build]\n").unwrap();
    std::fs::write(home.path().join("notes.toml"), "mine\n").unwrap();
    let viewer = start("business-card", Some(home.path()));
    wait_for_frame(&viewer);
    let save =
        |name: &str, replace: Option<&str>| answer(&viewer, serde_json::json!({ "type": "save_camera", "name": name, "replace": replace }));
    let folder = home.path().canonicalize().unwrap().display().to_string();
    assert_eq!(
        save(".cargo/config.toml", None)["message"],
        format!("'.cargo/config.toml' is refused: a name, not a path; the viewer saves into {folder} only")
    );
    assert_eq!(
        save(".config.toml", None)["message"],
        "'.config.toml' is refused: names starting with '.' (hidden and configuration files) are not saved"
    );
    let refused = save("notes.toml", None);
    assert_eq!(refused["message"], "'notes.toml' exists and the viewer did not write it; to replace it, send \"replace\": \"notes.toml\"");
    assert_eq!(refused["exists"], "notes.toml");
    assert_eq!(save("notes.toml", Some("other.toml"))["type"], "error", "replace must name the file");
    assert_eq!(std::fs::read_to_string(home.path().join("notes.toml")).unwrap(), "mine\n");
    assert_eq!(save("notes.toml", Some("notes.toml"))["type"], "saved", "the page asked, naming it");
    assert!(std::fs::read_to_string(home.path().join("notes.toml")).unwrap().starts_with("[camera]"));
    assert_eq!(save("camera.toml", None)["type"], "saved");
    assert_eq!(save("camera.toml", None)["type"], "saved", "the viewer's own file is replaced without asking");
    assert_eq!(std::fs::read_to_string(home.path().join(".cargo/config.toml")).unwrap(), "[build]\n");
}

#[test]
fn a_million_sample_explanation_records_64() {
    // See: issue 30 (spp = 1048576 and one click aborted the server).
    let viewer = start("business-card", None);
    wait_for_frame(&viewer);
    let frame = viewer.app.latest_frame().unwrap();
    let mut job = frame.wanted.job.clone();
    job.options.spp = 1 << 20;
    let loaded = lamplight_view::reload::load("business-card", &Request::default()).unwrap();
    let wanted = lamplight_view::renderer::Wanted { generation: 1, loaded: Arc::new(loaded), camera: None, job, preview: false };
    let start = Instant::now();
    let tree = wanted.explain(16, 16, Arc::new(AtomicBool::new(false))).unwrap();
    eprintln!("1,048,576 samples explained in {:?}", start.elapsed());
    assert_eq!(tree["samples"].as_array().unwrap().len(), 64);
    assert_eq!(tree["unrecorded"]["count"], (1 << 20) - 64);
    assert!(tree.to_string().len() < 1 << 20, "the answer is under a megabyte");
    // Cancelled, it stops at once and answers nothing.
    let err = wanted.explain(16, 16, Arc::new(AtomicBool::new(true))).unwrap_err();
    assert_eq!(err, "cannot render: cancelled");
}
