//! The viewer shows the warnings `lamplight render` prints about a scene's
//! lights (issue 27): a light shut in by geometry is named, with what blocks
//! it, in the `state` message the page reads over its WebSocket (and lists
//! under the image, `app.js`).

use std::time::{Duration, Instant};

use lamplight_scene::request::Request;
use lamplight_view::{ViewOptions, Viewer};

use crate::doors::{ask, frame, status, UPGRADE};

/// A grey floor, a closed sphere named "shell" and a point light at its centre.
const SHUT_IN: &str = r#"ambient = 0.2

[render]
width = 64
height = 48

[camera]
eye = [0.0, 2.0, 6.0]
look_at = [0.0, 0.5, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 40

[materials.grey]
color = [0.6, 0.6, 0.6]

[[objects]]
type = "rectangle"
material = "grey"
corner = [-5.0, 0.0, -5.0]
edge_u = [0.0, 0.0, 10.0]
edge_v = [10.0, 0.0, 0.0]

[[objects]]
type = "sphere"
name = "shell"
material = "grey"
center = [0.0, 1.0, 0.0]
radius = 0.5

[[objects]]
type = "point_light"
position = [0.0, 1.0, 0.0]
intensity = 2.0
"#;

/// The first `state` message the page gets over the WebSocket.
fn state(viewer: &Viewer) -> serde_json::Value {
    let t = viewer.app.token.clone();
    let (mut stream, head) = ask(viewer, &format!("GET /ws?token={t} HTTP/1.1\r\nHost: {}\r\n{UPGRADE}", viewer.address));
    assert_eq!(status(&head), 101, "{head}");
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let (opcode, payload) = frame(&mut stream);
        if opcode == 0x1 {
            let message: serde_json::Value = serde_json::from_slice(&payload).unwrap();
            if message["type"] == "state" {
                return message;
            }
        }
        assert!(Instant::now() < deadline, "no state message");
    }
}

fn start(scene: &str) -> Viewer {
    let request = Request { width: Some(64), ..Request::default() };
    Viewer::start(ViewOptions { scene: scene.into(), listen: Some("127.0.0.1:0".parse().unwrap()), request, save_dir: None }).unwrap()
}

#[test]
fn a_light_shut_in_by_geometry_is_named_in_the_page_s_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("shut_in.toml");
    std::fs::write(&file, SHUT_IN).unwrap();
    let viewer = start(&file.display().to_string());
    // The words `lamplight render` prints (crates/lamplight-cli/tests/lighting.rs),
    // probed at the viewer's image size (64x48, the scene's aspect).
    assert_eq!(
        state(&viewer)["warnings"],
        serde_json::json!(["light 0 (PointLight) lights nothing the camera sees: every shadow ray towards it from what the camera sees \
             (142 probed) is blocked by object 1 \"shell\" (Sphere)"])
    );
    // The light moved out of the shell: no warning.
    std::fs::write(&file, SHUT_IN.replace("position = [0.0, 1.0, 0.0]", "position = [0.0, 3.0, 0.0]")).unwrap();
    viewer.app.reload();
    assert_eq!(state(&viewer)["warnings"], serde_json::json!([]));
}
