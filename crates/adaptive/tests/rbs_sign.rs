//! Seed 003 eq (28): the sign of the post-fit `R` estimate, proved numerically.
//!
//! For a Kalman filter that uses the true `R`, the post-fit residual is
//! `ε = z − H x⁺ = R S⁻¹ ν`, so `E[εεᵀ] = R S⁻¹ R = R − H P⁺ Hᵀ`. Hence
//! `E[εεᵀ + H P⁺ Hᵀ] = R` (corrected sign) while the printed
//! `εεᵀ − H P⁺ Hᵀ` has mean `R − 2 H P⁺ Hᵀ`.

use argus_adaptive::{
    ConvertedPlot, DecoupledEstimate, DecoupledFilter, FrameHandling, aligned_frame,
    post_fit_sample,
};
use argus_core_math::{Matrix, Vector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

#[test]
fn corrected_sign_is_unbiased_and_printed_sign_is_not() {
    // Tracking index λ = qT²/σ = 1 on the range axis: the steady-state P⁺ is a large
    // fraction of R (α = 0.75), so the two signs are far apart.
    let (q, dt) = (1.0, 1.0);
    let frame = aligned_frame(0.7, 0.2);
    let r_aligned = Vector::<3>::new(1.0, 4.0, 0.25);
    let filter = DecoupledFilter::new(q, FrameHandling::Fixed).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(28);
    let mut n = || -> f64 { StandardNormal.sample(&mut rng) };
    let block = Matrix::<2, 2>::new(10.0, 0.0, 0.0, 10.0);
    let mut truth = Vector::<6>::zeros();
    let mut est = DecoupledEstimate::new(truth, [block; 3], frame).unwrap();
    let (burn, steps) = (100, 40_000);
    let mut plus = Vector::<3>::zeros();
    let mut minus = Vector::<3>::zeros();
    let mut p_post = Vector::<3>::zeros();
    for k in 0..burn + steps {
        for i in 0..3 {
            let w = q * n();
            truth[2 * i] += dt * truth[2 * i + 1] + 0.5 * dt * dt * w;
            truth[2 * i + 1] += dt * w;
        }
        let pos = Vector::<3>::new(truth[0], truth[2], truth[4]);
        let noise =
            frame * Vector::<3>::new(n(), n(), n()).component_mul(&r_aligned.map(f64::sqrt));
        let plot = ConvertedPlot::new(pos + noise, frame, r_aligned).unwrap();
        est = filter
            .update(&filter.predict(&est, dt).unwrap(), &plot)
            .unwrap()
            .0;
        if k >= burn {
            let eps = plot.position() - est.position();
            let hph = est.position_cov();
            let a = frame.transpose() * post_fit_sample(&eps, &hph) * frame;
            let b = frame.transpose() * (eps * eps.transpose() - hph) * frame;
            for i in 0..3 {
                plus[i] += a[(i, i)] / r_aligned[i] / steps as f64;
                minus[i] += b[(i, i)] / r_aligned[i] / steps as f64;
                p_post[i] = est.blocks()[i][(0, 0)] / r_aligned[i];
            }
        }
    }
    for i in 0..3 {
        eprintln!(
            "axis {i}: corrected {:.4}, printed {:.4} (predicted {:.4})",
            plus[i],
            minus[i],
            1.0 - 2.0 * p_post[i]
        );
        // Standard error of the mean of εε/R over 40 000 white samples: √(2/40 000)·(1 − P⁺/R)
        // ≤ 0.71 %; 3 % is over four standard errors.
        assert!(
            (plus[i] - 1.0).abs() < 0.03,
            "corrected sign, axis {i}: {}",
            plus[i]
        );
        // The printed sign's mean is 1 − 2 P⁺/R (derived above), far from 1.
        assert!(
            (minus[i] - (1.0 - 2.0 * p_post[i])).abs() < 0.03,
            "printed sign, axis {i}"
        );
        assert!(minus[i] < 0.9);
    }
}
