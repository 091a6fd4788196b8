//! The streaming session ([`Session`]): its rows are what the direct [`Tracker`] calls in
//! `argus track`'s former order (`crates/cli/src/track/feed.rs` before the session: plots
//! grouped by `(time, sensor)`, sectors stepped one by one, markers advanced to, the end
//! flushed) give; its errors name the plot's tag; a rotation input equals the configured
//! rotation.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Matrix, Vector};
use argus_sim::run_rng;
use argus_tracker::{
    Concluded, Input, Output, Plot, Rotation, ScanReport, SensorConfig, SensorId, Session,
    SessionError, Track, TrackEvent, TrackId, TrackStatus, Tracker, TrackerConfig, TrackerError,
};
use rand::RngExt;
use rand_distr::{Distribution, StandardNormal};

const P: f64 = 5.0;
const SIGMA_R: f64 = 70.0;
const SIGMA_AZ: f64 = 0.08 * std::f64::consts::PI / 180.0;

/// One row as compared: what the tracks CSV shows of a track.
type Row = (
    TrackId,
    TrackStatus,
    f64,
    Vec<f64>,
    Option<argus_tracker::DeletionReason>,
);

fn row_of(t: &Track) -> Row {
    let g = t.estimate();
    let mut v: Vec<f64> = g.mean().iter().copied().collect();
    v.extend(g.cov().iter().copied());
    (t.id(), t.status(), t.time(), v, t.deletion())
}

fn rows_of(c: &Concluded) -> (ScanReport, Vec<Row>) {
    let rows = c
        .rows
        .iter()
        .map(|s| {
            let mut v: Vec<f64> = s.estimate.mean().iter().copied().collect();
            v.extend(s.estimate.cov().iter().copied());
            (s.id, s.status, s.time, v, s.deletion)
        })
        .collect();
    (c.report.clone(), rows)
}

/// The rows `argus track` wrote after each report of one tracker call (tally.rs before
/// the session): the deleted tracks taken, the live ones the report concerns, id order.
fn direct_rows(
    tracker: &mut Tracker,
    reports: Vec<ScanReport>,
    out: &mut Vec<(ScanReport, Vec<Row>)>,
) {
    for r in reports {
        let deleted = tracker.take_deleted();
        let mut all: Vec<&Track> = tracker
            .tracks()
            .iter()
            .filter(|tr| {
                !r.sector
                    || r.visited.binary_search(&tr.id()).is_ok()
                    || r.initiated.contains(&tr.id())
            })
            .chain(&deleted)
            .collect();
        all.sort_by_key(|tr| tr.id());
        let rows = all.into_iter().map(row_of).collect();
        out.push((r, rows));
    }
}

/// feed.rs's order, by direct tracker calls: groups of one `(time, sensor)`; with a
/// rotating sensor every sector ending by a group's time (or a marker) concluded first by
/// `advance_to`; markers advanced to; the end flushed.
fn direct(config: &TrackerConfig, plots: &[Plot], markers: &[f64]) -> Vec<(ScanReport, Vec<Row>)> {
    let mut tracker = Tracker::new(config.clone()).unwrap();
    let rotating = config.sensors.iter().any(|s| s.rotation.is_some());
    let mut out = Vec::new();
    let mut markers = markers.iter().copied().peekable();
    let mut start = 0;
    let sectors_to = |tracker: &mut Tracker, t: f64, out: &mut Vec<_>| {
        while let Some(end) = tracker.next_sector_end()
            && end <= t
        {
            let r = tracker.advance_to(end).unwrap();
            direct_rows(tracker, r, out);
        }
    };
    while start < plots.len() {
        let (t, s) = (plots[start].time(), plots[start].sensor());
        let len = plots[start..]
            .iter()
            .take_while(|p| p.sensor() == s && p.time().total_cmp(&t).is_eq())
            .count();
        let group = &plots[start..start + len];
        // Markers before the group's first plot (the CLI pushes those first).
        while let Some(m) = markers.next_if(|m| *m <= t) {
            sectors_to(&mut tracker, m, &mut out);
            let r = tracker.advance_to(m).unwrap();
            direct_rows(&mut tracker, r, &mut out);
        }
        if rotating {
            sectors_to(&mut tracker, t, &mut out);
            let r = tracker.process(group).unwrap();
            direct_rows(&mut tracker, r, &mut out);
        } else {
            let r = tracker.process_scan(t, s, group).unwrap();
            direct_rows(&mut tracker, vec![r], &mut out);
        }
        start += len;
    }
    for m in markers {
        sectors_to(&mut tracker, m, &mut out);
        let r = tracker.advance_to(m).unwrap();
        direct_rows(&mut tracker, r, &mut out);
    }
    if rotating {
        let r = tracker.flush();
        direct_rows(&mut tracker, r, &mut out);
    }
    out
}

