//! The browser edge: `halfcast serve --web ADDR` serves the page at `/` and its WebSocket at
//! `/ws` from the same process and world as the SSH listener. A thin adapter over
//! [`crate::play`], as [`crate::serve::ssh`] is: [`listener`] takes connections in within the
//! server's limits (sharing [`edge`] with the rest of the server), [`request`] reads an HTTP request's head, [`routes`] answers it (the page,
//! `/healthz`, the upgrade), [`origin`] refuses other sites' pages, [`info`] answers `/info.json`, [`forwarded`] reads a trusted
//! proxy's client address, [`messages`] reads what the page sends, [`acked`] turns the page's
//! acknowledgements into link figures, [`sink`] is the session's frame sink (compressed by
//! [`deflate`] while the link needs it), [`session`] runs it, [`page`] holds the page's own
//! HTML, CSS and JavaScript, and [`trace_route`] answers the ray debugger's `/trace.json`,
//! `/trace.svg` and `/trace.png`.

pub(crate) mod acked;
pub(crate) mod deflate;
pub(crate) mod edge;
pub(crate) mod forwarded;
pub(crate) mod info;
pub(crate) mod listener;
pub(crate) mod messages;
pub(crate) mod options;
pub(crate) mod origin;
pub(crate) mod page;
pub(crate) mod request;
pub(crate) mod routes;
pub(crate) mod session;
pub(crate) mod sink;
pub(crate) mod trace_route;

pub use forwarded::ForwardedHeader;
pub use options::{Compress, WebOptions};
