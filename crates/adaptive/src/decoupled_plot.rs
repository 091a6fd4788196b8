//! Radar-beacon plots: spherical measurements and their conversion to Cartesian
//! positions with the measurement-aligned frame the decoupled filter works in
//! (seed 003 eqs 9–12, corrected). Their SNR-driven accuracy (eqs 6–8) is
//! `argus_sensors`' [`SnrNoise`](argus_sensors::SnrNoise) with a
//! [`LinkBudget`](argus_sensors::LinkBudget).

use argus_core_math::{Matrix, Vector};
use argus_sensors::{LinearMeasurementModel, MeasurementModel, Sigmas, SphericalMeasurement};

use crate::error::{AdaptiveError, finite, positive};

/// Tolerance on `|DᵀD − I|` for a frame to count as orthonormal.
const ORTHONORMAL_TOL: f64 = 1e-9;

/// A radar-beacon plot as the decoupled filter takes it: a spherical measurement
/// (the vocabulary's [`SphericalMeasurement`]) of a radar at the origin, with a range
/// above zero and an elevation inside `(−π/2, π/2)` (where the aligned frame exists).
///
/// # Errors
/// [`AdaptiveError::NonFinite`] for a NaN or infinite value,
/// [`AdaptiveError::InvalidParameter`] for a non-positive range or an elevation outside
/// `(−π/2, π/2)`.
pub fn beacon_plot(
    range: f64,
    azimuth: f64,
    elevation: f64,
) -> Result<SphericalMeasurement, AdaptiveError> {
    positive(range, "plot range")?;
    finite(azimuth, "plot azimuth")?;
    finite(elevation, "plot elevation")?;
    check_elevation(elevation)?;
    Ok(SphericalMeasurement::new(range, azimuth, elevation)?)
}

/// The noise-free plot of a Cartesian position `(x, y, z)` (inverse of eq 9).
///
/// # Errors
/// As [`beacon_plot`]: a position at the origin or on the z axis is rejected.
pub fn beacon_plot_of(p: &Vector<3>) -> Result<SphericalMeasurement, AdaptiveError> {
    let ground = p[0].hypot(p[1]);
    beacon_plot(p.norm(), p[1].atan2(p[0]), p[2].atan2(ground))
}

fn check_elevation(elevation: f64) -> Result<(), AdaptiveError> {
    if elevation.abs() >= std::f64::consts::FRAC_PI_2 {
        return Err(AdaptiveError::InvalidParameter {
            what: "plot elevation",
            value: elevation,
            reason: "must lie in (-pi/2, pi/2)",
        });
    }
    Ok(())
}