/// The session's outputs over the same inputs (markers pushed before the plots they
/// precede, as `argus track` does); plot `k`'s tag is `k`.
fn session_outputs(session: &mut Session, plots: &[Plot], markers: &[f64]) -> Vec<Output> {
    let mut out = Vec::new();
    let mut markers = markers.iter().copied().peekable();
    for (k, p) in plots.iter().enumerate() {
        while let Some(m) = markers.next_if(|m| *m <= p.time()) {
            session.push(Input::Marker(m), &mut out).unwrap();
        }
        let input = Input::Plot {
            plot: *p,
            tag: k as u64,
        };
        session.push(input, &mut out).unwrap();
    }
    for m in markers {
        session.push(Input::Marker(m), &mut out).unwrap();
    }
    session.push(Input::End, &mut out).unwrap();
    out
}

fn scans(out: &[Output]) -> Vec<&Concluded> {
    out.iter()
        .filter_map(|o| match o {
            Output::Scan(c) => Some(c),
            Output::End(_) => None,
        })
        .collect()
}

/// Three Cartesian targets seen every 2 s by sensor 0 (P_D 0.85) with two clutter plots
/// per scan, 40 scans; seed 11.
fn synchronous_plots() -> Vec<Plot> {
    let mut rng = run_rng(11, 0);
    let r = Matrix::<2, 2>::identity() * 900.0;
    let mut plots = Vec::new();
    for k in 0..40 {
        let t = 2.0 * f64::from(k);
        for (x0, y0, vx, vy) in [
            (0.0, 0.0, 200.0, 0.0),
            (5e3, 8e3, -150.0, 50.0),
            (-2e4, 3e3, 0.0, 220.0),
        ] {
            if rng.random::<f64>() < 0.85 {
                let n: [f64; 2] = [
                    StandardNormal.sample(&mut rng),
                    StandardNormal.sample(&mut rng),
                ];
                let z = Vector::<2>::new(x0 + vx * t + 30.0 * n[0], y0 + vy * t + 30.0 * n[1]);
                plots.push(Plot::cartesian(t, SensorId(0), z, r).unwrap());
            }
        }
        for _ in 0..2 {
            let z = Vector::<2>::new(
                rng.random::<f64>() * 6e4 - 3e4,
                rng.random::<f64>() * 6e4 - 3e4,
            );
            plots.push(Plot::cartesian(t, SensorId(0), z, r).unwrap());
        }
    }
    plots
}

/// Four targets 20–60 km out seen by a clockwise 5-s radar at their beam-crossing times
/// (P_D 0.9), 30 revolutions; seed 5. Sorted by time.
fn rotating_plots(rotation: Rotation) -> Vec<Plot> {
    let mut rng = run_rng(5, 0);
    let deg = std::f64::consts::PI / 180.0;
    let targets = [
        (30e3, 20.0 * deg, 200.0, 180.0 * deg),
        (45e3, -70.0 * deg, 150.0, 30.0 * deg),
        (20e3, 140.0 * deg, 240.0, -90.0 * deg),
        (60e3, -150.0 * deg, 180.0, 10.0 * deg),
    ];
    let mut plots = Vec::new();
    for (r0, a0, v, h) in targets {
        let at = |t: f64| {
            (
                r0 * a0.cos() + v * h.cos() * t,
                r0 * a0.sin() + v * h.sin() * t,
            )
        };
        let mut after = 0.0;
        while after < 30.0 * P {
            let mut t = after;
            for _ in 0..6 {
                let (x, y) = at(t);
                t = rotation.crossing_after(y.atan2(x), after);
            }
            if rng.random::<f64>() < 0.9 {
                let (x, y) = at(t);
                let nr: f64 = StandardNormal.sample(&mut rng);
                let na: f64 = StandardNormal.sample(&mut rng);
                let p = Plot::polar(
                    t,
                    SensorId(1),
                    x.hypot(y) + SIGMA_R * nr,
                    y.atan2(x) + SIGMA_AZ * na,
                );
                plots.push(p.unwrap());
            }
            after = t + 0.5 * P;
        }
    }
    plots.sort_by(|a, b| a.time().total_cmp(&b.time()));
    plots
}

