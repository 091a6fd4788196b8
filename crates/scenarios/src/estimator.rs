//! Estimator wiring of the scenarios: the Kalman filter on the 2-D constant-velocity
//! model (DWNA noise) with converted plots, the unbiased polar conversion, the position
//! measurement and one predict + update step — the single-target engine's own
//! (`argus_tracker::single`), re-exported so the scenarios and `argus track` share them.

use argus_filters::Kf;
use argus_motion_models::Cv2D;

/// KF on the 2-D CV model `[x, vx, y, vy]`, `Q = σ² Γ Γᵀ` (seed 000).
pub type CvKf = Kf<Cv2D>;

pub use argus_tracker::single::{cv_kf, position, step, unbiased};
