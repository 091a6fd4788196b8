//! I021/090 quality indicators and what a tracker makes of them: NACp as a
//! 95 % horizontal accuracy bound turned into a position covariance, NIC as
//! a horizontal containment radius (integrity, not accuracy).
//!
//! # Tables
//! - NACp → EPU (Estimated Position Uncertainty, the radius of a circle
//!   around the reported position that holds the true position with 95 %
//!   probability): RTCA DO-242A (ADS-B MASPS) Table 3.2.11a, carried
//!   unchanged into RTCA DO-260B / EUROCAE ED-102A (1090 MHz ES MOPS,
//!   version 2). Codes 1–11 bound the EPU from above; Argus takes the bound as
//!   the 95 % radius (the conservative reading). Code 0 (EPU ≥ 10 NM or
//!   unknown) and the reserved codes 12–15 give no covariance.
//! - NIC → Rc (containment radius, 10⁻⁷/h integrity): DO-242A Table
//!   3.2.10a / DO-260B, version 2 values. NIC 6 means Rc < 0.6 NM, 0.5 NM or
//!   0.3 NM depending on the NIC supplement bits, which CAT021 edition 2.1
//!   does not carry in I021/090: Argus takes the largest, 0.6 NM.
//!
//! # From a 95 % radius to σ
//! For a circular bivariate normal with per-axis standard deviation σ, the
//! radial error r is Rayleigh: P(r ≤ R) = 1 − exp(−R²/(2σ²)). Setting that to
//! 0.95 gives R95 = σ·√(−2 ln 0.05) ≈ 2.4477 σ, so σ = EPU / 2.4477 on each
//! of east and north, uncorrelated.
//!
//! # How Rc is used
//! Rc is an integrity bound (the probability of the true position lying
//! outside it undetected is ≤ 10⁻⁷ per flight hour), far larger than the
//! statistical error; turning it into a σ would make ADS-B look like a
//! primary radar. It is therefore not part of the covariance: it is exposed
//! through [`Quality::containment_radius_m`] so a consumer can reject reports
//! whose integrity is too weak for the use (e.g. Rc above a separation
//! minimum's requirement).

use crate::fields::NM;

/// R95 / σ for a circular bivariate normal: √(−2 ln 0.05).
pub const R95_PER_SIGMA: f64 = 2.447_746_830_680_816;

/// I021/090 quality indicators: the first octet and the first extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Quality {
    /// NUCr or NACv (3 bits).
    pub nac_v: u8,
    /// NUCp or NIC (4 bits).
    pub nic: u8,
    /// First extension: NIC BARO (1 bit), SIL (2 bits), NACp (4 bits).
    pub extension: Option<QualityExt>,
}

/// I021/090 first extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct QualityExt {
    /// NIC BARO.
    pub nic_baro: bool,
    /// SIL.
    pub sil: u8,
    /// NACp.
    pub nac_p: u8,
}

/// EPU bound in metres for NACp 1–11 (index = NACp); `None` for 0 and 12–15.
#[must_use]
pub fn epu_m(nac_p: u8) -> Option<f64> {
    Some(match nac_p {
        1 => 10.0 * NM,
        2 => 4.0 * NM,
        3 => 2.0 * NM,
        4 => NM,
        5 => 0.5 * NM,
        6 => 0.3 * NM,
        7 => 0.1 * NM,
        8 => 0.05 * NM,
        9 => 30.0,
        10 => 10.0,
        11 => 3.0,
        _ => return None,
    })
}

/// Containment radius bound Rc in metres for NIC 1–11; `None` for 0 (unknown)
/// and 12–15 (reserved). NIC 6 → 0.6 NM (the largest of its readings).
#[must_use]
pub fn containment_radius_m(nic: u8) -> Option<f64> {
    Some(match nic {
        1 => 20.0 * NM,
        2 => 8.0 * NM,
        3 => 4.0 * NM,
        4 => 2.0 * NM,
        5 => NM,
        6 => 0.6 * NM,
        7 => 0.2 * NM,
        8 => 0.1 * NM,
        9 => 75.0,
        10 => 25.0,
        11 => 7.5,
        _ => return None,
    })
}

impl Quality {
    /// The EPU (95 % horizontal radius) bound from NACp, metres; `None`
    /// without the first extension or for NACp 0 / 12–15.
    #[must_use]
    pub fn epu_m(self) -> Option<f64> {
        self.extension.and_then(|e| epu_m(e.nac_p))
    }

