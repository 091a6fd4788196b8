//! The unscented RTS smoother's forward quantities: the UKF's prediction with the
//! sigma-point cross covariance (Särkkä 2008).

use argus_core_math::Gaussian;
use argus_motion_models::MotionModel;

use super::{SmoothingFilter, Transition};
use crate::{FilterError, Ukf};

impl<const N: usize, Mo: MotionModel<N>> SmoothingFilter<N> for Ukf<N, Mo> {
    /// The unscented prediction (the UKF's own, on the same sigma points) and
    /// `Cₖ₊₁ = Σᵢ Wᵢᶜ (χᵢ − x̂ₖ)(f(χᵢ) − x̂ₖ₊₁⁻)ᵀ` (Särkkä 2008, eqs (12)–(14)); the backward
    /// pass with this `C` is the unscented RTS smoother (eqs (15)–(17)).
    ///
    /// # Errors
    /// As [`crate::GaussianFilter::predict`].
    fn predict_with_cross(
        &self,
        prior: &Gaussian<N>,
        dt: f64,
    ) -> Result<Transition<N>, FilterError> {
        let (predicted, cross) = self.unscented_predict::<true>(prior, dt)?;
        Ok(Transition { predicted, cross })
    }
}
