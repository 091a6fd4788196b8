//! [`ModeTrack`] and [`ForwardRecord`], the one interface of the IMM's and the aircraft
//! IMM's recorded tracks: a record built through it is the one built by the track's own
//! methods, its smoother over all steps is the track's fixed-interval smoother and over a
//! window the smoother of that window's steps (bit for bit: the same arithmetic), and a bad
//! window or a failed record gives an error, never a panic.

// A test binary: a panic on an unexpected error is the failure report.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::{Kf, SmoothError};
use argus_imm::{
    AircraftRadar, AircraftTrack, AircraftTuning, ForwardRecord, Imm, ImmEstimate, ImmSmoothError,
    ImmTrack, MarkovMatrix, ModeTrack, PairWeights, aircraft_smooth, imm_smooth,
};
use argus_motion_models::Cv2D;
use argus_sensors::{CartesianPosition, RadarNoise};

type Imm2 = Imm<Kf<Cv2D>, 4, 2>;

fn imm2() -> Imm2 {
    Imm::new(
        [
            Kf::new(Cv2D::discrete(0.1).unwrap()),
            Kf::new(Cv2D::discrete(3.0).unwrap()),
        ],
        MarkovMatrix::new([[0.9, 0.1], [0.1, 0.9]]).unwrap(),
    )
    .unwrap()
}

/// The IMM's posteriors over 30 plots of a target that speeds up at t = 40 s (so both
/// modes matter), one plot every 2–3 s; the first is the start.
fn imm_posteriors(imm: &Imm2) -> Vec<(f64, ImmEstimate<4, 2>)> {
    let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 400.0).unwrap();
    let g = Gaussian::new(
        Vector::<4>::new(0.0, 10.0, 0.0, -5.0),
        Matrix::<4, 4>::identity() * 1e4,
    )
    .unwrap();
    let mut est = ImmEstimate::from_common(g, [0.5, 0.5]).unwrap();
    let (mut t, mut out) = (0.0, vec![(0.0, est)]);
    for k in 1..30 {
        let tn = 2.0 * f64::from(k) + 0.5 * f64::from(k % 3);
        let x = 10.0 * tn
            + if tn > 40.0 {
                2.0 * (tn - 40.0).powi(2)
            } else {
                0.0
            };
        let z = Vector::<2>::new(x + 7.0 * f64::from(k % 5) - 14.0, -5.0 * tn);
        est = imm.step(&est, tn - t, &pos, &z).unwrap().estimate;
        out.push((tn, est));
        t = tn;
    }
    out
}

/// `T`'s record of `posteriors` through the trait alone.
fn record<T: ForwardRecord<M, 4>, M>(imm: &M, posteriors: &[(f64, T::Estimate)]) -> T
where
    T::Estimate: Copy,
{
    let mut track = T::start(imm, posteriors[0].0, posteriors[0].1).unwrap();
    track.reserve(posteriors.len() - 1);
    for (t, e) in &posteriors[1..] {
        track.push(imm, *t, *e).unwrap();
    }
    track
}

fn same(a: &Gaussian<4>, b: &Gaussian<4>) -> bool {
    a.mean() == b.mean() && a.cov() == b.cov()
}

#[test]
fn the_imm_track_through_the_trait() {
    let imm = imm2();
    let posts = imm_posteriors(&imm);
    let track: ImmTrack<4, 2> = record(&imm, &posts);
    assert_eq!(track.step_count(), posts.len());
    assert_eq!(
        track.latest_time().to_bits(),
        posts[posts.len() - 1].0.to_bits()
    );
    // The same record as the track's own methods build.
    let mut own = ImmTrack::new(*imm.markov(), posts[0].0, posts[0].1).unwrap();
    for (t, e) in &posts[1..] {
        own.push(&imm, *t, *e).unwrap();
    }
    assert_eq!(own, track);
    // Over all steps: the fixed-interval smoother, bit for bit.
    let all = track.smooth_steps(0, posts.len() - 1).unwrap();
    let fixed = own.smooth().unwrap();
    assert_eq!(all, fixed);
    // Over a window: the smoother of that window's steps alone, bit for bit, and not the
    // fixed-interval one (the later plots are ignored).
    let window = track.smooth_steps(5, 12).unwrap();
    let direct = imm_smooth(imm.markov(), PairWeights::default(), &own.steps()[5..=12]).unwrap();
    assert_eq!(window, direct);
    assert_eq!(window.len(), 8);
    assert!(!same(
        ImmTrack::combined(&window[0]),
        ImmTrack::combined(&fixed[5])
    ));
    // The window's last step is the filter's posterior.
    let filtered = own.steps()[12].filtered().combined().unwrap();
    let last = ImmTrack::combined(&window[7]);
    assert!((last.mean() - filtered.mean()).amax() < 1e-9 * filtered.mean().amax());
    let mu = ImmTrack::mode_probabilities(&window[7]);
    assert_eq!(mu, own.steps()[12].filtered().mode_probabilities());
}

