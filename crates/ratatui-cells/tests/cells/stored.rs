//! Stored cells snapshots in insta's workflow, as a user runs it: the snapshots committed
//! beside this file pass, and, in a child process with insta's switch set as a person would
//! set it, a changed screen fails at the test's line with the cell diff ahead of insta's, a
//! missing one is written only with `INSTA_UPDATE=always`, and a `Buffer`'s `Debug` or a
//! `TestBackend`'s `Display` snapshot migrates to cells text in one run.

use std::path::{Path, PathBuf};
use std::process::Command;

use ratatui::backend::TestBackend;
use ratatui::style::{Color, Modifier, Style, Stylize};
use ratatui::text::Line;
use ratatui::widgets::{Block, Gauge, Paragraph};
use ratatui::Terminal;
use ratatui_cells::{assert_cells_snapshot, cells_text, TermFrame};

/// A small screen with clusters of every width; `changed` moves the gauge and greets
/// someone else.
fn screen(changed: bool) -> Terminal<TestBackend> {
    let mut terminal = Terminal::new(TestBackend::new(24, 5)).unwrap();
    let who = if changed {
        "Zoë 👍🏿"
    } else {
        "Aiko 🇯🇵"
    };
    terminal
        .draw(|frame| {
            let area = frame.area();
            let block = Block::bordered().title("chat".cyan().bold());
            let inner = block.inner(area);
            frame.render_widget(block, area);
            let [hello, gauge, keys] = ratatui::layout::Layout::vertical([1, 1, 1]).areas(inner);
            let name = Style::new()
                .fg(Color::Indexed(208))
                .add_modifier(Modifier::BOLD);
            frame.render_widget(
                Line::from(vec![
                    ratatui::text::Span::styled(who, name),
                    " 界 1️⃣ 👨‍👩‍👧".into(),
                ]),
                hello,
            );
            frame.render_widget(
                Gauge::default()
                    .percent(if changed { 75 } else { 40 })
                    .gauge_style(Style::new().green().underline_color(Color::Red)),
                gauge,
            );
            frame.render_widget(Paragraph::new("q quit").reversed(), keys);
        })
        .unwrap();
    terminal
}

#[test]
fn the_committed_snapshots_pass() {
    let terminal = screen(false);
    assert_cells_snapshot!(terminal.backend());
    assert_cells_snapshot!("chat_buffer", terminal.backend().buffer());
}

/// Runs insta's assertion of `screen(CELLS_CHANGED)`, named `screen`, against the folder
/// `CELLS_SCRATCH`: what [`run_child`] starts, in a process of its own so insta's switches
/// are the ones it sets.
#[test]
#[ignore = "run by the other tests in this file, in a child process"]
fn child_asserts_a_screen() {
    let dir = std::env::var("CELLS_SCRATCH").map_or_else(|_| scratch("by-hand"), PathBuf::from);
    let terminal = screen(std::env::var_os("CELLS_CHANGED").is_some());
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(dir);
    settings.set_prepend_module_to_snapshot(false);
    let _bound = settings.bind_to_scope();
    println!("assertion at {}:{}", file!(), line!() + 1);
    assert_cells_snapshot!("screen", terminal.backend());
}

/// What a child run did: whether it passed, and everything it printed.
struct Run {
    passed: bool,
    output: String,
}

/// Runs [`child_asserts_a_screen`] with `INSTA_UPDATE` set to `update`, against `dir`.
fn run_child(dir: &Path, update: &str, changed: bool) -> Run {
    let mut command = Command::new(std::env::current_exe().unwrap());
    command
        .args([
            "--ignored",
            "--exact",
            "stored::child_asserts_a_screen",
            "--nocapture",
        ])
        .env("CELLS_SCRATCH", dir)
        .env("INSTA_UPDATE", update)
        .env("INSTA_OUTPUT", "diff")
        .env_remove("INSTA_FORCE_PASS")
        .env_remove("INSTA_FORCE_UPDATE")
        .env_remove("INSTA_REQUIRE_FULL_MATCH")
        .env_remove("INSTA_SNAPSHOT_REFERENCES_FILE")
        .env_remove("CELLS_CHANGED");
    if changed {
        command.env("CELLS_CHANGED", "1");
    }
    let out = command.output().unwrap();
    Run {
        passed: out.status.success(),
        output: String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr),
    }
}

