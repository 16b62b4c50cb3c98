//! Keystrokes from the raw byte stream an SSH client sends.
//!
//! A server has no tty layer between the client's terminal and us, so escape sequences (arrows,
//! function keys, the kitty keyboard protocol's `CSI … u`) arrive as bytes, possibly split across
//! reads. The parser keeps an unfinished sequence until the next read (bounded), and never panics
//! on garbage: whatever it cannot read is dropped.

/// A key the game or the session can act on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    /// A printable character as typed (Alt+char also arrives as the char).
    Char(char),
    /// Ctrl + a letter, lowercase (`Ctrl('c')` is Ctrl-C).
    Ctrl(char),
    Up,
    Down,
    Left,
    Right,
    Home,
    End,
    PageUp,
    PageDown,
    Insert,
    Delete,
    Enter,
    Tab,
    BackTab,
    Backspace,
    Esc,
    /// Function key F1–F12.
    F(u8),
}

/// Press, auto-repeat or release; only kitty-protocol terminals report the last two.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyKind {
    Press,
    Repeat,
    Release,
}

/// One key event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KeyEvent {
    pub key: Key,
    pub kind: KeyKind,
}

/// What the byte stream said.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputEvent {
    Key(KeyEvent),
    /// The terminal answered the kitty keyboard query (`CSI ? flags u`), so releases will come.
    KittyFlags(u32),
}

/// Longest escape sequence kept waiting for its end; longer ones are dropped as garbage.
pub const MAX_SEQUENCE: usize = 64;

const ESC: u8 = 0x1b;

/// Stateful parser: feed it each read, flush it when input has been quiet for a moment.
#[derive(Debug, Default, Clone)]
pub struct InputParser {
    pending: Vec<u8>,
}

/// The outcome of reading from the start of a byte slice.
enum Step {
    /// An event, and how many bytes it used.
    Event(InputEvent, usize),
    /// Bytes to drop without an event.
    Skip(usize),
    /// The slice ends inside a sequence; wait for more bytes.
    Incomplete,
}

impl InputParser {
    /// An empty parser.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Parses one read; complete events are appended to `out`, an unfinished tail is kept.
    pub fn feed(&mut self, bytes: &[u8], out: &mut Vec<InputEvent>) {
        self.pending.extend_from_slice(bytes);
        let mut at = 0;
        while at < self.pending.len() {
            match step(&self.pending[at..]) {
                Step::Event(ev, n) => {
                    out.push(ev);
                    at += n;
                }
                Step::Skip(n) => at += n,
                Step::Incomplete => break,
            }
        }
        self.pending.drain(..at);
    }

    /// Whether an unfinished sequence is waiting (the caller flushes it after a short pause).
    #[must_use]
    pub fn has_pending(&self) -> bool {
        !self.pending.is_empty()
    }

    /// Input went quiet: a lone ESC was the Esc key, `ESC O` was Alt+O; anything else is dropped.
    pub fn flush(&mut self, out: &mut Vec<InputEvent>) {
        match self.pending.as_slice() {
            [ESC] => out.push(press(Key::Esc)),
            [ESC, b'O'] => out.push(press(Key::Char('O'))),
            [ESC, b'['] => out.push(press(Key::Char('['))),
            _ => {}
        }
        self.pending.clear();
    }
}

fn press(key: Key) -> InputEvent {
    InputEvent::Key(KeyEvent {
        key,
        kind: KeyKind::Press,
    })
}

fn key_event(key: Key, kind: KeyKind) -> InputEvent {
    InputEvent::Key(KeyEvent { key, kind })
}

/// Reads one event (or skip) from the start of `b` (never empty).
fn step(b: &[u8]) -> Step {
    match b[0] {
        ESC => escape(b),
        0x80.. => utf8(b),
        byte => control_or_ascii(byte),
    }
}

fn control_or_ascii(byte: u8) -> Step {
    let key = match byte {
        b'\r' | b'\n' => Key::Enter,
        b'\t' => Key::Tab,
        0x7f | 0x08 => Key::Backspace,
        0x01..=0x1a => Key::Ctrl(char::from(b'a' + byte - 1)),
        0x20..=0x7e => Key::Char(char::from(byte)),
        _ => return Step::Skip(1),
    };
    Step::Event(press(key), 1)
}

