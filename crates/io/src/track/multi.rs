//! The multi-target job: the tracker ([`argus_tracker`]) over the plot file, the plots
//! grouped into scans by `(time, sensor)` in file order, one row per track per scan with
//! its id and status, and a JSON summary (see `docs/FORMATS.md`).

use std::path::{Path, PathBuf};

use crate::output::{AtomicFile, write_atomic};
use crate::plotfile::FilePlot;
use crate::rows::{Column, TrackRows};
use argus_config::MultiTarget;
use argus_tracker::{AssociationConfig, EstimatorConfig, Input, Output, Session, TrackerConfig};

use super::multi_files::{Files, plot_error, tracker_plot};
use super::multi_smooth::Recorded;
use super::smooth::Smoothing;
use super::tally::{Counts, Tally};
use crate::IoError;

/// Gives the sensors the rotations an ASTERIX file's CAT034 messages state (the
/// configured direction kept; a geodetic site's `north_time` moved by its grid rotation
/// `γ`, as a configured one is, [`argus_config::turned`]).
pub(super) fn set_rotations(
    m: &mut MultiTarget,
    rotations: &[crate::source::MessageRotation],
    grid_rotations: &[(u32, f64)],
) {
    for r in rotations {
        if let Some(s) = m.config.sensors.iter_mut().find(|s| s.id.0 == r.sensor) {
            let direction = s.rotation.map(|x| x.direction).unwrap_or_default();
            let gamma = grid_rotations
                .iter()
                .find(|(id, _)| *id == r.sensor)
                .map_or(0.0, |(_, g)| *g);
            let stated = argus_tracker::Rotation::clockwise(r.period)
                .with_direction(direction)
                .with_north_time(r.north_time);
            s.rotation = Some(argus_config::turned(stated, gamma));
        }
    }
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

/// Runs the tracker over `plots` (read and checked one at a time by `plotfile`). With a
/// file (`open` gives one, once the tracker is built), the rows are written to it as the
/// scans and sectors conclude: memory does not grow with the file (but with `--smooth`,
/// which holds every confirmed track's rows until the end); the caller writes the rest
/// and commits it. Without one, every row is kept. Returns the rows held, the file and
/// the summary.
///
/// # Errors
/// [`IoError::Input`] naming the plot file's line for a bad plot or one the tracker
/// rejects; [`IoError::Io`].
pub(super) fn run<'m, S: Sink>(
    m: &'m MultiTarget,
    files: &Files<'_>,
    plots: impl Iterator<Item = Result<FilePlot, IoError>>,
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
    let mut markers = files.markers.iter().copied().peekable();
    for p in plots {
        let p = p?;
        while let Some(m) = markers.next_if(|m| *m <= p.time()) {
            push(
                &mut session,
                &mut tally,
                files,
                Input::Marker(m),
                &mut outputs,
            )?;
        }
        let plot = tracker_plot(files, &p)?;
        let input = Input::Plot { plot, tag: p.line };
        push(&mut session, &mut tally, files, input, &mut outputs)?;
        n_plots += 1;
        file.flush(tally.out)?;
    }
    for m in markers {
        push(
            &mut session,
            &mut tally,
            files,
            Input::Marker(m),
            &mut outputs,
        )?;
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
    plots: impl Iterator<Item = Result<FilePlot, IoError>>,
) -> Result<(usize, PathBuf), IoError> {
    let (mut out, mut file, summary) = run(m, files, plots, || AtomicFile::create(files.out))?;
    let rows = out.rows();
    out.write_to(&mut file)?;
    file.commit()?;
    let path = summary_path(files.out);
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| IoError::io(&path, std::io::Error::other(e.to_string())))?;
    write_atomic(&path, json.as_bytes())?;
    Ok((rows, path))
}
