//! Where each pane goes for a terminal size: pure arithmetic on rectangles, tested at many sizes.

use ratatui::layout::Rect;

/// Smallest terminal the game draws in; below it a short message is shown instead.
pub const MIN_SIZE: (u16, u16) = (20, 8);

/// Narrowest terminal that gets the side panel beside the view.
const BESIDE_MIN_WIDTH: u16 = 100;

/// Narrowest terminal that gets the panes stacked under the view.
const STACK_MIN_WIDTH: u16 = 60;

/// Shortest terminal that gets the panes stacked under the view.
const STACK_MIN_HEIGHT: u16 = 30;

/// Narrowest terminal that gets the compact panes (a narrower view, a small minimap and the
/// last few DDA rows) beside the view, as at 80×24.
pub const COMPACT_MIN_WIDTH: u16 = 60;

/// Shortest body (terminal minus the status line) with room for both compact panes; below it
/// only one fits.
const COMPACT_BOTH_MIN_HEIGHT: u16 = 12;

/// Shortest body with room for one compact pane.
const COMPACT_ONE_MIN_HEIGHT: u16 = 6;

/// Which optional panes the player wants shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Toggles {
    pub minimap: bool,
    pub debug: bool,
    pub help: bool,
}

impl Default for Toggles {
    fn default() -> Self {
        Self {
            minimap: true,
            debug: true,
            help: false,
        }
    }
}

/// The rectangles of one frame; panes that do not fit are `None`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Panes {
    /// The terminal is below [`MIN_SIZE`]: only a message, in the whole area.
    TooSmall(Rect),
    Game {
        view: Rect,
        minimap: Option<Rect>,
        debug: Option<Rect>,
        status: Rect,
    },
}

impl Panes {
    /// Lays out `area`: the 3D view gets the most room; the side panes go beside it on wide
    /// terminals, under it on tall narrow ones, and away when there is no room.
    #[must_use]
    pub fn compute(area: Rect, toggles: Toggles) -> Self {
        if area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1 {
            return Self::TooSmall(area);
        }
        let status = Rect::new(area.x, area.bottom() - 1, area.width, 1);
        let body = Rect::new(area.x, area.y, area.width, area.height - 1);
        let wanted = toggles.minimap || toggles.debug;
        let (view, side) = if !wanted {
            (body, None)
        } else if body.width >= BESIDE_MIN_WIDTH {
            beside(body, (body.width * 3 / 10).clamp(46, 66))
        } else if body.width >= STACK_MIN_WIDTH && body.height >= STACK_MIN_HEIGHT {
            let strip = (body.height * 2 / 5).clamp(12, 22);
            let view_h = body.height - strip;
            (
                Rect::new(body.x, body.y, body.width, view_h),
                Some(Side::Below(Rect::new(
                    body.x,
                    body.y + view_h,
                    body.width,
                    strip,
                ))),
            )
        } else if body.width >= COMPACT_MIN_WIDTH && body.height >= COMPACT_ONE_MIN_HEIGHT {
            beside(body, (body.width * 3 / 8).clamp(24, 34))
        } else {
            (body, None)
        };
        let mut toggles = toggles;
        if toggles.minimap && toggles.debug && body.height < COMPACT_BOTH_MIN_HEIGHT {
            // Room for one pane only: the minimap.
            toggles.debug = false;
        }
        let (minimap, debug) = match side {
            None => (None, None),
            Some(side) => side.split(toggles),
        };
        Self::Game {
            view,
            minimap,
            debug,
            status,
        }
    }
}

impl Panes {
    /// The panes the player wants that did not fit (named as in the help), to say so.
    #[must_use]
    pub fn hidden(&self, toggles: Toggles) -> Vec<&'static str> {
        let (minimap, debug) = match self {
            Panes::TooSmall(_) => (None, None),
            Panes::Game { minimap, debug, .. } => (*minimap, *debug),
        };
        let mut out = Vec::new();
        if toggles.minimap && minimap.is_none() {
            out.push("minimap");
        }
        if toggles.debug && debug.is_none() {
            out.push("ray pane");
        }
        out
    }
}

/// Where the side panes live.
enum Side {
    Right(Rect),
    Below(Rect),
}

impl Side {
    fn split(self, t: Toggles) -> (Option<Rect>, Option<Rect>) {
        let (r, stacked_vertically) = match self {
            Side::Right(r) => (r, true),
            Side::Below(r) => (r, false),
        };
        match (t.minimap, t.debug) {
            (true, true) if stacked_vertically => {
                // A roughly square map on top, the (taller) step list below.
                let map_h = (r.height * 9 / 20)
                    .clamp(6, (r.width / 2 + 2).max(6))
                    .min(r.height - 5);
                let (a, b) = split_v(r, map_h);
                (Some(a), Some(b))
            }
            (true, true) => {
                let map_w = (r.width * 2 / 5)
                    .max(r.width.saturating_sub(48))
                    .min(r.width);
                let (a, b) = split_h(r, map_w);
                (Some(a), Some(b))
            }
            (true, false) => (Some(r), None),
            (false, true) => (None, Some(r)),
            (false, false) => (None, None),
        }
    }
}

