//! What the single-target estimators share: the plots' sensors and their conversion to
//! a Cartesian position, errors at the plot file's lines, and the one two-point start of
//! a track.

use std::path::Path;

use argus_config::Reference;
use argus_config::Sensor;
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::FilterError;
use argus_io::plotfile::FilePlot;
use argus_sensors::Measurement;

use super::smooth::Smoothing;
use crate::error::CliError;
use crate::estimator::{unbiased, unbiased3};

/// A converted plot: a global Cartesian position and its covariance.
pub(super) type Converted<const D: usize> = (Vector<D>, Matrix<D, D>);

/// The files and sensors of a single-target run, to convert plots and name errors.
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
    /// The sensor of `p`.
    pub(super) fn sensor(&self, p: &FilePlot) -> Result<&Sensor, CliError> {
        self.sensors
            .iter()
            .find(|s| s.id == p.sensor())
            .ok_or_else(|| {
                CliError::input(
                    self.plots_path,
                    Some(p.line),
                    Some("sensor"),
                    format!(
                        "unknown sensor {} (not in {})",
                        p.sensor(),
                        self.config.display()
                    ),
                )
            })
    }

    /// Range and azimuth σ of the plot's sensor.
    pub(super) fn polar_sigmas(&self, s: &Sensor) -> Result<(f64, f64), CliError> {
        s.polar.ok_or_else(|| {
            CliError::input(
                self.config,
                None,
                Some("sigma_range"),
                format!(
                    "sensor {} reports polar/spherical plots but has no sigma_range / sigma_azimuth_deg",
                    s.id
                ),
            )
        })
    }

    /// Range, azimuth and elevation σ of the plot's sensor.
    pub(super) fn spherical_sigmas(&self, s: &Sensor) -> Result<[f64; 3], CliError> {
        let (sr, sa) = self.polar_sigmas(s)?;
        let se = s.sigma_elevation.ok_or_else(|| {
            CliError::input(
                self.config,
                None,
                Some("sigma_elevation_deg"),
                format!(
                    "sensor {} reports spherical plots but has no sigma_elevation_deg",
                    s.id
                ),
            )
        })?;
        Ok([sr, sa, se])
    }

    /// A filter step failed at plot `p`.
    pub(super) fn filter_error(&self, p: &FilePlot) -> impl Fn(FilterError) -> CliError {
        let (path, line) = (self.plots_path.to_path_buf(), p.line);
        move |e| {
            CliError::input(
                &path,
                Some(line),
                None,
                format!("filter update failed: {e}"),
            )
        }
    }

    /// An IMM step failed at plot `p`.
    pub(super) fn imm_error(&self, p: &FilePlot) -> impl Fn(argus_imm::ImmError) -> CliError {
        let (path, line) = (self.plots_path.to_path_buf(), p.line);
        move |e| CliError::input(&path, Some(line), None, format!("IMM update failed: {e}"))
    }

    /// A plot of another dimension than the file's first.
    fn wrong_dim(&self, p: &FilePlot) -> CliError {
        CliError::input(
            self.plots_path,
            Some(p.line),
            None,
            "plot of another dimension than the file's first plot",
        )
    }

    /// A 2-D plot as a global position: polar plots by the unbiased conversion with the
    /// sensor's σ, Cartesian reports as given.
    pub(super) fn convert2(&self, p: &FilePlot) -> Result<Converted<2>, CliError> {
        let s = self.sensor(p)?;
        match p.measurement() {
            Measurement::Cartesian2(c) => Ok((*c.position(), *c.covariance())),
            Measurement::Polar(m) => {
                let (sr, sa) = self.polar_sigmas(s)?;
                let (z, r) = unbiased(m.range(), m.azimuth(), sr, sa).map_err(|e| {
                    CliError::input(self.plots_path, Some(p.line), Some("range"), e.to_string())
                })?;
                Ok((z + Vector::<2>::new(s.position[0], s.position[1]), r))
            }
            Measurement::Spherical(_) | Measurement::Cartesian3(_) => Err(self.wrong_dim(p)),
        }
    }

    /// A 3-D plot as a global position: spherical plots by the unbiased conversion,
    /// Cartesian reports as given.
    pub(super) fn convert3(&self, p: &FilePlot) -> Result<Converted<3>, CliError> {
        let s = self.sensor(p)?;
        match p.measurement() {
            Measurement::Cartesian3(c) => Ok((*c.position(), *c.covariance())),
            Measurement::Spherical(m) => {
                let sig = self.spherical_sigmas(s)?;
                let (z, r) =
                    unbiased3(m.range(), m.azimuth(), m.elevation(), sig).map_err(|e| {
                        CliError::input(self.plots_path, Some(p.line), Some("range"), e.to_string())
                    })?;
                Ok((z + Vector::<3>::from(s.position), r))
            }
            Measurement::Polar(_) | Measurement::Cartesian2(_) => Err(self.wrong_dim(p)),
        }
    }
}

/// A two-point initialisation on `D`-dimensional positions
/// ([`argus_filters::two_point_cv2`], [`argus_filters::two_point_cv3`]).
pub(super) type TwoPoint<const D: usize, const N: usize> = fn(
    &Vector<D>,
    &Matrix<D, D>,
    &Vector<D>,
    &Matrix<D, D>,
    f64,
) -> Result<Gaussian<N>, FilterError>;

/// A track started from the file's first two plots.
pub(super) struct Started<'p, const N: usize> {
    /// The estimate at the second plot's time.
    pub(super) estimate: Gaussian<N>,
    /// The second plot.
    pub(super) second: &'p FilePlot,
    /// The plots after it.
    pub(super) rest: &'p [FilePlot],
}

/// The two-point start on the first two plots, converted by `convert`.
///
/// # Errors
/// [`CliError::Input`] when there are fewer than two plots, for a plot `convert` refuses,
/// or at the second plot when the initialisation fails (e.g. the same time twice).
pub(super) fn two_point<'p, const D: usize, const N: usize>(
    ctx: &Ctx<'_>,
    plots: &'p [FilePlot],
    convert: impl Fn(&FilePlot) -> Result<Converted<D>, CliError>,
    init: TwoPoint<D, N>,
) -> Result<Started<'p, N>, CliError> {
    let (Some(p1), Some(p2)) = (plots.first(), plots.get(1)) else {
        return Err(too_few(ctx));
    };
    let (z1, r1) = convert(p1)?;
    let (z2, r2) = convert(p2)?;
    let estimate = init(&z1, &r1, &z2, &r2, p2.time() - p1.time()).map_err(|e| {
        CliError::input(
            ctx.plots_path,
            Some(p2.line),
            Some("t"),
            format!("two-point initialisation: {e}"),
        )
    })?;
    Ok(Started {
        estimate,
        second: p2,
        rest: plots.get(2..).unwrap_or(&[]),
    })
}

/// Fewer than two plots.
pub(super) fn too_few(ctx: &Ctx<'_>) -> CliError {
    CliError::input(
        ctx.plots_path,
        None,
        None,
        "at least two plots are needed to start a track",
    )
}
