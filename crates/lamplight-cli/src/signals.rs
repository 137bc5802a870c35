//! What the binary does on Ctrl-C, SIGTERM and SIGHUP: remove the temporary
//! files of writes in progress ([`lamplight_scene::atomic::remove_temporaries`])
//! and exit with code 130, leaving every output either as it was or whole.
//!
//! The handler runs on a thread of its own (the `ctrlc` crate), not inside the
//! signal handler, so it may take locks and remove files. There is one handler
//! per process: a later behaviour for the first Ctrl-C (such as writing the last
//! finished pass) belongs in this function, ending with the same clean-up.

/// Exit code after an interrupt: 128 + SIGINT, as shells report it.
pub const INTERRUPTED: i32 = 130;

/// Installs the handler; a failure to install it (another handler, no signal
/// support) only loses the clean-up, never the render.
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        lamplight_scene::atomic::remove_temporaries();
        eprintln!("lamplight: error: interrupted");
        std::process::exit(INTERRUPTED);
    });
}
