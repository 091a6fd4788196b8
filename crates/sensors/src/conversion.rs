//! Converted measurements: a polar (2-D) or spherical (3-D) plot turned into a
//! Cartesian position with its covariance, by the linearised, the debiased
//! (additive) or the unbiased (multiplicative) conversion.
//!
//! All three use the same noise model: the plot is `r_m = r + w_r`,
//! `ψ_m = ψ + w_ψ`, `θ_m = θ + w_θ` with independent zero-mean Gaussian noise,
//! and the angle factors `λ = E[cos w] = e^{−σ²/2}`, `λ' = E[cos 2w] = e^{−2σ²}`.
//! The covariances are evaluated at the measurement (the true position is
//! unknown): they are the conditional moments of the error given the plot,
//! treating the truth as `plot − noise`.
//!
//! The converted position is relative to the sensor: add the sensor position.

use argus_core_math::{Matrix, Vector, check_finite_matrix, check_finite_vector};

use crate::error::{SensorError, finite, non_negative, positive};

/// Which polar → Cartesian conversion to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ConversionMethod {
    /// `x = r cos θ`, `R_c = J R_p Jᵀ` with `J` the polar → Cartesian Jacobian at
    /// the plot. Biased by `−r(1 − λ)` along the range axis and over-confident
    /// when the cross-range error `r σθ` is large (`r σθ² / σr ≳ 0.4`).
    ///
    /// # References
    /// Bar-Shalom, Li & Kirubarajan (2001), §10.4.3; seed 003 eqs (9)–(12)
    /// (corrected: `R_c = J diag(σr², σψ², σθ²) Jᵀ`); seed 004 eq (6).
    Linearized,
    /// Lerro & Bar-Shalom's debiased conversion: subtract the conversion bias
    /// averaged over the truth given the plot, `μ_a = E[(λ_tot − 1) p | plot]`,
    /// and use the averaged true covariance `R_a = E[R_t | plot]`.
    ///
    /// # References
    /// D. Lerro & Y. Bar-Shalom, "Tracking with debiased consistent converted
    /// measurements versus EKF", IEEE Trans. AES 29(3), 1993 (the 2-D formulas);
    /// Bar-Shalom, Li & Kirubarajan (2001), §10.4.3.
    ///
    /// In 3-D ([`convert_spherical`]) with both angles noisy this covariance is
    /// over-confident at large cross-range errors (ANEES 3.53 for 3 dof at
    /// r = 50 km, σr = 50 m, σψ = σθ = 2°); prefer [`ConversionMethod::Unbiased`] there.
    Debiased,
    /// The unbiased conversion: divide by the angle factors, `x_u = λ⁻¹ r cos θ`
    /// (2-D), and use the conditional covariance of `x_u − x` given the plot.
    ///
    /// # References
    /// Mo Longbin, Song Xiaoquan, Zhou Yiyu, Sun Zhong Kang & Y. Bar-Shalom,
    /// "Unbiased converted measurements for tracking", IEEE Trans. AES 34(3),
    /// 1998 (2-D; the 3-D form here is derived the same way); Bar-Shalom, Li &
    /// Kirubarajan (2001), §10.4.3; seed 000 §2.
    #[default]
    Unbiased,
}

/// A converted plot: the Cartesian position (relative to the sensor) and its covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvertedMeasurement<const D: usize> {
    /// The converted position `(x, y)` or `(x, y, z)`, m, relative to the sensor.
    pub position: Vector<D>,
    /// Its error covariance, m².
    pub covariance: Matrix<D, D>,
}

/// The polar → Cartesian Jacobian `B = ∂(x, y)/∂(r, θ)` at `(r, θ)`:
///
/// `B = [[cos θ, −r sin θ], [sin θ, r cos θ]]`; its columns are the range and
/// (scaled) cross-range directions.
///
/// # References
/// Seed 004 (Kim et al. 2011), eq (4); Bar-Shalom, Li & Kirubarajan (2001), §10.4.3.
#[must_use]
pub fn polar_jacobian(range: f64, azimuth: f64) -> Matrix<2, 2> {
    let (s, c) = azimuth.sin_cos();
    Matrix::<2, 2>::new(c, -range * s, s, range * c)
}

