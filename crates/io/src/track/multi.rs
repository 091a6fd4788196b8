//! The multi-target job: the tracker's session ([`argus_tracker::Session`]) over the plot
//! file's events (one input each: the plots, grouped into scans by `(time, sensor)` in
//! file order, the markers and rotations of an ASTERIX file), one row per track per scan
//! with its id and status, and a JSON summary (see `docs/FORMATS.md`).

use std::path::{Path, PathBuf};

use crate::event::{Event, MessageRotation};
use crate::output::{AtomicFile, write_atomic};
use crate::rows::{Column, TrackRows};
use argus_config::MultiTarget;
use argus_tracker::{
    AssociationConfig, EstimatorConfig, Input, Output, Rotation, SensorId, Session, TrackerConfig,
};

use super::multi_files::{Files, plot_error, tracker_plot};
use super::multi_smooth::Recorded;
use super::smooth::Smoothing;
use super::tally::{Counts, Tally};
use crate::IoError;

/// The tracker's rotation of sensor `r.sensor` as an ASTERIX file's CAT034 messages state
/// it: the configured direction kept (clockwise by default), a geodetic site's
/// `north_time` moved by its grid rotation `γ` as a configured one is
/// ([`argus_config::turned`]).
fn stated(c: &TrackerConfig, r: &MessageRotation, grid_rotations: &[(u32, f64)]) -> Rotation {
    let direction = c
        .sensors
        .iter()
        .find(|s| s.id.0 == r.sensor)
        .and_then(|s| s.rotation)
        .map(|x| x.direction)
        .unwrap_or_default();
    let gamma = grid_rotations
        .iter()
        .find(|(id, _)| *id == r.sensor)
        .map_or(0.0, |(_, g)| *g);
    let stated = Rotation::clockwise(r.period)
        .with_direction(direction)
        .with_north_time(r.north_time);
    argus_config::turned(stated, gamma)
}

/// The tracks CSV's columns for a configuration: the IMMs add the mode probabilities,
/// the multi-IMM its noise estimate, the aircraft IMM its turn rate (before the score),
/// track-score management the score.
pub(super) fn columns(c: &TrackerConfig) -> Vec<Column> {
    let (modes, noise) = match c.estimator {
        EstimatorConfig::Kf | EstimatorConfig::Ekf => (0, false),
        EstimatorConfig::ImmCv2 { .. } => (2, false),
        EstimatorConfig::MultiImm { .. } => (2, true),
        EstimatorConfig::Aircraft { .. } => (3, false),
    };
    let mut cols = Column::tracker(modes, noise, c.score.is_some());
    if matches!(c.estimator, EstimatorConfig::Aircraft { .. }) {
        let at = cols.len() - usize::from(c.score.is_some());
        cols.splice(at..at, Column::TURN_RATE);
    }
    cols
}

/// Pushes `input` into the session and hands what it concludes to the tally (`outputs`: a
/// reused buffer, left empty).
///
/// # Errors
/// [`IoError::Input`] naming the plot's line for a plot the tracker refuses.
pub(super) fn push(
    session: &mut Session,
    tally: &mut Tally<'_>,
    files: &Files<'_>,
    input: Input,
    outputs: &mut Vec<Output>,
) -> Result<(), IoError> {
    let result = session.push(input, outputs);
    for o in outputs.drain(..) {
        match o {
            Output::Scan(c) => tally.record(c),
            Output::End(tracks) => tally.end(&tracks),
        }
    }
    result.map_err(|e| plot_error(files, e))
}

/// `<out>.summary.json`.
#[derive(Debug, serde::Serialize)]
pub(super) struct Summary<'a> {
    command: &'static str,
    config: String,
    plots_file: String,
    tracks_file: String,
    estimator: &'a str,
    association: &'static str,
    confirmation: String,
    plots: usize,
    scans: usize,
    plots_assigned: usize,
    rows: usize,
    tracks: Counts,
    /// With `--smooth` / `--smooth-lag`: the method.
    #[serde(skip_serializing_if = "Option::is_none")]
    smoothing: Option<String>,
    /// With smoothing: the tracks smoothed (those confirmed at some scan).
    #[serde(skip_serializing_if = "Option::is_none")]
    smoothed_tracks: Option<usize>,
}

/// The summary's path beside the tracks file: `<stem>.summary.json`.
pub(super) fn summary_path(out: &Path) -> PathBuf {
    out.with_extension("summary.json")
}

/// Tracked rows are written once this much text is held (bytes).
const FLUSH_BYTES: usize = 1 << 16;

/// Where [`run`] writes rows as they conclude: a file, or nowhere (`()`: every row kept).
pub(super) trait Sink {
    /// Writes `rows`' held text out when there is enough of it.
    ///
    /// # Errors
    /// [`IoError::Io`].
    fn flush(&mut self, rows: &mut TrackRows) -> Result<(), IoError>;
}

impl Sink for AtomicFile {
    fn flush(&mut self, rows: &mut TrackRows) -> Result<(), IoError> {
        if rows.pending() >= FLUSH_BYTES {
            rows.write_to(self)?;
        }
        Ok(())
    }
}

