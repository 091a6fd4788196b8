//! Test support for the GLRT tests: a 1-D constant-velocity model, a position
//! sensor and a plain linear Kalman filter implementing `GaussianFilter<2>`, and the
//! seed-001 1-D maneuver simulation (SPEC section 001, scenario "maneuver-1d").
#![allow(dead_code, missing_docs, unreachable_pub, clippy::unwrap_used)]

use argus_adaptive::{
    Compensation, FailureKind, GlrtConfig, ManeuverFilter, ManeuverState, ModelInput,
};
use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{CovarianceForm, FilterError, GaussianFilter, MeasurementPrediction};
use argus_motion_models::MotionModel;
use argus_sensors::MeasurementModel;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// `[x, v]` constant velocity; process noise `q` (m/s)² on the velocity per step
/// (seed 001 section 5.1: `Q = 0.5`, entering the velocity only).
#[derive(Debug, Clone, Copy)]
pub struct Cv1 {
    pub q: f64,
}

impl MotionModel<2> for Cv1 {
    fn propagate(&self, x: &Vector<2>, dt: f64) -> Vector<2> {
        self.jacobian(x, dt) * x
    }
    fn jacobian(&self, _x: &Vector<2>, dt: f64) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(1.0, dt, 0.0, 1.0)
    }
    fn process_noise(&self, _x: &Vector<2>, _dt: f64) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(0.0, 0.0, 0.0, self.q)
    }
}

/// Position plot `y = x + v`, `v ~ N(0, r)`.
#[derive(Debug, Clone, Copy)]
pub struct Pos1 {
    pub r: f64,
}

impl MeasurementModel<2, 1> for Pos1 {
    fn predict(&self, x: &Vector<2>) -> Vector<1> {
        Vector::<1>::new(x[0])
    }
    fn jacobian(&self, _x: &Vector<2>) -> Matrix<1, 2> {
        Matrix::<1, 2>::new(1.0, 0.0)
    }
    fn noise(&self, _x: &Vector<2>) -> Matrix<1, 1> {
        Matrix::<1, 1>::new(self.r)
    }
}

/// A plain (extended) Kalman filter over any motion model, for these tests.
#[derive(Debug, Clone, Copy)]
pub struct TestKf<Mo> {
    pub model: Mo,
}

impl<Mo: MotionModel<2>> GaussianFilter<2> for TestKf<Mo> {
    fn predict(&self, prior: &Gaussian<2>, dt: f64) -> Result<Gaussian<2>, FilterError> {
        argus_filters::check_dt(dt)?;
        let f = self.model.jacobian(prior.mean(), dt);
        let q = self.model.process_noise(prior.mean(), dt);
        let mean = self.model.propagate(prior.mean(), dt);
        Ok(Gaussian::from_symmetrized(
            mean,
            &(f * prior.cov() * f.transpose() + q),
        )?)
    }

    fn predict_measurement<const M: usize, Me: MeasurementModel<2, M>>(
        &self,
        predicted: &Gaussian<2>,
        meas: &Me,
    ) -> Result<MeasurementPrediction<2, M>, FilterError> {
        let h = meas.jacobian(predicted.mean());
        let r = meas.noise(predicted.mean());
        let s = h * predicted.cov() * h.transpose() + r;
        MeasurementPrediction::new(
            meas.predict(predicted.mean()),
            s,
            predicted.cov() * h.transpose(),
            Some(h),
            r,
            CovarianceForm::Joseph,
        )
    }
}

pub const T: f64 = 0.05;
pub const Q: f64 = 0.5;
pub const R: f64 = 36.0;
pub const STEPS: usize = 160; // 8 s

pub fn gamma() -> Vector<2> {
    Vector::<2>::new(0.5 * T * T, T)
}

pub fn adaptive(comp: Compensation) -> ManeuverFilter<TestKf<Cv1>, ModelInput<Cv1, 2, 1>> {
    let model = Cv1 { q: Q };
    ManeuverFilter::new(
        TestKf { model },
        ModelInput::new(model, Matrix::<2, 1>::new(0.0, 1.0)).unwrap(),
        comp,
    )
}

pub fn config(m: usize, n: usize, eta: f64) -> GlrtConfig {
    GlrtConfig::new(m, n, eta, FailureKind::Persistent).unwrap()
}

/// The acceleration held over `[t_k, t_k + T)`.
pub fn accel(windows: &[(f64, f64)], a: f64, k: usize) -> f64 {
    let t = k as f64 * T;
    if windows
        .iter()
        .any(|&(on, off)| t >= on - 1e-9 && t < off - 1e-9)
    {
        a
    } else {
        0.0
    }
}

/// One run: truth (with process noise) and plots at `t_k = k T`, `k = 1..=STEPS`.
pub struct Run {
    pub truth: Vec<Vector<2>>,
    pub plots: Vec<f64>,
    pub initial: Gaussian<2>,
}

pub fn simulate(seed: u64, windows: &[(f64, f64)], a: f64) -> Run {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut n = || -> f64 { StandardNormal.sample(&mut rng) };
    let x0 = Vector::<2>::new(2000.0, 70.0);
    let p0 = Matrix::<2, 2>::new(100.0, 0.0, 0.0, 100.0);
    let init_mean = x0 + Vector::<2>::new(10.0 * n(), 10.0 * n());
    let phi = Matrix::<2, 2>::new(1.0, T, 0.0, 1.0);
    let mut x = x0;
    let mut truth = Vec::with_capacity(STEPS);
    let mut plots = Vec::with_capacity(STEPS);
    for k in 0..STEPS {
        x = phi * x + gamma() * accel(windows, a, k) + Vector::<2>::new(0.0, Q.sqrt() * n());
        truth.push(x);
        plots.push(x[0] + R.sqrt() * n());
    }
    Run {
        truth,
        plots,
        initial: Gaussian::new(init_mean, p0).unwrap(),
    }
}

/// Per-step position errors of the plain KF and of the adaptive filter, and the
/// steps (1-based index into the run) at which the adaptive filter detected.
pub struct Outcome {
    pub kf_err: Vec<f64>,
    pub ad_err: Vec<f64>,
    pub detections: Vec<usize>,
    pub kf_means: Vec<Vector<2>>,
    pub ad_means: Vec<Vector<2>>,
}

pub fn run_filters(run: &Run, cfg: GlrtConfig, comp: Compensation) -> Outcome {
    let kf = TestKf {
        model: Cv1 { q: Q },
    };
    let meas = Pos1 { r: R };
    let ad = adaptive(comp);
    let mut est = run.initial;
    let mut st = ManeuverState::<2, 1, 1>::new(run.initial, cfg);
    let mut out = Outcome {
        kf_err: Vec::new(),
        ad_err: Vec::new(),
        detections: Vec::new(),
        kf_means: Vec::new(),
        ad_means: Vec::new(),
    };
    for (k, (x, z)) in run.truth.iter().zip(&run.plots).enumerate() {
        let zv = Vector::<1>::new(*z);
        let pred = kf.predict(&est, T).unwrap();
        est = kf.update(&pred, &meas, &zv).unwrap().0;
        let rep = ad.step(&mut st, T, &meas, &zv).unwrap();
        if rep.detection.is_some() {
            out.detections.push(k);
        }
        out.kf_err.push(est.mean()[0] - x[0]);
        out.ad_err.push(st.estimate().mean()[0] - x[0]);
        out.kf_means.push(*est.mean());
        out.ad_means.push(*st.estimate().mean());
    }
    out
}