/// A fresh folder of this test's own under the system's temporary folder.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ratatui-cells-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The files in `dir`, by name.
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The contents of an insta `.snap` file, its header removed.
fn body(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    text.splitn(3, "---\n").nth(2).unwrap().to_string()
}

/// Where the child's assertion is, as it printed it.
fn assertion_line(output: &str) -> String {
    let at = output.find("assertion at ").expect(output) + "assertion at ".len();
    output[at..].lines().next().unwrap().to_string()
}

#[test]
fn a_new_snapshot_is_written_only_by_insta_update_always() {
    let dir = scratch("new");
    let run = run_child(&dir, "no", false);
    assert!(!run.passed, "{}", run.output);
    assert!(
        run.output.contains("no stored snapshot to compare"),
        "{}",
        run.output
    );
    assert!(files(&dir).is_empty(), "{:?}", files(&dir));
    let run = run_child(&dir, "always", false);
    assert!(run.passed, "{}", run.output);
    assert_eq!(files(&dir), ["screen.snap"]);
    assert_eq!(
        body(&dir.join("screen.snap")),
        cells_text(screen(false).backend())
    );
    assert!(run_child(&dir, "no", false).passed);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_changed_screen_fails_at_the_tests_line_with_the_cell_diff_first() {
    let dir = scratch("changed");
    assert!(run_child(&dir, "always", false).passed);
    let stored = std::fs::read_to_string(dir.join("screen.snap")).unwrap();
    let run = run_child(&dir, "no", true);
    assert!(!run.passed, "{}", run.output);
    let out = &run.output;
    let cells = out
        .find("cells snapshot differs (stored -> new):")
        .expect(out);
    let insta = out.find("Snapshot Summary").expect(out);
    assert!(cells < insta, "the cell diff comes first:\n{out}");
    assert!(
        out.contains(r#"cell (1,1) glyph: "A" fg=idx208 bold -> "Z" fg=idx208 bold"#),
        "{out}"
    );
    let line = assertion_line(out);
    assert!(
        out.contains(&format!("panicked at {line}:")),
        "the failure is at {line}:\n{out}"
    );
    assert!(out.contains("the cells differ (cell diff above)"), "{out}");
    // INSTA_UPDATE=no: the stored snapshot is as it was, and nothing is written beside it.
    assert_eq!(files(&dir), ["screen.snap"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("screen.snap")).unwrap(),
        stored
    );
    // Accepting it, insta's way.
    assert!(run_child(&dir, "always", true).passed);
    assert_eq!(
        body(&dir.join("screen.snap")),
        cells_text(screen(true).backend())
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn debug_and_display_snapshots_migrate_in_one_run() {
    // A `Buffer`'s `Debug`, a `TestBackend`'s `Debug` (the buffer inside it), its `Display`.
    let terminal = screen(false);
    let header = "---\nsource: tests/ui.rs\nexpression: terminal.backend()\n---\n";
    let forms = [
        (
            format!("{:#?}", terminal.backend().buffer()),
            "stored as a ratatui Buffer's Debug form, showing the same cells",
        ),
        (
            format!("{:#?}", terminal.backend()),
            "stored as a ratatui Buffer's Debug form, showing the same cells",
        ),
        (
            terminal.backend().to_string(),
            "stored as a ratatui TestBackend's Display form (glyphs only), showing the same glyphs",
        ),
    ];
    for (old, says) in forms {
        let dir = scratch("migrate");
        let path = dir.join("screen.snap");
        std::fs::write(&path, format!("{header}{old}\n")).unwrap();
        let run = run_child(&dir, "no", false);
        assert!(!run.passed && run.output.contains(says), "{}", run.output);
        if says.contains("Display") {
            let styled = TermFrame::from(terminal.backend())
                .cells
                .iter()
                .filter(|c| !c.is_plain_style())
                .count();
            let adds = format!("the cells text adds the styles of {styled} cells");
            assert!(run.output.contains(&adds), "{}", run.output);
        }
        // A screen that changed since is told cell by cell, as for cells text.
        let run = run_child(&dir, "no", true);
        assert!(
            run.output.contains("differ (stored -> new):"),
            "{}",
            run.output
        );
        assert!(run.output.contains(r#"cell (1,1) glyph"#), "{}", run.output);
        // One run with insta's switch migrates it; then it passes as it is.
        assert!(run_child(&dir, "always", false).passed);
        assert_eq!(body(&path), cells_text(terminal.backend()));
        assert!(run_child(&dir, "no", false).passed);
        std::fs::remove_dir_all(dir).unwrap();
    }
}
