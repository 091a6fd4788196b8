//! Monte Carlo check of the converted measurements at a large cross-range error
//! (r = 50 km, σr = 50 m, σθ = 2°: r σθ² / σr = 1.22, the regime where
//! Lerro & Bar-Shalom (1993) show the linearised conversion to be inconsistent).
//!
//! For each method: the mean conversion error projected on the truth's range and
//! cross-range axes, against its expected value within 4 standard errors
//! (sample standard deviation / √n; two-sided p ≈ 6e−5 per check), and the
//! average NEES of the error against the method's own covariance, against the
//! two-sided 95 % chi-square interval for n draws (BLK 2001 §5.4.2).

#![allow(clippy::unwrap_used)] // test helpers: a failure is a test failure

use argus_core_math::{Matrix, SpdFactor, Vector, anees_interval};

type Matrix3 = Matrix<3, 3>;
use argus_sensors::{ConversionMethod, convert_polar, convert_spherical};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

const DRAWS: usize = 20_000;
const R: f64 = 50_000.0;
const SIGMA_R: f64 = 50.0;

fn sigma_angle() -> f64 {
    2f64.to_radians()
}

/// Running statistics of the error projected on D axes and of the NEES.
struct Stats<const D: usize> {
    sum: Vector<D>,
    sum_sq: Vector<D>,
    nees: f64,
    n: usize,
}

impl<const D: usize> Stats<D> {
    fn new() -> Self {
        Self {
            sum: Vector::<D>::zeros(),
            sum_sq: Vector::<D>::zeros(),
            nees: 0.0,
            n: 0,
        }
    }
    fn push(&mut self, projected: Vector<D>, nees: f64) {
        self.sum += projected;
        self.sum_sq += projected.component_mul(&projected);
        self.nees += nees;
        self.n += 1;
    }
    fn mean(&self) -> Vector<D> {
        self.sum / self.n as f64
    }
    /// Standard error of the mean per axis.
    fn std_err(&self) -> Vector<D> {
        let n = self.n as f64;
        let m = self.mean();
        (self.sum_sq / n - m.component_mul(&m)).map(|v| (v.max(0.0) * n / (n - 1.0) / n).sqrt())
    }
    fn anees(&self) -> f64 {
        self.nees / self.n as f64
    }
}

fn run_2d(method: ConversionMethod, seed: u64) -> Stats<2> {
    let theta: f64 = 30f64.to_radians();
    let truth = Vector::<2>::new(R * theta.cos(), R * theta.sin());
    let u_range = Vector::<2>::new(theta.cos(), theta.sin());
    let u_cross = Vector::<2>::new(-theta.sin(), theta.cos());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut st = Stats::<2>::new();
    for _ in 0..DRAWS {
        let n1: f64 = StandardNormal.sample(&mut rng);
        let n2: f64 = StandardNormal.sample(&mut rng);
        let rm = R + SIGMA_R * n1;
        let tm = theta + sigma_angle() * n2;
        let c = convert_polar(rm, tm, SIGMA_R, sigma_angle(), method).unwrap();
        let e = c.position - truth;
        let nees = SpdFactor::new_symmetric(&c.covariance, "R_c")
            .unwrap()
            .mahalanobis_sq(&e);
        st.push(Vector::<2>::new(e.dot(&u_range), e.dot(&u_cross)), nees);
    }
    st
}

#[test]
fn polar_conversions_bias_and_consistency() {
    let s2 = sigma_angle() * sigma_angle();
    let lambda = (-0.5 * s2).exp();
    // Derived: E[r_m cos(θ + w)] = r λ, so the linearised conversion's mean error
    // along the range axis is −r(1 − λ) = −50 000·(1 − e^{−6.0923e−4}) = −30.45 m,
    // and 0 along the cross-range axis (E[sin w] = 0).
    let lin_bias = -R * (1.0 - lambda);
    assert!((lin_bias + 30.45).abs() < 0.01);
    let interval = anees_interval(2, DRAWS, 0.95).unwrap();

    let unb = run_2d(ConversionMethod::Unbiased, 1);
    let (m, se) = (unb.mean(), unb.std_err());
    println!(
        "unbiased: mean {m:?} se {se:?} ANEES {} in {interval:?}",
        unb.anees()
    );
    assert!(
        m[0].abs() < 4.0 * se[0],
        "range-axis mean {} vs se {}",
        m[0],
        se[0]
    );
    assert!(m[1].abs() < 4.0 * se[1]);
    assert!(
        interval.contains(unb.anees()),
        "unbiased ANEES {}",
        unb.anees()
    );

    let lin = run_2d(ConversionMethod::Linearized, 1);
    let (m, se) = (lin.mean(), lin.std_err());
    println!("linearised: mean {m:?} se {se:?} ANEES {}", lin.anees());
    assert!(
        (m[0] - lin_bias).abs() < 4.0 * se[0],
        "range-axis mean {} vs {lin_bias}",
        m[0]
    );
    assert!(m[0].abs() > 20.0 * se[0], "the bias must be significant");
    assert!(m[1].abs() < 4.0 * se[1]);
    assert!(
        lin.anees() > interval.upper,
        "linearised ANEES {}",
        lin.anees()
    );

    // Debiased: the residual bias is second order, r(λ + λ² − λ³ − 1) ≈ −2r(1−λ)² = −0.037 m,
    // far below the standard error (~0.5 m), so it must test as unbiased.
    let deb = run_2d(ConversionMethod::Debiased, 1);
    let (m, se) = (deb.mean(), deb.std_err());
    println!("debiased: mean {m:?} se {se:?} ANEES {}", deb.anees());
    assert!(m[0].abs() < 4.0 * se[0]);
    assert!(m[1].abs() < 4.0 * se[1]);
    assert!(
        interval.contains(deb.anees()),
        "debiased ANEES {}",
        deb.anees()
    );
}

