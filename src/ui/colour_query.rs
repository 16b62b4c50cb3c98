//! Asking the terminal itself whether it shows 24-bit colour (pure: bytes in, answer out).
//!
//! `TERM=xterm-256color` is what most 24-bit terminals claim, and OpenSSH does not forward
//! `COLORTERM`, so the game asks: XTGETTCAP for the `RGB` and `Tc` capabilities, and DECRQSS of
//! a 24-bit background it has just set (a terminal that keeps the exact colour reports it
//! back). A primary device attributes request (DA1) goes last: every terminal answers it, and
//! in order, so its reply means "no more answers are coming" (tmux 3.3 answers only that).
//! Bytes that are not a reply (keys the player typed meanwhile) are handed back, in order.

/// What is sent: XTGETTCAP `RGB`, XTGETTCAP `Tc`, a 24-bit SGR then DECRQSS of it, the SGR
/// reset, DA1.
pub const QUERY: &[u8] =
    b"\x1bP+q524742\x1b\\\x1bP+q5463\x1b\\\x1b[48;2;1;2;3m\x1bP$qm\x1b\\\x1b[0m\x1b[c";

/// The total time a start-up colour query may take when the terminal never sends DA1's reply.
pub const QUERY_PATIENCE: std::time::Duration = std::time::Duration::from_millis(200);

const ESC: u8 = 0x1b;

/// Input kept from the query's time to be handled as keys afterwards: far more than anyone
/// types in a fraction of a second; a flood beyond it is dropped, not buffered.
const MAX_KEPT: usize = 4096;

/// Reads a terminal's replies to [`QUERY`] out of its input stream.
#[derive(Debug, Default)]
pub struct ReplyScanner {
    /// Bytes not yet classified (a reply may be cut between reads).
    pending: Vec<u8>,
    yes: bool,
    no: bool,
    done: bool,
    other: Vec<u8>,
}

/// One step of scanning `pending` from its start.
enum Scan {
    /// A whole reply (or DA1) of this length.
    Reply(usize, Answer),
    /// Could still become a reply: wait for more bytes.
    Incomplete,
    /// The first byte is not the start of a reply.
    NotReply,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Answer {
    TrueColor,
    NotTrueColor,
    Other,
    DeviceAttributes,
}

impl ReplyScanner {
    /// Takes the next bytes read from the terminal. Linear in the bytes fed, whatever they
    /// are (a client may paste megabytes while the query runs).
    pub fn feed(&mut self, bytes: &[u8]) {
        self.pending.extend_from_slice(bytes);
        let mut at = 0;
        while at < self.pending.len() {
            match scan(&self.pending[at..]) {
                Scan::Incomplete => break,
                Scan::NotReply => {
                    if self.other.len() < MAX_KEPT {
                        self.other.push(self.pending[at]);
                    }
                    at += 1;
                }
                Scan::Reply(n, answer) => {
                    at += n;
                    match answer {
                        Answer::TrueColor => self.yes = true,
                        Answer::NotTrueColor => self.no = true,
                        Answer::Other => {}
                        Answer::DeviceAttributes => self.done = true,
                    }
                }
            }
        }
        self.pending.drain(..at);
    }

    /// Whether the DA1 reply came: nothing more will answer the query.
    #[must_use]
    pub fn done(&self) -> bool {
        self.done
    }

    /// `Some(true)` when any reply said 24-bit, `Some(false)` when replies came and none did,
    /// `None` when the terminal said nothing about colour.
    #[must_use]
    pub fn truecolor(&self) -> Option<bool> {
        if self.yes {
            Some(true)
        } else if self.no {
            Some(false)
        } else {
            None
        }
    }

