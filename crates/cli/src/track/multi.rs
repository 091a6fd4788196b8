//! The multi-target job: the tracker ([`argus_tracker`]) over the plot file, the plots
//! grouped into scans by `(time, sensor)` in file order, one row per track per scan with
//! its id and status, and a JSON summary (see `docs/FORMATS.md`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use argus_sensors::Measurement;
use argus_tracker::{
    AssociationConfig, DeletionReason, EstimatorConfig, Plot, ScanReport, SensorId, Track,
    TrackStatus, Tracker, TrackerConfig, TrackerError,
};

use super::feed::Feed;
use super::geo::Reference;
use super::multi_smooth::Recorded;
use super::rows::{Column, Point, TrackRows};
use super::smooth::Smoothing;
use super::tracker_config::MultiTarget;
use crate::error::CliError;
use crate::output::{AtomicFile, write_atomic};
use crate::plotfile::FilePlot;

/// Where the run's inputs and outputs are, for errors and the summary.
pub(super) struct Files<'a> {
    /// The configuration.
    pub(super) config: &'a Path,
    /// The plot file.
    pub(super) plots: &'a Path,
    /// The tracks CSV to write.
    pub(super) out: &'a Path,
    /// The system reference point (`lat, lon` columns).
    pub(super) reference: Option<&'a Reference>,
    /// `--smooth` / `--smooth-lag` ([`super::multi_smooth`]).
    pub(super) smoothing: Option<Smoothing>,
    /// Times the tracker advances to with no plot (an ASTERIX file's CAT034 messages,
    /// [`super::source`]), in order.
    pub(super) markers: &'a [f64],
}

/// Gives the sensors the rotations an ASTERIX file's CAT034 messages state (the
/// configured direction kept; a geodetic site's `north_time` moved by its grid rotation
/// `γ`, as a configured one is, [`super::spec::turned`]).
pub(super) fn set_rotations(
    m: &mut MultiTarget,
    rotations: &[super::source::MessageRotation],
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
            s.rotation = Some(super::spec::turned(stated, gamma));
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

/// One row: the track's state at its time, as produced by the scan of `sensor`; with
/// smoothing, kept until the end of the run ([`Recorded`]).
pub(super) fn row(
    out: &mut TrackRows,
    rec: Option<&mut Recorded>,
    sensor: SensorId,
    track: &Track,
) {
    if let Some(rec) = rec {
        rec.push(sensor, track);
        return;
    }
    let reason = track.deletion().map_or("", reason_name);
    let mu = track.mode_probabilities();
    let p = Point::new(track.time(), track.estimate())
        .of_track(sensor.0, track.id().0, status_name(track.status()), reason)
        .modes(mu.as_ref().map(|m| m.as_slice()))
        .noise(track.noise_estimate())
        .turn_rate(track.turn_rate())
        .score(track.score());
    out.push(&p);
}

/// The tracker's plot of a file plot: polar plots go in as they are (the tracker converts
/// them with its sensor's noise, or the EKF and multi-IMM use them directly), Cartesian
/// reports with their covariance.
pub(super) fn tracker_plot(files: &Files<'_>, p: &FilePlot) -> Result<Plot, CliError> {
    match p.measurement() {
        Measurement::Cartesian2(_) | Measurement::Polar(_) => Ok(p.plot),
        Measurement::Spherical(_) | Measurement::Cartesian3(_) => Err(CliError::input(
            files.plots,
            Some(p.line),
            None,
            "the multi-target tracker ([tracker]) tracks 2-D plots (polar or x, y); this plot is 3-D",
        )),
    }
}

/// A [`TrackerError`] about plot `index` of the plots handed to the tracker together,
/// whose file lines are `lines`, at that plot's line.
pub(super) fn plot_error(files: &Files<'_>, lines: &[u64], e: TrackerError) -> CliError {
    let (index, field) = match &e {
        TrackerError::TimeOrder { index, .. } => (*index, Some("t")),
        TrackerError::UnknownSensor { index, .. } => (*index, Some("sensor")),
        TrackerError::NoPolarNoise { index, .. } | TrackerError::NotPolar { index, .. } => {
            (*index, Some("sensor"))
        }
        TrackerError::NonPositiveRange { index, .. } | TrackerError::Conversion { index, .. } => {
            (*index, Some("range"))
        }
        TrackerError::NonFinite { index, .. }
        | TrackerError::PlotCovariance { index, .. }
        | TrackerError::MixedScan { index, .. } => (*index, None),
        _ => return CliError::Tracker(e),
    };
    let line = lines.get(index).copied();
    CliError::input(files.plots, line, field, format!("tracker: {e}"))
}

/// The CSV name of a status.
pub(super) fn status_name(s: TrackStatus) -> &'static str {
    match s {
        TrackStatus::Tentative => "tentative",
        TrackStatus::Confirmed => "confirmed",
        TrackStatus::Deleted => "deleted",
    }
}

/// The CSV and JSON name of a deletion reason.
pub(super) fn reason_name(r: DeletionReason) -> &'static str {
    match r {
        DeletionReason::NotConfirmed => "not-confirmed",
        DeletionReason::Misses => "misses",
        DeletionReason::CovarianceGrowth => "covariance-growth",
        DeletionReason::FilterFailure => "filter-failure",
        DeletionReason::Score => "score",
    }
}

/// Every deletion reason, for the summary's zero counts.
const REASONS: [DeletionReason; 5] = [
    DeletionReason::NotConfirmed,
    DeletionReason::Misses,
    DeletionReason::CovarianceGrowth,
    DeletionReason::FilterFailure,
    DeletionReason::Score,
];

