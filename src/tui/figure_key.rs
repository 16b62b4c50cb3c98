//! The figure key: writes the debugged column's traversal as an SVG figure (the same drawing
//! `halfcast trace` makes) into a folder (the game's current one), under a name not yet taken. Local play
//! only: over SSH the key does nothing, since the file would land on the server.

use std::path::{Path, PathBuf};

use crate::game::GameState;
use crate::output::figure::ColumnCast;

/// Most numbered names tried before giving up (`halfcast-ray-col40-99.svg`).
const MAX_TRIES: usize = 100;

/// Writes the figure of `state`'s debugged column, for a view of `view` cells (columns, rows),
/// into `dir`, and returns the file's path.
///
/// # Errors
/// The file could not be created (the message says why).
pub fn write_figure(state: &GameState, view: (u16, u16), dir: &Path) -> Result<PathBuf, String> {
    let (cols, rows) = (usize::from(view.0), usize::from(view.1));
    let column = state.debug_column();
    let map = &state.world.map;
    let cast = ColumnCast::new(
        map,
        &state.doors,
        &state.camera,
        &state.view,
        (cols, rows),
        column,
    );
    let svg = cast.figure(map, &state.camera, cols).to_svg();
    for k in 0..MAX_TRIES {
        let name = if k == 0 {
            format!("halfcast-ray-col{column}.svg")
        } else {
            format!("halfcast-ray-col{column}-{k}.svg")
        };
        let path = dir.join(&name);
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
        {
            Ok(mut f) => {
                use std::io::Write;
                f.write_all(svg.as_bytes())
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                return Ok(path);
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(format!("{}: {e}", path.display())),
        }
    }
    Err(format!(
        "{MAX_TRIES} figures of column {column} are already in {}",
        dir.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::world::World;
    use std::sync::Arc;

    #[test]
    fn the_figure_is_written_under_a_fresh_name_each_time() {
        let dir = tempfile::tempdir().unwrap();
        let world = Arc::new(World::default_world());
        let cam = Camera::from_angle(world.map.start.pos(), 90.0, 66.0);
        let state = GameState::new(world, cam, 50);
        let first = write_figure(&state, (50, 23), dir.path());
        let second = write_figure(&state, (50, 23), dir.path());
        assert_eq!(first.unwrap(), dir.path().join("halfcast-ray-col25.svg"));
        assert_eq!(second.unwrap(), dir.path().join("halfcast-ray-col25-1.svg"));
        let svg = std::fs::read_to_string(dir.path().join("halfcast-ray-col25.svg")).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("column 25 of 50"));
    }
}
