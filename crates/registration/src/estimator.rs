//! The stacked bias estimate `b = [β₁; …; β_S]` and its recursive least-squares update
//! with a pseudo-measurement `z = H_b b + w`, `w ~ N(0, R_b)` (seed 004 eqs (33)–(36)).
//!
//! The bias state has `4·S` components. Small systems use nalgebra stack matrices; large
//! ones faer (`benches/benches/registration.rs` measures where each wins, see
//! [`STACK_MAX_SENSORS`]).

use argus_core_math::dynamic::DynSpdFactor;
use argus_core_math::faer::{Mat, MatRef};
use argus_core_math::{Matrix, SpdFactor, Vector};

use crate::error::RegistrationError;

/// Largest sensor count for which [`Backend::Auto`] uses the stack (nalgebra) path.
/// Chosen from the criterion bench `registration/pseudo_update`: the stack path is faster
/// up to this size (see `docs/papers/004-bias-32.md`).
pub const STACK_MAX_SENSORS: usize = 4;

/// Which linear-algebra backend an update uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// Stack matrices up to [`STACK_MAX_SENSORS`] sensors, faer above.
    #[default]
    Auto,
    /// Always faer (heap, run-time size).
    Faer,
    /// Stack matrices whenever the size is one the crate instantiates (S = 2, 3, 4, 8, 16),
    /// faer otherwise. For benchmarking.
    Stack,
}

/// A linear pseudo-measurement of the stacked bias: `z = H b + w`, `Cov w = R`.
#[derive(Debug, Clone)]
pub struct PseudoMeasurement {
    pub(crate) z: Mat<f64>,
    pub(crate) h: Mat<f64>,
    pub(crate) r: Mat<f64>,
}

impl PseudoMeasurement {
    /// A pseudo-measurement from its parts: `z` (`M × 1`), `H` (`M × 4S`), `R` (`M × M`).
    ///
    /// # Errors
    /// [`RegistrationError::DimensionMismatch`], [`RegistrationError::Empty`] for `M = 0`,
    /// [`RegistrationError::Math`] for non-finite values or an `R` that is not positive definite.
    pub fn new(z: Mat<f64>, h: Mat<f64>, r: Mat<f64>) -> Result<Self, RegistrationError> {
        let m = z.nrows();
        if m == 0 {
            return Err(RegistrationError::Empty {
                what: "pseudo-measurement",
            });
        }
        dims("pseudo-measurement z columns", 1, z.ncols())?;
        dims("pseudo-measurement H rows", m, h.nrows())?;
        dims("pseudo-measurement R rows", m, r.nrows())?;
        all_finite(z.as_ref(), "pseudo-measurement z")?;
        all_finite(h.as_ref(), "pseudo-measurement H")?;
        DynSpdFactor::new(r.as_ref(), "pseudo-measurement R")?;
        Ok(Self { z, h, r })
    }

    /// The measurement dimension `M`.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.z.nrows()
    }

    /// The value `z`.
    #[must_use]
    pub fn z(&self) -> MatRef<'_, f64> {
        self.z.as_ref()
    }

    /// The regressor `H_b`.
    #[must_use]
    pub fn h(&self) -> MatRef<'_, f64> {
        self.h.as_ref()
    }

    /// The noise covariance `R_b`.
    #[must_use]
    pub fn r(&self) -> MatRef<'_, f64> {
        self.r.as_ref()
    }
}

fn dims(what: &'static str, expected: usize, got: usize) -> Result<(), RegistrationError> {
    if expected == got {
        Ok(())
    } else {
        Err(RegistrationError::DimensionMismatch {
            what,
            expected,
            got,
        })
    }
}

fn all_finite(m: MatRef<'_, f64>, what: &'static str) -> Result<(), RegistrationError> {
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            if !m[(i, j)].is_finite() {
                return Err(RegistrationError::NonFinite {
                    what,
                    value: m[(i, j)],
                });
            }
        }
    }
    Ok(())
}

/// The stacked bias estimate of `S` sensors, `b̂` (`4S`) with covariance `Σ`.
#[derive(Debug, Clone)]
pub struct BiasEstimator {
    sensors: usize,
    b: Mat<f64>,
    sigma: Mat<f64>,
    backend: Backend,
    updates: usize,
}

