//! OpenSSH's own `ssh` client, in a scripted pseudo-terminal, plays on `halfcast serve` with
//! compression (`ssh -C`). Skipped with a notice where `ssh` is not installed.

use crate::serve_support;

use std::io::Write;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use portable_pty::PtySize;
use serve_support::openssh::{ssh_available, SshPty};
use serve_support::{half_block_cells, header_has, server, view_rect, PATIENCE};

/// Feeds pty output into the screen model until `done` holds (false on EOF or timeout).
fn until(
    rx: &mpsc::Receiver<Vec<u8>>,
    screen: &mut vt100::Parser,
    mut done: impl FnMut(&vt100::Screen) -> bool,
) -> bool {
    let deadline = Instant::now() + PATIENCE;
    loop {
        if done(screen.screen()) {
            return true;
        }
        let Some(left) = deadline.checked_duration_since(Instant::now()) else {
            return false;
        };
        match rx.recv_timeout(left) {
            Ok(b) => screen.process(&b),
            Err(_) => return false,
        }
    }
}

#[test]
fn openssh_client_plays_with_compression_resizes_and_quits() {
    if !ssh_available() {
        eprintln!("skip: OpenSSH `ssh` is not installed (apt-get install openssh-client)");
        return;
    }
    let rt = tokio::runtime::Runtime::new().expect("runtime");
    let (srv, dir) = rt.block_on(server(|_| {}));
    let log = dir.path().join("ssh.log");

    let SshPty {
        master,
        mut child,
        mut writer,
        rx,
    } = SshPty::spawn(
        srv.local_addr().port(),
        &["-C".as_ref(), "-v".as_ref(), "-E".as_ref(), log.as_os_str()],
        (80, 24),
    );
    let mut screen = vt100::Parser::new(24, 80, 0);
    let ok = until(&rx, &mut screen, |s| header_has(s, "you are ann"));
    let ssh_log = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(
        ok,
        "ssh shows the game; screen:\n{}\nlog:\n{ssh_log}",
        screen.screen().contents()
    );
    assert!(
        ssh_log.contains("compression: zlib@openssh.com"),
        "ssh -C negotiated delayed zlib:\n{ssh_log}"
    );
    // xterm-256color picks 256 colours: no 24-bit cells, but the view is half blocks.
    assert_eq!(half_block_cells(screen.screen(), view_rect(80, 24)), 0);

    // Keys go through, and the stream stays in sync for many compressed packets.
    let before = screen.screen().contents_formatted();
    for _ in 0..30 {
        writer.write_all(b"d").expect("key");
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(until(&rx, &mut screen, |s| s.contents_formatted() != before));

    // Resizing the pty sends a window-change through ssh.
    master
        .resize(PtySize {
            rows: 15,
            cols: 50,
            pixel_width: 0,
            pixel_height: 0,
        })
        .expect("resize");
    screen.set_size(15, 50);
    assert!(
        until(&rx, &mut screen, |s| header_has(s, "you are ann")),
        "after resize:\n{}",
        screen.screen().contents()
    );

    writer.write_all(b"\x03").expect("quit");
    let deadline = Instant::now() + PATIENCE;
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break Some(s);
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(
        status
            .as_ref()
            .is_some_and(portable_pty::ExitStatus::success),
        "ssh exits cleanly: {status:?}"
    );
    while let Ok(b) = rx.try_recv() {
        screen.process(&b);
    }
    assert!(!screen.screen().alternate_screen(), "alternate screen left");
    rt.block_on(srv.shutdown());
}
