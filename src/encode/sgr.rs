//! Select Graphic Rendition: the shortest sequence that moves the terminal from one fg/bg pair to another.

use super::level::ColorLevel;
use super::palette::{Code, DEFAULT};

/// Decimal digits of each byte value (truecolor parameters are three of them).
const DIGITS: [u8; 256] = {
    let mut t = [3u8; 256];
    let mut i = 0;
    while i < 100 {
        t[i] = if i < 10 { 1 } else { 2 };
        i += 1;
    }
    t
};

/// Each byte value's decimal digits (left-aligned) and how many there are.
const DECIMAL: [([u8; 3], u8); 256] = {
    let mut t = [([0u8; 3], 0u8); 256];
    let mut i = 0;
    while i < 256 {
        let (h, d, o) = ((i / 100) as u8, (i / 10 % 10) as u8, (i % 10) as u8);
        t[i] = if i >= 100 {
            ([b'0' + h, b'0' + d, b'0' + o], 3)
        } else if i >= 10 {
            ([b'0' + d, b'0' + o, 0], 2)
        } else {
            ([b'0' + o, 0, 0], 1)
        };
        i += 1;
    }
    t
};

/// Each byte value in decimal followed by `;` (left-aligned) and how many bytes that is.
const DECIMAL_SEMI: [([u8; 4], u8); 256] = {
    let mut t = [([0u8; 4], 0u8); 256];
    let mut i = 0;
    while i < 256 {
        let (d, n) = DECIMAL[i];
        let n = n as usize;
        let mut b = [d[0], d[1], d[2], 0];
        b[n] = b';';
        t[i] = (b, n as u8 + 1);
        i += 1;
    }
    t
};

#[inline]
fn d8(v: u32) -> u32 {
    u32::from(DIGITS[(v & 0xFF) as usize])
}

/// Decimal digits of a byte value without a table (branch-free, for the planner's hot loop).
#[inline]
fn digits8(v: u32) -> u32 {
    let v = v & 0xFF;
    1 + u32::from(v >= 10) + u32::from(v >= 100)
}

/// Bytes of one colour parameter (`38;2;r;g;b`, `38;5;n`, `31`, `101`, `39` …).
#[inline]
pub(crate) fn param_len(level: ColorLevel, code: Code, bg: bool) -> u32 {
    if code == DEFAULT {
        return 2;
    }
    match level {
        ColorLevel::TrueColor => 7 + d8(code >> 16) + d8(code >> 8) + d8(code),
        ColorLevel::Ansi256 => 5 + d8(code),
        // 30–37 / 90–97 are two bytes; 40–47 two, 100–107 three.
        ColorLevel::Ansi16 => 2 + u32::from(bg && code >= 8),
        ColorLevel::Mono => 0,
    }
}

/// Bytes of a colour's whole SGR alone (`ESC[`, the parameter, `m`) as (fg, bg), for the planner.
#[inline]
pub(crate) fn alone_lens(level: ColorLevel, code: Code) -> (u32, u32) {
    match level {
        ColorLevel::TrueColor if code != DEFAULT => {
            let n = 10 + digits8(code >> 16) + digits8(code >> 8) + digits8(code);
            (n, n)
        }
        ColorLevel::Ansi256 if code != DEFAULT => (8 + digits8(code), 8 + digits8(code)),
        _ => (
            3 + param_len(level, code, false),
            3 + param_len(level, code, true),
        ),
    }
}

/// A small stack buffer: a whole SGR sequence is assembled here and appended in one copy.
struct Buf<const N: usize = 48> {
    bytes: [u8; N],
    len: usize,
}

impl<const N: usize> Buf<N> {
    fn new() -> Self {
        Self {
            bytes: [0; N],
            len: 0,
        }
    }

    #[inline]
    fn push(&mut self, b: u8) {
        self.bytes[self.len] = b;
        self.len += 1;
    }

    #[inline]
    fn extend(&mut self, s: &[u8]) {
        self.bytes[self.len..self.len + s.len()].copy_from_slice(s);
        self.len += s.len();
    }

