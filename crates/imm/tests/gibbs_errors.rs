//! The Gibbs smoother's bad input: typed errors naming the step, never a panic.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::smooth::gibbs::{
    GibbsChain, GibbsConfig, GibbsError, GibbsProblem, gibbs_smooth, pooled,
};
use argus_imm::{Imm, MarkovMatrix};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::{CartesianPosition, LinearMeasurementModel, MeasurementModel};

type Pos = CartesianPosition<4, 2>;

fn imm() -> Imm<Kf<PlanarModel>, 4, 2> {
    Imm::new(
        [
            Kf::new(PlanarModel::from(Cv2D::discrete(0.1).unwrap())),
            Kf::new(PlanarModel::from(
                CoordinatedTurn::from_degrees_per_second(3.0, 0.5).unwrap(),
            )),
        ],
        // CT never follows itself: a sequence of two CT steps has zero prior.
        MarkovMatrix::new([[0.9, 0.1], [1.0, 0.0]]).unwrap(),
    )
    .unwrap()
}

fn start() -> Gaussian<4> {
    Gaussian::new(
        Vector::<4>::new(0.0, 100.0, 0.0, 0.0),
        Matrix::<4, 4>::identity() * 1e4,
    )
    .unwrap()
}

fn track(n: usize) -> (Vec<f64>, Vec<(Pos, Vector<2>)>) {
    let pos = Pos::cv(Matrix::<2, 2>::identity() * 2500.0).unwrap();
    let times: Vec<f64> = (0..=n).map(|k| 5.0 * k as f64).collect();
    let plots = times[1..]
        .iter()
        .map(|t| (pos, Vector::<2>::new(100.0 * t, 0.0)))
        .collect();
    (times, plots)
}

/// A position measurement whose noise is not positive definite (a zero variance).
#[derive(Debug, Clone, Copy)]
struct Degenerate;

impl MeasurementModel<4, 2> for Degenerate {
    fn predict(&self, x: &Vector<4>) -> Vector<2> {
        Vector::<2>::new(x[0], x[2])
    }
    fn jacobian(&self, _x: &Vector<4>) -> Matrix<2, 4> {
        self.matrix()
    }
    fn noise(&self, _x: &Vector<4>) -> Matrix<2, 2> {
        Matrix::<2, 2>::new(100.0, 0.0, 0.0, 0.0)
    }
}

impl LinearMeasurementModel<4, 2> for Degenerate {
    fn matrix(&self) -> Matrix<2, 4> {
        Matrix::<2, 4>::new(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0)
    }
}

#[test]
fn bad_problems_get_errors_naming_the_step() {
    let imm = imm();
    let (times, plots) = track(6);
    let mu0 = [0.5, 0.5];
    // Lengths: times must be one longer than plots.
    let e = GibbsProblem::new(&imm, mu0, &start(), &times[..6], &plots).unwrap_err();
    assert!(
        matches!(
            e,
            GibbsError::LengthMismatch {
                expected: 7,
                got: 6,
                ..
            }
        ),
        "{e}"
    );
    // Time going backwards at step 4.
    let mut back = times.clone();
    back[4] = back[2];
    let e = GibbsProblem::new(&imm, mu0, &start(), &back, &plots).unwrap_err();
    assert!(
        matches!(e, GibbsError::TimeNotIncreasing { step: 4, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("step 4"), "{e}");
    // A NaN plot at step 3.
    let mut nan = plots.clone();
    nan[2].1[0] = f64::NAN;
    let e = GibbsProblem::new(&imm, mu0, &start(), &times, &nan).unwrap_err();
    assert!(matches!(e, GibbsError::NonFinite { step: 3, .. }), "{e}");
    // A measurement noise that is not positive definite at step 1.
    let bad: Vec<(Degenerate, Vector<2>)> = plots.iter().map(|p| (Degenerate, p.1)).collect();
    let e = GibbsProblem::new(&imm, mu0, &start(), &times, &bad).unwrap_err();
    assert!(
        matches!(e, GibbsError::NotPositiveDefinite { step: 1, .. }),
        "{e}"
    );
    // A prior that does not sum to 1.
    let e = GibbsProblem::new(&imm, [0.5, 0.6], &start(), &times, &plots).unwrap_err();
    assert_eq!(e, GibbsError::InvalidPrior);
}

#[test]
fn bad_sequences_and_settings_get_errors() {
    let imm = imm();
    let (times, plots) = track(6);
    let p = GibbsProblem::new(&imm, [0.5, 0.5], &start(), &times, &plots).unwrap();
    // CT → CT (zero prior) at step 3; a mode out of range at step 2; a short sequence.
    let e = GibbsChain::new(&p, &[0, 0, 1, 1, 0, 0, 0], 1, 2).unwrap_err();
    assert_eq!(e, GibbsError::InvalidSequence { step: 3, mode: 1 });
    let e = GibbsChain::new(&p, &[0, 0, 2, 0, 0, 0, 0], 1, 2).unwrap_err();
    assert_eq!(e, GibbsError::InvalidSequence { step: 2, mode: 2 });
    let e = GibbsChain::new(&p, &[0, 0], 1, 2).unwrap_err();
    assert!(matches!(e, GibbsError::LengthMismatch { .. }), "{e}");
    // Block 0, a block of more than 65 536 paths, no recorded sweep.
    for block in [0, 17] {
        let e = GibbsChain::new(&p, &[0; 7], 1, block).unwrap_err();
        assert!(
            matches!(e, GibbsError::InvalidConfig { what: "block", .. }),
            "{e}"
        );
    }
    let cfg = GibbsConfig {
        sweeps: 0,
        ..GibbsConfig::default()
    };
    let e = gibbs_smooth(&p, &cfg, None).unwrap_err();
    assert!(
        matches!(e, GibbsError::InvalidConfig { what: "sweeps", .. }),
        "{e}"
    );
    let chain = GibbsChain::new(&p, &[0; 7], 1, 2).unwrap();
    let e = pooled(std::slice::from_ref(&chain)).unwrap_err();
    assert!(matches!(e, GibbsError::InvalidConfig { .. }), "{e}");
    // The most probable modes made a valid start: CT twice becomes CT, CV.
    let seq = p
        .most_probable_sequence([
            [0.9, 0.1],
            [0.2, 0.8],
            [0.1, 0.9],
            [0.9, 0.1],
            [1.0, 0.0],
            [1.0, 0.0],
            [1.0, 0.0],
        ])
        .unwrap();
    assert_eq!(seq, [0, 1, 0, 0, 0, 0, 0]);
    assert!(GibbsChain::new(&p, &seq, 1, 2).is_ok());
    // The same seed gives the same estimate, bit for bit (a chain depends on its seed only).
    let cfg = GibbsConfig {
        block: 2,
        burn_in: 3,
        sweeps: 10,
        seed: 9,
    };
    let a = gibbs_smooth(&p, &cfg, Some(&seq)).unwrap();
    let b = gibbs_smooth(&p, &cfg, Some(&seq)).unwrap();
    assert_eq!(a, b);
    assert_eq!(a.len(), 7);
}
