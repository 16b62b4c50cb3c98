//! The `.hcr` replay file: versioned JSON lines (a header, then input events by frame number).
//!
//! ```text
//! {"halfcast_replay":1,"map":null,"start":{"pos":[15.5,5.5],"angle":90.0,"fov":66.0},"size":[160,48],"fps":30,"seed":0}
//! {"frame":0,"held":["forward"]}
//! {"frame":12,"held":["forward","turn_left"]}
//! {"frame":20,"command":"toggle_pause"}
//! {"frame":21,"command":"move_column","by":-3}
//! {"frame":22,"ui":"toggle_minimap"}
//! {"frame":25,"ui":"set_glyphs","glyphs":"sextant"}
//! {"frame":30,"size":[120,40]}
//! {"end":40}
//! ```
//! `held` replaces the set of held actions from that frame on; commands and UI toggles happen
//! once, at the start of their frame. Frame 0 is the start; frame N is drawn after N steps of
//! 1/fps seconds each.
//!
//! The glyph key is recorded as the setting it led to (`set_glyphs`), since where it leads
//! depends on the terminal it was pressed in (octants are skipped behind tmux). Recordings made
//! before that hold the key itself (`cycle_glyphs`), which still replays as the plain cycle
//! through all four settings, as it did when they were made.

use std::fmt::Write;

use serde_json::{json, Value};

use crate::game::{Action, Command, Held, Input, Speeds};
use crate::render::glyphs::Glyphs;
use crate::vec2::Vec2;

/// Things the TUI itself does (not the game), recorded with each frame of a replay.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UiCommand {
    /// Quit.
    Quit,
    /// Esc: closes the help if open, else quits.
    Back,
    /// Show or hide the minimap.
    ToggleMinimap,
    /// Show or hide the ray pane.
    ToggleDebug,
    /// Show or hide the help.
    ToggleHelp,
    /// The colour key: the next colour level (truecolor → 256 → 16 → mono).
    CycleColours,
    /// The figure key: write the debugged column's figure to a file (local play only).
    SaveFigure,
    /// The glyph key: the next block characters (half → quadrant → sextant → octant). Live,
    /// the session resolves it into [`UiCommand::SetGlyphs`] before recording; in a recording
    /// (older ones only) it replays as the plain cycle.
    CycleGlyphs,
    /// The block characters the glyph key switched to (what recordings keep).
    SetGlyphs(Glyphs),
}

/// The format version this build writes and the newest it reads.
pub const VERSION: u64 = 1;

/// Longest replay accepted, in frames (about 9 hours at 30 fps), so a corrupt `end` cannot
/// make us allocate without bound.
pub const MAX_FRAMES: usize = 1_000_000;

/// Most bytes a replay file may hold: a million frames with an event line each fit easily.
pub const MAX_REPLAY_BYTES: u64 = 64 << 20;

/// Where the replayed map comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MapSource {
    /// The embedded default map.
    Embedded,
    /// A map file path, as given when recording.
    File(String),
}

/// The first line: everything needed to rebuild the starting state.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    /// The map played.
    pub map: MapSource,
    /// Start position in cells.
    pub pos: Vec2,
    /// Start angle in degrees (0 = east, 90 = north).
    pub angle_deg: f64,
    /// Horizontal field of view in degrees.
    pub fov_deg: f64,
    /// Terminal size at the start, in cells.
    pub size: (u16, u16),
    /// Frames (steps) per second; every step advances 1/fps seconds.
    pub fps: u32,
    /// Reserved for randomness (the game has none yet); replays keep it so they stay exact.
    pub seed: u64,
    /// Walking and turning speeds (written only when not the defaults).
    pub speeds: Speeds,
    /// Block characters of the view at the start (written only when not half-blocks; a
    /// recording without it, as every one before the glyph ladder, replays as half-blocks).
    pub glyphs: Glyphs,
}

/// What happens at the start of one frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrameInput {
    /// The game input of this frame.
    pub input: Input,
    /// UI commands of this frame, in order.
    pub ui: Vec<UiCommand>,
    /// A terminal resize at this frame.
    pub resize: Option<(u16, u16)>,
}

