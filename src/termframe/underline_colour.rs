//! Removes underline colours (SGR 58 and 59) from an ANSI stream before the vt100 model reads
//! it: the model does not know them and reads their numbers as other attributes (`58;2;4;44;1`
//! would turn on underline, a blue background and bold), so a frame ratatui's crossterm backend
//! drew with an underline colour would read back wrong everywhere after it.

/// The stream with every SGR 58 (`58;5;N`, `58;2;R;G;B`, `58:…`) and 59 removed; other bytes
/// as they were. An SGR left with no parameters is dropped whole (an empty one would reset).
#[must_use]
pub fn without_underline_colours(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == 0x1b && bytes.get(i + 1) == Some(&b'[') {
            let params_end = bytes[i + 2..]
                .iter()
                .position(|b| !(b.is_ascii_digit() || *b == b';' || *b == b':'))
                .map(|n| i + 2 + n);
            if let Some(end) = params_end.filter(|&e| bytes[e] == b'm') {
                if let Some(kept) = without(&bytes[i + 2..end]) {
                    if !kept.is_empty() {
                        out.extend_from_slice(b"\x1b[");
                        out.extend_from_slice(&kept.join(&b';'));
                        out.push(b'm');
                    }
                    i = end + 1;
                    continue;
                }
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    out
}

/// The SGR's parameters without the underline-colour ones, or `None` when it has none. A
/// colour's own numbers (`38;5;58`) are walked over, never taken for a parameter.
fn without(params: &[u8]) -> Option<Vec<&[u8]>> {
    let mut kept: Vec<&[u8]> = Vec::new();
    let mut removed = false;
    let mut parts = params.split(|&b| b == b';');
    while let Some(p) = parts.next() {
        let colour_numbers = |kind: Option<&[u8]>| match kind {
            Some(b"5") => 1,
            Some(b"2") => 3,
            _ => 0,
        };
        match p {
            b"38" | b"48" | b"58" => {
                let kind = parts.next();
                let numbers: Vec<&[u8]> = (0..colour_numbers(kind))
                    .filter_map(|_| parts.next())
                    .collect();
                if p == b"58" {
                    removed = true;
                } else {
                    kept.push(p);
                    kept.extend(kind);
                    kept.extend(numbers);
                }
            }
            b"59" => removed = true,
            p if p.starts_with(b"58:") => removed = true,
            p => kept.push(p),
        }
    }
    removed.then_some(kept)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_underline_colour_goes() {
        let cases: [(&[u8], &[u8]); 7] = [
            (b"\x1b[58;2;4;44;1mx", b"x"),
            (b"\x1b[1;58;5;8;4mx", b"\x1b[1;4mx"),
            (b"\x1b[59ma\x1b[0m", b"a\x1b[0m"),
            (b"\x1b[58:2::1:2:3;7mx", b"\x1b[7mx"),
            (b"\x1b[38;5;58mx\x1b[2J", b"\x1b[38;5;58mx\x1b[2J"),
            (b"\x1b[58;2;1", b"\x1b[58;2;1"),
            (b"\x1b[48;2;58;58;58;58;5;1;1m", b"\x1b[48;2;58;58;58;1m"),
        ];
        for (input, want) in cases {
            assert_eq!(
                without_underline_colours(input),
                want,
                "{:?}",
                String::from_utf8_lossy(input)
            );
        }
    }
}
