//! The documented tuning of the aircraft IMM and the filters it builds.

use argus_core_math::{Gaussian, Vector};
use argus_filters::Ekf;
use argus_motion_models::{CoordinatedTurnRate, Cv2D, MotionError};

use super::estimate::AircraftEstimate;
use super::estimator::AircraftImm;
use super::mixing::Augmentation;
use super::radar::AircraftRadar;
use super::start::{start_from_cv, two_point_start};
use crate::error::check_positive;
use crate::{ImmError, MarkovMatrix};

/// The aircraft IMM with EKFs: `C` CV modes (`Ekf<Cv2D>`, linear motion, polar update
/// linearised at the prediction) and the CT mode (`Ekf<CoordinatedTurnRate>`, analytic
/// Jacobian of the turn with its rate).
pub type AircraftEkf<const C: usize, const R: usize> =
    AircraftImm<Ekf<Cv2D>, Ekf<CoordinatedTurnRate>, C, R>;

/// Everything that tunes the aircraft IMM: process noise per mode, the transition matrix
/// per revisit, the start's turn-rate prior and mode probabilities, and the mixing rule.
/// [`AircraftTuning::build`] validates it once.
///
/// The default (`AircraftTuning::<2, 3>::default()`) is documented value by value on
/// [`AircraftTuning::default`]; docs/aircraft-imm.md gives the reasoning and the NEES and
/// RMSE it gives on simulated flights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftTuning<const C: usize, const R: usize> {
    /// Discrete white-noise acceleration σ_a of each CV mode, m/s².
    pub cv_sigma_a: [f64; C],
    /// σ_a of the CT mode's linear accelerations, m/s².
    pub ct_sigma_a: f64,
    /// σ_ω of the CT mode's turn-rate random walk, rad/s² (`ω' = ω + T w`, `w ~ N(0, σ_ω²)`).
    pub ct_sigma_omega: f64,
    /// Mode transition probabilities per plot (rows: from; CV modes, then CT).
    pub markov: [[f64; R]; R],
    /// Standard deviation of the CT mode's turn-rate prior at the start (mean 0), rad/s.
    pub start_sigma_omega: f64,
    /// Mode probabilities at the start.
    pub start_mu: [f64; R],
    /// The mixing rule for the turn rate.
    pub augmentation: Augmentation,
}

impl Default for AircraftTuning<2, 3> {
    /// Two CV modes and the CT mode, for civil aircraft seen by a 5-s surveillance radar:
    ///
    /// - CV "quiet", σ_a = 0.3 m/s²: straight, level legs (autopilot; a few m/s of speed
    ///   drift per minute).
    /// - CV "manoeuvre", σ_a = 2 m/s²: speed changes (0.5–2 m/s² along track), turn
    ///   entries and exits.
    /// - CT, σ_a = 0.5 m/s², σ_ω = 0.1 °/s² (the rate moves by ~0.5 °/s per 5-s revisit):
    ///   standard-rate turns of 1–3 °/s, established within two or three revisits.
    /// - Transitions per revisit (~5 s): CV quiet stays with 0.95 (mean leg ≈ 100 s),
    ///   the manoeuvre mode with 0.80 (≈ 25 s), CT with 0.90 (≈ 50 s, the 30–120 s turns);
    ///   `[[0.95, 0.03, 0.02], [0.10, 0.80, 0.10], [0.05, 0.05, 0.90]]`.
    /// - Start: `ω ~ N(0, (2 °/s)²)` (a standard-rate 3 °/s turn at 1.5 σ),
    ///   `μ₀ = (0.6, 0.2, 0.2)`.
    /// - Mixing: [`Augmentation::Unbiased`].
    fn default() -> Self {
        Self {
            cv_sigma_a: [0.3, 2.0],
            ct_sigma_a: 0.5,
            ct_sigma_omega: 0.1_f64.to_radians(),
            markov: [[0.95, 0.03, 0.02], [0.10, 0.80, 0.10], [0.05, 0.05, 0.90]],
            start_sigma_omega: 2.0_f64.to_radians(),
            start_mu: [0.6, 0.2, 0.2],
            augmentation: Augmentation::Unbiased,
        }
    }
}

/// A motion-model error after validation (cannot happen for checked values) as a
/// parameter error.
fn motion(what: &'static str, value: f64) -> impl Fn(MotionError) -> ImmError {
    move |_| ImmError::InvalidParameter {
        what,
        value,
        reason: "rejected by the motion model",
    }
}

impl<const C: usize, const R: usize> AircraftTuning<C, R> {
    /// Validates the tuning and builds the IMM.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for a σ that is not finite and positive (or a bad
    /// augmentation); [`ImmError::InvalidTransition`] / [`ImmError::RowSum`] for a bad
    /// Markov matrix; [`ImmError::InvalidProbabilities`] for bad start probabilities.
    pub fn build(&self) -> Result<AircraftEkf<C, R>, ImmError> {
        for s in self.cv_sigma_a {
            check_positive("CV sigma_a", s)?;
        }
        check_positive("CT sigma_a", self.ct_sigma_a)?;
        check_positive("CT sigma_omega", self.ct_sigma_omega)?;
        check_positive("start turn-rate sigma", self.start_sigma_omega)?;
        crate::log_probabilities(&self.start_mu, "start mode probabilities")?;
        let mut cv = [Ekf::new(Cv2D::discrete(1.0).map_err(motion("CV sigma_a", 1.0))?); C];
        for (f, s) in cv.iter_mut().zip(self.cv_sigma_a) {
            *f = Ekf::new(Cv2D::discrete(s).map_err(motion("CV sigma_a", s))?);
        }
        let ct = Ekf::new(
            CoordinatedTurnRate::new(self.ct_sigma_a, self.ct_sigma_omega)
                .map_err(motion("CT sigma", self.ct_sigma_a))?,
        );
        AircraftImm::new(cv, ct, MarkovMatrix::new(self.markov)?, self.augmentation)
    }

    /// The two-point start with this tuning's turn-rate prior and mode probabilities
    /// ([`two_point_start`]).
    ///
    /// # Errors
    /// As [`two_point_start`].
    pub fn start(
        &self,
        radar: &AircraftRadar,
        z1: &Vector<2>,
        z2: &Vector<2>,
        dt: f64,
    ) -> Result<AircraftEstimate<C, R>, ImmError> {
        two_point_start(radar, z1, z2, dt, self.start_sigma_omega, self.start_mu)
    }

    /// The start from a two-point CV estimate already made, with this tuning's turn-rate
    /// prior and mode probabilities ([`start_from_cv`]).
    ///
    /// # Errors
    /// As [`start_from_cv`].
    pub fn start_from_cv(&self, cv: &Gaussian<4>) -> Result<AircraftEstimate<C, R>, ImmError> {
        start_from_cv(cv, self.start_sigma_omega, self.start_mu)
    }
}
