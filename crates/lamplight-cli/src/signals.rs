//! What the binary does on Ctrl-C, SIGTERM and SIGHUP.
//!
//! While a render runs ([`Graceful`]), the first signal only asks it to stop:
//! the pass in progress is dropped and the passes already complete are written,
//! atomically, to the output, and the program exits with code 130 (a render
//! with no complete pass writes nothing). Any other signal, a second one or one
//! outside a render, removes the temporary files of writes in progress
//! ([`lamplight_scene::atomic::remove_temporaries`]) and exits with code 130 at
//! once, leaving every output either as it was or whole. `lamplight view`,
//! which Ctrl-C is the way to stop, says "stopped" and exits with code 0.
//!
//! The handler runs on a thread of its own (the `ctrlc` crate), not inside the
//! signal handler, so it may take locks and remove files. It never writes with
//! `eprintln!`, which panics once stderr is gone (a closed terminal, `| head`):
//! the panic ended the handler's thread before it exited, and every later
//! signal was ignored (issue 30). It writes with [`say`], which ignores a
//! failed write, and exits whatever happens to the words.

use std::sync::atomic::{AtomicBool, Ordering};

/// Exit code after an interrupt: 128 + SIGINT, as shells report it.
pub const INTERRUPTED: i32 = 130;

/// Set by the first signal during a render: the render loop's stop flag.
static STOP: AtomicBool = AtomicBool::new(false);
/// Whether a render that can stop on [`STOP`] is running.
static GRACEFUL: AtomicBool = AtomicBool::new(false);
/// Whether the program is a server that Ctrl-C is the way to stop ([`serving`]).
static SERVING: AtomicBool = AtomicBool::new(false);

/// Installs the handler; a failure to install it (another handler, no signal
/// support) only loses the clean-up, never the render.
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        if GRACEFUL.load(Ordering::SeqCst) && !STOP.swap(true, Ordering::SeqCst) {
            return;
        }
        lamplight_scene::atomic::remove_temporaries();
        if SERVING.load(Ordering::SeqCst) {
            // The documented way to stop the viewer: no error.
            say("lamplight view: stopped");
            std::process::exit(0);
        }
        say("lamplight: error: interrupted");
        std::process::exit(INTERRUPTED);
    });
}

/// Writes `line` to stderr, ignoring a stream that is gone.
fn say(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// While alive, the first signal stops the render instead of ending the program.
pub struct Graceful;

impl Graceful {
    /// Starts the render's graceful window.
    pub fn start() -> Graceful {
        GRACEFUL.store(true, Ordering::SeqCst);
        Graceful
    }

    /// The flag the render loop watches.
    pub fn stop_flag(&self) -> &'static AtomicBool {
        &STOP
    }
}

impl Drop for Graceful {
    fn drop(&mut self) {
        GRACEFUL.store(false, Ordering::SeqCst);
    }
}

/// From now on a signal stops a server (`lamplight view`) as asked: it says
/// so and exits with code 0, not as an interrupted render.
pub fn serving() {
    SERVING.store(true, Ordering::SeqCst);
}

/// Whether a signal asked the render to stop.
pub fn stop_requested() -> bool {
    STOP.load(Ordering::SeqCst)
}
