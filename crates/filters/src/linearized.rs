//! Helpers shared by the linearised filters (KF, EKF, second-order EKF, CD-EKF).

use argus_core_math::{
    Gaussian, MathError, Matrix, Vector, check_finite_matrix, check_finite_vector, kernels,
};
use argus_sensors::MeasurementModel;

use argus_motion_models::MotionModel;

use crate::{CovarianceForm, FilterError, Innovation, MeasurementPrediction, check_dt};

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
    Gaussian::from_lower_triangle(mean, cov).map_err(|e| name_stage(e, what_mean, what_cov))
}

/// [`checked_gaussian`] into `estimate`, which is left unchanged on an error.
#[inline(always)]
pub(crate) fn assign_checked<const N: usize>(
    estimate: &mut Gaussian<N>,
    mean: Vector<N>,
    cov: Matrix<N, N>,
    what_mean: &'static str,
    what_cov: &'static str,
) -> Result<(), FilterError> {
    estimate
        .assign_lower_triangle(mean, cov)
        .map_err(|e| name_stage(e, what_mean, what_cov))
}

/// A Gaussian's construction error renamed for the filter stage that produced it.
fn name_stage(e: MathError, what_mean: &'static str, what_cov: &'static str) -> FilterError {
    match e {
        MathError::NotPositiveDefinite { .. } => {
            FilterError::Math(MathError::NotPositiveDefinite { what: what_cov })
        }
        MathError::NonFinite { what: "mean" } => {
            FilterError::Math(MathError::NonFinite { what: what_mean })
        }
        MathError::NonFinite { .. } => FilterError::Math(MathError::NonFinite { what: what_cov }),
        other => FilterError::Math(other),
    }
}

/// The linearised prediction `x⁻ = f(x, dt)`, `P⁻ = F P Fᵀ + Q` of the KF and the EKF,
/// from the motion model's [`MotionModel::predict_moments`] (which exploits a structured
/// `F` and `Q`). A non-finite `F` or `Q` shows as a non-finite predicted covariance; only
/// then is `Q` examined, to name it as the cause.
#[inline(always)]
pub(crate) fn linearized_predict<const N: usize, Mo: MotionModel<N>>(
    model: &Mo,
    prior: &Gaussian<N>,
    dt: f64,
) -> Result<Gaussian<N>, FilterError> {
    check_dt(dt)?;
    let x = prior.mean();
    let (mean, cov) = model.predict_moments(x, prior.cov(), dt);
    checked_gaussian(mean, cov, "predicted mean", "predicted covariance")
        .map_err(|e| name_process_noise(model, x, dt, e))
}

/// [`linearized_predict`] in place: `estimate` becomes the prediction, and is left
/// unchanged on an error.
#[inline(always)]
pub(crate) fn linearized_predict_in_place<const N: usize, Mo: MotionModel<N>>(
    model: &Mo,
    estimate: &mut Gaussian<N>,
    dt: f64,
) -> Result<(), FilterError> {
    check_dt(dt)?;
    let x = *estimate.mean();
    let (mean, cov) = model.predict_moments(&x, estimate.cov(), dt);
    assign_checked(
        estimate,
        mean,
        cov,
        "predicted mean",
        "predicted covariance",
    )
    .map_err(|e| name_process_noise(model, &x, dt, e))
}

/// The Kalman filter's cycle in place ([`crate::Kf`]'s `step_in_place`, whose docs say why
/// the prediction is checked for finiteness only): `estimate` becomes the posterior, and is
/// left unchanged on an error. Out of line: one call per mode of an IMM cycle, whose loop
/// stays small enough for the compiler to inline every product in here (fully inlined into
/// the cycle, the joseph update and the posterior covariance were left as calls, ~100
/// instructions more per mode).
#[inline(never)]
pub(crate) fn linearized_step_in_place<const N: usize, const M: usize, Mo, Me>(
    model: &Mo,
    form: CovarianceForm,
    estimate: &mut Gaussian<N>,
    dt: f64,
    meas: &Me,
    z: &Vector<M>,
) -> Result<Innovation<M>, FilterError>
where
    Mo: MotionModel<N>,
    Me: MeasurementModel<N, M>,
{
    check_dt(dt)?;
    let x = *estimate.mean();
    let (mean, mut cov) = model.predict_moments(&x, estimate.cov(), dt);
    // The lower triangle is what a prediction's covariance means (`checked_gaussian`).
    kernels::mirror_lower(&mut cov);
    // Named as the checked prediction names it: the mean first, then the covariance, or a
    // non-finite `Q` as its cause.
    if let Err(e) = check_finite_vector(&mean, "predicted mean")
        .and_then(|()| check_finite_matrix(&cov, "predicted covariance"))
    {
        return Err(name_process_noise(model, &x, dt, FilterError::Math(e)));
    }
    let mp = first_order_measurement_of(&mean, &cov, meas, form)?;
    let innov = mp.innovation(meas, z)?;
    let (post_mean, post_cov) = mp.posterior_moments(&mean, &cov, &innov.residual)?;
    assign_checked(
        estimate,
        post_mean,
        post_cov,
        "posterior mean",
        "posterior covariance",
    )?;
    Ok(innov)
}

/// A failed prediction's error, or a non-finite `Q` named as its cause (examined only
/// when the prediction failed).
#[cold]
fn name_process_noise<const N: usize, Mo: MotionModel<N>>(
    model: &Mo,
    x: &Vector<N>,
    dt: f64,
    e: FilterError,
) -> FilterError {
    check_finite_matrix(&model.process_noise(x, dt), "process noise Q")
        .err()
        .map_or(e, FilterError::Math)
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
    first_order_measurement_of(predicted.mean(), predicted.cov(), meas, form)
}

/// [`first_order_measurement`] from a predicted mean `x` and symmetric covariance `P`.
#[allow(non_snake_case)]
#[inline(always)]
fn first_order_measurement_of<const N: usize, const M: usize, Me>(
    x: &Vector<N>,
    P: &Matrix<N, N>,
    meas: &Me,
    form: CovarianceForm,
) -> Result<MeasurementPrediction<N, M>, FilterError>
where
    Me: MeasurementModel<N, M>,
{
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
