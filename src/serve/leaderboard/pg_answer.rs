//! What a failed PostgreSQL connection means for a world that is starting: an answer that
//! refuses (a wrong password, a role or database that does not exist, a server that does not
//! speak PostgreSQL or wants TLS, a host name that does not exist) is a mistake to fix, so the
//! start stops; silence (connection refused, a timeout, the server starting up or shutting
//! down, too many connections) is an outage to ride out, so the world starts and queues. libpq
//! and sshd draw the line in the same place.

use postgres::error::SqlState;

use super::open_error::OpenError;
use super::pg_text::causes;

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
