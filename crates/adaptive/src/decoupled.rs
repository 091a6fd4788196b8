//! The decoupled tracking filter of Fitzgerald (1985) as used in seed 003 (CDKF).
//!
//! A 3-D constant-velocity Kalman filter on converted plots whose covariance is
//! kept in the measurement-aligned frame `D` (range, cross-range azimuth,
//! cross-range elevation). There `R` is diagonal and, with isotropic process
//! noise, the 6-state filter splits into three independent 2-state `[p, v]`
//! filters; the gain is rotated back to Cartesian axes.

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::check_dt;

use crate::decoupled_plot::{ConvertedPlot, check_frame};
use crate::error::{AdaptiveError, positive};

/// How the aligned-frame covariance is carried from one plot's frame to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrameHandling {
    /// The paper's filter (eq 22): the per-axis covariances are carried over
    /// unchanged, as if the line of sight did not rotate between plots.
    Fixed,
    /// The per-axis covariances are re-expressed in the new plot's frame
    /// (`P̄' = M P̄ Mᵀ`, `M = D_newᵀ D_old`) and the cross-axis terms dropped.
    /// Exact when the line of sight does not rotate; costs 27 multiplications.
    #[default]
    Rotate,
}

/// A decoupled estimate: the Cartesian mean `[x, vx, y, vy, z, vz]` and three
/// 2×2 covariances of `[p, v]` along the columns of the frame `D`.
///
/// The full Cartesian covariance is `P = D₂ P̄ D₂ᵀ` with `P̄` block diagonal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecoupledEstimate {
    mean: Vector<6>,
    blocks: [Matrix<2, 2>; 3],
    frame: Matrix<3, 3>,
}

/// Checks that a 2×2 covariance is finite, symmetric and positive definite.
fn check_block(b: &Matrix<2, 2>, stage: &'static str) -> Result<(), AdaptiveError> {
    if b.iter().any(|v| !v.is_finite()) {
        return Err(AdaptiveError::NonFinite {
            what: "per-axis covariance",
            value: b
                .iter()
                .copied()
                .find(|v| !v.is_finite())
                .unwrap_or(f64::NAN),
        });
    }
    let scale = b.amax().max(f64::MIN_POSITIVE);
    let asym = (b[(0, 1)] - b[(1, 0)]).abs() / scale;
    let det = b[(0, 0)] * b[(1, 1)] - b[(0, 1)] * b[(1, 0)];
    if asym > 1e-9 || b[(0, 0)] <= 0.0 || det <= 0.0 {
        return Err(AdaptiveError::NotPositiveDefinite {
            what: "per-axis covariance",
            stage,
        });
    }
    Ok(())
}

