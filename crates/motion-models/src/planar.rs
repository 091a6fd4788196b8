//! The closed set of planar 4-state models used by the IMMs.

use argus_core_math::{Matrix, Vector};

use crate::{CoordinatedTurn, Cv2D, LinearMotionModel, MotionModel};

/// A planar model on `[x, vx, y, vy]`: constant velocity or a coordinated turn at a known
/// rate. Every method delegates to the wrapped model.
///
/// # References
/// Seed 000 (Jeon et al. 2010): the IMM of one CV and two fixed-rate CT models.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum PlanarModel {
    /// Constant velocity.
    Cv(Cv2D),
    /// Coordinated turn at a known rate.
    Ct(CoordinatedTurn),
}

impl From<Cv2D> for PlanarModel {
    fn from(m: Cv2D) -> Self {
        Self::Cv(m)
    }
}

impl From<CoordinatedTurn> for PlanarModel {
    fn from(m: CoordinatedTurn) -> Self {
        Self::Ct(m)
    }
}

impl MotionModel<4> for PlanarModel {
    fn propagate(&self, x: &Vector<4>, dt: f64) -> Vector<4> {
        match self {
            Self::Cv(m) => m.propagate(x, dt),
            Self::Ct(m) => m.propagate(x, dt),
        }
    }

    fn jacobian(&self, x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        match self {
            Self::Cv(m) => m.jacobian(x, dt),
            Self::Ct(m) => m.jacobian(x, dt),
        }
    }

    fn process_noise(&self, x: &Vector<4>, dt: f64) -> Matrix<4, 4> {
        match self {
            Self::Cv(m) => m.process_noise(x, dt),
            Self::Ct(m) => m.process_noise(x, dt),
        }
    }

    fn propagate_covariance(&self, x: &Vector<4>, p: &Matrix<4, 4>, dt: f64) -> Matrix<4, 4> {
        match self {
            Self::Cv(m) => m.propagate_covariance(x, p, dt),
            Self::Ct(m) => m.propagate_covariance(x, p, dt),
        }
    }

    fn propagate_with_covariance(
        &self,
        x: &Vector<4>,
        p: &Matrix<4, 4>,
        dt: f64,
    ) -> (Vector<4>, Matrix<4, 4>) {
        match self {
            Self::Cv(m) => m.propagate_with_covariance(x, p, dt),
            Self::Ct(m) => m.propagate_with_covariance(x, p, dt),
        }
    }

    #[inline(always)]
    fn predict_moments(
        &self,
        x: &Vector<4>,
        p: &Matrix<4, 4>,
        dt: f64,
    ) -> (Vector<4>, Matrix<4, 4>) {
        match self {
            Self::Cv(m) => m.predict_moments(x, p, dt),
            Self::Ct(m) => m.predict_moments(x, p, dt),
        }
    }

    fn hessians(&self, x: &Vector<4>, dt: f64) -> Option<[Matrix<4, 4>; 4]> {
        match self {
            Self::Cv(m) => m.hessians(x, dt),
            Self::Ct(m) => m.hessians(x, dt),
        }
    }
}

impl LinearMotionModel<4> for PlanarModel {
    fn transition(&self, dt: f64) -> Matrix<4, 4> {
        match self {
            Self::Cv(m) => m.transition(dt),
            Self::Ct(m) => m.transition(dt),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_propagation_equals_the_separate_products() {
        // The structured / joint paths against f(x) and the literal F P Fᵀ; tolerance:
        // round-off of sums of products of entries ≲ 10⁴.
        #[rustfmt::skip]
        let p = Matrix::<4, 4>::new(
            900.0, 60.0, 100.0, 0.0,
            60.0, 100.0, 0.0, 5.0,
            100.0, 0.0, 700.0, 40.0,
            0.0, 5.0, 40.0, 80.0,
        );
        let x = Vector::<4>::new(1000.0, 120.0, -500.0, -80.0);
        for m in [
            PlanarModel::from(Cv2D::discrete(0.5).unwrap()),
            PlanarModel::from(CoordinatedTurn::from_degrees_per_second(3.0, 0.5).unwrap()),
            PlanarModel::from(CoordinatedTurn::from_degrees_per_second(-1e-9, 0.5).unwrap()),
        ] {
            for dt in [0.1, 2.0, 5.0] {
                let f = m.jacobian(&x, dt);
                let full = f * p * f.transpose();
                let (mean, cov) = m.propagate_with_covariance(&x, &p, dt);
                assert!((mean - m.propagate(&x, dt)).amax() < 1e-12 * x.amax());
                assert!((cov - full).amax() < 1e-12 * full.amax());
                assert!((m.propagate_covariance(&x, &p, dt) - full).amax() < 1e-12 * full.amax());
                assert_eq!(cov, cov.transpose());
                let q = m.process_noise(&x, dt);
                let (_, moments) = m.predict_moments(&x, &p, dt);
                assert!((moments - (full + q)).amax() < 1e-12 * (full + q).amax());
                assert_eq!(moments, moments.transpose());
            }
        }
    }

    #[test]
    fn delegates_to_wrapped_models() {
        // The seed-000 model set: CV (σv = 0.1) and CT at ±3 deg/s (σv = 0.5).
        let cv = Cv2D::discrete(0.1).unwrap();
        let ct = CoordinatedTurn::from_degrees_per_second(3.0, 0.5).unwrap();
        let set: [PlanarModel; 2] = [cv.into(), ct.into()];
        let x = Vector::<4>::new(-6e4, 90.0, -2e4, 0.0);
        assert_eq!(set[0].propagate(&x, 5.0), cv.propagate(&x, 5.0));
        assert_eq!(set[1].propagate(&x, 5.0), ct.propagate(&x, 5.0));
        assert_eq!(set[1].transition(5.0), ct.transition(5.0));
        assert_eq!(set[0].process_noise(&x, 5.0), cv.process_noise(&x, 5.0));
        assert_eq!(set[1].jacobian(&x, 5.0), ct.jacobian(&x, 5.0));
    }
}
