//! One HTTP/1.1 request's head, read from a socket within a size and a time bound: the page, the
//! health check and the WebSocket upgrade all start as one.

use std::time::Duration;

use tokio::io::AsyncReadExt;
use tokio::net::TcpStream;

/// The most a request line and its headers may take.
pub const MAX_HEAD: usize = 8 * 1024;
/// Headers at most in one request.
const MAX_HEADERS: usize = 48;
/// How long a client may take to send its request's head.
pub const HEAD_WAIT: Duration = Duration::from_secs(10);

/// A request's head as the routes need it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Request {
    pub method: String,
    /// The path without its query.
    pub path: String,
    /// The query after `?`, undecoded (empty when there is none).
    pub query: String,
    /// Header names lowercased, values as sent (non-UTF-8 bytes replaced).
    pub headers: Vec<(String, String)>,
}

impl Request {
    /// The first header named `name` (lowercase).
    #[must_use]
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    /// Every header named `name` (lowercase), in order.
    pub fn all<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a str> + 'a {
        self.headers
            .iter()
            .filter(move |(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    /// Whether a comma-separated header holds `token` (case-insensitive), as `Connection` and
    /// `Upgrade` do.
    #[must_use]
    pub fn has_token(&self, name: &str, token: &str) -> bool {
        self.all(name)
            .flat_map(|v| v.split(','))
            .any(|t| t.trim().eq_ignore_ascii_case(token))
    }
}

/// Why no request could be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum HeadError {
    /// The client closed, or the socket failed, before the head ended.
    Closed,
    /// Longer than [`MAX_HEAD`] or with too many headers.
    TooLarge,
    /// Not HTTP/1.x.
    Malformed,
}

/// Reads one request's head; bytes after it (a client that did not wait for our answer) are an
/// error, as neither the page nor the upgrade expects a body.
///
/// # Errors
/// [`HeadError`] when the head is cut short, too large or not HTTP.
pub async fn read_head(socket: &mut TcpStream) -> Result<Request, HeadError> {
    let mut buf = Vec::with_capacity(1024);
    let mut chunk = [0u8; 1024];
    loop {
        let n = socket
            .read(&mut chunk)
            .await
            .map_err(|_| HeadError::Closed)?;
        if n == 0 {
            return Err(HeadError::Closed);
        }
        buf.extend_from_slice(&chunk[..n]);
        match parse(&buf)? {
            Some((req, used)) if used == buf.len() => return Ok(req),
            Some(_) => return Err(HeadError::Malformed),
            None if buf.len() >= MAX_HEAD => return Err(HeadError::TooLarge),
            None => {}
        }
    }
}

/// The request in `buf` and the bytes its head took, `None` while it is incomplete.
///
/// # Errors
/// [`HeadError`] when the bytes are not an HTTP/1.x request or have too many headers.
pub fn parse(buf: &[u8]) -> Result<Option<(Request, usize)>, HeadError> {
    let mut headers = [httparse::EMPTY_HEADER; MAX_HEADERS];
    let mut req = httparse::Request::new(&mut headers);
    let used = match req.parse(buf) {
        Ok(httparse::Status::Complete(n)) => n,
        Ok(httparse::Status::Partial) => return Ok(None),
        Err(httparse::Error::TooManyHeaders) => return Err(HeadError::TooLarge),
        Err(_) => return Err(HeadError::Malformed),
    };
    let target = req.path.unwrap_or("/");
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    Ok(Some((
        Request {
            method: req.method.unwrap_or("").to_owned(),
            path: path.to_owned(),
            query: query.to_owned(),
            headers: req
                .headers
                .iter()
                .map(|h| {
                    (
                        h.name.to_ascii_lowercase(),
                        String::from_utf8_lossy(h.value).into_owned(),
                    )
                })
                .collect(),
        },
        used,
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_head_is_read_with_its_query_and_lowercased_headers() {
        let raw =
            b"GET /ws?name=ann HTTP/1.1\r\nHost: a:1\r\nConnection: keep-alive, Upgrade\r\n\r\n";
        let (req, used) = parse(raw).unwrap().unwrap();
        assert_eq!(used, raw.len());
        assert_eq!((req.path.as_str(), req.query.as_str()), ("/ws", "name=ann"));
        assert_eq!(req.header("host"), Some("a:1"));
        assert!(req.has_token("connection", "upgrade"));
        assert!(!req.has_token("connection", "close"));
    }

    #[test]
    fn partial_and_garbage_heads_are_told_apart() {
        assert_eq!(parse(b"GET / HTTP/1.1\r\nHost:"), Ok(None));
        assert_eq!(
            parse(b"\x16\x03\x01junk\r\n\r\n"),
            Err(HeadError::Malformed)
        );
        let mut many = b"GET / HTTP/1.1\r\n".to_vec();
        for i in 0..60 {
            many.extend_from_slice(format!("X-{i}: y\r\n").as_bytes());
        }
        many.extend_from_slice(b"\r\n");
        assert_eq!(parse(&many), Err(HeadError::TooLarge));
    }
}