impl BiasEstimator {
    /// An estimator for `sensors` sensors from the prior `b̂ = 0` and a per-sensor prior
    /// covariance `Σ₀` (the same for every sensor, block diagonal), as in seed 004 §7.
    ///
    /// # Errors
    /// [`RegistrationError::Empty`] for zero sensors, [`RegistrationError::Math`] when `Σ₀`
    /// is not symmetric positive definite.
    pub fn new(sensors: usize, prior_cov: &Matrix<4, 4>) -> Result<Self, RegistrationError> {
        if sensors == 0 {
            return Err(RegistrationError::Empty { what: "sensor set" });
        }
        SpdFactor::new(prior_cov, "prior bias covariance")?;
        let d = 4 * sensors;
        let sigma = Mat::from_fn(d, d, |i, j| {
            if i / 4 == j / 4 {
                prior_cov[(i % 4, j % 4)]
            } else {
                0.0
            }
        });
        Ok(Self {
            sensors,
            b: Mat::zeros(d, 1),
            sigma,
            backend: Backend::Auto,
            updates: 0,
        })
    }

    /// An estimator from a full stacked prior `b̂₀` (`4S × 1`) and `Σ₀` (`4S × 4S`).
    ///
    /// # Errors
    /// [`RegistrationError::DimensionMismatch`] unless the sizes are a positive multiple of
    /// 4 and agree; [`RegistrationError::Math`] for non-finite values or a non-PD `Σ₀`.
    pub fn with_prior(b: Mat<f64>, sigma: Mat<f64>) -> Result<Self, RegistrationError> {
        let d = b.nrows();
        if d == 0 || !d.is_multiple_of(4) {
            return Err(RegistrationError::DimensionMismatch {
                what: "stacked bias length (a positive multiple of 4)",
                expected: 4 * (d / 4).max(1),
                got: d,
            });
        }
        dims("stacked bias columns", 1, b.ncols())?;
        dims("bias covariance rows", d, sigma.nrows())?;
        all_finite(b.as_ref(), "prior bias")?;
        DynSpdFactor::new(sigma.as_ref(), "prior bias covariance")?;
        Ok(Self {
            sensors: d / 4,
            b,
            sigma,
            backend: Backend::Auto,
            updates: 0,
        })
    }

    /// Chooses the linear-algebra backend (results agree to round-off).
    pub fn set_backend(&mut self, backend: Backend) {
        self.backend = backend;
    }

    /// The number of sensors `S`.
    #[must_use]
    pub fn sensors(&self) -> usize {
        self.sensors
    }

    /// How many pseudo-measurements have been applied.
    #[must_use]
    pub fn updates(&self) -> usize {
        self.updates
    }

