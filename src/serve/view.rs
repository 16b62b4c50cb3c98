//! What one session shows: the 3D view from a player's eyes, other players in it, a small
//! minimap, and a status line.
//!
//! STAND-IN for the panes of the TUI branch (`HalfBlockView`, `Minimap`, `DebugPane`) and the
//! sprite renderer of the world branch: when those merge, draw their widgets into the session's
//! area instead of the overlay and markers below. The seam is [`render_view`] +
//! [`status_line`]; everything else in the session is independent of how the view looks.

use crate::camera::{Camera, DEFAULT_FOV_DEG};
use crate::color::Rgb;
use crate::framebuffer::Framebuffer;
use crate::map::Cell;
use crate::scene::Scene;
use crate::world::World;

use super::player::PLAYER_RADIUS;
use super::players::{PlayerId, PlayerView, Snapshot};

/// How tall a player marker stands, in wall heights.
const MARKER_HEIGHT: f64 = 0.7;

/// Renders `eye`'s view of the world into `fb` (at its size). Returns false if `eye` is gone.
pub fn render_view(world: &World, snap: &Snapshot, eye: PlayerId, fb: &mut Framebuffer) -> bool {
    let Some(me) = snap.player(eye) else {
        return false;
    };
    let camera = Camera::from_angle(me.pose.pos, me.pose.angle_deg, DEFAULT_FOV_DEG);
    let cast = Scene::new(world, camera).render_into(fb, None);
    let depth: Vec<f64> = cast.columns.iter().map(|c| c.perp_dist).collect();
    let mut others: Vec<&PlayerView> = snap.players.iter().filter(|p| p.id != eye).collect();
    // Far to near, so nearer markers cover farther ones.
    others.sort_by(|a, b| {
        let da = (a.pose.pos - me.pose.pos).length();
        let db = (b.pose.pos - me.pose.pos).length();
        db.total_cmp(&da)
    });
    for p in others {
        draw_marker(fb, &camera, &depth, p);
    }
    draw_minimap(fb, world, snap, eye);
    true
}

/// A player as an upright box of its colour, hidden behind nearer walls.
fn draw_marker(fb: &mut Framebuffer, camera: &Camera, depth: &[f64], p: &PlayerView) {
    let (w, h) = (fb.width(), fb.height());
    if w == 0 || h == 0 {
        return;
    }
    // Solve rel = a·plane + b·dir: b is the depth, a/b the screen position.
    let rel = p.pose.pos - camera.pos;
    let (dir, plane) = (camera.dir, camera.plane);
    let det = plane.x * dir.y - dir.x * plane.y;
    if det.abs() < 1e-12 {
        return;
    }
    let a = (rel.x * dir.y - dir.x * rel.y) / det;
    let b = (plane.x * rel.y - rel.x * plane.y) / det;
    if b < 0.1 {
        return;
    }
    let focal = camera.focal_length(w);
    let centre = w as f64 / 2.0 * (1.0 + a / b);
    let half_w = PLAYER_RADIUS * focal / b;
    let scale = focal / b;
    let floor = h as f64 / 2.0 + scale * 0.5;
    let top = floor - scale * MARKER_HEIGHT;
    let shade = (256.0 / (1.0 + b * 0.15)).clamp(48.0, 256.0) as u16;
    let body = p.color.scaled(shade);
    let head = Rgb::new(240, 240, 240).scaled(shade);
    let x0 = (centre - half_w).floor().max(0.0) as usize;
    let x1 = ((centre + half_w).ceil().max(0.0) as usize).min(w);
    let y0 = top.round().max(0.0) as usize;
    let y1 = (floor.round().max(0.0) as usize).min(h);
    let head_end = top + (floor - top) * 0.2;
    for x in x0..x1 {
        if depth.get(x).is_some_and(|&d| d < b) {
            continue;
        }
        for y in y0..y1 {
            fb.set(x, y, if (y as f64) < head_end { head } else { body });
        }
    }
}

