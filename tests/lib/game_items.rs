//! The game's items, keys, locked doors and exit, driven as a player would: a map's text →
//! World → GameState → step.

use crate::world_common;

use std::sync::Arc;

use halfcast::game::{step, Command, Event, GameState, Held, Input, Level, Player, Score};
use halfcast::{Camera, Vec2};
use world_common::world;

/// Start (1,1) facing east; a red-locked door at (3,1), the exit at (5,1), the red key at
/// (1.5, 2.5) in the alcove below the start, a treasure at (2.5, 1.5) on the way.
const GRID: &str = "1111111\n1E0D001\n1011111\n1111111\n";
const LINES: &str =
    "ITEM 2.5,1.5 barrel points=15\nITEM 1.5,2.5 lamp key=red\nDOORLOCK 3,1 red\nEXIT 5,1\n";

fn state_at(pos: (f64, f64), angle: f64) -> GameState {
    let w = Arc::new(world(LINES, GRID));
    GameState::new(
        w,
        Camera::from_angle(Vec2::new(pos.0, pos.1), angle, 66.0),
        80,
    )
}

fn tick(s: &mut GameState, commands: Vec<Command>, held: Held) {
    step(s, &Input { held, commands }, 1.0 / 30.0);
}

fn wait(s: &mut GameState, seconds: f64) {
    for _ in 0..(seconds * 30.0) as usize {
        tick(s, vec![], Held::default());
    }
}

#[test]
fn a_treasure_is_picked_up_once_by_the_first_to_reach_it() {
    let w = world(LINES, GRID);
    let mut level = Level::new(&w.map, 1);
    assert_eq!(
        (
            level.items_total(),
            level.treasures_total(),
            level.items_left()
        ),
        (2, 1, 2)
    );
    let (mut a, mut b) = (Score::default(), Score::default());
    let on_it = Vec2::new(2.5, 1.5);
    for _ in 0..3 {
        let mut players = [
            Player {
                pos: on_it,
                eye: 0.5,
                score: &mut a,
            },
            Player {
                pos: on_it,
                eye: 0.5,
                score: &mut b,
            },
        ];
        level.tick(
            &w.map,
            &halfcast::world::door::DoorState::new(&w.map),
            &mut players,
            0.1,
        );
    }
    assert_eq!((a.points, a.found), (15, 1));
    assert_eq!((b.points, b.found), (0, 0));
    assert_eq!(level.items_left(), 1);
}

#[test]
fn walking_over_a_treasure_scores_it_and_says_so() {
    let mut s = state_at((1.5, 1.5), 0.0);
    // Two items and the exit's arch.
    assert_eq!(s.level.sprites(&s.world).len(), 3);
    for _ in 0..10 {
        tick(
            &mut s,
            vec![],
            [halfcast::game::Action::Forward].into_iter().collect(),
        );
    }
    assert_eq!((s.score.points, s.score.found), (15, 1));
    assert_eq!(
        s.message.as_ref().map(|m| m.text.as_str()),
        Some("Treasure! +15 points")
    );
    assert_eq!(s.level.items_left(), 1);
    assert_eq!(
        s.level.sprites(&s.world).len(),
        2,
        "the taken item is no longer drawn"
    );
}

#[test]
fn a_locked_door_stays_shut_without_its_key_and_opens_with_it() {
    let mut s = state_at((2.5, 1.5), 0.0);
    // The first step picks up the treasure standing here.
    tick(&mut s, vec![], Held::default());
    tick(&mut s, vec![Command::UseDoor], Held::default());
    assert_eq!(
        s.events,
        [Event::Locked {
            player: 0,
            key: "red".into()
        }]
    );
    assert_eq!(
        s.message.as_ref().map(|m| m.text.as_str()),
        Some("Locked: needs the red key")
    );
    wait(&mut s, 1.5);
    assert_eq!(s.doors.open_amount((3, 1)), 0.0, "opened without the key");
    // Fetch the key from the alcove, come back, and try again.
    s.camera.pos = Vec2::new(1.5, 2.5);
    tick(&mut s, vec![], Held::default());
    assert!(s.score.has_key("red"));
    assert_eq!(
        s.message.as_ref().map(|m| m.text.as_str()),
        Some("You found the red key")
    );
    s.camera.pos = Vec2::new(2.5, 1.5);
    tick(&mut s, vec![Command::UseDoor], Held::default());
    wait(&mut s, 1.5);
    assert_eq!(s.doors.open_amount((3, 1)), 1.0);
}

#[test]
fn reaching_the_exit_ends_the_level() {
    let mut s = state_at((2.5, 1.5), 0.0);
    s.score.keys.insert("red".into());
    tick(&mut s, vec![Command::UseDoor], Held::default());
    wait(&mut s, 1.2);
    assert_eq!(s.level.finished(), None);
    let mut exited = false;
    for _ in 0..60 {
        tick(
            &mut s,
            vec![],
            [halfcast::game::Action::Forward].into_iter().collect(),
        );
        exited |= s.events.contains(&Event::Exit { player: 0 });
    }
    assert!(exited);
    assert_eq!(s.level.finished(), Some(0));
    assert_eq!(
        s.message.as_ref().map(|m| m.text.as_str()),
        Some("You reached the exit!")
    );
}

#[test]
fn shared_steps_respect_locks_but_leave_the_level_alone() {
    let mut s = state_at((2.5, 1.5), 0.0);
    let input = Input {
        held: Held::default(),
        commands: vec![Command::UseDoor],
    };
    halfcast::game::step_shared(&mut s, &input, 1.0 / 30.0, &[]);
    assert_eq!(s.events.len(), 1);
    assert_eq!(s.level.time(), 0.0);
    // A shot is handed to the shared world instead of flying in this player's copy.
    let fire = Input {
        held: Held::default(),
        commands: vec![Command::Fire],
    };
    halfcast::game::step_shared(&mut s, &fire, 1.0 / 30.0, &[]);
    assert_eq!(
        s.shots,
        [halfcast::game::Shot {
            from: s.camera.pos,
            z: s.view.eye(),
            dir: s.camera.dir
        }]
    );
    assert!(s.level.projectiles().is_empty());
    halfcast::game::step_shared(&mut s, &Input::default(), 1.0 / 30.0, &[]);
    assert!(s.shots.is_empty());
}

#[test]
fn a_tag_shot_is_recorded_in_replays_as_fire() {
    use halfcast::replay::{FrameInput, Header, MapSource};
    use halfcast::Replay;
    let replay = Replay {
        header: Header {
            map: MapSource::Embedded,
            pos: Vec2::new(1.5, 1.5),
            angle_deg: 0.0,
            fov_deg: 66.0,
            size: (80, 24),
            fps: 30,
            seed: 7,
            speeds: halfcast::game::Speeds::default(),
            glyphs: halfcast::Glyphs::Half,
        },
        frames: vec![
            FrameInput::default(),
            FrameInput {
                input: Input {
                    held: Held::default(),
                    commands: vec![Command::Fire],
                },
                ..FrameInput::default()
            },
        ],
    };
    let text = replay.to_jsonl();
    assert!(text.contains(r#"{"frame":1,"command":"fire"}"#), "{text}");
    assert_eq!(Replay::parse("r.hcr", &text).unwrap(), replay);
}
