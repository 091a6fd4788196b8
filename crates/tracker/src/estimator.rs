//! The per-track estimator: one variant per kind, each holding its filters, and what
//! prediction, gating, update and initiation do for each. A new estimator is a variant
//! here, one of [`EstimatorState`], and one arm in each `match` below.

use argus_core_math::{Gaussian, Vector};
use argus_filters::{Ekf, GaussianFilter, Kf, MeasurementPrediction};
use argus_imm::{
    AircraftTuning, ImmEstimate, ImmPrediction, MultiImm, MultiImmEstimate, NoiseGrid,
    NoiseVariances, log_sum_exp, moment_match,
};
use argus_motion_models::Cv2D;
use argus_sensors::Polar2D;
use argus_sensors::PolarMeasurement;

use crate::aircraft::{self, Aircraft3, AircraftGate};
use crate::field::{ConfigField, EstimatorField};
use crate::innovation::{gate_box, imm_gate_box, imm_innovation, innovation, polar_half};
use crate::pda::{imm_jpda_update, jpda_update};
use crate::plot::{CartesianPlots, PolarModel, ScanPoint};
use crate::state::{EstimatorState, MULTI_IMM_HYPOTHESES, MultiState};
use crate::{EstimatorConfig, TrackerConfig, TrackerError, TwoModeImm, two_mode_imm};

/// The filters of the configured estimator, built once.
#[derive(Debug, Clone)]
pub(crate) enum Estimator {
    /// The CV Kalman filter on (converted) Cartesian plots.
    Kf(Kf<Cv2D>),
    /// The EKF on polar plots, and the same CV model's Kalman filter for Cartesian ones.
    Ekf {
        /// The polar update.
        ekf: Ekf<Cv2D>,
        /// The linear (Cartesian) update.
        kf: Kf<Cv2D>,
    },
    /// The two-mode CV IMM.
    Imm(TwoModeImm),
    /// Seed 000's multi-IMM noise estimator.
    MultiImm(MultiImm<Kf<Cv2D>, 4, 2, MULTI_IMM_HYPOTHESES>),
    /// The aircraft IMM, and its tuning (for the start).
    Aircraft {
        /// The IMM.
        imm: Aircraft3,
        /// Its tuning.
        tuning: AircraftTuning<2, 3>,
    },
}

/// One track's prediction as gating sees it.
///
/// A temporary on the stack, one per track per gating pass: the aircraft variant holds its
/// modes' measurement predictions by value (boxing them would allocate per track and
/// scan).
#[allow(clippy::large_enum_variant)]
pub(crate) enum TrackGate<'a> {
    /// The combined prediction, with the EKF's polar measurement prediction when the
    /// scan has polar plots for an EKF.
    Single {
        /// The prediction.
        pred: &'a Gaussian<4>,
        /// The EKF's polar prediction, its model and the conversion's stretch.
        polar: Option<(&'a MeasurementPrediction<4, 2>, &'a PolarModel)>,
    },
    /// Per-mode gating of an IMM track.
    Imm(&'a TwoModeImm, &'a ImmPrediction<4, 2>),
    /// Per-mode polar gating of an aircraft-IMM track.
    Aircraft(AircraftGate<'a>),
}

impl TrackGate<'_> {
    /// The grid query box that holds the gate `νᵀS⁻¹ν ≤ gamma` of every plot whose
    /// position variances are at most `r_max`.
    pub(crate) fn query_box(&self, gamma: f64, r_max: [f64; 2]) -> (Vector<2>, [f64; 2]) {
        match self {
            Self::Single { pred, polar } => {
                let (centre, mut half) = gate_box(pred, gamma, r_max);
                if let Some((mp, pm)) = polar {
                    let h = polar_half(mp, gamma, pm.conversion_stretch);
                    half = [half[0].max(h), half[1].max(h)];
                }
                (centre, half)
            }
            Self::Imm(_, ip) => imm_gate_box(ip, gamma, r_max),
            Self::Aircraft(g) => g.query_box(gamma),
        }
    }

    /// The plot's normalised distance and log-likelihood per m².
    #[inline]
    pub(crate) fn innovation(&self, p: &ScanPoint) -> Option<(f64, f64)> {
        match self {
            Self::Single { pred, polar } => {
                innovation(pred, polar.map(|(mp, pm)| (mp, &pm.model)), p)
            }
            Self::Imm(imm, ip) => imm_innovation(imm, ip, p),
            Self::Aircraft(g) => g.innovation(p),
        }
    }
}

