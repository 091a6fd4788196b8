//! Radar-beacon plots: spherical measurements, their SNR-driven accuracy
//! (seed 003 eqs 6–8) and their conversion to Cartesian positions with the
//! measurement-aligned frame the decoupled filter works in (eqs 9–12, corrected).

use argus_core_math::{Matrix, Vector};
use argus_sensors::{LinearMeasurementModel, MeasurementModel};

use crate::decoupled_error::{AdaptiveError, finite, positive};

/// Tolerance on `|DᵀD − I|` for a frame to count as orthonormal.
const ORTHONORMAL_TOL: f64 = 1e-9;

/// One spherical plot of a radar at the origin: range (m), azimuth from +x
/// counter-clockwise (rad) and elevation above the x–y plane (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalPlot {
    range: f64,
    azimuth: f64,
    elevation: f64,
}

impl SphericalPlot {
    /// A validated plot.
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] for a NaN or infinite value,
    /// [`AdaptiveError::InvalidParameter`] for a non-positive range or an
    /// elevation outside `(−π/2, π/2)`.
    pub fn new(range: f64, azimuth: f64, elevation: f64) -> Result<Self, AdaptiveError> {
        positive(range, "plot range")?;
        finite(azimuth, "plot azimuth")?;
        finite(elevation, "plot elevation")?;
        if elevation.abs() >= std::f64::consts::FRAC_PI_2 {
            return Err(AdaptiveError::InvalidParameter {
                what: "plot elevation",
                value: elevation,
                reason: "must lie in (-pi/2, pi/2)",
            });
        }
        Ok(Self {
            range,
            azimuth,
            elevation,
        })
    }

    /// The noise-free plot of a Cartesian position `(x, y, z)` (inverse of eq 9).
    ///
    /// # Errors
    /// As [`SphericalPlot::new`]: a position at the origin or on the z axis is rejected.
    pub fn from_cartesian(p: &Vector<3>) -> Result<Self, AdaptiveError> {
        let ground = p[0].hypot(p[1]);
        Self::new(p.norm(), p[1].atan2(p[0]), p[2].atan2(ground))
    }

    /// Range, m.
    #[must_use]
    pub fn range(&self) -> f64 {
        self.range
    }

    /// Azimuth ψ, rad, from +x counter-clockwise.
    #[must_use]
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }

    /// Elevation θ, rad.
    #[must_use]
    pub fn elevation(&self) -> f64 {
        self.elevation
    }
}

/// Standard deviations of one plot's range (m), azimuth (rad) and elevation (rad) noise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalSigmas {
    /// σr, m.
    pub range: f64,
    /// σψ, rad.
    pub azimuth: f64,
    /// σθ, rad.
    pub elevation: f64,
}

impl SphericalSigmas {
    /// Validated standard deviations.
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] or [`AdaptiveError::InvalidParameter`] for a
    /// value that is not finite and positive.
    pub fn new(range: f64, azimuth: f64, elevation: f64) -> Result<Self, AdaptiveError> {
        Ok(Self {
            range: positive(range, "sigma range")?,
            azimuth: positive(azimuth, "sigma azimuth")?,
            elevation: positive(elevation, "sigma elevation")?,
        })
    }

    /// All three scaled by `factor` (the degraded cases of seed 003 use 5 and 10).
    ///
    /// # Errors
    /// As [`SphericalSigmas::new`] for a non-positive or non-finite factor.
    pub fn scaled(&self, factor: f64) -> Result<Self, AdaptiveError> {
        positive(factor, "sigma scale factor")?;
        Self::new(
            self.range * factor,
            self.azimuth * factor,
            self.elevation * factor,
        )
    }
}

/// The SNR-driven accuracy of a radar beacon system (seed 003 eqs 6–8, after Curry 2004):
/// `σr = Δr / √(2 SNR)`, `σψ = ψ_BW / (k_m √(2 SNR))`, `σθ = θ_BW / (k_m √(2 SNR))`,
/// with a link budget `SNR(R) = SNR_ref (R_ref / R)²` (a one-way beacon link).
///
/// # References
/// Kim & Hwang (2013), seed 003, eqs (6)–(8); the 1/R² link is SPEC section 003.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RbsNoiseModel {
    range_resolution: f64,
    azimuth_beamwidth: f64,
    elevation_beamwidth: f64,
    monopulse_slope: f64,
    reference_range: f64,
    reference_snr: f64,
}