impl DecoupledEstimate {
    /// An estimate from its parts.
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] for a non-finite mean or block,
    /// [`AdaptiveError::NotPositiveDefinite`] for a block that is not symmetric
    /// positive definite, [`AdaptiveError::NotOrthonormal`] for a bad frame.
    pub fn new(
        mean: Vector<6>,
        blocks: [Matrix<2, 2>; 3],
        frame: Matrix<3, 3>,
    ) -> Result<Self, AdaptiveError> {
        for v in mean.iter() {
            crate::error::finite(*v, "estimate mean")?;
        }
        for b in &blocks {
            check_block(b, "construction")?;
        }
        check_frame(&frame, "estimate frame D")?;
        Ok(Self {
            mean,
            blocks,
            frame,
        })
    }

    /// The decoupled approximation of a Cartesian Gaussian in frame `frame`:
    /// `P̄ = D₂ᵀ P D₂` with its cross-axis blocks dropped. Exact when `P` is
    /// block diagonal in that frame (an isotropic initial covariance is).
    ///
    /// # Errors
    /// As [`DecoupledEstimate::new`].
    pub fn from_gaussian(g: &Gaussian<6>, frame: &Matrix<3, 3>) -> Result<Self, AdaptiveError> {
        check_frame(frame, "estimate frame D")?;
        let p = g.cov();
        let mut blocks = [Matrix::<2, 2>::zeros(); 3];
        for (k, block) in blocks.iter_mut().enumerate() {
            for a in 0..2 {
                for b in 0..2 {
                    let mut acc = 0.0;
                    for i in 0..3 {
                        for j in 0..3 {
                            acc += frame[(i, k)] * frame[(j, k)] * p[(2 * i + a, 2 * j + b)];
                        }
                    }
                    block[(a, b)] = acc;
                }
            }
            *block = (*block + block.transpose()) * 0.5;
        }
        Self::new(*g.mean(), blocks, *frame)
    }

    /// The Cartesian mean `[x, vx, y, vy, z, vz]`.
    #[must_use]
    pub fn mean(&self) -> &Vector<6> {
        &self.mean
    }

    /// The per-axis `[p, v]` covariances along the frame's columns.
    #[must_use]
    pub fn blocks(&self) -> &[Matrix<2, 2>; 3] {
        &self.blocks
    }

    /// The frame `D` the covariance is kept in.
    #[must_use]
    pub fn frame(&self) -> &Matrix<3, 3> {
        &self.frame
    }

    /// The Cartesian position `(x, y, z)`.
    #[must_use]
    pub fn position(&self) -> Vector<3> {
        Vector::<3>::new(self.mean[0], self.mean[2], self.mean[4])
    }

    /// The Cartesian position covariance `D diag(P̄ₖ[0,0]) Dᵀ` (`H P Hᵀ`).
    #[must_use]
    pub fn position_cov(&self) -> Matrix<3, 3> {
        let diag = Vector::<3>::new(
            self.blocks[0][(0, 0)],
            self.blocks[1][(0, 0)],
            self.blocks[2][(0, 0)],
        );
        self.frame * Matrix::<3, 3>::from_diagonal(&diag) * self.frame.transpose()
    }

    /// The full Cartesian covariance `P = D₂ P̄ D₂ᵀ` in the interleaved layout.
    #[must_use]
    pub fn cartesian_cov(&self) -> Matrix<6, 6> {
        let d = &self.frame;
        let mut p = Matrix::<6, 6>::zeros();
        for i in 0..3 {
            for j in 0..3 {
                for a in 0..2 {
                    for b in 0..2 {
                        p[(2 * i + a, 2 * j + b)] = (0..3)
                            .map(|k| d[(i, k)] * d[(j, k)] * self.blocks[k][(a, b)])
                            .sum();
                    }
                }
            }
        }
        p
    }

    /// The estimate as a Cartesian [`Gaussian`].
    ///
    /// # Errors
    /// [`AdaptiveError::Math`] if the rotated covariance fails the PD check (round-off).
    pub fn to_gaussian(&self) -> Result<Gaussian<6>, AdaptiveError> {
        Ok(Gaussian::from_symmetrized(
            self.mean,
            &self.cartesian_cov(),
        )?)
    }

    /// The NEES `(x − x̂)ᵀ P⁻¹ (x − x̂)` of a true state, computed per aligned axis
    /// (`P̄` is block diagonal). `+∞` for a non-finite truth.
    #[must_use]
    pub fn nees(&self, truth: &Vector<6>) -> f64 {
        let e = truth - self.mean;
        let ep = self.frame.transpose() * Vector::<3>::new(e[0], e[2], e[4]);
        let ev = self.frame.transpose() * Vector::<3>::new(e[1], e[3], e[5]);
        let mut total = 0.0;
        for k in 0..3 {
            let b = &self.blocks[k];
            let det = b[(0, 0)] * b[(1, 1)] - b[(0, 1)] * b[(1, 0)];
            let (p, v) = (ep[k], ev[k]);
            total += (b[(1, 1)] * p * p - 2.0 * b[(0, 1)] * p * v + b[(0, 0)] * v * v) / det;
        }
        if total.is_finite() {
            total
        } else {
            f64::INFINITY
        }
    }

    /// The blocks re-expressed in `new_frame` (cross-axis terms dropped).
    fn rotated_blocks(&self, new_frame: &Matrix<3, 3>) -> [Matrix<2, 2>; 3] {
        let m = new_frame.transpose() * self.frame;
        let mut out = [Matrix::<2, 2>::zeros(); 3];
        for (k, o) in out.iter_mut().enumerate() {
            for (mm, b) in self.blocks.iter().enumerate() {
                *o += b * m[(k, mm)].powi(2);
            }
        }
        out
    }
}

