//! What one session keeps of its client between frames: what is on its screen, its keys and
//! where they go, whom it watches, and what the next frame would be drawn from.

use std::time::Instant;

use super::end::End;
use super::header_text::HeaderFrom;
use super::input::Input;
use super::link_text::{rate_text, rtt_text};
use super::pacing::LinkFigures;
use super::ray_debug::RayDebug;
use super::screen::{panes_for, view_rect, SessionScreen};
use super::setup::Setup;
use super::sink::Note;
use super::world_port::WorldMsg;
use crate::encode::{ColourChoice, ColourReason};
use crate::game::multi::players::{PlayerId, Snapshot};
use crate::game::Held;
use crate::render::glyphs::Glyphs;
use crate::ui::glyph_cycle::GlyphCycle;
use crate::ui::key_bytes::{InputEvent, InputParser};
use crate::ui::key_route::{route, Routed};
use crate::ui::keys::{Controls, InputMode, UiCommand};
use crate::ui::layout::Toggles;
use crate::ui::results::Board;

/// How often the link figures on the header may change.
const LINK_SHOWN_EVERY: std::time::Duration = std::time::Duration::from_secs(1);

/// Everything a frame is drawn from: two frames from equal keys are the same bytes, so the
/// second need not be sent.
#[derive(Debug, Clone, PartialEq)]
struct ShownKey {
    /// The world snapshot's version.
    version: u64,
    size: (u16, u16),
    colour: ColourChoice,
    glyphs: Glyphs,
    /// Whether a note is over the status line.
    note: bool,
    /// Whose eyes the view is seen through.
    eye: Option<PlayerId>,
    toggles: Toggles,
    /// The leaderboard, and whether `L` put it over the game.
    leaders: Option<(Board, bool)>,
}

/// What is on the client's screen and what it asked for; everything the frame depends on.
pub(super) struct Player {
    spectator: bool,
    me: PlayerId,
    size: (u16, u16),
    /// Whether the client claimed a bigger terminal than we draw (the header says so).
    clamped: bool,
    following: Option<PlayerId>,
    parser: InputParser,
    /// Parsed input events, reused.
    keys: Vec<InputEvent>,
    /// Since when an unfinished escape sequence waits for its next byte.
    pending_since: Option<Instant>,
    controls: Controls,
    /// What the world was last told: held keys and view width.
    sent: (Held, usize),
    /// Messages for the world not yet sent (one per key event, with known releases).
    to_world: Vec<WorldMsg>,
    /// The column a page asked to debug, until the world shows it.
    ray: RayDebug,
    /// Where the client was last told the view is.
    view_told: Option<Note>,
    last_input: Instant,
    screen: SessionScreen,
    /// What the frame on screen was drawn from, to skip identical frames.
    shown: Option<ShownKey>,
    /// The leaderboard to show (on the results, and over the game while `L` is on).
    leaders: Option<Board>,
    /// Whether `L` put the leaderboard over the game.
    show_leaders: bool,
    /// The glyph key's cycle for this client (without octant behind tmux, unless asked for).
    glyph_cycle: GlyphCycle,
    /// The last header and what it was made from: it changes only when someone joins, leaves
    /// or scores, so most frames reuse it.
    header: Option<(HeaderFrom, String)>,
    /// Whether a note was over the status line in the frame on screen.
    notice_shown: bool,
    /// Whether the transport measures this link (then the header shows its figures).
    link_known: bool,
    /// The link figures the header shows, and when they last changed.
    link: Option<(String, Instant)>,
}

impl Player {
    pub fn new(setup: &Setup, size: (u32, u32), link_known: bool, now: Instant) -> Self {
        let (client, rules) = (&setup.client, &setup.rules);
        let mut screen = SessionScreen::new(
            &rules.world_data,
            rules.avatar_sheet,
            client.facts.colour.level,
        );
        screen.set_colour(client.facts.colour);
        screen.set_glyphs(client.facts.glyphs);
        Self {
            spectator: client.spectator,
            me: client.id,
            size: clamp_size(size),
            clamped: is_clamped(size),
            following: None,
            parser: InputParser::new(),
            keys: Vec::new(),
            pending_since: None,
            controls: Controls::new(client.facts.input_mode),
            sent: (Held::default(), usize::MAX),
            to_world: Vec::new(),
            ray: RayDebug::default(),
            view_told: None,
            last_input: now,
            screen,
            shown: None,
            leaders: None,
            show_leaders: false,
            glyph_cycle: GlyphCycle::new(
                client.facts.octant_dropper.clone(),
                client.facts.glyphs,
                client.facts.force_octants,
            ),
            header: None,
            notice_shown: false,
            link_known,
            link: None,
        }
    }

