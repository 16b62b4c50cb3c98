//! The SVG back-end: a [`Drawing`] as a plain, readable SVG document — one element per shape,
//! text as `<text>`, numbers rounded to 0.1 px, no embedded raster, no scripts.

use std::fmt::Write;

use super::drawing::{Anchor, Drawing, Shape, Stroke, Tag};
use crate::color::Rgb;

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c.r, c.g, c.b)
}

/// A coordinate with at most one decimal (`12`, `12.5`).
fn n(v: f64) -> String {
    let r = (v * 10.0).round() / 10.0;
    if r == r.trunc() {
        format!("{}", r as i64)
    } else {
        format!("{r:.1}")
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn stroke_attrs(s: &Stroke) -> String {
    let mut out = format!(
        r#" stroke="{}" stroke-width="{}""#,
        hex(s.colour),
        n(s.width)
    );
    if s.dashed {
        let d = n(s.dash());
        let _ = write!(out, r#" stroke-dasharray="{d} {d}""#);
    }
    out
}

fn tag_attrs(t: &Tag) -> String {
    let mut out = String::new();
    if !t.class.is_empty() {
        let _ = write!(out, r#" class="{}""#, escape(&t.class));
    }
    for (k, v) in &t.data {
        let _ = write!(out, r#" data-{k}="{}""#, escape(v));
    }
    out
}

/// The SVG document of `d`.
#[must_use]
pub fn to_svg(d: &Drawing) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="monospace">"#,
        w = n(d.width),
        h = n(d.height)
    );
    let _ = writeln!(
        s,
        r#"<rect width="{}" height="{}" fill="{}"/>"#,
        n(d.width),
        n(d.height),
        hex(d.background)
    );
    for shape in &d.shapes {
        match shape {
            Shape::Rect {
                at,
                size,
                fill,
                stroke,
            } => {
                let fill = match fill {
                    Some((c, o)) if *o < 1.0 => {
                        format!(r#" fill="{}" fill-opacity="{}""#, hex(*c), n2(*o))
                    }
                    Some((c, _)) => format!(r#" fill="{}""#, hex(*c)),
                    None => r#" fill="none""#.to_owned(),
                };
                let stroke = stroke.as_ref().map(stroke_attrs).unwrap_or_default();
                let _ = writeln!(
                    s,
                    r#"<rect x="{}" y="{}" width="{}" height="{}"{fill}{stroke}/>"#,
                    n(at.0),
                    n(at.1),
                    n(size.0),
                    n(size.1)
                );
            }
            Shape::Line { from, to, stroke } => {
                let _ = writeln!(
                    s,
                    r#"<line x1="{}" y1="{}" x2="{}" y2="{}"{} stroke-linecap="round"/>"#,
                    n(from.0),
                    n(from.1),
                    n(to.0),
                    n(to.1),
                    stroke_attrs(stroke)
                );
            }
            Shape::Circle {
                centre,
                r,
                fill,
                stroke,
            } => {
                let fill = fill.map_or_else(|| "none".to_owned(), hex);
                let stroke = stroke.as_ref().map(stroke_attrs).unwrap_or_default();
                let _ = writeln!(
                    s,
                    r#"<circle cx="{}" cy="{}" r="{}" fill="{fill}"{stroke}/>"#,
                    n(centre.0),
                    n(centre.1),
                    n(*r)
                );
            }
            Shape::Polygon { points, fill } => {
                let pts: Vec<String> = points
                    .iter()
                    .map(|p| format!("{},{}", n(p.0), n(p.1)))
                    .collect();
                let _ = writeln!(
                    s,
                    r#"<polygon points="{}" fill="{}" fill-opacity="{}"/>"#,
                    pts.join(" "),
                    hex(fill.0),
                    n2(fill.1)
                );
            }
            Shape::Text {
                at,
                text,
                size,
                colour,
                anchor,
                tag,
            } => {
                let anchor = match anchor {
                    Anchor::Start => "",
                    Anchor::Middle => r#" text-anchor="middle""#,
                    Anchor::End => r#" text-anchor="end""#,
                };
                // `size` is the cap height; a monospace font's em is about 1.4 of it.
                let _ = writeln!(
                    s,
                    r#"<text x="{}" y="{}" font-size="{}" fill="{}"{anchor}{}>{}</text>"#,
                    n(at.0),
                    n(at.1),
                    n(size * 1.4),
                    hex(*colour),
                    tag_attrs(tag),
                    escape(text)
                );
            }
        }
    }
    s.push_str("</svg>\n");
    s
}

fn n2(v: f64) -> String {
    let s = format!("{v:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::figure::drawing::Stroke;

    #[test]
    fn shapes_become_plain_elements_and_text_is_escaped() {
        let mut d = Drawing::new(100.0, 50.0, Rgb::new(255, 255, 255));
        d.line(
            (0.0, 0.0),
            (10.25, 5.0),
            Stroke::dashed(Rgb::new(0, 0, 0), 1.0),
        );
        d.tagged_text(
            (5.0, 20.0),
            "a < b & c",
            8.0,
            Rgb::new(1, 2, 3),
            Anchor::Middle,
            Tag {
                class: "crossing x".into(),
                data: vec![("step", "3".into())],
            },
        );
        let svg = to_svg(&d);
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100\""));
        assert!(svg.contains(
            r##"<line x1="0" y1="0" x2="10.3" y2="5" stroke="#000000" stroke-width="1" stroke-dasharray="3 3" stroke-linecap="round"/>"##
        ), "{svg}");
        assert!(
            svg.contains(r#"class="crossing x" data-step="3">a &lt; b &amp; c</text>"#),
            "{svg}"
        );
        assert!(svg.ends_with("</svg>\n"));
    }
}
