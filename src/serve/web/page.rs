//! The page: our own HTML, CSS and JavaScript, compiled into the binary (no third-party code, no
//! build step). The script is given halfcast's own tables at start-up: the 256-colour palette
//! the encoder matches against, and which pixels of a cell each quadrant, sextant and octant
//! character shows, so the page draws the same picture the encoder meant.

use std::fmt::Write as _;
use std::sync::LazyLock;

use crate::encode::glyph_mask::glyph;
use crate::encode::palette::xterm_rgb;
use crate::render::glyphs::Glyphs;

/// The page at `/`.
pub const HTML: &str = include_str!("page/index.html");
/// Its style sheet.
pub const CSS: &str = include_str!("page/halfcast.css");
/// The ray debugger's own page (`/ray?pos=…`): the ray panel without playing.
pub const RAY_HTML: &str = include_str!("page/ray.html");
/// The ray panel's style sheet.
pub const RAY_CSS: &str = include_str!("page/ray.css");

/// The ray panel's modules, served at `/js/<name>.js`.
const RAY_MODULES: [(&str, &str); 3] = [
    ("/js/ray.js", include_str!("page/ray.js")),
    ("/js/ray_figure.js", include_str!("page/ray_figure.js")),
    ("/js/ray_text.js", include_str!("page/ray_text.js")),
];

/// The ray panel's module at `path` (empty for a path that is none of them).
#[must_use]
pub fn ray_module(path: &str) -> &'static str {
    RAY_MODULES
        .iter()
        .find(|(p, _)| *p == path)
        .map_or("", |(_, js)| js)
}

/// Its script, before the tables.
const JS: &str = include_str!("page/halfcast.js");

static SCRIPT: LazyLock<String> = LazyLock::new(|| format!("{}\n{JS}", tables()));

/// The script as served: the tables, then the painter and the connection.
#[must_use]
pub fn script() -> &'static str {
    &SCRIPT
}

/// `const PALETTE = [[r,g,b]…]; const BLOCKS = {codepoint: [rows, mask]…};` from the encoder.
fn tables() -> String {
    let mut out = String::from("const PALETTE = [");
    for i in 0..=255u8 {
        let c = xterm_rgb(i);
        let _ = write!(out, "[{},{},{}],", c.r, c.g, c.b);
    }
    out.push_str("];\nconst BLOCKS = {");
    let mut seen = std::collections::HashSet::new();
    for g in [Glyphs::Quadrant, Glyphs::Sextant, Glyphs::Octant] {
        let rows = g.cell_size().1;
        for mask in 0..(1u16 << g.pixels_per_cell()) {
            let ch = glyph(g, mask as u8);
            if matches!(ch, ' ' | '▀' | '▄' | '█') || !seen.insert(ch) {
                continue;
            }
            let _ = write!(out, "{}:[{rows},{mask}],", u32::from(ch));
        }
    }
    out.push_str("};\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tables_name_every_block_character_once() {
        let t = tables();
        assert!(t.starts_with("const PALETTE = [[0,0,0],[205,0,0],"));
        assert!(t.contains("[238,238,238],];"), "the last grey");
        // ▘ is the upper-left quadrant; the first sextant and octant are there too.
        assert!(t.contains(&format!("{}:[2,1],", u32::from('▘'))));
        assert!(t.contains(&format!("{}:[3,1],", 0x1FB00)));
        assert!(t.contains("118016:"), "U+1CD00, the first octant");
        assert!(!t.contains(&format!("{}:", u32::from('▀'))));
    }
}
