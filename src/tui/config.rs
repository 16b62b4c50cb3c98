//! The player's config file (`$XDG_CONFIG_HOME/halfcast/config.toml` or `--config FILE`): key
//! bindings, speeds, the default colour level and which panes start shown.
//!
//! Every setting is optional. Unknown names and bad values are errors that name the file, line
//! and column, like a compiler would, so a typo is never silently ignored.

use std::collections::BTreeMap;
use std::fmt::Write;
use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use crate::encode::ColorLevel;
use crate::game::Speeds;
use crate::ui::keymap::KeyMap;

/// Everything the config file can set, with the defaults filled in.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    pub speeds: Speeds,
    /// The colour level to use when `--colors` is not given; `None` = detect from the environment.
    pub colors: Option<ColorLevel>,
    /// Block characters of the view when `--glyphs` is not given (U cycles them).
    pub glyphs: crate::render::glyphs::Glyphs,
    /// Whether the minimap is shown at start (M toggles it).
    pub minimap: bool,
    /// Whether the ray (DDA) pane is shown at start (I toggles it).
    pub ray_pane: bool,
    pub keys: KeyMap,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            speeds: Speeds::default(),
            colors: None,
            glyphs: crate::render::glyphs::Glyphs::Half,
            minimap: true,
            ray_pane: true,
            keys: KeyMap::default(),
        }
    }
}

/// A config file that cannot be used: where, and why.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ConfigError {
    /// `FILE:LINE:COL: message`.
    #[error("{file}:{line}:{col}: {message}")]
    At {
        file: String,
        line: usize,
        col: usize,
        message: String,
    },
    /// The file could not be read.
    #[error("{file}: {message}")]
    Read { file: String, message: String },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    #[serde(default)]
    speeds: RawSpeeds,
    #[serde(default)]
    display: RawDisplay,
    #[serde(default)]
    keys: BTreeMap<Spanned<String>, Spanned<Vec<Spanned<String>>>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawSpeeds {
    #[serde(rename = "move")]
    walk: Option<Spanned<Number>>,
    turn: Option<Spanned<Number>>,
}

/// A TOML integer or float (`turn = 90` and `turn = 90.0` both mean 90).
#[derive(Deserialize, Clone, Copy)]
#[serde(untagged)]
enum Number {
    Int(i64),
    Float(f64),
}

impl Number {
    #[allow(clippy::cast_precision_loss)]
    fn value(self) -> f64 {
        match self {
            Number::Int(i) => i as f64,
            Number::Float(f) => f,
        }
    }
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawDisplay {
    colors: Option<Spanned<String>>,
    glyphs: Option<Spanned<String>>,
    minimap: Option<bool>,
    ray_pane: Option<bool>,
}

/// Most bytes a config file may hold (a few dozen lines in practice).
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

impl Config {
    /// Where the config file lives when `--config` is not given:
    /// `$XDG_CONFIG_HOME/halfcast/config.toml`, else `~/.config/halfcast/config.toml`.
    #[must_use]
    pub fn default_path() -> Option<PathBuf> {
        let base = std::env::var_os("XDG_CONFIG_HOME")
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .or_else(|| {
                std::env::var_os("HOME")
                    .filter(|v| !v.is_empty())
                    .map(|h| PathBuf::from(h).join(".config"))
            })?;
        Some(base.join("halfcast").join("config.toml"))
    }

    /// Loads `path` (a regular file of at most [`MAX_CONFIG_BYTES`]); with `required` false a
    /// missing file means the defaults.
    ///
    /// # Errors
    /// The file cannot be read (or is a FIFO or device), is not TOML, or has an unknown name or a
    /// bad value.
    pub fn load(path: &Path, required: bool) -> Result<Self, ConfigError> {
        let file = path.display().to_string();
        match crate::input_file::read_regular_text(path, MAX_CONFIG_BYTES) {
            Ok(text) => Self::parse(&text, &file),
            Err(e) if !required && e.is_not_found() => Ok(Self::default()),
            Err(e) => Err(ConfigError::Read {
                file,
                message: e.to_string(),
            }),
        }
    }

