//! The whole registration loop of seed 004 Fig. 1 for asynchronous sensors: each plot,
//! as soon as it arrives, (1) makes a pseudo bias measurement against the other sensors'
//! local tracks of the same target and updates the bias estimate, (2) updates its own
//! sensor's biased local track, and (3) makes the compensated track available. The EXX
//! baseline can run alongside on the same converted plots.

use argus_core_math::{Gaussian, Matrix, Vector};

use crate::error::{RegistrationError, finite};
use crate::estimator::BiasEstimator;
use crate::exx::ExxCollector;
use crate::local::{BiasedLocalFilter, BiasedTrack, position_matrix};
use crate::polar::{ConvertedPlot, Linearization, PolarSensor};
use crate::pseudo::pseudo_measurement;
use argus_sensors::PolarMeasurement;

/// How local tracks start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Initiation {
    /// Two-point differencing from the sensor's first two plots of the target (eqs (8)–(11)).
    #[default]
    TwoPoint,
    /// The caller supplies each track with [`Registrar::set_track`] (for example bias-free,
    /// `G = 0`, as in seed 004 §7); plots before that only feed the bias estimators.
    Given,
}

/// The configuration of a [`Registrar`].
#[derive(Debug, Clone, PartialEq)]
pub struct RegistrarConfig {
    /// The sensors (index = sensor id).
    pub sensors: Vec<PolarSensor>,
    /// Number of targets (index = target id; association is known).
    pub targets: usize,
    /// DCWNA process-noise PSD `q̃` (m²/s³) of the local filters.
    pub q_tilde: f64,
    /// Prior bias covariance `Σ₀` of each sensor (prior mean 0).
    pub prior_cov: Matrix<4, 4>,
    /// Where `B`, `C`, `R` are evaluated.
    pub linearization: Linearization,
    /// How local tracks start.
    pub initiation: Initiation,
    /// Also run the EXX baseline.
    pub run_exx: bool,
}

/// What one plot did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotOutcome {
    /// The converted plot.
    pub converted: ConvertedPlot,
    /// The proposed estimator was updated (some other sensor had a track of the target).
    pub proposed_updated: bool,
    /// The EXX estimator was updated (a slot filled).
    pub exx_updated: bool,
}

/// Multisensor, multitarget registration with biased local tracks (seed 004).
#[derive(Debug, Clone)]
pub struct Registrar {
    sensors: Vec<PolarSensor>,
    targets: usize,
    filter: BiasedLocalFilter,
    linearization: Linearization,
    initiation: Initiation,
    tracks: Vec<Option<BiasedTrack>>,
    pending: Vec<Option<ConvertedPlot>>,
    proposed: BiasEstimator,
    exx: Option<(BiasEstimator, ExxCollector)>,
}

impl Registrar {
    /// Builds the registrar.
    ///
    /// # Errors
    /// [`RegistrationError::Empty`] for no sensors or no targets; as
    /// [`BiasedLocalFilter::new`] and [`BiasEstimator::new`].
    pub fn new(config: RegistrarConfig) -> Result<Self, RegistrationError> {
        let s = config.sensors.len();
        if s == 0 {
            return Err(RegistrationError::Empty { what: "sensor set" });
        }
        if config.targets == 0 {
            return Err(RegistrationError::Empty { what: "target set" });
        }
        let proposed = BiasEstimator::new(s, &config.prior_cov)?;
        let exx = if config.run_exx {
            Some((proposed.clone(), ExxCollector::new(s, config.targets)?))
        } else {
            None
        };
        Ok(Self {
            filter: BiasedLocalFilter::new(config.q_tilde)?,
            tracks: vec![None; s * config.targets],
            pending: vec![None; s * config.targets],
            sensors: config.sensors,
            targets: config.targets,
            linearization: config.linearization,
            initiation: config.initiation,
            proposed,
            exx,
        })
    }

    fn index(&self, s: usize, t: usize) -> Result<usize, RegistrationError> {
        if s >= self.sensors.len() {
            return Err(RegistrationError::UnknownSensor {
                sensor: s,
                sensors: self.sensors.len(),
            });
        }
        if t >= self.targets {
            return Err(RegistrationError::InvalidParameter {
                what: "target index",
                value: t as f64,
                reason: "out of range",
            });
        }
        Ok(s * self.targets + t)
    }

    /// The local filter.
    #[must_use]
    pub fn filter(&self) -> &BiasedLocalFilter {
        &self.filter
    }

    /// The sensors.
    #[must_use]
    pub fn sensors(&self) -> &[PolarSensor] {
        &self.sensors
    }

    /// Sets (or replaces) sensor `s`'s local track of target `t`.
    ///
    /// # Errors
    /// [`RegistrationError::UnknownSensor`] / [`RegistrationError::InvalidParameter`] for an
    /// index out of range.
    pub fn set_track(
        &mut self,
        s: usize,
        t: usize,
        track: BiasedTrack,
    ) -> Result<(), RegistrationError> {
        let k = self.index(s, t)?;
        if let Some(slot) = self.tracks.get_mut(k) {
            *slot = Some(track);
        }
        Ok(())
    }