fn utf8(b: &[u8]) -> Step {
    let len = match b[0] {
        0xc2..=0xdf => 2,
        0xe0..=0xef => 3,
        0xf0..=0xf4 => 4,
        _ => return Step::Skip(1),
    };
    if b.len() < len {
        // A continuation byte must follow; if one already seen is not one, don't wait.
        if b[1..].iter().any(|&c| c & 0xc0 != 0x80) {
            return Step::Skip(1);
        }
        return Step::Incomplete;
    }
    match std::str::from_utf8(&b[..len])
        .ok()
        .and_then(|s| s.chars().next())
    {
        Some(c) => Step::Event(press(Key::Char(c)), len),
        None => Step::Skip(1),
    }
}

fn escape(b: &[u8]) -> Step {
    let Some(&next) = b.get(1) else {
        return Step::Incomplete;
    };
    match next {
        b'[' => csi(b),
        b'O' => match b.get(2) {
            None => Step::Incomplete,
            Some(&f) => Step::Event(
                press(match f {
                    b'A' => Key::Up,
                    b'B' => Key::Down,
                    b'C' => Key::Right,
                    b'D' => Key::Left,
                    b'H' => Key::Home,
                    b'F' => Key::End,
                    b'P' => Key::F(1),
                    b'Q' => Key::F(2),
                    b'R' => Key::F(3),
                    b'S' => Key::F(4),
                    _ => return Step::Skip(3),
                }),
                3,
            ),
        },
        // Alt + a key arrives as ESC then the key: report the key itself.
        0x20..=0x7e | 0x80.. => match step(&b[1..]) {
            Step::Event(ev, n) => Step::Event(ev, n + 1),
            Step::Skip(n) => Step::Skip(n + 1),
            Step::Incomplete => Step::Incomplete,
        },
        // ESC ESC, or ESC before a control byte: the first was the Esc key on its own.
        _ => Step::Event(press(Key::Esc), 1),
    }
}

/// `ESC [ params intermediates final`, with the whole sequence bounded by [`MAX_SEQUENCE`].
fn csi(b: &[u8]) -> Step {
    for (i, &c) in b.iter().enumerate().skip(2) {
        if i >= MAX_SEQUENCE {
            return Step::Skip(2);
        }
        match c {
            0x20..=0x3f => {}
            0x40..=0x7e => return csi_final(&b[2..i], c, i + 1),
            // A byte that cannot be inside a CSI: drop the `ESC [` and read on from there.
            _ => return Step::Skip(2),
        }
    }
    if b.len() >= MAX_SEQUENCE {
        Step::Skip(2)
    } else {
        Step::Incomplete
    }
}

/// Parsed numeric fields: `1;5:3` → [[1], [5, 3]]; missing numbers are `None`.
fn fields(params: &[u8]) -> Vec<Vec<Option<u32>>> {
    params
        .split(|&c| c == b';')
        .map(|f| {
            f.split(|&c| c == b':')
                .map(|n| {
                    if n.is_empty() || !n.iter().all(u8::is_ascii_digit) {
                        return None;
                    }
                    Some(n.iter().fold(0u32, |acc, &d| {
                        acc.saturating_mul(10).saturating_add(u32::from(d - b'0'))
                    }))
                })
                .collect()
        })
        .collect()
}

fn field(fs: &[Vec<Option<u32>>], i: usize, j: usize) -> Option<u32> {
    fs.get(i).and_then(|f| f.get(j)).copied().flatten()
}

