//! The doors every request passes before the token is looked at: the `Host`
//! header must name this server, and an `Origin` header, when a browser sends
//! one, must be this server's own page (Jupyter's server checks both).
//!
//! - **Host** (DNS rebinding): a page of `evil.example` whose name its DNS
//!   later points at 127.0.0.1 reaches the viewer with `Host: evil.example:PORT`.
//!   Accepted are `localhost`, `127.0.0.1` and `[::1]` with the viewer's port,
//!   and, when `--listen` names another address, that address with its port.
//!   Listening on every interface (`0.0.0.0`, `[::]`) accepts any name: the
//!   machine's names are not known, and the token still guards every request.
//! - **Origin** (cross-site WebSockets, which browsers do not keep to their
//!   origin): `http://` and an accepted host, nothing else; `Origin: null`
//!   (a sandboxed or `file:` page) is refused. A request without one (a
//!   program, not a browser page) passes to the token check.

use std::net::SocketAddr;

/// Who may knock: the host names of this server.
#[derive(Clone, Debug)]
pub struct Doors {
    hosts: Vec<String>,
    any_host: bool,
}

impl Doors {
    /// The doors of a server listening on `address`.
    pub fn new(address: SocketAddr) -> Doors {
        let port = address.port();
        let mut hosts = vec![format!("localhost:{port}"), format!("127.0.0.1:{port}"), format!("[::1]:{port}")];
        if !address.ip().is_loopback() {
            hosts.push(address.to_string());
        }
        Doors { hosts, any_host: address.ip().is_unspecified() }
    }

    /// Why a request with these `Host` and `Origin` headers is refused, if it is.
    pub fn check(&self, host: Option<&str>, origin: Option<&str>) -> Result<(), String> {
        let host = host.unwrap_or("");
        if !self.any_host && !self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host)) {
            return Err(format!(
                "forbidden: Host '{host}' is not this viewer's address (it answers {}); open the URL that `lamplight view` printed\n",
                self.hosts.join(", ")
            ));
        }
        if let Some(origin) = origin {
            let own = origin.strip_prefix("http://").is_some_and(|o| o.eq_ignore_ascii_case(host));
            if !own {
                return Err(format!("forbidden: Origin '{origin}' is not this viewer's page; only http://{host} may use it\n"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loopback_names_with_the_port_and_the_page_s_own_origin_only() {
        let doors = Doors::new("127.0.0.1:8765".parse().unwrap());
        for host in ["localhost:8765", "127.0.0.1:8765", "[::1]:8765", "LOCALHOST:8765"] {
            assert_eq!(doors.check(Some(host), None), Ok(()), "{host}");
            assert_eq!(doors.check(Some(host), Some(&format!("http://{host}"))), Ok(()), "{host}");
        }
        let refused = "forbidden: Host 'evil.example:8765' is not this viewer's address (it answers localhost:8765, \
                       127.0.0.1:8765, [::1]:8765); open the URL that `lamplight view` printed\n";
        assert_eq!(doors.check(Some("evil.example:8765"), None).unwrap_err(), refused);
        assert!(doors.check(Some("localhost:9999"), None).is_err(), "another port");
        assert!(doors.check(Some("localhost"), None).is_err(), "no port");
        assert!(doors.check(None, None).is_err(), "no Host");
        let foreign = |origin: &str| doors.check(Some("127.0.0.1:8765"), Some(origin)).unwrap_err();
        assert_eq!(foreign("null"), "forbidden: Origin 'null' is not this viewer's page; only http://127.0.0.1:8765 may use it\n");
        assert!(foreign("http://evil.example").starts_with("forbidden: Origin 'http://evil.example'"));
        assert!(foreign("http://localhost:8765").starts_with("forbidden"), "another of the names: not the same origin");
        assert!(foreign("https://127.0.0.1:8765").starts_with("forbidden"));
    }

    #[test]
    fn listen_adds_its_own_address() {
        let doors = Doors::new("192.168.1.5:9000".parse().unwrap());
        assert_eq!(doors.check(Some("192.168.1.5:9000"), Some("http://192.168.1.5:9000")), Ok(()));
        assert_eq!(doors.check(Some("localhost:9000"), None), Ok(()));
        assert!(doors.check(Some("evil.example:9000"), None).is_err());
        let everywhere = Doors::new("0.0.0.0:9000".parse().unwrap());
        assert_eq!(everywhere.check(Some("my-laptop.local:9000"), None), Ok(()), "any name on every interface");
        assert!(everywhere.check(Some("my-laptop.local:9000"), Some("http://evil.example")).is_err(), "but its own origin only");
    }
}
