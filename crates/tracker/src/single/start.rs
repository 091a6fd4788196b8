//! What the single-target estimators share: the plots' sensors and their conversion to
//! a Cartesian position, errors at the plots' tags, and the one two-point start of a
//! track.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::FilterError;
use argus_sensors::Measurement;

use super::error::SingleError;
use super::estimator::{unbiased, unbiased3};
use super::output::TaggedPlot;
use super::spec::SingleSensor;
use crate::smooth::Smoothing;

/// A converted plot: a global Cartesian position and its covariance.
pub(super) type Converted<const D: usize> = (Vector<D>, Matrix<D, D>);

/// The sensors and smoothing of a single-target run, to convert plots and name errors.
pub(super) struct Ctx<'a> {
    pub(super) sensors: &'a [SingleSensor],
    /// `--smooth` / `--smooth-lag`.
    pub(super) smoothing: Option<Smoothing>,
}

impl Ctx<'_> {
    /// The sensor of `p`.
    pub(super) fn sensor(&self, p: &TaggedPlot) -> Result<&SingleSensor, SingleError> {
        self.sensors
            .iter()
            .find(|s| s.id == p.sensor())
            .ok_or(SingleError::UnknownSensor {
                tag: p.tag,
                sensor: p.sensor(),
            })
    }

    /// Range and azimuth σ of the plot's sensor.
    pub(super) fn polar_sigmas(&self, s: &SingleSensor) -> Result<(f64, f64), SingleError> {
        s.polar.ok_or(SingleError::NoPolarSigma { sensor: s.id })
    }

    /// Range, azimuth and elevation σ of the plot's sensor.
    pub(super) fn spherical_sigmas(&self, s: &SingleSensor) -> Result<[f64; 3], SingleError> {
        let (sr, sa) = self.polar_sigmas(s)?;
        let se = s
            .sigma_elevation
            .ok_or(SingleError::NoElevationSigma { sensor: s.id })?;
        Ok([sr, sa, se])
    }

    /// A filter step failed at plot `p`.
    pub(super) fn filter_error(&self, p: &TaggedPlot) -> impl Fn(FilterError) -> SingleError {
        let tag = p.tag;
        move |source| SingleError::FilterStep { tag, source }
    }

    /// An IMM step failed at plot `p`.
    pub(super) fn imm_error(&self, p: &TaggedPlot) -> impl Fn(argus_imm::ImmError) -> SingleError {
        let tag = p.tag;
        move |source| SingleError::ImmStep { tag, source }
    }

    /// A plot of another dimension than the first.
    fn wrong_dim(&self, p: &TaggedPlot) -> SingleError {
        SingleError::WrongDimension { tag: p.tag }
    }

    /// A 2-D plot as a global position: polar plots by the unbiased conversion with the
    /// sensor's σ, Cartesian reports as given.
    pub(super) fn convert2(&self, p: &TaggedPlot) -> Result<Converted<2>, SingleError> {
        let s = self.sensor(p)?;
        match p.measurement() {
            Measurement::Cartesian2(c) => Ok((*c.position(), *c.covariance())),
            Measurement::Polar(m) => {
                let (sr, sa) = self.polar_sigmas(s)?;
                let (z, r) = unbiased(m.range(), m.azimuth(), sr, sa)
                    .map_err(|source| SingleError::PolarConversion { tag: p.tag, source })?;
                Ok((z + Vector::<2>::new(s.position[0], s.position[1]), r))
            }
            Measurement::Spherical(_) | Measurement::Cartesian3(_) => Err(self.wrong_dim(p)),
        }
    }

    /// A 3-D plot as a global position: spherical plots by the unbiased conversion,
    /// Cartesian reports as given.
    pub(super) fn convert3(&self, p: &TaggedPlot) -> Result<Converted<3>, SingleError> {
        let s = self.sensor(p)?;
        match p.measurement() {
            Measurement::Cartesian3(c) => Ok((*c.position(), *c.covariance())),
            Measurement::Spherical(m) => {
                let sig = self.spherical_sigmas(s)?;
                let (z, r) = unbiased3(m.range(), m.azimuth(), m.elevation(), sig)
                    .map_err(|source| SingleError::SphericalConversion { tag: p.tag, source })?;
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

/// A track started from the first two plots.
pub(super) struct Started<'p, const N: usize> {
    /// The estimate at the second plot's time.
    pub(super) estimate: Gaussian<N>,
    /// The second plot.
    pub(super) second: &'p TaggedPlot,
    /// The plots after it.
    pub(super) rest: &'p [TaggedPlot],
}

/// The two-point start on the first two plots, converted by `convert`.
///
/// # Errors
/// [`SingleError::TooFewPlots`] when there are fewer than two plots, `convert`'s error,
/// or [`SingleError::Start`] at the second plot when the initialisation fails (e.g. the
/// same time twice).
pub(super) fn two_point<'p, const D: usize, const N: usize>(
    plots: &'p [TaggedPlot],
    convert: impl Fn(&TaggedPlot) -> Result<Converted<D>, SingleError>,
    init: TwoPoint<D, N>,
) -> Result<Started<'p, N>, SingleError> {
    let (Some(p1), Some(p2)) = (plots.first(), plots.get(1)) else {
        return Err(SingleError::TooFewPlots);
    };
    let (z1, r1) = convert(p1)?;
    let (z2, r2) = convert(p2)?;
    let estimate =
        init(&z1, &r1, &z2, &r2, p2.time() - p1.time()).map_err(|source| SingleError::Start {
            tag: p2.tag,
            source,
        })?;
    Ok(Started {
        estimate,
        second: p2,
        rest: plots.get(2..).unwrap_or(&[]),
    })
}
