//! `halfcast scores`: a server's lasting leaderboard from the command line, as text or JSON
//! (the JSON shape is in docs/serving.md).

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use halfcast::serve::leaderboard::database::{postgres_url, Access, Database};
use halfcast::serve::leaderboard::store::SCHEMA_VERSION;
use halfcast::serve::leaderboard::{content_hash, escaped, shown_name, Entry, DEFAULT_FILE, TOP};
use serde::Serialize;

use super::Failure;

#[derive(Args, Debug)]
pub(crate) struct ScoresArgs {
    /// The leaderboard `halfcast serve` writes: its SQLite file, or a postgres:// URL.
    #[arg(long, default_value = DEFAULT_FILE, value_name = "FILE|URL")]
    pub(crate) db: PathBuf,
    /// The PostgreSQL password on this file's first line (as `serve --db-password-file`);
    /// refused when its group or others may read it.
    #[arg(long, value_name = "FILE")]
    pub(crate) db_password_file: Option<PathBuf>,
    /// Use a PostgreSQL password file (--db-password-file, ~/.pgpass) that others may read.
    #[arg(long)]
    pub(crate) db_insecure_password_file: bool,
    /// Only this map (its content decides: an edited map has a board of its own).
    #[arg(long, value_name = "MAP")]
    pub(crate) map: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    /// Instead of printing, copy the leaderboard to FILE (replacing it) while servers write
    /// it, with SQLite's online backup; the copy is checked before it takes FILE's place.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["map", "json"])]
    pub(crate) backup: Option<PathBuf>,
}

/// `scores --json`: every board.
#[derive(Serialize)]
struct Report {
    /// The database's schema version.
    schema: i64,
    maps: Vec<MapReport>,
}

/// One map's board for one mode.
#[derive(Serialize)]
struct MapReport {
    hash: String,
    name: String,
    mode: String,
    rounds: u64,
    top: Vec<Ranked>,
}

/// An entry with its rank.
#[derive(Serialize)]
struct Ranked {
    rank: usize,
    #[serde(flatten)]
    entry: Entry,
}

pub(crate) fn scores(args: &ScoresArgs) -> Result<(), Failure> {
    if let Some(to) = &args.backup {
        if postgres_url(&args.db).is_some() {
            return Err(Failure::input(
                "--backup copies a SQLite file; back PostgreSQL up with its own pg_dump",
            ));
        }
        let rounds =
            halfcast::serve::leaderboard::backup::backup(&args.db, to).map_err(Failure::input)?;
        println!(
            "{} backed up to {}: {rounds} {}",
            args.db.display(),
            to.display(),
            if rounds == 1 { "round" } else { "rounds" }
        );
        return Ok(());
    }
    if postgres_url(&args.db).is_some_and(halfcast::serve::leaderboard::pg_config::url_has_password)
    {
        // Warned, not refused (as `serve` does): this runs for a moment, in the operator's own
        // shell, whose history holds the URL anyway.
        eprintln!(
            "halfcast scores: warning: the password in --db is readable by every local user \
             while this runs; --db-password-file, PGPASSWORD or ~/.pgpass (PGPASSFILE) keep it \
             out of the process list"
        );
    }
    let access = Access {
        password_file: args.db_password_file.clone(),
        insecure_password_file: args.db_insecure_password_file,
    };
    let mut store = Database::open_read(&args.db, &access).map_err(Failure::input)?;
    let only = match &args.map {
        Some(p) => {
            let bytes = halfcast::map::read_map_file(p).map_err(Failure::input)?;
            Some(content_hash(&bytes))
        }
        None => None,
    };
    let mut maps = Vec::new();
    for (hash, name, mode, rounds) in store.maps().map_err(Failure::io)? {
        if only.as_ref().is_some_and(|h| *h != hash) {
            continue;
        }
        let top = store
            .top(&hash, &mode, TOP)
            .map_err(Failure::io)?
            .into_iter()
            .enumerate()
            .map(|(i, entry)| Ranked { rank: i + 1, entry })
            .collect();
        maps.push(MapReport {
            hash,
            name,
            mode,
            rounds,
            top,
        });
    }
    let out = if args.json {
        let report = Report {
            schema: SCHEMA_VERSION,
            maps,
        };
        let mut s = serde_json::to_string_pretty(&report).map_err(Failure::io)?;
        s.push('\n');
        s
    } else {
        text(&maps, args.map.is_some())
    };
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(out.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(Failure::io)
}

/// The boards as text: names escaped and cut, one block per map.
fn text(maps: &[MapReport], one_map: bool) -> String {
    if maps.is_empty() {
        return if one_map {
            "no rounds recorded on that map\n".into()
        } else {
            "no rounds recorded\n".into()
        };
    }
    let mut out = String::new();
    for m in maps {
        out.push_str(&format!(
            "{} ({}, {} {}, {})\n",
            escaped(&m.name),
            m.mode,
            m.rounds,
            if m.rounds == 1 { "round" } else { "rounds" },
            m.hash
        ));
        for r in &m.top {
            out.push_str(&format!(
                "  {:>2}. {:<16}  {}\n",
                r.rank,
                shown_name(&r.entry.name),
                r.entry.figure(&m.mode)
            ));
        }
    }
    out
}