/// A plot converted to Cartesian `(x, y, z)` with its first-order covariance
/// kept in the measurement-aligned frame.
///
/// Not the vocabulary's [`argus_sensors::CartesianMeasurement`]: the decoupled filter
/// works in the aligned frame `D` and adapts the aligned variances one by one
/// ([`ConvertedPlot::with_aligned_variances`]), so the covariance is kept factored as
/// `D diag(v) Dᵀ` and formed only on demand ([`ConvertedPlot::cartesian_noise`],
/// [`ConvertedPlot::measurement`]).
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
    /// Converts a spherical plot with the given accuracy (range m, azimuth and
    /// elevation rad; e.g. [`SnrNoise::sigmas_at_range`](argus_sensors::SnrNoise::sigmas_at_range)).
    ///
    /// # Errors
    /// [`AdaptiveError::NonFinite`] if the conversion overflows,
    /// [`AdaptiveError::InvalidParameter`] for a zero range, an elevation outside
    /// `(−π/2, π/2)` (see [`beacon_plot`]) or a zero standard deviation (the aligned
    /// variances must be positive).
    pub fn from_spherical(
        plot: &SphericalMeasurement,
        sigmas: &Sigmas,
    ) -> Result<Self, AdaptiveError> {
        let (r, psi, theta) = (plot.range(), plot.azimuth(), plot.elevation());
        positive(r, "plot range")?;
        check_elevation(theta)?;
        let (sp, cp) = psi.sin_cos();
        let (st, ct) = theta.sin_cos();
        let position = Vector::<3>::new(r * cp * ct, r * sp * ct, r * st);
        let frame = aligned_frame(psi, theta);
        let aligned_variances = Vector::<3>::new(
            sigmas.range().powi(2),
            (r * ct * sigmas.azimuth()).powi(2),
            (r * sigmas.elevation()).powi(2),
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

    /// The position and `R_c` as the vocabulary's Cartesian measurement.
    ///
    /// # Errors
    /// [`AdaptiveError::Sensor`] when the formed `R_c` is not numerically positive
    /// definite (aligned variances many orders of magnitude apart).
    pub fn measurement(&self) -> Result<argus_sensors::CartesianMeasurement<3>, AdaptiveError> {
        Ok(argus_sensors::CartesianMeasurement::new(
            self.position,
            self.cartesian_noise(),
        )?)
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
        let s = Sigmas::new(2.97, 4.3e-4, 4.3e-4).unwrap();
        let plot = ConvertedPlot::from_spherical(&beacon_plot(r, psi, theta).unwrap(), &s).unwrap();
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
            s.range().powi(2),
            s.azimuth().powi(2),
            s.elevation().powi(2),
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
        let sp = beacon_plot_of(&p).unwrap();
        assert!((convert(sp.range(), sp.azimuth(), sp.elevation()) - p).amax() < 1e-9);
    }

    #[test]
    fn sensors_snr_noise_gives_the_eqs_6_to_8_plots() {
        // The plots' accuracy now comes from argus_sensors' SnrNoise; it must give what this
        // module computed before (eqs 6–8 written out here, calibration SNR_ref = (Δr/σr)²/2 of
        // SPEC 003), so the experiment's results are unchanged. Tolerance 1e-14 relative: the two
        // evaluation orders differ by at most a few ulps.
        let (dr, bw, km, r_ref, s_ref) = (149.9, 2f64.to_radians(), 1.6, 3006.0, 2.97);
        let link = argus_sensors::SnrNoise::link_for_range_sigma(dr, s_ref, r_ref).unwrap();
        let noise = argus_sensors::SnrNoise::new(dr, bw, bw, km, link).unwrap();
        let snr_ref = 0.5 * (dr / s_ref).powi(2);
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(link.snr_ref(), snr_ref) < 1e-14);
        for (range, db) in [(3006.0, 0.0), (6012.0, 0.0), (5713.4, 2.7), (410.0, -4.1)] {
            let snr = snr_ref * (r_ref / range).powi(2) * 10f64.powf(db / 10.0);
            let root = (2.0 * snr).sqrt();
            let (sr, sa) = (dr / root, bw / (km * root));
            let s = noise.sigmas_at_snr(snr).unwrap();
            assert!(rel(s.range(), sr) < 1e-14 && rel(s.azimuth(), sa) < 1e-14);
            assert!(rel(s.elevation(), sa) < 1e-14);
            let plot = beacon_plot(range, 3.13, 0.05).unwrap();
            let c = ConvertedPlot::from_spherical(&plot, &s).unwrap();
            let want = [
                sr * sr,
                (range * 0.05f64.cos() * sa).powi(2),
                (range * sa).powi(2),
            ];
            for (g, w) in c.aligned_variances().iter().zip(want) {
                assert!(rel(*g, w) < 1e-13, "{g} vs {w}");
            }
        }
        // At the calibration range σr = 2.97 m; the 1/R² link doubles σ at twice the range.
        assert!((noise.sigmas_at_range(3006.0).range() - 2.97).abs() < 1e-12);
        assert!((noise.sigmas_at_range(6012.0).range() - 5.94).abs() < 1e-12);
    }

    #[test]
    fn bad_input_is_rejected() {
        assert!(matches!(
            beacon_plot(f64::NAN, 0.0, 0.0),
            Err(AdaptiveError::NonFinite {
                what: "plot range",
                ..
            })
        ));
        assert!(matches!(
            beacon_plot(-1.0, 0.0, 0.0),
            Err(AdaptiveError::InvalidParameter {
                what: "plot range",
                ..
            })
        ));
        assert!(matches!(
            beacon_plot(1.0, 0.0, 2.0),
            Err(AdaptiveError::InvalidParameter {
                what: "plot elevation",
                ..
            })
        ));
        // The conversion itself refuses what beacon_plot refuses, for a measurement built
        // elsewhere (here one on the sensor, range 0, and one straight up).
        for m in [
            SphericalMeasurement::new(0.0, 0.0, 0.1).unwrap(),
            SphericalMeasurement::new(10.0, 0.0, 1.6).unwrap(),
        ] {
            let ok = Sigmas::new(1.0, 1e-3, 1e-3).unwrap();
            assert!(matches!(
                ConvertedPlot::from_spherical(&m, &ok),
                Err(AdaptiveError::InvalidParameter { .. })
            ));
        }
        // The factored covariance formed whole is the vocabulary's measurement.
        let c = ConvertedPlot::from_spherical(
            &beacon_plot(3000.0, 0.3, 0.1).unwrap(),
            &Sigmas::new(3.0, 4e-4, 4e-4).unwrap(),
        )
        .unwrap();
        assert_eq!(*c.measurement().unwrap().covariance(), c.cartesian_noise());
        // A zero standard deviation gives a zero aligned variance: rejected, not a singular R.
        let zero = Sigmas::new(1.0, 0.0, 1.0).unwrap();
        assert!(matches!(
            ConvertedPlot::from_spherical(&beacon_plot(100.0, 0.0, 0.1).unwrap(), &zero),
            Err(AdaptiveError::InvalidParameter {
                what: "aligned measurement variance",
                ..
            })
        ));
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
