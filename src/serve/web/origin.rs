//! Cross-site WebSocket hijacking: a browser lets any site's page open a WebSocket to any host,
//! and sends the page's `Origin` with it. Only the page this server serves (the same host as the
//! request's `Host`) and origins the operator named may play; a client that sends no `Origin` is
//! not a browser page, and is let in (it could send any header it liked).

/// Whether a WebSocket upgrade with `origin` to `host` may proceed, `allowed` being the
/// operator's named origins.
#[must_use]
pub fn allowed(origin: Option<&str>, host: Option<&str>, allowed: &[String]) -> bool {
    let Some(origin) = origin else {
        return true;
    };
    let origin = origin.trim().trim_end_matches('/');
    if allowed
        .iter()
        .any(|a| a.trim_end_matches('/').eq_ignore_ascii_case(origin))
    {
        return true;
    }
    let Some(host) = host else {
        return false;
    };
    let authority = origin
        .strip_prefix("http://")
        .or_else(|| origin.strip_prefix("https://"));
    authority.is_some_and(|a| a.eq_ignore_ascii_case(host.trim()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_served_page_and_named_origins_pass_others_do_not() {
        let none: &[String] = &[];
        assert!(allowed(
            Some("http://127.0.0.1:8080"),
            Some("127.0.0.1:8080"),
            none
        ));
        assert!(allowed(
            Some("https://Game.Example"),
            Some("game.example"),
            none
        ));
        assert!(!allowed(
            Some("https://evil.example"),
            Some("game.example"),
            none
        ));
        assert!(!allowed(
            Some("http://game.example:81"),
            Some("game.example"),
            none
        ));
        assert!(!allowed(Some("null"), Some("game.example"), none));
        assert!(!allowed(Some("http://a"), None, none));
        assert!(allowed(None, Some("game.example"), none));
        let named = ["https://friends.example/".to_owned()];
        assert!(allowed(Some("https://friends.example"), Some("x"), &named));
    }
}
