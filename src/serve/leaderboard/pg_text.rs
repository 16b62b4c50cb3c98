//! PostgreSQL's words for people: a URL without its password, an error with its causes.

/// `url` without its password, for logs and errors.
#[must_use]
pub fn shown(url: &str) -> String {
    // The query string may carry a password too: it is not shown at all.
    let url = url.split_once('?').map_or(url, |(u, _)| u);
    let Some((scheme, rest)) = url.split_once("://") else {
        return url.to_owned();
    };
    match rest.rsplit_once('@') {
        Some((user, host)) => {
            let user = user.split_once(':').map_or(user, |(u, _)| u);
            format!("{scheme}://{user}@{host}")
        }
        None => url.to_owned(),
    }
}

/// An error with its causes ("error connecting to server: Connection refused (os error 111)"),
/// on one line (a server's DETAIL and HINT lines joined to it): the client's own message alone
/// rarely says what went wrong.
#[must_use]
pub fn causes(e: &(dyn std::error::Error + 'static)) -> String {
    let mut out = e.to_string();
    let mut next = e.source();
    while let Some(cause) = next {
        let c = cause.to_string();
        if !out.ends_with(&c) {
            out.push_str(": ");
            out.push_str(&c);
        }
        next = cause.source();
    }
    out.replace('\n', " ")
}