    /// The answer and every byte that was not a reply (an unfinished sequence included), in
    /// the order they came.
    #[must_use]
    pub fn finish(mut self) -> (Option<bool>, Vec<u8>) {
        let answer = self.truecolor();
        self.other.append(&mut self.pending);
        (answer, self.other)
    }
}

/// Classifies the bytes at the start of `b`.
fn scan(b: &[u8]) -> Scan {
    if b[0] != ESC {
        return Scan::NotReply;
    }
    let Some(&kind) = b.get(1) else {
        return Scan::Incomplete;
    };
    match kind {
        b'P' => scan_dcs(b),
        b'[' => scan_da1(b),
        _ => Scan::NotReply,
    }
}

/// `ESC P 1 + r … ESC \` (XTGETTCAP), `ESC P 1 $ r … ESC \` (DECRQSS), or their `0` failures.
fn scan_dcs(b: &[u8]) -> Scan {
    let head = &b[2..b.len().min(5)];
    let known: [&[u8]; 4] = [b"1+r", b"0+r", b"1$r", b"0$r"];
    if !known.iter().any(|k| k.starts_with(head)) {
        return Scan::NotReply;
    }
    if head.len() < 3 {
        return Scan::Incomplete;
    }
    let Some(end) = b.windows(2).position(|w| w == b"\x1b\\") else {
        // A reply is short; a long run without its terminator is not one.
        return if b.len() > 256 {
            Scan::NotReply
        } else {
            Scan::Incomplete
        };
    };
    let body = &b[5..end];
    let answer = match head {
        b"1+r" => Answer::TrueColor,
        b"1$r" if sgr_is_our_truecolour(body) => Answer::TrueColor,
        b"1$r" | b"0$r" | b"0+r" => Answer::NotTrueColor,
        _ => Answer::Other,
    };
    Scan::Reply(end + 2, answer)
}

/// Whether a DECRQSS SGR report still holds the exact colour `48;2;1;2;3` we set (with `;` or
/// `:` separators, with or without a colour-space field).
fn sgr_is_our_truecolour(body: &[u8]) -> bool {
    let text: String = String::from_utf8_lossy(body)
        .trim_end_matches('m')
        .replace(':', ";");
    let fields: Vec<&str> = text.split(';').collect();
    fields.windows(5).any(|w| w == ["48", "2", "1", "2", "3"])
        || fields.windows(6).any(|w| {
            w[0] == "48"
                && w[1] == "2"
                && (w[2].is_empty() || w[2] == "0")
                && w[3..] == ["1", "2", "3"]
        })
}

/// `ESC [ ? digits ; … c`: the device attributes reply.
fn scan_da1(b: &[u8]) -> Scan {
    match b.get(2) {
        None => return Scan::Incomplete,
        Some(b'?') => {}
        Some(_) => return Scan::NotReply,
    }
    for (i, &c) in b.iter().enumerate().skip(3) {
        match c {
            b'0'..=b'9' | b';' => {}
            b'c' => return Scan::Reply(i + 1, Answer::DeviceAttributes),
            _ => return Scan::NotReply,
        }
        if i > 64 {
            return Scan::NotReply;
        }
    }
    Scan::Incomplete
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan_all(chunks: &[&[u8]]) -> (bool, Option<bool>, Vec<u8>) {
        let mut s = ReplyScanner::default();
        for c in chunks {
            s.feed(c);
        }
        let done = s.done();
        let (answer, rest) = s.finish();
        (done, answer, rest)
    }

    #[test]
    fn a_flood_while_asking_is_scanned_in_linear_time_and_kept_bounded() {
        let mut s = ReplyScanner::default();
        let chunk: Vec<u8> = b"wasd\x1b[9;9;9".repeat(4096);
        for _ in 0..64 {
            s.feed(&chunk);
        }
        s.feed(b"\x1b[?62;22c");
        assert!(s.done());
        let (answer, rest) = s.finish();
        assert_eq!(answer, None);
        assert!(
            rest.starts_with(b"wasd") && rest.len() <= MAX_KEPT + 256,
            "{}",
            rest.len()
        );
    }

    #[test]
    fn xtgettcap_rgb_or_tc_means_truecolor() {
        let r = scan_all(&[b"\x1bP1+r524742=382f382f38\x1b\\\x1bP0+r5463\x1b\\\x1b[?62;22c"]);
        assert_eq!(r, (true, Some(true), vec![]));
        let r = scan_all(&[b"\x1bP0+r524742\x1b\\\x1bP1+r5463\x1b\\\x1b[?1;2c"]);
        assert_eq!(r, (true, Some(true), vec![]));
    }

    #[test]
    fn decrqss_reporting_the_exact_colour_means_truecolor() {
        for reply in [
            &b"\x1bP1$r0;48;2;1;2;3m\x1b\\"[..],
            b"\x1bP1$r48:2::1:2:3m\x1b\\",
            b"\x1bP1$r0;48:2:0:1:2:3m\x1b\\",
        ] {
            let r = scan_all(&[reply, b"\x1b[?62c"]);
            assert_eq!(r, (true, Some(true), vec![]), "{reply:?}");
        }
        // Rounded to the 256-colour cube: not 24-bit.
        let r = scan_all(&[b"\x1bP1$r0;48;5;16m\x1b\\\x1b[?62c"]);
        assert_eq!(r, (true, Some(false), vec![]));
    }

    #[test]
    fn only_da1_means_no_answer_and_keys_are_kept_in_order() {
        // tmux 3.3: nothing but DA1; the player typed "w" before it and "a" after it.
        let r = scan_all(&[b"w\x1b[?1;2c", b"a"]);
        assert_eq!(r, (true, None, b"wa".to_vec()));
    }

    #[test]
    fn a_kitty_flags_reply_is_not_taken_for_da1() {
        // Over SSH the session's kitty query goes out just before: its reply is input.
        let r = scan_all(&[b"\x1b[?1u\x1bP1+r524742\x1b\\\x1b[?62;22c"]);
        assert_eq!(r, (true, Some(true), b"\x1b[?1u".to_vec()));
    }

    #[test]
    fn replies_split_between_reads_are_joined() {
        let all: &[u8] = b"\x1bP1+r5463\x1b\\\x1b[?62;22c";
        for cut in 1..all.len() {
            let r = scan_all(&[&all[..cut], &all[cut..]]);
            assert_eq!(r, (true, Some(true), vec![]), "cut at {cut}");
        }
    }

    #[test]
    fn nothing_at_all_is_no_answer_and_other_escapes_pass_through() {
        assert_eq!(scan_all(&[]), (false, None, vec![]));
        // An arrow key and a lone Esc are keys, not replies; an unfinished reply is returned.
        let r = scan_all(&[b"\x1b[A\x1bx\x1bP1+"]);
        assert_eq!(r, (false, None, b"\x1b[A\x1bx\x1bP1+".to_vec()));
    }
}