/// What one decoupled update produced besides the posterior.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecoupledUpdate {
    /// The innovation `ν = z − H x⁻` in Cartesian axes.
    pub residual: Vector<3>,
    /// The innovation in the aligned frame, `Dᵀ ν`.
    pub aligned_residual: Vector<3>,
    /// The per-axis innovation variances `s̄ₖ = P̄ₖ[0,0] + r̄ₖ`.
    pub aligned_s: Vector<3>,
    /// The normalised innovation squared `Σ ν̄ₖ² / s̄ₖ`.
    pub nis: f64,
}

/// The conventional decoupled Kalman filter (CDKF) for a 3-D constant-velocity
/// target on converted plots.
///
/// Predict per aligned axis with `F = [[1, T], [0, 1]]` and the discrete white
/// noise acceleration `Q = q² G Gᵀ`, `G = [T²/2, T]ᵀ` (eqs 14–17, 21–22); update
/// per axis with `K̄ₖ = P̄ₖ hᵀ (h P̄ₖ hᵀ + r̄ₖ)⁻¹`, `P̄ₖ⁺ = (I − K̄ₖ h) P̄ₖ` (eqs 24–25,
/// with the inverse that eq 25 lacks), and the Cartesian mean moved by the gain
/// rotated back, `x⁺ = x⁻ + D₂ K̄ Dᵀ (z − H x⁻)` (eqs 23, 26–27; the paper writes
/// `D₂ K̄ D₂ᵀ`, which does not conform: the residual is 3-D).
///
/// # References
/// Kim & Hwang (2013), seed 003, eqs (13)–(27); Fitzgerald, IEE Proc. F 132 (1985) 65–67.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecoupledFilter {
    accel_sd: f64,
    frame_handling: FrameHandling,
}