/// The spherical → Cartesian Jacobian `J = ∂(x, y, z)/∂(r, ψ, θ)` of
/// `x = r cosψ cosθ, y = r sinψ cosθ, z = r sinθ` (seed 003 eq (9)):
///
/// ```text
/// J = [ cosψ cosθ   −r sinψ cosθ   −r cosψ sinθ ]
///     [ sinψ cosθ    r cosψ cosθ   −r sinψ sinθ ]
///     [ sinθ         0              r cosθ      ]
/// ```
///
/// Its columns are the range, cross-range-azimuth and cross-range-elevation
/// directions (scaled by 1, `r cosθ`, `r`).
///
/// # References
/// Seed 003 (Kim & Hwang 2013), eq (11) as corrected in SPEC.md (the printed `D`
/// has wrong terms and signs).
#[must_use]
pub fn spherical_jacobian(range: f64, azimuth: f64, elevation: f64) -> Matrix<3, 3> {
    let (sp, cp) = azimuth.sin_cos();
    let (st, ct) = elevation.sin_cos();
    let r = range;
    Matrix::<3, 3>::new(
        cp * ct,
        -r * sp * ct,
        -r * cp * st,
        sp * ct,
        r * cp * ct,
        -r * sp * st,
        st,
        0.0,
        r * ct,
    )
}

