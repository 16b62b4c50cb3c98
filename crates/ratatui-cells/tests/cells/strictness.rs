//! Each difference the cells text shows fails `assert_frames_eq`; the loose comparison lets
//! through exactly those that look the same on screen.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui_cells::{assert_frames_eq, assert_frames_look_same, cells_text};

fn one(symbol: &str, style: Style) -> Buffer {
    let mut b = Buffer::empty(Rect::new(0, 0, 1, 1));
    b[(0, 0)].set_symbol(symbol).set_style(style);
    b
}

fn fails(f: impl FnOnce() + std::panic::UnwindSafe) -> bool {
    std::panic::catch_unwind(f).is_err()
}

#[test]
fn each_strict_difference_fails_and_the_loose_comparison_passes_what_looks_the_same() {
    let (red, blue) = (Color::Red, Color::Rgb(0, 0, 200));
    let plain = Style::new();
    // (what, a, b, looks the same on screen)
    let cases = [
        (
            "default fg vs default bg: █ against a space",
            one("█", plain),
            one(" ", plain),
            true,
        ),
        (
            "the foreground of a blank cell",
            one(" ", plain.fg(red)),
            one(" ", plain),
            true,
        ),
        (
            "▀ against ▄ with the colours swapped",
            one("▀", plain.fg(red).bg(blue)),
            one("▄", plain.fg(blue).bg(red)),
            true,
        ),
        (
            "underline colour",
            one("a", plain.underline_color(red)),
            one("a", plain.underline_color(blue)),
            false,
        ),
        (
            "named against indexed",
            one("a", plain.fg(Color::Green)),
            one("a", plain.fg(Color::Indexed(2))),
            false,
        ),
    ];
    for (what, a, b, looks_same) in cases {
        assert_ne!(
            cells_text(&a),
            cells_text(&b),
            "{what}: the cells text shows it"
        );
        assert!(fails(|| assert_frames_eq(&a, &b)), "{what}: strict");
        assert_eq!(
            !fails(|| assert_frames_look_same(&a, &b)),
            looks_same,
            "{what}: loose"
        );
    }
    for m in Modifier::all().iter() {
        let (a, b) = (one("a", plain.add_modifier(m)), one("a", plain));
        assert!(fails(|| assert_frames_eq(&a, &b)), "{m:?}: strict");
        assert!(fails(|| assert_frames_look_same(&a, &b)), "{m:?}: loose");
    }
}

#[test]
fn the_failure_counts_every_cell_lists_fifty_and_names_the_callers_line() {
    let a = Buffer::empty(Rect::new(0, 0, 70, 1));
    let mut b = a.clone();
    b.set_string(0, 0, "█".repeat(70), Style::new());
    let payload = std::panic::catch_unwind(|| assert_frames_eq(&a, &b)).unwrap_err();
    let message = payload.downcast_ref::<String>().unwrap();
    assert!(
        message.starts_with("frames differ (expected -> actual):\n70x1 cells, 70 differ"),
        "{message}"
    );
    assert_eq!(
        message
            .lines()
            .filter(|l| l.starts_with("  cell ("))
            .count(),
        50
    );
    assert!(message.ends_with("  … and 20 more\n"), "{message}");
    // #[track_caller]: the location the panic names is this line (seen by a hook that
    // watches this thread only and passes other threads' panics on).
    let seen = std::sync::Arc::new(std::sync::Mutex::new(None));
    let (record, me) = (seen.clone(), std::thread::current().id());
    let previous = std::sync::Arc::new(std::panic::take_hook());
    let pass_on = previous.clone();
    std::panic::set_hook(Box::new(move |info| {
        if std::thread::current().id() == me {
            *record.lock().unwrap() = info.location().map(|l| (l.file().to_string(), l.line()));
        } else {
            pass_on(info);
        }
    }));
    let at = line!() + 1;
    let _ = std::panic::catch_unwind(|| assert_frames_eq(&a, &b));
    let _ = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| previous(info)));
    assert_eq!(*seen.lock().unwrap(), Some((file!().to_string(), at)));
}
