//! `lamplight view`: starts the viewer ([`lamplight_view`]), prints its URL and
//! serves until Ctrl-C.

use std::io::Write;

use lamplight_view::{ViewOptions, Viewer};

use crate::args::{UsageError, ViewArgs};

pub fn view_command(args: ViewArgs) -> anyhow::Result<()> {
    let request = args.render.request(args.threads);
    if let Some(address) = args.listen.filter(|a| !lamplight_view::is_loopback(a)) {
        eprintln!(
            "lamplight: warning: listening on {address}, not loopback: other machines can reach the viewer \
             (each request still needs the token in the URL; the traffic is not encrypted)"
        );
    }
    let viewer =
        Viewer::start(ViewOptions { scene: args.render.scene.clone(), listen: args.listen, request, save_dir: args.save_dir.clone() })
            .map_err(UsageError)?;
    crate::signals::serving();
    let url = viewer.url();
    // A reader that went away (`| head -1`, a closed terminal) must not stop
    // the server or its Ctrl-C: these writes ignore a closed stream. The hint
    // goes out before the URL: a caller that stops the viewer as soon as it
    // reads the URL then sees "stopped" last (with the hint after the URL, a
    // Ctrl-C right away printed "stopped" before it, which failed a test).
    let _ = writeln!(
        std::io::stderr(),
        "open that URL in a browser (it holds the access token); saves go into {}; Ctrl-C stops the viewer",
        viewer.app.save_dir.display()
    );
    let _ = writeln!(std::io::stdout(), "lamplight view: {url}");
    let _ = std::io::stdout().flush();
    if args.open {
        open_browser(&url);
    }
    viewer.wait()
}

/// Opens `url` with the desktop's handler; a failure is a warning only.
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") { "open" } else { "xdg-open" };
    if let Err(e) = std::process::Command::new(opener).arg(url).stdin(std::process::Stdio::null()).spawn() {
        eprintln!("lamplight: warning: cannot open a browser ({opener}: {e}); open the URL by hand");
    }
}
