//! The drawing model both figure back-ends read: a canvas of plain shapes — rectangles, lines,
//! circles, polygons and text — in pixel units, y down. A figure is built once as a
//! [`Drawing`]; [`super::svg`] writes it as SVG and [`super::raster`] paints it for a PNG, so the
//! two can never show different things.

use crate::color::Rgb;

/// How a line or outline is stroked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// Colour.
    pub colour: Rgb,
    /// Width in pixels.
    pub width: f64,
    /// Dashed (dash and gap of 3 widths each, at least 3 px) rather than solid.
    pub dashed: bool,
}

impl Stroke {
    /// A solid stroke.
    #[must_use]
    pub const fn solid(colour: Rgb, width: f64) -> Self {
        Self {
            colour,
            width,
            dashed: false,
        }
    }

    /// A dashed stroke.
    #[must_use]
    pub const fn dashed(colour: Rgb, width: f64) -> Self {
        Self {
            colour,
            width,
            dashed: true,
        }
    }

    /// Dash and gap length in pixels.
    #[must_use]
    pub fn dash(&self) -> f64 {
        (self.width * 3.0).max(3.0)
    }
}

/// Where a text's anchor point is along it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// The text starts at the point.
    Start,
    /// The text is centred on the point.
    Middle,
    /// The text ends at the point.
    End,
}

/// A label that tests and readers of the SVG can find: a class and `data-` attributes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tag {
    /// SVG class names, space separated.
    pub class: String,
    /// `data-NAME` attributes (name without the prefix, value).
    pub data: Vec<(&'static str, String)>,
}

/// One thing drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// An axis-aligned rectangle.
    Rect {
        /// Top-left corner.
        at: (f64, f64),
        /// Width and height.
        size: (f64, f64),
        /// Fill colour and opacity (0–1), if filled.
        fill: Option<(Rgb, f64)>,
        /// Outline, if any.
        stroke: Option<Stroke>,
    },
    /// A straight line.
    Line {
        /// Start point.
        from: (f64, f64),
        /// End point.
        to: (f64, f64),
        /// How it is stroked.
        stroke: Stroke,
    },
    /// A circle.
    Circle {
        /// Centre.
        centre: (f64, f64),
        /// Radius.
        r: f64,
        /// Fill colour, if filled.
        fill: Option<Rgb>,
        /// Outline, if any.
        stroke: Option<Stroke>,
    },
    /// A filled polygon (no outline).
    Polygon {
        /// Corners in order.
        points: Vec<(f64, f64)>,
        /// Fill colour and opacity (0–1).
        fill: (Rgb, f64),
    },
    /// One line of text; `at` is on its baseline.
    Text {
        /// Anchor point on the baseline.
        at: (f64, f64),
        /// The text.
        text: String,
        /// Cap height in pixels (the PNG font scales by whole pixels to about this).
        size: f64,
        /// Colour.
        colour: Rgb,
        /// Which end (or the middle) sits at `at`.
        anchor: Anchor,
        /// Class and data for readers of the SVG.
        tag: Tag,
    },
}

/// A whole figure: its size, background and shapes, painted in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Width in pixels.
    pub width: f64,
    /// Height in pixels.
    pub height: f64,
    /// Background colour.
    pub background: Rgb,
    /// Shapes, back to front.
    pub shapes: Vec<Shape>,
}

impl Drawing {
    /// An empty drawing.
    #[must_use]
    pub fn new(width: f64, height: f64, background: Rgb) -> Self {
        Self {
            width,
            height,
            background,
            shapes: Vec::new(),
        }
    }

    /// Adds a line.
    pub fn line(&mut self, from: (f64, f64), to: (f64, f64), stroke: Stroke) {
        self.shapes.push(Shape::Line { from, to, stroke });
    }

    /// Adds a filled rectangle (opacity 0–1).
    pub fn rect(&mut self, at: (f64, f64), size: (f64, f64), fill: Rgb, opacity: f64) {
        self.shapes.push(Shape::Rect {
            at,
            size,
            fill: Some((fill, opacity)),
            stroke: None,
        });
    }

    /// Adds an outlined rectangle.
    pub fn frame(&mut self, at: (f64, f64), size: (f64, f64), stroke: Stroke) {
        self.shapes.push(Shape::Rect {
            at,
            size,
            fill: None,
            stroke: Some(stroke),
        });
    }

    /// Adds a circle.
    pub fn circle(
        &mut self,
        centre: (f64, f64),
        r: f64,
        fill: Option<Rgb>,
        stroke: Option<Stroke>,
    ) {
        self.shapes.push(Shape::Circle {
            centre,
            r,
            fill,
            stroke,
        });
    }

    /// Adds a filled polygon.
    pub fn polygon(&mut self, points: Vec<(f64, f64)>, fill: Rgb, opacity: f64) {
        self.shapes.push(Shape::Polygon {
            points,
            fill: (fill, opacity),
        });
    }

    /// Adds a line of plain text.
    pub fn text(
        &mut self,
        at: (f64, f64),
        text: impl Into<String>,
        size: f64,
        colour: Rgb,
        anchor: Anchor,
    ) {
        self.tagged_text(at, text, size, colour, anchor, Tag::default());
    }

    /// Adds a line of text readers can find by its tag.
    pub fn tagged_text(
        &mut self,
        at: (f64, f64),
        text: impl Into<String>,
        size: f64,
        colour: Rgb,
        anchor: Anchor,
        tag: Tag,
    ) {
        self.shapes.push(Shape::Text {
            at,
            text: text.into(),
            size,
            colour,
            anchor,
            tag,
        });
    }

    /// An arrow from `from` to `to` with a two-stroke head.
    pub fn arrow(&mut self, from: (f64, f64), to: (f64, f64), stroke: Stroke) {
        self.line(from, to, stroke);
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let len = dx.hypot(dy);
        if len < 1e-9 {
            return;
        }
        let (ux, uy) = (dx / len, dy / len);
        let head = (stroke.width * 4.0).max(7.0).min(len * 0.5);
        for s in [-1.0, 1.0] {
            let back = (
                to.0 - ux * head - uy * head * 0.5 * s,
                to.1 - uy * head + ux * head * 0.5 * s,
            );
            self.line(
                to,
                back,
                Stroke {
                    dashed: false,
                    ..stroke
                },
            );
        }
    }
}
