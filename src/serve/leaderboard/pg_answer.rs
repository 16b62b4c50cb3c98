//! What a failed PostgreSQL connection means for a world that is starting: an answer that
//! refuses (a wrong password, a role or database that does not exist, a server that does not
//! speak PostgreSQL or wants TLS, a host name that does not exist) is a mistake to fix, so the
//! start stops; silence (connection refused, a timeout, the server starting up or shutting
//! down, too many connections) is an outage to ride out, so the world starts and queues. libpq
//! and sshd draw the line in the same place.

use std::io::{ErrorKind, Read, Write};
use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

use postgres::config::Host;
use postgres::error::SqlState;
use postgres::Config;

use super::open_error::OpenError;
use super::pg_text::causes;

/// How long the check that a port speaks PostgreSQL waits, unless the URL's `connect_timeout`
/// says otherwise.
const PROBE_WAIT: Duration = Duration::from_secs(5);

/// `e` from connecting, worded with `what` (the message's start), as an outage or a refusal.
#[must_use]
pub fn classify(e: &postgres::Error, what: impl FnOnce(String) -> String) -> OpenError {
    let words = what(causes(e));
    if refuses(e) {
        OpenError::Refused(words)
    } else {
        OpenError::Away(words)
    }
}

/// Asks the first TCP host and port of `config`, plainly, whether it speaks PostgreSQL, before
/// the client logs in: the client waits without end for a server that accepted the connection
/// and says nothing (an HTTP server waiting for a request's end), and takes another program's
/// greeting for a broken line. PostgreSQL answers a TLS request (`SSLRequest`) with one byte,
/// `S` or `N` (`E` from a very old server), and waits; an SSH server greets first
/// (`SSH-2.0-…`), MySQL greets with a packet of its own.
///
/// # Errors
/// [`OpenError::Refused`] when another program answered, [`OpenError::Away`] when the server
/// accepted the connection and said nothing in time. No error when it speaks PostgreSQL, or
/// cannot be reached (the client then says why), or listens on a Unix socket.
pub fn speaks_postgres(config: &Config) -> Result<(), OpenError> {
    let Some(host) = config.get_hosts().iter().find_map(|h| match h {
        Host::Tcp(name) => Some(name.clone()),
        #[cfg(unix)]
        Host::Unix(_) => None,
    }) else {
        return Ok(());
    };
    let port = config.get_ports().first().copied().unwrap_or(5432);
    let wait = config.get_connect_timeout().copied().unwrap_or(PROBE_WAIT);
    let Some(addr) = (host.as_str(), port)
        .to_socket_addrs()
        .ok()
        .and_then(|mut a| a.next())
    else {
        return Ok(());
    };
    let Ok(mut tcp) = TcpStream::connect_timeout(&addr, wait) else {
        return Ok(());
    };
    let _ = tcp.set_read_timeout(Some(wait));
    // Length 8, then the request code 80877103 (1234 << 16 | 5679).
    let _ = tcp.write_all(&[0, 0, 0, 8, 0x04, 0xd2, 0x16, 0x2f]);
    let mut answer = [0u8; 64];
    match tcp.read(&mut answer) {
        Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
            Err(OpenError::Away(format!(
                "the server at {host}:{port} accepted the connection but did not answer in \
                 {:.0} s (is it PostgreSQL?)",
                wait.as_secs_f64()
            )))
        }
        Err(_) => Ok(()),
        Ok(n) => match answered_otherwise(&answer[..n]) {
            Some(said) => Err(OpenError::Refused(format!(
                "the server at {host}:{port} does not speak PostgreSQL (it answered {said})"
            ))),
            None => Ok(()),
        },
    }
}

/// The answer to a TLS request, when it is not PostgreSQL's (shown escaped and cut); none for
/// PostgreSQL's one byte, or for no answer at all (an outage, not a mistake).
#[must_use]
pub fn answered_otherwise(answer: &[u8]) -> Option<String> {
    if answer.is_empty() || matches!(answer, [b'S'] | [b'N']) || answer[0] == b'E' {
        return None;
    }
    let shown: String = answer
        .iter()
        .take(24)
        .flat_map(|&b| std::ascii::escape_default(b))
        .map(char::from)
        .collect();
    Some(format!("\"{shown}\""))
}

/// Whether the server (or the name service) answered, and the answer was no.
fn refuses(e: &postgres::Error) -> bool {
    if let Some(code) = e.code() {
        return refusing_code(code);
    }
    let text = e.to_string();
    match text.as_str() {
        // Nobody answered, or the line broke: an outage, unless the host's name is unknown.
        "error connecting to server" => unknown_host(&causes(e)),
        "timeout waiting for server" | "error communicating with the server" => false,
        "connection closed" => false,
        // Something answered that is not a PostgreSQL server as configured: another program
        // on that port, TLS wanted or refused, a password wanted and none given.
        _ => true,
    }
}

