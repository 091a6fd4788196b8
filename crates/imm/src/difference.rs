//! A plot-difference measurement-noise estimator around one IMM (beyond seed 000).

use argus_filters::GaussianFilter;
use argus_sensors::PolarMeasurement;

use crate::error::{check_forgetting, check_positive};
use crate::{Imm, ImmError, ImmEstimate, ImmUpdate, NoiseVariances, PlotConversion};
use argus_sensors::wrap_angle;

/// The state of a [`DifferenceNoiseImm`]: the IMM estimate, the last three plots with the
/// intervals between them, and the accumulated squared differences per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DifferenceEstimate<const N: usize, const R: usize> {
    imm: ImmEstimate<N, R>,
    /// The last plots seen as `(range, azimuth)`, oldest first (valid: the last `seen`).
    recent: [[f64; 2]; 3],
    /// The intervals between `recent[0]` and `recent[1]`, and `recent[1]` and `recent[2]`.
    gaps: [f64; 2],
    /// Plots seen so far, saturating at 3.
    seen: usize,
    /// Accumulated weight: the prior pseudo-count plus one per difference (with forgetting).
    count: f64,
    /// Accumulated normalised squared differences `d²/Σw²` per axis, prior included.
    sums: [f64; 2],
}

impl<const N: usize, const R: usize> DifferenceEstimate<N, R> {
    /// A start from `imm`, the initial guess `initial` of the variances, held with the weight
    /// of `prior_count` pseudo-differences (the estimate is the guess until plots arrive).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `prior_count` is finite and positive.
    pub fn new(
        imm: ImmEstimate<N, R>,
        initial: NoiseVariances,
        prior_count: f64,
    ) -> Result<Self, ImmError> {
        check_positive("prior count", prior_count)?;
        Ok(Self {
            imm,
            recent: [[0.0; 2]; 3],
            gaps: [0.0; 2],
            seen: 0,
            count: prior_count,
            sums: [
                prior_count * initial.range(),
                prior_count * initial.azimuth(),
            ],
        })
    }

    /// The IMM estimate.
    #[must_use]
    pub fn imm(&self) -> &ImmEstimate<N, R> {
        &self.imm
    }

    /// The number of differences accumulated (with forgetting), the prior's pseudo-count
    /// included.
    #[must_use]
    pub fn count(&self) -> f64 {
        self.count
    }

    /// The current variance estimates (the mean normalised squared difference per axis).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] if they are not finite and positive (not reachable from
    /// a validated start).
    pub fn variances(&self) -> Result<NoiseVariances, ImmError> {
        NoiseVariances::new(self.sums[0] / self.count, self.sums[1] / self.count)
    }
}

/// Third divided-difference weights for plots at times `0, a, a + b, a + b + c`, in units of
/// the span (so they neither overflow nor underflow with the time unit): `wᵢ = 1/∏ⱼ≠ᵢ(τᵢ − τⱼ)`.
/// `Σ wᵢ τᵢᵏ = 0` for `k = 0, 1, 2`, so the weighted sum of samples of any quadratic is zero.
pub(crate) fn third_difference_weights(a: f64, b: f64, c: f64) -> [f64; 4] {
    let span = a + b + c;
    let t = [0.0, a / span, (a + b) / span, 1.0];
    let mut w = [1.0; 4];
    for (i, wi) in w.iter_mut().enumerate() {
        for (j, tj) in t.iter().enumerate() {
            if i != j {
                *wi /= t[i] - tj;
            }
        }
    }
    w
}

