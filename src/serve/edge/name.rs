//! The name a player is shown to others by, whatever the transport brought (an SSH user name, a
//! page's `name=`): printable ASCII, short, never empty.

/// Longest player name shown to others.
pub const MAX_NAME: usize = 16;

/// `raw` made safe to show on other people's screens: printable ASCII, at most [`MAX_NAME`]
/// characters; `None` when nothing is left.
#[must_use]
pub fn shown_name(raw: &str) -> Option<String> {
    let name: String = raw
        .chars()
        .filter(char::is_ascii_graphic)
        .take(MAX_NAME)
        .collect();
    (!name.is_empty()).then_some(name)
}

/// The name connection `id` plays as: [`shown_name`] of what it asked for, else `player{id}`.
#[must_use]
pub fn display_name(raw: &str, id: u64) -> String {
    shown_name(raw).unwrap_or_else(|| format!("player{id}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_printable_and_short() {
        assert_eq!(display_name("ann", 1), "ann");
        assert_eq!(display_name("\x1b[31mevil", 2), "[31mevil");
        assert_eq!(display_name("", 3), "player3");
        assert_eq!(display_name(&"x".repeat(100), 4).len(), MAX_NAME);
        assert_eq!(shown_name("  "), None);
    }
}
