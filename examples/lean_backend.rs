//! Any ratatui app, switched to halfcast's `LeanBackend` in one line (`main`, marked below):
//! a dashboard of gauges, a sparkline and a table that change every frame. It runs for five
//! seconds (q quits sooner) and then prints how many bytes it sent; `-- --stock` runs the same
//! app on ratatui's `CrosstermBackend` to compare.
//!
//! ```sh
//! cargo run --example lean_backend --no-default-features --features crossterm
//! cargo run --example lean_backend --no-default-features --features crossterm -- --stock
//! ```

use std::cell::Cell;
use std::io::{self, Write};
use std::rc::Rc;
use std::time::{Duration, Instant};

use halfcast::{ColorLevel, LeanBackend};
use ratatui::backend::{Backend, CrosstermBackend};
use ratatui::crossterm::event::{self, Event, KeyCode};
use ratatui::crossterm::terminal::{self, EnterAlternateScreen, LeaveAlternateScreen};
use ratatui::crossterm::ExecutableCommand;
use ratatui::layout::{Constraint, Layout};
use ratatui::style::{Color, Style};
use ratatui::widgets::{Block, Gauge, Row, Sparkline, Table};
use ratatui::Terminal;

/// stdout, counting what goes through.
struct Counted {
    out: io::Stdout,
    bytes: Rc<Cell<usize>>,
}

impl Write for Counted {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.out.write(buf)?;
        self.bytes.set(self.bytes.get() + n);
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

fn main() -> io::Result<()> {
    let stock = std::env::args().any(|a| a == "--stock");
    let bytes = Rc::new(Cell::new(0));
    let out = Counted {
        out: io::stdout(),
        bytes: Rc::clone(&bytes),
    };
    terminal::enable_raw_mode()?;
    io::stdout().execute(EnterAlternateScreen)?;
    let frames = if stock {
        run(&mut Terminal::new(CrosstermBackend::new(out))?)
    } else {
        // The one line: `CrosstermBackend::new(out)` becomes this.
        run(&mut Terminal::new(LeanBackend::new(
            out,
            ColorLevel::from_env(),
        ))?)
    };
    let bytes = bytes.get();
    io::stdout().execute(LeaveAlternateScreen)?;
    terminal::disable_raw_mode()?;
    let frames = frames?;
    let backend = if stock {
        "CrosstermBackend"
    } else {
        "LeanBackend"
    };
    println!(
        "{backend}: {bytes} bytes in {frames} frames ({} per frame)",
        bytes / frames.max(1)
    );
    Ok(())
}

/// The app: draws until q or five seconds; returns the number of frames drawn.
fn run<B: Backend<Error = io::Error>>(terminal: &mut Terminal<B>) -> io::Result<usize> {
    let start = Instant::now();
    let mut frame_no = 0usize;
    while start.elapsed() < Duration::from_secs(5) {
        let i = frame_no;
        terminal.draw(|f| {
            let [top, spark, table] = Layout::vertical([
                Constraint::Length(9),
                Constraint::Length(6),
                Constraint::Fill(1),
            ])
            .areas(f.area());
            let rows = Layout::vertical([Constraint::Length(3); 3]).split(top);
            for (k, r) in rows.iter().enumerate() {
                let ratio = ((i * (k + 1)) % 100) as f64 / 100.0;
                let shade = (ratio * 255.0) as u8;
                f.render_widget(
                    Gauge::default()
                        .block(Block::bordered().title(format!("job {k}")))
                        .gauge_style(Style::new().fg(Color::Rgb(shade, 180, 255 - shade)))
                        .ratio(ratio),
                    *r,
                );
            }
            let data: Vec<u64> = (0..200).map(|x| ((x * 7 + i * 3) % 40) as u64).collect();
            f.render_widget(
                Sparkline::default()
                    .block(Block::bordered().title("load"))
                    .data(&data)
                    .style(Style::new().fg(Color::Cyan)),
                spark,
            );
            let rows = (0..30).map(|r| {
                let v = (r * 31 + i * 7) % 1000;
                Row::new(vec![
                    format!("host-{r:02}"),
                    format!("{v}"),
                    format!("{} ms", v % 97),
                ])
            });
            f.render_widget(
                Table::new(rows, [Constraint::Length(12); 3])
                    .header(Row::new(vec!["host", "load", "latency"]).style(Style::new().bold()))
                    .block(Block::bordered().title("hosts (q quits)")),
                table,
            );
        })?;
        frame_no += 1;
        if event::poll(Duration::from_millis(33))? {
            if let Event::Key(k) = event::read()? {
                if k.code == KeyCode::Char('q') {
                    break;
                }
            }
        }
    }
    Ok(frame_no)
}