    /// The stacked estimate `b̂` (`4S × 1`).
    #[must_use]
    pub fn stacked(&self) -> MatRef<'_, f64> {
        self.b.as_ref()
    }

    /// The stacked covariance `Σ` (`4S × 4S`).
    #[must_use]
    pub fn covariance(&self) -> MatRef<'_, f64> {
        self.sigma.as_ref()
    }

    /// Sensor `s`'s bias estimate `β̂_s` and its covariance block `Σ_ss`.
    ///
    /// # Errors
    /// [`RegistrationError::UnknownSensor`].
    pub fn sensor(&self, s: usize) -> Result<(Vector<4>, Matrix<4, 4>), RegistrationError> {
        if s >= self.sensors {
            return Err(RegistrationError::UnknownSensor {
                sensor: s,
                sensors: self.sensors,
            });
        }
        let o = 4 * s;
        Ok((
            Vector::<4>::from_fn(|i, _| self.b[(o + i, 0)]),
            Matrix::<4, 4>::from_fn(|i, j| self.sigma[(o + i, o + j)]),
        ))
    }

    /// The normalised estimation error squared `(b − b̂)ᵀ Σ⁻¹ (b − b̂)` for the true
    /// stacked bias `truth` (`4S` values).
    ///
    /// # Errors
    /// [`RegistrationError::DimensionMismatch`]; [`RegistrationError::Math`] if `Σ` cannot be factored.
    pub fn nees(&self, truth: &[f64]) -> Result<f64, RegistrationError> {
        let d = 4 * self.sensors;
        dims("true stacked bias", d, truth.len())?;
        let e = Mat::from_fn(d, 1, |i, _| {
            truth.get(i).copied().unwrap_or(0.0) - self.b[(i, 0)]
        });
        let f = DynSpdFactor::new(self.sigma.as_ref(), "bias covariance")?;
        let x = f.solve(e.as_ref())?;
        Ok((0..d).map(|i| e[(i, 0)] * x[(i, 0)]).sum())
    }

    /// Applies one pseudo-measurement, eqs (33)–(35):
    /// `K = Σ Hᵀ (H Σ Hᵀ + R)⁻¹`, `b̂ ← b̂ + K (z − H b̂)`, `Σ ← Σ − K H Σ` (symmetrised).
    /// Sequential application over the targets gives eq (36).
    ///
    /// # Errors
    /// [`RegistrationError::DimensionMismatch`] when `H` does not have `4S` columns,
    /// [`RegistrationError::Math`] when the innovation covariance is not positive definite,
    /// [`RegistrationError::Degenerate`] when the updated `Σ` has a non-positive or
    /// non-finite diagonal. On error the estimate is unchanged.
    pub fn update(&mut self, pm: &PseudoMeasurement) -> Result<(), RegistrationError> {
        let next = self.prepare(pm)?;
        self.commit(next);
        Ok(())
    }

    /// Computes the update of [`Self::update`] without applying it.
    pub(crate) fn prepare(
        &self,
        pm: &PseudoMeasurement,
    ) -> Result<(Mat<f64>, Mat<f64>), RegistrationError> {
        let d = 4 * self.sensors;
        dims("pseudo-measurement H columns", d, pm.h.ncols())?;
        let (b, sigma) = self.compute(pm)?;
        for i in 0..d {
            if sigma[(i, i)].is_nan() || sigma[(i, i)] <= 0.0 || !b[(i, 0)].is_finite() {
                return Err(RegistrationError::Degenerate {
                    what: "bias covariance",
                });
            }
        }
        Ok((b, sigma))
    }

    /// Applies an update computed by [`Self::prepare`].
    pub(crate) fn commit(&mut self, (b, sigma): (Mat<f64>, Mat<f64>)) {
        self.b = b;
        self.sigma = sigma;
        self.updates += 1;
    }

    fn compute(&self, pm: &PseudoMeasurement) -> Result<(Mat<f64>, Mat<f64>), RegistrationError> {
        let s = self.sensors;
        let m = pm.dim();
        let use_stack = match self.backend {
            Backend::Faer => false,
            Backend::Auto => s <= STACK_MAX_SENSORS,
            Backend::Stack => true,
        };
        if use_stack {
            macro_rules! try_stack {
                ($($d:literal, $m:literal);*) => {
                    $(if 4 * s == $d && m == $m {
                        return stack_update::<$d, $m>(self.b.as_ref(), self.sigma.as_ref(), pm);
                    })*
                };
            }
            // Proposed method: M = 2(S − 1); EXX: M = 2.
            try_stack!(8, 2; 12, 4; 12, 2; 16, 6; 16, 2; 32, 14; 32, 2; 64, 30; 64, 2);
        }
        faer_update(self.b.as_ref(), self.sigma.as_ref(), pm)
    }
}

#[allow(non_snake_case)]
fn stack_update<const D: usize, const M: usize>(
    b: MatRef<'_, f64>,
    sigma: MatRef<'_, f64>,
    pm: &PseudoMeasurement,
) -> Result<(Mat<f64>, Mat<f64>), RegistrationError> {
    let bv = Vector::<D>::from_fn(|i, _| b[(i, 0)]);
    let Sig = Matrix::<D, D>::from_fn(|i, j| sigma[(i, j)]);
    let H = Matrix::<M, D>::from_fn(|i, j| pm.h[(i, j)]);
    let R = Matrix::<M, M>::from_fn(|i, j| pm.r[(i, j)]);
    let z = Vector::<M>::from_fn(|i, _| pm.z[(i, 0)]);
    let U = Sig * H.transpose();
    let S = argus_core_math::symmetrize(&(H * U + R));
    let f = SpdFactor::new_symmetric(&S, "pseudo-measurement innovation covariance")?;
    let X = f.solve_matrix(&U.transpose()); // S⁻¹ Uᵀ = Kᵀ
    let nb = bv + X.transpose() * (z - H * bv);
    let ns = argus_core_math::symmetrize(&(Sig - U * X));
    Ok((
        Mat::from_fn(D, 1, |i, _| nb[i]),
        Mat::from_fn(D, D, |i, j| ns[(i, j)]),
    ))
}

