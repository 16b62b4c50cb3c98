//! `halfcast replay`: plays a `.hcr` recording headlessly and writes chosen frames or an asciicast.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use halfcast::encode::{ColorLevel, EncodeOptions};
use halfcast::input_file::read_regular_capped;
use halfcast::output::{json::RayReport, text};
use halfcast::present::Presenter;
use halfcast::replay::{MapSource, Replay, MAX_FRAMES, MAX_REPLAY_BYTES};
use halfcast::termframe::{to_cells_text, TermFrame};
use halfcast::ui::replay_player::{Frame, Player};
use halfcast::world::World;

/// What a replayed frame is written as.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReplayFormat {
    /// The 3D view's framebuffer (COLS × 2·ROWS pixels of the view pane).
    Png,
    /// The whole screen as the terminal receives it in a full redraw.
    Ansi,
    /// The 3D view as a plain ASCII shade ramp.
    Txt,
    /// The whole screen as text for code review: the glyph grid, then style runs (colours, attributes).
    Cells,
    /// The 3D view's rays (same shape as `render --format json`).
    Json,
    /// An asciicast v2 recording of the whole run at the recorded timing.
    Cast,
}

/// An error with the exit code it ends the program with.
pub struct ReplayFailure {
    pub code: u8,
    pub message: String,
}

fn input(message: impl std::fmt::Display) -> ReplayFailure {
    ReplayFailure {
        code: 2,
        message: message.to_string(),
    }
}

fn io(message: impl std::fmt::Display) -> ReplayFailure {
    ReplayFailure {
        code: 1,
        message: message.to_string(),
    }
}

/// Reads and parses a replay file.
///
/// # Errors
/// Unreadable or invalid files (exit 2).
pub fn read_replay(path: &Path) -> Result<Replay, ReplayFailure> {
    let bytes = read_regular_capped(path, MAX_REPLAY_BYTES)
        .map_err(|e| input(format!("{}: cannot read: {e}", path.display())))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| input(format!("{}: cannot read: not UTF-8 text", path.display())))?;
    Replay::parse(&path.display().to_string(), &text).map_err(input)
}

/// Drops the frames after frame `last`, so a run ends showing it (`--until-frame`).
///
/// # Errors
/// `last` is past the end of the replay (exit 2).
pub fn cut_after(replay: &mut Replay, last: usize) -> Result<(), ReplayFailure> {
    if last >= replay.frames.len() {
        return Err(past_the_end(last, replay));
    }
    replay.frames.truncate(last + 1);
    Ok(())
}

fn past_the_end(frame: usize, replay: &Replay) -> ReplayFailure {
    input(format!(
        "frame {frame} is past the end (the replay has {} frames, 0 to {})",
        replay.frames.len(),
        replay.frames.len().saturating_sub(1)
    ))
}

/// Loads the world a replay was recorded in: the embedded map, or its map file (as recorded,
/// else beside the replay file).
///
/// # Errors
/// The map cannot be found or is invalid (exit 2).
pub fn replay_world(replay: &Replay, replay_path: &Path) -> Result<Arc<World>, ReplayFailure> {
    match &replay.header.map {
        MapSource::Embedded => Ok(Arc::new(World::default_world())),
        MapSource::File(p) => {
            let direct = PathBuf::from(p);
            let beside = replay_path.parent().map(|d| d.join(p));
            let path = if direct.exists() {
                direct
            } else {
                beside.filter(|b| b.exists()).unwrap_or(direct)
            };
            let (world, warnings) = World::from_file(&path, false).map_err(input)?;
            for w in warnings {
                eprintln!("{w}");
            }
            Ok(Arc::new(world))
        }
    }
    .and_then(|world| {
        // A start in a cell too low for the eye (an edited file) is refused like a bad `--pos`.
        halfcast::game::pose::player_start(&world.map, replay.header.pos, "start")
            .map_err(|m| input(format!("{}: {m}", replay_path.display())))?;
        Ok(world)
    })
}

