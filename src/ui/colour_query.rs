//! Asking the terminal itself whether it shows 24-bit colour (pure: bytes in, answer out).
//!
//! `TERM=xterm-256color` is what most 24-bit terminals claim, and OpenSSH does not forward
//! `COLORTERM`, so the game asks: XTGETTCAP for the `RGB` and `Tc` capabilities, and DECRQSS of
//! a 24-bit background it has just set (a terminal that keeps the exact colour reports it
//! back). A primary device attributes request (DA1) goes last: every terminal answers it, and
//! in order, so its reply means "no more answers are coming" (tmux 3.3 answers only that).
//! Bytes that are not a reply (keys the player typed meanwhile) are handed back, in order.
//!
//! Where `TERM` names no colours (a plain `xterm`, as PuTTY sends) and `COLORTERM` says nothing,
//! ENQ goes too, between two DA1s ([`ANSWERBACK_QUERY`]): the terminal's answerback (`PuTTY`) is
//! whatever arrives between the two DA1 replies, so it is told apart from keys and swallowed.
//! [`rules`] turns the answers into a colour level, for the local game and the server alike.

pub mod rules;

/// What is sent: XTGETTCAP `RGB`, XTGETTCAP `Tc`, a 24-bit SGR then DECRQSS of it, the SGR
/// reset, DA1.
pub const QUERY: &[u8] =
    b"\x1bP+q524742\x1b\\\x1bP+q5463\x1b\\\x1b[48;2;1;2;3m\x1bP$qm\x1b\\\x1b[0m\x1b[c";

/// Sent after [`QUERY`] where the answerback matters: ENQ, then DA1 again. Answers come in
/// order, so the answerback is what arrives between the first DA1 reply and the second.
pub const ANSWERBACK_QUERY: &[u8] = b"\x05\x1b[c";

/// PuTTY's answerback to ENQ unless its user changed it ("Answerback to ^E").
pub const PUTTY_ANSWERBACK: &[u8] = b"PuTTY";

/// The bytes to send: [`QUERY`], then [`ANSWERBACK_QUERY`] when `answerback` (only where its
/// answer matters, see [`crate::encode::ColourChoice::worth_an_answerback`]).
#[must_use]
pub fn query(answerback: bool) -> Vec<u8> {
    if answerback {
        [QUERY, ANSWERBACK_QUERY].concat()
    } else {
        QUERY.to_vec()
    }
}

/// The total time a start-up colour query may take when the terminal never sends DA1's reply.
pub const QUERY_PATIENCE: std::time::Duration = std::time::Duration::from_millis(200);

/// The local game's patience when ENQ went too: an answerback later than the wait would reach
/// the game as keys (nothing strips it once crossterm reads them), so a terminal on a slow link
/// (PuTTY, then ssh, then the game) gets longer. Only terminals that never answer DA1 wait it all.
pub const ANSWERBACK_PATIENCE: std::time::Duration = std::time::Duration::from_secs(1);

const ESC: u8 = 0x1b;

/// Input kept from the query's time to be handled as keys afterwards: far more than anyone
/// types in a fraction of a second; a flood beyond it is dropped, not buffered.
const MAX_KEPT: usize = 4096;

/// Longest answerback kept: PuTTY's is five bytes; a longer one is swallowed all the same.
const MAX_ANSWERBACK: usize = 64;

/// What a terminal said of itself in answer to the query.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Answers {
    /// `Some(true)` when a reply said 24-bit, `Some(false)` when replies came and none did,
    /// `None` when the terminal said nothing about colour.
    pub truecolor: Option<bool>,
    /// The parameters of the first DA1 reply (`"6"` for `ESC [ ? 6 c`, a VT102), if it came.
    pub device: Option<String>,
    /// The answerback to ENQ (empty for a terminal that has none), when it was asked for and
    /// the DA1 reply before it came.
    pub answerback: Option<Vec<u8>>,
}

