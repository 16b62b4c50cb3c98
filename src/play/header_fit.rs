//! Fitting the SSH header to the client's width: at 80 columns a cut line lost the end of the
//! scoreboard (the part a player joins a game for), so the header drops its least useful pieces
//! first and shortens a list of names to "+N more" before anything is cut.

/// One piece of the header; when the row is too narrow the lowest `keep` goes (or shrinks) first.
#[derive(Clone, Debug, PartialEq)]
pub enum Piece {
    /// Shown whole or not at all.
    Text { keep: u8, text: String },
    /// `prefix` then `items` joined by ", "; shortened from the end (", +N more") before it goes.
    List {
        keep: u8,
        prefix: String,
        items: Vec<String>,
    },
}

impl Piece {
    /// A piece shown whole or not at all.
    #[must_use]
    pub fn text(keep: u8, text: impl Into<String>) -> Self {
        Self::Text {
            keep,
            text: text.into(),
        }
    }

    fn keep(&self) -> u8 {
        match self {
            Self::Text { keep, .. } | Self::List { keep, .. } => *keep,
        }
    }

    fn render(&self, shown: usize) -> String {
        match self {
            Self::Text { text, .. } => text.clone(),
            Self::List { prefix, items, .. } => {
                let mut s = format!("{prefix}{}", items[..shown].join(", "));
                let hidden = items.len() - shown;
                if hidden > 0 {
                    if shown > 0 {
                        s.push_str(", ");
                    }
                    s.push_str(&format!("+{hidden} more"));
                }
                s
            }
        }
    }

    fn len(&self) -> usize {
        match self {
            Self::Text { .. } => usize::MAX,
            Self::List { items, .. } => items.len(),
        }
    }
}

/// The header line for `width` columns: every piece if they fit; otherwise pieces go, lowest
/// `keep` first, a list shortening to as many names as fit before it goes; a line still too
/// long (a very narrow terminal) is cut at the width, down to its most useful piece.
#[must_use]
pub fn fit(pieces: &[Piece], width: usize) -> String {
    // How much of each piece is shown: None = dropped; for a list, how many items.
    let mut shown: Vec<Option<usize>> = pieces.iter().map(|p| Some(p.len())).collect();
    let line = |shown: &[Option<usize>]| -> String {
        let parts: Vec<String> = pieces
            .iter()
            .zip(shown)
            .filter_map(|(p, n)| n.map(|n| p.render(n)))
            .collect();
        format!(" {}", parts.join(" | "))
    };
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by_key(|&i| pieces[i].keep());
    // The most useful piece never goes: too long, it is cut instead.
    order.pop();
    for i in order {
        if line(&shown).chars().count() <= width {
            break;
        }
        if let Piece::List { items, .. } = &pieces[i] {
            // The most names that fit (at least one, or the piece goes).
            let fits = (1..items.len()).rev().find(|&n| {
                shown[i] = Some(n);
                line(&shown).chars().count() <= width
            });
            if fits.is_some() {
                break;
            }
        }
        shown[i] = None;
    }
    line(&shown).chars().take(width).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pieces() -> Vec<Piece> {
        vec![
            Piece::text(1, "halfcast"),
            Piece::text(8, "you are ada"),
            Piece::text(3, "256 (TERM)"),
            Piece::text(6, "coop: team 30 pts, 11 items left"),
            Piece::List {
                keep: 5,
                prefix: String::new(),
                items: ["ada 30", "bob 0", "cy 0", "dee 0", "eve 0", "fay 0"]
                    .map(String::from)
                    .to_vec(),
            },
            Piece::text(0, "O colours"),
        ]
    }

    #[test]
    fn everything_shows_when_it_fits() {
        let s = fit(&pieces(), 200);
        assert_eq!(
            s,
            " halfcast | you are ada | 256 (TERM) | coop: team 30 pts, 11 items left | \
             ada 30, bob 0, cy 0, dee 0, eve 0, fay 0 | O colours"
        );
    }

    #[test]
    fn at_80_columns_the_whole_scoreboard_stays_and_the_key_hint_goes() {
        let s = fit(&pieces(), 80);
        assert_eq!(
            s,
            " you are ada | coop: team 30 pts, 11 items left | ada 30, bob 0, cy 0, \
             +3 more"
        );
        assert!(s.chars().count() <= 80);
    }

    #[test]
    fn narrower_the_list_shortens_before_the_summary_goes() {
        let s = fit(&pieces(), 70);
        assert_eq!(
            s,
            " you are ada | coop: team 30 pts, 11 items left | ada 30, +5 more"
        );
        let s = fit(&pieces(), 60);
        assert_eq!(s, " you are ada | coop: team 30 pts, 11 items left");
        let s = fit(&pieces(), 40);
        assert_eq!(s, " you are ada");
        let s = fit(&pieces(), 8);
        assert_eq!(s, " you are");
    }

    #[test]
    fn every_width_fits() {
        for w in 0..200 {
            assert!(fit(&pieces(), w).chars().count() <= w, "{w}");
        }
    }
}