fn run_3d(method: ConversionMethod, seed: u64) -> (Stats<3>, Vector<3>) {
    let (psi, el): (f64, f64) = (30f64.to_radians(), 20f64.to_radians());
    let (sp, cp) = psi.sin_cos();
    let (se, ce) = el.sin_cos();
    let truth = Vector::<3>::new(R * cp * ce, R * sp * ce, R * se);
    let axes = [
        Vector::<3>::new(cp * ce, sp * ce, se),   // range
        Vector::<3>::new(-sp, cp, 0.0),           // cross-range, azimuth
        Vector::<3>::new(-cp * se, -sp * se, ce), // cross-range, elevation
    ];
    let sa = sigma_angle();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut st = Stats::<3>::new();
    for _ in 0..DRAWS {
        let n: [f64; 3] = [
            StandardNormal.sample(&mut rng),
            StandardNormal.sample(&mut rng),
            StandardNormal.sample(&mut rng),
        ];
        let c = convert_spherical(
            R + SIGMA_R * n[0],
            psi + sa * n[1],
            el + sa * n[2],
            [SIGMA_R, sa, sa],
            method,
        )
        .unwrap();
        let e = c.position - truth;
        let nees = SpdFactor::new_symmetric(&c.covariance, "R_c")
            .unwrap()
            .mahalanobis_sq(&e);
        st.push(
            Vector::<3>::new(e.dot(&axes[0]), e.dot(&axes[1]), e.dot(&axes[2])),
            nees,
        );
    }
    // Derived linearised bias: E[p_m] = L ⊙ p, L = (λ², λ², λ) for σψ = σθ, projected on the axes.
    let lam = (-0.5 * sa * sa).exp();
    let bias = (Vector::<3>::new(lam * lam, lam * lam, lam) - Vector::<3>::repeat(1.0))
        .component_mul(&truth);
    (
        st,
        Vector::<3>::new(bias.dot(&axes[0]), bias.dot(&axes[1]), bias.dot(&axes[2])),
    )
}

#[test]
fn spherical_conversions_bias_and_consistency() {
    let interval = anees_interval(3, DRAWS, 0.95).unwrap();
    let (unb, lin_bias) = run_3d(ConversionMethod::Unbiased, 2);
    // With λ = e^{−σ²/2} = 0.999 391: range-axis bias −r[(1−λ²)cos²θ + (1−λ)sin²θ]
    // = −50 000·(1.2177e−3·0.883 + 6.0905e−4·0.117) = −57.33 m; elevation axis
    // r sinθ cosθ λ(1−λ) = +9.78 m; azimuth axis 0.
    assert!((lin_bias[0] + 57.33).abs() < 0.05, "{lin_bias:?}");
    assert!((lin_bias[2] - 9.78).abs() < 0.05, "{lin_bias:?}");
    assert!(lin_bias[1].abs() < 1e-9);

    let (m, se) = (unb.mean(), unb.std_err());
    println!(
        "3-D unbiased: mean {m:?} se {se:?} ANEES {} in {interval:?}",
        unb.anees()
    );
    for k in 0..3 {
        assert!(
            m[k].abs() < 4.0 * se[k],
            "axis {k}: mean {} se {}",
            m[k],
            se[k]
        );
    }
    assert!(
        interval.contains(unb.anees()),
        "unbiased ANEES {}",
        unb.anees()
    );

    let (lin, _) = run_3d(ConversionMethod::Linearized, 2);
    let (m, se) = (lin.mean(), lin.std_err());
    println!("3-D linearised: mean {m:?} se {se:?} ANEES {}", lin.anees());
    for k in 0..3 {
        assert!(
            (m[k] - lin_bias[k]).abs() < 4.0 * se[k],
            "axis {k}: {} vs {}",
            m[k],
            lin_bias[k]
        );
    }
    assert!(m[0].abs() > 20.0 * se[0]);
    assert!(
        lin.anees() > interval.upper,
        "linearised ANEES {}",
        lin.anees()
    );

    let (deb, _) = run_3d(ConversionMethod::Debiased, 2);
    let (m, se) = (deb.mean(), deb.std_err());
    println!("3-D debiased: mean {m:?} se {se:?} ANEES {}", deb.anees());
    for k in 0..3 {
        assert!(
            m[k].abs() < 4.0 * se[k],
            "axis {k}: mean {} se {}",
            m[k],
            se[k]
        );
    }
    // Not consistent here: ANEES 3.53 against [2.97, 3.03] (seed 2; numpy with
    // another seed and 2e5 draws gives 3.54). Lerro's construction R_a = E[R_t | plot]
    // carried to 3-D is implemented exactly (see `debiased_covariance_is_average_of_true_covariance`
    // below), so this is a property of the method, not of the code: with two noisy
    // angles its range-axis terms of order r²σ⁴ (≈ 3.7e3 m² against σr² = 2.5e3 m²)
    // do not match the error. With one noisy angle it is consistent (2-D test above).
    // Prefer the unbiased conversion in 3-D.
    assert!(
        deb.anees() > interval.upper,
        "debiased ANEES {}",
        deb.anees()
    );
    assert!(
        (deb.anees() - 3.53).abs() < 0.1,
        "debiased ANEES {}",
        deb.anees()
    );
}