/// A whole recording, expanded to one [`FrameInput`] per frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Replay {
    /// The starting state.
    pub header: Header,
    /// One entry per frame.
    pub frames: Vec<FrameInput>,
}

/// A replay file that cannot be used, with the line that broke it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}: {message}")]
pub struct ReplayError {
    /// The replay file's name.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

const ACTIONS: [(Action, &str); 9] = [
    (Action::Forward, "forward"),
    (Action::Back, "back"),
    (Action::TurnLeft, "turn_left"),
    (Action::TurnRight, "turn_right"),
    (Action::StrafeLeft, "strafe_left"),
    (Action::StrafeRight, "strafe_right"),
    (Action::LookUp, "look_up"),
    (Action::LookDown, "look_down"),
    (Action::Crouch, "crouch"),
];

const UI: [(UiCommand, &str); 8] = [
    (UiCommand::ToggleMinimap, "toggle_minimap"),
    (UiCommand::ToggleDebug, "toggle_debug"),
    (UiCommand::ToggleHelp, "toggle_help"),
    (UiCommand::Back, "back"),
    (UiCommand::Quit, "quit"),
    (UiCommand::CycleColours, "cycle_colours"),
    (UiCommand::SaveFigure, "save_figure"),
    (UiCommand::CycleGlyphs, "cycle_glyphs"),
];

fn action_name(a: Action) -> &'static str {
    ACTIONS
        .iter()
        .find(|(x, _)| *x == a)
        .map_or("?", |(_, n)| n)
}

fn ui_name(u: UiCommand) -> &'static str {
    UI.iter().find(|(x, _)| *x == u).map_or("?", |(_, n)| n)
}

fn held_names(h: Held) -> Vec<&'static str> {
    Action::ALL
        .iter()
        .filter(|&&a| h.contains(a))
        .map(|&a| action_name(a))
        .collect()
}

fn command_json(frame: usize, c: &Command) -> Value {
    match *c {
        Command::TogglePause => json!({"frame": frame, "command": "toggle_pause"}),
        Command::MoveColumn(by) => json!({"frame": frame, "command": "move_column", "by": by}),
        Command::StepDda => json!({"frame": frame, "command": "step_dda"}),
        Command::RunToHit => json!({"frame": frame, "command": "run_to_hit"}),
        Command::Turn(r) => json!({"frame": frame, "command": "turn", "radians": r}),
        Command::UseDoor => json!({"frame": frame, "command": "use_door"}),
        Command::Jump => json!({"frame": frame, "command": "jump"}),
        Command::ToggleNight => json!({"frame": frame, "command": "toggle_night"}),
        Command::Nudge(a, secs) => {
            json!({"frame": frame, "command": "nudge", "action": action_name(a), "seconds": secs})
        }
        Command::CentrePitch => json!({"frame": frame, "command": "centre_pitch"}),
        Command::Fire => json!({"frame": frame, "command": "fire"}),
        Command::ScrollPane(by) => json!({"frame": frame, "command": "scroll_pane", "by": by}),
    }
}

impl Replay {
    /// Writes the file: the header, then only the frames where something happens.
    #[must_use]
    pub fn to_jsonl(&self) -> String {
        let h = &self.header;
        let map = match &h.map {
            MapSource::Embedded => Value::Null,
            MapSource::File(p) => Value::String(p.clone()),
        };
        let mut head = json!({
            "halfcast_replay": VERSION, "map": map,
            "start": {"pos": [h.pos.x, h.pos.y], "angle": h.angle_deg, "fov": h.fov_deg},
            "size": [h.size.0, h.size.1], "fps": h.fps, "seed": h.seed,
        });
        if h.glyphs != Glyphs::Half {
            head["glyphs"] = json!(h.glyphs.name());
        }
        if h.speeds != Speeds::default() {
            head["speeds"] = json!({"move": h.speeds.move_cells, "turn": h.speeds.turn_deg()});
        }
        let mut out = format!("{head}\n");
        let mut held = Held::default();
        for (i, f) in self.frames.iter().enumerate() {
            if let Some((c, r)) = f.resize {
                let _ = writeln!(out, "{}", json!({"frame": i, "size": [c, r]}));
            }
            if f.input.held != held || (i == 0 && !held.is_empty()) {
                held = f.input.held;
                let _ = writeln!(out, "{}", json!({"frame": i, "held": held_names(held)}));
            }
            for c in &f.input.commands {
                let _ = writeln!(out, "{}", command_json(i, c));
            }
            for u in &f.ui {
                let line = match u {
                    UiCommand::SetGlyphs(g) => {
                        json!({"frame": i, "ui": "set_glyphs", "glyphs": g.name()})
                    }
                    _ => json!({"frame": i, "ui": ui_name(*u)}),
                };
                let _ = writeln!(out, "{line}");
            }
        }
        let _ = writeln!(out, "{}", json!({"end": self.frames.len()}));
        out
    }

