//! The header row over a session's panes: who you are or whom you watch, who is here (or the
//! game's scoreboard), the colour level, the link while it limits, the keys. It is made again
//! only when something it shows changes.

use super::header_fit::{self, Piece};
use crate::encode::ColourChoice;
use crate::game::multi::players::{PlayerId, Snapshot};
use crate::game::multi::round::Scoreboard;

/// Everything a header reads: names here, the eye's name, the scoreboard, the colour level, the
/// size and whether it was clamped, whether the map has a game, the link figures shown.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct HeaderFrom {
    names: Vec<String>,
    eye: Option<String>,
    scoreboard: Scoreboard,
    colour: ColourChoice,
    size: (u16, u16),
    clamped: bool,
    /// Whether the map has a game (its scoreboard replaces the list of who is here).
    game: bool,
    /// The link figures shown.
    link: Option<String>,
}

impl HeaderFrom {
    /// The parts that cost nothing to gather; names and scoreboard are compared in place by
    /// [`HeaderFrom::same`] and copied only for a new header ([`HeaderFrom::with_names`]).
    pub fn cheap(
        colour: ColourChoice,
        (size, clamped): ((u16, u16), bool),
        game: bool,
        link: Option<String>,
    ) -> Self {
        Self {
            names: Vec::new(),
            eye: None,
            scoreboard: Scoreboard::default(),
            colour,
            size,
            clamped,
            game,
            link,
        }
    }

    /// `self` with the names, eye and scoreboard of `snap`.
    pub fn with_names(mut self, snap: &Snapshot, eye: Option<&str>) -> Self {
        self.names = snap.players.iter().map(|p| p.name.clone()).collect();
        self.eye = eye.map(str::to_owned);
        self.scoreboard = snap.scoreboard.clone();
        self
    }

    /// Whether a header made from `self` is the one `snap` through `eye` would make, the rest
    /// being `now`.
    pub fn same(&self, snap: &Snapshot, eye: Option<&str>, now: &HeaderFrom) -> bool {
        self.size == now.size
            && self.clamped == now.clamped
            && self.game == now.game
            && self.colour == now.colour
            && self.link == now.link
            && self.eye.as_deref() == eye
            && self.scoreboard == snap.scoreboard
            && self.names.len() == snap.players.len()
            && self
                .names
                .iter()
                .zip(&snap.players)
                .all(|(n, p)| *n == p.name)
    }

    /// The header text for `snap` through `eye`. ASCII only, so it reads the same at every
    /// colour level (mono turns other glyphs to `#`).
    pub fn header(&self, snap: &Snapshot, eye: Option<PlayerId>, spectator: bool) -> String {
        let names: Vec<&str> = snap.players.iter().map(|p| p.name.as_str()).collect();
        let who = match (eye.and_then(|e| snap.player(e)), spectator) {
            (Some(p), true) => format!("watching {} (Tab: next)", p.name),
            (None, true) => "waiting for players (Tab: next)".to_string(),
            // The world's name for us: unique among those here (`ada-2`).
            (Some(p), false) => format!("you are {}", p.name),
            (None, false) => "joining...".to_string(),
        };
        // On maps with something to play for, the game's scoreboard (which names everyone)
        // takes the place of the list of who is here; spectators see it too. When the line is
        // too narrow the key hint, the name and the colour level go before the scoreboard's
        // tail (or the list of who is here) shortens to ", +N more".
        let game = self.game && !snap.scoreboard.is_empty();
        let mut pieces = vec![Piece::text(1, "halfcast"), Piece::text(8, who)];
        if !game {
            pieces.push(Piece::List {
                keep: 5,
                prefix: format!("{} here: ", names.len()),
                items: names.iter().map(|n| (*n).to_owned()).collect(),
            });
        }
        pieces.push(Piece::text(3, self.colour.to_string()));
        if let Some(link) = &self.link {
            pieces.push(Piece::text(2, link.clone()));
        }
        if game {
            pieces.push(Piece::text(6, snap.scoreboard.summary.clone()));
            pieces.push(Piece::List {
                keep: 5,
                prefix: String::new(),
                items: snap.scoreboard.rows.clone(),
            });
        }
        // O is the key map's default colour key (sessions use the default keys).
        pieces.push(Piece::text(0, "O colours"));
        if self.clamped {
            pieces.push(Piece::text(
                4,
                format!("clamped to {}x{}", self.size.0, self.size.1),
            ));
        }
        header_fit::fit(&pieces, usize::from(self.size.0))
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::game::multi::players::Players;
    use crate::world::World;

    #[test]
    fn the_header_is_made_again_when_someone_joins_or_the_size_changes() {
        let mut ps = Players::new(Arc::new(World::default_world()));
        ps.join(5, "a");
        let snap = ps.snapshot();
        let colour = crate::ui::colour_query::rules::guess(None, Some("xterm-256color"), None);
        let from =
            HeaderFrom::cheap(colour, ((80, 24), false), false, None).with_names(&snap, Some("a"));
        assert!(from.same(&snap, Some("a"), &from.clone()));
        let wider = HeaderFrom::cheap(colour, ((81, 24), false), false, None);
        assert!(!from.same(&snap, Some("a"), &wider));
        ps.join(7, "b");
        assert!(!from.same(&ps.snapshot(), Some("a"), &from.clone()));
    }
}
