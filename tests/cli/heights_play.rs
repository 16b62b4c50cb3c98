//! Playing on maps with floor and ceiling heights (`Hz`): steps up to 0.25 are walked, a jump
//! climbs up to 0.5, any drop is allowed, a cell needs ceiling − floor ≥ eye + 0.1, and the
//! eye eases onto a new floor. Each lane of the test map sits right at one of those limits.

use crate::world_common;

use std::sync::Arc;

use halfcast::camera::Camera;
use halfcast::game::{step, Action, Command, GameState, Held, Input, CROUCH_EYE, STEP_EASE};
use halfcast::render::view::STANDING_EYE;
use halfcast::{Vec2, World};

/// Heights of the lanes (each a corridor running east, its ledge at x = 3).
const ZONES: &str = "\
Ha 0.25 2
Hb 0.26 2
Hc 0.5 2
Hd 0.51 2
He 0 0.5
Hf -1 2
Hg 1 2
Hk 0.25 0.8
";

/// Lane rows: 1 a walkable step, 3 a step too high, 5 a ledge a jump climbs, 7 one it does
/// not, 9 a low passage, 11 a balcony above a pit, 13 a step up under a low ceiling.
const LANES: &str = "\
111111111
1E0aaaa01
111111111
100bbbb01
111111111
100cccc01
111111111
100dddd01
111111111
100eeee01
111111111
1ggffff01
111111111
100kkkk01
111111111
";

/// Where a body stops against the ledge at x = 3: its half-size short of it.
const AGAINST: f64 = 3.0 - halfcast::game::PLAYER_RADIUS;

fn world() -> Arc<World> {
    Arc::new(world_common::world(ZONES, LANES))
}

/// A player at the west end of lane `row`, facing east.
fn player(row: usize) -> GameState {
    let cam = Camera::from_angle(Vec2::new(1.5, row as f64 + 0.5), 0.0, 66.0);
    GameState::new(world(), cam, 80)
}

fn hold(s: &mut GameState, actions: &[Action], seconds: f64, fps: f64) {
    for _ in 0..(seconds * fps).round() as usize {
        step(s, &Input::holding(actions), 1.0 / fps);
    }
}

fn jump_forward(s: &mut GameState, fps: f64) {
    let input = Input {
        held: [Action::Forward].into_iter().collect::<Held>(),
        commands: vec![Command::Jump],
    };
    step(s, &input, 1.0 / fps);
    hold(s, &[Action::Forward], 1.0, fps);
}

fn x(s: &GameState) -> f64 {
    s.camera.pos.x
}

#[test]
fn a_quarter_step_is_walked_and_the_floor_under_the_player_changes() {
    let mut s = player(1);
    assert_eq!(s.footing.floor, 0.0);
    hold(&mut s, &[Action::Forward], 1.0, 60.0);
    assert!(x(&s) > 4.0, "walked up the step: {:?}", s.camera.pos);
    assert_eq!(s.footing.floor, 0.25);
    assert_eq!(s.view.ground, 0.25);
    assert!((s.view.eye() - 0.75).abs() < 1e-12, "{}", s.view.eye());
}

#[test]
fn a_step_of_0_26_stops_the_player_without_a_jump() {
    let mut s = player(3);
    hold(&mut s, &[Action::Forward], 1.0, 60.0);
    assert!((x(&s) - AGAINST).abs() < 1e-6, "{:?}", s.camera.pos);
    assert_eq!(s.footing.floor, 0.0);
    // A jump clears it easily.
    jump_forward(&mut s, 60.0);
    assert!(x(&s) > 3.5, "{:?}", s.camera.pos);
    assert_eq!(s.footing.floor, 0.26);
}

#[test]
fn a_body_that_dropped_into_a_pit_half_over_its_rim_cannot_walk_back_up() {
    // Lane 11: balcony g (floor 1) then pit f (floor -1) from x = 3.
    let mut s = player(11);
    hold(&mut s, &[Action::Forward], 0.55, 60.0);
    assert!(x(&s) > 3.0 && x(&s) - halfcast::game::PLAYER_RADIUS < 3.0);
    assert_eq!(
        s.footing.floor, -1.0,
        "the centre is over the pit: {:?}",
        s.camera.pos
    );
    hold(&mut s, &[Action::Back], 1.0, 60.0);
    assert!(x(&s) >= 3.0, "walked back up 2 walls: {:?}", s.camera.pos);
    assert_eq!(s.footing.floor, -1.0);
}

