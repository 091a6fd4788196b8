//! The EXX baseline (Lin, Bar-Shalom & Kirubarajan 2005) in the plot-triple form of
//! SPEC §004: three plots of one target at times `t₁, t₂, t₃` combined with weights
//! `a ∝ (t₂ − t₃, t₃ − t₁, t₁ − t₂)`, which cancel a constant-velocity state
//! (`Σ a_k = 0`, `Σ a_k t_k = 0`), leaving a state-independent pseudo-measurement of the
//! biases: `Σ a_k z_k = Σ a_k B_k C_k β_{s_k} + Σ a_k w_k`.
//!
//! **Slot rule**: per target, the plots are taken in arrival order and grouped into
//! consecutive *disjoint* triples; a triple whose plots all come from one sensor is not
//! used — its oldest plot is dropped and the slot waits for the next plot. Disjoint
//! triples have independent noise, so the least-squares estimate stays consistent.

use argus_core_math::faer::Mat;

use crate::error::{RegistrationError, finite};
use crate::estimator::PseudoMeasurement;
use crate::polar::ConvertedPlot;

/// The EXX pseudo-measurement of three plots `(sensor, plot)` of one target.
///
/// # References
/// Lin, Bar-Shalom & Kirubarajan, IEEE T-AES 41(3), 2005 (EXX); SPEC §004.
///
/// # Errors
/// [`RegistrationError::UnknownSensor`] for a sensor out of range,
/// [`RegistrationError::InvalidParameter`] when all three times coincide.
#[allow(non_snake_case)]
pub fn exx_pseudo_measurement(
    sensors: usize,
    plots: &[(usize, ConvertedPlot); 3],
) -> Result<PseudoMeasurement, RegistrationError> {
    for &(s, _) in plots {
        if s >= sensors {
            return Err(RegistrationError::UnknownSensor { sensor: s, sensors });
        }
    }
    let [t1, t2, t3] = [plots[0].1.time(), plots[1].1.time(), plots[2].1.time()];
    let raw = [t2 - t3, t3 - t1, t1 - t2];
    let scale = raw.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if scale.is_nan() || scale <= 0.0 {
        return Err(RegistrationError::InvalidParameter {
            what: "EXX triple time spread",
            value: scale,
            reason: "three plots at the same time cancel nothing",
        });
    }
    let d = 4 * sensors;
    let mut z = Mat::<f64>::zeros(2, 1);
    let mut h = Mat::<f64>::zeros(2, d);
    let mut r = Mat::<f64>::zeros(2, 2);
    for (&(s, ref p), a) in plots.iter().zip(raw.map(|x| x / scale)) {
        let BC = p.bias_jacobian();
        for i in 0..2 {
            z[(i, 0)] += a * p.z()[i];
            for c in 0..4 {
                h[(i, 4 * s + c)] += a * BC[(i, c)];
            }
            for j in 0..2 {
                r[(i, j)] += a * a * p.noise()[(i, j)];
            }
        }
    }
    PseudoMeasurement::new(z, h, r)
}

/// A target's pending plots and the time of its last plot.
pub(crate) type Slot = (Vec<(usize, ConvertedPlot)>, Option<f64>);

/// Collects plots per target into EXX slots (see the module docs for the slot rule).
#[derive(Debug, Clone)]
pub struct ExxCollector {
    sensors: usize,
    slots: Vec<Vec<(usize, ConvertedPlot)>>,
    last_time: Vec<Option<f64>>,
}

impl ExxCollector {
    /// A collector for `sensors` sensors and `targets` targets.
    ///
    /// # Errors
    /// [`RegistrationError::Empty`] for zero sensors or targets.
    pub fn new(sensors: usize, targets: usize) -> Result<Self, RegistrationError> {
        if sensors == 0 {
            return Err(RegistrationError::Empty { what: "sensor set" });
        }
        if targets == 0 {
            return Err(RegistrationError::Empty { what: "target set" });
        }
        Ok(Self {
            sensors,
            slots: vec![Vec::with_capacity(3); targets],
            last_time: vec![None; targets],
        })
    }

    pub(crate) fn snapshot(&self, target: usize) -> Option<Slot> {
        Some((
            self.slots.get(target)?.clone(),
            *self.last_time.get(target)?,
        ))
    }

    pub(crate) fn restore(&mut self, target: usize, snap: Slot) {
        if let (Some(slot), Some(last)) =
            (self.slots.get_mut(target), self.last_time.get_mut(target))
        {
            *slot = snap.0;
            *last = snap.1;
        }
    }

    /// Adds sensor `s`'s plot of `target`; returns the pseudo-measurement when a slot fills.
    ///
    /// # Errors
    /// [`RegistrationError::UnknownSensor`], [`RegistrationError::InvalidParameter`] for a
    /// target out of range, [`RegistrationError::TimeNotIncreasing`] when the plot is earlier
    /// than the target's previous plot. On error nothing is stored.
    pub fn push(
        &mut self,
        target: usize,
        s: usize,
        plot: ConvertedPlot,
    ) -> Result<Option<PseudoMeasurement>, RegistrationError> {
        if s >= self.sensors {
            return Err(RegistrationError::UnknownSensor {
                sensor: s,
                sensors: self.sensors,
            });
        }
        finite("plot time", plot.time())?;
        let n = self.slots.len();
        let (Some(slot), Some(last)) = (self.slots.get_mut(target), self.last_time.get_mut(target))
        else {
            return Err(RegistrationError::InvalidParameter {
                what: "target index",
                value: target as f64,
                reason: if n == 0 { "no targets" } else { "out of range" },
            });
        };
        if let Some(prev) = *last
            && plot.time() < prev
        {
            return Err(RegistrationError::TimeNotIncreasing {
                what: "EXX plot stream",
                prev,
                now: plot.time(),
            });
        }
        let prev_last = *last;
        *last = Some(plot.time());
        slot.push((s, plot));
        if slot.len() < 3 {
            return Ok(None);
        }
        let one_sensor = slot.iter().all(|(k, _)| *k == s);
        let triple = match slot.as_slice() {
            [a, b, c] if !one_sensor => Some([*a, *b, *c]),
            _ => None,
        };
        match triple {
            Some(t) => match exx_pseudo_measurement(self.sensors, &t) {
                Ok(pm) => {
                    slot.clear();
                    Ok(Some(pm))
                }
                Err(e) => {
                    slot.pop();
                    *last = prev_last;
                    Err(e)
                }
            },
            None => {
                slot.remove(0);
                Ok(None)
            }
        }
    }
}