/// Converts a 2-D polar plot `(r, θ)` with noise standard deviations `(σr, σθ)`
/// to a Cartesian position and covariance.
///
/// With `λ = e^{−σθ²/2}`, `λ' = e^{−2σθ²}`, `s = σθ²`, `c = cos θ`, `n = sin θ`:
///
/// - [`ConversionMethod::Linearized`]: `p = r (c, n)`, `R = B diag(σr², σθ²) Bᵀ`.
/// - [`ConversionMethod::Debiased`] (Lerro & Bar-Shalom 1993):
///   `p = r (c, n) − r (λ² − λ)(c, n)` and
///   `R₁₁ = r² e^{−2s}[c²(cosh 2s − cosh s) + n²(sinh 2s − sinh s)]
///        + σr² e^{−2s}[c²(2cosh 2s − cosh s) + n²(2sinh 2s − sinh s)]`,
///   `R₂₂` the same with `c ↔ n`,
///   `R₁₂ = c n e^{−4s}[σr² + (r² + σr²)(1 − e^{s})]`.
/// - [`ConversionMethod::Unbiased`] (Mo et al. 1998, BLK 2001 §10.4.3):
///   `p = λ⁻¹ r (c, n)` and
///   `R₁₁ = (λ⁻² − 2) r² c² + ½(r² + σr²)(1 + λ' cos 2θ)`,
///   `R₂₂ = (λ⁻² − 2) r² n² + ½(r² + σr²)(1 − λ' cos 2θ)`,
///   `R₁₂ = (λ⁻² − 2) r² c n + ½(r² + σr²) λ' sin 2θ`.
///
/// # Errors
/// [`SensorError::NotPositive`] unless `r > 0`, [`SensorError::NonFinite`] for a
/// non-finite input, [`SensorError::Negative`] for a negative σ;
/// [`SensorError::Math`] if the result is not finite (extreme σθ).
#[allow(non_snake_case)]
pub fn convert_polar(
    range: f64,
    azimuth: f64,
    sigma_range: f64,
    sigma_azimuth: f64,
    method: ConversionMethod,
) -> Result<ConvertedMeasurement<2>, SensorError> {
    let r = positive(range, "range")?;
    let t = finite(azimuth, "azimuth")?;
    let sr = non_negative(sigma_range, "range sigma")?;
    let st = non_negative(sigma_azimuth, "azimuth sigma")?;
    let (n, c) = t.sin_cos();
    let s = st * st;
    let sr2 = sr * sr;
    let r2 = r * r;
    let lam = (-0.5 * s).exp();
    // e^{−2σ²} = (e^{−σ²/2})⁴: one exponential, not two.
    let lam_sq = lam * lam;
    let lam2 = lam_sq * lam_sq;
    let out = match method {
        ConversionMethod::Linearized => {
            let B = polar_jacobian(r, t);
            let Rp = Matrix::<2, 2>::new(sr2, 0.0, 0.0, s);
            ConvertedMeasurement {
                position: Vector::<2>::new(r * c, r * n),
                covariance: B * Rp * B.transpose(),
            }
        }
        ConversionMethod::Debiased => {
            let k = 1.0 - (lam_sq - lam);
            let e2 = lam2;
            let (ch2, ch1) = ((2.0 * s).cosh(), s.cosh());
            let (sh2, sh1) = ((2.0 * s).sinh(), s.sinh());
            let (c2, n2) = (c * c, n * n);
            let r11 = r2 * e2 * (c2 * (ch2 - ch1) + n2 * (sh2 - sh1))
                + sr2 * e2 * (c2 * (2.0 * ch2 - ch1) + n2 * (2.0 * sh2 - sh1));
            let r22 = r2 * e2 * (n2 * (ch2 - ch1) + c2 * (sh2 - sh1))
                + sr2 * e2 * (n2 * (2.0 * ch2 - ch1) + c2 * (2.0 * sh2 - sh1));
            let r12 = c * n * (-4.0 * s).exp() * (sr2 + (r2 + sr2) * (1.0 - s.exp()));
            ConvertedMeasurement {
                position: Vector::<2>::new(k * r * c, k * r * n),
                covariance: Matrix::<2, 2>::new(r11, r12, r12, r22),
            }
        }
        ConversionMethod::Unbiased => UnbiasedPolarConversion::from_checked(sr, st).formula(r, t),
    };
    check_finite_vector(&out.position, "converted position")?;
    check_finite_matrix(&out.covariance, "converted covariance")?;
    Ok(out)
}

/// The unbiased conversion of [`convert_polar`] ([`ConversionMethod::Unbiased`], Mo et al.
/// 1998; BLK 2001 §10.4.3) for a radar of constant `(σr, σθ)`: the constants that depend on
/// the noise alone (`σr²`, `λ = e^{−σθ²/2}`, `λ⁻² − 2`, `λ' = e^{−2σθ²}`) are formed once, so a
/// plot costs one sine and cosine and no exponential. The arithmetic is `convert_polar`'s
/// own (that function's unbiased branch is this type's formula), so the results are the same
/// to the bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnbiasedPolarConversion {
    /// `σr²`.
    sr2: f64,
    /// `λ = e^{−σθ²/2}`.
    lam: f64,
    /// `λ⁻² − 2`.
    a: f64,
    /// `λ' = e^{−2σθ²} = λ⁴`.
    lam2: f64,
}

