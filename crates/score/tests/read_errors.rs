//! The readers: accepted layouts, and typed errors naming file, line and field.

#![allow(clippy::unwrap_used, missing_docs)]

use argus_score::{ScoreError, read_tracks, read_tracks_from, read_truth_from};

fn truth_err(text: &str) -> String {
    read_truth_from(text.as_bytes(), "u.csv")
        .unwrap_err()
        .to_string()
}

fn tracks_err(text: &str) -> String {
    read_tracks_from(text.as_bytes(), "t.csv")
        .unwrap_err()
        .to_string()
}

#[test]
fn truth_layout_of_argus_simulate_is_accepted() {
    // Interleaved aircraft, extra z/vz columns, names kept as text (ICAO addresses work).
    let text =
        "t,target,x,vx,y,vy,z,vz\n0,0,1,2,3,4,5,6\n0,3c4a5f,0,0,0,0,0,0\n5,0,11,2,23,4,5,6\n";
    let paths = read_truth_from(text.as_bytes(), "u.csv").unwrap();
    assert_eq!(paths.len(), 2);
    assert_eq!(paths[0].name(), "0");
    assert_eq!(paths[0].samples().len(), 2);
    assert_eq!(paths[1].name(), "3c4a5f");
    let s = paths[0].samples()[1];
    assert_eq!((s.t, s.x, s.vx, s.y, s.vy), (5.0, 11.0, 2.0, 23.0, 4.0));
}

#[test]
fn tracks_status_decides_confirmed_and_its_absence_means_all() {
    let text = "t,track,status,x,vx,y,vy\n0,1,tentative,0,0,0,0\n5,1,confirmed,0,0,0,0\n10,1,deleted,0,0,0,0\n";
    let tracks = read_tracks_from(text.as_bytes(), "t.csv").unwrap();
    let c: Vec<bool> = tracks[0].rows().iter().map(|r| r.confirmed).collect();
    assert_eq!(c, vec![false, true, false]);
    let text = "t,track,x,vx,y,vy,var_x,var_vx,var_y,var_vy\n0,0,1,1,1,1,1,1,1,1\n";
    let tracks = read_tracks_from(text.as_bytes(), "t.csv").unwrap();
    assert!(tracks[0].rows()[0].confirmed);
    // A header and no row: no track.
    assert!(
        read_tracks_from("t,track,x,vx,y,vy\n".as_bytes(), "t.csv")
            .unwrap()
            .is_empty()
    );
}

#[test]
fn messages_name_file_line_and_field() {
    assert_eq!(
        truth_err("t,target,x,vx,y\n"),
        "u.csv:1: missing column 'vy'"
    );
    assert_eq!(
        truth_err("t,target,x,vx,y,vy\n0,A,0,0,0,0\n5,A,1,abc,0,0\n"),
        "u.csv:3: field 'vx': 'abc' is not a number"
    );
    assert_eq!(
        truth_err("t,target,x,vx,y,vy\n0,A,NaN,0,0,0\n"),
        "u.csv:2: field 'x': NaN is not a finite number"
    );
    assert_eq!(
        truth_err("t,target,x,vx,y,vy\n0,,0,0,0,0\n"),
        "u.csv:2: field 'target': empty"
    );
    assert_eq!(
        truth_err("t,target,x,vx,y,vy\n5,A,0,0,0,0\n0,B,0,0,0,0\n5,A,0,0,0,0\n"),
        "u.csv:4: field 't': time 5 is not after target A's previous sample at 5 (line 2)"
    );
    assert_eq!(truth_err("t,target,x,vx,y,vy\n"), "u.csv: no truth sample");
    assert_eq!(
        tracks_err("t,track,status,x,vx,y,vy\n0,1,lost,0,0,0,0\n"),
        "t.csv:2: field 'status': 'lost' is not a status (tentative, confirmed or deleted)"
    );
    assert_eq!(
        tracks_err("t,track,x,vx,y,vy\n5,1,0,0,0,0\n4,1,0,0,0,0\n"),
        "t.csv:3: field 't': time 4 is before track 1's previous row at 5 (line 2)"
    );
    assert_eq!(
        tracks_err("t,track,x,vx,y,vy\n5,1,0,0,0,inf\n"),
        "t.csv:2: field 'vy': inf is not a finite number"
    );
    // A row with the wrong number of fields is a syntax error at its line.
    let e = tracks_err("t,track,x,vx,y,vy\n5,1,0,0,0,0\n6,1,0\n");
    assert!(e.starts_with("t.csv:3: "), "{e}");
}

#[test]
fn missing_file_is_an_io_error_with_its_path() {
    let e = read_tracks(std::path::Path::new("/nonexistent/t.csv")).unwrap_err();
    assert!(matches!(e, ScoreError::Io { .. }));
    assert!(e.to_string().starts_with("/nonexistent/t.csv: "));
}
