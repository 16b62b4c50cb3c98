//! The SSH world obeys the height rules: a player driven through the world task (the same
//! messages a session sends) walks a quarter step, climbs a half-wall ledge only by jumping,
//! and never climbs 0.51.

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::spawn_rounds;
use crate::game::multi::players::Rules;
use crate::game::multi::round::Mode;
use crate::game::{Action, Command, Held, Input, PLAYER_RADIUS};
use crate::map::parse_map;
use crate::play::world_port::{WorldHandle, WorldMsg};
use crate::world::{TextureSource, World};

/// A corridor east from the start: floor 0, a quarter step (a), a ledge 0.5 higher (c), and one
/// 0.51 higher again (d).
const ZONES: &str = "Ha 0.25 2\nHc 0.75 2\nHd 1.26 3\n";
const GRID: &str = "1111111111\n1E0aaccdd1\n1111111111\n";

/// A world from extra header lines and a grid, textures from the embedded set.
fn world(extra: &str, grid: &str) -> World {
    let text = format!("NO textures/bricks.png\nSO textures/bricks.png\nWE textures/stone.png\nEA textures/stone.png\nF 96,88,80\nC 150,146,136\n{extra}\n{grid}");
    let map = parse_map("test.cub", text.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    World::load(map, &TextureSource::Embedded, true).unwrap().0
}

const TICK_HZ: u32 = 60;

/// How long the player must stay put (on the ground) to count as stopped: longer than a jump.
const STILL: Duration = Duration::from_millis(700);

async fn send(world: &WorldHandle, held: &[Action], commands: Vec<Command>) {
    world
        .send(WorldMsg::Input {
            id: 1,
            input: Input {
                held: held.iter().copied().collect::<Held>(),
                commands,
            },
            view_width: 80,
            releases_known: false,
        })
        .await;
}

/// Waits until player 1 has not moved and stood on the ground for [`STILL`]; its x and floor.
async fn settle(world: &WorldHandle) -> (f64, f64) {
    let mut rx = world.snapshots();
    let start = Instant::now();
    let mut last: Option<(f64, Instant)> = None;
    loop {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "the player never stopped"
        );
        tokio::time::timeout(Duration::from_secs(2), rx.changed())
            .await
            .expect("a snapshot within 2 s")
            .expect("the world is running");
        let snap = rx.borrow_and_update().clone();
        let p = snap.player(1).expect("joined");
        let (x, grounded) = (p.state.camera.pos.x, p.state.jump == (0.0, 0.0));
        match last {
            Some((lx, since)) if lx == x && grounded => {
                if since.elapsed() >= STILL {
                    return (x, p.state.footing.floor);
                }
            }
            _ => last = Some((x, Instant::now())),
        }
    }
}

#[tokio::test]
async fn the_world_task_moves_players_by_the_same_height_rules() {
    let world = Arc::new(world(ZONES, GRID));
    let (handle, _phase) = spawn_rounds(
        vec![world],
        TICK_HZ,
        Rules::new(Mode::Coop, 0),
        |_| {},
        tokio::sync::watch::channel(false).1,
    );
    handle
        .send(WorldMsg::Join {
            id: 1,
            name: "ada".into(),
        })
        .await;
    let against = |edge: f64| edge - PLAYER_RADIUS;

    send(&handle, &[Action::Forward], vec![]).await;
    let (x, floor) = settle(&handle).await;
    assert!(
        (x - against(5.0)).abs() < 1e-6,
        "walked up 0.25, stopped at 0.5: {x}"
    );
    assert_eq!(floor, 0.25);

    send(&handle, &[Action::Forward], vec![Command::Jump]).await;
    let (x, floor) = settle(&handle).await;
    assert!(
        (x - against(7.0)).abs() < 1e-6,
        "jumped up 0.5, stopped at 0.51: {x}"
    );
    assert_eq!(floor, 0.75);

    send(&handle, &[Action::Forward], vec![Command::Jump]).await;
    let (x, floor) = settle(&handle).await;
    assert!(
        (x - against(7.0)).abs() < 1e-6,
        "a jump does not climb 0.51: {x}"
    );
    assert_eq!(floor, 0.75);
}