/// Whether a server's error code at login says "no" for good, rather than "not now".
#[must_use]
pub fn refusing_code(code: &SqlState) -> bool {
    let c = code.code();
    // 08: connection exceptions, but for a protocol violation (08P01: not the protocol it
    // speaks) and a rejected connection (08004); 53: out of resources (too many connections,
    // disk full); 57P0x: the server is shutting down, starting up, or was stopped.
    let broken_line = c.starts_with("08") && c != "08P01" && c != "08004";
    let transient = broken_line || c.starts_with("53") || c.starts_with("57P");
    !transient
}

/// Whether a connect error's causes say the host's name does not exist (rather than that
/// the name service did not answer, "Temporary failure in name resolution").
#[must_use]
pub fn unknown_host(causes: &str) -> bool {
    causes.contains("Name or service not known")
        || causes.contains("No address associated with hostname")
        || causes.contains("nodename nor servname provided")
        || causes.contains("could not resolve any addresses")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mistakes_refuse_and_unavailability_waits() {
        for refused in [
            SqlState::INVALID_PASSWORD,
            SqlState::INVALID_AUTHORIZATION_SPECIFICATION,
            SqlState::INVALID_CATALOG_NAME,
            SqlState::INSUFFICIENT_PRIVILEGE,
            SqlState::PROTOCOL_VIOLATION,
        ] {
            assert!(refusing_code(&refused), "{}", refused.code());
        }
        for away in [
            SqlState::CANNOT_CONNECT_NOW,
            SqlState::ADMIN_SHUTDOWN,
            SqlState::CRASH_SHUTDOWN,
            SqlState::TOO_MANY_CONNECTIONS,
            SqlState::CONNECTION_FAILURE,
        ] {
            assert!(!refusing_code(&away), "{}", away.code());
        }
    }

    #[test]
    fn postgresql_answers_a_tls_request_with_one_byte_and_others_do_not() {
        assert_eq!(answered_otherwise(b"N"), None);
        assert_eq!(answered_otherwise(b"S"), None);
        assert_eq!(answered_otherwise(b""), None, "silence is an outage");
        let ssh = answered_otherwise(b"SSH-2.0-OpenSSH_9.2p1 Debian-2+deb12u3\r\n").unwrap();
        assert!(ssh.starts_with("\"SSH-2.0-OpenSSH_9.2p1"), "{ssh}");
        assert!(answered_otherwise(b"HTTP/1.1 400 Bad Request\r\n").is_some());
        assert!(
            answered_otherwise(&[0x4a, 0, 0, 0, 0x0a, b'8']).is_some(),
            "MySQL"
        );
    }

    #[test]
    fn another_program_on_the_port_is_told_from_postgresql() {
        use std::net::TcpListener;
        for (greeting, other) in [(&b"SSH-2.0-test\r\n"[..], true), (b"N", false)] {
            let l = TcpListener::bind("127.0.0.1:0").unwrap();
            let port = l.local_addr().unwrap().port();
            let server = std::thread::spawn(move || {
                let (mut s, _) = l.accept().unwrap();
                let mut request = [0u8; 8];
                s.read_exact(&mut request).unwrap();
                s.write_all(greeting).unwrap();
                request
            });
            let config: Config = format!("postgres://ann@127.0.0.1:{port}/db")
                .parse()
                .unwrap();
            let said = speaks_postgres(&config);
            assert_eq!(server.join().unwrap(), [0, 0, 0, 8, 4, 210, 22, 47]);
            match said {
                Err(OpenError::Refused(s)) => {
                    assert!(other, "{s}");
                    assert!(s.contains("does not speak PostgreSQL") && s.contains("SSH-2.0"));
                }
                Ok(()) => assert!(!other),
                Err(e) => panic!("{e:?}"),
            }
        }
        // A server that accepts and says nothing (an HTTP server waiting for the request's
        // end) is an outage after the connect timeout, not a wait without end.
        let l = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = l.local_addr().unwrap().port();
        let config: Config = format!("postgres://ann@127.0.0.1:{port}/db?connect_timeout=1")
            .parse()
            .unwrap();
        let silent = std::thread::spawn(move || l.accept().map(|(s, _)| s));
        let said = speaks_postgres(&config);
        drop(silent.join());
        let away = matches!(&said, Err(OpenError::Away(s)) if s.contains("did not answer"));
        assert!(away, "{said:?}");
    }

    #[test]
    fn an_unknown_host_refuses_and_a_silent_resolver_waits() {
        assert!(unknown_host(
            "error connecting to server: failed to lookup address information: Name or service \
             not known"
        ));
        assert!(!unknown_host(
            "error connecting to server: failed to lookup address information: Temporary \
             failure in name resolution"
        ));
        assert!(!unknown_host(
            "error connecting to server: Connection refused (os error 111)"
        ));
    }
}
