//! `Imm::step_in_place` is `Imm::step` written into the estimate: the same bits along a
//! turning track, and the estimate restored on a bad interval or plot.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::{Imm, ImmError, ImmEstimate, MarkovMatrix};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_sensors::CartesianPosition;

fn imm() -> Imm<Kf<PlanarModel>, 4, 3> {
    let w = 3.0_f64.to_radians();
    Imm::new(
        [
            Kf::new(PlanarModel::from(Cv2D::discrete(0.5).unwrap())),
            Kf::new(PlanarModel::from(CoordinatedTurn::new(w, 0.5).unwrap())),
            Kf::new(PlanarModel::from(CoordinatedTurn::new(-w, 0.5).unwrap())),
        ],
        MarkovMatrix::new([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]).unwrap(),
    )
    .unwrap()
}

fn start() -> ImmEstimate<4, 3> {
    let g = Gaussian::new(
        Vector::<4>::new(-60_000.0, 90.0, -20_000.0, 0.0),
        Matrix::<4, 4>::identity() * 1e4,
    )
    .unwrap();
    ImmEstimate::from_common(g, [1.0 / 3.0; 3]).unwrap()
}

#[test]
fn step_in_place_equals_step_bit_for_bit() {
    let imm = imm();
    let meas =
        CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::new(900.0, 40.0, 40.0, 400.0)).unwrap();
    let (mut a, mut b) = (start(), start());
    let (mut x, mut y, mut heading) = (-60_000.0_f64, -20_000.0_f64, 0.0_f64);
    for k in 0..120 {
        // Varying intervals and a 3°/s turn in the middle, so every mode leads for a while.
        #[allow(clippy::cast_precision_loss)]
        let dt = 4.0 + 0.25 * (k % 5) as f64;
        if (40..70).contains(&k) {
            heading += 3.0_f64.to_radians() * dt;
        }
        x += 90.0 * heading.cos() * dt;
        y += 90.0 * heading.sin() * dt;
        #[allow(clippy::cast_precision_loss)]
        let z = Vector::<2>::new(x + 20.0 * (k as f64).sin(), y - 15.0 * (k as f64).cos());
        let upd = imm.step(&a, dt, &meas, &z).unwrap();
        let (ll, mode_ll) = imm.step_in_place(&mut b, dt, &meas, &z).unwrap();
        a = upd.estimate;
        // Exact equality: the same arithmetic in the same order, only the copies differ.
        assert_eq!(a, b, "step {k}");
        assert_eq!(upd.log_likelihood.to_bits(), ll.to_bits(), "step {k}");
        assert_eq!(
            upd.mode_log_likelihoods.map(f64::to_bits),
            mode_ll.map(f64::to_bits),
            "step {k}"
        );
    }
}

#[test]
fn step_in_place_leaves_the_estimate_unchanged_on_an_error() {
    let imm = imm();
    let meas = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 100.0).unwrap();
    let mut est = start();
    let copy = est;
    let z = Vector::<2>::new(-59_500.0, -20_000.0);
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            imm.step_in_place(&mut est, dt, &meas, &z),
            Err(ImmError::InvalidInterval { .. })
        ));
        assert_eq!(est, copy);
    }
    // A NaN plot fails the first mode's update, after every mode was predicted in place.
    assert!(matches!(
        imm.step_in_place(&mut est, 5.0, &meas, &Vector::<2>::new(f64::NAN, 0.0)),
        Err(ImmError::Filter { mode: 0, .. })
    ));
    assert_eq!(est, copy);
}
