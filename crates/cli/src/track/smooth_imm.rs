//! `argus track --smooth` / `--smooth-lag` for the IMM (`imm`, and the multi-IMM over its
//! merged posteriors): its forward pass recorded one step per time
//! ([`argus_imm::ImmTrack`], through [`ModeRecorder`]) and smoothed by `argus_imm`'s IMM
//! smoother ([`argus_imm::imm_smooth`]), fixed interval or, by windows of the same
//! backward pass, fixed lag.

use argus_imm::{ImmEstimate, ImmTrack};

use super::mode_record::ModeRecorder;

/// An IMM forward pass with `R` modes being recorded for smoothing.
pub(super) type ImmRecorder<const R: usize> = ModeRecorder<ImmTrack<4, R>, ImmEstimate<4, R>>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::smooth::Smoothing;
    use argus_core_math::{Gaussian, Matrix, Vector};
    use argus_filters::Kf;
    use argus_imm::{Imm, MarkovMatrix};
    use argus_motion_models::Cv2D;
    use argus_sensors::CartesianPosition;

    #[test]
    fn the_imm_record_keeps_one_step_per_time() {
        let imm = Imm::new(
            [
                Kf::new(Cv2D::discrete(0.1).unwrap()),
                Kf::new(Cv2D::discrete(3.0).unwrap()),
            ],
            MarkovMatrix::new([[0.9, 0.1], [0.1, 0.9]]).unwrap(),
        )
        .unwrap();
        let pos = CartesianPosition::<4, 2>::cv(Matrix::<2, 2>::identity() * 400.0).unwrap();
        let start = Gaussian::new(
            Vector::<4>::new(0.0, 10.0, 0.0, -5.0),
            Matrix::<4, 4>::identity() * 1e4,
        )
        .unwrap();
        let mut est = ImmEstimate::from_common(start, [0.5, 0.5]).unwrap();
        let mut rec = ImmRecorder::new();
        rec.record(&imm, 0.0, est).unwrap();
        let mut t = 0.0;
        // Plots at 2, 4, 4 (one instant twice), 7 s.
        for (tn, off) in [(2.0, 0.0), (4.0, 1.0), (4.0, 2.0), (7.0, 3.0)] {
            let z = Vector::<2>::new(10.0 * tn + off, -5.0 * tn);
            est = if tn > t {
                imm.step(&est, tn - t, &pos, &z).unwrap().estimate
            } else {
                imm.update(&est.into_prediction(), &pos, &z)
                    .unwrap()
                    .estimate
            };
            t = tn;
            rec.record(&imm, t, est).unwrap();
        }
        let last = est.combined().unwrap();
        let sm = rec.smooth(&imm, Smoothing::Interval).unwrap();
        // Four times, four steps; the last is the filter's (the second update at 4 s
        // is the step's estimate).
        assert_eq!(sm.len(), 4);
        assert_eq!(sm[3].combined, last);
    }
}