fn radar() -> SensorConfig {
    SensorConfig::polar(SensorId(1), [0.0, 0.0], SIGMA_R, SIGMA_AZ)
}

#[test]
fn synchronous_rows_equal_the_direct_calls() {
    let config = TrackerConfig::new(vec![SensorId(0)]);
    let plots = synchronous_plots();
    let expected = direct(&config, &plots, &[]);
    let mut session = Session::new(config).unwrap();
    let out = session_outputs(&mut session, &plots, &[]);
    let got: Vec<_> = scans(&out).into_iter().map(rows_of).collect();
    assert_eq!(got.len(), 40);
    assert_eq!(got, expected);
    // Tracks were made and kept (so the comparison is not of empty rows).
    assert!(got.iter().any(|(r, _)| !r.confirmed.is_empty()));
    // Every track of a synchronous scan has a row.
    let Some(Output::End(end)) = out.last() else {
        panic!("no end")
    };
    assert_eq!(end.len(), session.tracker().tracks().len());
    assert!(
        end.iter()
            .filter(|s| s.status == TrackStatus::Confirmed)
            .count()
            >= 3
    );
}

#[test]
fn rotating_rows_with_markers_equal_the_direct_calls() {
    let rotation = Rotation::clockwise(P);
    let config = TrackerConfig::new(vec![radar().with_rotation(rotation)]);
    let plots = rotating_plots(rotation);
    // A north marker every revolution, past the last plot too.
    let markers: Vec<f64> = (0..33).map(|k| P * f64::from(k)).collect();
    let expected = direct(&config, &plots, &markers);
    let mut session = Session::new(config).unwrap();
    let out = session_outputs(&mut session, &plots, &markers);
    let got: Vec<_> = scans(&out).into_iter().map(rows_of).collect();
    assert!(got.len() > 100, "{} sectors", got.len());
    assert_eq!(got, expected);
    assert!(got.iter().all(|(r, _)| r.sector));
    assert!(got.iter().map(|(r, _)| r.confirmed.len()).sum::<usize>() >= 4);
}

#[test]
fn rows_are_in_id_order_with_their_events() {
    let rotation = Rotation::clockwise(P);
    let config = TrackerConfig::new(vec![radar().with_rotation(rotation)]);
    let mut session = Session::new(config).unwrap();
    let out = session_outputs(&mut session, &rotating_plots(rotation), &[]);
    let (mut started, mut updated, mut missed) = (0, 0, 0);
    for c in scans(&out) {
        let ids: Vec<_> = c.rows.iter().map(|s| s.id).collect();
        assert!(ids.windows(2).all(|w| w[0] < w[1]), "{ids:?}");
        for s in &c.rows {
            match s.event {
                TrackEvent::Started => {
                    started += 1;
                    assert!(c.report.initiated.contains(&s.id));
                    assert!(s.plot.is_some());
                }
                TrackEvent::Confirmed => assert!(c.report.confirmed.contains(&s.id)),
                TrackEvent::Deleted => {
                    assert_eq!(s.status, TrackStatus::Deleted);
                    assert!(s.deletion.is_some());
                }
                TrackEvent::Updated => {
                    updated += 1;
                    // Updated at the plot's own time.
                    assert_eq!(s.plot.map(|p| p.time()), Some(s.time));
                }
                TrackEvent::Missed => {
                    missed += 1;
                    assert!(s.plot.is_none());
                }
            }
        }
    }
    assert!(
        started >= 4 && updated > 50 && missed > 0,
        "{started} {updated} {missed}"
    );
}

