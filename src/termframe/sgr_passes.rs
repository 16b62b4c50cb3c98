//! Rewriting an ANSI stream's SGR sequences so the vt100 model reports what it does not keep.
//!
//! The model keeps bold, italic, underline and reverse video per cell, not dim, blinking,
//! hidden, crossed out or the underline colour (SGR 58, whose numbers it would even misread as
//! other attributes). So the stream is read more than once: the main reading with underline
//! colours removed, then one reading per lost attribute in which that attribute is sent as bold
//! (and real bold not at all), and one in which the underline colour is sent as the foreground.
//! Each extra reading's bold flags (or foregrounds) are that attribute's (or colour's) cells:
//! the model still does all the cursor work, on the same bytes otherwise.

/// One SGR parameter, with a colour's own numbers kept with it (`38;5;58` is one colour, not
/// the parameter 58).
pub(super) enum Item<'a> {
    /// A plain parameter (`1`, `22`, `0`, or empty).
    Code(&'a [u8]),
    /// `38`, `48` or `58` with the numbers after it (`5;N` or `2;R;G;B`), or a colon form
    /// (`58:2::R:G:B`) as one token.
    Colour {
        which: &'a [u8],
        spec: Vec<&'a [u8]>,
    },
}

/// An SGR's parameters as items.
fn items(params: &[u8]) -> Vec<Item<'_>> {
    let mut out = Vec::new();
    let mut parts = params.split(|&b| b == b';');
    while let Some(p) = parts.next() {
        if let Some(colon) = p.iter().position(|&b| b == b':') {
            out.push(Item::Colour {
                which: &p[..colon],
                spec: vec![&p[colon..]],
            });
            continue;
        }
        if matches!(p, b"38" | b"48" | b"58") {
            let mut spec = Vec::new();
            if let Some(kind) = parts.next() {
                let n = match kind {
                    b"5" => 1,
                    b"2" => 3,
                    _ => 0,
                };
                spec.push(kind);
                spec.extend((0..n).filter_map(|_| parts.next()));
            }
            out.push(Item::Colour { which: p, spec });
        } else {
            out.push(Item::Code(p));
        }
    }
    out
}

/// What one reading does with each item: the parameters to send instead (none to drop it).
pub(super) type Pass = fn(&Item<'_>) -> Vec<Vec<u8>>;

/// The item as it was.
fn unchanged(item: &Item<'_>) -> Vec<Vec<u8>> {
    match item {
        Item::Code(c) => vec![c.to_vec()],
        Item::Colour { which, spec } => {
            let mut v = vec![which.to_vec()];
            if spec.first().is_some_and(|s| s.starts_with(b":")) {
                v[0].extend_from_slice(spec[0]);
            } else {
                v.extend(spec.iter().map(|s| s.to_vec()));
            }
            v
        }
    }
}

/// Whether the item sets or clears the underline colour.
fn is_underline_colour(item: &Item<'_>) -> bool {
    match item {
        Item::Code(c) => *c == b"58" || *c == b"59",
        Item::Colour { which, .. } => *which == b"58",
    }
}

/// The main reading: everything but the underline colour.
pub(super) fn main_pass(item: &Item<'_>) -> Vec<Vec<u8>> {
    if is_underline_colour(item) {
        return Vec::new();
    }
    unchanged(item)
}

/// A reading in which the attribute switched on by `on` and off by `off` is sent as bold.
fn attribute_as_bold(item: &Item<'_>, on: &[u8], off: &[u8]) -> Vec<Vec<u8>> {
    match item {
        Item::Code(c) if *c == on => vec![b"1".to_vec()],
        Item::Code(c) if *c == off => vec![b"22".to_vec()],
        // Real bold, and what ends it, say nothing about this attribute.
        Item::Code(b"1" | b"22") => Vec::new(),
        _ => main_pass(item),
    }
}

/// The readings for the attributes the model drops: the modifier, the parameter that switches
/// it on, the reading.
pub(super) const ATTRIBUTE_PASSES: [(ratatui::style::Modifier, &[u8], Pass); 5] = {
    use ratatui::style::Modifier as M;
    [
        (M::DIM, b"2", |i| attribute_as_bold(i, b"2", b"22")),
        (M::SLOW_BLINK, b"5", |i| attribute_as_bold(i, b"5", b"25")),
        (M::RAPID_BLINK, b"6", |i| attribute_as_bold(i, b"6", b"25")),
        (M::HIDDEN, b"8", |i| attribute_as_bold(i, b"8", b"28")),
        (M::CROSSED_OUT, b"9", |i| attribute_as_bold(i, b"9", b"29")),
    ]
};

/// The reading whose foreground is the underline colour: foregrounds dropped, `58` sent as
/// `38`, `59` as `39`.
pub(super) fn underline_as_foreground(item: &Item<'_>) -> Vec<Vec<u8>> {
    match item {
        Item::Code(b"59") => vec![b"39".to_vec()],
        Item::Code(c) if is_foreground(c) => Vec::new(),
        Item::Colour { which, spec } if *which == b"58" => unchanged(&Item::Colour {
            which: b"38",
            spec: spec.clone(),
        }),
        Item::Colour { which, .. } if *which == b"38" => Vec::new(),
        _ => unchanged(item),
    }
}

/// `30`–`37`, `39` and `90`–`97`: the plain foreground parameters.
fn is_foreground(code: &[u8]) -> bool {
    match code {
        [b'3', d] => (b'0'..=b'7').contains(d) || *d == b'9',
        [b'9', d] => (b'0'..=b'7').contains(d),
        _ => false,
    }
}

/// Calls `each` with every SGR's parameters and the span of bytes it takes (`ESC [ … m` with
/// digits, `;` and `:` only); other bytes are not SGRs.
fn for_each_sgr(bytes: &[u8], mut each: impl FnMut(std::ops::Range<usize>, &[u8])) {
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == 0x1b && bytes.get(i + 1) == Some(&b'[') {
            let end = bytes[i + 2..]
                .iter()
                .position(|b| !(b.is_ascii_digit() || *b == b';' || *b == b':'))
                .map(|n| i + 2 + n)
                .filter(|&e| bytes[e] == b'm');
            if let Some(end) = end {
                each(i..end + 1, &bytes[i + 2..end]);
                i = end + 1;
                continue;
            }
        }
        i += 1;
    }
}