#[test]
fn bad_windows_and_failed_records_are_errors() {
    let imm = imm2();
    let posts = imm_posteriors(&imm);
    let mut track: ImmTrack<4, 2> = record(&imm, &posts[..10]);
    let past = ImmSmoothError::Sequence(SmoothError::LengthMismatch {
        what: "smoothing window's last step (against the recorded steps)",
        expected: 10,
        found: 11,
    });
    assert_eq!(track.smooth_steps(3, 10).unwrap_err(), past);
    // first > last: an empty window.
    assert!(matches!(
        track.smooth_steps(6, 5).unwrap_err(),
        ImmSmoothError::Sequence(SmoothError::LengthMismatch { .. })
    ));
    // usize::MAX as the last step does not overflow.
    assert!(track.smooth_steps(0, usize::MAX).is_err());
    // A push going back in time is recorded: every window then fails with it.
    let err = ForwardRecord::<Imm2, 4>::push(&mut track, &imm, 1.0, posts[1].1).unwrap_err();
    assert!(matches!(
        err,
        ImmSmoothError::Sequence(SmoothError::TimeNotIncreasing { step: 10, .. })
    ));
    assert_eq!(track.smooth_steps(0, 9).unwrap_err(), err);
    // A non-finite start time.
    assert!(<ImmTrack<4, 2> as ForwardRecord<Imm2, 4>>::start(&imm, f64::NAN, posts[0].1).is_err());
}

#[test]
fn the_aircraft_track_through_the_trait() {
    let tuning = AircraftTuning::<2, 3>::default();
    let imm = tuning.build().unwrap();
    let radar = AircraftRadar::new(
        [0.0, 0.0],
        RadarNoise::constant(50.0, 0.1_f64.to_radians(), 0.0).unwrap(),
    )
    .unwrap();
    // A target flying east at 200 m/s, 40 km north, then turning at 3 °/s from t = 60 s;
    // plots every 4 s, noise-free (the records are compared, not the accuracy).
    let truth = |t: f64| -> (f64, f64) {
        if t <= 60.0 {
            (-20_000.0 + 200.0 * t, 40_000.0)
        } else {
            let w = 3.0_f64.to_radians();
            let a = w * (t - 60.0);
            (
                -8_000.0 + 200.0 / w * a.sin(),
                40_000.0 + 200.0 / w * (1.0 - a.cos()),
            )
        }
    };
    let plot = |t: f64| {
        let (x, y) = truth(t);
        Vector::<2>::new(x.hypot(y), y.atan2(x))
    };
    let start = tuning.start(&radar, &plot(0.0), &plot(4.0), 4.0).unwrap();
    let mut own = AircraftTrack::new(*imm.markov(), 4.0, start).unwrap();
    let mut posts = vec![(4.0, start)];
    for k in 2..40 {
        let t = 4.0 * f64::from(k);
        own.step(&imm, t, &radar, &plot(t)).unwrap();
        posts.push((t, *own.latest()));
    }
    let track: AircraftTrack<2, 3> = record(&imm, &posts);
    assert_eq!(track.step_count(), 39);
    assert_eq!(track.latest_time().to_bits(), 156.0_f64.to_bits());
    let all = track.smooth_steps(0, 38).unwrap();
    assert_eq!(all, track.smooth().unwrap());
    assert_eq!(all, own.smooth().unwrap());
    let window = track.smooth_steps(10, 20).unwrap();
    let direct = aircraft_smooth(
        imm.markov(),
        PairWeights::default(),
        &track.steps()[10..=20],
    )
    .unwrap();
    assert_eq!(window, direct);
    assert_eq!(
        AircraftTrack::mode_probabilities(&window[10]).len(),
        3,
        "two CV modes and the CT mode"
    );
    assert!(matches!(
        track.smooth_steps(30, 39).unwrap_err(),
        ImmSmoothError::Sequence(SmoothError::LengthMismatch {
            expected: 39,
            found: 40,
            ..
        })
    ));
}
