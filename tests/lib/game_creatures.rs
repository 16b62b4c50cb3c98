//! Creatures, sight and tag shots, driven through the library as a game would: whole games
//! through `GameState` for catches, tags and determinism. (The properties on random maps,
//! creatures never inside walls and sight = the renderer's DDA, are unit tests in
//! `src/game/random_grid_props.rs`.)

use crate::world_common;

use std::sync::Arc;

use halfcast::game::{step, Action, Command, Event, GameState, Held, Input, Level, Player, Score};
use halfcast::world::door::DoorState;
use halfcast::{Camera, Vec2};
use world_common::world;

/// A corridor: start (1,1) facing east, open floor to (8,1).
const CORRIDOR: &str = "1111111111\n1E00000001\n1111111111\n";

fn game(lines: &str, grid: &str, pos: (f64, f64), angle: f64, seed: u64) -> GameState {
    let w = Arc::new(world(lines, grid));
    GameState::with_seed(
        w,
        Camera::from_angle(Vec2::new(pos.0, pos.1), angle, 66.0),
        80,
        seed,
    )
}

fn run(s: &mut GameState, seconds: f64, input: &Input) -> Vec<Event> {
    let mut events = Vec::new();
    for _ in 0..(seconds * 30.0).round() as usize {
        step(s, input, 1.0 / 30.0);
        events.extend(s.events.iter().cloned());
    }
    events
}

#[test]
fn a_chaser_catches_the_player_costs_points_and_backs_off() {
    let mut s = game(
        "CREATURE 6.5,1.5 creature behaviour=chase\n",
        CORRIDOR,
        (1.5, 1.5),
        0.0,
        1,
    );
    s.score.points = 40;
    let events = run(&mut s, 4.0, &Input::default());
    let caught: Vec<&Event> = events
        .iter()
        .filter(|e| matches!(e, Event::Caught { .. }))
        .collect();
    assert_eq!(
        caught,
        [&Event::Caught {
            player: 0,
            lost: 25
        }],
        "{events:?}"
    );
    assert_eq!(s.score.points, 15);
    let c = &s.level.creatures()[0];
    assert!(c.backing_off > 0.0 || (c.pos - s.camera.pos).length() > 0.45);
    // Caught again later: the score stops at 0.
    let events = run(&mut s, 8.0, &Input::default());
    assert!(
        events.contains(&Event::Caught {
            player: 0,
            lost: 15
        }),
        "{events:?}"
    );
    assert_eq!(s.score.points, 0);
}

#[test]
fn a_tag_shot_stops_at_walls_and_takes_a_creature_out() {
    // Facing a wall two cells away: the shot lights up, flies and is gone within a second.
    let mut s = game("", CORRIDOR, (7.5, 1.5), 0.0, 1);
    step(
        &mut s,
        &Input {
            held: Held::default(),
            commands: vec![Command::Fire],
        },
        1.0 / 30.0,
    );
    assert_eq!(s.level.projectiles().len(), 1);
    assert_eq!(s.level.lights().len(), 1);
    let mut furthest: f64 = 0.0;
    for _ in 0..30 {
        furthest = s
            .level
            .projectiles()
            .iter()
            .map(|p| p.pos.x)
            .fold(furthest, f64::max);
        step(&mut s, &Input::default(), 1.0 / 30.0);
    }
    assert!(s.level.projectiles().is_empty());
    assert!(furthest <= 9.0, "flew into the wall: {furthest}");
    // A creature patrolling ahead is tagged, frozen and harmless for a while.
    let mut s = game(
        "CREATURE 5.5,1.5 creature behaviour=patrol speed=0.5\n",
        CORRIDOR,
        (1.5, 1.5),
        0.0,
        1,
    );
    let fire = Input {
        held: Held::default(),
        commands: vec![Command::Fire],
    };
    step(&mut s, &fire, 1.0 / 30.0);
    let events = run(&mut s, 1.0, &Input::default());
    assert!(events.contains(&Event::Tagged { player: 0 }), "{events:?}");
    let c = s.level.creatures()[0].clone();
    assert!(c.is_out() && !c.can_catch());
    run(&mut s, 2.0, &Input::default());
    assert_eq!(
        s.level.creatures()[0].pos,
        c.pos,
        "a tagged creature stays put"
    );
    assert_eq!(
        s.message.as_ref().map(|m| m.text.as_str()),
        Some("Tagged a creature! It is out for a while")
    );
}

#[test]
fn the_debugger_pause_freezes_creatures_and_shots() {
    let mut s = game(
        "CREATURE 5.5,1.5 creature behaviour=wander\n",
        CORRIDOR,
        (1.5, 1.5),
        0.0,
        1,
    );
    step(
        &mut s,
        &Input {
            held: Held::default(),
            commands: vec![Command::Fire],
        },
        1.0 / 30.0,
    );
    step(
        &mut s,
        &Input {
            held: Held::default(),
            commands: vec![Command::TogglePause],
        },
        1.0 / 30.0,
    );
    let before = s.level.clone();
    run(&mut s, 1.0, &Input::default());
    assert_eq!(s.level, before);
}