/// A top-down map of the area around `eye` in the top-right corner: walls, floor, players.
fn draw_minimap(fb: &mut Framebuffer, world: &World, snap: &Snapshot, eye: PlayerId) {
    let Some(me) = snap.player(eye) else {
        return;
    };
    let side = (fb.width() / 4).min(fb.height() / 2).min(48);
    // Two pixels per map cell when there is room, else one.
    let k = if side >= 24 { 2 } else { 1 };
    let cells = side / k;
    if cells < 5 {
        return;
    }
    let x_off = fb.width() - cells * k;
    let (ci, cj) = (me.pose.pos.x.floor() as i64, me.pose.pos.y.floor() as i64);
    let half = (cells / 2) as i64;
    let map = &world.map;
    for dj in 0..cells {
        for di in 0..cells {
            let (i, j) = (ci - half + di as i64, cj - half + dj as i64);
            let c = match map.cell(i, j) {
                Cell::Wall(_) => Rgb::new(150, 150, 160),
                Cell::Floor { .. } => Rgb::new(30, 30, 36),
                Cell::Void => Rgb::new(0, 0, 0),
                Cell::Door(_) => Rgb::new(196, 140, 60),
            };
            fill(fb, x_off + di * k, dj * k, k, c);
        }
    }
    for p in &snap.players {
        let (di, dj) = (
            p.pose.pos.x.floor() as i64 - ci + half,
            p.pose.pos.y.floor() as i64 - cj + half,
        );
        if di < 0 || dj < 0 || di >= cells as i64 || dj >= cells as i64 {
            continue;
        }
        let c = if p.id == eye {
            Rgb::new(255, 255, 255)
        } else {
            p.color
        };
        fill(fb, x_off + di as usize * k, dj as usize * k, k, c);
    }
}

fn fill(fb: &mut Framebuffer, x: usize, y: usize, k: usize, c: Rgb) {
    for yy in y..(y + k).min(fb.height()) {
        for xx in x..(x + k).min(fb.width()) {
            fb.set(xx, yy, c);
        }
    }
}

/// The bottom line: who you are (or whom you watch), who is here, the keys. Cut to `cols`.
#[must_use]
pub fn status_line(
    snap: &Snapshot,
    eye: Option<PlayerId>,
    spectating: bool,
    extra: &str,
    cols: u16,
) -> String {
    let names: Vec<&str> = snap.players.iter().map(|p| p.name.as_str()).collect();
    let who = match (eye.and_then(|e| snap.player(e)), spectating) {
        (Some(p), true) => format!("watching {} (Tab: next)", p.name),
        (None, true) => "waiting for players (Tab: next)".to_string(),
        (Some(p), false) => format!("you are {}", p.name),
        (None, false) => "joining…".to_string(),
    };
    let keys = if spectating {
        "c colours · Esc quit"
    } else {
        "WASD/arrows move · q/e strafe · c colours · Esc quit"
    };
    let line = format!(
        " halfcast · {who} · {} here: {} · {extra} · {keys}",
        names.len(),
        names.join(", ")
    );
    line.chars().take(usize::from(cols)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::serve::players::Players;

    #[test]
    fn each_player_sees_the_other_in_the_minimap_and_the_status_line() {
        let world = World::default_world();
        let mut ps = Players::new();
        ps.join(&world.map, 1, "ann");
        ps.join(&world.map, 2, "bob");
        let snap = ps.snapshot();
        let bob_colour = snap.player(2).expect("bob").color;
        let mut fb = Framebuffer::for_cells(120, 40);
        assert!(render_view(&world, &snap, 1, &mut fb));
        assert!(
            fb.pixels().contains(&bob_colour),
            "bob shows on ann's minimap"
        );
        assert!(status_line(&snap, Some(1), false, "truecolor", 200).contains("ann, bob"));
        assert!(!render_view(&world, &snap, 3, &mut fb));
    }

    #[test]
    fn tiny_and_huge_views_do_not_panic() {
        let world = World::default_world();
        let mut ps = Players::new();
        ps.join(&world.map, 1, "ann");
        ps.join(&world.map, 2, "bob");
        let snap = ps.snapshot();
        for (c, r) in [(1, 1), (2, 1), (5, 3), (500, 200)] {
            let mut fb = Framebuffer::for_cells(c, r);
            render_view(&world, &snap, 2, &mut fb);
        }
        assert_eq!(status_line(&snap, Some(1), true, "", 3).chars().count(), 3);
    }
}