impl UnbiasedPolarConversion {
    /// The conversion for noise standard deviations `σr` (m) and `σθ` (rad).
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] or [`SensorError::Negative`] for a bad σ, as
    /// [`convert_polar`].
    pub fn new(sigma_range: f64, sigma_azimuth: f64) -> Result<Self, SensorError> {
        let sr = non_negative(sigma_range, "range sigma")?;
        let st = non_negative(sigma_azimuth, "azimuth sigma")?;
        Ok(Self::from_checked(sr, st))
    }

    /// The constants of checked σ, computed as [`convert_polar`] computes them.
    #[inline(always)]
    fn from_checked(sr: f64, st: f64) -> Self {
        let s = st * st;
        let lam = (-0.5 * s).exp();
        // e^{−2σ²} = (e^{−σ²/2})⁴: one exponential, not two.
        let lam_sq = lam * lam;
        Self {
            sr2: sr * sr,
            lam,
            a: 1.0 / lam_sq - 2.0,
            lam2: lam_sq * lam_sq,
        }
    }

    /// Converts the plot `(range, azimuth)`: the same values as [`convert_polar`] with this
    /// conversion's σ and [`ConversionMethod::Unbiased`].
    ///
    /// # Errors
    /// As [`convert_polar`]: [`SensorError::NotPositive`] unless `range > 0`,
    /// [`SensorError::NonFinite`] for a non-finite azimuth, [`SensorError::Math`] for a
    /// non-finite result.
    #[inline]
    pub fn convert(
        &self,
        range: f64,
        azimuth: f64,
    ) -> Result<ConvertedMeasurement<2>, SensorError> {
        let r = positive(range, "range")?;
        let t = finite(azimuth, "azimuth")?;
        let out = self.formula(r, t);
        check_finite_vector(&out.position, "converted position")?;
        check_finite_matrix(&out.covariance, "converted covariance")?;
        Ok(out)
    }

    /// `p = λ⁻¹ r (c, n)` and `R` of [`convert_polar`]'s unbiased branch, for checked inputs.
    #[inline(always)]
    fn formula(&self, r: f64, t: f64) -> ConvertedMeasurement<2> {
        let (n, c) = t.sin_cos();
        let r2 = r * r;
        let (a, lam, lam2) = (self.a, self.lam, self.lam2);
        let b = 0.5 * (r2 + self.sr2);
        // cos 2θ and sin 2θ from the double-angle identities (no second sine and cosine).
        let (c2t, s2t) = ((c - n) * (c + n), 2.0 * n * c);
        let r11 = a * r2 * c * c + b * (1.0 + lam2 * c2t);
        let r22 = a * r2 * n * n + b * (1.0 - lam2 * c2t);
        let r12 = a * r2 * c * n + b * lam2 * s2t;
        ConvertedMeasurement {
            position: Vector::<2>::new(r * c / lam, r * n / lam),
            covariance: Matrix::<2, 2>::new(r11, r12, r12, r22),
        }
    }
}

/// Expectations of the trigonometric functions of a true angle `φ = φ_m − w`,
/// `w ~ N(0, σ²)`, given the measured `φ_m`, with `l1 = E[cos w]` and `l2 = E[cos 2w]`.
#[derive(Clone, Copy)]
struct TrigMoments {
    cos: f64,
    sin: f64,
    cos2: f64,
    sin2: f64,
    sincos: f64,
}

impl TrigMoments {
    fn new(angle: f64, l1: f64, l2: f64) -> Self {
        let (s, c) = angle.sin_cos();
        let (s2, c2) = (2.0 * angle).sin_cos();
        Self {
            cos: l1 * c,
            sin: l1 * s,
            cos2: 0.5 * (1.0 + l2 * c2),
            sin2: 0.5 * (1.0 - l2 * c2),
            sincos: 0.5 * l2 * s2,
        }
    }
}

/// `E[p pᵀ]` for `p = ρ (cosψ cosθ, sinψ cosθ, sinθ)` with `E[ρ²] = rho2` and
/// independent angle moments.
fn spherical_second_moment(rho2: f64, psi: &TrigMoments, th: &TrigMoments) -> Matrix<3, 3> {
    let xx = rho2 * psi.cos2 * th.cos2;
    let yy = rho2 * psi.sin2 * th.cos2;
    let zz = rho2 * th.sin2;
    let xy = rho2 * psi.sincos * th.cos2;
    let xz = rho2 * psi.cos * th.sincos;
    let yz = rho2 * psi.sin * th.sincos;
    Matrix::<3, 3>::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}

