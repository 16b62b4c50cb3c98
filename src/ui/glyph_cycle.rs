//! The glyph key's cycle for one session: half → quadrant → sextant → octant → half, without
//! octant where something on the way to the screen is known to drop it
//! ([`super::octant_support`]). A session that started at octant (the player asked for it by
//! flag, config or, over SSH, environment) keeps octant in the cycle.
//!
//! The key is resolved here into the setting it leads to ([`UiCommand::SetGlyphs`]), and that is
//! what a recording keeps, so a replay shows the same settings wherever it runs.

use super::octant_support::OctantDropper;
use crate::render::glyphs::Glyphs;
use crate::replay::format::UiCommand;

/// One session's glyph cycle, and whether it already said why octants are skipped.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GlyphCycle {
    /// Why octant is left out of the cycle (`None`: it is in).
    skip: Option<OctantDropper>,
    /// How this session forces octants, for the note (`--glyphs octant forces`).
    forces: &'static str,
    /// Whether the note was given (it is given once).
    told: bool,
}

impl GlyphCycle {
    /// The cycle of a session that starts at `start` behind `dropper`; `forces` tells the
    /// player how to ask for octants anyway (e.g. `--glyphs octant forces`).
    #[must_use]
    pub fn new(dropper: Option<OctantDropper>, start: Glyphs, forces: &'static str) -> Self {
        Self {
            skip: dropper.filter(|_| start != Glyphs::Octant),
            forces,
            told: false,
        }
    }

    /// The setting after `current`, and the note to show the first time octant is skipped.
    pub fn next(&mut self, current: Glyphs) -> (Glyphs, Option<String>) {
        let next = current.cycled();
        match &self.skip {
            Some(why) if next == Glyphs::Octant => {
                let note = (!self.told)
                    .then(|| format!("octants off: {} drops them; {}", why.name(), self.forces));
                self.told = true;
                (next.cycled(), note)
            }
            _ => (next, None),
        }
    }

    /// Turns each glyph key in `ui` into the setting it leads to, from `current` on; returns
    /// the note to show, if one of them skipped octant for the first time.
    pub fn resolve(&mut self, ui: &mut [UiCommand], mut current: Glyphs) -> Option<String> {
        let mut note = None;
        for u in ui {
            match *u {
                UiCommand::CycleGlyphs => {
                    let (next, said) = self.next(current);
                    *u = UiCommand::SetGlyphs(next);
                    current = next;
                    note = note.or(said);
                }
                UiCommand::SetGlyphs(g) => current = g,
                _ => {}
            }
        }
        note
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FORCES: &str = "--glyphs octant forces";

    fn presses(cycle: &mut GlyphCycle, from: Glyphs, n: usize) -> Vec<Glyphs> {
        let mut ui = vec![UiCommand::CycleGlyphs; n];
        cycle.resolve(&mut ui, from);
        ui.iter()
            .map(|u| match u {
                UiCommand::SetGlyphs(g) => *g,
                other => panic!("unresolved {other:?}"),
            })
            .collect()
    }

    #[test]
    fn with_nothing_in_the_way_the_cycle_visits_all_four() {
        let mut c = GlyphCycle::new(None, Glyphs::Half, FORCES);
        assert_eq!(
            presses(&mut c, Glyphs::Half, 4),
            [
                Glyphs::Quadrant,
                Glyphs::Sextant,
                Glyphs::Octant,
                Glyphs::Half
            ]
        );
    }

    #[test]
    fn behind_tmux_octant_is_skipped_and_the_note_comes_once() {
        let mut c = GlyphCycle::new(Some(OctantDropper::Tmux), Glyphs::Half, FORCES);
        let mut ui = vec![UiCommand::CycleGlyphs; 2];
        assert_eq!(c.resolve(&mut ui, Glyphs::Half), None);
        assert_eq!(
            ui,
            [
                UiCommand::SetGlyphs(Glyphs::Quadrant),
                UiCommand::SetGlyphs(Glyphs::Sextant)
            ]
        );
        let mut ui = vec![UiCommand::ToggleMinimap, UiCommand::CycleGlyphs];
        assert_eq!(
            c.resolve(&mut ui, Glyphs::Sextant).as_deref(),
            Some("octants off: tmux drops them; --glyphs octant forces")
        );
        assert_eq!(ui[1], UiCommand::SetGlyphs(Glyphs::Half));
        // Round again: still no octant, and no second note.
        let mut ui = vec![UiCommand::CycleGlyphs; 8];
        assert_eq!(c.resolve(&mut ui, Glyphs::Half), None);
        assert!(!ui.contains(&UiCommand::SetGlyphs(Glyphs::Octant)));
    }

    #[test]
    fn starting_at_octant_forces_it_even_behind_tmux() {
        let mut c = GlyphCycle::new(Some(OctantDropper::Tmux), Glyphs::Octant, FORCES);
        assert_eq!(
            presses(&mut c, Glyphs::Octant, 4),
            [
                Glyphs::Half,
                Glyphs::Quadrant,
                Glyphs::Sextant,
                Glyphs::Octant
            ]
        );
        // An explicit sextant start is no request for octants.
        let mut c = GlyphCycle::new(Some(OctantDropper::Multiplexer), Glyphs::Sextant, FORCES);
        assert_eq!(
            presses(&mut c, Glyphs::Sextant, 2),
            [Glyphs::Half, Glyphs::Quadrant]
        );
    }

    #[test]
    fn presses_in_one_frame_chain_and_set_events_move_the_start() {
        let mut c = GlyphCycle::new(Some(OctantDropper::Tmux), Glyphs::Half, FORCES);
        let mut ui = vec![
            UiCommand::SetGlyphs(Glyphs::Sextant),
            UiCommand::CycleGlyphs,
            UiCommand::CycleGlyphs,
        ];
        assert!(c.resolve(&mut ui, Glyphs::Half).is_some());
        assert_eq!(
            &ui[1..],
            [
                UiCommand::SetGlyphs(Glyphs::Half),
                UiCommand::SetGlyphs(Glyphs::Quadrant)
            ]
        );
    }
}