#[test]
fn a_jump_climbs_a_ledge_of_0_5_but_not_0_51_at_any_frame_rate() {
    for fps in [20.0, 30.0, 60.0, 144.0] {
        let mut s = player(5);
        hold(&mut s, &[Action::Forward], 1.0, fps);
        assert!((x(&s) - AGAINST).abs() < 1e-6, "{fps}: walked onto 0.5");
        jump_forward(&mut s, fps);
        assert!(
            x(&s) > 3.5,
            "{fps} fps: the jump did not climb 0.5: {:?}",
            s.camera.pos
        );
        assert_eq!(s.footing.floor, 0.5);

        let mut s = player(7);
        hold(&mut s, &[Action::Forward], 1.0, fps);
        jump_forward(&mut s, fps);
        assert!(
            x(&s) <= AGAINST + 1e-6,
            "{fps} fps: the jump climbed 0.51: {:?}",
            s.camera.pos
        );
        assert_eq!(s.footing.floor, 0.0);
        // The jump's top is a quarter wall above the eye, and it lands again.
        assert_eq!(s.jump, (0.0, 0.0));
    }
}

#[test]
fn a_jump_tops_out_at_a_quarter_wall() {
    let mut s = player(1);
    let mut top: f64 = 0.0;
    step(
        &mut s,
        &Input {
            held: Held::default(),
            commands: vec![Command::Jump],
        },
        1.0 / 60.0,
    );
    for _ in 0..60 {
        top = top.max(s.view.eye_z - STANDING_EYE);
        step(&mut s, &Input::default(), 1.0 / 60.0);
    }
    assert_eq!(top, halfcast::game::JUMP_RISE);
    assert_eq!(s.view.eye_z, STANDING_EYE);
}

#[test]
fn crouching_passes_a_low_passage_that_standing_does_not_and_stays_down_inside() {
    let mut s = player(9);
    hold(&mut s, &[Action::Forward], 1.0, 60.0);
    assert!(
        (x(&s) - AGAINST).abs() < 1e-6,
        "walked in standing: {:?}",
        s.camera.pos
    );
    hold(&mut s, &[Action::Forward, Action::Crouch], 0.6, 60.0);
    assert!(
        x(&s) > 3.5,
        "crouched, the passage is open: {:?}",
        s.camera.pos
    );
    assert_eq!(s.base_eye, CROUCH_EYE);
    // Crouch released under the 0.5 ceiling: the player stays crouched (0.5 + 0.1 > 0.5).
    hold(&mut s, &[Action::Forward], 0.5, 60.0);
    assert!(x(&s) > 4.5 && x(&s) < 6.5, "{:?}", s.camera.pos);
    assert_eq!(s.base_eye, CROUCH_EYE);
    assert_eq!(s.view.eye_z, CROUCH_EYE);
    // Out of the passage, the player gets up.
    hold(&mut s, &[Action::Forward], 1.0, 60.0);
    assert!(x(&s) > 7.2, "{:?}", s.camera.pos);
    assert_eq!(s.base_eye, STANDING_EYE);
}

#[test]
fn a_step_up_needs_the_ceiling_above_the_head_on_the_new_floor() {
    // Floor 0.25, ceiling 0.8: 0.55 of room, standing needs 0.6, crouching 0.4.
    let mut s = player(13);
    hold(&mut s, &[Action::Forward], 1.0, 60.0);
    assert!((x(&s) - AGAINST).abs() < 1e-6, "{:?}", s.camera.pos);
    hold(&mut s, &[Action::Forward, Action::Crouch], 1.0, 60.0);
    assert!(x(&s) > 3.5, "{:?}", s.camera.pos);
    assert_eq!(s.footing.floor, 0.25);
}

#[test]
fn any_drop_is_allowed_and_the_eye_eases_down_to_the_pit() {
    let mut s = player(11);
    assert_eq!(
        (s.footing.floor, s.view.ground),
        (1.0, 1.0),
        "starts on the balcony"
    );
    let fps = 60.0;
    let mut grounds = Vec::new();
    for _ in 0..60 {
        step(&mut s, &Input::holding(&[Action::Forward]), 1.0 / fps);
        grounds.push(s.view.ground);
    }
    assert_eq!(s.footing.floor, -1.0);
    assert_eq!(s.view.ground, -1.0);
    // From the balcony's 1 to the pit's -1 without a jump cut: every frame a little lower.
    let first_down = grounds.iter().position(|&g| g < 1.0).expect("stepped off");
    let settled = grounds.iter().position(|&g| g == -1.0).expect("settled");
    assert!(grounds.windows(2).all(|w| w[1] <= w[0]), "{grounds:?}");
    let frames = (settled - first_down + 1) as f64;
    assert!(
        (frames / fps - STEP_EASE).abs() < 1.5 / fps,
        "eased over {frames} frames"
    );
    // The pit's far side rises a whole wall: no way out east.
    hold(&mut s, &[Action::Forward], 2.0, fps);
    assert!((x(&s) - (7.0 - 0.2)).abs() < 1e-6, "{:?}", s.camera.pos);
}

