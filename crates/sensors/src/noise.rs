//! Measurement-noise standard deviations: constant, or from the signal-to-noise
//! ratio through a link budget over range (seed 003, eqs (6)–(8)).

use crate::error::{SensorError, non_negative, positive};

/// Standard deviations of a radar plot's range (m), azimuth (rad) and elevation
/// (rad) noise. Two-dimensional and bearing-only sensors ignore the components
/// they do not measure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sigmas {
    range: f64,
    azimuth: f64,
    elevation: f64,
}

impl Sigmas {
    /// Validated standard deviations.
    ///
    /// # Errors
    /// [`SensorError::NonFinite`] or [`SensorError::Negative`] for a value that is
    /// not finite and `≥ 0`.
    pub fn new(range: f64, azimuth: f64, elevation: f64) -> Result<Self, SensorError> {
        Ok(Self {
            range: non_negative(range, "range sigma")?,
            azimuth: non_negative(azimuth, "azimuth sigma")?,
            elevation: non_negative(elevation, "elevation sigma")?,
        })
    }

    /// Standard deviations of a two-dimensional (range, azimuth) sensor; the
    /// elevation component is 0.
    ///
    /// # Errors
    /// As [`Sigmas::new`].
    pub fn polar(range: f64, azimuth: f64) -> Result<Self, SensorError> {
        Self::new(range, azimuth, 0.0)
    }

    /// Range standard deviation σr, metres.
    #[must_use]
    pub fn range(&self) -> f64 {
        self.range
    }

    /// Azimuth standard deviation σψ, radians.
    #[must_use]
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }

    /// Elevation standard deviation σθ, radians.
    #[must_use]
    pub fn elevation(&self) -> f64 {
        self.elevation
    }
}

/// Converts decibels to a linear power ratio: `10^(dB/10)`.
#[must_use]
pub fn db_to_linear(db: f64) -> f64 {
    10f64.powf(db / 10.0)
}

/// Converts a linear power ratio to decibels: `10 log₁₀(x)` (−∞ for 0, NaN for a
/// negative ratio).
#[must_use]
pub fn linear_to_db(ratio: f64) -> f64 {
    10.0 * ratio.log10()
}

/// A one-way-attenuation link budget: `SNR(R) = SNR_ref (R_ref / R)²` (linear,
/// not dB), as for a beacon whose reply falls as `1/R²`.
///
/// # References
/// Seed 003 (Kim & Hwang 2013), §IV: "link budget over range"; the `1/R²` law
/// is the beacon (one-way) case fixed in SPEC.md.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkBudget {
    snr_ref: f64,
    range_ref: f64,
}

impl LinkBudget {
    /// A link budget with linear SNR `snr_ref` at range `range_ref` (m).
    ///
    /// # Errors
    /// [`SensorError::NotPositive`] / [`SensorError::NonFinite`] unless both are finite and `> 0`.
    pub fn new(snr_ref: f64, range_ref: f64) -> Result<Self, SensorError> {
        Ok(Self {
            snr_ref: positive(snr_ref, "reference SNR")?,
            range_ref: positive(range_ref, "reference range")?,
        })
    }

    /// The linear SNR at `range`: `SNR_ref (R_ref / R)²`. Infinite at `range = 0`
    /// (the noise standard deviations are then 0).
    #[must_use]
    pub fn snr_at(&self, range: f64) -> f64 {
        let q = self.range_ref / range.abs();
        self.snr_ref * q * q
    }

    /// The linear reference SNR.
    #[must_use]
    pub fn snr_ref(&self) -> f64 {
        self.snr_ref
    }

    /// The reference range, m.
    #[must_use]
    pub fn range_ref(&self) -> f64 {
        self.range_ref
    }
}

