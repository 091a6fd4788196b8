//! Helpers shared by the linearised filters (KF, EKF, second-order EKF, CD-EKF).

use argus_core_math::{Gaussian, MathError, Matrix, Vector, check_finite_matrix, kernels};
use argus_sensors::MeasurementModel;

use crate::{CovarianceForm, FilterError, MeasurementPrediction};

/// Builds an estimate from a filter stage's mean and covariance, naming the stage
/// in the error (`what_mean`, `what_cov`) when a value is non-finite or the
/// covariance is not positive definite.
#[inline(always)]
pub(crate) fn checked_gaussian<const N: usize>(
    mean: Vector<N>,
    cov: Matrix<N, N>,
    what_mean: &'static str,
    what_cov: &'static str,
) -> Result<Gaussian<N>, FilterError> {
    // `from_lower_triangle` checks the mean and tells a non-finite covariance from a
    // non-positive-definite one. Every filter's covariance is symmetric by construction;
    // its lower triangle is kept.
    Gaussian::from_lower_triangle(mean, cov).map_err(|e| match e {
        MathError::NotPositiveDefinite { .. } => {
            FilterError::Math(MathError::NotPositiveDefinite { what: what_cov })
        }
        MathError::NonFinite { what: "mean" } => {
            FilterError::Math(MathError::NonFinite { what: what_mean })
        }
        MathError::NonFinite { .. } => FilterError::Math(MathError::NonFinite { what: what_cov }),
        other => FilterError::Math(other),
    })
}

/// The linearised prediction `x⁻ = f`, `P⁻ = F P Fᵀ + Q` from a propagated mean,
/// the propagated covariance `F P Fᵀ` (the motion model's
/// [`argus_motion_models::MotionModel::propagate_covariance`], which exploits a
/// structured `F`) and the process noise `Q`. A non-finite `F` shows as a non-finite
/// predicted covariance.
#[allow(non_snake_case)]
#[inline]
pub(crate) fn covariance_predict<const N: usize>(
    mean: Vector<N>,
    FPFt: &Matrix<N, N>,
    Q: &Matrix<N, N>,
) -> Result<Gaussian<N>, FilterError> {
    let cov = FPFt + Q;
    // A non-finite `Q` makes the predicted covariance fail its test; only then is `Q`
    // examined, to name it as the cause.
    checked_gaussian(mean, cov, "predicted mean", "predicted covariance").map_err(|e| {
        check_finite_matrix(Q, "process noise Q")
            .err()
            .map_or(e, FilterError::Math)
    })
}

/// The first-order measurement prediction at the predicted mean:
/// `ẑ = h(x⁻)`, `H = ∂h/∂x(x⁻)`, `S = H P⁻ Hᵀ + R`, `P_xz = P⁻ Hᵀ`.
/// For a linear measurement `h(x) = H x` this is the Kalman filter's.
#[allow(non_snake_case)]
#[inline(always)]
pub(crate) fn first_order_measurement<const N: usize, const M: usize, Me>(
    predicted: &Gaussian<N>,
    meas: &Me,
    form: CovarianceForm,
) -> Result<MeasurementPrediction<N, M>, FilterError>
where
    Me: MeasurementModel<N, M>,
{
    let x = predicted.mean();
    let P = predicted.cov();
    let z_pred = meas.predict(x);
    let H = meas.jacobian(x);
    let R = meas.noise(x);
    check_finite_matrix(&R, "measurement noise R")?;
    if let Some(idx) = meas.selection().filter(|idx| idx.iter().all(|&i| i < N)) {
        // `H` selects entries: `P Hᵀ` is columns `idx` of `P`, `H P Hᵀ` rows `idx` of those.
        let mut PHt = Matrix::<N, M>::zeros();
        for (col, &i) in PHt.data.0.iter_mut().zip(&idx) {
            *col = P.data.0[i];
        }
        let S = Matrix::<M, M>::from_fn(|r, c| PHt[(idx[r], c)]) + R;
        return MeasurementPrediction::new(z_pred, S, PHt, Some(H), R, form);
    }
    // A non-finite `H` reaches the diagonal of `S` (through `H P Hᵀ`) and fails its
    // factorisation; only then is `H` examined, to name it as the cause.
    let PHt = kernels::mul_transpose(P, &H);
    let S = kernels::mul(&H, &PHt) + R;
    MeasurementPrediction::new(z_pred, S, PHt, Some(H), R, form).map_err(|e| {
        check_finite_matrix(&H, "measurement Jacobian H")
            .err()
            .map_or(e, FilterError::Math)
    })
}