/// Reads a terminal's replies to [`QUERY`] out of its input stream.
#[derive(Debug, Default)]
pub struct ReplyScanner {
    /// Bytes not yet classified (a reply may be cut between reads).
    pending: Vec<u8>,
    yes: bool,
    no: bool,
    /// DA1 replies seen (two are due when the answerback was asked for).
    da1: u8,
    /// The first DA1 reply's parameters.
    device: Option<String>,
    /// Whether [`ANSWERBACK_QUERY`] went out after [`QUERY`].
    asked_answerback: bool,
    /// What arrived between the two DA1 replies.
    answerback: Vec<u8>,
    /// The answerback came before the first DA1 reply instead (an out-of-order answer).
    answerback_early: bool,
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
    /// A scanner for [`query`]`(answerback)`'s replies.
    #[must_use]
    pub fn new(answerback: bool) -> Self {
        Self {
            asked_answerback: answerback,
            ..Self::default()
        }
    }

    /// Whether a byte that is not a reply belongs to the answerback: it came after the first
    /// DA1 reply and before the second.
    fn in_answerback(&self) -> bool {
        self.asked_answerback && self.da1 == 1 && !self.answerback_early
    }

    /// Takes the next bytes read from the terminal. Linear in the bytes fed, whatever they
    /// are (a client may paste megabytes while the query runs).
    pub fn feed(&mut self, bytes: &[u8]) {
        self.pending.extend_from_slice(bytes);
        let mut at = 0;
        while at < self.pending.len() {
            match scan(&self.pending[at..]) {
                Scan::Incomplete => break,
                Scan::NotReply => {
                    if self.in_answerback() {
                        if self.answerback.len() < MAX_ANSWERBACK {
                            self.answerback.push(self.pending[at]);
                        }
                    } else if self.other.len() < MAX_KEPT {
                        self.other.push(self.pending[at]);
                    }
                    at += 1;
                }
                Scan::Reply(n, answer) => {
                    match answer {
                        Answer::TrueColor => self.yes = true,
                        Answer::NotTrueColor => self.no = true,
                        Answer::Other => {}
                        Answer::DeviceAttributes => {
                            let params = &self.pending[at + 3..at + n - 1];
                            self.on_device_attributes(params.to_vec());
                        }
                    }
                    at += n;
                }
            }
        }
        self.pending.drain(..at);
    }

    /// Counts a DA1 reply; the first one's parameters are the device's.
    fn on_device_attributes(&mut self, params: Vec<u8>) {
        self.da1 = self.da1.saturating_add(1);
        if self.da1 > 1 {
            return;
        }
        self.device = Some(String::from_utf8_lossy(&params).into_owned());
        // A terminal that answered ENQ ahead of the DA1 sent before it: its default answerback
        // right before this reply is taken as the answerback, not as keys.
        if self.asked_answerback && self.other.ends_with(PUTTY_ANSWERBACK) {
            self.other
                .truncate(self.other.len() - PUTTY_ANSWERBACK.len());
            self.answerback = PUTTY_ANSWERBACK.to_vec();
            self.answerback_early = true;
        }
    }

    /// Whether the last DA1 reply due came: nothing more will answer the query.
    #[must_use]
    pub fn done(&self) -> bool {
        self.da1 >= 1 && (!self.asked_answerback || self.da1 >= 2 || self.answerback_early)
    }

    /// Whether the terminal has begun answering but is not done: the rest is on its way (worth
    /// a little more patience, rather than letting an answerback arrive as keys).
    #[must_use]
    pub fn answering(&self) -> bool {
        self.da1 >= 1 && !self.done()
    }

    /// Everything the terminal said so far.
    #[must_use]
    pub fn answers(&self) -> Answers {
        Answers {
            truecolor: self.truecolor(),
            device: self.device.clone(),
            answerback: (self.asked_answerback && self.da1 >= 1).then(|| self.answerback.clone()),
        }
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

    /// The answers and every byte that was not a reply (an unfinished sequence included), in
    /// the order they came. An answerback still unfinished is swallowed, not handed back.
    #[must_use]
    pub fn finish(mut self) -> (Answers, Vec<u8>) {
        let answers = self.answers();
        let mut keys = self.take_keys();
        keys.append(&mut self.take_unfinished());
        (answers, keys)
    }

    /// The bytes that were not a reply so far (keys), leaving an unfinished sequence to be
    /// completed by the next bytes fed: for reading on past the patience, when late replies
    /// are still to be stripped from the keys.
    #[must_use]
    pub fn take_keys(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.other)
    }