fn too_many_frames() -> String {
    format!(
        "a replay holds at most {MAX_FRAMES} frames (0 to {})",
        MAX_FRAMES - 1
    )
}

/// Parses `0,5,10` and ranges like `20-30` into sorted, unique frame numbers.
///
/// # Errors
/// Anything but numbers, commas and ascending ranges.
pub fn parse_frames(s: &str) -> Result<Vec<usize>, String> {
    let mut out = Vec::new();
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let num = |t: &str| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("'{part}' is not a frame number or range"))
        };
        match part.split_once('-') {
            Some((a, b)) => {
                let (a, b) = (num(a)?, num(b)?);
                if a > b {
                    return Err(format!("'{part}' is not an ascending range"));
                }
                if b >= MAX_FRAMES || out.len() + (b - a) >= MAX_FRAMES {
                    return Err(too_many_frames());
                }
                out.extend(a..=b);
            }
            None => {
                let n = num(part)?;
                if n >= MAX_FRAMES || out.len() >= MAX_FRAMES {
                    return Err(too_many_frames());
                }
                out.push(n);
            }
        }
    }
    if out.is_empty() {
        return Err("no frames given".into());
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// The bytes of one frame in a per-frame format.
fn frame_bytes(
    frame: &Frame,
    format: ReplayFormat,
    level: ColorLevel,
) -> Result<Vec<u8>, ReplayFailure> {
    Ok(match format {
        ReplayFormat::Png => frame.view.to_png().map_err(io)?,
        ReplayFormat::Txt => text::to_text(&frame.view).into_bytes(),
        ReplayFormat::Cells => to_cells_text(&TermFrame::from_buffer(&frame.screen)).into_bytes(),
        ReplayFormat::Ansi => {
            let mut p = Presenter::new(EncodeOptions::new(level));
            p.frame(&frame.screen, &frame.view, frame.view_area)
                .to_vec()
        }
        ReplayFormat::Json => {
            let camera = frame.camera;
            let mut s = RayReport::new(&camera, &frame.cast, frame.view.cell_rows()).to_json();
            s.push('\n');
            s.into_bytes()
        }
        ReplayFormat::Cast => unreachable!("cast is a whole-run format"),
    })
}

fn extension(format: ReplayFormat) -> &'static str {
    match format {
        ReplayFormat::Png => "png",
        ReplayFormat::Ansi => "ansi",
        ReplayFormat::Txt => "txt",
        ReplayFormat::Cells => "cells.txt",
        ReplayFormat::Json => "json",
        ReplayFormat::Cast => "cast",
    }
}

/// Writes the chosen frames as `DIR/frame-NNNNN.EXT`, each file whole or not at all, and at
/// most `max_bytes` in all.
///
/// # Errors
/// A frame past the end or the byte cap reached (exit 2), or a file that cannot be written
/// (exit 1).
pub fn write_frames(
    replay: &Replay,
    world: Arc<World>,
    frames: &[usize],
    format: ReplayFormat,
    level: ColorLevel,
    dir: &Path,
    max_bytes: u64,
) -> Result<(), ReplayFailure> {
    let last = *frames
        .last()
        .expect("parse_frames never returns an empty list");
    if last >= replay.frames.len() {
        return Err(past_the_end(last, replay));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| io(format!("cannot create {}: {e}", dir.display())))?;
    let mut player = Player::new(world, &replay.header);
    let mut wanted = frames.iter().peekable();
    let mut written = 0u64;
    for input_frame in &replay.frames {
        let Some(frame) = player.play(input_frame) else {
            break;
        };
        if wanted.peek() == Some(&&frame.index) {
            wanted.next();
            let path = dir.join(format!("frame-{:05}.{}", frame.index, extension(format)));
            let bytes = frame_bytes(&frame, format, level)?;
            written = written.saturating_add(bytes.len() as u64);
            if written > max_bytes {
                return Err(input(format!(
                    "stopped before writing frame {}: the frame files would pass \
                     --max-output-bytes {max_bytes} (the frames before it were written, each \
                     complete)",
                    frame.index
                )));
            }
            super::output_file::write_whole(&path, &bytes)
                .map_err(|e| io(format!("cannot write {}: {e}", path.display())))?;
        }
        if wanted.peek().is_none() {
            break;
        }
    }
    match wanted.next() {
        Some(f) => Err(input(format!("the replay quits before frame {f}"))),
        None => Ok(()),
    }
}

