//! Running worlds as a service: what an operator watches and how a world stops. [`metrics`]
//! (the Prometheus series) and [`metrics_http`] (`/metrics` and `/healthz`), [`health`] (whether
//! a balancer should send players), [`process_stats`] (memory, CPU and files from `/proc`),
//! [`drain`] (stopping on SIGTERM without losing players), [`log`] (text or JSON lines) and
//! [`stats`] (the totals printed at exit).

pub(crate) mod drain;
pub(crate) mod drain_wait;
pub mod health;
pub mod log;
pub(crate) mod metrics;
pub(crate) mod metrics_http;
pub(crate) mod process_stats;
pub(crate) mod stats;