/// Range and azimuth measurement-noise variances estimated from third differences of the
/// raw polar plots, with one IMM filtering under the current estimate.
///
/// Per plot `k` (times `t_{k−3} … t_k`, any spacing): with the third divided-difference
/// weights `wᵢ = 1/∏ⱼ≠ᵢ(tᵢ − tⱼ)`, `d = Σ wᵢ zᵢ` per axis (`z` = range, or azimuth
/// unwrapped against the newest plot) and `q = d² / Σ wᵢ²`. The weights annihilate every
/// quadratic in time, so for a truth that is locally quadratic over four plots
/// `d = Σ wᵢ nᵢ` and `E[q] = σ²` exactly: white plot noise of variance `σ²` is all that
/// is left. The estimate is the running mean `σ̂² = (n₀σ₀² + Σ q) / (n₀ + #q)` (forgetting
/// `ρ` per difference, prior of `n₀` pseudo-differences at the guess). Its expectation is
/// the truth whatever the IMM's motion models and whatever the start (the start stays
/// only in the prior's share `n₀/(n₀ + #q)`); nothing feeds back from the filter. The IMM
/// then runs one cycle with the plot converted under `σ̂²`.
///
/// What it needs of the truth: the cubic and higher terms over three intervals must be
/// small against the noise. In the equal-spacing scaling `(−1, 3, −3, 1)`, where the noise
/// part has sd `√20 σ`, for a target at range `r`, speed `v`, interval `T`: straight
/// flight leaves `|θ'''| T³ ≲ 2 (vT/r)³` rad in azimuth (≪ σθ unless the target passes
/// within a few `vT` of the radar); a change of acceleration `Δa` leaves `≈ Δa T²/2` m in
/// one or two differences, a turn at rate `ω` leaves `ω a T³` per difference. In
/// expectation each adds to the estimate, never subtracts. Cost per plot: one IMM cycle (`R` filters) and a few
/// flops, against `5 R` filter cycles for the paper's 5 × 3 rule.
///
/// # References
/// The variate-difference method (G. Tintner, *The Variate Difference Method*, 1940);
/// difference-based residual variance with unequal spacing: T. Gasser, L. Sroka &
/// C. Jennen-Steinmetz, "Residual variance and residual pattern in nonlinear regression",
/// Biometrika 73(3), 1986 (second differences; here the third, which also cancel a constant
/// acceleration and the curvature of polar coordinates).
#[derive(Debug, Clone, PartialEq)]
pub struct DifferenceNoiseImm<F, const N: usize, const R: usize> {
    imm: Imm<F, N, R>,
    forgetting: f64,
}

impl<F: GaussianFilter<N>, const N: usize, const R: usize> DifferenceNoiseImm<F, N, R> {
    /// Around `imm`, with forgetting factor `forgetting` per difference (`ρ`, 1 = none).
    ///
    /// # Errors
    /// [`ImmError::InvalidParameter`] unless `forgetting ∈ (0, 1]`.
    pub fn new(imm: Imm<F, N, R>, forgetting: f64) -> Result<Self, ImmError> {
        check_forgetting(forgetting)?;
        Ok(Self { imm, forgetting })
    }

    /// The IMM.
    #[must_use]
    pub fn imm(&self) -> &Imm<F, N, R> {
        &self.imm
    }