impl DecoupledFilter {
    /// A filter with white-acceleration standard deviation `q` (m/s², per axis).
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] or [`AdaptiveError::NonFinite`] for a `q`
    /// that is not finite and positive.
    pub fn new(accel_sd: f64, frame_handling: FrameHandling) -> Result<Self, AdaptiveError> {
        Ok(Self {
            accel_sd: positive(accel_sd, "acceleration noise q")?,
            frame_handling,
        })
    }

    /// The process-noise standard deviation `q`.
    #[must_use]
    pub fn accel_sd(&self) -> f64 {
        self.accel_sd
    }

    /// The frame handling.
    #[must_use]
    pub fn frame_handling(&self) -> FrameHandling {
        self.frame_handling
    }

    /// Predicts over `dt` seconds (eqs 21–22), per aligned axis.
    ///
    /// # Errors
    /// [`AdaptiveError::Filter`] for a `dt` that is not finite and positive
    /// (time standing still or going backwards).
    #[allow(non_snake_case)]
    pub fn predict(
        &self,
        prior: &DecoupledEstimate,
        dt: f64,
    ) -> Result<DecoupledEstimate, AdaptiveError> {
        check_dt(dt)?;
        let F = Matrix::<2, 2>::new(1.0, dt, 0.0, 1.0);
        let q2 = self.accel_sd * self.accel_sd;
        let Q = Matrix::<2, 2>::new(
            q2 * dt.powi(4) / 4.0,
            q2 * dt.powi(3) / 2.0,
            q2 * dt.powi(3) / 2.0,
            q2 * dt * dt,
        );
        let mut mean = prior.mean;
        for i in 0..3 {
            mean[2 * i] += dt * mean[2 * i + 1];
        }
        let mut blocks = prior.blocks;
        for b in &mut blocks {
            *b = F * *b * F.transpose() + Q;
            check_block(b, "prediction")?;
        }
        if mean.iter().any(|v| !v.is_finite()) {
            return Err(AdaptiveError::NonFinite {
                what: "predicted mean",
                value: f64::NAN,
            });
        }
        Ok(DecoupledEstimate {
            mean,
            blocks,
            frame: prior.frame,
        })
    }

    /// The predicted position variances along `plot`'s aligned axes, `p̄ₖ = P̄ₖ⁻[0,0]`
    /// after the frame handling: what [`DecoupledFilter::update`] adds `r̄ₖ` to.
    #[must_use]
    pub fn aligned_position_variances(
        &self,
        predicted: &DecoupledEstimate,
        plot: &ConvertedPlot,
    ) -> Vector<3> {
        let blocks = match self.frame_handling {
            FrameHandling::Fixed => predicted.blocks,
            FrameHandling::Rotate => predicted.rotated_blocks(plot.frame()),
        };
        Vector::<3>::new(blocks[0][(0, 0)], blocks[1][(0, 0)], blocks[2][(0, 0)])
    }

    /// Updates with a converted plot, using the plot's aligned variances as `R̄`.
    ///
    /// # Errors
    /// [`AdaptiveError::NotPositiveDefinite`] when a posterior block loses
    /// definiteness, [`AdaptiveError::NonFinite`] on overflow. `predicted` is untouched.
    #[allow(non_snake_case)]
    pub fn update(
        &self,
        predicted: &DecoupledEstimate,
        plot: &ConvertedPlot,
    ) -> Result<(DecoupledEstimate, DecoupledUpdate), AdaptiveError> {
        let D = plot.frame();
        let blocks_prior = match self.frame_handling {
            FrameHandling::Fixed => predicted.blocks,
            FrameHandling::Rotate => predicted.rotated_blocks(D),
        };
        let residual = plot.position() - predicted.position();
        let aligned_residual = D.transpose() * residual;
        let r = plot.aligned_variances();
        let mut blocks = blocks_prior;
        let mut dp = Vector::<3>::zeros();
        let mut dv = Vector::<3>::zeros();
        let mut aligned_s = Vector::<3>::zeros();
        let mut nis = 0.0;
        for k in 0..3 {
            let b = blocks_prior[k];
            let s = b[(0, 0)] + r[k];
            if !(s.is_finite() && s > 0.0) {
                return Err(AdaptiveError::NotPositiveDefinite {
                    what: "innovation variance",
                    stage: "update",
                });
            }
            let K = Vector::<2>::new(b[(0, 0)] / s, b[(1, 0)] / s);
            dp[k] = K[0] * aligned_residual[k];
            dv[k] = K[1] * aligned_residual[k];
            // P̄⁺ = (I − K h) P̄ = P̄ − s K Kᵀ (eq 24), exactly symmetric.
            blocks[k] = b - K * K.transpose() * s;
            check_block(&blocks[k], "update")?;
            aligned_s[k] = s;
            nis += aligned_residual[k].powi(2) / s;
        }
        let dp = D * dp;
        let dv = D * dv;
        let mut mean = predicted.mean;
        for i in 0..3 {
            mean[2 * i] += dp[i];
            mean[2 * i + 1] += dv[i];
        }
        if mean.iter().any(|v| !v.is_finite()) || !nis.is_finite() {
            return Err(AdaptiveError::NonFinite {
                what: "posterior mean",
                value: f64::NAN,
            });
        }
        Ok((
            DecoupledEstimate {
                mean,
                blocks,
                frame: *D,
            },
            DecoupledUpdate {
                residual,
                aligned_residual,
                aligned_s,
                nis,
            },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coupled::CoupledCvFilter;
    use crate::decoupled_plot::aligned_frame;
    use argus_filters::GaussianFilter;

    fn plot(pos: Vector<3>, psi: f64, theta: f64, var: Vector<3>) -> ConvertedPlot {
        ConvertedPlot::new(pos, aligned_frame(psi, theta), var).unwrap()
    }

    #[test]
    fn equals_coupled_kf_when_the_frame_is_fixed() {
        // With one fixed frame, isotropic Q and a block-diagonal prior, the decoupled filter is
        // an exact rewrite of the 6-state KF (Fitzgerald 1985): agreement to round-off (1e-9 rel).
        let (psi, theta) = (3.16, 0.05);
        let d = aligned_frame(psi, theta);
        let mut p0 = Matrix::<6, 6>::zeros();
        for i in 0..3 {
            p0[(2 * i, 2 * i)] = 100.0;
            p0[(2 * i + 1, 2 * i + 1)] = 25.0;
        }
        let g0 = Gaussian::new(
            Vector::<6>::new(-6000.0, 35.0, -100.0, 0.0, 314.0, -1.8),
            p0,
        )
        .unwrap();
        let mut dec = DecoupledEstimate::from_gaussian(&g0, &d).unwrap();
        let mut cpl = g0;
        let fd = DecoupledFilter::new(0.05, FrameHandling::Fixed).unwrap();
        let fc = CoupledCvFilter::new(0.05).unwrap();
        let var = Vector::<3>::new(9.0, 16.0, 25.0);
        for k in 0..50 {
            let t = f64::from(k);
            let z = Vector::<3>::new(-6000.0 + 3.5 * t + (t * 0.7).sin(), -100.0 + t.cos(), 314.0);
            let pl = plot(z, psi, theta, var);
            dec = fd.update(&fd.predict(&dec, 0.1).unwrap(), &pl).unwrap().0;
            cpl = fc
                .update(&fc.predict(&cpl, 0.1).unwrap(), &pl, pl.position())
                .unwrap()
                .0;
        }
        assert!((dec.mean() - cpl.mean()).amax() < 1e-9);
        assert!((dec.cartesian_cov() - cpl.cov()).amax() / cpl.cov().amax() < 1e-9);
    }

    #[test]
    fn rotate_is_exact_for_an_isotropic_covariance() {
        // An isotropic per-axis covariance is invariant under rotation: Rotate must return it.
        let b = Matrix::<2, 2>::new(4.0, 1.0, 1.0, 2.0);
        let e =
            DecoupledEstimate::new(Vector::<6>::zeros(), [b; 3], aligned_frame(0.3, 0.1)).unwrap();
        let r = e.rotated_blocks(&aligned_frame(1.2, -0.4));
        for rb in r {
            assert!((rb - b).amax() < 1e-12);
        }
    }

    #[test]
    fn nees_matches_the_cartesian_form() {
        let b = [
            Matrix::<2, 2>::new(4.0, 1.0, 1.0, 2.0),
            Matrix::<2, 2>::new(9.0, -2.0, -2.0, 3.0),
            Matrix::<2, 2>::new(1.0, 0.1, 0.1, 0.5),
        ];
        let e = DecoupledEstimate::new(Vector::<6>::zeros(), b, aligned_frame(2.0, 0.3)).unwrap();
        let x = Vector::<6>::new(1.0, -2.0, 0.5, 0.3, -1.0, 2.0);
        let want = e.to_gaussian().unwrap().mahalanobis_sq(&x);
        assert!((e.nees(&x) - want).abs() < 1e-9 * want);
    }

    #[test]
    fn bad_input_leaves_the_estimate_unchanged() {
        let b = Matrix::<2, 2>::new(4.0, 1.0, 1.0, 2.0);
        let e = DecoupledEstimate::new(Vector::<6>::zeros(), [b; 3], Matrix::<3, 3>::identity())
            .unwrap();
        let before = e;
        let f = DecoupledFilter::new(0.05, FrameHandling::Rotate).unwrap();
        assert!(matches!(f.predict(&e, -0.1), Err(AdaptiveError::Filter(_))));
        assert!(matches!(
            f.predict(&e, f64::NAN),
            Err(AdaptiveError::Filter(_))
        ));
        assert_eq!(e, before);
        assert!(DecoupledFilter::new(-1.0, FrameHandling::Fixed).is_err());
        assert!(DecoupledFilter::new(f64::NAN, FrameHandling::Fixed).is_err());
        let not_pd = Matrix::<2, 2>::new(1.0, 2.0, 2.0, 1.0);
        assert!(matches!(
            DecoupledEstimate::new(
                Vector::<6>::zeros(),
                [b, not_pd, b],
                Matrix::<3, 3>::identity()
            ),
            Err(AdaptiveError::NotPositiveDefinite { .. })
        ));
        let mut nan_mean = Vector::<6>::zeros();
        nan_mean[3] = f64::NAN;
        assert!(matches!(
            DecoupledEstimate::new(nan_mean, [b; 3], Matrix::<3, 3>::identity()),
            Err(AdaptiveError::NonFinite { .. })
        ));
    }
}