impl RbsNoiseModel {
    /// A model with range resolution `Δr` (m), beamwidths (rad), monopulse slope
    /// `k_m`, and the mean SNR (linear, not dB) `reference_snr` at `reference_range` (m).
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] or [`AdaptiveError::InvalidParameter`] for
    /// any value that is not finite and positive.
    pub fn new(
        range_resolution: f64,
        azimuth_beamwidth: f64,
        elevation_beamwidth: f64,
        monopulse_slope: f64,
        reference_range: f64,
        reference_snr: f64,
    ) -> Result<Self, AdaptiveError> {
        Ok(Self {
            range_resolution: positive(range_resolution, "range resolution")?,
            azimuth_beamwidth: positive(azimuth_beamwidth, "azimuth beamwidth")?,
            elevation_beamwidth: positive(elevation_beamwidth, "elevation beamwidth")?,
            monopulse_slope: positive(monopulse_slope, "monopulse slope k_m")?,
            reference_range: positive(reference_range, "reference range")?,
            reference_snr: positive(reference_snr, "reference SNR")?,
        })
    }

    /// A model calibrated so that `σr = sigma_range` at the mean SNR at
    /// `reference_range`: `SNR_ref = (Δr / σr)² / 2` (eq 6 solved for SNR).
    ///
    /// # Errors
    /// As [`RbsNoiseModel::new`].
    pub fn calibrated(
        range_resolution: f64,
        azimuth_beamwidth: f64,
        elevation_beamwidth: f64,
        monopulse_slope: f64,
        reference_range: f64,
        sigma_range: f64,
    ) -> Result<Self, AdaptiveError> {
        positive(range_resolution, "range resolution")?;
        positive(sigma_range, "reference sigma range")?;
        let snr = 0.5 * (range_resolution / sigma_range).powi(2);
        Self::new(
            range_resolution,
            azimuth_beamwidth,
            elevation_beamwidth,
            monopulse_slope,
            reference_range,
            snr,
        )
    }

    /// The mean SNR (linear) at `range` m from the link budget.
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] for a range that is not finite and positive.
    pub fn mean_snr(&self, range: f64) -> Result<f64, AdaptiveError> {
        positive(range, "range")?;
        Ok(self.reference_snr * (self.reference_range / range).powi(2))
    }

    /// The mean SNR at the reference range (linear).
    #[must_use]
    pub fn reference_snr(&self) -> f64 {
        self.reference_snr
    }

    /// The plot accuracy at a given SNR (linear), eqs (6)–(8).
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] for an SNR that is not finite and positive.
    pub fn sigmas_at_snr(&self, snr: f64) -> Result<SphericalSigmas, AdaptiveError> {
        positive(snr, "SNR")?;
        let root = (2.0 * snr).sqrt();
        SphericalSigmas::new(
            self.range_resolution / root,
            self.azimuth_beamwidth / (self.monopulse_slope * root),
            self.elevation_beamwidth / (self.monopulse_slope * root),
        )
    }

    /// The accuracy at the link-budget mean SNR at `range` (what the filters assume).
    ///
    /// # Errors
    /// As [`RbsNoiseModel::mean_snr`].
    pub fn sigmas_at_range(&self, range: f64) -> Result<SphericalSigmas, AdaptiveError> {
        self.sigmas_at_snr(self.mean_snr(range)?)
    }
}

/// A plot converted to Cartesian `(x, y, z)` with its first-order covariance
/// kept in the measurement-aligned frame.
///
/// Conversion (eq 9): `x = r cosψ cosθ, y = r sinψ cosθ, z = r sinθ`. The
/// Jacobian `J = ∂(x,y,z)/∂(r,ψ,θ) = D diag(1, r cosθ, r)` where `D` is the
/// orthonormal frame of unit range, cross-range-azimuth and cross-range-elevation
/// directions (columns), so `R_c = J diag(σr², σψ², σθ²) Jᵀ = D diag(σr²,
/// (r cosθ σψ)², (r σθ)²) Dᵀ`: `R` is diagonal in the aligned frame.
///
/// # References
/// Kim & Hwang (2013), seed 003, eqs (9)–(12). The printed eq (11) `D` has wrong
/// terms and signs and eq (12) uses `r` instead of `r²` (SPEC section 003); the
/// form above is re-derived and tested against central differences.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvertedPlot {
    position: Vector<3>,
    frame: Matrix<3, 3>,
    aligned_variances: Vector<3>,
}