impl Estimator {
    pub(crate) fn new(config: &TrackerConfig) -> Result<Self, TrackerError> {
        let cv = || Cv2D::discrete(config.sigma_a);
        // The CV model of `sigma_a` was built first for every estimator before: its
        // error, if any, still comes first.
        cv()?;
        Ok(match config.estimator {
            EstimatorConfig::Kf => Self::Kf(Kf::new(cv()?)),
            EstimatorConfig::Ekf => Self::Ekf {
                ekf: Ekf::new(cv()?),
                kf: Kf::new(cv()?),
            },
            EstimatorConfig::ImmCv2 {
                sigma_a_low,
                sigma_a_high,
                p_stay,
            } => Self::Imm(two_mode_imm(sigma_a_low, sigma_a_high, p_stay)?),
            EstimatorConfig::MultiImm {
                sigma_a_low,
                sigma_a_high,
                p_stay,
                grid_spacing,
                clip,
            } => {
                let bad = |field, value| TrackerError::InvalidConfig {
                    field: ConfigField::Estimator(field),
                    value,
                    reason: "the multi-IMM rejected it",
                };
                let grid = NoiseGrid::common(grid_spacing)
                    .map_err(|_| bad(EstimatorField::GridSpacing, grid_spacing))?;
                let imm = two_mode_imm(sigma_a_low, sigma_a_high, p_stay)?;
                Self::MultiImm(
                    MultiImm::new(imm, grid, clip)
                        .map_err(|_| bad(EstimatorField::Clip, clip.unwrap_or(f64::NAN)))?,
                )
            }
            // Validated field by field by `TrackerConfig::validate`; `build` checks again.
            EstimatorConfig::Aircraft { tuning } => Self::Aircraft {
                imm: tuning.build().map_err(|_| TrackerError::InvalidConfig {
                    field: ConfigField::Estimator(EstimatorField::Kind),
                    value: f64::NAN,
                    reason: "the aircraft IMM rejected its tuning",
                })?,
                tuning,
            },
        })
    }

    /// Whether Cartesian plots are accepted (the multi-IMM and the aircraft IMM need
    /// polar ones).
    pub(crate) fn takes_cartesian(&self) -> CartesianPlots {
        match self {
            Self::Kf(_) | Self::Ekf { .. } | Self::Imm(_) => CartesianPlots::Accepted,
            Self::MultiImm(_) => CartesianPlots::Refused("multi-IMM"),
            Self::Aircraft { .. } => CartesianPlots::Refused("aircraft IMM"),
        }
    }

    /// Whether the tracks gate polar plots in `(r, θ)` (the EKF), so that a scan of polar
    /// plots needs each track's [`Estimator::polar_prediction`]. (The aircraft IMM gates
    /// in `(r, θ)` per mode, through its own [`TrackGate::Aircraft`].)
    pub(crate) fn gates_polar(&self) -> bool {
        match self {
            Self::Ekf { .. } => true,
            Self::Kf(_) | Self::Imm(_) | Self::MultiImm(_) | Self::Aircraft { .. } => false,
        }
    }

    /// The state of a track started at `estimate` (two-point initiation; `reference`: the
    /// configured noise of the second plot's sensor, for the multi-IMM); `None` when it
    /// cannot start.
    pub(crate) fn start(
        &self,
        estimate: Gaussian<4>,
        reference: Option<NoiseVariances>,
    ) -> Option<EstimatorState> {
        match self {
            Self::Kf(_) | Self::Ekf { .. } => Some(EstimatorState::Plain),
            Self::Imm(_) => ImmEstimate::from_common(estimate, [0.5, 0.5])
                .ok()
                .map(EstimatorState::Imm),
            Self::MultiImm(_) => {
                let start = ImmEstimate::from_common(estimate, [0.5, 0.5]).ok()?;
                let reference = reference?;
                Some(EstimatorState::MultiImm(Box::new(MultiImmEstimate::new(
                    start, reference,
                ))))
            }
            Self::Aircraft { tuning, .. } => tuning
                .start_from_cv(&estimate)
                .ok()
                .map(|a| EstimatorState::Aircraft(Box::new(a))),
        }
    }