    /// Takes new link figures for the header, at most once per [`LINK_SHOWN_EVERY`] (so the
    /// header, and the frame, change rarely for them). They show while the link limits the
    /// frames or set the colour level; a link that keeps up leaves the header as it was.
    pub fn show_link(&mut self, f: LinkFigures, now: Instant) {
        if !self.link_known
            || self
                .link
                .as_ref()
                .is_some_and(|(_, at)| now.duration_since(*at) < LINK_SHOWN_EVERY)
        {
            return;
        }
        let shown = f.limiting || self.screen.colour().reason == ColourReason::Link;
        let text = match (shown, f.rate) {
            (true, Some(rate)) => Some(format!("link {} {}", rate_text(rate), rtt_text(f.rtt))),
            _ => None,
        };
        if self.link.as_ref().map(|(t, _)| t) != text.as_ref() {
            self.link = text.map(|t| (t, now));
        }
    }

    /// The colour level frames are drawn at.
    pub fn colour(&self) -> ColourChoice {
        self.screen.colour()
    }

    /// Draws later frames at `colour` (the link's step, not the player's choice).
    pub fn set_colour(&mut self, colour: ColourChoice) {
        self.screen.set_colour(colour);
    }

    /// How long the last frame took to render and to encode, for the server's metrics.
    pub fn frame_times(&self) -> (std::time::Duration, std::time::Duration) {
        self.screen.last_times()
    }

    /// Shows `note` over the status line until `until`.
    pub fn note_until(&mut self, note: String, until: Instant) {
        self.screen.notice.show_until(note, until);
    }

    /// Whether a note appeared or ran out since the frame on screen.
    pub fn note_changed(&self, now: Instant) -> bool {
        self.screen.notice.showing(now) != self.notice_shown
    }

    /// How long the client has sent nothing.
    pub fn idle_for(&self, now: Instant) -> std::time::Duration {
        now.duration_since(self.last_input)
    }

    /// Whether an unfinished escape sequence has waited `wait` for its next byte (then it is a
    /// lone Esc after all: [`Player::flush_escape`]).
    pub fn escape_due(&self, now: Instant, wait: std::time::Duration) -> bool {
        self.pending_since
            .is_some_and(|t| now.duration_since(t) >= wait)
    }

    /// Whether the frame from `snap` shows a leaderboard: on the results, or while `L` is on.
    pub fn wants_board(&self, snap: &Snapshot) -> bool {
        snap.ended.is_some() || self.show_leaders
    }

    /// The leaderboard for the next frame (none while it is not shown).
    pub fn set_leaders(&mut self, board: Option<Board>) {
        self.leaders = board;
    }

    /// Follows the client's claimed terminal size, within the bounds.
    pub fn resize(&mut self, cols: u32, rows: u32) {
        self.size = clamp_size((cols, rows));
        self.clamped = is_clamped((cols, rows));
    }

    /// Takes the client's input at `now`: a terminal's bytes are parsed (an unfinished escape
    /// waits for [`Player::flush_escape`]), key events are taken as they are. Returns an end if a
    /// key quits.
    pub fn take(&mut self, input: Input, snap: &Snapshot, now: Instant) -> Option<End> {
        self.last_input = now;
        let mut keys = std::mem::take(&mut self.keys);
        keys.clear();
        match input {
            Input::Bytes(bytes) => {
                self.parser.feed(&bytes, &mut keys);
                if self.parser.has_pending() {
                    self.pending_since.get_or_insert(now);
                } else {
                    self.pending_since = None;
                }
            }
            Input::Keys(events) => {
                self.releases_known(InputMode::Released);
                keys.extend(events.into_iter().map(InputEvent::Key));
            }
            Input::Ray(column) => self.debug_column(column, snap),
        }
        let end = self.on_keys(&keys, snap, now);
        self.keys = keys;
        end
    }

    /// An unfinished escape sequence that waited long enough: its bytes are keys after all (a
    /// lone Esc). Returns an end if one quits.
    pub fn flush_escape(&mut self, snap: &Snapshot, now: Instant) -> Option<End> {
        let mut keys = std::mem::take(&mut self.keys);
        keys.clear();
        self.parser.flush(&mut keys);
        self.pending_since = None;
        let end = self.on_keys(&keys, snap, now);
        self.keys = keys;
        end
    }

