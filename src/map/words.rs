//! A header line's words with their columns, so an error points at the word that broke a rule.

/// The blank-separated words of `rest` (which starts at 1-based column `rest_col`), each with
/// the column of its first character.
pub(super) fn words(rest: &str, rest_col: usize) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    let mut cur: Option<(String, usize)> = None;
    for (col, c) in (rest_col..).zip(rest.chars()) {
        if c == ' ' || c == '\t' {
            out.extend(cur.take());
        } else {
            cur.get_or_insert_with(|| (String::new(), col)).0.push(c);
        }
    }
    out.extend(cur);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_keep_their_columns_across_blanks_and_tabs() {
        let got = words(" a\tbc  d", 5);
        let want = [("a", 6), ("bc", 8), ("d", 12)].map(|(w, c)| (w.to_owned(), c));
        assert_eq!(got, want);
        assert!(words(" \t ", 1).is_empty());
    }
}
