//! Embedding a smaller motion model in a larger common IMM state.

use argus_core_math::{Matrix, Vector};
use argus_motion_models::{LinearMotionModel, MotionModel};

use crate::ImmError;

/// A motion model of `NS` states lifted to a common state of `NC ≥ NS` states.
///
/// The first `NS` components of the common state are the small model's state and move
/// with it; the remaining `NC − NS` components (e.g. the turn rate of a CT model that
/// shares the IMM with a 4-state CV model) are held constant with a random-walk process
/// noise of `extra_q_rate · dt` per component: `F = diag(F_s, I)`, `Q = diag(Q_s, q dt I)`.
///
/// Order the common state so that the shared components come first (`[x, vx, y, vy, ω]`).
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001) §11.7.3 (IMM with a CV and a coordinated-turn model
/// of different dimensions, the CV model augmented by the turn rate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Embedded<Mo, const NS: usize, const NC: usize> {
    model: Mo,
    extra_q_rate: f64,
}

impl<Mo, const NS: usize, const NC: usize> Embedded<Mo, NS, NC> {
    /// Lifts `model` into `NC` states with random-walk rate `extra_q_rate` (≥ 0) on the extra ones.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] when `NS > NC` or `extra_q_rate` is negative or non-finite.
    pub fn new(model: Mo, extra_q_rate: f64) -> Result<Self, ImmError> {
        if NS > NC || NS == 0 {
            return Err(ImmError::InvalidParameter {
                what: "embedded state size",
                value: NS as f64,
                reason: "must be positive and at most the common state size",
            });
        }
        if !(extra_q_rate.is_finite() && extra_q_rate >= 0.0) {
            return Err(ImmError::InvalidParameter {
                what: "extra process-noise rate",
                value: extra_q_rate,
                reason: "must be finite and non-negative",
            });
        }
        Ok(Self {
            model,
            extra_q_rate,
        })
    }

    /// The embedded model.
    #[must_use]
    pub fn model(&self) -> &Mo {
        &self.model
    }
}

impl<Mo: MotionModel<NS>, const NS: usize, const NC: usize> MotionModel<NC>
    for Embedded<Mo, NS, NC>
{
    fn propagate(&self, x: &Vector<NC>, dt: f64) -> Vector<NC> {
        let small: Vector<NS> = x.fixed_rows::<NS>(0).into_owned();
        let mut out = *x;
        out.fixed_rows_mut::<NS>(0)
            .copy_from(&self.model.propagate(&small, dt));
        out
    }

    fn jacobian(&self, x: &Vector<NC>, dt: f64) -> Matrix<NC, NC> {
        let small: Vector<NS> = x.fixed_rows::<NS>(0).into_owned();
        let mut f = Matrix::<NC, NC>::identity();
        f.fixed_view_mut::<NS, NS>(0, 0)
            .copy_from(&self.model.jacobian(&small, dt));
        f
    }

    fn process_noise(&self, x: &Vector<NC>, dt: f64) -> Matrix<NC, NC> {
        let small: Vector<NS> = x.fixed_rows::<NS>(0).into_owned();
        let mut q = Matrix::<NC, NC>::zeros();
        q.fixed_view_mut::<NS, NS>(0, 0)
            .copy_from(&self.model.process_noise(&small, dt));
        for i in NS..NC {
            q[(i, i)] = self.extra_q_rate * dt;
        }
        q
    }
}

impl<Mo: LinearMotionModel<NS>, const NS: usize, const NC: usize> LinearMotionModel<NC>
    for Embedded<Mo, NS, NC>
{
    fn transition(&self, dt: f64) -> Matrix<NC, NC> {
        let mut f = Matrix::<NC, NC>::identity();
        f.fixed_view_mut::<NS, NS>(0, 0)
            .copy_from(&self.model.transition(dt));
        f
    }
}