#[test]
fn the_eye_eases_up_a_step_over_a_short_time_while_collision_stands_on_it_at_once() {
    let mut s = player(1);
    let fps = 100.0;
    let mut trail = Vec::new();
    for _ in 0..100 {
        step(&mut s, &Input::holding(&[Action::Forward]), 1.0 / fps);
        trail.push((s.camera.pos.x, s.footing.floor, s.view.ground));
    }
    let crossed = trail
        .iter()
        .position(|t| t.0 >= 3.0)
        .expect("crossed the step");
    assert_eq!(trail[crossed].1, 0.25, "collision's floor changes at once");
    assert!(trail[crossed].2 < 0.25, "the eye has not jumped up");
    let between: Vec<f64> = trail[crossed..]
        .iter()
        .map(|t| t.2)
        .take_while(|&g| g < 0.25)
        .collect();
    // 0.15 s at 100 fps: 14 frames strictly between, rising, then exactly on the step.
    assert_eq!(between.len(), 14, "{between:?}");
    assert!(between.windows(2).all(|w| w[1] > w[0]), "{between:?}");
    assert_eq!(trail[crossed + 14].2, 0.25);
}

#[test]
fn a_player_set_down_under_a_low_ceiling_starts_crouched() {
    let cam = Camera::from_angle(Vec2::new(4.5, 9.5), 0.0, 66.0);
    let s = GameState::new(world(), cam, 80);
    assert_eq!(s.base_eye, CROUCH_EYE);
    assert_eq!(s.view.eye_z, CROUCH_EYE);
}

/// A map whose cell (2,1) is 0.3 high: too low even to crawl (crouching needs 0.4).
fn low_map() -> (tempfile::TempDir, std::path::PathBuf) {
    world_common::map_file("Hz 0 0.3\n", "11111\n1Nz01\n11111\n")
}

#[test]
fn play_refuses_a_start_with_no_room_for_the_eye() {
    let (_dir, map) = low_map();
    let out = world_common::halfcast(&[map.to_str().unwrap(), "--pos", "2.5,1.5"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --pos 2.5,1.5 has no room for the eye: cell (2,1) of test.cub is 0.3 high, and \
         even crouching needs 0.4\n"
    );
}

#[test]
fn render_refuses_an_eye_inside_the_ceiling_but_flat_maps_keep_their_range() {
    let (_dir, map) = world_common::map_file("Hz 0 0.5\n", "11111\n1Nz01\n11111\n");
    let map = map.to_str().unwrap();
    let render = |z: &str| {
        world_common::halfcast(&[
            "render", map, "--pos", "2.5,1.5", "--z", z, "--size", "20x6", "--format", "txt",
        ])
    };
    let out = render("0.46");
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --z 0.46 puts the eye inside the ceiling: cell (2,1) of test.cub is 0.5 high \
         (floor 0, ceiling 0.5), so the eye may be at most 0.45 above its floor\n"
    );
    assert!(out.stdout.is_empty());
    assert_eq!(render("0.45").status.code(), Some(0));
    let flat =
        world_common::halfcast(&["render", "--z", "0.95", "--size", "20x6", "--format", "txt"]);
    assert_eq!(
        flat.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&flat.stderr)
    );
}