    /// Per-axis (east, north) position standard deviation, metres:
    /// EPU / [`R95_PER_SIGMA`].
    #[must_use]
    pub fn position_sigma_m(self) -> Option<f64> {
        self.epu_m().map(|r| r / R95_PER_SIGMA)
    }

    /// The horizontal position covariance in local east/north, m²: σ² on the
    /// diagonal, no correlation (the EPU is a circle).
    #[must_use]
    pub fn position_covariance(self) -> Option<[[f64; 2]; 2]> {
        self.position_sigma_m()
            .map(|s| [[s * s, 0.0], [0.0, s * s]])
    }

    /// The containment radius bound Rc from NIC, metres (integrity only; not
    /// used in the covariance).
    #[must_use]
    pub fn containment_radius_m(self) -> Option<f64> {
        containment_radius_m(self.nic)
    }

    pub(crate) fn read(b: &[u8]) -> Self {
        Self {
            nac_v: b[0] >> 5,
            nic: (b[0] >> 1) & 0x0f,
            extension: b.get(1).map(|e| QualityExt {
                nic_baro: e & 0x80 != 0,
                sil: (e >> 5) & 3,
                nac_p: (e >> 1) & 0x0f,
            }),
        }
    }

    /// The first octet, and the first extension when present (FX chained);
    /// out-of-width values are masked to their bits.
    pub(crate) fn bytes(self, out: &mut [u8; 2]) -> usize {
        out[0] = ((self.nac_v & 7) << 5) | ((self.nic & 0x0f) << 1);
        match self.extension {
            None => 1,
            Some(e) => {
                out[0] |= 1;
                out[1] = (u8::from(e.nic_baro) << 7) | ((e.sil & 3) << 5) | ((e.nac_p & 0x0f) << 1);
                2
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r95_per_sigma_is_the_rayleigh_95_percent_point() {
        // Exact definition; 1e-15 relative is f64 rounding of ln and sqrt.
        let k = (-2.0 * 0.05f64.ln()).sqrt();
        assert!((k - R95_PER_SIGMA).abs() < 1e-15 * k);
        // Rayleigh CDF at R95 is 0.95 (same rounding tolerance).
        let p = 1.0 - (-(R95_PER_SIGMA * R95_PER_SIGMA) / 2.0).exp();
        assert!((p - 0.95).abs() < 1e-15);
    }

    #[test]
    fn nacp_tables_and_covariance() {
        // DO-242A Table 3.2.11a: NACp 9 → EPU < 30 m; 8 → 0.05 NM = 92.6 m.
        assert_eq!(epu_m(9), Some(30.0));
        assert!((epu_m(8).unwrap_or(0.0) - 92.6).abs() < 1e-9);
        assert_eq!(epu_m(0), None);
        assert_eq!(epu_m(12), None);
        // Monotone: a higher NACp is a tighter bound.
        let bounds: Vec<f64> = (1..=11).filter_map(epu_m).collect();
        assert_eq!(bounds.len(), 11);
        assert!(bounds.windows(2).all(|w| w[1] < w[0]));
        let q = Quality {
            nac_v: 1,
            nic: 8,
            extension: Some(QualityExt {
                nic_baro: true,
                sil: 3,
                nac_p: 10,
            }),
        };
        // σ = 10 m / 2.4477 = 4.085 m; variance 16.69 m² (1e-12 relative: arithmetic only).
        let c = q.position_covariance().unwrap_or([[0.0; 2]; 2]);
        let s = 10.0 / R95_PER_SIGMA;
        assert!((c[0][0] - s * s).abs() < 1e-12 && (c[1][1] - s * s).abs() < 1e-12);
        assert!(c[0][1].abs() < f64::MIN_POSITIVE && c[1][0].abs() < f64::MIN_POSITIVE);
        // NIC 8 → Rc < 0.1 NM = 185.2 m.
        assert!((q.containment_radius_m().unwrap_or(0.0) - 185.2).abs() < 1e-9);
        assert_eq!(containment_radius_m(0), None);
        // No extension: no NACp, no covariance.
        let bare = Quality {
            extension: None,
            ..q
        };
        assert_eq!(bare.position_covariance(), None);
    }

    #[test]
    fn bytes_round_trip() {
        for v in 0u8..=255 {
            for e in [None, Some(v & 0xfe)] {
                let first = v & 0xfe;
                let mut b = vec![first | u8::from(e.is_some())];
                b.extend(e);
                let q = Quality::read(&b);
                let mut out = [0u8; 2];
                let n = q.bytes(&mut out);
                // The spare LSB of the extension (FX) is 0; everything else is carried.
                assert_eq!(&out[..n], &b[..]);
            }
        }
    }
}
