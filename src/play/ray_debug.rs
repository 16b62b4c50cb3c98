//! A browser page's click on its 3D view: that column's ray becomes this player's debugged one
//! (its view freezes, as pausing does in a terminal, while the world goes on), and once the world
//! shows it so, the page is told the ray in `halfcast trace`'s terms, to draw and step itself.

use crate::game::multi::players::{PlayerId, Snapshot};
use crate::game::{Command, Debugger};

use super::sink::RayQuery;

/// The column a player asked to debug, until the world shows it debugged.
#[derive(Debug, Default)]
pub(super) struct RayDebug {
    wanted: Option<usize>,
}

impl RayDebug {
    /// The world commands that debug `column` of a view `width` columns wide (pausing first), or
    /// leave the debugger (`None`), for a player whose debugger is as `snap` shows it.
    pub fn ask(
        &mut self,
        column: Option<u32>,
        (snap, me): (&Snapshot, PlayerId),
        width: usize,
    ) -> Vec<Command> {
        // Not in a snapshot yet (the click came before the world's first tick with us): the
        // debugger is as it starts.
        let fresh = Debugger::default();
        let d = snap.player(me).map_or(&fresh, |p| &p.state.debugger);
        let Some(column) = column else {
            self.wanted = None;
            return if d.paused {
                vec![Command::TogglePause]
            } else {
                Vec::new()
            };
        };
        let column = (column as usize).min(width.saturating_sub(1));
        self.wanted = Some(column);
        let mut out = Vec::new();
        if !d.paused {
            out.push(Command::TogglePause);
        }
        let by = column as i64 - d.column_in(width) as i64;
        if by != 0 {
            out.push(Command::MoveColumn(i32::try_from(by).unwrap_or(0)));
        }
        out
    }

    /// The asked ray, once `snap` shows the player paused on it, for a 3D view of `size` cells.
    pub fn ready(
        &mut self,
        (snap, me): (&Snapshot, PlayerId),
        size: (u16, u16),
    ) -> Option<RayQuery> {
        let column = self.wanted?;
        let state = &snap.player(me)?.state;
        let d = &state.debugger;
        if !d.paused || d.column_in(usize::from(size.0)) != column {
            return None;
        }
        self.wanted = None;
        let cam = &state.camera;
        Some(RayQuery {
            pos: (cam.pos.x, cam.pos.y),
            angle: (-cam.dir.y).atan2(cam.dir.x).to_degrees(),
            column,
            size,
            fov: cam.fov_deg(),
            map: snap.map,
        })
    }
}