    /// Acts on parsed keys at `now`; returns an end if one of them quits.
    fn on_keys(&mut self, events: &[InputEvent], snap: &Snapshot, now: Instant) -> Option<End> {
        if let Some(p) = snap.player(self.me) {
            // Paused, the turn keys move the debugged column instead of turning.
            self.controls.set_paused(p.state.debugger.paused);
        }
        for ev in events {
            match *ev {
                InputEvent::KittyFlags(_) => self.releases_known(InputMode::Kitty),
                InputEvent::Key(k) => match route(k) {
                    Routed::NextTarget => self.following = cycle(snap, self.following, true),
                    Routed::PrevTarget => self.following = cycle(snap, self.following, false),
                    Routed::Leaderboard => self.show_leaders = !self.show_leaders,
                    Routed::Tui(ev) => {
                        self.controls.handle(&ev, now);
                        self.each_key_to_world(now);
                    }
                    Routed::Nothing => {}
                },
            }
        }
        let mut uis = self.controls.take_ui();
        if let Some(note) = self.glyph_cycle.resolve(&mut uis, self.screen.glyphs()) {
            self.screen.notice.show(note, now);
        }
        for ui in uis {
            let toggles = &mut self.screen.toggles;
            match ui {
                UiCommand::Quit => return Some(End::Quit),
                UiCommand::Back if toggles.help => toggles.help = false,
                UiCommand::Back => return Some(End::Quit),
                UiCommand::ToggleMinimap => toggles.minimap = !toggles.minimap,
                UiCommand::ToggleDebug => toggles.debug = !toggles.debug,
                UiCommand::ToggleHelp => toggles.help = !toggles.help,
                UiCommand::CycleColours => self.screen.set_colour(self.screen.colour().cycled()),
                UiCommand::SetGlyphs(g) => self.screen.set_glyphs(g),
                // Resolved into `SetGlyphs` by the glyph cycle above.
                UiCommand::CycleGlyphs => self.screen.set_glyphs(self.screen.glyphs().cycled()),
                // In a session the figure key is off: it would write on the server's disk.
                UiCommand::SaveFigure => {}
            }
        }
        None
    }

    /// The client reports key releases (`mode`: the kitty keyboard protocol, or a browser's
    /// events): holds end at release instead of being inferred from auto-repeat.
    fn releases_known(&mut self, mode: InputMode) {
        if self.controls.mode() != mode {
            self.controls = Controls::new(mode);
        }
    }

    /// Debugs `column` of the view (or leaves the debugger): the world is told at once.
    fn debug_column(&mut self, column: Option<u32>, snap: &Snapshot) {
        if self.spectator {
            return;
        }
        let width = usize::from(self.view().width);
        let commands = self.ray.ask(column, (snap, self.me), width);
        if commands.is_empty() {
            return;
        }
        self.to_world.push(WorldMsg::Input {
            id: self.me,
            input: crate::game::Input {
                held: self.sent.0,
                commands,
            },
            view_width: width,
            releases_known: self.controls.mode() != InputMode::Emulated,
        });
    }

    /// The 3D view's cells on this client's screen.
    fn view(&self) -> ratatui::layout::Rect {
        view_rect(&panes_for(self.size, self.screen.toggles))
    }

    /// What the client should be told before the frame from `snap`: where the view is, when it
    /// moved, and the ray it asked for, once the world debugs it.
    pub fn notes(&mut self, snap: &Snapshot) -> Vec<Note> {
        let mut out = Vec::new();
        let v = self.view();
        let view = Note::View {
            x: v.x,
            y: v.y,
            cols: v.width,
            rows: v.height,
        };
        if self.view_told.as_ref() != Some(&view) {
            self.view_told = Some(view.clone());
            out.push(view);
        }
        if let Some(ray) = self.ray.ready((snap, self.me), (v.width, v.height)) {
            out.push(Note::Ray(ray));
        }
        out
    }

    /// With known releases, the world hears every key event on its own, so a press and release
    /// that arrive together (a quick tap, or a link bunching them) are still a hold and its end
    /// in the world's inbox ([`crate::game::multi::players::Players::input_with_releases`]).
    fn each_key_to_world(&mut self, now: Instant) {
        if self.spectator || self.controls.mode() == InputMode::Emulated {
            return;
        }
        if let Some(msg) = self.world_input(now) {
            self.to_world.push(msg);
        }
    }

    /// The messages for the world since the last call, oldest first, ending with the input at
    /// `now` when it changed.
    pub fn world_messages(&mut self, now: Instant) -> Vec<WorldMsg> {
        let mut out = std::mem::take(&mut self.to_world);
        out.extend(self.world_input(now));
        out
    }