#[test]
fn an_error_names_the_plot_tag_and_the_session_goes_on() {
    let r = Matrix::<2, 2>::identity() * 900.0;
    let plot = |t: f64, s: u32| {
        Plot::cartesian(t, SensorId(s), Vector::<2>::new(200.0 * t, 0.0), r).unwrap()
    };
    let mut session = Session::new(TrackerConfig::new(vec![SensorId(0)])).unwrap();
    let mut out = Vec::new();
    session
        .push(
            Input::Plot {
                plot: plot(0.0, 0),
                tag: 10,
            },
            &mut out,
        )
        .unwrap();
    // Sensor 7 is not configured: its group (tags 11, 12) is refused when the next
    // plot arrives, naming its first plot's tag.
    session
        .push(
            Input::Plot {
                plot: plot(5.0, 7),
                tag: 11,
            },
            &mut out,
        )
        .unwrap();
    session
        .push(
            Input::Plot {
                plot: plot(5.0, 7),
                tag: 12,
            },
            &mut out,
        )
        .unwrap();
    let e = session
        .push(
            Input::Plot {
                plot: plot(10.0, 0),
                tag: 13,
            },
            &mut out,
        )
        .unwrap_err();
    assert!(
        matches!(e.error, TrackerError::UnknownSensor { index: 0, .. }),
        "{e:?}"
    );
    assert_eq!(e.tag, Some(11));
    // The scan at 0 was concluded before the refused group.
    assert_eq!(scans(&out).len(), 1);
    // Going on: the refused group is dropped, plot 13 pushed again is taken.
    out.clear();
    session
        .push(
            Input::Plot {
                plot: plot(10.0, 0),
                tag: 13,
            },
            &mut out,
        )
        .unwrap();
    session
        .push(
            Input::Plot {
                plot: plot(15.0, 0),
                tag: 14,
            },
            &mut out,
        )
        .unwrap();
    session.push(Input::End, &mut out).unwrap();
    let times: Vec<f64> = scans(&out).iter().map(|c| c.report.time).collect();
    assert_eq!(times, [10.0, 15.0]);
    assert_eq!(session.tracker().tracks().len(), 1);
    // A plot before the time processed: its own tag.
    let e: SessionError = {
        session
            .push(
                Input::Plot {
                    plot: plot(1.0, 0),
                    tag: 20,
                },
                &mut out,
            )
            .unwrap();
        session.push(Input::EndOfScan, &mut out).unwrap_err()
    };
    assert!(matches!(e.error, TrackerError::TimeOrder { .. }));
    assert_eq!(e.tag, Some(20));
    // A marker's error names no plot.
    let e = session.push(Input::Marker(2.0), &mut out).unwrap_err();
    assert_eq!(e.tag, None);
}

#[test]
fn a_rotation_before_the_first_plot_equals_configuring_it() {
    let rotation = Rotation::clockwise(P).with_north_time(1.25);
    let plots = rotating_plots(rotation);
    let mut configured =
        Session::new(TrackerConfig::new(vec![radar().with_rotation(rotation)])).unwrap();
    let expected = session_outputs(&mut configured, &plots, &[]);
    // Learnt from the stream: the sensor is configured synchronous.
    let mut learnt = Session::new(TrackerConfig::new(vec![radar()])).unwrap();
    let mut out = Vec::new();
    learnt
        .push(
            Input::Rotation {
                sensor: SensorId(1),
                rotation,
            },
            &mut out,
        )
        .unwrap();
    assert!(out.is_empty());
    let got = session_outputs(&mut learnt, &plots, &[]);
    assert!(scans(&got).len() > 100);
    assert_eq!(got, expected);
    // After the sensor's first plot: refused, the session unchanged.
    let before = learnt.tracker().config().clone();
    let e = learnt
        .push(
            Input::Rotation {
                sensor: SensorId(1),
                rotation: Rotation::clockwise(4.0),
            },
            &mut out,
        )
        .unwrap_err();
    assert!(
        matches!(e.error, TrackerError::LateRotation { .. }),
        "{e:?}"
    );
    assert_eq!(e.tag, None);
    assert_eq!(learnt.tracker().config(), &before);
    // An unknown sensor's rotation is refused too.
    let e = learnt
        .push(
            Input::Rotation {
                sensor: SensorId(9),
                rotation,
            },
            &mut out,
        )
        .unwrap_err();
    assert!(matches!(e.error, TrackerError::LateRotation { .. }));
}
