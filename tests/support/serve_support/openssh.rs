//! OpenSSH's own `ssh`, run against the test server the way a person runs it: in a
//! pseudo-terminal, with `TERM=xterm-256color` and no `COLORTERM` (OpenSSH does not forward it).

use std::io::Read;
use std::process::Command;
use std::sync::mpsc;

use portable_pty::{native_pty_system, Child, CommandBuilder, MasterPty, PtySize};

/// Whether an OpenSSH client is installed (tests that need it print a skip notice otherwise).
pub fn ssh_available() -> bool {
    Command::new("ssh")
        .arg("-V")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// An `ssh` process in a pty: its output arrives on `rx` in chunks, keys go to `writer`.
pub struct SshPty {
    pub master: Box<dyn MasterPty + Send>,
    pub child: Box<dyn Child + Send + Sync>,
    pub writer: Box<dyn std::io::Write + Send>,
    pub rx: mpsc::Receiver<Vec<u8>>,
}

impl SshPty {
    /// Runs `ssh -tt EXTRA… ann@127.0.0.1` against `port` in a `cols`×`rows` pty, with no user
    /// config, host-key checks off and batch mode (no prompt can stall a test).
    pub fn spawn(port: u16, extra: &[&std::ffi::OsStr], size: (u16, u16)) -> Self {
        Self::spawn_checking(port, None, extra, size)
    }

    /// [`SshPty::spawn`], checking the host key against the `known_hosts` file when given (as
    /// a returning player's `ssh` does: a new host is added, a changed key is refused).
    pub fn spawn_checking(
        port: u16,
        known_hosts: Option<&std::path::Path>,
        extra: &[&std::ffi::OsStr],
        (cols, rows): (u16, u16),
    ) -> Self {
        let pty = native_pty_system()
            .openpty(PtySize {
                rows,
                cols,
                pixel_width: 0,
                pixel_height: 0,
            })
            .expect("pty");
        let mut cmd = CommandBuilder::new("ssh");
        cmd.args(["-tt", "-F", "/dev/null", "-p", &port.to_string()]);
        if let Some(file) = known_hosts {
            cmd.args(["-o", "StrictHostKeyChecking=accept-new"]);
            cmd.arg("-o");
            cmd.arg(format!("UserKnownHostsFile={}", file.display()));
        } else {
            cmd.args(["-o", "StrictHostKeyChecking=no"]);
            cmd.args(["-o", "UserKnownHostsFile=/dev/null"]);
        }
        cmd.args(["-o", "BatchMode=yes", "-o", "ConnectTimeout=10"]);
        cmd.args(extra);
        cmd.arg("ann@127.0.0.1");
        cmd.env("TERM", "xterm-256color");
        cmd.env_remove("COLORTERM");
        let child = pty.slave.spawn_command(cmd).expect("spawn ssh");
        drop(pty.slave);
        let mut reader = pty.master.try_clone_reader().expect("reader");
        let writer = pty.master.take_writer().expect("writer");
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let mut buf = [0u8; 8192];
            while let Ok(n) = reader.read(&mut buf) {
                if n == 0 || tx.send(buf[..n].to_vec()).is_err() {
                    break;
                }
            }
        });
        Self {
            master: pty.master,
            child,
            writer,
            rx,
        }
    }
}