    /// Sensor `s`'s biased local track of target `t`, if started.
    #[must_use]
    pub fn track(&self, s: usize, t: usize) -> Option<&BiasedTrack> {
        self.index(s, t)
            .ok()
            .and_then(|k| self.tracks.get(k))
            .and_then(Option::as_ref)
    }

    /// The compensated track `X̂ᵇ − G β̂_s`, `P + G Σ_ss Gᵀ` (eqs (38), (41)) with the
    /// proposed method's current estimate; `None` while the track has not started.
    ///
    /// # Errors
    /// As [`BiasedTrack::compensated`].
    pub fn compensated(
        &self,
        s: usize,
        t: usize,
    ) -> Result<Option<Gaussian<4>>, RegistrationError> {
        let Some(track) = self.track(s, t) else {
            return Ok(None);
        };
        let (b, sig) = self.proposed.sensor(s)?;
        track.compensated(&b, &sig).map(Some)
    }

    /// The proposed method's estimator.
    #[must_use]
    pub fn proposed(&self) -> &BiasEstimator {
        &self.proposed
    }

    /// The EXX estimator, if it runs.
    #[must_use]
    pub fn exx(&self) -> Option<&BiasEstimator> {
        self.exx.as_ref().map(|(e, _)| e)
    }

    /// Processes sensor `s`'s plot of target `t` taken at `time` (Fig. 1 of seed 004).
    ///
    /// # Errors
    /// Index errors; [`RegistrationError::NonFinite`] / [`RegistrationError::InvalidParameter`]
    /// for a bad plot; [`RegistrationError::TimeNotIncreasing`] when the plot is earlier
    /// than sensor `s`'s track (or pending plot) of `t`, or earlier than another sensor's
    /// track used for the pseudo-measurement; numerical errors from the updates. On error
    /// nothing changes.
    pub fn process(
        &mut self,
        s: usize,
        t: usize,
        time: f64,
        plot: &PolarMeasurement,
    ) -> Result<PlotOutcome, RegistrationError> {
        let k = self.index(s, t)?;
        finite("plot time", time)?;
        let sensor = *self
            .sensors
            .get(s)
            .ok_or(RegistrationError::UnknownSensor {
                sensor: s,
                sensors: self.sensors.len(),
            })?;
        let own = self.tracks.get(k).copied().flatten();
        let own_pred = match &own {
            Some(tr) => Some(self.filter.predict(tr, time)?),
            None => None,
        };
        let at: Option<Vector<2>> = match (self.linearization, &own_pred) {
            (Linearization::AtPrediction, Some(p)) => Some(position_matrix() * p.estimate().mean()),
            _ => None,
        };
        let converted = sensor.convert(time, plot, at.as_ref())?;

        // (2) the new local track (computed now, committed last).
        let pending = self.pending.get(k).copied().flatten();
        let (new_track, new_pending) = match (own, self.initiation, pending) {
            (Some(tr), _, _) => (Some(self.filter.update(&tr, &converted)?), None),
            (None, Initiation::TwoPoint, Some(first)) => {
                (Some(BiasedTrack::two_point(&first, &converted)?), None)
            }
            (None, Initiation::TwoPoint, None) => (None, Some(converted)),
            (None, Initiation::Given, _) => (None, None),
        };

        // (1) the pseudo bias measurement against every other sensor's track of t.
        let others: Vec<(usize, &BiasedTrack)> = (0..self.sensors.len())
            .filter(|&j| j != s)
            .filter_map(|j| {
                self.tracks
                    .get(j * self.targets + t)
                    .and_then(Option::as_ref)
                    .map(|tr| (j, tr))
            })
            .collect();
        let proposed_next = if others.is_empty() {
            None
        } else {
            let pm = pseudo_measurement(&self.filter, self.sensors.len(), s, &converted, &others)?;
            Some(self.proposed.prepare(&pm)?)
        };

        // EXX on the same converted plot.
        let mut exx_updated = false;
        if let Some((est, coll)) = self.exx.as_mut() {
            let snap = coll.snapshot(t);
            let res = coll
                .push(t, s, converted)
                .and_then(|pm| pm.map(|pm| est.prepare(&pm)).transpose());
            match res {
                Ok(Some(next)) => {
                    est.commit(next);
                    exx_updated = true;
                }
                Ok(None) => {}
                Err(e) => {
                    if let Some(sn) = snap {
                        coll.restore(t, sn);
                    }
                    return Err(e);
                }
            }
        }

        let proposed_updated = proposed_next.is_some();
        if let Some(next) = proposed_next {
            self.proposed.commit(next);
        }
        if let Some(slot) = self.tracks.get_mut(k)
            && new_track.is_some()
        {
            *slot = new_track;
        }
        if let Some(slot) = self.pending.get_mut(k) {
            *slot = new_pending;
        }
        Ok(PlotOutcome {
            converted,
            proposed_updated,
            exx_updated,
        })
    }
}
