//! The render stage of a frame: game state → 3D view pixels (no terminal involved).

use crate::color::Rgb;
use crate::game::GameState;
use crate::render::cast::Cast;
use crate::render::framebuffer::Framebuffer;
use crate::render::kept_background::KeptBackground;
use crate::render::scene::Scene;
use crate::widget::plot::mix;

/// Tint of the debugged column in the 3D view while the debugger is paused.
const MARK: Rgb = Rgb::new(255, 230, 60);

/// Renders the view into `fb` (sized by the caller to the view pane) and returns the rays,
/// with the debugged column traced; while paused that column is tinted so it can be found.
/// At a finer glyph setting the rays are one per pixel column (2 per cell).
pub fn render_view(state: &GameState, fb: &mut Framebuffer) -> Cast {
    render(state, fb, None)
}

/// [`render_view`] for a loop that renders one world frame after frame: the walls, floors and
/// ceilings are copied from `kept` when they would be the same as last frame's (the caller
/// forgets `kept` when its world is replaced).
pub(crate) fn render_view_kept(
    state: &GameState,
    fb: &mut Framebuffer,
    kept: &mut KeptBackground,
) -> Cast {
    render(state, fb, Some(kept))
}

fn render(state: &GameState, fb: &mut Framebuffer, kept: Option<&mut KeptBackground>) -> Cast {
    let column = state.debug_column();
    let sprites = state.level.sprites(&state.world);
    let lights = state.level.lights();
    let mut scene = Scene::new(&state.world, state.camera)
        .with_view(state.view)
        .with_doors(&state.doors)
        .with_sprites(&sprites)
        .with_lights(&lights)
        .at_time(state.time);
    scene.light.night = state.night;
    // At a sub-grid two pixels wide the debugged cell column traces its left sub-column (the
    // same ray: cameraX = 2·(2x)/(2W) − 1 = 2x/W − 1), and both sub-columns are tinted.
    let per_cell = fb.glyphs().cell_size().0;
    let traced = column * per_cell;
    let cast = match kept {
        Some(kept) => scene.render_frame_kept(fb, Some(traced), kept).cast,
        None => scene.render_into(fb, Some(traced)),
    };
    if state.debugger.paused && traced < fb.width() {
        for x in traced..(traced + per_cell).min(fb.width()) {
            for y in 0..fb.height() {
                let c = fb.get(x, y);
                fb.set(x, y, mix(c, MARK, 120));
            }
        }
    }
    cast
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::world::World;
    use std::sync::Arc;

    #[test]
    fn the_debugged_column_is_marked_only_while_paused() {
        let world = Arc::new(World::default_world());
        let cam = Camera::from_angle(world.map.start.pos(), 90.0, 66.0);
        let mut state = GameState::new(world, cam, 40);
        let mut plain = Framebuffer::for_cells(40, 10);
        let cast = render_view(&state, &mut plain);
        assert_eq!(cast.trace.as_ref().map(|t| t.column), Some(20));
        state.debugger.toggle_pause();
        let mut marked = Framebuffer::for_cells(40, 10);
        render_view(&state, &mut marked);
        for y in 0..20 {
            assert_eq!(plain.get(19, y), marked.get(19, y));
            assert_ne!(plain.get(20, y), marked.get(20, y));
        }
    }
}
