//! What the page sends, one JSON object per WebSocket text message: `{"ack":N}` once frame N is
//! drawn, `{"size":[cols,rows]}` when the window changes, `{"key":"d","down":true}` for a key's
//! press or release (`"ctrl":true` with a letter for Ctrl+letter; keys named as the browser's
//! `KeyboardEvent.key`), `{"ray":C}` to debug column C of the 3D view and `{"ray":null}` to
//! leave the debugger. Anything else is a bad message, and closes the connection with its
//! reason.

use serde::Deserialize;

use crate::ui::key_bytes::{Key, KeyEvent, KeyKind};

/// One message from the page.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PageMessage {
    /// Frame `n` (counting from 1) has been drawn.
    Ack(u64),
    /// The page's grid is now this many columns and rows.
    Size(u32, u32),
    /// A key went down or up.
    Key(KeyEvent),
    /// Debug this column of the 3D view (the view freezes for this player), or leave (`None`).
    Ray(Option<u32>),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Wire {
    ack: Option<u64>,
    size: Option<(u32, u32)>,
    key: Option<String>,
    down: Option<bool>,
    ctrl: Option<bool>,
    /// `null` is there but empty: it leaves the debugger.
    #[serde(default, deserialize_with = "present")]
    ray: Option<Option<u32>>,
}

/// A field that may be `null`: `Some(None)` then, `None` only when it is absent.
fn present<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Option<u32>>, D::Error> {
    Option::<u32>::deserialize(d).map(Some)
}

/// Reads one text message.
///
/// # Errors
/// The reason the connection is closed with, when the message is not one of the above.
pub fn parse(text: &str) -> Result<PageMessage, &'static str> {
    let w: Wire = serde_json::from_str(text).map_err(|_| "not a message this server reads")?;
    if let Some(column) = w.ray {
        return match (w.ack, w.size, w.key, w.down) {
            (None, None, None, None) => Ok(PageMessage::Ray(column)),
            _ => Err("not a message this server reads"),
        };
    }
    match (w.ack, w.size, w.key, w.down) {
        (Some(n), None, None, None) => Ok(PageMessage::Ack(n)),
        (None, Some((c, r)), None, None) => {
            // Any size goes, as over SSH: the session draws at most what
            // [`crate::play::size`] allows and its header says it clamped.
            if c >= 1 && r >= 1 {
                Ok(PageMessage::Size(c, r))
            } else {
                Err("window size out of range")
            }
        }
        (None, None, Some(name), Some(down)) => {
            let key = key_named(&name, w.ctrl.unwrap_or(false)).ok_or("unknown key")?;
            let kind = if down {
                KeyKind::Press
            } else {
                KeyKind::Release
            };
            Ok(PageMessage::Key(KeyEvent { key, kind }))
        }
        _ => Err("not a message this server reads"),
    }
}

/// The key a browser names `name` (its `KeyboardEvent.key`).
fn key_named(name: &str, ctrl: bool) -> Option<Key> {
    let mut chars = name.chars();
    if let (Some(c), None) = (chars.next(), chars.next()) {
        if c.is_control() {
            return None;
        }
        return Some(if ctrl && c.is_ascii_alphabetic() {
            Key::Ctrl(c.to_ascii_lowercase())
        } else {
            Key::Char(c)
        });
    }
    Some(match name {
        "ArrowUp" => Key::Up,
        "ArrowDown" => Key::Down,
        "ArrowLeft" => Key::Left,
        "ArrowRight" => Key::Right,
        "Home" => Key::Home,
        "End" => Key::End,
        "PageUp" => Key::PageUp,
        "PageDown" => Key::PageDown,
        "Insert" => Key::Insert,
        "Delete" => Key::Delete,
        "Enter" => Key::Enter,
        "Tab" => Key::Tab,
        "Backspace" => Key::Backspace,
        "Escape" => Key::Esc,
        f => {
            let n: u8 = f.strip_prefix('F')?.parse().ok()?;
            if !(1..=12).contains(&n) {
                return None;
            }
            Key::F(n)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pages_messages_are_read() {
        assert_eq!(parse(r#"{"ack":7}"#), Ok(PageMessage::Ack(7)));
        assert_eq!(parse(r#"{"size":[80,24]}"#), Ok(PageMessage::Size(80, 24)));
        let d = parse(r#"{"key":"d","down":true}"#);
        assert_eq!(
            d,
            Ok(PageMessage::Key(KeyEvent {
                key: Key::Char('d'),
                kind: KeyKind::Press
            }))
        );
        let up = parse(r#"{"key":"ArrowUp","down":false}"#);
        assert!(matches!(
            up,
            Ok(PageMessage::Key(KeyEvent {
                key: Key::Up,
                kind: KeyKind::Release
            }))
        ));
        let c = parse(r#"{"key":"c","down":true,"ctrl":true}"#);
        assert!(matches!(
            c,
            Ok(PageMessage::Key(KeyEvent {
                key: Key::Ctrl('c'),
                ..
            }))
        ));
        assert!(matches!(
            parse(r#"{"key":"F5","down":true}"#),
            Ok(PageMessage::Key(KeyEvent { key: Key::F(5), .. }))
        ));
        assert_eq!(parse(r#"{"ray":12}"#), Ok(PageMessage::Ray(Some(12))));
        assert_eq!(parse(r#"{"ray":null}"#), Ok(PageMessage::Ray(None)));
        assert!(parse(r#"{"ray":1,"ack":1}"#).is_err());
    }

    #[test]
    fn anything_else_is_refused_with_a_reason() {
        for bad in [
            "",
            "{}",
            "[1]",
            r#"{"ack":-1}"#,
            r#"{"ack":1,"size":[1,1]}"#,
            r#"{"size":[0,24]}"#,
            r#"{"size":[80,-1]}"#,
            r#"{"ray":"x"}"#,
            r#"{"key":"Meta","down":true}"#,
            r#"{"key":"F13","down":true}"#,
            r#"{"key":"\u0007","down":true}"#,
            r#"{"key":"d"}"#,
            r#"{"cmd":"rm -rf"}"#,
        ] {
            assert!(parse(bad).is_err(), "{bad:?}");
        }
    }
}