/// Radar parameters that set the noise from the SNR, seed 003 eqs (6)–(8):
///
/// `σr = Δr / √(2 SNR)`, `σψ = ψ_BW / (k_m √(2 SNR))`, `σθ = θ_BW / (k_m √(2 SNR))`,
///
/// with `Δr` the range resolution, `ψ_BW`, `θ_BW` the beamwidths and `k_m` the
/// monopulse slope; the SNR comes from a [`LinkBudget`] at the target's range.
///
/// # References
/// Seed 003 (Kim & Hwang 2013), eqs (6)–(8) (after G. R. Curry, *Radar System Performance Modeling*,
/// 2nd ed., Artech House 2004, their ref. \[12\]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnrNoise {
    range_resolution: f64,
    azimuth_beamwidth: f64,
    elevation_beamwidth: f64,
    monopulse_slope: f64,
    link: LinkBudget,
}

impl SnrNoise {
    /// Validated radar parameters: range resolution `Δr` (m), azimuth and
    /// elevation beamwidths (rad), monopulse slope `k_m`, and the link budget.
    ///
    /// # Errors
    /// [`SensorError::NotPositive`] / [`SensorError::NonFinite`] unless every
    /// parameter is finite and `> 0`.
    pub fn new(
        range_resolution: f64,
        azimuth_beamwidth: f64,
        elevation_beamwidth: f64,
        monopulse_slope: f64,
        link: LinkBudget,
    ) -> Result<Self, SensorError> {
        Ok(Self {
            range_resolution: positive(range_resolution, "range resolution")?,
            azimuth_beamwidth: positive(azimuth_beamwidth, "azimuth beamwidth")?,
            elevation_beamwidth: positive(elevation_beamwidth, "elevation beamwidth")?,
            monopulse_slope: positive(monopulse_slope, "monopulse slope k_m")?,
            link,
        })
    }

    /// The link budget that makes `σr = sigma_range` at `range_ref`:
    /// `SNR_ref = Δr² / (2 σr²)` (eq (6) solved for the SNR).
    ///
    /// # Errors
    /// [`SensorError::NotPositive`] / [`SensorError::NonFinite`] unless all three are finite and `> 0`.
    pub fn link_for_range_sigma(
        range_resolution: f64,
        sigma_range: f64,
        range_ref: f64,
    ) -> Result<LinkBudget, SensorError> {
        let dr = positive(range_resolution, "range resolution")?;
        let s = positive(sigma_range, "range sigma")?;
        LinkBudget::new(dr * dr / (2.0 * s * s), range_ref)
    }

    /// The standard deviations at a given linear SNR (eqs (6)–(8)). Use this with
    /// a per-plot SNR (e.g. the link-budget SNR with a random fluctuation).
    ///
    /// # Errors
    /// [`SensorError::NotPositive`] / [`SensorError::NonFinite`] unless `snr` is
    /// finite and `> 0`.
    pub fn sigmas_at_snr(&self, snr: f64) -> Result<Sigmas, SensorError> {
        let snr = positive(snr, "SNR")?;
        Ok(self.sigmas_unchecked(snr))
    }

    /// The standard deviations at the link-budget SNR for a target at `range` (m).
    /// They are 0 at `range = 0` (infinite SNR).
    #[must_use]
    pub fn sigmas_at_range(&self, range: f64) -> Sigmas {
        self.sigmas_unchecked(self.link.snr_at(range))
    }

    fn sigmas_unchecked(&self, snr: f64) -> Sigmas {
        let root = (2.0 * snr).sqrt();
        Sigmas {
            range: self.range_resolution / root,
            azimuth: self.azimuth_beamwidth / (self.monopulse_slope * root),
            elevation: self.elevation_beamwidth / (self.monopulse_slope * root),
        }
    }

    /// The link budget.
    #[must_use]
    pub fn link(&self) -> &LinkBudget {
        &self.link
    }
}

/// How a measurement model's noise is set: constant standard deviations, or
/// from the SNR at the target's range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RadarNoise {
    /// The same standard deviations for every plot.
    Constant(Sigmas),
    /// Standard deviations from the link-budget SNR at the predicted range
    /// (seed 003 eqs (6)–(8)).
    Snr(SnrNoise),
}