impl ConvertedPlot {
    /// Converts a spherical plot with the given accuracy.
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] if the conversion overflows.
    pub fn from_spherical(
        plot: &SphericalPlot,
        sigmas: &SphericalSigmas,
    ) -> Result<Self, AdaptiveError> {
        let (r, psi, theta) = (plot.range, plot.azimuth, plot.elevation);
        let (sp, cp) = psi.sin_cos();
        let (st, ct) = theta.sin_cos();
        let position = Vector::<3>::new(r * cp * ct, r * sp * ct, r * st);
        let frame = aligned_frame(psi, theta);
        let aligned_variances = Vector::<3>::new(
            sigmas.range.powi(2),
            (r * ct * sigmas.azimuth).powi(2),
            (r * sigmas.elevation).powi(2),
        );
        Self::new(position, frame, aligned_variances)
    }

    /// A converted plot from its parts.
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] for a non-finite entry,
    /// [`AdaptiveError::NotOrthonormal`] when `frame` is not a rotation,
    /// [`AdaptiveError::InvalidParameter`] for a non-positive variance.
    pub fn new(
        position: Vector<3>,
        frame: Matrix<3, 3>,
        aligned_variances: Vector<3>,
    ) -> Result<Self, AdaptiveError> {
        for v in position.iter() {
            finite(*v, "plot position")?;
        }
        check_frame(&frame, "plot frame D")?;
        for v in aligned_variances.iter() {
            positive(*v, "aligned measurement variance")?;
        }
        Ok(Self {
            position,
            frame,
            aligned_variances,
        })
    }

    /// The same plot with other aligned-frame variances (the adaptive filter's `R̂`).
    ///
    /// # Errors
    /// [`AdaptiveError::InvalidParameter`] or [`AdaptiveError::NonFinite`] for a
    /// variance that is not finite and positive.
    pub fn with_aligned_variances(&self, variances: Vector<3>) -> Result<Self, AdaptiveError> {
        for v in variances.iter() {
            positive(*v, "aligned measurement variance")?;
        }
        Ok(Self {
            aligned_variances: variances,
            ..*self
        })
    }

    /// The Cartesian position `z = (x, y, z)`.
    #[must_use]
    pub fn position(&self) -> &Vector<3> {
        &self.position
    }

    /// The measurement-aligned frame `D` (columns: range, cross-range azimuth,
    /// cross-range elevation unit vectors).
    #[must_use]
    pub fn frame(&self) -> &Matrix<3, 3> {
        &self.frame
    }

    /// The noise variances along the aligned axes: `(σr², (r cosθ σψ)², (r σθ)²)`.
    #[must_use]
    pub fn aligned_variances(&self) -> &Vector<3> {
        &self.aligned_variances
    }

    /// The Cartesian noise covariance `R_c = D diag(aligned variances) Dᵀ`.
    #[must_use]
    pub fn cartesian_noise(&self) -> Matrix<3, 3> {
        self.frame * Matrix::<3, 3>::from_diagonal(&self.aligned_variances) * self.frame.transpose()
    }
}

/// The measurement-aligned frame at azimuth `psi` and elevation `theta`:
/// columns `∂u/∂r`, `∂u/∂ψ / (r cosθ)`, `∂u/∂θ / r` of the conversion (eq 9).
#[must_use]
pub fn aligned_frame(psi: f64, theta: f64) -> Matrix<3, 3> {
    let (sp, cp) = psi.sin_cos();
    let (st, ct) = theta.sin_cos();
    Matrix::<3, 3>::new(cp * ct, -sp, -cp * st, sp * ct, cp, -sp * st, st, 0.0, ct)
}

/// Checks that `d` is finite and orthonormal.
pub(crate) fn check_frame(d: &Matrix<3, 3>, what: &'static str) -> Result<(), AdaptiveError> {
    for v in d.iter() {
        finite(*v, what)?;
    }
    let deviation = (d.transpose() * d - Matrix::<3, 3>::identity()).amax();
    if deviation > ORTHONORMAL_TOL {
        return Err(AdaptiveError::NotOrthonormal { what, deviation });
    }
    Ok(())
}

/// The converted plot as a linear measurement of the 3-D CV state
/// `[x, vx, y, vy, z, vz]`: `H` picks the positions, `R` is `R_c`.
impl MeasurementModel<6, 3> for ConvertedPlot {
    fn predict(&self, x: &Vector<6>) -> Vector<3> {
        Vector::<3>::new(x[0], x[2], x[4])
    }

    fn jacobian(&self, _x: &Vector<6>) -> Matrix<3, 6> {
        self.matrix()
    }

    fn noise(&self, _x: &Vector<6>) -> Matrix<3, 3> {
        self.cartesian_noise()
    }
}