/// Why an asciicast stopped before the end of the run.
#[derive(Debug)]
pub enum CastStop {
    /// A write failed.
    Io(std::io::Error),
    /// The next event would have taken the output past `cap` bytes; it was not written.
    OutputLimit {
        /// The frame whose event did not fit.
        frame: usize,
        /// The time of that frame in the cast, in seconds.
        at: f64,
        /// The cap (`--max-output-bytes`).
        cap: u64,
    },
}

impl From<std::io::Error> for CastStop {
    fn from(e: std::io::Error) -> Self {
        Self::Io(e)
    }
}

/// Writes whole lines to an output, refusing the line that would take it past a byte cap, so
/// what was written always ends with a complete line.
struct CappedLines<'a, W: Write> {
    out: &'a mut W,
    written: u64,
    cap: u64,
}

impl<W: Write> CappedLines<'_, W> {
    /// Writes `line` and a newline, or returns false (writing nothing) if it would not fit.
    fn line(&mut self, line: &str) -> std::io::Result<bool> {
        let n = line.len() as u64 + 1;
        if self.written.saturating_add(n) > self.cap {
            return Ok(false);
        }
        self.out.write_all(line.as_bytes())?;
        self.out.write_all(b"\n")?;
        self.written += n;
        Ok(true)
    }
}

/// One asciicast v2 event line.
fn cast_event(t: f64, kind: &str, data: &str) -> String {
    serde_json::json!([t, kind, data]).to_string()
}

/// The event that ends a cast cut short, so whoever plays it sees that it is incomplete.
#[must_use]
pub fn cast_cut_notice(at: f64, why: &str) -> String {
    cast_event(
        at,
        "o",
        &format!("\x1b[0m\x1b[?25h\r\n[halfcast: this cast is incomplete: {why}]\r\n"),
    )
}

/// The whole run as an asciicast v2 file, written to `out` frame by frame as it is rendered
/// (a header line, then one output event per frame), so memory stays flat however long the run;
/// at most `max_bytes` are written, and only whole lines.
///
/// # Errors
/// The first write that fails, or the first event that would pass `max_bytes`.
pub fn write_asciicast(
    replay: &Replay,
    world: Arc<World>,
    level: ColorLevel,
    max_bytes: u64,
    out: &mut impl Write,
) -> Result<(), CastStop> {
    let h = &replay.header;
    let head = serde_json::json!({
        "version": 2, "width": h.size.0, "height": h.size.1,
        "title": "halfcast replay", "env": {"TERM": "xterm-256color"},
    });
    let mut lines = CappedLines {
        out,
        written: 0,
        cap: max_bytes,
    };
    let over = |frame: usize, at: f64| CastStop::OutputLimit {
        frame,
        at,
        cap: max_bytes,
    };
    if !lines.line(&head.to_string())? || !lines.line(&cast_event(0.0, "o", "\x1b[?25l"))? {
        return Err(over(0, 0.0));
    }
    let mut presenter = Presenter::new(EncodeOptions::new(level));
    let mut player = Player::new(world, &replay.header);
    let mut size = h.size;
    for input_frame in &replay.frames {
        let Some(frame) = player.play(input_frame) else {
            break;
        };
        let t = frame.index as f64 / f64::from(h.fps);
        if player.size() != size {
            size = player.size();
            if !lines.line(&cast_event(t, "r", &format!("{}x{}", size.0, size.1)))? {
                return Err(over(frame.index, t));
            }
        }
        let bytes = presenter.frame(&frame.screen, &frame.view, frame.view_area);
        if !lines.line(&cast_event(t, "o", &String::from_utf8_lossy(bytes)))? {
            return Err(over(frame.index, t));
        }
    }
    lines.out.flush()?;
    Ok(())
}
