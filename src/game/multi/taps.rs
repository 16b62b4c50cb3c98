//! Every tap counts, for a client whose key releases are known (a browser, a kitty-protocol
//! terminal): a hold that ends having moved the player less than one tap, because its press and
//! release fell between two world ticks or only one tick saw it, is made up to exactly one tap;
//! a longer hold moves by the ticks that saw it. The world is the judge, as only it knows which
//! ticks saw a key held.

use crate::game::{tap_seconds, Action, Command, Held, Speeds};

/// For each action, the seconds the world has stepped with it held since its hold began.
#[derive(Debug, Clone, Default)]
pub(super) struct Taps {
    stepped: [f64; Action::ALL.len()],
}

impl Taps {
    /// The world stepped `dt` seconds with `held`.
    pub fn ticked(&mut self, held: Held, dt: f64) {
        for a in Action::ALL {
            if held.contains(a) {
                self.stepped[a as usize] += dt;
            }
        }
    }

    /// The client's held keys change from `was` to `now`: a new hold starts from nothing, and
    /// one that ends short of a tap gets a nudge for the rest of it, pushed onto `commands`.
    pub fn changed(
        &mut self,
        (was, now): (Held, Held),
        speeds: Speeds,
        commands: &mut Vec<Command>,
    ) {
        for a in Action::ALL {
            match (was.contains(a), now.contains(a)) {
                (false, true) => self.stepped[a as usize] = 0.0,
                (true, false) => {
                    let seen = self.stepped[a as usize];
                    if let Some(tap) = tap_seconds(a, speeds).filter(|&t| seen < t) {
                        commands.push(Command::Nudge(a, tap - seen));
                    }
                }
                _ => {}
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn held(actions: &[Action]) -> Held {
        let mut h = Held::default();
        for &a in actions {
            h.insert(a);
        }
        h
    }

    fn nudges(commands: &[Command]) -> Vec<(Action, f64)> {
        commands
            .iter()
            .filter_map(|c| match *c {
                Command::Nudge(a, s) => Some((a, (s * 1e6).round() / 1e6)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn a_hold_no_tick_saw_is_one_whole_tap() {
        let (mut t, speeds, mut out) = (Taps::default(), Speeds::default(), Vec::new());
        let turn = tap_seconds(Action::TurnRight, speeds).unwrap();
        t.changed((held(&[]), held(&[Action::TurnRight])), speeds, &mut out);
        t.changed((held(&[Action::TurnRight]), held(&[])), speeds, &mut out);
        assert_eq!(
            nudges(&out),
            nudges(&[Command::Nudge(Action::TurnRight, turn)])
        );
    }

    #[test]
    fn a_hold_one_tick_saw_is_topped_up_to_a_tap_and_a_long_one_is_not() {
        let (mut t, speeds, mut out) = (Taps::default(), Speeds::default(), Vec::new());
        let walk = tap_seconds(Action::Forward, speeds).unwrap();
        let w = held(&[Action::Forward]);
        t.changed((held(&[]), w), speeds, &mut out);
        t.ticked(w, walk / 4.0);
        t.changed((w, held(&[])), speeds, &mut out);
        assert_eq!(
            nudges(&out),
            nudges(&[Command::Nudge(Action::Forward, walk * 0.75)])
        );
        out.clear();
        t.changed((held(&[]), w), speeds, &mut out);
        t.ticked(w, walk);
        t.ticked(w, walk);
        t.changed((w, held(&[])), speeds, &mut out);
        assert!(out.is_empty(), "{out:?}");
    }

    #[test]
    fn a_new_hold_forgets_the_last_and_crouch_has_no_tap() {
        let (mut t, speeds, mut out) = (Taps::default(), Speeds::default(), Vec::new());
        let l = held(&[Action::TurnLeft]);
        t.changed((held(&[]), l), speeds, &mut out);
        t.ticked(l, 1.0);
        t.changed((l, held(&[])), speeds, &mut out);
        t.changed((held(&[]), l), speeds, &mut out);
        t.changed((l, held(&[])), speeds, &mut out);
        assert_eq!(
            out.len(),
            1,
            "the second hold, which no tick saw, is a tap: {out:?}"
        );
        out.clear();
        let c = held(&[Action::Crouch]);
        t.changed((held(&[]), c), speeds, &mut out);
        t.changed((c, held(&[])), speeds, &mut out);
        assert!(out.is_empty());
    }
}