#[allow(non_snake_case)]
fn faer_update(
    b: MatRef<'_, f64>,
    sigma: MatRef<'_, f64>,
    pm: &PseudoMeasurement,
) -> Result<(Mat<f64>, Mat<f64>), RegistrationError> {
    let d = b.nrows();
    let H = pm.h.as_ref();
    let U: Mat<f64> = sigma * H.transpose();
    let mut S: Mat<f64> = H * &U + &pm.r;
    let m = S.nrows();
    for i in 0..m {
        for j in 0..i {
            let v = 0.5 * (S[(i, j)] + S[(j, i)]);
            S[(i, j)] = v;
            S[(j, i)] = v;
        }
    }
    let f = DynSpdFactor::new(S.as_ref(), "pseudo-measurement innovation covariance")?;
    let X = f.solve(U.transpose())?; // S⁻¹ Uᵀ = Kᵀ
    let innov: Mat<f64> = &pm.z - H * b;
    let nb: Mat<f64> = b + &U * f.solve(innov.as_ref())?;
    let mut ns: Mat<f64> = sigma - &U * &X;
    for i in 0..d {
        for j in 0..i {
            let v = 0.5 * (ns[(i, j)] + ns[(j, i)]);
            ns[(i, j)] = v;
            ns[(j, i)] = v;
        }
    }
    Ok((nb, ns))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pm(s: usize, m: usize, seed: u64) -> PseudoMeasurement {
        // A deterministic pseudo-random pseudo-measurement.
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let d = 4 * s;
        let h = Mat::from_fn(m, d, |_, _| next());
        let z = Mat::from_fn(m, 1, |_, _| next());
        let a = Mat::from_fn(m, m, |_, _| next());
        let r: Mat<f64> = &a * a.transpose() + Mat::<f64>::identity(m, m);
        PseudoMeasurement::new(z, h, r).unwrap()
    }

    #[test]
    fn stack_and_faer_agree() {
        // Same algebra on two backends: agreement to round-off (1e-10 relative).
        for (s, m) in [(2, 2), (3, 4), (4, 6), (8, 14)] {
            let p = pm(s, m, 7 + s as u64);
            let prior = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(1e4, 0.04, 1e-4, 1e-2));
            let mut a = BiasEstimator::new(s, &prior).unwrap();
            let mut b = a.clone();
            a.set_backend(Backend::Stack);
            b.set_backend(Backend::Faer);
            a.update(&p).unwrap();
            b.update(&p).unwrap();
            for i in 0..4 * s {
                assert!((a.b[(i, 0)] - b.b[(i, 0)]).abs() < 1e-10 * (1.0 + a.b[(i, 0)].abs()));
                for j in 0..4 * s {
                    let x = a.sigma[(i, j)];
                    assert!((x - b.sigma[(i, j)]).abs() < 1e-10 * (1.0 + x.abs()) * 1e4);
                }
            }
        }
    }

    #[test]
    fn scalar_update_matches_closed_form() {
        // One sensor, z = b_r + w, prior var 4, R = 1 (padded with a second row on b_θ):
        // posterior var 4·1/(4+1) = 0.8, mean 4/5·z.
        let prior = Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(4.0, 4.0, 4.0, 4.0));
        let mut e = BiasEstimator::new(1, &prior).unwrap();
        let h = Mat::from_fn(2, 4, |i, j| if i == j { 1.0 } else { 0.0 });
        let z = Mat::from_fn(2, 1, |i, _| if i == 0 { 2.5 } else { 0.0 });
        e.update(&PseudoMeasurement::new(z, h, Mat::identity(2, 2)).unwrap())
            .unwrap();
        let (b, s) = e.sensor(0).unwrap();
        assert!((b[0] - 2.0).abs() < 1e-12);
        assert!((s[(0, 0)] - 0.8).abs() < 1e-12);
        assert!((s[(2, 2)] - 4.0).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_rejected_and_estimate_kept() {
        let prior = Matrix::<4, 4>::identity();
        assert!(matches!(
            BiasEstimator::new(0, &prior),
            Err(RegistrationError::Empty { .. })
        ));
        assert!(BiasEstimator::new(2, &(-prior)).is_err());
        let mut e = BiasEstimator::new(2, &prior).unwrap();
        let before = (e.b.clone(), e.sigma.clone());
        let wrong = pm(3, 4, 1); // 12 columns for an 8-state estimator
        assert!(matches!(
            e.update(&wrong),
            Err(RegistrationError::DimensionMismatch { .. })
        ));
        assert_eq!(before.0, e.b);
        assert_eq!(before.1, e.sigma);
        assert!(
            PseudoMeasurement::new(Mat::zeros(0, 1), Mat::zeros(0, 8), Mat::zeros(0, 0)).is_err()
        );
        let nan = Mat::from_fn(2, 1, |_, _| f64::NAN);
        assert!(PseudoMeasurement::new(nan, Mat::zeros(2, 8), Mat::identity(2, 2)).is_err());
        assert!(
            PseudoMeasurement::new(
                Mat::zeros(2, 1),
                Mat::zeros(2, 8),
                -Mat::<f64>::identity(2, 2)
            )
            .is_err()
        );
        assert!(e.sensor(2).is_err());
        assert!(e.nees(&[0.0; 3]).is_err());
        assert!(BiasEstimator::with_prior(Mat::zeros(5, 1), Mat::identity(5, 5)).is_err());
    }
}