    /// Reads a replay file's text; `file` names it in errors.
    ///
    /// # Errors
    /// Not JSON lines, a newer version, unknown names, frames out of order or past the end.
    pub fn parse(file: &str, text: &str) -> Result<Self, ReplayError> {
        let err = |line: usize, message: String| ReplayError {
            file: file.to_owned(),
            line,
            message,
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l))
            .filter(|(_, l)| !l.trim().is_empty());
        let (n, first) = lines
            .next()
            .ok_or_else(|| err(1, "empty file: not a halfcast replay".into()))?;
        let head: Value = serde_json::from_str(first)
            .map_err(|e| err(n, format!("not a halfcast replay header: {e}")))?;
        let header = parse_header(&head).map_err(|m| err(n, m))?;
        let mut frames: Vec<FrameInput> = Vec::new();
        let mut held = Held::default();
        let mut end = None;
        for (n, line) in lines {
            if end.is_some() {
                return Err(err(n, "content after the end line".into()));
            }
            let v: Value =
                serde_json::from_str(line).map_err(|e| err(n, format!("not JSON: {e}")))?;
            if let Some(e) = v.get("end") {
                let e = e
                    .as_u64()
                    .and_then(|e| usize::try_from(e).ok())
                    .ok_or_else(|| err(n, "end must be a frame count".into()))?;
                if e > MAX_FRAMES || e < frames.len() {
                    return Err(err(
                        n,
                        format!("end {e} is before the last event or over {MAX_FRAMES} frames"),
                    ));
                }
                while frames.len() < e {
                    frames.push(FrameInput {
                        input: Input {
                            held,
                            commands: Vec::new(),
                        },
                        ..FrameInput::default()
                    });
                }
                end = Some(e);
                continue;
            }
            let frame = v
                .get("frame")
                .and_then(Value::as_u64)
                .and_then(|f| usize::try_from(f).ok())
                .ok_or_else(|| err(n, "event without a frame number".into()))?;
            if frame >= MAX_FRAMES || frame + 1 < frames.len() {
                return Err(err(
                    n,
                    format!("frame {frame} is out of order or over {MAX_FRAMES}"),
                ));
            }
            while frames.len() <= frame {
                frames.push(FrameInput {
                    input: Input {
                        held,
                        commands: Vec::new(),
                    },
                    ..FrameInput::default()
                });
            }
            let slot = frames.last_mut().expect("pushed above");
            parse_event(&v, &mut held, slot).map_err(|m| err(n, m))?;
        }
        if end.is_none() {
            return Err(err(
                text.lines().count().max(1),
                "missing the final {\"end\":N} line (truncated file?)".into(),
            ));
        }
        Ok(Self { header, frames })
    }
}

