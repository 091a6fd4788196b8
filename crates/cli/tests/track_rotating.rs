//! `argus track` on a rotating radar's plots (each at its own time, where the beam crossed
//! its target): `docs/examples/real-traffic.toml` on a simulated surveillance picture, and
//! the rotating-sensor keys' errors at their lines.

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::{PI, TAU};
use std::path::Path;

use argus_tracker::Rotation;
use rand::{RngExt as _, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

mod common;
use common::tracker_run::{self, Run, assert_config_error};
use common::{Row, argus, num, rows as parse_rows};

const P: f64 = 5.0;
const REVOLUTIONS: u32 = 120;

/// An aircraft: straight, or turning at a constant rate (rad/s) from t = 0.
#[derive(Debug, Clone, Copy)]
struct Aircraft {
    p0: [f64; 2],
    speed: f64,
    heading: f64,
    rate: f64,
}

impl Aircraft {
    fn at(&self, t: f64) -> [f64; 2] {
        if self.rate == 0.0 {
            return [
                self.p0[0] + self.speed * self.heading.cos() * t,
                self.p0[1] + self.speed * self.heading.sin() * t,
            ];
        }
        let r = self.speed / self.rate;
        let h = self.heading + self.rate * t;
        [
            self.p0[0] + r * (h.sin() - self.heading.sin()),
            self.p0[1] - r * (h.cos() - self.heading.cos()),
        ]
    }
}

/// Four aircraft 40–100 km out, none flying over the radar (nearest pass 6.9 km, the
/// first one's), one in a 2 °/s turn.
fn aircraft() -> Vec<Aircraft> {
    let deg = PI / 180.0;
    let polar = |r: f64, az: f64| [r * az.cos(), r * az.sin()];
    vec![
        Aircraft {
            p0: polar(40_000.0, 20.0 * deg),
            speed: 220.0,
            heading: 190.0 * deg,
            rate: 0.0,
        },
        Aircraft {
            p0: polar(80_000.0, -70.0 * deg),
            speed: 250.0,
            heading: 60.0 * deg,
            rate: 0.0,
        },
        // A 2 °/s turn for the whole run.
        Aircraft {
            p0: polar(60_000.0, 160.0 * deg),
            speed: 200.0,
            heading: -90.0 * deg,
            rate: 2.0 * deg,
        },
        Aircraft {
            p0: polar(100_000.0, -150.0 * deg),
            speed: 180.0,
            heading: 45.0 * deg,
            rate: 0.0,
        },
    ]
}

/// The radar of `docs/examples/real-traffic.toml`: clockwise, 5 s, north at t = 0,
/// σr 70 m, σθ 0.08°, P_D 0.9, 10 clutter plots per revolution uniform over 150 km.
/// Each aircraft's plot is at the time the beam crosses it; the clutter plots at uniform
/// times, at the beam's azimuth then (so uniform over the disc). Returns the file and
/// each aircraft's beam crossing times.
fn plots(seed: u64, ac: &[Aircraft]) -> (String, Vec<Vec<f64>>) {
    let rot = Rotation::clockwise(P);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (nr, na) = (
        Normal::new(0.0, 70.0).unwrap(),
        Normal::new(0.0, 0.08_f64.to_radians()).unwrap(),
    );
    let end = P * f64::from(REVOLUTIONS);
    let mut rows: Vec<(f64, f64, f64)> = Vec::new();
    let mut crossings = vec![Vec::new(); ac.len()];
    for (k, a) in ac.iter().enumerate() {
        let az = |t: f64| {
            let p = a.at(t);
            p[1].atan2(p[0])
        };
        let mut t = rot.crossing_after(az(0.0), 0.0);
        while t < end {
            for _ in 0..6 {
                t = rot.crossing_after(az(t), t - 0.5 * P);
            }
            crossings[k].push(t);
            if rng.random::<f64>() < 0.9 {
                let p = a.at(t);
                rows.push((
                    t,
                    p[0].hypot(p[1]) + nr.sample(&mut rng),
                    az(t) + na.sample(&mut rng),
                ));
            }
            t = rot.crossing_after(az(t + 0.5 * P), t + 0.5 * P);
        }
    }
    for _ in 0..10 * REVOLUTIONS {
        let t = end * rng.random::<f64>();
        let r = 150_000.0 * rng.random::<f64>().sqrt();
        rows.push((t, r.max(100.0), rot.beam_azimuth(t)));
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut s = String::from("t,sensor,range,azimuth\n");
    for (t, r, a) in rows {
        // Azimuth wrapped to (−π, π] as the plot format wants.
        let a = (a + PI).rem_euclid(TAU) - PI;
        s.push_str(&format!("{t},1,{r},{a}\n"));
    }
    (s, crossings)
}

/// Runs `argus track --config rot.toml --plots plots.csv --out tracks.csv` in `dir`.
fn track(dir: &Path, config: &str, plots: &str) -> Run {
    tracker_run::run(dir, "rot.toml", config, plots)
}

fn example() -> String {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/examples");
    std::fs::read_to_string(docs.join("real-traffic.toml")).unwrap()
}

#[test]
fn the_real_traffic_example_tracks_every_aircraft_on_a_rotating_radar() {
    let ac = aircraft();
    let dir = tempfile::tempdir().unwrap();
    let (file, crossings) = plots(18, &ac);
    let run = track(dir.path(), &example(), &file);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.csv
            .starts_with("t,sensor,track,status,reason,x,vx,y,vy,sigma_x,sigma_y,mu_1,mu_2,mu_3,turn_rate_deg,sigma_turn_rate_deg\n"),
        "today's columns"
    );
    let rows = parse_rows(&run.csv);
    // Each confirmed row's nearest aircraft (at the row's time) and its distance.
    let nearest = |r: &Row| {
        let (t, x, y) = (num(r, "t"), num(r, "x"), num(r, "y"));
        (0..ac.len())
            .map(|k| {
                let p = ac[k].at(t);
                (k, (p[0] - x).hypot(p[1] - y))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap()
    };
    let mut tracks_of: BTreeMap<usize, BTreeSet<String>> = BTreeMap::new();
    let mut first_confirmed = vec![f64::INFINITY; ac.len()];
    for r in rows.iter().filter(|r| r["status"] == "confirmed") {
        let (k, d) = nearest(r);
        // No confirmed false track: every confirmed row is on an aircraft (2 km: 10× the
        // largest cross-range σ, 100 km × 0.0014 rad).
        assert!(
            d < 2_000.0,
            "confirmed track {} is {d} m from any aircraft",
            r["track"]
        );
        tracks_of.entry(k).or_default().insert(r["track"].clone());
        first_confirmed[k] = first_confirmed[k].min(num(r, "t"));
    }
    for (k, t) in first_confirmed.iter().enumerate() {
        // Confirmed within 12 revolutions (3 hits of 4 after a first pair at P_D 0.9:
        // not within 12 with probability < 1e-4).
        assert!(*t < 12.0 * P, "aircraft {k} confirmed at {t}");
        // One track each for the whole 10 min: 4 misses in a row at P_D 0.9 (1e-4 per
        // revolution, 0.05 over the 480 aircraft-revolutions here) would break it.
        assert_eq!(tracks_of[&k].len(), 1, "aircraft {k}: {:?}", tracks_of[&k]);
    }
    // One row per track per revolution (updated or missed), at its aircraft's beam
    // crossing: every crossing from the track's first row to its last has exactly one
    // row, within 0.1 s of it (a hit's row is at its plot's time, the crossing; a miss's
    // at the predicted crossing, off by the track's azimuth error over the beam's rate:
    // at most ~100 m at the 6.9 km nearest pass, 0.015 rad, 0.012 s).
    let mut by_track: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for r in rows.iter().filter(|r| r["status"] != "deleted") {
        by_track
            .entry(r["track"].as_str())
            .or_default()
            .push(num(r, "t"));
    }
    for (k, ids) in &tracks_of {
        let times = &by_track[ids.first().unwrap().as_str()];
        let (first, last) = (times[0], times[times.len() - 1]);
        let due: Vec<f64> = crossings[*k]
            .iter()
            .copied()
            .filter(|&c| c > first - 0.1 && c < last + 0.1)
            .collect();
        assert_eq!(times.len(), due.len(), "aircraft {k}: rows per crossing");
        for (t, c) in times.iter().zip(&due) {
            assert!(
                (t - c).abs() < 0.25,
                "aircraft {k}: row at {t}, crossing at {c}"
            );
        }
    }
    // Sectors, not plot times, are the summary's scans: 8 per revolution at most.
    let scans = run.summary["scans"].as_u64().unwrap();
    assert!(scans <= 8 * u64::from(REVOLUTIONS) + 8, "{scans}");
    assert_eq!(run.summary["tracks"]["deleted_after_confirmation"], 0);
}

/// Asserts exit code 2, that stderr names `at` (file:line) and the field, and that no
/// tracks file was written.
#[test]
fn bad_rotating_sensor_keys_name_their_line() {
    let dir = tempfile::tempdir().unwrap();
    let plots = "t,sensor,range,azimuth\n0.5,1,30000,0.3\n";
    let example = example();
    let line_of =
        |text: &str, key: &str| 1 + text.lines().position(|l| l.starts_with(key)).unwrap();
    for bad in ["0.0", "-5.0", "nan", "inf"] {
        let config = example.replace(
            "revolution_period = 5.0",
            &format!("revolution_period = {bad}"),
        );
        let run = track(dir.path(), &config, plots);
        let line = line_of(&config, "revolution_period");
        assert_config_error(&run, &format!("rot.toml:{line}"), "revolution_period");
        assert!(
            run.stderr.contains("must be finite and positive"),
            "{}",
            run.stderr
        );
    }
    let config = example.replace("north_time = 0.0", "north_time = nan");
    let run = track(dir.path(), &config, plots);
    let line = line_of(&config, "north_time");
    assert_config_error(&run, &format!("rot.toml:{line}"), "north_time");
    for bad in ["0.0", "1.5", "-0.25", "nan"] {
        let config = example.replace(
            "sector_fraction = 0.125",
            &format!("sector_fraction = {bad}"),
        );
        let run = track(dir.path(), &config, plots);
        let line = line_of(&config, "sector_fraction");
        assert_config_error(&run, &format!("rot.toml:{line}"), "tracker.sector_fraction");
    }
    // An unknown direction: serde names the line.
    let config = example.replace("rotation = \"clockwise\"", "rotation = \"sideways\"");
    let run = track(dir.path(), &config, plots);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    let line = line_of(&config, "rotation");
    assert!(
        run.stderr.contains(&format!("rot.toml:{line}")),
        "{}",
        run.stderr
    );
    // rotation and north_time need revolution_period.
    let config = example.replace("revolution_period = 5.0", "");
    let run = track(dir.path(), &config, plots);
    let line = line_of(&config, "rotation");
    assert_config_error(&run, &format!("rot.toml:{line}"), "rotation");
}

#[test]
fn a_bad_plot_late_in_the_file_leaves_no_tracks_file_behind() {
    // The tracks are written as the sectors conclude (to a temporary, renamed at the
    // end): a bad plot after many good ones stops the run with nothing written, neither
    // the tracks file nor the temporary, and an older tracks file stays as it was.
    let dir = tempfile::tempdir().unwrap();
    let (mut plots, _) = plots(7, &aircraft());
    let good_lines = plots.lines().count();
    plots.push_str("600.0,1,-30000,0.3\n");
    std::fs::write(dir.path().join("tracks.csv"), "old\n").unwrap();
    std::fs::write(dir.path().join("rot.toml"), example()).unwrap();
    std::fs::write(dir.path().join("plots.csv"), &plots).unwrap();
    let o = argus(
        &[
            "track",
            "--config",
            "rot.toml",
            "--plots",
            "plots.csv",
            "--out",
            "tracks.csv",
        ],
        dir.path(),
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("plots.csv:{}", good_lines + 1)) && stderr.contains("range"),
        "{stderr}"
    );
    let left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let mut left = left;
    left.sort();
    assert_eq!(left, ["plots.csv", "rot.toml", "tracks.csv"], "files left");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("tracks.csv")).unwrap(),
        "old\n"
    );
    assert!(good_lines > 1000, "{good_lines} plots before the bad one");
}