impl RadarNoise {
    /// Constant standard deviations (range m, azimuth rad, elevation rad).
    ///
    /// # Errors
    /// As [`Sigmas::new`].
    pub fn constant(range: f64, azimuth: f64, elevation: f64) -> Result<Self, SensorError> {
        Ok(Self::Constant(Sigmas::new(range, azimuth, elevation)?))
    }

    /// The standard deviations for a target at `range` (m).
    #[must_use]
    pub fn sigmas_at_range(&self, range: f64) -> Sigmas {
        match self {
            Self::Constant(s) => *s,
            Self::Snr(snr) => snr.sigmas_at_range(range),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snr_sigmas_by_hand() {
        // Δr = 149.9 m, BW = 2° = 0.034906585 rad, k_m = 1.6, SNR = 13 dB = 19.952623:
        // √(2·19.952623) = 6.3170599; σr = 149.9/6.3170599 = 23.7294;
        // σψ = 0.034906585/(1.6·6.3170599) = 3.4536e-3 rad (hand computation).
        let link = LinkBudget::new(db_to_linear(13.0), 1000.0).unwrap();
        let bw = 2f64.to_radians();
        let n = SnrNoise::new(149.9, bw, bw, 1.6, link).unwrap();
        let s = n.sigmas_at_range(1000.0);
        let root = (2.0 * 19.952_623_149_688_8_f64).sqrt();
        assert!((root - 6.317_059_9).abs() < 1e-6);
        assert!((s.range() - 23.729_4).abs() < 1e-3);
        assert!((s.azimuth() - 3.453_6e-3).abs() < 1e-6);
        assert!((s.elevation() - s.azimuth()).abs() < 1e-18);
        // Twice the range: SNR/4, so every σ doubles (1/R² link, σ ∝ 1/√SNR).
        let s2 = n.sigmas_at_range(2000.0);
        assert!((s2.range() / s.range() - 2.0).abs() < 1e-12);
        assert!((s2.azimuth() / s.azimuth() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn calibrated_link_reproduces_spec_sigma() {
        // SPEC.md, seed 003 defaults: Δr = 149.9 m, σr = 2.97 m at 3006 m.
        // SNR_ref = 149.9²/(2·2.97²) = 1273.68 (31.05 dB).
        let link = SnrNoise::link_for_range_sigma(149.9, 2.97, 3006.0).unwrap();
        assert!((link.snr_ref() - 1273.68).abs() < 0.01);
        assert!((linear_to_db(link.snr_ref()) - 31.05).abs() < 0.01);
        let bw = 2f64.to_radians();
        let n = SnrNoise::new(149.9, bw, bw, 1.6, link).unwrap();
        assert!((n.sigmas_at_range(3006.0).range() - 2.97).abs() < 1e-12);
        // σψ = 0.034906585/(1.6 · 149.9/2.97) = 4.3226e-4 rad.
        assert!((n.sigmas_at_range(3006.0).azimuth() - 4.3226e-4).abs() < 1e-8);
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        assert!(matches!(
            Sigmas::new(-1.0, 0.0, 0.0),
            Err(SensorError::Negative { .. })
        ));
        assert!(matches!(
            Sigmas::new(f64::NAN, 0.0, 0.0),
            Err(SensorError::NonFinite { .. })
        ));
        assert!(matches!(
            LinkBudget::new(0.0, 1.0),
            Err(SensorError::NotPositive { .. })
        ));
        let link = LinkBudget::new(10.0, 1.0).unwrap();
        assert!(SnrNoise::new(1.0, 1.0, 1.0, 0.0, link).is_err());
        let n = SnrNoise::new(1.0, 1.0, 1.0, 1.0, link).unwrap();
        assert!(n.sigmas_at_snr(-3.0).is_err());
    }
}
