//! The page: our own HTML, CSS and JavaScript, compiled into the binary (no third-party code, no
//! build step). The script is ES modules served at `/js/<name>.js` from [`MODULES`]; one of them,
//! `tables.js`, is written here at start-up from halfcast's own tables: the 256-colour palette
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

/// The page's modules as written, by the name they are served under (`/js/<name>`).
const MODULES: &[(&str, &str)] = &[
    ("main.js", include_str!("page/main.js")),
    ("ansi.js", include_str!("page/ansi.js")),
    ("paint.js", include_str!("page/paint.js")),
    ("link.js", include_str!("page/link.js")),
    ("input.js", include_str!("page/input.js")),
    ("touch.js", include_str!("page/touch.js")),
    ("landing.js", include_str!("page/landing.js")),
    ("layout.js", include_str!("page/layout.js")),
    // The ray debugger's panel (issue 53), on the game page and on `/ray`.
    ("ray.js", include_str!("page/ray.js")),
    ("raywire.js", include_str!("page/raywire.js")),
    ("ray_figure.js", include_str!("page/ray_figure.js")),
    ("ray_text.js", include_str!("page/ray_text.js")),
];

static TABLES: LazyLock<String> = LazyLock::new(tables);

/// The module served at `/js/<name>`, `None` for a name the page does not have.
#[must_use]
pub fn module(name: &str) -> Option<&'static str> {
    if name == "tables.js" {
        return Some(&TABLES);
    }
    MODULES.iter().find(|(n, _)| *n == name).map(|(_, js)| *js)
}

/// `export const PALETTE = [[r,g,b]…]; export const BLOCKS = {codepoint: [rows, mask]…};` from
/// the encoder.
fn tables() -> String {
    let mut out = String::from("export const PALETTE = [");
    for i in 0..=255u8 {
        let c = xterm_rgb(i);
        let _ = write!(out, "[{},{},{}],", c.r, c.g, c.b);
    }
    out.push_str("];\nexport const BLOCKS = {");
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
        assert!(t.starts_with("export const PALETTE = [[0,0,0],[205,0,0],"));
        assert!(t.contains("[238,238,238],];"), "the last grey");
        // ▘ is the upper-left quadrant; the first sextant and octant are there too.
        assert!(t.contains(&format!("{}:[2,1],", u32::from('▘'))));
        assert!(t.contains(&format!("{}:[3,1],", 0x1FB00)));
        assert!(t.contains("118016:"), "U+1CD00, the first octant");
        assert!(!t.contains(&format!("{}:", u32::from('▀'))));
    }

    #[test]
    fn every_module_the_page_imports_is_served_and_short() {
        assert!(HTML.contains("src=\"js/main.js\""));
        for (name, js) in MODULES {
            assert!(js.lines().count() < 300, "{name} has 300 lines or more");
            for line in js.lines().filter(|l| l.starts_with("import ")) {
                let from = line.rsplit("./").next().unwrap_or("");
                let wanted = from.trim_end_matches(['"', '\'', ';']);
                assert!(
                    module(wanted).is_some(),
                    "{name} imports {wanted}, not served"
                );
            }
        }
        assert!(module("tables.js").is_some());
        assert_eq!(module("../etc/passwd"), None);
    }
}