fn parse_header(v: &Value) -> Result<Header, String> {
    let version = v
        .get("halfcast_replay")
        .and_then(Value::as_u64)
        .ok_or("not a halfcast replay (no \"halfcast_replay\" version)")?;
    if version > VERSION {
        return Err(format!("replay version {version} is newer than this halfcast reads (version {VERSION}); upgrade halfcast"));
    }
    if version == 0 {
        return Err("replay version 0 does not exist".into());
    }
    let num = |v: Option<&Value>, what: &str| {
        v.and_then(Value::as_f64)
            .filter(|x| x.is_finite())
            .ok_or(format!("header: {what} must be a number"))
    };
    let map = match v.get("map") {
        None | Some(Value::Null) => MapSource::Embedded,
        Some(Value::String(s)) => MapSource::File(s.clone()),
        _ => return Err("header: map must be null or a path".into()),
    };
    let start = v.get("start").ok_or("header: missing start")?;
    let pos = start
        .get("pos")
        .and_then(Value::as_array)
        .filter(|a| a.len() == 2)
        .ok_or("header: start.pos must be [x,y]")?;
    let size = v
        .get("size")
        .and_then(Value::as_array)
        .filter(|a| a.len() == 2)
        .ok_or("header: size must be [cols,rows]")?;
    let dim = |x: &Value| {
        x.as_u64()
            .and_then(|d| u16::try_from(d).ok())
            .filter(|&d| d > 0 && d <= 2000)
            .ok_or("header: size must be 1..=2000")
    };
    let fps = v
        .get("fps")
        .and_then(Value::as_u64)
        .filter(|&f| (1..=1000).contains(&f))
        .ok_or("header: fps must be 1..=1000")?;
    let fov = num(start.get("fov"), "start.fov")?;
    if !(fov > 0.0 && fov < 180.0) {
        return Err("header: start.fov must be between 0 and 180".into());
    }
    Ok(Header {
        map,
        pos: Vec2::new(
            num(pos.first(), "start.pos")?,
            num(pos.get(1), "start.pos")?,
        ),
        angle_deg: num(start.get("angle"), "start.angle")?,
        fov_deg: fov,
        size: (dim(&size[0])?, dim(&size[1])?),
        fps: fps as u32,
        seed: v.get("seed").and_then(Value::as_u64).unwrap_or(0),
        speeds: match v.get("speeds") {
            None => Speeds::default(),
            Some(sp) => Speeds::new(
                num(sp.get("move"), "speeds.move")?,
                num(sp.get("turn"), "speeds.turn")?,
            )?,
        },
        glyphs: match v.get("glyphs") {
            None => Glyphs::Half,
            Some(g) => g
                .as_str()
                .ok_or_else(|| "header: glyphs must be a name".to_owned())?
                .parse()
                .map_err(|e| format!("header: {e}"))?,
        },
    })
}