    /// Whether bytes wait for more to tell whether they are a reply.
    #[must_use]
    pub fn has_unfinished(&self) -> bool {
        !self.pending.is_empty()
    }

    /// The unfinished sequence, when nothing more came to complete it: keys (a lone Esc), or
    /// nothing when it is part of an answerback.
    #[must_use]
    pub fn take_unfinished(&mut self) -> Vec<u8> {
        let unfinished = std::mem::take(&mut self.pending);
        if self.in_answerback() {
            Vec::new()
        } else {
            unfinished
        }
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
    use proptest::prelude::any;

    fn scan_all(chunks: &[&[u8]]) -> (bool, Option<bool>, Vec<u8>) {
        let mut s = ReplyScanner::default();
        for c in chunks {
            s.feed(c);
        }
        let done = s.done();
        let (answers, rest) = s.finish();
        (done, answers.truecolor, rest)
    }

    /// Feeds `chunks` to a scanner that asked for the answerback.
    fn with_answerback(chunks: &[&[u8]]) -> (bool, Answers, Vec<u8>) {
        let mut s = ReplyScanner::new(true);
        for c in chunks {
            s.feed(c);
        }
        let done = s.done();
        let (answers, rest) = s.finish();
        (done, answers, rest)
    }

    fn putty() -> Answers {
        Answers {
            truecolor: None,
            device: Some("6".into()),
            answerback: Some(b"PuTTY".to_vec()),
        }
    }

    #[test]
    fn the_answerback_query_follows_the_colour_query_only_when_asked() {
        assert_eq!(query(false), QUERY);
        assert_eq!(query(true), b"\x1bP+q524742\x1b\\\x1bP+q5463\x1b\\\x1b[48;2;1;2;3m\x1bP$qm\x1b\\\x1b[0m\x1b[c\x05\x1b[c");
    }

    #[test]
    fn the_answerback_between_the_two_da1_replies_is_swallowed_and_kept_apart() {
        // PuTTY: no XTGETTCAP or DECRQSS reply; DA1, its answerback, DA1. The player typed "w"
        // before the terminal read the query and "a" after it answered.
        let r = with_answerback(&[b"w\x1b[?6cPuTTY\x1b[?6ca"]);
        assert_eq!(r, (true, putty(), b"wa".to_vec()));
    }

    #[test]
    fn an_answerback_split_across_reads_anywhere_is_swallowed() {
        let all: &[u8] = b"m\x1b[?6cPuTTY\x1b[?6c";
        for cut in 1..all.len() {
            for cut2 in cut..all.len() {
                let r = with_answerback(&[&all[..cut], &all[cut..cut2], &all[cut2..]]);
                assert_eq!(r, (true, putty(), b"m".to_vec()), "cut at {cut}, {cut2}");
            }
        }
        // One byte a read.
        let bytes: Vec<&[u8]> = all.chunks(1).collect();
        assert_eq!(with_answerback(&bytes), (true, putty(), b"m".to_vec()));
    }

    #[test]
    fn an_answerback_still_arriving_is_not_done_and_never_handed_back_as_keys() {
        // The first DA1 reply and part of the answerback came; the rest is late.
        let mut s = ReplyScanner::new(true);
        s.feed(b"\x1b[?6cPu");
        assert!(!s.done());
        assert!(s.answering());
        s.feed(b"TT");
        let (answers, rest) = s.finish();
        assert_eq!(answers.answerback.as_deref(), Some(&b"PuTT"[..]));
        assert_eq!(rest, b"");
        // Cut inside a control sequence of a changed answerback: still swallowed.
        let (_, _, rest) = with_answerback(&[b"\x1b[?6chi\x1b"]);
        assert_eq!(rest, b"");
    }

    #[test]
    fn no_answerback_or_a_changed_one_is_what_it_is() {
        // xterm: replies, its (empty) answerback, DA1 twice.
        let r = with_answerback(&[b"\x1bP1+r524742\x1b\\\x1b[?64;1;2;6;22c\x1b[?64;1;2;6;22c"]);
        assert!(r.0);
        assert_eq!(r.1.truecolor, Some(true));
        assert_eq!(r.1.device.as_deref(), Some("64;1;2;6;22"));
        assert_eq!(r.1.answerback.as_deref(), Some(&b""[..]));
        // A PuTTY whose answerback says something else.
        let r = with_answerback(&[b"\x1b[?6cKiTTY\x1b[?6c"]);
        assert_eq!(r.1.answerback.as_deref(), Some(&b"KiTTY"[..]));
        assert_eq!(r.2, b"");
        // A very long answerback is swallowed whole, kept bounded.
        let long = [
            b"\x1b[?6c".to_vec(),
            vec![b'x'; 1000],
            b"\x1b[?6cq".to_vec(),
        ]
        .concat();
        let r = with_answerback(&[&long]);
        assert_eq!(r.1.answerback.map(|a| a.len()), Some(MAX_ANSWERBACK));
        assert_eq!(r.2, b"q");
    }

    #[test]
    fn only_one_da1_reply_means_not_done_and_what_follows_it_is_the_answerback() {
        // A terminal that answered ENQ and DA1 only once, DA1 first: the answerback follows it.
        let mut s = ReplyScanner::new(true);
        s.feed(b"\x1b[?6cPuTTY");
        assert!(!s.done());
        let (answers, rest) = s.finish();
        assert_eq!((answers, rest), (putty(), vec![]));
    }

    #[test]
    fn the_default_answerback_right_before_the_first_da1_reply_is_taken_too() {
        // Answered out of order (ENQ before the DA1 sent ahead of it): PuTTY's answerback
        // right before the reply is still the answerback, and the query is done.
        let r = with_answerback(&[b"qPu", b"TTY\x1b[?6c"]);
        assert_eq!(r, (true, putty(), b"q".to_vec()));
    }

    #[test]
    fn without_the_answerback_asked_text_between_da1_replies_is_keys() {
        let mut s = ReplyScanner::default();
        s.feed(b"\x1b[?6cPuTTY\x1b[?6c");
        assert!(s.done());
        let (answers, rest) = s.finish();
        assert_eq!(answers.answerback, None);
        assert_eq!(answers.device.as_deref(), Some("6"));
        assert_eq!(rest, b"PuTTY");
    }

    proptest::proptest! {
        #[test]
        fn any_answerback_cut_anywhere_is_swallowed_and_the_keys_around_it_kept(
            before in "[a-z ]{0,8}",
            answerback in "[ -~]{0,20}",
            after in "[a-z ]{0,8}",
            cuts in proptest::collection::vec(any::<proptest::sample::Index>(), 0..6),
        ) {
            let stream = [
                before.as_bytes(),
                b"\x1b[?6c",
                answerback.as_bytes(),
                b"\x1b[?6c",
                after.as_bytes(),
            ]
            .concat();
            let mut points: Vec<usize> = cuts.iter().map(|i| i.index(stream.len() + 1)).collect();
            points.sort_unstable();
            let mut chunks: Vec<&[u8]> = Vec::new();
            let mut last = 0;
            for p in points {
                chunks.push(&stream[last..p]);
                last = p;
            }
            chunks.push(&stream[last..]);
            let (done, answers, keys) = with_answerback(&chunks);
            proptest::prop_assert!(done);
            proptest::prop_assert_eq!(answers.answerback, Some(answerback.into_bytes()));
            proptest::prop_assert_eq!(keys, [before, after].concat().into_bytes());
        }
    }

    #[test]
    fn no_da1_reply_means_no_answerback_and_keys_are_kept() {
        let r = with_answerback(&[b"wasd"]);
        assert_eq!(r, (false, Answers::default(), b"wasd".to_vec()));
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
        assert_eq!(
            answer,
            Answers {
                device: Some("62;22".into()),
                ..Answers::default()
            }
        );
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
