//! The ADKF start-up ([`Warmup::InnovationScale`]): for the first `L` plots the plot's
//! assumed `R₀` is scaled by `max(λ̄, 1)`, `λ̄` the running mean of the innovation-based
//! samples `(ν̄ᵢ² − p̄ᵢ⁻)/r̄₀ᵢ`, before the plot is fused; then the paper's post-fit method.
//!
//! Why the sample is unbiased: with a prior `x⁻ ~ N(x, P⁻)` and a plot `z = Hx + w`,
//! `w ~ N(0, λ R₀)`, the innovation `ν = z − Hx⁻` has covariance `H P⁻ Hᵀ + λ R₀`
//! whatever `R` the filter then uses, so along an aligned axis `E[ν̄ᵢ²] = p̄ᵢ⁻ + λ r̄₀ᵢ`.

use argus_adaptive::{
    AdaptiveDecoupledFilter, AdaptiveRConfig, AdaptiveState, ConvertedPlot, DecoupledEstimate,
    DecoupledFilter, FrameHandling, REstimate, Warmup, aligned_frame, post_fit_sample,
};
use argus_core_math::{Matrix, Vector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

const L: usize = 5;

#[allow(clippy::unwrap_used)] // test helper: a bad constant must fail the test
fn filter() -> AdaptiveDecoupledFilter {
    AdaptiveDecoupledFilter::new(
        DecoupledFilter::new(0.05, FrameHandling::Rotate).unwrap(),
        AdaptiveRConfig::new(L, 1e-6, Warmup::InnovationScale).unwrap(),
    )
}

#[allow(clippy::unwrap_used)] // test helper
fn state(mean: Vector<6>, frame: Matrix<3, 3>, r0: &Matrix<3, 3>) -> AdaptiveState {
    let block = Matrix::<2, 2>::new(100.0, 2.0, 2.0, 25.0);
    AdaptiveState {
        estimate: DecoupledEstimate::new(mean, [block; 3], frame).unwrap(),
        r: REstimate::new(*r0).unwrap(),
    }
}

#[test]
fn start_up_scale_sample_is_unbiased() {
    // 20 000 independent first updates with a consistent prior (P⁻ position variance 100 m²
    // per axis) and plots 25× noisier than assumed (r̄₀ = 4, 9, 1 m²). The sample's mean over
    // the three axes has sd √2 (p̄ + λ r̄₀)/r̄₀ / √3 per draw (≤ 58): the mean over 20 000 draws
    // has a standard error ≤ 0.41, i.e. 1.6 % of λ = 25; 6 % is over 3.5 standard errors.
    let lambda = 25.0;
    let frame = aligned_frame(3.1, 0.05);
    let r0 = Vector::<3>::new(4.0, 9.0, 1.0);
    let r0_cart = frame * Matrix::<3, 3>::from_diagonal(&r0) * frame.transpose();
    let f = filter();
    let mut rng = ChaCha8Rng::seed_from_u64(2013);
    let mut n = || -> f64 { StandardNormal.sample(&mut rng) };
    let truth = Vector::<3>::new(-3000.0, -100.0, 157.0);
    let draws = 20_000;
    let mut mean_scale = 0.0;
    for _ in 0..draws {
        // Prior position error ~ N(0, 100 I) in the aligned frame (isotropic: any frame).
        let e0 = frame * Vector::<3>::new(n(), n(), n()) * 10.0;
        let mean = Vector::<6>::new(
            truth[0] + e0[0],
            35.0,
            truth[1] + e0[1],
            0.0,
            truth[2] + e0[2],
            -1.8,
        );
        let w =
            frame * Vector::<3>::new(n(), n(), n()).component_mul(&(r0 * lambda).map(f64::sqrt));
        let plot = ConvertedPlot::new(truth + w, frame, r0).unwrap();
        // The update itself (no prediction: the prior covariance is the one stated above).
        let (_, info) = f.update(&state(mean, frame, &r0_cart), &plot).unwrap();
        let s = frame.transpose() * info.sample * frame;
        mean_scale += (0..3).map(|i| s[(i, i)] / r0[i]).sum::<f64>() / 3.0 / draws as f64;
    }
    eprintln!("mean start-up scale sample {mean_scale:.3} (λ = {lambda})");
    assert!((mean_scale / lambda - 1.0).abs() < 0.06, "{mean_scale}");
}

#[test]
fn the_plot_is_fused_with_the_scaled_r_then_the_paper_takes_over() {
    let frame = aligned_frame(3.1, 0.05);
    let r0 = Vector::<3>::new(4.0, 9.0, 1.0);
    let r0_cart = frame * Matrix::<3, 3>::from_diagonal(&r0) * frame.transpose();
    let f = filter();
    let mean = Vector::<6>::new(-3000.0, 35.0, -100.0, 0.0, 157.0, -1.8);
    let st = state(mean, frame, &r0_cart);
    let pos = Vector::<3>::new(-3000.0, -100.0, 157.0);
    // Innovation 60 m along the range axis, 0 elsewhere: λ sample = ((3600 − 100)/4 − 100/9 − 100)/3.
    let plot = ConvertedPlot::new(pos + frame.column(0) * 60.0, frame, r0).unwrap();
    let (post, info) = f.update(&st, &plot).unwrap();
    let want = ((3600.0 - 100.0) / 4.0 - 100.0 / 9.0 - 100.0) / 3.0;
    for i in 0..3 {
        // Algebra, so 1e-9 relative (round-off only).
        let got = info.aligned_r[i] / r0[i];
        assert!((got / want - 1.0).abs() < 1e-9, "axis {i}: {got} vs {want}");
    }
    assert_eq!(post.r.count(), 1);
    let r_hat = frame.transpose() * post.r.r_hat() * frame;
    assert!((r_hat[(0, 0)] / (want * 4.0) - 1.0).abs() < 1e-9);
    // A plot on the prediction: the sample mean is negative, so λ̄ is floored at 1 (R₀).
    let (_, quiet) = f
        .update(&st, &ConvertedPlot::new(pos, frame, r0).unwrap())
        .unwrap();
    assert!((quiet.aligned_r - r0).amax() < 1e-12);
    // After L start-up updates the paper's post-fit sample takes over.
    let mut s = st;
    for k in 0..=L {
        let p = f.predict(&s, 0.1).unwrap();
        let (next, info) = f.update(&p, &plot).unwrap();
        let post_fit = post_fit_sample(&info.post_fit_residual, &next.estimate.position_cov());
        let is_post_fit = (info.sample - post_fit).amax() < 1e-9 * post_fit.amax();
        assert_eq!(is_post_fit, k == L, "update {k}");
        s = next;
    }
}
