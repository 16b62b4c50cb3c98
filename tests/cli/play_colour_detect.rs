//! The local game decides its colour level before the first frame, through a real
//! pseudo-terminal: `COLORTERM` first, else the terminal is asked (XTGETTCAP `RGB`/`Tc`, DECRQSS
//! of a 24-bit SGR, DA1 as the end marker) for at most a short time, else the `TERM` rule. The
//! status line says which; the O key cycles from there; keys typed during the query are kept.
#![cfg(unix)]

use crate::pty_support;

use pty_support::{contains, PtyRun};

const SIZE: (u16, u16) = (160, 40);
/// The query's first bytes (XTGETTCAP `RGB`), as the game sends them.
const QUERY_START: &[u8] = b"\x1bP+q524742\x1b\\";

fn status(s: &vt100::Screen) -> String {
    s.contents().lines().last().unwrap_or_default().to_owned()
}

/// The game with `TERM=xterm-256color` and no `COLORTERM`, once its query has arrived; the
/// kitty-keys probe before it is answered by the harness.
fn queried(extra: &[(&str, &str)]) -> PtyRun {
    let mut env = vec![("COLORTERM", "")];
    env.extend_from_slice(extra);
    let mut run = PtyRun::spawn_with(&["--fps", "30"], SIZE, &env);
    run.wait_for("the colour query", |b| contains(b, QUERY_START));
    run
}

fn wait_status(run: &mut PtyRun, needle: &str) {
    run.wait_for_screen(needle, |s| status(s).contains(needle));
}

fn quit(mut run: PtyRun) {
    run.send(b"q");
    assert!(run.wait_exit().success());
}

#[test]
fn a_terminal_answering_xtgettcap_gets_truecolor() {
    let mut run = queried(&[]);
    run.send(b"\x1bP0+r524742\x1b\\\x1bP1+r5463\x1b\\\x1b[?62;22c");
    wait_status(&mut run, " truecolor (terminal said so)");
    quit(run);
}

#[test]
fn a_terminal_reporting_the_24_bit_sgr_gets_truecolor() {
    let mut run = queried(&[]);
    run.send(b"\x1bP1$r0;48;2;1;2;3m\x1b\\\x1b[?62;22c");
    wait_status(&mut run, " truecolor (terminal said so)");
    quit(run);
}

#[test]
fn a_terminal_answering_only_da1_keeps_the_term_rule_and_the_keys_typed_meanwhile() {
    // tmux 3.3 answers neither query. The player pressed M (hide the minimap) before the
    // answer came: the key is not lost.
    let mut run = queried(&[]);
    run.send(b"m\x1b[?1;2c");
    wait_status(&mut run, " 256 (TERM)");
    run.wait_for_screen("the minimap M hid", |s| {
        s.contents().contains("╭ ray") && !s.contents().contains("╭ map")
    });
    quit(run);
}

#[test]
fn a_terminal_answering_nothing_gets_the_term_rule_after_the_timeout() {
    let mut run = queried(&[]);
    wait_status(&mut run, " 256 (TERM)");
    // The O key cycles from the detected level: 256 → 16 → mono → truecolor → 256.
    for next in ["16", "mono", "truecolor", "256"] {
        run.send(b"o");
        wait_status(&mut run, &format!(" {next} (O key)"));
    }
    quit(run);
}

#[test]
fn a_quit_typed_during_the_query_quits() {
    let mut run = queried(&[]);
    run.send(b"q");
    assert!(run.wait_exit().success());
}

#[test]
fn colorterm_and_the_flag_are_not_second_guessed() {
    let mut run = PtyRun::spawn_with(&["--fps", "30"], SIZE, &[("COLORTERM", "truecolor")]);
    wait_status(&mut run, " truecolor (COLORTERM)");
    assert!(!contains(&run.bytes(), QUERY_START), "no query");
    quit(run);
    let mut run = PtyRun::spawn_with(
        &["maps/default.cub", "--colors", "16"],
        SIZE,
        &[("COLORTERM", "")],
    );
    wait_status(&mut run, " 16 (--colors)");
    assert!(!contains(&run.bytes(), QUERY_START), "no query");
    quit(run);
}

/// The end of the query where `TERM` names no colours: ENQ between two DA1 requests.
const ANSWERBACK_QUERY: &[u8] = b"\x1b[c\x05\x1b[c";

/// The game with `TERM=term` and no `COLORTERM`, once its whole query has arrived.
fn queried_as(term: &str, end: &[u8]) -> PtyRun {
    let mut run = PtyRun::spawn_with(&["--fps", "30"], SIZE, &[("COLORTERM", ""), ("TERM", term)]);
    run.wait_for("the colour query", |b| {
        contains(b, QUERY_START) && contains(b, end)
    });
    run
}

#[test]
fn putty_known_by_its_answers_gets_truecolor_and_its_answerback_is_not_typed() {
    // PuTTY 0.78's own answers, the answerback cut between reads. Typed, its `T` and `Y` would
    // do nothing visible, so an answerback of `m` (hide the minimap) shows it was not typed.
    let mut run = queried_as("xterm", ANSWERBACK_QUERY);
    run.send(b"\x1b[?6cPu");
    run.send(b"TTY\x1b[?6c");
    wait_status(&mut run, " truecolor (PuTTY)");
    quit(run);
    let mut run = queried_as("xterm", ANSWERBACK_QUERY);
    run.send(b"\x1b[?6cm");
    run.send(b"\x1b[?6c");
    wait_status(&mut run, " 256 (TERM)");
    run.wait_for_screen("the minimap", |s| s.contents().contains("╭ map"));
    quit(run);
}

#[test]
fn putty_on_a_slow_link_still_gets_truecolor_and_its_answerback_is_not_typed() {
    // PuTTY, then ssh, then the game: the answers come later than the 200 ms a local terminal
    // gets, but within the longer wait where ENQ went. `m` as its answerback shows it was not
    // typed (the minimap stays).
    let mut run = queried_as("xterm", ANSWERBACK_QUERY);
    std::thread::sleep(std::time::Duration::from_millis(400));
    run.send(b"\x1b[?6cm\x1b[?6c");
    wait_status(&mut run, " 256 (TERM)");
    run.wait_for_screen("the minimap", |s| s.contents().contains("╭ map"));
    quit(run);
    let mut run = queried_as("xterm", ANSWERBACK_QUERY);
    std::thread::sleep(std::time::Duration::from_millis(400));
    run.send(b"\x1b[?6cPuTTY\x1b[?6c");
    wait_status(&mut run, " truecolor (PuTTY)");
    quit(run);
}

#[test]
fn a_plain_xterm_answering_nothing_gets_256_and_the_console_16() {
    let mut run = queried_as("xterm", ANSWERBACK_QUERY);
    wait_status(&mut run, " 256 (TERM)");
    quit(run);
    // The Linux console answers DA1 as a VT102 and ignores ENQ.
    let mut run = queried_as("linux", ANSWERBACK_QUERY);
    run.send(b"\x1b[?6c\x1b[?6c");
    wait_status(&mut run, " 16 (TERM)");
    quit(run);
}

#[test]
fn no_enq_goes_to_a_terminal_whose_term_names_its_colours() {
    let mut run = queried(&[]);
    run.send(b"\x1b[?6c");
    wait_status(&mut run, " 256 (TERM)");
    assert!(!run.bytes().contains(&0x05), "ENQ sent to xterm-256color");
    quit(run);
}