    /// The message for the world at `now`, when the player's input changed since the last one.
    fn world_input(&mut self, now: Instant) -> Option<WorldMsg> {
        let input = self.controls.take_input(now);
        let width = usize::from(self.view().width);
        if input.commands.is_empty() && (input.held, width) == self.sent {
            return None;
        }
        self.sent = (input.held, width);
        Some(WorldMsg::Input {
            id: self.me,
            input,
            view_width: width,
            releases_known: self.controls.mode() != InputMode::Emulated,
        })
    }

    /// Whose eyes this session looks through now.
    fn eye(&mut self, snap: &Snapshot) -> Option<PlayerId> {
        if !self.spectator {
            return Some(self.me);
        }
        if self.following.is_none_or(|id| snap.player(id).is_none()) {
            self.following = snap.players.first().map(|p| p.id);
        }
        self.following
    }

    /// Whether the frame drawn from `snap` at `now` would be the one on screen (nothing to send).
    pub fn unchanged(&mut self, snap: &Snapshot, now: Instant) -> bool {
        let key = self.key(snap, now);
        self.shown.as_ref() == Some(&key)
    }

    /// Everything the frame drawn from `snap` depends on.
    fn key(&mut self, snap: &Snapshot, now: Instant) -> ShownKey {
        ShownKey {
            version: snap.version,
            size: self.size,
            colour: self.screen.colour(),
            glyphs: self.screen.glyphs(),
            note: self.screen.notice.showing(now),
            eye: self.eye(snap),
            toggles: self.screen.toggles,
            leaders: self.leaders.clone().map(|b| (b, self.show_leaders)),
        }
    }

    /// Appends the bytes of the next frame to `out` (nothing if the screen would not change).
    pub fn compose(&mut self, snap: &Snapshot, now: Instant, out: &mut Vec<u8>) {
        let key = self.key(snap, now);
        let eye = key.eye;
        if self.shown.as_ref() == Some(&key) {
            return;
        }
        self.notice_shown = key.note;
        self.shown = Some(key);
        self.screen
            .set_leaders(self.leaders.clone(), self.show_leaders);
        let eye_name = eye.and_then(|e| snap.player(e)).map(|p| p.name.as_str());
        let from = HeaderFrom::cheap(
            self.screen.colour(),
            (self.size, self.clamped),
            self.screen.map().has_game(),
            self.link.as_ref().map(|(t, _)| t.clone()),
        );
        let fresh = self
            .header
            .as_ref()
            .is_some_and(|(was, _)| was.same(snap, eye_name, &from));
        if !fresh {
            let from = from.with_names(snap, eye_name);
            let text = from.header(snap, eye, self.spectator);
            self.header = Some((from, text));
        }
        let header = self.header.as_ref().map_or("", |(_, h)| h.as_str());
        let mode = self.controls.mode();
        out.extend_from_slice(self.screen.frame(snap, eye, header, self.size, mode, now));
    }
}

/// A claimed size within what we draw.
fn clamp_size((cols, rows): (u32, u32)) -> (u16, u16) {
    super::size::clamp_size(cols, rows)
}

/// Whether a claimed size is outside what we draw (beyond the bounds, or zero).
fn is_clamped((cols, rows): (u32, u32)) -> bool {
    let (c, r) = clamp_size((cols, rows));
    (u32::from(c), u32::from(r)) != (cols, rows)
}

/// The next (or previous) player after `current` in join order, wrapping; `None` if nobody.
fn cycle(snap: &Snapshot, current: Option<PlayerId>, forward: bool) -> Option<PlayerId> {
    let ids: Vec<PlayerId> = snap.players.iter().map(|p| p.id).collect();
    if ids.is_empty() {
        return None;
    }
    let at = current.and_then(|c| ids.iter().position(|&i| i == c));
    let n = ids.len();
    let next = match (at, forward) {
        (None, _) => 0,
        (Some(i), true) => (i + 1) % n,
        (Some(i), false) => (i + n - 1) % n,
    };
    Some(ids[next])
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::game::multi::players::Players;
    use crate::world::World;

    #[test]
    fn tab_cycles_through_players_both_ways() {
        let mut ps = Players::new(Arc::new(World::default_world()));
        for (id, n) in [(5, "a"), (7, "b"), (9, "c")] {
            ps.join(id, n);
        }
        let snap = ps.snapshot();
        assert_eq!(cycle(&snap, None, true), Some(5));
        assert_eq!(cycle(&snap, Some(5), true), Some(7));
        assert_eq!(cycle(&snap, Some(9), true), Some(5));
        assert_eq!(cycle(&snap, Some(5), false), Some(9));
        assert_eq!(cycle(&Snapshot::default(), Some(5), true), None);
    }
}