impl Sink for () {
    fn flush(&mut self, _: &mut TrackRows) -> Result<(), IoError> {
        Ok(())
    }
}

/// What [`run`] gives back: the rows not yet written (all of them without a file), the
/// sink, and the summary.
pub(super) type Ran<'a, S> = (TrackRows, S, Summary<'a>);

/// The session's input of `event` (a plot moved into the reference frame by the sites'
/// grid rotations); `None` for a rotation of a sensor the tracker does not have.
///
/// # Errors
/// [`IoError::Input`] for a 3-D plot.
fn input_of(
    c: &TrackerConfig,
    files: &Files<'_>,
    grid: &[(u32, f64)],
    event: Event,
) -> Result<Option<Input>, IoError> {
    Ok(match event {
        Event::Plot(p) => {
            let p = p.to_reference(grid);
            let plot = tracker_plot(files, &p)?;
            Some(Input::Plot { plot, tag: p.line })
        }
        Event::Marker(t) => Some(Input::Marker(t)),
        Event::Rotation(r) => {
            c.sensors
                .iter()
                .any(|s| s.id.0 == r.sensor)
                .then(|| Input::Rotation {
                    sensor: SensorId(r.sensor),
                    rotation: stated(c, &r, grid),
                })
        }
    })
}

/// Runs the tracker's session over `events` (plots read and checked one at a time by
/// `plotfile`, or an ASTERIX file's events; `grid` the sites' grid rotations). With a
/// file (`open` gives one, once the tracker is built), the rows are written to it as the
/// scans and sectors conclude: memory does not grow with the file (but with `--smooth`,
/// which holds every confirmed track's rows until the end); the caller writes the rest
/// and commits it. Without one, every row is kept. Returns the rows held, the file and
/// the summary.
///
/// # Errors
/// [`IoError::Input`] naming the plot file's line for a bad plot or one the tracker
/// rejects; [`IoError::Tracker`] for a rotation it refuses; [`IoError::Io`].
pub(super) fn run<'m, S: Sink>(
    m: &'m MultiTarget,
    files: &Files<'_>,
    grid: &[(u32, f64)],
    events: impl Iterator<Item = Result<Event, IoError>>,
    open: impl FnOnce() -> Result<S, IoError>,
) -> Result<Ran<'m, S>, IoError> {
    let c = &m.config;
    let mut recorded = match files.smoothing {
        Some(_) => Some(Recorded::new(c)?),
        None => None,
    };
    let mut session = Session::new(c.clone())?;
    let mut columns = columns(c);
    if let Some(rec) = &recorded {
        columns.extend(rec.columns());
    }
    let mut out = TrackRows::with_reference(columns, files.reference);
    let mut file = open()?;
    let mut tally = Tally::new(&mut out, recorded.as_mut());
    let mut outputs = Vec::new();
    let mut n_plots = 0;
    for e in events {
        let Some(input) = input_of(c, files, grid, e?)? else {
            continue;
        };
        let plot = matches!(input, Input::Plot { .. });
        push(&mut session, &mut tally, files, input, &mut outputs)?;
        if plot {
            n_plots += 1;
            file.flush(tally.out)?;
        }
    }
    push(&mut session, &mut tally, files, Input::End, &mut outputs)?;
    let (scans, assigned, counts) = (tally.scans, tally.assigned, tally.counts);
    let smoothed_tracks = match (recorded, files.smoothing) {
        (Some(rec), Some(how)) => Some(rec.smooth_into(how, &mut out)?),
        _ => None,
    };
    let rows = out.rows();
    let summary = Summary {
        command: "track",
        config: files.config.display().to_string(),
        plots_file: files.plots.display().to_string(),
        tracks_file: files.out.display().to_string(),
        estimator: m.estimator,
        association: match c.association {
            AssociationConfig::Gnn => "gnn",
            AssociationConfig::Jpda { .. } => "jpda",
        },
        confirmation: match &c.score {
            Some(_) => "score".to_owned(),
            None => format!("m-of-n {}/{}", c.confirm_m, c.confirm_n),
        },
        plots: n_plots,
        scans,
        plots_assigned: assigned,
        rows,
        tracks: counts,
        smoothing: files.smoothing.map(Smoothing::describe),
        smoothed_tracks,
    };
    Ok((out, file, summary))
}

/// [`run`] writing the tracks CSV to `files.out` (a temporary renamed at the end, so a
/// bad plot anywhere stops the run with nothing written), then the summary, atomically.
/// Returns the number of rows and the summary's path.
///
/// # Errors
/// As [`run`]; [`IoError::Io`] writing the files.
pub(super) fn run_to_files(
    m: &MultiTarget,
    files: &Files<'_>,
    grid: &[(u32, f64)],
    events: impl Iterator<Item = Result<Event, IoError>>,
) -> Result<(usize, PathBuf), IoError> {
    let open = || AtomicFile::create(files.out);
    let (mut out, mut file, summary) = run(m, files, grid, events, open)?;
    let rows = out.rows();
    out.write_to(&mut file)?;
    file.commit()?;
    let path = summary_path(files.out);
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| IoError::io(&path, std::io::Error::other(e.to_string())))?;
    write_atomic(&path, json.as_bytes())?;
    Ok((rows, path))
}
