//! The minimap of `maps/heights.cub` as the terminal shows it at 80×24 (the real bytes through
//! vt100): in colour, floors are shaded by height and ledges outlined; in mono (plain ASCII),
//! each level is a digit. The ray pane beside it lists the traced column's heights.
#![cfg(unix)]

use crate::common;
use crate::pty_support;

use common::root;
use halfcast::termframe::{CellRgb, TermFrame};
use halfcast::Rgb;
use pty_support::{final_screen, replay_size, PtyRun};

const FIXTURE: &str = "tests/fixtures/heights_stairs.hcr";

/// The frame the recording has climbed the stairs by (facing north on the balcony).
const ON_TOP: usize = 66;

/// The minimap pane's inside: from the row whose border carries the ` map ` title to the
/// border's bottom corner, between its side borders (rounded `╭╮╰` in colour, `+` in mono).
fn map_pane(rows: &[String]) -> Vec<String> {
    let top = rows
        .iter()
        .position(|r| r.contains("╭ map") || r.contains("+ map"))
        .unwrap_or_else(|| panic!("no map pane on screen:\n{}", rows.join("\n")));
    let line: Vec<char> = rows[top].chars().collect();
    let title = rows[top].find(" map ").unwrap();
    let left = rows[top][..title].chars().count() - 1;
    let right = (left + 1..line.len())
        .find(|&x| matches!(line[x], '╮' | '+'))
        .expect("the pane's right corner");
    let bottom = (top + 1..rows.len())
        .find(|&y| matches!(rows[y].chars().nth(left), Some('╰' | '+')))
        .expect("the pane's bottom corner");
    rows[top + 1..bottom]
        .iter()
        .map(|r| r.chars().skip(left + 1).take(right - left - 1).collect())
        .collect()
}

fn frame_rows(frame: &TermFrame) -> Vec<String> {
    (0..frame.rows)
        .map(|y| {
            (0..frame.cols)
                .map(|x| frame.cell(x, y).glyph.as_str())
                .collect()
        })
        .collect()
}

#[test]
fn the_minimap_shades_floors_by_height_and_outlines_ledges() {
    // The replay shown on screen at the recording's size, ending on frame ON_TOP.
    let size = replay_size(&root().join(FIXTURE));
    let n = ON_TOP.to_string();
    let args = ["replay", FIXTURE, "--until-frame", &n];
    let mut run = PtyRun::spawn(&args, size);
    let status = run.wait_exit();
    assert!(status.success(), "halfcast {args:?}: {status:?}");
    let screen = final_screen(&run.bytes(), size);
    let rows = frame_rows(&screen);
    let pane = map_pane(&rows);
    assert!(!pane.is_empty());
    // Colours of the cells inside the pane.
    let top = rows.iter().position(|r| r.contains("╭ map")).unwrap();
    let left = rows[top].chars().position(|c| c == '╭').unwrap();
    let colours: Vec<Rgb> = (top + 1..top + 1 + pane.len())
        .flat_map(|y| (left + 1..left + 1 + pane[0].chars().count()).map(move |x| (x, y)))
        .flat_map(|(x, y)| {
            let c = screen.cell(x, y);
            [c.fg_rgb(), c.bg_rgb()]
        })
        .flatten()
        .collect();
    // The balcony (zone d, `Fd 120,96,72`, floor 1) is brighter than a floor at 0 would be
    // (brightness 110 + 64 per wall height, of 256), in both checker tones.
    let balcony = Rgb::new(120, 96, 72);
    let lit = balcony.scaled(174);
    assert!(colours.contains(&lit), "no balcony shade {lit:?}");
    assert!(colours.contains(&lit.scaled(226)));
    assert!(
        !colours.contains(&balcony.scaled(110)),
        "the balcony is drawn as a flat floor"
    );
    // The balcony's lip over the hall (a whole wall down) is outlined.
    assert!(colours.contains(&Rgb::new(6, 6, 8)), "no ledge line");
    // The ray pane lists the traced column's heights, closed by the wall the player faces.
    assert!(
        rows.iter()
            .any(|r| r.contains("window closed (1,0) at 0.20")),
        "{}",
        rows.join("\n")
    );
}

#[test]
fn the_mono_minimap_writes_each_level_as_a_digit() {
    // Playing at the foot of the stairs, facing up them, in plain ASCII.
    let args = [
        "maps/heights.cub",
        "--pos",
        "1.5,6.5",
        "--angle",
        "90",
        "--colors",
        "mono",
        "--fps",
        "30",
    ];
    let mut run = PtyRun::spawn(&args, (80, 24));
    let levels = ["44", "33", "22", "11", ".."];
    run.wait_for_screen("the minimap with every level of the stairs", |sc| {
        let rows: Vec<String> = sc.contents().lines().map(str::to_owned).collect();
        rows.iter().any(|r| r.contains("+ map"))
            && levels
                .iter()
                .all(|l| map_pane(&rows).join("\n").contains(l))
    });
    let rows: Vec<String> = run.screen().contents().lines().map(str::to_owned).collect();
    let pane = map_pane(&rows);
    let all = pane.join("\n");
    assert!(all.contains('@') && all.is_ascii(), "{all}");
    // North up the stairs column: the hall, then 1, 2, 3 quarter walls, then the balcony.
    let row_of = |c: char| pane.iter().position(|r| r.contains(&format!("{c}{c}")));
    let rows_up: Vec<usize> = ['4', '3', '2', '1']
        .iter()
        .filter_map(|&c| row_of(c))
        .collect();
    assert_eq!(rows_up.len(), 4, "{all}");
    assert!(
        rows_up.windows(2).all(|w| w[0] < w[1]),
        "levels out of order:\n{all}"
    );
    run.send(b"q");
    assert!(run.wait_exit().success());
}