#[test]
fn a_replay_starting_with_no_room_for_the_eye_is_refused() {
    let (dir, map) = low_map();
    let file = dir.path().join("low.hcr");
    let header = serde_json::json!({
        "halfcast_replay": 1,
        "map": map.to_str().unwrap(),
        "start": {"pos": [2.5, 1.5], "angle": 0.0, "fov": 66.0},
        "size": [40, 12],
        "fps": 30,
        "seed": 0
    });
    std::fs::write(&file, format!("{header}\n{{\"end\":2}}\n")).unwrap();
    let out_dir = dir.path().join("frames");
    let out = world_common::halfcast(&[
        "replay",
        file.to_str().unwrap(),
        "--frames",
        "0",
        "--format",
        "txt",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!(
            "error: {}: start 2.5,1.5 has no room for the eye: cell (2,1) of test.cub is 0.3 \
             high, and even crouching needs 0.4\n",
            file.display()
        )
    );
}

#[test]
fn the_window_of_heights_cub_is_crossed_by_a_crouching_jump_only() {
    // Hall floor 0 (ceiling 2) | window cell (11,5): floor 0.4, ceiling 0.8 | east room.
    let (map, _) = World::from_file(std::path::Path::new("maps/heights.cub"), true).unwrap();
    let map = Arc::new(map);
    let start = || {
        let cam = Camera::from_angle(Vec2::new(10.5, 5.5), 0.0, 66.0);
        GameState::new(Arc::clone(&map), cam, 80)
    };
    let jump = |s: &mut GameState, held: &[Action]| {
        let input = Input {
            held: held.iter().copied().collect::<Held>(),
            commands: vec![Command::Jump],
        };
        step(s, &input, 1.0 / 60.0);
        hold(s, held, 1.5, 60.0);
    };
    // Standing, the jump reaches the sill (0.4 <= 0.5) but the head does not fit under 0.8.
    let mut s = start();
    hold(&mut s, &[Action::Forward], 0.5, 60.0);
    jump(&mut s, &[Action::Forward]);
    assert!(x(&s) < 11.0, "{:?}", s.camera.pos);
    // Crouched, it climbs in (0.8 - 0.4 = 0.4 = crouching eye + head room) and drops out east.
    let mut s = start();
    hold(&mut s, &[Action::Forward, Action::Crouch], 0.5, 60.0);
    jump(&mut s, &[Action::Forward, Action::Crouch]);
    assert!(x(&s) > 12.0, "{:?}", s.camera.pos);
    assert_eq!(s.footing.floor, 0.0);
}

/// Zone heights the random maps pick from: steps at and just past every limit.
const FLOORS: [f64; 10] = [-1.0, -0.5, 0.0, 0.25, 0.26, 0.5, 0.51, 0.75, 1.0, 1.5];
const ROOMS: [f64; 7] = [0.35, 0.4, 0.5, 0.6, 0.8, 1.0, 2.0];

/// The actions a random player holds in one frame (a bit set over these), or jumps.
const ACTIONS: [Action; 7] = [
    Action::Forward,
    Action::Back,
    Action::StrafeLeft,
    Action::StrafeRight,
    Action::TurnLeft,
    Action::TurnRight,
    Action::Crouch,
];

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(40))]

    /// Whatever a player does on whatever heights: its cell is open, its eye (jump included)
    /// stays 0.1 under that cell's ceiling, and the floor under it never rises more than 0.5
    /// from one frame to the next (a walked step plus a jump).
    #[test]
    fn no_input_breaks_the_height_rules(
        zones in proptest::collection::vec((0..FLOORS.len(), 0..ROOMS.len()), 6),
        cells in proptest::collection::vec(0u8..8, 64),
        frames in proptest::collection::vec((0u8..128, 0u8..12), 1..240),
    ) {
        let letters = "abcdef";
        let mut extra = String::new();
        for (z, &(f, r)) in letters.chars().zip(&zones) {
            extra.push_str(&format!("H{z} {} {}\n", FLOORS[f], FLOORS[f] + ROOMS[r]));
        }
        let mut grid = String::from("1111111111\n");
        for j in 0..8 {
            grid.push('1');
            for i in 0..8 {
                let c = match cells[j * 8 + i] {
                    _ if (i, j) == (3, 3) => 'N',
                    0 => '0',
                    7 => '1',
                    k => letters.as_bytes()[usize::from(k) - 1] as char,
                };
                grid.push(c);
            }
            grid.push_str("1\n");
        }
        grid.push_str("1111111111\n");
        let world = Arc::new(world_common::world(&extra, &grid));
        let cam = Camera::from_angle(Vec2::new(4.5, 4.5), 90.0, 66.0);
        let mut s = GameState::new(Arc::clone(&world), cam, 80);
        for (bits, jump) in frames {
            let held: Held = ACTIONS
                .iter()
                .enumerate()
                .filter(|(k, _)| bits & (1 << k) != 0)
                .map(|(_, &a)| a)
                .collect();
            let commands = if jump == 0 { vec![Command::Jump] } else { vec![] };
            let before = s.footing.floor;
            step(&mut s, &Input { held, commands }, 1.0 / 30.0);
            let (i, j) = (s.camera.pos.x.floor() as i64, s.camera.pos.y.floor() as i64);
            let span = world.map.span(i, j);
            proptest::prop_assert!(span.is_some(), "in a wall at {:?}", s.camera.pos);
            let span = span.unwrap();
            proptest::prop_assert_eq!(s.footing.floor, span.floor);
            let head = s.footing.floor + s.jump.0 + s.base_eye + halfcast::game::HEAD_ROOM;
            proptest::prop_assert!(head <= span.ceil + 1e-9, "head {} over {:?}", head, span);
            proptest::prop_assert!(
                s.footing.floor - before <= 0.5 + 1e-9,
                "climbed {} -> {} at {:?}", before, s.footing.floor, s.camera.pos
            );
        }
    }
}
