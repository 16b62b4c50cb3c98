//! The session screen: frames, names over the view, the waiting message, tiny sizes.

use super::*;
use crate::game::multi::players::Players;
use crate::termframe::from_screen;

fn served() -> (World, usize) {
    avatars::with_avatar_sheet(World::default_world())
}

/// The served world with ann its only player.
fn ann_alone() -> (World, usize, Snapshot) {
    let (world, sheet) = served();
    let mut ps = Players::new(Arc::new(world.clone()));
    ps.join(1, "ann");
    let snap = ps.snapshot();
    (world, sheet, snap)
}

fn show(bytes: &[u8], size: (u16, u16)) -> vt100::Parser {
    let mut p = vt100::Parser::new(size.1, size.0, 0);
    p.process(bytes);
    p
}

#[test]
fn a_wide_screen_has_the_header_view_minimap_debug_pane_and_status() {
    let (world, sheet) = served();
    let mut ps = Players::new(Arc::new(world.clone()));
    ps.join(1, "ann");
    ps.join(2, "bob");
    let snap = ps.snapshot();
    let mut s = SessionScreen::new(&world, sheet, ColorLevel::TrueColor);
    let size = (140, 40);
    let bytes = s
        .frame(
            &snap,
            Some(1),
            " you are ann",
            size,
            InputMode::Emulated,
            Instant::now(),
        )
        .to_vec();
    let p = show(&bytes, size);
    let text = p.screen().contents();
    assert!(text.starts_with(" you are ann"), "{text}");
    assert!(text.contains(" map ") && text.contains(" ray "), "{text}");
    // Bob's name is on ann's minimap; the status line is the TUI's.
    assert!(text.contains("bob"), "{text}");
    assert!(text.contains("help"), "{text}");
    let Panes::Game { view, .. } = panes_for(size, Toggles::default()) else {
        panic!("too small")
    };
    let frame = from_screen(p.screen(), usize::from(size.0), usize::from(size.1));
    let cell = frame.cell(usize::from(view.x) + 3, usize::from(view.y) + 3);
    assert!(
        matches!(cell.glyph.first_char(), '▀' | '▄' | ' ' | '█'),
        "{cell:?}"
    );
}

#[test]
fn the_other_player_changes_the_pixels_where_they_stand() {
    let (world, sheet) = served();
    let mut ps = Players::new(Arc::new(world.clone()));
    ps.join(1, "ann");
    ps.join(2, "bob");
    let snap = ps.snapshot();
    let ann = &snap.player(1).expect("ann").state;
    // Ann looks straight at bob.
    let to = snap.player(2).expect("bob").state.camera.pos - ann.camera.pos;
    let mut looking = snap.clone();
    looking.players[0].state.camera = crate::Camera::from_angle(
        ann.camera.pos,
        (-to.y).atan2(to.x).to_degrees(),
        crate::camera::DEFAULT_FOV_DEG,
    );
    let mut alone = looking.clone();
    alone.players.retain(|p| p.id == 1);
    let mut a = SessionScreen::new(&world, sheet, ColorLevel::TrueColor);
    let mut b = SessionScreen::new(&world, sheet, ColorLevel::TrueColor);
    let size = (80, 30);
    let with = show(
        a.frame(
            &looking,
            Some(1),
            "",
            size,
            InputMode::Emulated,
            Instant::now(),
        ),
        size,
    );
    let without = show(
        b.frame(
            &alone,
            Some(1),
            "",
            size,
            InputMode::Emulated,
            Instant::now(),
        ),
        size,
    );
    let Panes::Game { view, .. } = panes_for(size, Toggles::default()) else {
        panic!("too small")
    };
    // The centre column of the view, where bob stands, differs; the view's edges do not.
    let col = |p: &vt100::Parser, x: u16| -> Vec<String> {
        (view.y..view.bottom())
            .map(|y| {
                format!(
                    "{:?}",
                    p.screen().cell(y, x).map(|c| (c.fgcolor(), c.bgcolor()))
                )
            })
            .collect()
    };
    let mid = view.x + view.width / 2;
    assert_ne!(col(&with, mid), col(&without, mid), "bob is drawn");
    assert_eq!(col(&with, view.x), col(&without, view.x));
}

