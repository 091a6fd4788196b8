//! The multi-IMM's posterior merged over its noise hypotheses: one IMM estimate of the
//! common dynamics.
//!
//! The `K` IMMs of a [`crate::MultiImm`] differ only in the measurement-noise variances
//! they assume; their motion models and Markov matrix are the same. Their posterior,
//! merged over the hypotheses with the noise-mode probabilities `νₘ`, is per motion mode
//! `i` the moment match of `Σₘ νₘ μₘⁱ N(x̂ₘⁱ, Pₘⁱ) / μⁱ` with `μⁱ = Σₘ νₘ μₘⁱ` — an IMM
//! estimate of the common dynamics, whose own combined output is the multi-IMM's
//! ([`MultiImmEstimate::combined`], the same mixture grouped the other way).

use argus_core_math::Gaussian;

use crate::imm::{ModeWeights, moment_match};
use crate::{ImmError, ImmEstimate, MultiImmEstimate, log_sum_exp};

impl<const N: usize, const R: usize, const K: usize> MultiImmEstimate<N, R, K> {
    /// The posterior merged over the noise hypotheses (module docs): per mode `i`,
    /// `μⁱ = Σₘ νₘ μₘⁱ` (in logarithms, so that a mode improbable in every hypothesis
    /// keeps its tiny probability) and the moment match of the hypotheses' `x̂ₘⁱ, Pₘⁱ`
    /// with weights `νₘ μₘⁱ / μⁱ` (with `νₘ` for a mode impossible in every hypothesis).
    ///
    /// # Errors
    /// [`ImmError::Empty`] for `K = 0` or `R = 0`; [`ImmError::Math`] if a moment match
    /// is not finite.
    pub fn merged(&self) -> Result<ImmEstimate<N, R>, ImmError> {
        let first = self.imms().first().ok_or(ImmError::Empty {
            what: "noise hypotheses",
        })?;
        let start = *first
            .modes()
            .first()
            .ok_or(ImmError::Empty { what: "IMM modes" })?;
        let log_nu = self.noise_probabilities().map(f64::ln);
        let mut log_mu = [f64::NEG_INFINITY; R];
        let mut modes = [start; R];
        for (i, (mode, lm)) in modes.iter_mut().zip(log_mu.iter_mut()).enumerate() {
            let mut joint = [f64::NEG_INFINITY; K];
            let mut parts: [Gaussian<N>; K] = [start; K];
            for ((j, p), (imm, ln_nu)) in joint
                .iter_mut()
                .zip(parts.iter_mut())
                .zip(self.imms().iter().zip(&log_nu))
            {
                *j = ln_nu + imm.log_mode_probabilities()[i];
                *p = imm.modes()[i];
            }
            *lm = log_sum_exp(&joint);
            let weights = if lm.is_finite() {
                joint.map(|j| (j - *lm).exp())
            } else {
                *self.noise_probabilities()
            };
            *mode = moment_match(&weights, &parts)?;
        }
        let mut out = ImmEstimate::from_common(start, [1.0 / R as f64; R])?;
        *out.modes_mut() = modes;
        out.set_weights(ModeWeights::from_logs(&log_mu));
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;
    use crate::NoiseVariances;
    use argus_core_math::{Matrix, Vector};

    fn g(x: f64, p: f64) -> Gaussian<2> {
        Gaussian::new(Vector::<2>::new(x, 0.5 * x), Matrix::<2, 2>::identity() * p).unwrap()
    }

    /// One hypothesis: the merge is that IMM's estimate (to round-off, 1e-12: a
    /// one-part moment match and `exp(ln μ)`).
    #[test]
    fn one_hypothesis_is_its_imm() {
        let imm = ImmEstimate::new([g(1.0, 2.0), g(3.0, 5.0)], [0.3, 0.7]).unwrap();
        let m =
            MultiImmEstimate::<2, 2, 1>::new(imm, NoiseVariances::from_sigmas(10.0, 0.01).unwrap());
        let merged = m.merged().unwrap();
        for (a, b) in merged.modes().iter().zip(imm.modes()) {
            assert!((a.mean() - b.mean()).norm() < 1e-12);
            assert!((a.cov() - b.cov()).norm() < 1e-12);
        }
        for (a, b) in merged
            .mode_probabilities()
            .iter()
            .zip(imm.mode_probabilities())
        {
            assert!((a - b).abs() < 1e-12);
        }
    }

    /// `K` equal hypotheses (`MultiImmEstimate::new` starts every IMM from one state): the
    /// merge is that state, and its combined output is the multi-IMM's
    /// [`MultiImmEstimate::combined`] (the same mixture, 1e-12 round-off).
    #[test]
    fn equal_hypotheses_merge_to_the_common_state() {
        let imm = ImmEstimate::new([g(1.0, 2.0), g(-4.0, 9.0)], [0.6, 0.4]).unwrap();
        let m =
            MultiImmEstimate::<2, 2, 5>::new(imm, NoiseVariances::from_sigmas(10.0, 0.01).unwrap());
        let merged = m.merged().unwrap();
        for (a, b) in merged.modes().iter().zip(imm.modes()) {
            assert!((a.mean() - b.mean()).norm() < 1e-12);
            assert!((a.cov() - b.cov()).norm() < 1e-12);
        }
        let (c, d) = (merged.combined().unwrap(), m.combined().unwrap());
        assert!((c.mean() - d.mean()).norm() < 1e-12);
        assert!((c.cov() - d.cov()).norm() < 1e-12);
    }

    /// Hypotheses that differ (ten steps of the paper's multi-IMM on simulated plots,
    /// fixed seed): the merge's probabilities sum to one and its combined output is the
    /// multi-IMM's [`MultiImmEstimate::combined`] — the same mixture of `K·R` Gaussians,
    /// grouped by mode first instead of by hypothesis (1e-9 relative: round-off of
    /// moment matches of positions ~1e4 m).
    #[test]
    fn merged_combined_is_the_multi_imm_output() {
        use crate::test_support::{beam_times, paper_imm, plots, two_point};
        use crate::{MultiImm, NoiseGrid, UnbiasedConversion};
        use rand::SeedableRng;
        let times = beam_times();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let pl = plots(&times[..12], 60.0, 0.002, &mut rng);
        let var = NoiseVariances::from_sigmas(60.0, 0.002).unwrap();
        let m = MultiImm::new(
            paper_imm(),
            NoiseGrid::<5>::common(0.1).unwrap(),
            Some(0.05),
        )
        .unwrap();
        let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
        let mut est =
            MultiImmEstimate::new(two_point(&pl[0], &pl[1], times[1] - times[0], &var), var);
        for k in 2..12 {
            est = m
                .step(&est, times[k] - times[k - 1], &pl[k], &conv)
                .unwrap()
                .estimate;
        }
        let spread = est
            .imms()
            .iter()
            .map(|e| (e.modes()[0].mean() - est.imms()[0].modes()[0].mean()).norm())
            .fold(0.0, f64::max);
        assert!(spread > 1e-6, "the hypotheses differ ({spread} m)");
        let merged = est.merged().unwrap();
        let sum: f64 = merged.mode_probabilities().iter().sum();
        assert!((sum - 1.0).abs() < 1e-12);
        for (a, b) in merged
            .mode_probabilities()
            .iter()
            .zip(est.mode_probabilities())
        {
            assert!((a - b).abs() < 1e-12);
        }
        let (c, d) = (merged.combined().unwrap(), est.combined().unwrap());
        assert!((c.mean() - d.mean()).norm() <= 1e-9 * d.mean().norm());
        assert!((c.cov() - d.cov()).norm() <= 1e-9 * d.cov().norm());
    }

    /// One hypothesis (factor 1, no clip): the multi-IMM is the plain IMM with the
    /// reference `R` (eq (13) keeps it), so the IMM smoother over its merged posteriors
    /// ([`crate::ImmTrack::push`], what `argus track --smooth` records for `multi-imm`)
    /// equals the smoother of the plain IMM's own forward pass ([`crate::ImmTrack::step`],
    /// the `imm` kind's) on the same plots (1e-9 relative: the same arithmetic, the merge
    /// a one-part moment match).
    #[test]
    fn one_hypothesis_smooths_as_the_imm() {
        use crate::test_support::{beam_times, paper_imm, plots, two_point};
        use crate::{ImmTrack, MultiImm, NoiseGrid, PlotConversion, UnbiasedConversion};
        use rand::SeedableRng;
        let times = beam_times();
        let n = 40;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let pl = plots(&times[..n], 60.0, 0.002, &mut rng);
        let var = NoiseVariances::from_sigmas(60.0, 0.002).unwrap();
        let imm = paper_imm();
        let grid = NoiseGrid::<1>::custom([[1.0, 1.0]]).unwrap();
        let m = MultiImm::new(paper_imm(), grid, None).unwrap();
        let conv = UnbiasedConversion::<4>::new(0, 2).unwrap();
        let start = two_point(&pl[0], &pl[1], times[1] - times[0], &var);
        let mut est = MultiImmEstimate::new(start, var);
        let mut merged = ImmTrack::new(*imm.markov(), times[1], est.merged().unwrap()).unwrap();
        let mut plain = ImmTrack::new(*imm.markov(), times[1], start).unwrap();
        let mut filtered = vec![start.combined().unwrap()];
        for k in 2..n {
            est = m
                .step(&est, times[k] - times[k - 1], &pl[k], &conv)
                .unwrap()
                .estimate;
            merged.push(&imm, times[k], est.merged().unwrap()).unwrap();
            let (meas, z) = conv.convert(&pl[k], &var).unwrap();
            plain.step(&imm, times[k], &meas, &z).unwrap();
            filtered.push(plain.latest().combined().unwrap());
        }
        let (a, b) = (merged.smooth().unwrap(), plain.smooth().unwrap());
        assert_eq!(a.len(), n - 1);
        let mut moved = 0.0_f64;
        for (k, (a, b)) in a.iter().zip(&b).enumerate() {
            let (ga, gb) = (&a.combined, &b.combined);
            assert!(
                (ga.mean() - gb.mean()).norm() <= 1e-9 * gb.mean().norm(),
                "step {k}"
            );
            assert!(
                (ga.cov() - gb.cov()).norm() <= 1e-9 * gb.cov().norm(),
                "step {k}"
            );
            for (p, q) in a.mode_probabilities.iter().zip(&b.mode_probabilities) {
                assert!((p - q).abs() <= 1e-9, "step {k}");
            }
            moved = moved.max((gb.mean() - filtered[k].mean()).norm());
        }
        // Both sides can fail: the smoother moves the estimate (metres, not round-off).
        assert!(moved > 1.0, "{moved}");
    }
}