/// Whether any SGR in the stream holds the parameter `code` (so a reading for it is needed).
#[must_use]
pub(super) fn mentions(bytes: &[u8], code: &[u8]) -> bool {
    let mut found = false;
    for_each_sgr(bytes, |_, params| {
        found = found
            || items(params).iter().any(|item| match item {
                Item::Code(c) => *c == code,
                Item::Colour { which, .. } => *which == code,
            });
    });
    found
}

/// The stream with every SGR's parameters passed through `pass`; other bytes as they were. An
/// SGR left with no parameters is dropped whole (an empty one would reset everything).
#[must_use]
pub(super) fn rewrite(bytes: &[u8], pass: Pass) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len());
    let mut copied = 0;
    for_each_sgr(bytes, |span, params| {
        out.extend_from_slice(&bytes[copied..span.start]);
        copied = span.end;
        let kept: Vec<Vec<u8>> = items(params).iter().flat_map(pass).collect();
        if params.is_empty() || !kept.is_empty() {
            out.extend_from_slice(b"\x1b[");
            out.extend_from_slice(&kept.join(&b';'));
            out.push(b'm');
        }
    });
    out.extend_from_slice(&bytes[copied..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_main_reading_drops_only_the_underline_colour() {
        let cases: [(&[u8], &[u8]); 8] = [
            (b"\x1b[58;2;4;44;1mx", b"x"),
            (b"\x1b[1;58;5;8;4mx", b"\x1b[1;4mx"),
            (b"\x1b[59ma\x1b[0m", b"a\x1b[0m"),
            (b"\x1b[58:2::1:2:3;7mx", b"\x1b[7mx"),
            (b"\x1b[38;5;58mx\x1b[2J", b"\x1b[38;5;58mx\x1b[2J"),
            (b"\x1b[58;2;1", b"\x1b[58;2;1"),
            (b"\x1b[48;2;58;58;58;58;5;1;1m", b"\x1b[48;2;58;58;58;1m"),
            (b"\x1b[mx", b"\x1b[mx"),
        ];
        for (input, want) in cases {
            assert_eq!(
                rewrite(input, main_pass),
                want,
                "{:?}",
                String::from_utf8_lossy(input)
            );
        }
    }

    #[test]
    fn a_lost_attribute_is_read_as_bold() {
        let (_, _, dim) = ATTRIBUTE_PASSES[0];
        assert_eq!(
            rewrite(b"\x1b[1;2;38;5;2mx\x1b[22m", dim),
            b"\x1b[1;38;5;2mx\x1b[22m"
        );
        let (_, _, crossed) = ATTRIBUTE_PASSES[4];
        assert!(mentions(b"\x1b[1;9mx", b"9") && !mentions(b"\x1b[38;5;9mx", b"9"));
        assert_eq!(
            rewrite(b"\x1b[1;9mx\x1b[22;29m", crossed),
            b"\x1b[1mx\x1b[22m"
        );
    }

    #[test]
    fn the_underline_colour_is_read_as_the_foreground() {
        assert_eq!(
            rewrite(b"\x1b[31;58;5;200mx\x1b[39;59m", underline_as_foreground),
            b"\x1b[38;5;200mx\x1b[39m"
        );
        assert_eq!(
            rewrite(b"\x1b[38;2;1;2;3;58:2::4:5:6m", underline_as_foreground),
            b"\x1b[38:2::4:5:6m"
        );
    }
}