fn parse_event(v: &Value, held: &mut Held, slot: &mut FrameInput) -> Result<(), String> {
    if let Some(list) = v.get("held") {
        let list = list
            .as_array()
            .ok_or("held must be a list of action names")?;
        let mut h = Held::default();
        for a in list {
            let name = a.as_str().unwrap_or_default();
            let (action, _) = ACTIONS.iter().find(|(_, n)| *n == name).ok_or_else(|| format!("unknown action '{a}' (known: forward, back, turn_left, turn_right, strafe_left, strafe_right, look_up, look_down, crouch)"))?;
            h.insert(*action);
        }
        *held = h;
        slot.input.held = h;
    } else if let Some(c) = v.get("command") {
        let name = c.as_str().unwrap_or_default();
        let command = match name {
            "toggle_pause" => Command::TogglePause,
            "step_dda" => Command::StepDda,
            "run_to_hit" => Command::RunToHit,
            "use_door" => Command::UseDoor,
            "jump" => Command::Jump,
            "toggle_night" => Command::ToggleNight,
            "centre_pitch" => Command::CentrePitch,
            "fire" => Command::Fire,
            "nudge" => {
                let name = v.get("action").and_then(Value::as_str).unwrap_or_default();
                let (action, _) = ACTIONS
                    .iter()
                    .find(|(_, n)| *n == name)
                    .ok_or("nudge needs a known \"action\"")?;
                let secs = v
                    .get("seconds")
                    .and_then(Value::as_f64)
                    .filter(|s| s.is_finite() && *s >= 0.0)
                    .ok_or("nudge needs a number \"seconds\" (0 or more)")?;
                Command::Nudge(*action, secs)
            }
            "move_column" => Command::MoveColumn(
                v.get("by")
                    .and_then(Value::as_i64)
                    .and_then(|b| i32::try_from(b).ok())
                    .ok_or("move_column needs an integer \"by\"")?,
            ),
            "scroll_pane" => Command::ScrollPane(
                v.get("by")
                    .and_then(Value::as_i64)
                    .and_then(|b| i32::try_from(b).ok())
                    .ok_or("scroll_pane needs an integer \"by\"")?,
            ),
            "turn" => Command::Turn(
                v.get("radians")
                    .and_then(Value::as_f64)
                    .filter(|r| r.is_finite())
                    .ok_or("turn needs a number \"radians\"")?,
            ),
            _ => return Err(format!("unknown command '{c}'")),
        };
        slot.input.commands.push(command);
    } else if let Some(u) = v.get("ui") {
        let name = u.as_str().unwrap_or_default();
        if name == "set_glyphs" {
            let glyphs = v
                .get("glyphs")
                .and_then(Value::as_str)
                .ok_or("set_glyphs needs a \"glyphs\" name")?
                .parse()?;
            slot.ui.push(UiCommand::SetGlyphs(glyphs));
            return Ok(());
        }
        let (ui, _) = UI
            .iter()
            .find(|(_, n)| *n == name)
            .ok_or_else(|| format!("unknown ui command '{u}'"))?;
        slot.ui.push(*ui);
    } else if let Some(s) = v.get("size") {
        let s = s
            .as_array()
            .filter(|a| a.len() == 2)
            .ok_or("size must be [cols,rows]")?;
        let dim = |x: &Value| {
            x.as_u64()
                .and_then(|d| u16::try_from(d).ok())
                .filter(|&d| d > 0 && d <= 2000)
                .ok_or("size must be 1..=2000")
        };
        slot.resize = Some((dim(&s[0])?, dim(&s[1])?));
    } else {
        return Err("event has none of held, command, ui, size".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Replay {
        let header = Header {
            map: MapSource::Embedded,
            pos: Vec2::new(15.5, 5.5),
            angle_deg: 90.0,
            fov_deg: 66.0,
            size: (80, 24),
            fps: 30,
            seed: 0,
            speeds: Speeds::default(),
            glyphs: Glyphs::Half,
        };
        let mut frames = vec![FrameInput::default(); 6];
        frames[1].input.held = [Action::Forward].into_iter().collect();
        frames[2].input.held = frames[1].input.held;
        frames[2].input.commands.push(Command::MoveColumn(-3));
        frames[3].ui.push(UiCommand::ToggleMinimap);
        frames[4].resize = Some((100, 30));
        frames[4].input.commands.push(Command::Turn(0.25));
        Replay { header, frames }
    }

    #[test]
    fn writes_and_reads_back_the_same_replay() {
        let r = sample();
        let text = r.to_jsonl();
        assert!(
            text.starts_with("{\"halfcast_replay\":1,\"map\":null,\"start\":{\"pos\":[15.5,5.5],"),
            "{text}"
        );
        assert_eq!(Replay::parse("r.hcr", &text).unwrap(), r);
        assert!(text.ends_with("{\"end\":6}\n"));
    }

    #[test]
    fn the_glyph_setting_rides_in_the_header_and_old_recordings_are_half_blocks() {
        let mut r = sample();
        assert!(!r.to_jsonl().contains("glyphs"));
        r.header.glyphs = Glyphs::Octant;
        r.frames[2].ui.push(UiCommand::CycleGlyphs);
        let text = r.to_jsonl();
        assert!(text
            .lines()
            .next()
            .unwrap()
            .contains("\"glyphs\":\"octant\""));
        assert_eq!(Replay::parse("r.hcr", &text).unwrap(), r);
        let old = sample().to_jsonl();
        assert_eq!(
            Replay::parse("r.hcr", &old).unwrap().header.glyphs,
            Glyphs::Half
        );
        let bad = text.replace("\"octant\"", "\"braille\"");
        assert_eq!(
            Replay::parse("r.hcr", &bad).unwrap_err().to_string(),
            "r.hcr:1: header: 'braille' is not a glyph setting (half, quadrant, sextant or octant)"
        );
    }

    #[test]
    fn the_glyph_key_is_kept_as_the_setting_it_led_to_and_old_key_lines_still_read() {
        let mut r = sample();
        r.frames[3].ui.push(UiCommand::SetGlyphs(Glyphs::Sextant));
        r.frames[5].ui.push(UiCommand::SetGlyphs(Glyphs::Half));
        let text = r.to_jsonl();
        assert!(
            text.contains("{\"frame\":3,\"ui\":\"set_glyphs\",\"glyphs\":\"sextant\"}\n"),
            "{text}"
        );
        assert!(text.starts_with("{\"halfcast_replay\":1,"), "{text}");
        assert_eq!(Replay::parse("r.hcr", &text).unwrap(), r);
        // A recording from before holds the key; it reads as the key.
        let old = text.replace(
            "{\"frame\":5,\"ui\":\"set_glyphs\",\"glyphs\":\"half\"}",
            "{\"frame\":5,\"ui\":\"cycle_glyphs\"}",
        );
        let back = Replay::parse("r.hcr", &old).unwrap();
        assert_eq!(back.frames[5].ui, [UiCommand::CycleGlyphs]);
        let bad = text.replace("\"sextant\"", "\"braille\"");
        assert_eq!(
            Replay::parse("r.hcr", &bad).unwrap_err().to_string(),
            "r.hcr:6: 'braille' is not a glyph setting (half, quadrant, sextant or octant)"
        );
        let bare = text.replace(",\"glyphs\":\"sextant\"", "");
        assert_eq!(
            Replay::parse("r.hcr", &bare).unwrap_err().to_string(),
            "r.hcr:6: set_glyphs needs a \"glyphs\" name"
        );
    }

    #[test]
    fn future_versions_and_corruption_are_clear_errors() {
        let e = Replay::parse("r.hcr", "{\"halfcast_replay\":2}\n").unwrap_err();
        assert_eq!(e.to_string(), "r.hcr:1: replay version 2 is newer than this halfcast reads (version 1); upgrade halfcast");
        let text = sample().to_jsonl().replace("\"forward\"", "\"jump\"");
        let e = Replay::parse("r.hcr", &text).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("r.hcr:2: unknown action '\"jump\"'"),
            "{e}"
        );
        let truncated: String = sample()
            .to_jsonl()
            .lines()
            .take(3)
            .map(|l| format!("{l}\n"))
            .collect();
        assert!(Replay::parse("r.hcr", &truncated)
            .unwrap_err()
            .message
            .contains("missing the final"));
        assert!(Replay::parse("r.hcr", "garbage")
            .unwrap_err()
            .message
            .starts_with("not a halfcast replay header"));
        assert!(Replay::parse("r.hcr", "").is_err());
    }

    #[test]
    fn taps_re_centring_and_speeds_round_trip() {
        let mut r = sample();
        r.header.speeds = Speeds::new(2.0, 90.0).unwrap();
        r.frames[5]
            .input
            .commands
            .push(Command::Nudge(Action::TurnRight, 0.0625));
        r.frames[5].input.commands.push(Command::CentrePitch);
        let text = r.to_jsonl();
        assert!(
            text.contains("\"speeds\":{\"move\":2.0,\"turn\":90.0}"),
            "{text}"
        );
        let back = Replay::parse("r.hcr", &text).unwrap();
        assert!((back.header.speeds.turn_deg() - 90.0).abs() < 1e-9);
        assert_eq!(back.frames, r.frames);
        // Default speeds are not written, so older files and new ones read the same.
        assert!(!sample().to_jsonl().contains("speeds"));
        let bad = text.replace("\"seconds\":0.0625", "\"seconds\":-1");
        let e = Replay::parse("r.hcr", &bad).unwrap_err();
        assert!(e.message.contains("nudge needs a number"), "{e}");
    }

    #[test]
    fn held_actions_persist_until_changed() {
        let text = "{\"halfcast_replay\":1,\"map\":null,\"start\":{\"pos\":[1.5,1.5],\"angle\":0,\"fov\":66},\"size\":[80,24],\"fps\":10}\n{\"frame\":2,\"held\":[\"forward\"]}\n{\"frame\":5,\"held\":[]}\n{\"end\":7}\n";
        let r = Replay::parse("r.hcr", text).unwrap();
        let held: Vec<bool> = r
            .frames
            .iter()
            .map(|f| f.input.held.contains(Action::Forward))
            .collect();
        assert_eq!(held, [false, false, true, true, true, false, false]);
    }
}
