//! The mixing rule between the 4-state CV modes and the 5-state CT mode.
//!
//! Into a CV mode the CT estimate enters through its marginal on `[x, vx, y, vy]` (the
//! turn rate is dropped: exact for a Gaussian). Into the CT mode a CV estimate `N(x̂ᵢ, Pᵢ)`
//! must first be given a turn rate; [`Augmentation`] says how.

use argus_core_math::{Gaussian, MathError, Matrix, Vector};

use crate::ImmError;
use crate::error::check_positive;

/// How a CV estimate (no turn rate) is extended to the CT mode's `[x, vx, y, vy, ω]` when
/// it is mixed into the CT mode.
///
/// # References
/// K. Granström, P. Willett & Y. Bar-Shalom, "Systematic approach to IMM mixing for
/// unequal dimension states", IEEE Trans. Aerospace and Electronic Systems 51(4),
/// 2975–2986, 2015: extending the smaller state with a fixed value (zero padding is the
/// special case `ω = 0`, variance 0) biases the mixed turn rate towards that value by the
/// weight of the smaller modes; extending it with the moments of the missing components
/// held by the larger mode(s) ("unbiased mixing") does not.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Augmentation {
    /// Granström et al.'s unbiased mixing: the CV estimate's missing turn rate takes the
    /// CT mode's own moments, `ω̂ = ω̂_CT`, `Var ω = P_CT,ωω`, uncorrelated with the CV
    /// estimate: `x̂ᵢᵃ = [x̂ᵢ; ω̂_CT]`, `Pᵢᵃ = diag(Pᵢ, P_CT,ωω)`. The mixed turn rate is
    /// then `ω̂_CT` whatever the mixing weights (no pull towards 0), and the mixed
    /// `Var ω` is `P_CT,ωω` (no spread term in ω). With several modes carrying `ω` the
    /// rule takes their moment-matched mixture; this estimator has one.
    Unbiased,
    /// A fixed extension: `ω = 0` with standard deviation `sigma` (rad/s),
    /// `x̂ᵢᵃ = [x̂ᵢ; 0]`, `Pᵢᵃ = diag(Pᵢ, sigma²)`. Zero padding (`sigma → 0`) is its
    /// limit; it cannot be represented exactly (the padded covariance is singular and is
    /// not a valid Gaussian), so take a small `sigma` to compare with it.
    Fixed {
        /// Standard deviation of the assumed turn rate (rad/s), positive.
        sigma: f64,
    },
}

impl Augmentation {
    /// Checks the parameters.
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] for a [`Augmentation::Fixed`] `sigma` that is not
    /// finite and positive.
    pub fn validate(&self) -> Result<(), ImmError> {
        match *self {
            Self::Unbiased => Ok(()),
            Self::Fixed { sigma } => check_positive("augmentation turn-rate sigma", sigma),
        }
    }

    /// The turn-rate mean and variance given to a CV estimate mixed into the CT mode
    /// whose current estimate is `ct`.
    pub(crate) fn turn_rate(&self, ct: &Gaussian<5>) -> (f64, f64) {
        match *self {
            Self::Unbiased => (ct.mean()[4], ct.cov()[(4, 4)]),
            Self::Fixed { sigma } => (0.0, sigma * sigma),
        }
    }
}

impl Default for Augmentation {
    /// [`Augmentation::Unbiased`].
    fn default() -> Self {
        Self::Unbiased
    }
}

/// The marginal of a CT estimate on the kinematic part `[x, vx, y, vy]` (its first four
/// components): a principal block of a positive-definite matrix, positive definite.
///
/// # Errors
/// [`MathError`] only if round-off broke definiteness (reported, never returned).
#[inline]
pub(crate) fn kinematic_marginal(ct: &Gaussian<5>) -> Result<Gaussian<4>, MathError> {
    let mean: Vector<4> = ct.mean().fixed_rows::<4>(0).into_owned();
    let cov: Matrix<4, 4> = ct.cov().fixed_view::<4, 4>(0, 0).into_owned();
    Gaussian::from_lower_triangle(mean, cov)
}