impl LinearMeasurementModel<6, 3> for ConvertedPlot {
    fn matrix(&self) -> Matrix<3, 6> {
        let mut h = Matrix::<3, 6>::zeros();
        h[(0, 0)] = 1.0;
        h[(1, 2)] = 1.0;
        h[(2, 4)] = 1.0;
        h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn convert(r: f64, psi: f64, theta: f64) -> Vector<3> {
        let (sp, cp) = psi.sin_cos();
        let (st, ct) = theta.sin_cos();
        Vector::<3>::new(r * cp * ct, r * sp * ct, r * st)
    }

    #[test]
    fn covariance_matches_central_difference_jacobian() {
        // R_c = J diag(σ²) Jᵀ with J from central differences of eq (9); agreement to 1e-6 relative
        // (step 1e-6 in each coordinate, truncation error O(h²)).
        let (r, psi, theta) = (3005.8, 3.17, 0.052);
        let s = SphericalSigmas::new(2.97, 4.3e-4, 4.3e-4).unwrap();
        let plot =
            ConvertedPlot::from_spherical(&SphericalPlot::new(r, psi, theta).unwrap(), &s).unwrap();
        let h = 1e-6;
        let mut j = Matrix::<3, 3>::zeros();
        j.set_column(
            0,
            &((convert(r + h, psi, theta) - convert(r - h, psi, theta)) / (2.0 * h)),
        );
        j.set_column(
            1,
            &((convert(r, psi + h, theta) - convert(r, psi - h, theta)) / (2.0 * h)),
        );
        j.set_column(
            2,
            &((convert(r, psi, theta + h) - convert(r, psi, theta - h)) / (2.0 * h)),
        );
        let rs = Matrix::<3, 3>::from_diagonal(&Vector::<3>::new(
            s.range.powi(2),
            s.azimuth.powi(2),
            s.elevation.powi(2),
        ));
        let want = j * rs * j.transpose();
        let got = plot.cartesian_noise();
        assert!((want - got).amax() / want.amax() < 1e-6, "{want} vs {got}");
        assert!((plot.position() - convert(r, psi, theta)).amax() < 1e-9);
    }

    #[test]
    fn frame_is_a_rotation_and_roundtrips() {
        let d = aligned_frame(-2.0, 0.4);
        assert!(check_frame(&d, "d").is_ok());
        // det = +1 (right-handed): exact identity of the unit vectors, to round-off.
        assert!((d.determinant() - 1.0).abs() < 1e-12);
        let p = Vector::<3>::new(-3000.0, -100.0, 157.2);
        let sp = SphericalPlot::from_cartesian(&p).unwrap();
        assert!((convert(sp.range(), sp.azimuth(), sp.elevation()) - p).amax() < 1e-9);
    }

    #[test]
    fn noise_model_eqs_6_to_8() {
        // Calibration of SPEC 003: σr = 2.97 m at 3006 m with Δr = 149.9 m → SNR = (149.9/2.97)²/2.
        let m = RbsNoiseModel::calibrated(
            149.9,
            2f64.to_radians(),
            2f64.to_radians(),
            1.6,
            3006.0,
            2.97,
        )
        .unwrap();
        let snr = 0.5 * (149.9f64 / 2.97).powi(2);
        assert!((m.reference_snr() - snr).abs() < 1e-9);
        let s = m.sigmas_at_range(3006.0).unwrap();
        assert!((s.range - 2.97).abs() < 1e-12);
        // σψ = ψ_BW / (k_m √(2 SNR)) = (2° in rad) · 2.97 / (1.6 · 149.9).
        let want = 2f64.to_radians() * 2.97 / (1.6 * 149.9);
        assert!((s.azimuth - want).abs() < 1e-15);
        // 1/R² link: doubling the range halves √SNR, doubling σ.
        let s2 = m.sigmas_at_range(6012.0).unwrap();
        assert!((s2.range - 5.94).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_rejected() {
        assert!(matches!(
            SphericalPlot::new(f64::NAN, 0.0, 0.0),
            Err(AdaptiveError::NonFinite {
                what: "plot range",
                ..
            })
        ));
        assert!(matches!(
            SphericalPlot::new(-1.0, 0.0, 0.0),
            Err(AdaptiveError::InvalidParameter {
                what: "plot range",
                ..
            })
        ));
        assert!(matches!(
            SphericalPlot::new(1.0, 0.0, 2.0),
            Err(AdaptiveError::InvalidParameter {
                what: "plot elevation",
                ..
            })
        ));
        assert!(SphericalSigmas::new(1.0, 0.0, 1.0).is_err());
        assert!(RbsNoiseModel::new(1.0, 1.0, 1.0, f64::INFINITY, 1.0, 1.0).is_err());
        let bad_frame = Matrix::<3, 3>::identity() * 1.1;
        assert!(matches!(
            ConvertedPlot::new(Vector::<3>::zeros(), bad_frame, Vector::<3>::repeat(1.0)),
            Err(AdaptiveError::NotOrthonormal { .. })
        ));
        assert!(matches!(
            ConvertedPlot::new(
                Vector::<3>::zeros(),
                Matrix::<3, 3>::identity(),
                Vector::<3>::new(1.0, -1.0, 1.0)
            ),
            Err(AdaptiveError::InvalidParameter { .. })
        ));
    }
}
