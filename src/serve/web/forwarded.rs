//! The player's address behind a reverse proxy: only a proxy the operator trusts may name it, in
//! `Forwarded: for=…` (RFC 7239) or `X-Forwarded-For`; the last entry is the one that proxy added.
//! Anyone else's headers are ignored, so a player cannot dodge the per-address limits by
//! claiming another address.

use std::net::{IpAddr, SocketAddr};

use super::request::Request;

/// The address limits, logs and metrics use for a request that came from `peer`.
#[must_use]
pub fn client_addr(peer: SocketAddr, req: &Request, trusted: &[IpAddr]) -> SocketAddr {
    if !trusted.contains(&canonical(peer.ip())) {
        return peer;
    }
    let named = last_forwarded(req).or_else(|| last_x_forwarded_for(req));
    named.map_or(peer, |ip| SocketAddr::new(ip, 0))
}

fn canonical(ip: IpAddr) -> IpAddr {
    match ip {
        IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
        IpAddr::V4(_) => ip,
    }
}

fn last_x_forwarded_for(req: &Request) -> Option<IpAddr> {
    let last = req.all("x-forwarded-for").last()?;
    parse_ip(last.rsplit(',').next()?)
}

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

    #[test]
    fn only_a_trusted_proxy_names_the_client() {
        let proxy: SocketAddr = "10.0.0.1:5000".parse().unwrap();
        let trusted = ["10.0.0.1".parse().unwrap()];
        let r = req(&[("x-forwarded-for", "6.6.6.6, 203.0.113.9")]);
        assert_eq!(
            client_addr(proxy, &r, &trusted).ip().to_string(),
            "203.0.113.9"
        );
        assert_eq!(client_addr(proxy, &r, &[]), proxy);
        let r = req(&[(
            "forwarded",
            "for=1.1.1.1, for=\"[2001:db8::1]:4711\";proto=https",
        )]);
        assert_eq!(
            client_addr(proxy, &r, &trusted).ip().to_string(),
            "2001:db8::1"
        );
        let r = req(&[("forwarded", "for=_hidden")]);
        assert_eq!(client_addr(proxy, &r, &trusted), proxy);
        let mapped: SocketAddr = "[::ffff:10.0.0.1]:5000".parse().unwrap();
        let r = req(&[("x-forwarded-for", "198.51.100.7")]);
        assert_eq!(
            client_addr(mapped, &r, &trusted).ip().to_string(),
            "198.51.100.7"
        );
    }
}