/// `N([x̂; ω], diag(P, var))`: a CV estimate extended by an independent turn rate.
///
/// # Errors
/// [`MathError`] when `omega` or `var` is not finite or `var` is not positive.
#[inline]
pub(crate) fn augmented(cv: &Gaussian<4>, omega: f64, var: f64) -> Result<Gaussian<5>, MathError> {
    let mut mean = Vector::<5>::zeros();
    mean.fixed_rows_mut::<4>(0).copy_from(cv.mean());
    mean[4] = omega;
    let mut cov = Matrix::<5, 5>::zeros();
    cov.fixed_view_mut::<4, 4>(0, 0).copy_from(cv.cov());
    cov[(4, 4)] = var;
    Gaussian::from_lower_triangle(mean, cov)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ct() -> Gaussian<5> {
        #[rustfmt::skip]
        let p = Matrix::<5, 5>::new(
            900.0, 30.0, 10.0, 0.0, 0.05,
            30.0, 25.0, 0.0, 1.0, 0.01,
            10.0, 0.0, 800.0, 20.0, -0.04,
            0.0, 1.0, 20.0, 16.0, 0.02,
            0.05, 0.01, -0.04, 0.02, 1e-4,
        );
        Gaussian::new(Vector::<5>::new(1e4, 150.0, -2e4, 30.0, 0.03), p).unwrap()
    }

    #[test]
    fn marginal_and_augmentation_are_exact_blocks() {
        let c = ct();
        let m = kinematic_marginal(&c).unwrap();
        assert_eq!(m.mean().as_slice(), &c.mean().as_slice()[..4]);
        assert_eq!(*m.cov(), c.cov().fixed_view::<4, 4>(0, 0).into_owned());
        let a = augmented(&m, 0.02, 4e-4).unwrap();
        assert_eq!(a.mean()[4].to_bits(), 0.02_f64.to_bits());
        assert_eq!(a.cov()[(4, 4)].to_bits(), 4e-4_f64.to_bits());
        assert!(a.cov().row(4).iter().take(4).all(|v| *v == 0.0));
        assert!(augmented(&m, f64::NAN, 1.0).is_err());
        assert!(augmented(&m, 0.0, 0.0).is_err());
    }

    #[test]
    fn unbiased_rule_keeps_the_turn_rate_and_fixed_rule_pulls_it_to_zero() {
        // Granström et al. (2015): mixing a CV estimate (weight 0.4) into the CT mode
        // (weight 0.6). Unbiased: mixed ω = ω̂_CT exactly and Var ω = P_CT,ωω.
        // Fixed ω = 0: mixed ω = 0.6 ω̂_CT (the bias the paper shows).
        let c = ct();
        let cv = kinematic_marginal(&c).unwrap();
        let w = [0.4, 0.6];
        let (om, var) = Augmentation::Unbiased.turn_rate(&c);
        let mix = Gaussian::mixture(&w, &[augmented(&cv, om, var).unwrap(), c]).unwrap();
        // Tolerance: round-off of a two-term weighted sum.
        assert!((mix.mean()[4] - 0.03).abs() < 1e-15);
        assert!((mix.cov()[(4, 4)] - 1e-4).abs() < 1e-18);
        let fixed = Augmentation::Fixed { sigma: 1e-6 };
        let (om, var) = fixed.turn_rate(&c);
        let mix = Gaussian::mixture(&w, &[augmented(&cv, om, var).unwrap(), c]).unwrap();
        assert!((mix.mean()[4] - 0.6 * 0.03).abs() < 1e-15);
        assert!(Augmentation::Fixed { sigma: 0.0 }.validate().is_err());
        assert!(Augmentation::Fixed { sigma: f64::NAN }.validate().is_err());
        assert!(Augmentation::Unbiased.validate().is_ok());
    }
}
