//! Replays of the game: a recording that walks over a treasure to the exit ends on the results
//! screen (in the library's frames and on a real terminal's screen) and is the same bytes on
//! every run; a replay with tag shots at a wandering creature is the same game for the same
//! header seed, and a different game for another.
#![cfg(unix)]

use crate::common;
use crate::pty_support;

use std::sync::Arc;

use common::{replay_cast, root};
use halfcast::replay::Replay;
use halfcast::ui::replay_player::{play_all, Frame, Player};
use halfcast::World;

const TO_EXIT: &str = "tests/fixtures/game_to_exit.hcr";

fn load(file: &str, text: &str) -> (Arc<World>, Replay) {
    let replay = Replay::parse(file, text).expect("valid replay");
    let map = match &replay.header.map {
        halfcast::replay::MapSource::File(p) => root().join(p),
        halfcast::replay::MapSource::Embedded => panic!("a game fixture names its map"),
    };
    let (world, _) = World::from_file(&map, true).expect("the fixture's map loads");
    (Arc::new(world), replay)
}

fn text_of(frame: &Frame) -> String {
    let a = frame.screen.area;
    (a.top()..a.bottom())
        .map(|y| {
            (a.left()..a.right())
                .map(|x| frame.screen[(x, y)].symbol().to_owned())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_fixture_walks_over_the_treasure_to_the_exit_and_shows_the_results() {
    let text = std::fs::read_to_string(root().join(TO_EXIT)).unwrap();
    let (world, replay) = load(TO_EXIT, &text);
    let mut player = Player::new(world, &replay.header);
    let mut finished_at = None;
    let mut last = None;
    for (i, input) in replay.frames.iter().enumerate() {
        last = Some(player.play(input).expect("no quit"));
        if finished_at.is_none() && player.state().level.finished().is_some() {
            finished_at = Some(i);
        }
    }
    let finished_at = finished_at.expect("the replay reaches the exit");
    assert!(
        finished_at < replay.frames.len() - 1,
        "the exit is reached before the end"
    );
    let state = player.state();
    assert_eq!(state.score.points, 10);
    assert_eq!(state.score.found, 1);
    // The world stops at the exit: the position after the last frame is the one at the exit.
    assert!(
        state.camera.pos.x >= 3.0 && state.camera.pos.x < 4.0,
        "{:?}",
        state.camera.pos
    );
    let screen = text_of(&last.unwrap());
    for want in [
        "Level complete!",
        "Points    10",
        "Treasures 1 of 1",
        "game_tiny_a.cub",
    ] {
        assert!(screen.contains(want), "{want:?} missing:\n{screen}");
    }
}

#[test]
fn the_fixture_ends_on_the_results_box_on_a_real_screen() {
    // `halfcast replay FILE` in a pseudo-terminal of the replay's size; its bytes up to where
    // it leaves the alternate screen, through a VT100 model.
    let mut run = pty_support::PtyRun::spawn(&["replay", TO_EXIT], (80, 24));
    assert!(run.wait_exit().success());
    let bytes = run.bytes();
    let end = pty_support::last_index(&bytes, pty_support::LEAVE_ALT_SCREEN)
        .expect("the session restored the terminal");
    let mut term = vt100::Parser::new(24, 80, 0);
    term.process(&bytes[..end]);
    let text = term.screen().contents();
    for want in ["Level complete!", "Points    10", "Treasures 1 of 1"] {
        assert!(text.contains(want), "{want:?} missing:\n{text}");
    }
    // The HUD under it agrees.
    assert!(text.contains("10 pts") && text.contains("0 left"), "{text}");
}

#[test]
fn the_fixture_replays_byte_for_byte() {
    let one = replay_cast(TO_EXIT, &[]);
    let two = replay_cast(TO_EXIT, &[]);
    assert!(
        one.contains("Level complete!"),
        "the cast never shows the results"
    );
    // The asciicast's timestamps come from the frame numbers, so whole files compare.
    assert_eq!(one, two);
}

/// A replay on the creature room (the creature's room walled off, so it wanders
/// by its seeded RNG rather than chasing): turning on the spot and firing a tag every 10 frames, with
/// the header's `seed`.
fn firing_replay(seed: u64) -> String {
    let mut s = format!(
        "{{\"halfcast_replay\":1,\"map\":\"tests/fixtures/game_creature_room.cub\",\
         \"start\":{{\"pos\":[1.5,1.5],\"angle\":0.0,\"fov\":66.0}},\"size\":[80,24],\
         \"fps\":30,\"seed\":{seed}}}\n{{\"frame\":0,\"held\":[\"turn_right\"]}}\n"
    );
    for f in (5..150).step_by(10) {
        s.push_str(&format!("{{\"frame\":{f},\"command\":\"fire\"}}\n"));
    }
    s.push_str("{\"end\":150}\n");
    s
}

/// Every frame's screen and the creature's position after it, and whether a shot flew.
fn run(seed: u64) -> (Vec<ratatui::buffer::Buffer>, Vec<(f64, f64)>, bool) {
    let text = firing_replay(seed);
    let (world, replay) = load("firing.hcr", &text);
    assert_eq!(replay.header.seed, seed);
    let mut screens = Vec::new();
    let mut trail = Vec::new();
    let mut shot = false;
    let mut player = Player::new(Arc::clone(&world), &replay.header);
    for input in &replay.frames {
        let frame = player.play(input).expect("no quit");
        screens.push(frame.screen);
        let level = &player.state().level;
        shot |= !level.projectiles().is_empty();
        let c = &level.creatures()[0];
        trail.push((c.pos.x, c.pos.y));
    }
    // play_all draws the same frames as stepping by hand.
    let mut again = Vec::new();
    play_all(world, &replay, |f| again.push(f.screen.clone()));
    assert_eq!(again, screens);
    (screens, trail, shot)
}

#[test]
fn a_firing_replay_with_a_creature_is_the_same_game_for_the_same_seed() {
    let (screens, trail, shot) = run(11);
    assert!(shot, "the fire commands never launched a tag");
    assert!(
        trail.first() != trail.last(),
        "the creature never moved: {:?}",
        trail.first()
    );
    let (screens2, trail2, _) = run(11);
    assert_eq!(trail, trail2);
    assert!(screens == screens2, "the same replay drew different frames");
    // The header's seed drives the creature: another seed walks it elsewhere.
    let (_, other, _) = run(12);
    assert_ne!(trail, other, "the header seed is not honoured");
}