/// Converts a 3-D spherical plot `(r, ψ, θ)` (azimuth ψ from +x counter-clockwise,
/// elevation θ above the horizontal plane) with standard deviations
/// `(σr, σψ, σθ)` to a Cartesian position and covariance.
///
/// `p_m = r (cosψ cosθ, sinψ cosθ, sinθ)` (seed 003 eq (9)). Given the truth,
/// `E[p_m] = L ⊙ p` with `L = (λψ λθ, λψ λθ, λθ)`, `λ = e^{−σ²/2}` per angle —
/// the 3-D form of the 2-D factor `λ`. With `E[· | plot]` taken over the truth
/// `plot − noise` (cosφ → λ cosφ_m, cos 2φ → λ' cos 2φ_m, `λ' = e^{−2σ²}`,
/// `r² → r_m² + σr²`):
///
/// - [`ConversionMethod::Linearized`]: `p = p_m`, `R = J diag(σr², σψ², σθ²) Jᵀ`
///   ([`spherical_jacobian`]).
/// - [`ConversionMethod::Debiased`]: `p = p_m − (L − 1) ⊙ E[p | plot]`,
///   `R = E[R_t | plot]` with `R_t = E[p_m p_mᵀ | truth] − (L ⊙ p)(L ⊙ p)ᵀ`
///   (Lerro & Bar-Shalom's construction carried to three dimensions; it is
///   over-confident when both angle errors are large, see [`ConversionMethod::Debiased`]).
/// - [`ConversionMethod::Unbiased`]: `p = p_m ⊘ L`, `R = E[(p − p_true)(p − p_true)ᵀ | plot]`
///   (Mo et al.'s construction in three dimensions).
///
/// For `θ = σθ = 0` every method reduces to [`convert_polar`] in `(x, y)`.
///
/// # Errors
/// As [`convert_polar`].
#[allow(non_snake_case)]
pub fn convert_spherical(
    range: f64,
    azimuth: f64,
    elevation: f64,
    sigmas: [f64; 3],
    method: ConversionMethod,
) -> Result<ConvertedMeasurement<3>, SensorError> {
    let r = positive(range, "range")?;
    let psi = finite(azimuth, "azimuth")?;
    let th = finite(elevation, "elevation")?;
    let sr = non_negative(sigmas[0], "range sigma")?;
    let sp = non_negative(sigmas[1], "azimuth sigma")?;
    let se = non_negative(sigmas[2], "elevation sigma")?;
    let (sp2, se2, sr2, r2) = (sp * sp, se * se, sr * sr, r * r);
    let (lp1, lp2) = ((-0.5 * sp2).exp(), (-2.0 * sp2).exp());
    let (lt1, lt2) = ((-0.5 * se2).exp(), (-2.0 * se2).exp());
    let (spsi, cpsi) = psi.sin_cos();
    let (sth, cth) = th.sin_cos();
    let pm = Vector::<3>::new(r * cpsi * cth, r * spsi * cth, r * sth);
    let L = Vector::<3>::new(lp1 * lt1, lp1 * lt1, lt1);
    // Moments of the true angles given the plot.
    let mpsi = TrigMoments::new(psi, lp1, lp2);
    let mth = TrigMoments::new(th, lt1, lt2);
    // E[p | plot].
    let mean_true = Vector::<3>::new(r * mpsi.cos * mth.cos, r * mpsi.sin * mth.cos, r * mth.sin);
    let out = match method {
        ConversionMethod::Linearized => {
            let J = spherical_jacobian(r, psi, th);
            let Rs = Matrix::<3, 3>::from_diagonal(&Vector::<3>::new(sr2, sp2, se2));
            ConvertedMeasurement {
                position: pm,
                covariance: J * Rs * J.transpose(),
            }
        }
        ConversionMethod::Debiased => {
            let mu = (L - Vector::<3>::repeat(1.0)).component_mul(&mean_true);
            // E[E[p_m p_mᵀ | truth] | plot]: each angle moment applied twice, r² → r_m² + 2σr².
            let mpsi_twice = TrigMoments::new(psi, lp1 * lp1, lp2 * lp2);
            let mth_twice = TrigMoments::new(th, lt1 * lt1, lt2 * lt2);
            let m_meas = spherical_second_moment(r2 + 2.0 * sr2, &mpsi_twice, &mth_twice);
            let m_true = spherical_second_moment(r2 + sr2, &mpsi, &mth);
            ConvertedMeasurement {
                position: pm - mu,
                covariance: m_meas - (L * L.transpose()).component_mul(&m_true),
            }
        }
        ConversionMethod::Unbiased => {
            let u = pm.component_div(&L);
            let m_true = spherical_second_moment(r2 + sr2, &mpsi, &mth);
            let cross = u * mean_true.transpose();
            ConvertedMeasurement {
                position: u,
                covariance: u * u.transpose() - cross - cross.transpose() + m_true,
            }
        }
    };
    check_finite_vector(&out.position, "converted position")?;
    check_finite_matrix(&out.covariance, "converted covariance")?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const METHODS: [ConversionMethod; 3] = [
        ConversionMethod::Linearized,
        ConversionMethod::Debiased,
        ConversionMethod::Unbiased,
    ];

    proptest::proptest! {
        #[test]
        fn precomputed_unbiased_conversion_equals_convert_polar_to_the_bit(
            r in 1.0f64..2e5,
            t in -7.0f64..7.0,
            sr in 0.0f64..200.0,
            st in 0.0f64..0.3,
        ) {
            // The same arithmetic by construction (convert_polar's unbiased branch is the
            // type's formula): equal bits, not a tolerance.
            let a = convert_polar(r, t, sr, st, ConversionMethod::Unbiased).unwrap();
            let b = UnbiasedPolarConversion::new(sr, st).unwrap().convert(r, t).unwrap();
            for (x, y) in a.position.iter().zip(b.position.iter()) {
                proptest::prop_assert_eq!(x.to_bits(), y.to_bits());
            }
            for (x, y) in a.covariance.iter().zip(b.covariance.iter()) {
                proptest::prop_assert_eq!(x.to_bits(), y.to_bits());
            }
        }

        #[test]
        fn unbiased_polar_equals_its_closed_form(
            r in 100.0f64..2e5,
            t in -3.2f64..3.2,
            sr in 0.0f64..200.0,
            st in 0.0f64..0.2,
        ) {
            // Mo Longbin et al. (1998) / Bar-Shalom (2001) with cos 2θ, sin 2θ, e^{−σ²/2} and
            // e^{−2σ²} each evaluated directly; the implementation uses the double-angle
            // identities and λ⁴. Tolerance: round-off relative to r² + σr², the size of the
            // terms that cancel in r11 and r22 (both forms carry that absolute round-off).
            let got = convert_polar(r, t, sr, st, ConversionMethod::Unbiased).unwrap();
            let s = st * st;
            let (lam, lam2) = ((-0.5 * s).exp(), (-2.0 * s).exp());
            let a = 1.0 / (lam * lam) - 2.0;
            let b = 0.5 * (r * r + sr * sr);
            let (c, n) = (t.cos(), t.sin());
            let r11 = a * r * r * c * c + b * (1.0 + lam2 * (2.0 * t).cos());
            let r22 = a * r * r * n * n + b * (1.0 - lam2 * (2.0 * t).cos());
            let r12 = a * r * r * c * n + b * lam2 * (2.0 * t).sin();
            let want = Matrix::<2, 2>::new(r11, r12, r12, r22);
            proptest::prop_assert!((got.covariance - want).amax() <= 1e-12 * (r * r + sr * sr));
            let pos = Vector::<2>::new(r * c / lam, r * n / lam);
            proptest::prop_assert!((got.position - pos).amax() <= 1e-12 * r);
        }
    }

    #[test]
    fn spherical_reduces_to_polar_in_the_plane() {
        // θ = σθ = 0: the z row/column vanishes and (x, y) must equal the 2-D closed
        // forms (Lerro 1993, Mo 1998) — an independent check of the 3-D moment algebra.
        for method in METHODS {
            for &(r, t, sr, st) in &[
                (50e3, 0.7, 50.0, 0.035),
                (1e3, -2.5, 5.0, 0.2),
                (7e4, 3.1, 1.0, 0.01),
            ] {
                let p = convert_polar(r, t, sr, st, method).unwrap();
                let s = convert_spherical(r, t, 0.0, [sr, st, 0.0], method).unwrap();
                let scale = p.covariance.norm();
                for i in 0..2 {
                    assert!((p.position[i] - s.position[i]).abs() < 1e-9 * r);
                    for j in 0..2 {
                        assert!(
                            (p.covariance[(i, j)] - s.covariance[(i, j)]).abs() < 1e-10 * scale,
                            "{method:?} ({i},{j}): {} vs {}",
                            p.covariance[(i, j)],
                            s.covariance[(i, j)]
                        );
                    }
                }
                assert!(s.covariance[(2, 2)].abs() < 1e-10 * scale);
            }
        }
    }

    #[test]
    fn no_angle_noise_means_no_correction() {
        // σθ = 0: λ = 1, all three conversions coincide with r(cos θ, sin θ) and
        // the covariance is σr² along the range axis only (exact).
        for method in METHODS {
            let c = convert_polar(1000.0, 0.3, 10.0, 0.0, method).unwrap();
            assert!((c.position[0] - 1000.0 * 0.3f64.cos()).abs() < 1e-9);
            let u = Vector::<2>::new(0.3f64.cos(), 0.3f64.sin());
            assert!(((u.transpose() * c.covariance * u)[0] - 100.0).abs() < 1e-9);
            let v = Vector::<2>::new(-0.3f64.sin(), 0.3f64.cos());
            assert!((v.transpose() * c.covariance * v)[0].abs() < 1e-9);
        }
    }

    #[test]
    fn invalid_inputs_are_rejected() {
        let m = ConversionMethod::Unbiased;
        assert!(matches!(
            convert_polar(0.0, 0.0, 1.0, 0.1, m),
            Err(SensorError::NotPositive { .. })
        ));
        assert!(matches!(
            convert_polar(1.0, f64::NAN, 1.0, 0.1, m),
            Err(SensorError::NonFinite { .. })
        ));
        assert!(matches!(
            convert_polar(1.0, 0.0, -1.0, 0.1, m),
            Err(SensorError::Negative { .. })
        ));
        assert!(convert_spherical(1.0, 0.0, 0.0, [1.0, 0.1, -0.1], m).is_err());
        assert!(convert_spherical(1.0, 0.0, f64::INFINITY, [1.0, 0.1, 0.1], m).is_err());
    }

    #[test]
    fn precomputed_unbiased_conversion_reports_the_same_errors() {
        assert!(matches!(
            UnbiasedPolarConversion::new(-1.0, 0.01),
            Err(SensorError::Negative { .. })
        ));
        assert!(matches!(
            UnbiasedPolarConversion::new(10.0, f64::NAN),
            Err(SensorError::NonFinite { .. })
        ));
        let conv = UnbiasedPolarConversion::new(10.0, 0.01).unwrap();
        for (r, t) in [
            (0.0, 0.1),
            (-5.0, 0.1),
            (f64::NAN, 0.1),
            (1e3, f64::INFINITY),
        ] {
            // By text: an error carrying a NaN value is not `==` to itself.
            assert_eq!(
                conv.convert(r, t).unwrap_err().to_string(),
                convert_polar(r, t, 10.0, 0.01, ConversionMethod::Unbiased)
                    .unwrap_err()
                    .to_string()
            );
        }
    }
}