#[test]
fn the_stream_tracks_a_rotating_radar_as_argus_track_does() {
    // `argus_io::track::TrackStream` (the Python `Tracker`'s engine) fed the plot file in two halves gives
    // the rows `argus track` gives for the whole file, in order, except those of the
    // sectors still open when the plots end (`argus track` flushes them; a stream keeps
    // them open for plots still to come).
    let dir = tempfile::tempdir().unwrap();
    let (file, _) = plots(5, &aircraft());
    let run = track(dir.path(), &example(), &file);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let config = dir.path().join("rot.toml");
    let loaded = argus_config::load(&config).unwrap();
    let mut stream = argus_io::track::TrackStream::new(loaded, &config).unwrap();
    let mut lines: Vec<&str> = file.lines().collect();
    let header = lines.remove(0);
    let half = lines.len() / 2;
    let mut streamed = Vec::new();
    for part in [&lines[..half], &lines[half..]] {
        let text = format!("{header}\n{}\n", part.join("\n"));
        let out = stream.process_text(&text, Path::new("part.csv")).unwrap();
        streamed.extend(out.lines().skip(1).map(str::to_owned));
    }
    let whole: Vec<&str> = run.csv.lines().skip(1).collect();
    assert!(
        streamed.len() > 400,
        "{} rows streamed of {}",
        streamed.len(),
        whole.len()
    );
    // The open sectors at the end hold at most a revolution of rows (four aircraft, and
    // clutter tentatives).
    assert!(
        whole.len() - streamed.len() < 50,
        "{} against {}",
        streamed.len(),
        whole.len()
    );
    assert_eq!(streamed, whole[..streamed.len()], "the streamed rows");
}