    /// Predicts a track over `dt` (`dt = 0`: unchanged): its combined prediction, and an
    /// IMM's mode-conditioned one pushed on `modes` (only IMM trackers keep those, a large
    /// value to move per track for nothing otherwise). A multi-IMM track's state becomes
    /// its prediction.
    pub(crate) fn predict(
        &self,
        state: &mut EstimatorState,
        estimate: &Gaussian<4>,
        dt: f64,
        modes: &mut Vec<Option<ImmPrediction<4, 2>>>,
    ) -> Option<Gaussian<4>> {
        match (self, state) {
            (Self::Kf(kf), _) => predict_single(kf, estimate, dt),
            (Self::Ekf { ekf, .. }, _) => predict_single(ekf, estimate, dt),
            (Self::Imm(imm), EstimatorState::Imm(est)) => {
                let p = if dt > 0.0 {
                    imm.predict(est, dt).ok()
                } else {
                    Some(est.into_prediction())
                };
                let combined = p.as_ref().and_then(|p| {
                    let w = p.log_predicted_probabilities().map(f64::exp);
                    moment_match(&w, p.modes()).ok()
                });
                modes.push(p);
                combined
            }
            (Self::MultiImm(multi), EstimatorState::MultiImm(m)) => {
                if dt > 0.0 {
                    **m = multi.predict(m, dt).ok()?;
                }
                m.combined().ok()
            }
            (Self::Aircraft { imm, .. }, EstimatorState::Aircraft(a)) => {
                aircraft::predict(imm, a, dt)
            }
            (Self::Imm(_), _) => {
                modes.push(None);
                None
            }
            (Self::MultiImm(_) | Self::Aircraft { .. }, _) => None,
        }
    }

    /// The EKF's measurement prediction for polar plots of `sensor`.
    pub(crate) fn polar_prediction(
        &self,
        pred: &Gaussian<4>,
        sensor: Option<&PolarModel>,
    ) -> Option<MeasurementPrediction<4, 2>> {
        match self {
            Self::Ekf { ekf, .. } => ekf.predict_measurement(pred, &sensor?.model).ok(),
            Self::Kf(_) | Self::Imm(_) | Self::MultiImm(_) | Self::Aircraft { .. } => None,
        }
    }

    /// The per-mode polar gate of an aircraft-IMM track (its state holds its prediction)
    /// for the plots of `sensor`; `None` for the other estimators or when it fails.
    pub(crate) fn aircraft_gate<'a>(
        &'a self,
        state: &'a EstimatorState,
        sensor: Option<&'a PolarModel>,
    ) -> Option<AircraftGate<'a>> {
        match (self, state) {
            (Self::Aircraft { imm, .. }, EstimatorState::Aircraft(a)) => {
                AircraftGate::new(imm, a, sensor?)
            }
            _ => None,
        }
    }

    /// Updates a track predicted at `pred` (`modes`: its IMM prediction) with its plot
    /// `hit`, or with its JPDA weights when `weights` is not empty, or coasts: the
    /// posterior and, for a single plot, its log-likelihood per m² (for the score). The
    /// track's `state` is updated; `None` when a filter step fails.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn update(
        &self,
        state: &mut EstimatorState,
        pred: Gaussian<4>,
        modes: Option<ImmPrediction<4, 2>>,
        hit: Option<usize>,
        weights: &[(usize, f64)],
        points: &[ScanPoint],
        sensor: Option<&PolarModel>,
    ) -> Option<(Gaussian<4>, Option<f64>)> {
        match (self, state) {
            (Self::Kf(kf), _) => single_update(&pred, hit, weights, points, |p| {
                let (post, innov) = kf.update(&pred, &p.model, &p.position).ok()?;
                Some((post, innov.log_likelihood()))
            }),
            (Self::Ekf { ekf, kf }, _) => {
                let polar = sensor.map(|pm| &pm.model);
                single_update(&pred, hit, weights, points, |p| {
                    ekf_update(ekf, kf, &pred, polar, p)
                })
            }
            (Self::Imm(imm), EstimatorState::Imm(est)) => {
                let ip = modes?;
                if weights.is_empty() {
                    imm_step(imm, ip, hit.map(|j| &points[j])).map(|(g, ll, e)| {
                        *est = e;
                        (g, ll)
                    })
                } else {
                    imm_jpda_update(imm, &ip, weights, points).map(|(g, e)| {
                        *est = e;
                        (g, None)
                    })
                }
            }
            (Self::MultiImm(multi), EstimatorState::MultiImm(m)) => match (hit, sensor) {
                (None, _) => Some((pred, None)),
                (Some(j), Some(pm)) => points[j]
                    .polar
                    .and_then(|z| multi_update(multi, m, pm, &z))
                    .map(|(state, g, ll)| {
                        **m = state;
                        (g, Some(ll))
                    }),
                (Some(_), None) => None,
            },
            // JPDA (its weights), a hit or a coast.
            (Self::Aircraft { imm, .. }, EstimatorState::Aircraft(a)) => match (hit, sensor) {
                (_, Some(pm)) if !weights.is_empty() => {
                    aircraft::jpda_update(imm, a, weights, points, pm).map(|g| (g, None))
                }
                (None, _) => Some((pred, None)),
                (Some(j), Some(pm)) => points[j]
                    .polar
                    .and_then(|z| aircraft::update(imm, a, pm, &z))
                    .map(|(g, ll)| (g, Some(ll))),
                (Some(_), None) => None,
            },
            (Self::Imm(_) | Self::MultiImm(_) | Self::Aircraft { .. }, _) => None,
        }
    }
}

