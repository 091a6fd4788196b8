//! Chi-square quantiles, gates, NEES/NIS intervals and the unit-ball volume.

use statrs::distribution::{ChiSquared, ContinuousCDF};
use statrs::function::gamma::ln_gamma;

use crate::MathError;

fn chi2(dof: f64) -> Result<ChiSquared, MathError> {
    if !(dof.is_finite() && dof > 0.0) {
        return Err(MathError::OutOfDomain {
            what: "degrees of freedom",
            value: dof,
            domain: "(0, ∞)",
        });
    }
    ChiSquared::new(dof).map_err(|_| MathError::OutOfDomain {
        what: "degrees of freedom",
        value: dof,
        domain: "(0, ∞)",
    })
}

fn check_probability(p: f64, what: &'static str) -> Result<(), MathError> {
    if p.is_finite() && p > 0.0 && p < 1.0 {
        Ok(())
    } else {
        Err(MathError::OutOfDomain {
            what,
            value: p,
            domain: "(0, 1)",
        })
    }
}

/// The `p`-quantile of the chi-square distribution with `dof` degrees of freedom.
///
/// # Errors
/// [`MathError::OutOfDomain`] when `p ∉ (0, 1)` or `dof ≤ 0`.
pub fn chi2_quantile(p: f64, dof: f64) -> Result<f64, MathError> {
    check_probability(p, "probability")?;
    Ok(chi2(dof)?.inverse_cdf(p))
}

/// The chi-square CDF `P(X ≤ x)` with `dof` degrees of freedom.
///
/// # Errors
/// [`MathError::OutOfDomain`] when `dof ≤ 0` or `x` is not finite.
pub fn chi2_cdf(x: f64, dof: f64) -> Result<f64, MathError> {
    if !x.is_finite() {
        return Err(MathError::OutOfDomain {
            what: "x",
            value: x,
            domain: "finite",
        });
    }
    Ok(chi2(dof)?.cdf(x.max(0.0)))
}

/// The validation-gate threshold `γ` such that a measurement of dimension `dim`
/// from the target falls inside `νᵀS⁻¹ν ≤ γ` with probability `p_gate`.
///
/// # Errors
/// [`MathError::OutOfDomain`] when `p_gate ∉ (0, 1)` or `dim = 0`.
pub fn gate_threshold(p_gate: f64, dim: usize) -> Result<f64, MathError> {
    check_probability(p_gate, "gate probability")?;
    chi2_quantile(p_gate, dim as f64)
}

/// Volume `c_n = π^{n/2} / Γ(n/2 + 1)` of the unit ball in `n` dimensions
/// (`c₁ = 2`, `c₂ = π`, `c₃ = 4π/3`). The gate volume is `c_n γ^{n/2} |S|^{1/2}`.
#[must_use]
pub fn unit_ball_volume(n: usize) -> f64 {
    let h = n as f64 / 2.0;
    (h * std::f64::consts::PI.ln() - ln_gamma(h + 1.0)).exp()
}

/// A two-sided chi-square acceptance interval for an averaged statistic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChiSquareInterval {
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
}

impl ChiSquareInterval {
    /// Whether `x` lies inside `[lower, upper]`.
    #[must_use]
    pub fn contains(&self, x: f64) -> bool {
        x >= self.lower && x <= self.upper
    }
}

/// The two-sided `confidence` interval of the average NEES (ANEES) or NIS over
/// `runs` independent runs of a `dim`-dimensional statistic: `runs · ANEES` is
/// chi-square with `dim · runs` degrees of freedom, so the bounds are
/// `χ²_{dim·runs}((1 ∓ confidence)/2) / runs`.
///
/// Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking
/// and Navigation*, §5.4.2.
///
/// # Errors
/// [`MathError::OutOfDomain`] for `confidence ∉ (0, 1)`, `dim = 0` or `runs = 0`.
pub fn anees_interval(
    dim: usize,
    runs: usize,
    confidence: f64,
) -> Result<ChiSquareInterval, MathError> {
    check_probability(confidence, "confidence")?;
    let dof = (dim * runs) as f64;
    let runs_f = runs as f64;
    Ok(ChiSquareInterval {
        lower: chi2_quantile((1.0 - confidence) / 2.0, dof)? / runs_f,
        upper: chi2_quantile((1.0 + confidence) / 2.0, dof)? / runs_f,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_match_tables() {
        // Standard chi-square table values (e.g. Abramowitz & Stegun Table 26.8).
        assert!((chi2_quantile(0.95, 1.0).unwrap() - 3.841_458_820_694_124).abs() < 1e-9);
        assert!((chi2_quantile(0.99, 2.0).unwrap() - 9.210_340_371_976_18).abs() < 1e-9);
        assert!((chi2_quantile(0.975, 4.0).unwrap() - 11.143_286_781_877_8).abs() < 1e-8);
        // For 2 dof the CDF is 1 − exp(−x/2): closed form.
        assert!((chi2_cdf(3.0, 2.0).unwrap() - (1.0 - (-1.5f64).exp())).abs() < 1e-12);
    }

    #[test]
    fn anees_interval_for_bar_shalom_example() {
        // Bar-Shalom et al. (2001) §5.4.2: n = 2, N = 50 runs, 95 %: [1.5, 2.6]. From the
        // chi-square table with 100 dof: χ²(0.025) = 74.222, χ²(0.975) = 129.561, over 50 runs.
        let iv = anees_interval(2, 50, 0.95).unwrap();
        assert!((iv.lower - 74.222 / 50.0).abs() < 1e-4, "{iv:?}");
        assert!((iv.upper - 129.561 / 50.0).abs() < 1e-4, "{iv:?}");
    }

    #[test]
    fn unit_ball_volumes() {
        assert!((unit_ball_volume(1) - 2.0).abs() < 1e-12);
        assert!((unit_ball_volume(2) - std::f64::consts::PI).abs() < 1e-12);
        assert!((unit_ball_volume(3) - 4.0 * std::f64::consts::PI / 3.0).abs() < 1e-12);
        assert!((unit_ball_volume(4) - std::f64::consts::PI.powi(2) / 2.0).abs() < 1e-12);
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert!(chi2_quantile(1.0, 2.0).is_err());
        assert!(chi2_quantile(f64::NAN, 2.0).is_err());
        assert!(chi2_quantile(0.5, 0.0).is_err());
        assert!(gate_threshold(0.99, 0).is_err());
        assert!(anees_interval(2, 0, 0.95).is_err());
    }
}