/// Track counts over the run, for the summary.
#[derive(Debug, Default, serde::Serialize)]
struct Counts {
    initiated: usize,
    confirmed: usize,
    deleted: usize,
    deleted_by_reason: BTreeMap<&'static str, usize>,
    deleted_after_confirmation: usize,
    tentative_at_end: usize,
    confirmed_at_end: usize,
}

/// `<out>.summary.json`.
#[derive(Debug, serde::Serialize)]
struct Summary<'a> {
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

/// What the reports add up to, and the rows they give.
pub(super) struct Tally<'a> {
    out: &'a mut TrackRows,
    /// The smoothing recorder (`--smooth`): rows go there instead.
    recorded: Option<&'a mut Recorded>,
    counts: Counts,
    scans: usize,
    assigned: usize,
}

impl<'a> Tally<'a> {
    /// A tally writing its rows to `out`, or to `recorded` for smoothing.
    pub(super) fn new(out: &'a mut TrackRows, recorded: Option<&'a mut Recorded>) -> Self {
        Self {
            out,
            recorded,
            counts: Counts {
                deleted_by_reason: REASONS.iter().map(|r| (reason_name(*r), 0)).collect(),
                ..Counts::default()
            },
            scans: 0,
            assigned: 0,
        }
    }

    /// Counts one report (a scan or a sector) and writes its rows: every track of a
    /// synchronous scan; the tracks a sector visited (updated or missed), initiated (at
    /// the second plot's time, as a scan's first row of a track) and deleted. In id order (live tracks are in id order; a deleted one goes in its
    /// place).
    pub(super) fn record(&mut self, tracker: &mut Tracker, report: &ScanReport) {
        self.scans += 1;
        self.assigned += report.assigned;
        let counts = &mut self.counts;
        counts.initiated += report.initiated.len();
        counts.confirmed += report.confirmed.len();
        counts.deleted += report.deleted.len();
        let deleted = tracker.take_deleted();
        for d in &deleted {
            if let Some(r) = d.deletion() {
                *counts.deleted_by_reason.entry(reason_name(r)).or_insert(0) += 1;
            }
            if d.confirmed_at().is_some() {
                counts.deleted_after_confirmation += 1;
            }
        }
        let mut all: Vec<&Track> = tracker
            .tracks()
            .iter()
            .filter(|tr| {
                !report.sector
                    || report.visited.binary_search(&tr.id()).is_ok()
                    || report.initiated.contains(&tr.id())
            })
            .chain(&deleted)
            .collect();
        all.sort_by_key(|tr| tr.id());
        for tr in all {
            row(self.out, self.recorded.as_deref_mut(), report.sensor, tr);
        }
    }
}

/// The summary's path beside the tracks file: `<stem>.summary.json`.
fn summary_path(out: &Path) -> PathBuf {
    out.with_extension("summary.json")
}

/// Tracked rows are written once this much text is held (bytes).
const FLUSH_BYTES: usize = 1 << 16;

/// Runs the tracker over `plots` (read and checked one at a time by `plotfile`), writing
/// the rows as the scans and sectors conclude: memory does not grow with the file (but
/// with `--smooth`, which holds every confirmed track's rows until the end). The tracks
/// CSV goes to a temporary renamed at the end, so a bad plot anywhere stops the run with
/// nothing written; then the summary, atomically. Returns the number of rows and the
/// summary's path.
///
/// # Errors
/// [`CliError::Input`] naming the plot file's line for a bad plot or one the tracker
/// rejects; [`CliError::Io`].
pub(super) fn run(
    m: &MultiTarget,
    files: &Files<'_>,
    plots: impl Iterator<Item = Result<FilePlot, CliError>>,
) -> Result<(usize, PathBuf), CliError> {
    let c = &m.config;
    let mut recorded = match files.smoothing {
        Some(_) => Some(Recorded::new(c)?),
        None => None,
    };
    let mut tracker = Tracker::new(c.clone())?;
    let mut columns = columns(c);
    if let Some(rec) = &recorded {
        columns.extend(rec.columns());
    }
    let mut out = TrackRows::with_reference(columns, files.reference);
    let mut file = AtomicFile::create(files.out)?;
    let mut tally = Tally::new(&mut out, recorded.as_mut());
    let mut feed = Feed::new(c);
    let mut n_plots = 0;
    let mut markers = files.markers.iter().copied().peekable();
    for p in plots {
        let p = p?;
        while let Some(m) = markers.next_if(|m| *m <= p.time()) {
            feed.advance(&mut tracker, &mut tally, files, m)?;
        }
        feed.push(&mut tracker, &mut tally, files, &p)?;
        n_plots += 1;
        if tally.out.pending() >= FLUSH_BYTES {
            tally.out.write_to(&mut file)?;
        }
    }
    for m in markers {
        feed.advance(&mut tracker, &mut tally, files, m)?;
    }
    feed.finish(&mut tracker, &mut tally, files)?;
    let (scans, assigned, mut counts) = (tally.scans, tally.assigned, tally.counts);
    for tr in tracker.tracks() {
        match tr.status() {
            TrackStatus::Tentative => counts.tentative_at_end += 1,
            TrackStatus::Confirmed => counts.confirmed_at_end += 1,
            TrackStatus::Deleted => {}
        }
    }
    let smoothed_tracks = match (recorded, files.smoothing) {
        (Some(rec), Some(how)) => Some(rec.smooth_into(how, &mut out)?),
        _ => None,
    };
    let rows = out.rows();
    out.write_to(&mut file)?;
    file.commit()?;
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
    let path = summary_path(files.out);
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| CliError::io(&path, std::io::Error::other(e.to_string())))?;
    write_atomic(&path, json.as_bytes())?;
    Ok((rows, path))
}