/// A hall with four wanderers and a pillar, and the player shut in a cubby of its own (so the
/// creatures never see them and their walks are the dice's alone), for the determinism runs.
const ROOM: &str =
    "111111111111\n1E1000000001\n101000000001\n111000110001\n100000000001\n111111111111\n";
const WANDERERS: &str = "CREATURE 7.5,1.5 creature\nCREATURE 9.5,4.5 creature speed=2\nCREATURE 3.5,1.5 creature behaviour=patrol\nCREATURE 4.5,4.5 creature speed=1\n";

fn play(seed: u64) -> GameState {
    let mut s = game(WANDERERS, ROOM, (1.5, 1.5), 0.0, seed);
    let script: [(&[Action], Vec<Command>); 4] = [
        (&[Action::TurnLeft], vec![]),
        (&[Action::Forward], vec![Command::Fire]),
        (&[], vec![]),
        (&[Action::TurnRight, Action::Forward], vec![Command::Fire]),
    ];
    for k in 0..600 {
        let (held, commands) = &script[(k / 40) % script.len()];
        let input = Input {
            held: held.iter().copied().collect(),
            commands: commands.clone(),
        };
        step(&mut s, &input, 1.0 / 30.0);
    }
    s
}

#[test]
fn same_seed_same_game_other_seed_other_wanderers() {
    let (a, b) = (play(42), play(42));
    assert_eq!(a.level, b.level);
    assert_eq!(a.score, b.score);
    assert_eq!(format!("{:?}", a.level), format!("{:?}", b.level));
    let c = play(43);
    let pos = |s: &GameState| {
        s.level
            .creatures()
            .iter()
            .map(|c| c.pos)
            .collect::<Vec<_>>()
    };
    assert_ne!(
        pos(&a),
        pos(&c),
        "the seed did not change the wanderers' walks"
    );
}

#[test]
fn a_door_does_not_shut_on_a_creature_in_its_doorway() {
    let grid = "11111111\n1E0D0001\n11111111\n";
    let mut s = game(
        "CREATURE 6.5,1.5 creature behaviour=chase speed=1\n",
        grid,
        (1.5, 1.5),
        0.0,
        1,
    );
    s.doors.set_open((3, 1), 1.0);
    let mut inside = false;
    for _ in 0..150 {
        step(&mut s, &Input::default(), 1.0 / 30.0);
        if s.level.creature_in((3, 1)) {
            inside = true;
            break;
        }
    }
    assert!(inside, "the chaser never came through the door");
    step(
        &mut s,
        &Input {
            held: Held::default(),
            commands: vec![Command::UseDoor],
        },
        1.0 / 30.0,
    );
    run(&mut s, 0.3, &Input::default());
    assert_eq!(s.doors.open_amount((3, 1)), 1.0);
}

#[test]
fn creatures_keep_off_ledges_too_high_to_step_onto() {
    // A raised dais (zone a, floor 0.5) in the middle of a hall: too high to step onto.
    let grid = "11111111\n1E000001\n100aa001\n100aa001\n10000001\n11111111\n";
    let lines = "Ha 0.5 1.5\nCREATURE 6.5,4.5 creature speed=3\nCREATURE 1.5,4.5 creature speed=3 behaviour=patrol\n";
    let w = world(lines, grid);
    let doors = DoorState::new(&w.map);
    for seed in 0..8 {
        let mut level = Level::new(&w.map, seed);
        let mut score = Score::default();
        let mut walked = 0.0;
        for _ in 0..600 {
            // The player stands on the dais, in sight: chasers would like to climb it.
            let mut players = [Player {
                pos: Vec2::new(3.5, 2.5),
                eye: w.map.floor_height(3, 2) + 0.5,
                score: &mut score,
            }];
            level.tick(&w.map, &doors, &mut players, 1.0 / 30.0);
            for c in level.creatures() {
                let (i, j) = (c.pos.x.floor() as i64, c.pos.y.floor() as i64);
                assert!(
                    !(3..=4).contains(&i) || !(2..=3).contains(&j),
                    "climbed the dais: {:?}",
                    c.pos
                );
            }
        }
        walked += level.creatures().iter().map(|c| c.walked).sum::<f64>();
        assert!(walked > 10.0, "the creatures did not walk: {walked}");
    }
}

#[test]
fn a_creature_below_a_ledge_does_not_catch_a_player_on_it_but_one_on_a_step_is_caught() {
    let grid = "11111111\n1E000001\n100aa001\n100aa001\n10000001\n11111111\n";
    for (dais, caught) in [("Ha 1.0 2.0", false), ("Ha 0.2 1.5", true)] {
        let lines = format!("{dais}\nCREATURE 2.8,2.5 creature speed=0.01 behaviour=chase\n");
        let w = world(&lines, grid);
        let doors = DoorState::new(&w.map);
        let mut level = Level::new(&w.map, 1);
        let mut score = Score::default();
        // On the dais, 0.3 from the creature on the hall floor beside it.
        let mut players = [Player {
            pos: Vec2::new(3.1, 2.5),
            eye: w.map.floor_height(3, 2) + 0.5,
            score: &mut score,
        }];
        let events = level.tick(&w.map, &doors, &mut players, 1.0 / 30.0);
        assert_eq!(
            events.iter().any(|e| matches!(e, Event::Caught { .. })),
            caught,
            "{dais}: {events:?}"
        );
    }
}
