//! A table given as columns reads exactly as the same table written as CSV: the same
//! tracks and truth, and the same `file:line: field` errors (row `i` at line `i + 2`).

#![allow(clippy::unwrap_used)]

use argus_score::{
    Column, read_tracks_columns, read_tracks_from, read_truth_columns, read_truth_from,
};

fn names(n: &[&str]) -> Vec<String> {
    n.iter().map(|s| (*s).to_owned()).collect()
}

/// The CSV text of the columns (numbers as Rust writes them, which read back exactly).
fn text(names: &[String], columns: &[Column<'_>]) -> String {
    let mut t = names.join(",");
    t.push('\n');
    for i in 0..columns[0].len() {
        let row: Vec<String> = columns
            .iter()
            .map(|c| match c {
                Column::Float(v) => v[i].to_string(),
                Column::Int(v) => v[i].to_string(),
                Column::Text(v) => v[i].clone(),
            })
            .collect();
        t.push_str(&row.join(","));
        t.push('\n');
    }
    t
}

#[test]
fn columns_read_as_their_csv_text() {
    let n = names(&["t", "track", "status", "x", "vx", "y", "vy"]);
    let t = [0.0, 0.0, 5.0, 5.0, 10.0];
    let track = [1, 2, 1, 2, 1];
    let status: Vec<String> = [
        "tentative",
        "confirmed",
        "confirmed",
        "deleted",
        "confirmed",
    ]
    .iter()
    .map(|s| (*s).to_owned())
    .collect();
    let x = [0.0, 1e4, 500.5, 1.00001e4, 1000.25];
    let v = [100.0, -3.5, 100.0, -3.5, 99.0];
    let cols = [
        Column::Float(&t),
        Column::Int(&track),
        Column::Text(&status),
        Column::Float(&x),
        Column::Float(&v),
        Column::Float(&x),
        Column::Float(&v),
    ];
    let want = read_tracks_from(text(&n, &cols).as_bytes(), "tracks").unwrap();
    let got = read_tracks_columns(&n, &cols, "tracks").unwrap();
    assert_eq!(got, want);
    assert_eq!(got.len(), 2);
    assert_eq!(got[0].rows().iter().filter(|r| r.confirmed).count(), 2);

    let n = names(&["t", "target", "x", "vx", "y", "vy"]);
    let target: Vec<String> = ["a", "b", "a", "b", "a"]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    let cols = [
        Column::Float(&t),
        Column::Text(&target),
        Column::Float(&x),
        Column::Float(&v),
        Column::Float(&x),
        Column::Float(&v),
    ];
    let want = read_truth_from(text(&n, &cols).as_bytes(), "truth").unwrap();
    assert_eq!(read_truth_columns(&n, &cols, "truth").unwrap(), want);
}

#[test]
fn bad_cells_are_the_csv_readers_errors_at_the_same_line() {
    let n = names(&["t", "track", "status", "x", "vx", "y", "vy"]);
    let ok = [0.0, 5.0, 10.0];
    let nan = [0.0, f64::NAN, 10.0];
    let back = [0.0, 10.0, 5.0];
    let track = [1_i64, 1, 1];
    let empty: Vec<String> = ["1", "", "1"].iter().map(|s| (*s).to_owned()).collect();
    let good: Vec<String> = ["confirmed"; 3].iter().map(|s| (*s).to_owned()).collect();
    let odd: Vec<String> = ["confirmed", "lost", "confirmed"]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    let word: Vec<String> = ["0", "five", "10"]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    let o = Column::Float(&ok);
    let table = |t, id, st| vec![t, id, st, o, o, o, o];
    let (fine, id) = (Column::Float(&ok), Column::Int(&track));
    let cases = [
        table(Column::Float(&nan), id, Column::Text(&good)),
        table(Column::Float(&back), id, Column::Text(&good)),
        table(fine, Column::Text(&empty), Column::Text(&good)),
        table(fine, id, Column::Text(&odd)),
        table(Column::Text(&word), id, Column::Text(&good)),
    ];
    let mut seen = Vec::new();
    // The line of each case's bad row: the NaN, the time going back, the empty name,
    // the unknown status, the word for a number.
    for (cols, line) in cases.iter().zip([3, 4, 3, 3, 3]) {
        let want = read_tracks_from(text(&n, cols).as_bytes(), "tracks")
            .unwrap_err()
            .to_string();
        let got = read_tracks_columns(&n, cols, "tracks")
            .unwrap_err()
            .to_string();
        assert_eq!(got, want);
        assert!(got.starts_with(&format!("tracks:{line}:")), "{got}");
        seen.push(got);
    }
    seen.dedup();
    assert_eq!(seen.len(), cases.len(), "five different errors: {seen:?}");
    // A missing column, and columns of different lengths.
    let short = [0.0, 5.0];
    let cols = [Column::Float(&ok), Column::Float(&short)];
    let e = read_tracks_columns(&names(&["t", "x"]), &cols, "tracks")
        .unwrap_err()
        .to_string();
    assert!(e.contains("column 'x' has 2 rows"), "{e}");
    let e = read_truth_columns(&names(&["t"]), &cols[..1], "truth")
        .unwrap_err()
        .to_string();
    let want = read_truth_from("t\n0\n5\n10\n".as_bytes(), "truth")
        .unwrap_err()
        .to_string();
    assert_eq!(e, want);
}
