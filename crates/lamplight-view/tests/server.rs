//! The viewer's server from outside: the token and path rules over real HTTP,
//! and the limits on its settings.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::time::Duration;

use lamplight_scene::request::Request;
use lamplight_view::{ViewOptions, Viewer};

fn start(scene: &str, width: u32) -> Viewer {
    let request = Request { width: Some(width), ..Request::default() };
    Viewer::start(ViewOptions { scene: scene.into(), listen: Some("127.0.0.1:0".parse().unwrap()), request, save_dir: None }).unwrap()
}

/// A raw HTTP/1.1 GET of `target` exactly as written (no client normalises it):
/// the status code and the body.
fn get(viewer: &Viewer, target: &str, extra: &str) -> (u16, String) {
    let mut stream = TcpStream::connect(viewer.address).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    let connection = if extra.contains("Connection:") { "" } else { "Connection: close\r\n" };
    write!(stream, "GET {target} HTTP/1.1\r\nHost: {}\r\n{connection}{extra}\r\n", viewer.address).unwrap();
    let mut response = String::new();
    if extra.contains("Upgrade") {
        // A switched protocol keeps the connection open: read the head only.
        let mut bytes = Vec::new();
        let mut byte = [0u8; 1];
        while !bytes.ends_with(b"\r\n\r\n") && stream.read(&mut byte).unwrap() == 1 {
            bytes.push(byte[0]);
        }
        response = String::from_utf8_lossy(&bytes).into_owned();
    } else {
        stream.read_to_string(&mut response).unwrap();
    }
    let status = response.split(' ').nth(1).and_then(|s| s.parse().ok()).unwrap_or(0);
    let body = response.split_once("\r\n\r\n").map(|(_, b)| b.to_string()).unwrap_or_default();
    (status, body)
}

fn scene_folder() -> (tempfile::TempDir, String) {
    let outer = tempfile::tempdir().unwrap();
    let folder = outer.path().join("scene");
    std::fs::create_dir(&folder).unwrap();
    let luxo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/luxo.toml");
    std::fs::copy(luxo, folder.join("luxo.toml")).unwrap();
    std::fs::write(outer.path().join("secret.txt"), "not for the page").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(outer.path().join("secret.txt"), folder.join("link.txt")).unwrap();
    let file = folder.join("luxo.toml").display().to_string();
    (outer, file)
}

#[test]
fn every_request_needs_the_token() {
    let viewer = start("business-card", 32);
    let token = viewer.app.token.clone();
    let refused = "forbidden: this request lacks the viewer's token; open the URL that `lamplight view` printed\n";
    for target in ["/", "/app.js", "/inspector.js", "/ws", "/files/x.toml", "/nothing"] {
        assert_eq!(get(&viewer, target, ""), (403, refused.to_string()), "{target} without a token");
        assert_eq!(get(&viewer, &format!("{target}?token=0123"), "").0, 403, "{target} with a wrong token");
    }
    let upgrade =
        "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n";
    assert_eq!(get(&viewer, "/ws", upgrade).0, 403, "a WebSocket without the token");
    // Browsers ask for a favicon without the token: an empty answer, not a 403.
    assert_eq!(get(&viewer, "/favicon.ico", ""), (204, String::new()));
    assert_eq!(get(&viewer, &format!("/ws?token={token}"), upgrade).0, 101, "a WebSocket with it");
    let (status, page) = get(&viewer, &format!("/?token={token}"), "");
    assert_eq!(status, 200);
    for script in ["inspector.js", "app.js"] {
        assert!(page.contains(&format!("<script src=\"{script}?token={token}\">")), "the page loads {script} with the token");
        assert_eq!(get(&viewer, &format!("/{script}?token={token}"), "").0, 200, "{script} is served");
    }
    assert_eq!(get(&viewer, "/app.css", &format!("X-Lamplight-Token: {token}\r\n")).0, 200, "the token as a header");
    assert_eq!(get(&viewer, &format!("/nothing?token={token}"), "").0, 404);
    let not_found = "not found: the viewer serves its page only\n".to_string();
    assert_eq!(get(&viewer, &format!("/files/Cargo.toml?token={token}"), ""), (404, not_found), "not the working folder's files");
}

#[test]
fn no_file_is_served_even_inside_the_scene_s_folder() {
    let (_outer, file) = scene_folder();
    let viewer = start(&file, 32);
    let t = viewer.app.token.clone();
    for target in ["/files/luxo.toml", "/files/../secret.txt", "/files/%2e%2e/secret.txt", "/files/link.txt"] {
        assert_eq!(get(&viewer, &format!("{target}?token={t}"), "").0, 404, "{target}");
    }
}

#[test]
fn settings_out_of_bounds_are_refused_with_the_request_layer_s_words() {
    let viewer = start("business-card", 32);
    let err = viewer.app.set_request(|r| r.spp = Some(u32::MAX)).unwrap_err();
    assert_eq!(err, "spp must be between 1 and 1048576, got 4294967295");
    let err = viewer.app.set_request(|r| r.max_depth = Some(65)).unwrap_err();
    assert_eq!(err, "max_depth must be between 1 and 64 (work grows as 2^depth), got 65");
    assert_eq!(viewer.app.lock().request.spp, None, "the refused settings were not kept");
    let request = Request { width: Some(100_000), height: Some(100_000), ..Request::default() };
    let err =
        Viewer::start(ViewOptions { scene: "luxo".into(), listen: Some("127.0.0.1:0".parse().unwrap()), request, save_dir: None }).err();
    assert_eq!(err.as_deref(), Some("image 100000x100000 is too large (at most 268435456 pixels)"));
}

#[test]
fn the_denoise_switch_denoises_every_frame_and_says_what_it_added() {
    if lamplight_scene::denoise::for_test("the_denoise_switch_denoises_every_frame_and_says_what_it_added").is_none() {
        return;
    }
    let viewer = start("cornell-box", 32);
    viewer.app.set_request(|r| r.denoise = Some(true)).unwrap();
    let start = std::time::Instant::now();
    loop {
        if let Some(frame) = viewer.app.latest_frame().filter(|f| f.wanted.job.denoiser.is_some()) {
            assert!(frame.denoise_time.is_some(), "a denoised frame says what denoising added");
            if frame.last {
                break;
            }
        }
        assert!(start.elapsed() < Duration::from_secs(60), "no denoised frame came");
        std::thread::sleep(Duration::from_millis(20));
    }
    viewer.app.set_request(|r| r.denoise = None).unwrap();
}