#[test]
fn a_frame_that_changes_nothing_sends_nothing_and_the_next_change_is_sent() {
    let (world, sheet, snap) = ann_alone();
    let size = (80, 24);
    for level in [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono] {
        let mut s = SessionScreen::new(&world, sheet, level);
        let mut p = vt100::Parser::new(size.1, size.0, 0);
        p.process(s.frame(
            &snap,
            Some(1),
            "hdr",
            size,
            InputMode::Emulated,
            Instant::now(),
        ));
        // The second frame shows the first one's figures; after it, the same world draws
        // the same screen until the status line's fps window ends (every half second).
        p.process(s.frame(
            &snap,
            Some(1),
            "hdr",
            size,
            InputMode::Emulated,
            Instant::now(),
        ));
        let still = (0..6).any(|_| {
            s.frame(
                &snap,
                Some(1),
                "hdr",
                size,
                InputMode::Emulated,
                Instant::now(),
            )
            .is_empty()
        });
        assert!(still, "{level}: every frame of a still world sent bytes");
        let before = p.screen().contents();
        let mut turned = snap.clone();
        let cam = &mut turned.players[0].state.camera;
        *cam = crate::Camera::from_angle(cam.pos, 123.0, crate::camera::DEFAULT_FOV_DEG);
        let bytes = s.frame(
            &turned,
            Some(1),
            "hdr",
            size,
            InputMode::Emulated,
            Instant::now(),
        );
        assert!(!bytes.is_empty(), "{level}: the turn was not sent");
        p.process(bytes);
        assert_ne!(p.screen().contents(), before, "{level}");
    }
}

#[test]
fn a_reused_screen_buffer_keeps_nothing_of_the_last_frame() {
    // A long header, a short one, the waiting message, and so on: each screen as a fresh
    // session draws it, the status line aside (its timings differ between sessions).
    let (world, sheet, snap) = ann_alone();
    let size = (80, 24);
    let mut s = SessionScreen::new(&world, sheet, ColorLevel::Ansi256);
    let mut p = vt100::Parser::new(size.1, size.0, 0);
    let long = "a long header that runs well past the short one";
    p.process(s.frame(
        &snap,
        Some(1),
        long,
        size,
        InputMode::Emulated,
        Instant::now(),
    ));
    let none = Snapshot::default();
    // Each frame draws into the buffer of the frame before last.
    for (snap, eye, header) in [
        (&snap, Some(1), "short"),
        (&none, None, "waiting"),
        (&snap, Some(1), long),
        (&snap, Some(1), "short"),
        (&none, None, "waiting"),
    ] {
        p.process(s.frame(snap, eye, header, size, InputMode::Emulated, Instant::now()));
        let mut fresh = SessionScreen::new(&world, sheet, ColorLevel::Ansi256);
        let mut q = vt100::Parser::new(size.1, size.0, 0);
        q.process(fresh.frame(snap, eye, header, size, InputMode::Emulated, Instant::now()));
        // Every cell as it looks (a space written or never written look alike).
        let cells = |p: &vt100::Parser| -> Vec<String> {
            (0..size.1 - 1)
                .flat_map(|y| (0..size.0).map(move |x| (y, x)))
                .map(|(y, x)| {
                    let c = p.screen().cell(y, x).expect("cell");
                    let mut text = c.contents();
                    if text.is_empty() {
                        text.push(' ');
                    }
                    format!("{y},{x} {text:?} {:?} {:?}", c.fgcolor(), c.bgcolor())
                })
                .collect()
        };
        assert_eq!(cells(&p), cells(&q), "{header}");
    }
}

#[test]
fn nobody_to_follow_shows_a_message_and_tiny_sizes_do_not_panic() {
    let (world, sheet) = served();
    let mut s = SessionScreen::new(&world, sheet, ColorLevel::Ansi16);
    let bytes = s
        .frame(
            &Snapshot::default(),
            None,
            "hdr",
            (60, 12),
            InputMode::Kitty,
            Instant::now(),
        )
        .to_vec();
    assert!(show(&bytes, (60, 12))
        .screen()
        .contents()
        .contains("waiting"));
    let mut ps = Players::new(Arc::new(world.clone()));
    ps.join(1, "ann");
    let snap = ps.snapshot();
    for size in [(1, 1), (2, 1), (20, 9), (19, 30), (500, 200)] {
        let _ = s.frame(
            &snap,
            Some(1),
            "hdr",
            size,
            InputMode::Kitty,
            Instant::now(),
        );
    }
}