    /// One step with `plot` after `dt` seconds: the difference statistic first (from the
    /// fourth plot on), then one IMM cycle under the updated estimate. Returns the new
    /// estimate and the IMM update.
    ///
    /// # Errors
    /// [`ImmError::InvalidInterval`] for `dt` not finite and positive; as [`Imm::step`] and
    /// the conversion. `est` is never modified.
    pub fn step<const M: usize, C: PlotConversion<N, M>>(
        &self,
        est: &DifferenceEstimate<N, R>,
        dt: f64,
        plot: &PolarMeasurement,
        conversion: &C,
    ) -> Result<(DifferenceEstimate<N, R>, ImmUpdate<N, R>), ImmError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(ImmError::InvalidInterval { dt });
        }
        let z = [plot.range(), plot.azimuth()];
        let (mut count, mut sums) = (est.count, est.sums);
        if est.seen == 3 {
            let w = third_difference_weights(est.gaps[0], est.gaps[1], dt);
            let norm: f64 = w.iter().map(|x| x * x).sum();
            // Σw = 0, so the newest plot can be subtracted from every sample (it then drops
            // out): that keeps the sums small, and for the azimuth removes any 2π jump.
            let mut d = [0.0; 2];
            for (wi, zi) in w.iter().zip(&est.recent) {
                d[0] += wi * (zi[0] - z[0]);
                d[1] += wi * wrap_angle(zi[1] - z[1]);
            }
            let q = d.map(|x| x * x / norm);
            // A span with two plots at (nearly) one instant can overflow the weights; such
            // a difference carries no information and is skipped.
            if q.iter().all(|x| x.is_finite()) {
                let rho = self.forgetting;
                count = rho * count + 1.0;
                sums = [rho * sums[0] + q[0], rho * sums[1] + q[1]];
            }
        }
        let var = NoiseVariances::new(sums[0] / count, sums[1] / count)?;
        let (meas, zc) = conversion.convert(plot, &var)?;
        let upd = self.imm.step(&est.imm, dt, &meas, &zc)?;
        let (recent, gaps) = match est.seen {
            0 => ([[0.0; 2], [0.0; 2], z], [0.0; 2]),
            1 => ([[0.0; 2], est.recent[2], z], [0.0, dt]),
            _ => ([est.recent[1], est.recent[2], z], [est.gaps[1], dt]),
        };
        let next = DifferenceEstimate {
            imm: upd.estimate,
            recent,
            gaps,
            seen: (est.seen + 1).min(3),
            count,
            sums,
        };
        Ok((next, upd))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use argus_core_math::{Gaussian, Matrix, Vector};
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, StandardNormal};

    use super::*;
    use crate::UnbiasedConversion;
    use crate::test_support::paper_imm;

    #[test]
    fn weights_cancel_every_quadratic_at_any_spacing() {
        // Σ wᵢ tᵢᵏ = 0 for k = 0, 1, 2 (divided differences of order 3); the cubic term is
        // what remains: Σ wᵢ τᵢ³ = 1 for the third divided difference (in span units).
        for (a, b, c) in [(1.0, 1.0, 1.0), (4.9, 5.2, 5.05), (0.3, 2.0, 7.0)] {
            let w = third_difference_weights(a, b, c);
            let span = a + b + c;
            let t = [0.0, a / span, (a + b) / span, 1.0];
            for k in 0..3 {
                let m: f64 = w.iter().zip(&t).map(|(wi, ti)| wi * ti.powi(k)).sum();
                let scale: f64 = w.iter().map(|x| x.abs()).sum();
                assert!(m.abs() < 1e-12 * scale, "({a}, {b}, {c}) k = {k}: {m}");
            }
            let m3: f64 = w.iter().zip(&t).map(|(wi, ti)| wi * ti.powi(3)).sum();
            assert!((m3 - 1.0).abs() < 1e-12, "{m3}");
        }
        // Equal spacing: (−1, 3, −3, 1)/6 in span units (T = 1/3).
        let w = third_difference_weights(2.0, 2.0, 2.0);
        for (wi, want) in w.iter().zip([-4.5, 13.5, -13.5, 4.5]) {
            assert!((wi - want).abs() < 1e-12, "{w:?}");
        }
    }

    /// A target flying a quadratic path in (range, azimuth) with white plot noise at
    /// irregular intervals: `E[d²/Σw²] = σ²` exactly, so the estimate from 20 000 plots is
    /// the truth within its standard error. Relative sd of the estimate ≈ √(2 · 2.31 / n),
    /// 2.31 = 1 + 2 Σ ρ_ℓ² for the lag correlations −¾, 3/10, −1/20 of overlapping third
    /// differences at equal spacing: 0.0152 here, tolerance 3 of them (0.046). The IMM's
    /// models (paper set) play no part in the estimate. An azimuth crossing ±π changes nothing.
    #[test]
    fn estimate_is_the_plot_noise_whatever_the_path() {
        let (sr, st) = (70.0, 0.0014);
        let truth = NoiseVariances::from_sigmas(sr, st).unwrap();
        let imm = paper_imm();
        let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
        let est_imm = DifferenceNoiseImm::new(imm, 1.0).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let n = 20_000;
        let start = Gaussian::new(
            Vector::<4>::new(-30_000.0, 0.0, 10.0, 0.0),
            Matrix::<4, 4>::from_diagonal(&Vector::<4>::new(1e4, 1e3, 1e4, 1e3)),
        )
        .unwrap();
        let init = ImmEstimate::from_common(start, [1.0 / 3.0; 3]).unwrap();
        // Start far from the truth (×3): the prior weight 2 against ≈ 20 000 differences
        // shifts the estimate by 2 · 2/20 000 = 0.0002.
        let guess = NoiseVariances::new(3.0 * truth.range(), 3.0 * truth.azimuth()).unwrap();
        let mut est = DifferenceEstimate::new(init, guess, 2.0).unwrap();
        let mut t = 0.0;
        for k in 0..n {
            let dt = 5.0 + 0.3 * (k as f64 * 0.7).sin();
            t += dt;
            // Azimuth sweeps through ±π (the target passes behind the radar's −x axis).
            let r = 30_000.0 + 0.5 * t - 5e-6 * t * t;
            let az = std::f64::consts::PI - 0.2 + 6e-6 * t - 3e-11 * t * t;
            let nr: f64 = StandardNormal.sample(&mut rng);
            let nt: f64 = StandardNormal.sample(&mut rng);
            let plot = PolarMeasurement::new(r + sr * nr, wrap_angle(az + st * nt)).unwrap();
            // The IMM sees a target it cannot follow (it starts at rest); the estimate
            // does not care.
            est = est_imm.step(&est, dt, &plot, &conv).unwrap().0;
        }
        let v = est.variances().unwrap();
        println!(
            "ratios {:.4} {:.4}",
            v.range() / truth.range(),
            v.azimuth() / truth.azimuth()
        );
        let tol = 3.0 * (2.0 * 2.31 / n as f64).sqrt();
        assert!((v.range() / truth.range() - 1.0).abs() < tol, "{v:?}");
        assert!((v.azimuth() / truth.azimuth() - 1.0).abs() < tol, "{v:?}");
        assert!((est.count() - (n as f64 - 3.0 + 2.0)).abs() < 1e-9);
    }

    #[test]
    fn bad_input_is_rejected_and_the_estimate_is_untouched() {
        let imm = paper_imm();
        assert!(DifferenceNoiseImm::new(imm.clone(), 0.0).is_err());
        assert!(DifferenceNoiseImm::new(imm.clone(), 1.5).is_err());
        assert!(DifferenceNoiseImm::new(imm.clone(), f64::NAN).is_err());
        let d = DifferenceNoiseImm::new(imm, 1.0).unwrap();
        let start = Gaussian::new(
            Vector::<4>::new(1000.0, 0.0, 0.0, 0.0),
            Matrix::<4, 4>::identity() * 100.0,
        )
        .unwrap();
        let init = ImmEstimate::from_common(start, [1.0 / 3.0; 3]).unwrap();
        let var = NoiseVariances::new(100.0, 1e-6).unwrap();
        assert!(DifferenceEstimate::new(init, var, 0.0).is_err());
        assert!(DifferenceEstimate::new(init, var, f64::INFINITY).is_err());
        let est = DifferenceEstimate::new(init, var, 2.0).unwrap();
        let before = est;
        let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
        let plot = PolarMeasurement::new(1000.0, 0.0).unwrap();
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                d.step(&est, dt, &plot, &conv),
                Err(ImmError::InvalidInterval { .. })
            ));
        }
        assert_eq!(est, before);
    }
}