    /// Parses a config file's text; `file` names it in errors.
    ///
    /// # Errors
    /// Not TOML, an unknown name, or a bad value (with its line and column).
    pub fn parse(text: &str, file: &str) -> Result<Self, ConfigError> {
        let at = |span: Range<usize>, message: String| {
            let (line, col) = line_col(text, span.start);
            ConfigError::At {
                file: file.to_string(),
                line,
                col,
                message,
            }
        };
        let raw: RawFile = toml::from_str(text).map_err(|e| {
            let message = e.message().trim().to_string();
            at(e.span().unwrap_or(0..0), message)
        })?;
        let mut c = Self::default();
        let walk = raw.speeds.walk.map(|v| (v.span(), v.get_ref().value()));
        let turn = raw.speeds.turn.map(|v| (v.span(), v.get_ref().value()));
        let move_cells = walk.clone().map_or(c.speeds.move_cells, |v| v.1);
        let turn_deg = turn.clone().map_or(c.speeds.turn_deg(), |v| v.1);
        let any = walk.is_some() || turn.is_some();
        for (value, max, unit, what) in [
            (walk, Speeds::MAX.0, "cells per second", "speeds.move"),
            (turn, Speeds::MAX.1, "degrees per second", "speeds.turn"),
        ] {
            if let Some((span, v)) = value {
                if !(v.is_finite() && v > 0.0 && v <= max) {
                    return Err(at(
                        span,
                        format!("{what} must be above 0 and at most {max} ({unit}), not {v}"),
                    ));
                }
            }
        }
        if any {
            c.speeds = Speeds::new(move_cells, turn_deg).map_err(|m| at(0..0, m))?;
        }
        if let Some(colors) = raw.display.colors {
            let name = colors.get_ref();
            c.colors = if name == "auto" {
                None
            } else {
                Some(name.parse().map_err(|_| {
                    at(
                        colors.span(),
                        format!(
                            "display.colors: '{name}' is not a colour level (auto, truecolor, 256, 16 or mono)"
                        ),
                    )
                })?)
            };
        }
        if let Some(glyphs) = raw.display.glyphs {
            c.glyphs = glyphs
                .get_ref()
                .parse()
                .map_err(|m| at(glyphs.span(), format!("display.glyphs: {m}")))?;
        }
        c.minimap = raw.display.minimap.unwrap_or(c.minimap);
        c.ray_pane = raw.display.ray_pane.unwrap_or(c.ray_pane);
        let mut spans = Vec::new();
        for (name, keys) in raw.keys {
            spans.push((name.get_ref().clone(), name.span()));
            let mut names = Vec::new();
            for k in keys.get_ref() {
                crate::ui::keymap::Key::parse(k.get_ref())
                    .map_err(|m| at(k.span(), format!("keys.{}: {m}", name.get_ref())))?;
                names.push(k.get_ref().clone());
            }
            c.keys
                .bind(name.get_ref(), &names)
                .map_err(|m| at(name.span(), format!("keys: {m}")))?;
        }
        if let Some((key, a, b)) = c.keys.conflict() {
            // Point at whichever of the two the file set (the other kept its default key).
            let span = spans
                .iter()
                .filter(|(n, _)| n == a || n == b)
                .map(|(_, s)| s.clone())
                .max_by_key(|s| s.start)
                .unwrap_or(0..0);
            return Err(at(
                span,
                format!("keys: '{key}' is bound to both {a} and {b} (give one of them other keys)"),
            ));
        }
        Ok(c)
    }

