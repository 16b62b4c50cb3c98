//! The first word when it is neither a command nor a map file (`halfcast frobnicate`): said as
//! such, with the commands listed, instead of an error about reading a file named like it. And
//! a flag's bad value in one line (clap's own message, without its two-line tip).

use std::path::Path;

use clap::error::ErrorKind;

use super::Failure;

/// With no command, the map argument must name a file: a bare word (no folder, no extension)
/// that names none is a mistyped command as likely as a mistyped map, so the message offers both
/// (exit 2).
pub(crate) fn not_a_command(cli: &clap::Command, map: Option<&Path>) -> Result<(), Failure> {
    let Some(word) = map else {
        return Ok(());
    };
    // A path or a file name (`maps/x.cub`, `x.cub`) is meant as a map: reading it says why not.
    let as_text = word.to_string_lossy();
    if as_text.contains(['/', '.', std::path::MAIN_SEPARATOR]) {
        return Ok(());
    }
    match std::fs::symlink_metadata(word) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        // It exists (or cannot be looked at): reading it says what is wrong with it.
        _ => return Ok(()),
    }
    let word = word.display().to_string();
    let names: Vec<&str> = cli.get_subcommands().map(clap::Command::get_name).collect();
    let near = names
        .iter()
        .filter(|n| edit_distance(n, &word) <= 2)
        .min_by_key(|n| edit_distance(n, &word))
        .map(|n| format!(" (did you mean {n}?)"))
        .unwrap_or_default();
    Err(Failure::input(format!(
        "no such command or map: {word}{near}; commands: {} (or a .cub map file to play)",
        names.join(", ")
    )))
}

/// Clap's errors as clap prints them, except a flag's bad value: that is one line, clap's first
/// (`invalid value '…' for '--size <SIZE>': …`), exit 2.
pub(crate) fn exit_on_parse_error(e: &clap::Error) -> ! {
    match e.kind() {
        ErrorKind::ValueValidation | ErrorKind::InvalidValue => {
            let text = e.to_string();
            eprintln!("{}", text.lines().next().unwrap_or("error: invalid value"));
            std::process::exit(2)
        }
        _ => e.exit(),
    }
}

/// Levenshtein distance in characters (for the nearest command's suggestion).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::edit_distance;

    #[test]
    fn edit_distance_counts_single_character_changes() {
        assert_eq!(edit_distance("render", "render"), 0);
        assert_eq!(edit_distance("render", "rendr"), 1);
        assert_eq!(edit_distance("serve", "serv3r"), 2);
        assert_eq!(edit_distance("", "abc"), 3);
    }
}
