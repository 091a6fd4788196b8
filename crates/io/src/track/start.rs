//! What the single-target job hands the engine ([`argus_tracker::single`]) and takes back:
//! the files and sensors of the run, and the engine's errors as the command's, at the plot
//! file's lines and the configuration's keys.

use std::path::Path;

use argus_tracker::single::{MAX_MODELS, OneRadar, SingleError, SingleSensor};

use super::smooth::{SmoothFailure as _, Smoothing};
use crate::IoError;
use argus_config::{Reference, Sensor};

/// The files and sensors of a single-target run, to name errors and write rows.
pub(super) struct Ctx<'a> {
    pub(super) config: &'a Path,
    pub(super) plots_path: &'a Path,
    pub(super) sensors: &'a [Sensor],
    /// The system reference point (`lat, lon` columns).
    pub(super) reference: Option<&'a Reference>,
    /// `--smooth` / `--smooth-lag`.
    pub(super) smoothing: Option<Smoothing>,
}

impl Ctx<'_> {
    /// The sensors as the engine takes them.
    pub(super) fn engine_sensors(&self) -> Vec<SingleSensor> {
        self.sensors
            .iter()
            .map(|s| SingleSensor {
                id: s.id,
                position: s.position,
                polar: s.polar,
                sigma_elevation: s.sigma_elevation,
            })
            .collect()
    }

    /// The command's error for the engine's `e`: [`IoError::Input`] at the plot file's
    /// line (a plot's tag is its line) or the configuration's key, [`IoError::Smooth`]
    /// for track 1, the models' errors as they are.
    pub(super) fn error(&self, e: SingleError) -> IoError {
        let (config, plots) = (self.config, self.plots_path);
        let one_radar = |estimator: OneRadar| match estimator {
            OneRadar::MultiImm => "the multi-IMM estimates one polar radar's noise",
            _ => "the aircraft IMM tracks one 2-D radar's polar plots",
        };
        match e {
            SingleError::UnknownSensor { tag, sensor } => IoError::input(
                plots,
                Some(tag),
                Some("sensor"),
                format!("unknown sensor {sensor} (not in {})", config.display()),
            ),
            SingleError::NoPolarSigma { sensor } => IoError::input(
                config,
                None,
                Some("sigma_range"),
                format!(
                    "sensor {sensor} reports polar/spherical plots but has no sigma_range / sigma_azimuth_deg"
                ),
            ),
            SingleError::NoElevationSigma { sensor } => IoError::input(
                config,
                None,
                Some("sigma_elevation_deg"),
                format!("sensor {sensor} reports spherical plots but has no sigma_elevation_deg"),
            ),
            SingleError::SensorNoise { sensor, message } => IoError::input(
                config,
                None,
                Some("sigma_range"),
                format!("sensor {sensor}: {message}"),
            ),
            SingleError::WrongDimension { tag } => IoError::input(
                plots,
                Some(tag),
                None,
                "plot of another dimension than the file's first plot",
            ),
            SingleError::ImmNot2D => IoError::input(
                config,
                None,
                Some("estimator.kind"),
                format!(
                    "the IMM estimators track 2-D plots ([x, vx, y, vy]); {} holds 3-D plots",
                    plots.display()
                ),
            ),
            SingleError::ModeCount { count } => {
                IoError::Usage(format!("{count} IMM models: at most {MAX_MODELS}"))
            }
            SingleError::MultiSize { n } => {
                IoError::Usage(format!("multi-IMM with n = {n} is not built"))
            }
            SingleError::TooFewPlots => IoError::input(
                plots,
                None,
                None,
                "at least two plots are needed to start a track",
            ),
            SingleError::Start { tag, source } => IoError::input(
                plots,
                Some(tag),
                Some("t"),
                format!("two-point initialisation: {source}"),
            ),
            SingleError::AircraftStart { tag, source } => IoError::input(
                plots,
                Some(tag),
                Some("t"),
                format!("two-point initialisation: {source}"),
            ),
            SingleError::PolarConversion { tag, source } => {
                IoError::input(plots, Some(tag), Some("range"), source.to_string())
            }
            // The 3-D conversion's error went through `IoError::Sensor` ("sensor: …").
            SingleError::SphericalConversion { tag, source } => IoError::input(
                plots,
                Some(tag),
                Some("range"),
                IoError::from(source).to_string(),
            ),
            SingleError::OtherSensor {
                tag,
                estimator,
                sensor,
                first,
            } => IoError::input(
                plots,
                Some(tag),
                Some("sensor"),
                format!(
                    "{}: plot of sensor {sensor} after sensor {first}",
                    one_radar(estimator)
                ),
            ),
            SingleError::NotPolar { tag, estimator } => {
                let what = match estimator {
                    OneRadar::MultiImm => "a Cartesian report",
                    _ => "not a (range, azimuth) plot",
                };
                IoError::input(
                    plots,
                    Some(tag),
                    Some("sensor"),
                    format!("{}: {what}", one_radar(estimator)),
                )
            }
            SingleError::FilterStep { tag, source } => IoError::input(
                plots,
                Some(tag),
                None,
                format!("filter update failed: {source}"),
            ),
            SingleError::ImmStep { tag, source } => IoError::input(
                plots,
                Some(tag),
                None,
                format!("IMM update failed: {source}"),
            ),
            // The run's one track is track 1.
            SingleError::Smoothing(f) => f.into_cli(1),
            SingleError::Motion(e) => e.into(),
            SingleError::Sensor(e) => e.into(),
            SingleError::Imm(e) => e.into(),
            other => IoError::Usage(other.to_string()),
        }
    }
}
