//! `lamplight view` from the command line: bad input stops it before it
//! listens (exit code 2, one line); started, it prints a loopback URL with the
//! token, warns when told to listen beyond loopback, and opens nothing.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

fn lamplight(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).stdin(Stdio::null()).output().expect("the binary runs")
}

#[test]
fn bad_input_stops_the_viewer_before_it_listens() {
    let out = lamplight(&["view", "nosuch"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("lamplight: error: unknown scene \"nosuch\" (built-in scenes: "), "{err}");
    let out = lamplight(&["view", "luxo", "--width", "100000", "--height", "100000"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(String::from_utf8_lossy(&out.stderr), "lamplight: error: image 100000x100000 is too large (at most 268435456 pixels)\n");
    let out = lamplight(&["view", "luxo", "--max-depth", "65"]);
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "lamplight: error: --max-depth must be between 1 and 64 (work grows as 2^depth), got 65\n"
    );
}

/// Starts the viewer with its output piped; returns it and the first line it
/// prints (its URL: it is listening from then on).
fn started(args: &[&str]) -> (std::process::Child, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_lamplight"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    (child, line)
}

/// Starts the viewer, returns the first line it prints and its error output so far.
fn first_line(args: &[&str]) -> (String, String) {
    let (mut child, line) = started(args);
    let mut err = String::new();
    BufReader::new(child.stderr.take().unwrap()).read_line(&mut err).unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    (line, err)
}

#[test]
fn it_prints_a_loopback_url_with_a_token() {
    let (line, err) = first_line(&["view", "business-card", "--listen", "127.0.0.1:0"]);
    let url = line.strip_prefix("lamplight view: http://127.0.0.1:").expect(&line);
    let (_port, token) = url.trim_end().split_once("/?token=").expect(&line);
    assert_eq!(token.len(), 32, "{line}");
    assert!(!err.contains("warning"), "{err}");
    let (line, err) = first_line(&["view", "business-card", "--listen", "0.0.0.0:0"]);
    assert!(line.starts_with("lamplight view: http://0.0.0.0:"), "{line}");
    assert!(err.starts_with("lamplight: warning: listening on 0.0.0.0:0, not loopback"), "{err}");
}

#[test]
fn ctrl_c_stops_the_viewer_without_an_error() {
    let (mut child, line) = started(&["view", "business-card", "--listen", "127.0.0.1:0"]);
    assert!(line.starts_with("lamplight view: http://127.0.0.1:"), "{line}");
    Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    let status = child.wait().unwrap();
    let mut err = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut err).unwrap();
    assert_eq!(status.code(), Some(0), "{err}");
    assert!(err.ends_with("lamplight view: stopped\n") && !err.contains("error"), "{err}");
}

/// See: issue 30. With the readers of its stdout and stderr gone (`| head -1`,
/// a closed terminal), each of SIGTERM, SIGHUP and SIGINT still stops the
/// viewer, within seconds, with the code of a clean stop.
#[test]
fn signals_stop_the_viewer_after_its_readers_are_gone() {
    for signal in ["-TERM", "-HUP", "-INT"] {
        let (mut child, line) = started(&["view", "business-card", "--listen", "127.0.0.1:0"]);
        assert!(line.starts_with("lamplight view: http://127.0.0.1:"), "{line}");
        drop(child.stderr.take());
        // The stdout reader went with `started`'s BufReader: both pipes are closed now.
        std::thread::sleep(std::time::Duration::from_millis(100));
        Command::new("kill").args([signal, &child.id().to_string()]).status().unwrap();
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(5);
        let status = loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            if std::time::Instant::now() > deadline {
                child.kill().unwrap();
                child.wait().unwrap();
                panic!("{signal}: the viewer was still running 5 s after the signal");
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        };
        assert_eq!(status.code(), Some(0), "{signal}");
    }
}