fn csi_final(params: &[u8], fin: u8, len: usize) -> Step {
    // Replies and private modes: `CSI ? flags u` is the kitty keyboard answer; others are ignored.
    if let Some(&lead) = params.first() {
        if matches!(lead, b'?' | b'<' | b'>' | b'=') {
            if lead == b'?' && fin == b'u' {
                let flags = field(&fields(&params[1..]), 0, 0).unwrap_or(0);
                return Step::Event(InputEvent::KittyFlags(flags), len);
            }
            return Step::Skip(len);
        }
    }
    let fs = fields(params);
    let mods = field(&fs, 1, 0).unwrap_or(1).saturating_sub(1);
    let kind = match field(&fs, 1, 1) {
        Some(2) => KeyKind::Repeat,
        Some(3) => KeyKind::Release,
        _ => KeyKind::Press,
    };
    let first = field(&fs, 0, 0);
    let key = match fin {
        b'A' => Key::Up,
        b'B' => Key::Down,
        b'C' => Key::Right,
        b'D' => Key::Left,
        b'H' => Key::Home,
        b'F' => Key::End,
        b'Z' => Key::BackTab,
        b'P' => Key::F(1),
        b'Q' => Key::F(2),
        // `CSI row;col R` is a cursor position report; F3 is `CSI R` or `CSI 1;mods R`.
        b'R' if first.is_none() || first == Some(1) => Key::F(3),
        b'S' => Key::F(4),
        b'~' => match tilde_key(first) {
            Some(k) => k,
            None => return Step::Skip(len),
        },
        b'u' => match kitty_key(first, mods) {
            Some(k) => k,
            None => return Step::Skip(len),
        },
        _ => return Step::Skip(len),
    };
    Step::Event(key_event(key, kind), len)
}

fn tilde_key(code: Option<u32>) -> Option<Key> {
    Some(match code? {
        1 | 7 => Key::Home,
        2 => Key::Insert,
        3 => Key::Delete,
        4 | 8 => Key::End,
        5 => Key::PageUp,
        6 => Key::PageDown,
        n @ 11..=15 => Key::F(u8::try_from(n - 10).ok()?),
        n @ 17..=21 => Key::F(u8::try_from(n - 11).ok()?),
        23 => Key::F(11),
        24 => Key::F(12),
        _ => return None,
    })
}