fn split_v(r: Rect, top: u16) -> (Rect, Rect) {
    (
        Rect::new(r.x, r.y, r.width, top),
        Rect::new(r.x, r.y + top, r.width, r.height - top),
    )
}

fn split_h(r: Rect, left: u16) -> (Rect, Rect) {
    (
        Rect::new(r.x, r.y, left, r.height),
        Rect::new(r.x + left, r.y, r.width - left, r.height),
    )
}

/// Splits `body` into the view on the left and a side column `side_w` wide on the right.
fn beside(body: Rect, side_w: u16) -> (Rect, Option<Side>) {
    let view_w = body.width - side_w;
    (
        Rect::new(body.x, body.y, view_w, body.height),
        Some(Side::Right(Rect::new(
            body.x + view_w,
            body.y,
            side_w,
            body.height,
        ))),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inside(r: Rect, area: Rect) -> bool {
        r.x >= area.x && r.y >= area.y && r.right() <= area.right() && r.bottom() <= area.bottom()
    }

    #[test]
    fn every_size_gives_rectangles_inside_the_area_that_do_not_overlap() {
        let all = [
            Toggles::default(),
            Toggles {
                minimap: false,
                ..Toggles::default()
            },
            Toggles {
                debug: false,
                ..Toggles::default()
            },
            Toggles {
                minimap: false,
                debug: false,
                help: true,
            },
        ];
        for w in (0..=520)
            .step_by(7)
            .chain([1, 19, 20, 59, 60, 99, 100, 500])
        {
            for h in (0..=210).step_by(5).chain([1, 7, 8, 29, 30, 200]) {
                for t in all {
                    let area = Rect::new(3, 2, w, h);
                    match Panes::compute(area, t) {
                        Panes::TooSmall(_) => assert!(w < 20 || h < 8, "{w}x{h}"),
                        Panes::Game {
                            view,
                            minimap,
                            debug,
                            status,
                        } => {
                            let rects: Vec<Rect> = [Some(view), minimap, debug, Some(status)]
                                .into_iter()
                                .flatten()
                                .collect();
                            for (i, a) in rects.iter().enumerate() {
                                assert!(inside(*a, area), "{w}x{h} {a:?}");
                                for b in &rects[i + 1..] {
                                    assert!(!a.intersects(*b), "{w}x{h} {a:?} {b:?}");
                                }
                            }
                            assert!(view.width >= 20 && view.height >= 4, "{w}x{h} {view:?}");
                            assert_eq!(minimap.is_some() && t.minimap, minimap.is_some());
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn at_80x24_both_panes_fit_beside_a_narrower_view() {
        let t = Toggles::default();
        let panes = Panes::compute(Rect::new(0, 0, 80, 24), t);
        let Panes::Game {
            view,
            minimap,
            debug,
            ..
        } = panes
        else {
            panic!()
        };
        assert_eq!(view, Rect::new(0, 0, 50, 23));
        let (m, d) = (minimap.unwrap(), debug.unwrap());
        assert_eq!((m.x, m.width, d.x, d.width), (50, 30, 50, 30));
        assert!(m.height >= 6 && d.height >= 5, "{m:?} {d:?}");
        assert!(panes.hidden(t).is_empty());
        // Too short for both: the minimap stays, the ray pane is named as hidden.
        let short = Panes::compute(Rect::new(0, 0, 80, 10), t);
        assert_eq!(short.hidden(t), vec!["ray pane"]);
        let narrow = Panes::compute(Rect::new(0, 0, 59, 24), t);
        assert_eq!(narrow.hidden(t), vec!["minimap", "ray pane"]);
        let only_ray = Toggles {
            minimap: false,
            ..t
        };
        assert!(Panes::compute(Rect::new(0, 0, 80, 10), only_ray)
            .hidden(only_ray)
            .is_empty());
    }

    #[test]
    fn wide_terminals_put_the_panes_beside_the_view() {
        let Panes::Game {
            view,
            minimap,
            debug,
            status,
        } = Panes::compute(Rect::new(0, 0, 160, 48), Toggles::default())
        else {
            panic!("too small?")
        };
        assert_eq!(status, Rect::new(0, 47, 160, 1));
        assert_eq!(view, Rect::new(0, 0, 112, 47));
        let (m, d) = (minimap.unwrap(), debug.unwrap());
        assert_eq!((m.x, d.x, m.width), (112, 112, 48));
        assert!(d.height >= 20, "{d:?}");
    }

    #[test]
    fn tall_narrow_terminals_stack_and_small_ones_hide() {
        let Panes::Game { view, minimap, .. } =
            Panes::compute(Rect::new(0, 0, 80, 40), Toggles::default())
        else {
            panic!()
        };
        assert_eq!(view.width, 80);
        assert_eq!(minimap.unwrap().y, view.bottom());
        let Panes::Game {
            view,
            minimap,
            debug,
            ..
        } = Panes::compute(Rect::new(0, 0, 40, 24), Toggles::default())
        else {
            panic!()
        };
        assert_eq!(view, Rect::new(0, 0, 40, 23));
        assert!(minimap.is_none() && debug.is_none());
        assert_eq!(
            Panes::compute(Rect::new(0, 0, 19, 30), Toggles::default()),
            Panes::TooSmall(Rect::new(0, 0, 19, 30))
        );
    }
}
