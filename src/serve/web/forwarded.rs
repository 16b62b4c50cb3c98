//! The player's address behind a reverse proxy: only a proxy the operator trusts may name it,
//! and only in the one header that proxy writes (`--web-forwarded-header`: `X-Forwarded-For` by
//! default, what HAProxy's `option forwardfor` and Caddy's `reverse_proxy` send, or RFC 7239's
//! `Forwarded: for=`). Within that header only the last entry counts: a proxy appends its own
//! (a new header line, or `, entry` after the others), so whatever a client wrote itself comes
//! before it. The other header, and anyone else's headers, are ignored, so a player cannot dodge
//! the per-address limits, or put another address in the logs, by claiming one.

use std::net::{IpAddr, SocketAddr};
use std::str::FromStr;

use super::request::Request;

/// The header a trusted proxy names the client in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ForwardedHeader {
    /// `X-Forwarded-For: client` (HAProxy's `option forwardfor`, Caddy, nginx's
    /// `$proxy_add_x_forwarded_for`).
    #[default]
    XForwardedFor,
    /// `Forwarded: for=client` (RFC 7239; HAProxy's `option forwarded`, Envoy, nginx by hand).
    Forwarded,
}

impl FromStr for ForwardedHeader {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "x-forwarded-for" => Ok(Self::XForwardedFor),
            "forwarded" => Ok(Self::Forwarded),
            _ => Err(format!(
                "unknown header '{s}' (x-forwarded-for or forwarded: the one the proxy writes)"
            )),
        }
    }
}

/// The address limits, logs and metrics use for a request that came from `peer`: `peer` itself
/// unless it is a `trusted` proxy whose `header`'s last entry names an address.
#[must_use]
pub fn client_addr(
    peer: SocketAddr,
    req: &Request,
    trusted: &[IpAddr],
    header: ForwardedHeader,
) -> SocketAddr {
    if !trusted.contains(&canonical(peer.ip())) {
        return peer;
    }
    let named = match header {
        ForwardedHeader::XForwardedFor => last_x_forwarded_for(req),
        ForwardedHeader::Forwarded => last_forwarded(req),
    };
    named.map_or(peer, |ip| SocketAddr::new(ip, 0))
}

fn canonical(ip: IpAddr) -> IpAddr {
    match ip {
        IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
        IpAddr::V4(_) => ip,
    }
}

/// The last entry of every `X-Forwarded-For` line taken together (the proxy's own).
fn last_x_forwarded_for(req: &Request) -> Option<IpAddr> {
    let last = req.all("x-forwarded-for").last()?;
    parse_ip(last.rsplit(',').next()?)
}

/// The `for=` of the last element of every `Forwarded` line taken together (the proxy's own);
/// none when that element has no `for=`, even if an earlier one does.
fn last_forwarded(req: &Request) -> Option<IpAddr> {
    let last = req.all("forwarded").last()?;
    let element = last.rsplit(',').next()?;
    element.split(';').find_map(|pair| {
        let (k, v) = pair.split_once('=')?;
        k.trim().eq_ignore_ascii_case("for").then(|| parse_ip(v))?
    })
}

/// `1.2.3.4`, `"[2001:db8::1]:4711"`, `1.2.3.4:80`; obfuscated names (`_hidden`, `unknown`) are
/// none.
fn parse_ip(s: &str) -> Option<IpAddr> {
    let s = s.trim().trim_matches('"');
    if let Ok(ip) = s.parse::<IpAddr>() {
        return Some(canonical(ip));
    }
    if let Ok(sa) = s.parse::<SocketAddr>() {
        return Some(canonical(sa.ip()));
    }
    let inner = s.strip_prefix('[')?.split(']').next()?;
    inner.parse().ok().map(canonical)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(headers: &[(&str, &str)]) -> Request {
        Request {
            method: "GET".into(),
            path: "/ws".into(),
            query: String::new(),
            headers: headers
                .iter()
                .map(|(n, v)| ((*n).to_owned(), (*v).to_owned()))
                .collect(),
        }
    }

    const XFF: ForwardedHeader = ForwardedHeader::XForwardedFor;
    const FWD: ForwardedHeader = ForwardedHeader::Forwarded;

    #[test]
    fn only_a_trusted_proxy_names_the_client() {
        let proxy: SocketAddr = "10.0.0.1:5000".parse().unwrap();
        let trusted = ["10.0.0.1".parse().unwrap()];
        let r = req(&[("x-forwarded-for", "6.6.6.6, 203.0.113.9")]);
        assert_eq!(
            client_addr(proxy, &r, &trusted, XFF).ip().to_string(),
            "203.0.113.9"
        );
        assert_eq!(client_addr(proxy, &r, &[], XFF), proxy);
        let r = req(&[(
            "forwarded",
            "for=1.1.1.1, for=\"[2001:db8::1]:4711\";proto=https",
        )]);
        assert_eq!(
            client_addr(proxy, &r, &trusted, FWD).ip().to_string(),
            "2001:db8::1"
        );
        let r = req(&[("forwarded", "for=_hidden")]);
        assert_eq!(client_addr(proxy, &r, &trusted, FWD), proxy);
        let mapped: SocketAddr = "[::ffff:10.0.0.1]:5000".parse().unwrap();
        let r = req(&[("x-forwarded-for", "198.51.100.7")]);
        assert_eq!(
            client_addr(mapped, &r, &trusted, XFF).ip().to_string(),
            "198.51.100.7"
        );
    }

    #[test]
    fn a_clients_own_headers_never_name_it() {
        let proxy: SocketAddr = "10.0.0.1:5000".parse().unwrap();
        let trusted = ["10.0.0.1".parse().unwrap()];
        // HAProxy's option forwardfor: the client's lines first, the proxy's line last.
        let r = req(&[
            ("forwarded", "for=203.0.113.5"),
            ("x-forwarded-for", "203.0.113.6, 203.0.113.7"),
            ("x-forwarded-for", "192.0.2.44"),
        ]);
        assert_eq!(
            client_addr(proxy, &r, &trusted, XFF).ip().to_string(),
            "192.0.2.44",
            "the Forwarded line the client sent is not read"
        );
        // A proxy writing Forwarded: the client's X-Forwarded-For is not read, and an element
        // of its own before the proxy's is not either.
        let r = req(&[
            ("x-forwarded-for", "203.0.113.6"),
            ("forwarded", "for=203.0.113.5"),
            ("forwarded", "for=192.0.2.45;proto=http"),
        ]);
        assert_eq!(
            client_addr(proxy, &r, &trusted, FWD).ip().to_string(),
            "192.0.2.45"
        );
        // The proxy's entry unreadable: the proxy's own address, not an earlier entry.
        let r = req(&[("forwarded", "for=203.0.113.5, for=unknown")]);
        assert_eq!(client_addr(proxy, &r, &trusted, FWD), proxy);
        let r = req(&[("x-forwarded-for", "203.0.113.5, garbage")]);
        assert_eq!(client_addr(proxy, &r, &trusted, XFF), proxy);
        // Only the configured header: a Forwarded line alone is ignored under the default.
        let r = req(&[("forwarded", "for=203.0.113.5")]);
        assert_eq!(client_addr(proxy, &r, &trusted, XFF), proxy);
    }

    #[test]
    fn the_header_is_named_as_the_proxy_writes_it() {
        assert_eq!("X-Forwarded-For".parse(), Ok(XFF));
        assert_eq!("forwarded".parse(), Ok(FWD));
        assert!("x-real-ip".parse::<ForwardedHeader>().is_err());
        assert_eq!(ForwardedHeader::default(), XFF);
    }
}