/// Predicts a single-filter (KF or EKF) estimate over `dt` (`dt = 0`: unchanged).
fn predict_single<F: GaussianFilter<4>>(f: &F, est: &Gaussian<4>, dt: f64) -> Option<Gaussian<4>> {
    if dt <= 0.0 {
        return Some(*est);
    }
    f.predict(est, dt).ok()
}

/// A single-filter track's update: JPDA (PDA mixture) when it has weights, else with its
/// plot by `update` (posterior and log-likelihood), else its prediction.
fn single_update(
    pred: &Gaussian<4>,
    hit: Option<usize>,
    weights: &[(usize, f64)],
    points: &[ScanPoint],
    update: impl Fn(&ScanPoint) -> Option<(Gaussian<4>, f64)>,
) -> Option<(Gaussian<4>, Option<f64>)> {
    if !weights.is_empty() {
        return jpda_update(pred, weights, points, |p| update(p).map(|u| u.0)).map(|g| (g, None));
    }
    match hit {
        Some(j) => update(&points[j]).map(|(g, ll)| (g, Some(ll))),
        None => Some((*pred, None)),
    }
}

/// The EKF's update with one plot: a polar plot in `(r, θ)` through `polar` (its
/// log-likelihood per m² is the `(r, θ)` density divided by the Jacobian `r` of the polar
/// map, `dx dy = r dr dθ`), a Cartesian one through the linear update.
fn ekf_update(
    ekf: &Ekf<Cv2D>,
    kf: &Kf<Cv2D>,
    pred: &Gaussian<4>,
    polar: Option<&Polar2D<4>>,
    p: &ScanPoint,
) -> Option<(Gaussian<4>, f64)> {
    if let (Some(model), Some(z)) = (polar, p.polar) {
        let (post, innov) = ekf.update(pred, model, &z).ok()?;
        return Some((post, innov.log_likelihood() - z[0].ln()));
    }
    let (post, innov) = kf.update(pred, &p.model, &p.position).ok()?;
    Some((post, innov.log_likelihood()))
}

/// One IMM update (or coast through a miss): the moment-matched posterior with the
/// plot's total log-likelihood, and the IMM estimate; `None` on failure.
fn imm_step(
    imm: &TwoModeImm,
    pred: ImmPrediction<4, 2>,
    hit: Option<&ScanPoint>,
) -> Option<(Gaussian<4>, Option<f64>, ImmEstimate<4, 2>)> {
    let (est, ll) = match hit {
        Some(p) => {
            let u = imm.update(&pred, &p.model, &p.position).ok()?;
            (u.estimate, Some(u.log_likelihood))
        }
        None => (pred.into_estimate(), None),
    };
    Some((est.combined().ok()?, ll, est))
}

/// One multi-IMM update of a track whose state holds its prediction (from
/// [`MultiImm::predict`]): the new state, its combined estimate and the plot's
/// log-likelihood `ln (1/K) Σₘ Λᵐ` (per m², the hypotheses' measurements being converted
/// positions). `None` on failure.
fn multi_update(
    multi: &MultiImm<Kf<Cv2D>, 4, 2, MULTI_IMM_HYPOTHESES>,
    predicted: &MultiState,
    pm: &PolarModel,
    z: &Vector<2>,
) -> Option<(MultiState, Gaussian<4>, f64)> {
    let plot = PolarMeasurement::new(z[0], z[1]).ok()?;
    let u = multi.update(predicted, &plot, &pm.conversion).ok()?;
    let ll = log_sum_exp(&u.log_likelihoods) - (MULTI_IMM_HYPOTHESES as f64).ln();
    let combined = u.estimate.combined().ok()?;
    Some((u.estimate, combined, ll))
}
