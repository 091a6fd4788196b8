//! Pseudo bias measurements for asynchronous sensors, seed 004 eqs (22)–(32).

use argus_core_math::faer::Mat;

use crate::error::RegistrationError;
use crate::estimator::PseudoMeasurement;
use crate::local::{BiasedLocalFilter, BiasedTrack, position_matrix};
use crate::polar::ConvertedPlot;

/// The stacked pseudo bias measurement made when sensor `i`'s plot of a target arrives,
/// against every other sensor `j`'s local track of the same target predicted to the
/// plot time, eqs (22)–(32):
///
/// `z^{b(i,j)} = z_i − H Φ X̂ᵇ_j = [B_i C_i, −H Φ G_j] [β_i; β_j] + w`, with
/// `Cov w^{(i,j)} = H P_j⁻ Hᵀ + R_i` (eq (27)). The blocks are stacked over `j ≠ i`
/// (eq (28)); because every block carries the same plot noise `w_i`, the off-diagonal
/// blocks of the stacked `R_b` are `R_i` (eq (32); a diagonal `R_b` would be over-confident).
///
/// `others` lists `(j, track_j)`; each track must not be later than the plot.
///
/// # References
/// Seed 004 eqs (22)–(32).
///
/// # Errors
/// [`RegistrationError::Empty`] without other tracks, [`RegistrationError::UnknownSensor`]
/// for `i` or a `j` out of range, [`RegistrationError::InvalidParameter`] for `j = i` or a
/// repeated `j`, [`RegistrationError::TimeNotIncreasing`] for a track later than the plot.
#[allow(non_snake_case)]
pub fn pseudo_measurement(
    filter: &BiasedLocalFilter,
    sensors: usize,
    i: usize,
    plot: &ConvertedPlot,
    others: &[(usize, &BiasedTrack)],
) -> Result<PseudoMeasurement, RegistrationError> {
    if i >= sensors {
        return Err(RegistrationError::UnknownSensor { sensor: i, sensors });
    }
    if others.is_empty() {
        return Err(RegistrationError::Empty {
            what: "other sensors' tracks",
        });
    }
    let mut seen = vec![false; sensors];
    for &(j, _) in others {
        let slot = seen
            .get_mut(j)
            .ok_or(RegistrationError::UnknownSensor { sensor: j, sensors })?;
        if j == i || *slot {
            return Err(RegistrationError::InvalidParameter {
                what: "other sensor index",
                value: j as f64,
                reason: "must differ from the plot's sensor and appear once",
            });
        }
        *slot = true;
    }
    let H = position_matrix();
    let n = others.len();
    let m = 2 * n;
    let d = 4 * sensors;
    let mut z = Mat::<f64>::zeros(m, 1);
    let mut hb = Mat::<f64>::zeros(m, d);
    let mut r = Mat::<f64>::zeros(m, m);
    let Ri = plot.noise();
    let BCi = plot.bias_jacobian();
    for (k, &(j, track)) in others.iter().enumerate() {
        let pred = filter.predict(track, plot.time())?;
        let zk = plot.z() - H * pred.estimate().mean();
        let Gj = -(H * pred.g());
        let Pj = H * pred.estimate().cov() * H.transpose();
        for a in 0..2 {
            let row = 2 * k + a;
            z[(row, 0)] = zk[a];
            for c in 0..4 {
                hb[(row, 4 * i + c)] = BCi[(a, c)];
                hb[(row, 4 * j + c)] = Gj[(a, c)];
            }
            for (l, _) in others.iter().enumerate() {
                for bcol in 0..2 {
                    r[(row, 2 * l + bcol)] = Ri[(a, bcol)];
                }
            }
            for bcol in 0..2 {
                r[(row, 2 * k + bcol)] += Pj[(a, bcol)];
            }
        }
    }
    PseudoMeasurement::new(z, hb, r)
}