    /// This configuration as a config file (comments explain each setting); loads back equal.
    #[must_use]
    pub fn to_toml(&self) -> String {
        let mut out = String::from(
            "# halfcast config: $XDG_CONFIG_HOME/halfcast/config.toml (or --config FILE).\n\
             # Every setting is optional; command-line flags win over this file.\n\n[speeds]\n",
        );
        let _ = writeln!(out, "# Walking speed, cells per second (--move-speed).");
        let _ = writeln!(out, "move = {:?}", self.speeds.move_cells);
        let _ = writeln!(
            out,
            "# Turning speed, degrees per second (--turn-speed). The default is 2.6 radians a second, written out in degrees: about 149."
        );
        let _ = writeln!(out, "turn = {:?}", self.speeds.turn_deg());
        let _ = writeln!(out, "\n[display]");
        let _ = writeln!(
            out,
            "# Colour level when --colors is not given: auto (NO_COLOR, COLORTERM, else ask the terminal, else TERM), truecolor, 256, 16, mono."
        );
        let level = self.colors.map_or("auto", ColorLevel::name);
        let _ = writeln!(out, "colors = {level:?}");
        let _ = writeln!(
            out,
            "# Block characters of the view when --glyphs is not given: half, quadrant, sextant, octant (U cycles them)."
        );
        let _ = writeln!(out, "glyphs = {:?}", self.glyphs.name());
        let _ = writeln!(out, "# Panes shown at start (M and I toggle them).");
        let _ = writeln!(out, "minimap = {}", self.minimap);
        let _ = writeln!(out, "ray_pane = {}", self.ray_pane);
        let _ = writeln!(
            out,
            "\n[keys]\n# Each action takes a list of keys: a character (\"w\", \"?\") or a named key (space, up,\n\
             # down, left, right, enter, esc, tab, backspace, pageup, pagedown, home, end, insert,\n\
             # delete, f1-f12), optionally \"shift+\" before a named key. Ctrl+C always quits."
        );
        for (name, what, keys) in self.keys.entries() {
            let list: Vec<String> = keys.iter().map(|k| format!("{k:?}")).collect();
            let _ = writeln!(out, "{name} = [{}]  # {what}", list.join(", "));
        }
        out
    }
}

/// 1-based line and column (in characters) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_printed_defaults_load_back_as_the_defaults() {
        let text = Config::default().to_toml();
        let back = Config::parse(&text, "defaults.toml").unwrap();
        assert_eq!(back.keys, KeyMap::default());
        assert_eq!(back.colors, None);
        assert!(back.minimap && back.ray_pane);
        let d = Speeds::default();
        assert!((back.speeds.move_cells - d.move_cells).abs() < 1e-12);
        assert!((back.speeds.turn_radians - d.turn_radians).abs() < 1e-12);
    }

    #[test]
    fn settings_override_the_defaults() {
        let c = Config::parse(
            "[speeds]\nturn = 90\n[display]\ncolors = \"mono\"\nminimap = false\n[keys]\nforward = [\"k\", \"up\"]\n",
            "c.toml",
        )
        .unwrap();
        assert!((c.speeds.turn_deg() - 90.0).abs() < 1e-9);
        assert_eq!(c.colors, Some(ColorLevel::Mono));
        assert!(!c.minimap && c.ray_pane);
        assert_eq!(c.keys.first_key("forward").as_deref(), Some("k"));
    }

    #[test]
    fn a_missing_optional_file_is_the_defaults_and_a_missing_required_one_an_error() {
        let p = Path::new("/nonexistent/halfcast/config.toml");
        assert_eq!(Config::load(p, false).unwrap(), Config::default());
        let e = Config::load(p, true).unwrap_err().to_string();
        assert!(e.starts_with("/nonexistent/halfcast/config.toml: "), "{e}");
    }

    #[test]
    fn line_and_column_count_characters() {
        assert_eq!(line_col("ab\ncd", 4), (2, 2));
        assert_eq!(line_col("é\nx", 3), (2, 1));
        assert_eq!(line_col("", 0), (1, 1));
    }
}