    /// `r;g;b` of a packed colour: two 4-byte and one 3-byte fixed-size copies.
    #[inline]
    fn rgb(&mut self, code: u32) {
        let (r, n) = DECIMAL_SEMI[((code >> 16) & 0xFF) as usize];
        self.bytes[self.len..self.len + 4].copy_from_slice(&r);
        self.len += usize::from(n);
        let (g, n) = DECIMAL_SEMI[((code >> 8) & 0xFF) as usize];
        self.bytes[self.len..self.len + 4].copy_from_slice(&g);
        self.len += usize::from(n);
        self.num(code);
    }

    /// A byte value in decimal, no leading zeros (one table lookup, one 3-byte copy).
    #[inline]
    fn num(&mut self, v: u32) {
        let (digits, n) = DECIMAL[(v & 0xFF) as usize];
        self.bytes[self.len..self.len + 3].copy_from_slice(&digits);
        self.len += usize::from(n);
    }
}

/// Writes one colour parameter.
#[inline(always)]
fn push_param<const N: usize>(out: &mut Buf<N>, level: ColorLevel, code: Code, bg: bool) {
    if code == DEFAULT {
        out.extend(if bg { b"49" } else { b"39" });
        return;
    }
    match level {
        ColorLevel::TrueColor => {
            out.extend(if bg { b"48;2;" } else { b"38;2;" });
            out.rgb(code);
        }
        ColorLevel::Ansi256 => {
            out.extend(if bg { b"48;5;" } else { b"38;5;" });
            out.num(code);
        }
        ColorLevel::Ansi16 => {
            let base = match (bg, code >= 8) {
                (false, false) => 30,
                (false, true) => 90 - 8,
                (true, false) => 40,
                (true, true) => 100 - 8,
            };
            out.num(base + code);
        }
        ColorLevel::Mono => {}
    }
}

/// Bytes needed to go from (fg, bg) `from` to `to` (the planner inlines the same arithmetic; tests pin
/// it to what [`write`] emits).
#[inline]
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) fn cost(level: ColorLevel, from: (Code, Code), to: (Code, Code)) -> u32 {
    match (from.0 != to.0, from.1 != to.1) {
        (false, false) => 0,
        _ if to == (DEFAULT, DEFAULT) => 3,
        (true, false) => 3 + param_len(level, to.0, false),
        (false, true) => 3 + param_len(level, to.1, true),
        (true, true) => 4 + param_len(level, to.0, false) + param_len(level, to.1, true),
    }
}

/// Writes the sequence whose length [`cost`] reports.
#[inline]
pub(crate) fn write(out: &mut Vec<u8>, level: ColorLevel, from: (Code, Code), to: (Code, Code)) {
    let (f, b) = (from.0 != to.0, from.1 != to.1);
    if !f && !b {
        return;
    }
    if to == (DEFAULT, DEFAULT) {
        out.extend_from_slice(b"\x1b[m");
        return;
    }
    let mut buf = Buf::<48>::new();
    buf.extend(b"\x1b[");
    if f {
        push_param(&mut buf, level, to.0, false);
    }
    if f && b {
        buf.push(b';');
    }
    if b {
        push_param(&mut buf, level, to.1, true);
    }
    buf.push(b'm');
    // A fixed-size copy compiles to a few vector stores (no memcpy call); then drop the slack.
    let at = out.len();
    out.extend_from_slice(&buf.bytes);
    out.truncate(at + buf.len);
}

/// Writes one SGR sequence whose colours may each be of another kind (a 24-bit colour beside an
/// indexed one, as ratatui cells mix them): the attribute parameters `attrs` first, then the
/// foreground and background when given, each as `(kind, code)`. Nothing when all are empty.
pub(crate) fn write_mixed(
    out: &mut Vec<u8>,
    attrs: &[u8],
    fg: Option<(ColorLevel, Code)>,
    bg: Option<(ColorLevel, Code)>,
) {
    if attrs.is_empty() && fg.is_none() && bg.is_none() {
        return;
    }
    // At most 11 attributes of 3 bytes, two colours of 19 bytes, separators and `ESC[`…`m`.
    let mut buf = Buf::<96>::new();
    buf.extend(b"\x1b[");
    let mut first = true;
    let mut sep = |buf: &mut Buf<96>| {
        if !std::mem::take(&mut first) {
            buf.push(b';');
        }
    };
    for &a in attrs {
        sep(&mut buf);
        buf.num(u32::from(a));
    }
    for (colour, is_bg) in [(fg, false), (bg, true)] {
        if let Some((kind, code)) = colour {
            sep(&mut buf);
            push_param(&mut buf, kind, code, is_bg);
        }
    }
    buf.push(b'm');
    out.extend_from_slice(&buf.bytes[..buf.len]);
}