/// Kitty's `CSI code ; mods u`: `mods` is the modifier bitmask (1 shift, 2 alt, 4 ctrl).
fn kitty_key(code: Option<u32>, mods: u32) -> Option<Key> {
    let code = code?;
    Some(match code {
        27 => Key::Esc,
        13 => Key::Enter,
        9 => Key::Tab,
        127 | 8 => Key::Backspace,
        57417 => Key::Left,
        57418 => Key::Right,
        57419 => Key::Up,
        57420 => Key::Down,
        _ => {
            let c = char::from_u32(code).filter(|c| !c.is_control())?;
            if mods & 4 != 0 && c.is_ascii_alphabetic() {
                Key::Ctrl(c.to_ascii_lowercase())
            } else {
                Key::Char(c)
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn parse(chunks: &[&[u8]]) -> Vec<InputEvent> {
        let mut p = InputParser::new();
        let mut out = Vec::new();
        for c in chunks {
            p.feed(c, &mut out);
        }
        p.flush(&mut out);
        out
    }

    fn keys(evs: &[InputEvent]) -> Vec<Key> {
        evs.iter()
            .filter_map(|e| match e {
                InputEvent::Key(k) => Some(k.key),
                InputEvent::KittyFlags(_) => None,
            })
            .collect()
    }

    #[test]
    fn plain_keys_and_controls() {
        let evs = parse(&[b"wA\r\t\x7f\x03 "]);
        assert_eq!(
            keys(&evs),
            [
                Key::Char('w'),
                Key::Char('A'),
                Key::Enter,
                Key::Tab,
                Key::Backspace,
                Key::Ctrl('c'),
                Key::Char(' ')
            ]
        );
    }

    #[test]
    fn arrows_in_both_modes_and_split_across_reads() {
        assert_eq!(
            keys(&parse(&[b"\x1b[A\x1bOB\x1b[1;5C"])),
            [Key::Up, Key::Down, Key::Right]
        );
        assert_eq!(keys(&parse(&[b"\x1b", b"[", b"D"])), [Key::Left]);
        assert_eq!(keys(&parse(&[b"\x1b[1;", b"5D"])), [Key::Left]);
    }

    #[test]
    fn lone_escape_waits_for_the_flush() {
        let mut p = InputParser::new();
        let mut out = Vec::new();
        p.feed(b"\x1b", &mut out);
        assert!(out.is_empty() && p.has_pending());
        p.flush(&mut out);
        assert_eq!(keys(&out), [Key::Esc]);
        assert!(!p.has_pending());
        assert_eq!(keys(&parse(&[b"\x1b\x1b[A"])), [Key::Esc, Key::Up]);
    }

    #[test]
    fn kitty_keys_with_event_types() {
        let evs = parse(&[b"\x1b[119u\x1b[119;1:2u\x1b[119;1:3u\x1b[99;5u\x1b[1;1:3A\x1b[27u"]);
        let want = [
            (Key::Char('w'), KeyKind::Press),
            (Key::Char('w'), KeyKind::Repeat),
            (Key::Char('w'), KeyKind::Release),
            (Key::Ctrl('c'), KeyKind::Press),
            (Key::Up, KeyKind::Release),
            (Key::Esc, KeyKind::Press),
        ];
        let got: Vec<_> = evs
            .iter()
            .map(|e| match e {
                InputEvent::Key(k) => (k.key, k.kind),
                InputEvent::KittyFlags(_) => panic!("no flags here"),
            })
            .collect();
        assert_eq!(got, want);
        assert_eq!(parse(&[b"\x1b[?11u"]), [InputEvent::KittyFlags(11)]);
    }

    #[test]
    fn tilde_keys_utf8_and_alt() {
        assert_eq!(
            keys(&parse(&[b"\x1b[3~\x1b[5~\x1b[15~\x1b[24~"])),
            [Key::Delete, Key::PageUp, Key::F(5), Key::F(12)]
        );
        assert_eq!(
            keys(&parse(&[
                "é".as_bytes()[..1].as_ref(),
                &"é".as_bytes()[1..]
            ])),
            [Key::Char('é')]
        );
        assert_eq!(keys(&parse(&[b"\x1bw"])), [Key::Char('w')]);
    }

    #[test]
    fn overlong_and_broken_sequences_are_dropped() {
        let mut long = b"\x1b[".to_vec();
        long.extend(std::iter::repeat_n(b'1', 200));
        long.extend(b"Aw");
        let evs = parse(&[&long]);
        // The ESC [ is dropped, the digits read as characters, and parsing goes on.
        assert_eq!(keys(&evs).last(), Some(&Key::Char('w')));
        assert_eq!(
            keys(&parse(&[b"\x1b[12\x03x"])),
            [
                Key::Char('1'),
                Key::Char('2'),
                Key::Ctrl('c'),
                Key::Char('x')
            ]
        );
        assert!(keys(&parse(&[b"\xff\xfe\xc3"])).is_empty());
        // Cursor position and device attribute replies are not keys.
        assert!(keys(&parse(&[b"\x1b[24;80R\x1b[?62;22c"])).is_empty());
    }

    proptest! {
        #[test]
        fn garbage_never_panics_and_splitting_does_not_matter(
            bytes in proptest::collection::vec(any::<u8>(), 0..400),
            cuts in proptest::collection::vec(any::<prop::sample::Index>(), 0..8),
        ) {
            let whole = parse(&[&bytes]);
            let mut points: Vec<usize> = cuts.iter().map(|i| i.index(bytes.len() + 1)).collect();
            points.sort_unstable();
            let mut chunks: Vec<&[u8]> = Vec::new();
            let mut last = 0;
            for p in points {
                chunks.push(&bytes[last..p]);
                last = p;
            }
            chunks.push(&bytes[last..]);
            prop_assert_eq!(parse(&chunks), whole);
        }

        #[test]
        fn pending_stays_bounded(bytes in proptest::collection::vec(any::<u8>(), 0..2000)) {
            let mut p = InputParser::new();
            let mut out = Vec::new();
            for chunk in bytes.chunks(7) {
                p.feed(chunk, &mut out);
                prop_assert!(p.pending.len() < MAX_SEQUENCE);
            }
        }

        #[test]
        fn sequences_mixed_with_text_survive_any_split(
            parts in proptest::collection::vec(prop::sample::select(vec![
                &b"\x1b[A"[..], b"\x1b[1;1:3B", b"\x1bOC", b"w", b"\x1b[119;1:3u", b"\x1b[6~", "é".as_bytes(),
            ]), 0..30),
            split in any::<prop::sample::Index>(),
        ) {
            let bytes: Vec<u8> = parts.concat();
            let at = split.index(bytes.len() + 1);
            let evs = parse(&[&bytes[..at], &bytes[at..]]);
            prop_assert_eq!(evs.len(), parts.len());
        }
    }
}