/// Independent check of the 3-D debiased covariance algebra: it must equal the
/// average over the truth given the plot (truth = plot − noise) of the true
/// covariance `R_t = E[p_m p_mᵀ | truth] − (L ⊙ p)(L ⊙ p)ᵀ`, estimated here by
/// Monte Carlo over 200 000 truth hypotheses. `R_t` at a truth is itself
/// closed-form (E[cos ψ_m | ψ] = λ cos ψ, E[cos² ψ_m | ψ] = ½(1 + λ' cos 2ψ), …).
#[test]
fn debiased_covariance_is_average_of_true_covariance() {
    let (rm, psi_m, el_m) = (50_100.0, 0.6_f64, 0.3_f64);
    let sa = sigma_angle();
    let (l1, l2) = ((-0.5 * sa * sa).exp(), (-2.0 * sa * sa).exp());
    let c = convert_spherical(
        rm,
        psi_m,
        el_m,
        [SIGMA_R, sa, sa],
        ConversionMethod::Debiased,
    )
    .unwrap();
    let u = Vector::<3>::new(
        psi_m.cos() * el_m.cos(),
        psi_m.sin() * el_m.cos(),
        el_m.sin(),
    );
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let k = 200_000;
    let (mut sum, mut sum_sq) = (Matrix3::zeros(), 0.0);
    let mut sum_range = 0.0;
    for _ in 0..k {
        let n: [f64; 3] = [
            StandardNormal.sample(&mut rng),
            StandardNormal.sample(&mut rng),
            StandardNormal.sample(&mut rng),
        ];
        let (r, psi, el) = (rm - SIGMA_R * n[0], psi_m - sa * n[1], el_m - sa * n[2]);
        let rho2 = r * r + SIGMA_R * SIGMA_R;
        let (cp2, sp2, scp) = (
            0.5 * (1.0 + l2 * (2.0 * psi).cos()),
            0.5 * (1.0 - l2 * (2.0 * psi).cos()),
            0.5 * l2 * (2.0 * psi).sin(),
        );
        let (ct2, st2, sct) = (
            0.5 * (1.0 + l2 * (2.0 * el).cos()),
            0.5 * (1.0 - l2 * (2.0 * el).cos()),
            0.5 * l2 * (2.0 * el).sin(),
        );
        let (cp, sp) = (l1 * psi.cos(), l1 * psi.sin());
        let second = Matrix3::new(
            rho2 * cp2 * ct2,
            rho2 * scp * ct2,
            rho2 * cp * sct,
            rho2 * scp * ct2,
            rho2 * sp2 * ct2,
            rho2 * sp * sct,
            rho2 * cp * sct,
            rho2 * sp * sct,
            rho2 * st2,
        );
        let mean = Vector::<3>::new(
            r * cp * l1 * el.cos(),
            r * sp * l1 * el.cos(),
            r * l1 * el.sin(),
        );
        let rt = second - mean * mean.transpose();
        let along = (u.transpose() * rt * u)[0];
        sum += rt;
        sum_range += along;
        sum_sq += along * along;
    }
    let kf = k as f64;
    let avg = sum / kf;
    // Standard error of the range-axis average (the smallest, most sensitive entry).
    let mean_range = sum_range / kf;
    let se_range = ((sum_sq / kf - mean_range * mean_range) / kf).sqrt();
    let closed_range = (u.transpose() * c.covariance * u)[0];
    assert!(
        (closed_range - mean_range).abs() < 4.0 * se_range,
        "range axis: closed form {closed_range}, Monte Carlo {mean_range} ± {se_range}"
    );
    // Every entry within 1e-4 of the diagonal scale (MC relative error ≈ 2e-5 at 2e5 samples).
    let scale = avg.diagonal().amax();
    assert!(
        (avg - c.covariance).amax() < 1e-4 * scale,
        "{avg} vs {}",
        c.covariance
    );
}