/// Writes the underline colour as its own SGR in the colon forms terminals that draw coloured
/// underlines read (`58:2::R:G:B` for 24-bit, `58:5:N` for a palette index), or `59` (back to
/// the foreground's colour) for `None`.
pub(crate) fn write_underline(out: &mut Vec<u8>, colour: Option<(ColorLevel, Code)>) {
    out.extend_from_slice(b"\x1b[");
    match colour {
        None => out.extend_from_slice(b"59"),
        Some((ColorLevel::TrueColor, code)) => {
            out.extend_from_slice(b"58:2:");
            for shift in [16, 8, 0] {
                out.push(b':');
                super::number::push_num(out, (code >> shift) & 0xff);
            }
        }
        Some((_, code)) => {
            out.extend_from_slice(b"58:5:");
            super::number::push_num(out, code);
        }
    }
    out.push(b'm');
}

#[cfg(test)]
mod tests {
    use super::super::palette::UNKNOWN;
    use super::*;

    fn check(level: ColorLevel, from: (Code, Code), to: (Code, Code), want: &str) {
        let mut v = Vec::new();
        write(&mut v, level, from, to);
        assert_eq!(String::from_utf8(v.clone()).unwrap(), want);
        assert_eq!(cost(level, from, to) as usize, v.len(), "{want:?}");
    }

    #[test]
    fn alone_lengths_match_the_written_sequences() {
        use ColorLevel::*;
        for level in [TrueColor, Ansi256, Ansi16] {
            for code in [
                0, 7, 9, 15, 16, 99, 100, 231, 255, 0x0A_FF_00, 0xFF_FF_FF, DEFAULT,
            ] {
                let (f, b) = alone_lens(level, code);
                let other = if code == 1 { 2 } else { 1 };
                assert_eq!(f, cost(level, (other, 3), (code, 3)), "{level} {code}");
                assert_eq!(b, cost(level, (3, other), (3, code)), "{level} {code}");
            }
        }
    }

    #[test]
    fn mixed_sequences_put_attributes_then_each_colour_in_its_own_kind() {
        use ColorLevel::*;
        let mut v = Vec::new();
        write_mixed(
            &mut v,
            &[22, 1],
            Some((Ansi16, 9)),
            Some((TrueColor, 0x01_02_03)),
        );
        assert_eq!(v, b"\x1b[22;1;91;48;2;1;2;3m");
        v.clear();
        write_mixed(&mut v, &[], None, Some((Ansi256, 200)));
        assert_eq!(v, b"\x1b[48;5;200m");
        v.clear();
        write_mixed(&mut v, &[], None, None);
        assert!(v.is_empty());
    }

    #[test]
    fn sequences_are_combined_and_minimal() {
        use ColorLevel::*;
        check(TrueColor, (1, 2), (1, 2), "");
        check(TrueColor, (1, 2), (0x0A_FF_00, 2), "\x1b[38;2;10;255;0m");
        check(
            TrueColor,
            (UNKNOWN, UNKNOWN),
            (0, 0x010203),
            "\x1b[38;2;0;0;0;48;2;1;2;3m",
        );
        check(Ansi256, (16, 17), (16, 231), "\x1b[48;5;231m");
        check(Ansi256, (UNKNOWN, 17), (16, 17), "\x1b[38;5;16m");
        check(Ansi16, (0, 0), (1, 9), "\x1b[31;101m");
        check(Ansi16, (0, 0), (15, 7), "\x1b[97;47m");
        check(Ansi16, (3, 3), (DEFAULT, DEFAULT), "\x1b[m");
        check(Ansi16, (DEFAULT, 3), (DEFAULT, DEFAULT), "\x1b[m");
        check(Ansi16, (DEFAULT, DEFAULT), (DEFAULT, 3), "\x1b[43m");
    }
}
