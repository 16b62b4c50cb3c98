//! A recording on `maps/heights.cub`: up the stairs to the balcony, east along it and off its
//! edge into the hall. It replays byte for byte, and the floor under the player rises a quarter
//! at a time (`tests/heights_minimap_pty.rs` looks at its minimap on screen).

use crate::common;

use std::sync::Arc;

use common::{halfcast_ok, root};
use halfcast::replay::Replay;
use halfcast::ui::replay_player::Player;
use halfcast::World;

const FIXTURE: &str = "tests/fixtures/heights_stairs.hcr";

/// The frame the player has climbed all the stairs by (and stands still, facing north).
pub const ON_TOP: usize = 66;

fn replay() -> Replay {
    let text = std::fs::read_to_string(root().join(FIXTURE)).unwrap();
    Replay::parse(FIXTURE, &text).unwrap()
}

/// (x, y, floor stood on, the eye's ground, eye height) after every frame.
fn trail() -> Vec<(f64, f64, f64, f64, f64)> {
    let r = replay();
    let (world, _) = World::from_file(&root().join("maps/heights.cub"), true).unwrap();
    let mut player = Player::new(Arc::new(world), &r.header);
    r.frames
        .iter()
        .map(|input| {
            player.play(input).expect("no quit");
            let s = player.state();
            (
                s.camera.pos.x,
                s.camera.pos.y,
                s.footing.floor,
                s.view.ground,
                s.view.eye(),
            )
        })
        .collect()
}

#[test]
fn the_recording_climbs_the_stairs_a_quarter_at_a_time_and_drops_off_the_balcony() {
    let t = trail();
    let mut floors: Vec<f64> = Vec::new();
    for f in t[..=ON_TOP].iter().map(|f| f.2) {
        if floors.last() != Some(&f) {
            floors.push(f);
        }
    }
    assert_eq!(floors, [0.0, 0.25, 0.5, 0.75, 1.0]);
    // The eye rises smoothly (never down) on the way up and stands exactly on the balcony.
    assert!(t[..=ON_TOP].windows(2).all(|w| w[1].3 >= w[0].3));
    let top = t[ON_TOP];
    assert!(
        (top.1 - 1.2).abs() < 1e-6,
        "against the north wall: {top:?}"
    );
    assert_eq!((top.2, top.3, top.4), (1.0, 1.0, 1.5));
    // Then east along the balcony, off its edge at x = 6 into the hall (floor 0), to the wall.
    let end = *t.last().unwrap();
    assert!((end.0 - 10.8).abs() < 1e-6, "{end:?}");
    assert_eq!((end.2, end.3, end.4), (0.0, 0.0, 0.5));
}

#[test]
fn two_runs_write_the_same_bytes() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let last = replay().frames.len() - 1;
    for dir in [&a, &b] {
        halfcast_ok(&[
            "replay",
            FIXTURE,
            "--frames",
            &format!("0-{last}"),
            "--format",
            "ansi",
            "--out",
            dir.path().to_str().unwrap(),
        ]);
    }
    for i in 0..=last {
        let name = format!("frame-{i:05}.ansi");
        let read = |d: &tempfile::TempDir| std::fs::read(d.path().join(&name)).unwrap();
        assert!(read(&a) == read(&b), "{name} differs between runs");
    }
}