/// Ann looking straight at bob, with bob placed `dist` cells in front of her.
fn facing(dist: f64) -> (World, usize, Snapshot) {
    let (world, sheet) = served();
    let mut ps = Players::new(Arc::new(world.clone()));
    ps.join(1, "ann");
    ps.join(2, "bob");
    let mut snap = ps.snapshot();
    // The default map's row y = 5, clear from x = 12 to 26: ann looks east along it.
    snap.players[0].state.camera =
        crate::Camera::from_angle(crate::Vec2::new(16.5, 5.5), 0.0, 66.0);
    snap.players[1].state.camera =
        crate::Camera::from_angle(crate::Vec2::new(16.5 + dist, 5.5), 0.0, 66.0);
    (world, sheet, snap)
}

fn view_text(p: &vt100::Parser, view: Rect) -> String {
    (view.y..view.bottom())
        .map(|y| p.screen().contents_between(y, view.x, y, view.right()))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn a_near_player_wears_its_name_and_colour_and_the_tag_goes_when_it_walks_off() {
    let size = (100, 30);
    let Panes::Game { view, .. } = panes_for(size, Toggles::default()) else {
        panic!("too small")
    };
    // Every level, and octants too (their view cells are not `▀`, and the tag still shows).
    let settings = [ColorLevel::TrueColor, ColorLevel::Ansi256, ColorLevel::Mono]
        .map(|l| (l, Glyphs::Half))
        .into_iter()
        .chain([(ColorLevel::TrueColor, Glyphs::Octant)]);
    for (level, glyphs) in settings {
        let (world, sheet, near) = facing(2.5);
        let bob = near.player(2).expect("bob").color;
        let mut s = SessionScreen::new(&world, sheet, level);
        s.set_glyphs(glyphs);
        let mut p = vt100::Parser::new(size.1, size.0, 0);
        p.process(s.frame(
            &near,
            Some(1),
            "",
            size,
            InputMode::Emulated,
            Instant::now(),
        ));
        let text = view_text(&p, view);
        assert!(text.contains("bob"), "{level}: {text}");
        if level == ColorLevel::TrueColor {
            // The marker over bob's head is in his minimap colour.
            let colour = vt100::Color::Rgb(bob.r, bob.g, bob.b);
            let marked = (view.y..view.bottom()).any(|y| {
                (view.x..view.right()).any(|x| {
                    let c = p.screen().cell(y, x).expect("cell");
                    !c.contents().chars().any(char::is_alphanumeric)
                        && (c.fgcolor() == colour || c.bgcolor() == colour)
                })
            });
            assert!(marked, "no marker in bob's colour");
        }
        // Bob walks off down the corridor: his name leaves the view, no letter stays behind.
        let (_, _, far) = facing(8.0);
        p.process(s.frame(&far, Some(1), "", size, InputMode::Emulated, Instant::now()));
        let text = view_text(&p, view);
        assert!(!text.contains("bob"), "{level}: {text}");
        assert!(
            !text.contains('b') && !text.contains('o'),
            "{level}: {text}"
        );
    }
}

#[test]
fn a_name_tag_stays_under_the_help_box() {
    let size = (100, 30);
    let Panes::Game { view, .. } = panes_for(size, Toggles::default()) else {
        panic!("too small")
    };
    let (world, sheet, near) = facing(2.5);
    let mut s = SessionScreen::new(&world, sheet, ColorLevel::TrueColor);
    let mut p = vt100::Parser::new(size.1, size.0, 0);
    p.process(s.frame(
        &near,
        Some(1),
        "",
        size,
        InputMode::Emulated,
        Instant::now(),
    ));
    assert!(view_text(&p, view).contains("bob"));
    s.toggles.help = true;
    p.process(s.frame(
        &near,
        Some(1),
        "",
        size,
        InputMode::Emulated,
        Instant::now(),
    ));
    let text = view_text(&p, view);
    assert!(text.contains("help") && !text.contains("bob"), "{text}");
}
