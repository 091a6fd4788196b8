//! The IMM estimators behind one trait object: a plain IMM on Cartesian or converted
//! polar plots, seed 000's multi-IMM noise estimator and the difference estimator, each
//! for its compile-time mode count `R` (and hypothesis count `K`), run over a whole plot
//! array without Python objects (so the GIL can be released).

use argus_core_math::{Gaussian, Matrix, Vector};
use argus_filters::Kf;
use argus_imm::{
    DifferenceEstimate, DifferenceNoiseImm, ImmError, ImmEstimate, MultiImm, MultiImmEstimate,
    NoiseVariances, PlanarImm, UnbiasedConversion,
};
use argus_motion_models::PlanarModel;
use argus_sensors::{CartesianPosition, PolarMeasurement, UnbiasedPolarConversion};

/// How plots are read.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Plots {
    /// `(x, y)` with covariance `R`.
    Cartesian(Matrix<2, 2>),
    /// `(range, azimuth)` from `origin` with constant σ, converted without bias.
    Polar {
        origin: [f64; 2],
        sigma_range: f64,
        sigma_azimuth: f64,
    },
}

/// A batch IMM run's outputs (row-major).
#[derive(Debug, Default)]
pub(crate) struct ImmOut {
    pub(crate) x: Vec<f64>,
    pub(crate) p: Vec<f64>,
    pub(crate) mu: Vec<f64>,
    /// `(σ_range, σ_azimuth)` per step, for the noise estimators.
    pub(crate) noise: Option<Vec<f64>>,
}

impl ImmOut {
    /// Empty outputs with room for `steps` steps of `modes` modes (and the noise estimate
    /// when `noise`): no reallocation inside the run.
    fn with_capacity(steps: usize, modes: usize, noise: bool) -> Self {
        Self {
            x: Vec::with_capacity(4 * steps),
            p: Vec::with_capacity(16 * steps),
            mu: Vec::with_capacity(modes * steps),
            noise: noise.then(|| Vec::with_capacity(2 * steps)),
        }
    }
}

/// How a plain IMM's run reads its plots: Cartesian through one sensor (its fixed `R`
/// checked once per run), or polar through the unbiased conversion (constants formed once)
/// and the radar's position, with a sensor per plot (each plot's own covariance).
enum Reader {
    Cartesian(CartesianPosition<4, 2>),
    Polar(UnbiasedPolarConversion, Vector<2>),
}

/// Where a run failed.
#[derive(Debug)]
pub(crate) enum ImmFail {
    /// The start (x0, P0, mu0) is invalid.
    Start(String, ImmError),
    /// Plot `index` failed: the Rust error's name and text.
    Step(usize, String, String),
}

/// The failure of plot `k` with the Rust error `e` of type `ty`.
fn fail<E: std::fmt::Debug + std::fmt::Display>(k: usize, ty: &str, e: &E) -> ImmFail {
    ImmFail::Step(k, crate::errors::rust_name(ty, e), e.to_string())
}

/// An IMM estimator over a batch of plots.
pub(crate) trait DynImm: Send + Sync {
    /// The mode count.
    fn modes(&self) -> usize;
    /// Runs from `(x0, P0, mu0)`; `dts[k]` is the interval before plot `k`.
    fn run(
        &self,
        start: (&[f64], &[f64], &[f64]),
        dts: &[f64],
        plots: &[f64],
    ) -> Result<ImmOut, ImmFail>;
}

fn start_estimate<const R: usize>(
    (x0, p0, mu0): (&[f64], &[f64], &[f64]),
) -> Result<ImmEstimate<4, R>, ImmFail> {
    let g = Gaussian::new(
        Vector::<4>::from_column_slice(x0),
        Matrix::<4, 4>::from_row_slice(p0),
    )
    .map_err(|e| ImmFail::Start("P0".into(), ImmError::from(e)))?;
    let mut mu = [0.0; R];
    mu.copy_from_slice(mu0);
    ImmEstimate::from_common(g, mu).map_err(|e| ImmFail::Start("mu0".into(), e))
}

fn push<const R: usize>(out: &mut ImmOut, c: &Gaussian<4>, mu: &[f64; R]) {
    out.x.extend_from_slice(c.mean().as_slice());
    out.p.extend_from_slice(c.cov().transpose().as_slice());
    out.mu.extend_from_slice(mu);
}

fn polar(plots: &[f64], k: usize) -> Result<PolarMeasurement, ImmFail> {
    PolarMeasurement::new(plots[2 * k], plots[2 * k + 1]).map_err(|e| fail(k, "SensorError", &e))
}

fn conversion(origin: [f64; 2]) -> Result<UnbiasedConversion<4>, ImmFail> {
    UnbiasedConversion::<4>::new(0, 2)
        .and_then(|c| c.at(origin))
        .map_err(|e| ImmFail::Start("sensor_position".into(), e))
}

/// The plain IMM.
pub(crate) struct PlainImm<const R: usize> {
    pub(crate) imm: PlanarImm<R>,
    pub(crate) plots: Plots,
}

impl<const R: usize> DynImm for PlainImm<R> {
    fn modes(&self) -> usize {
        R
    }

    fn run(
        &self,
        start: (&[f64], &[f64], &[f64]),
        dts: &[f64],
        plots: &[f64],
    ) -> Result<ImmOut, ImmFail> {
        let mut est = start_estimate::<R>(start)?;
        let mut out = ImmOut::with_capacity(dts.len(), R, false);
        // The polar conversion's noise-only constants (its exponential) once per run, not
        // per plot: the same arithmetic as `argus_scenarios::estimator::unbiased`
        // (`convert_polar`), so the same bits.
        let reader = match self.plots {
            Plots::Cartesian(r) => Reader::Cartesian(
                CartesianPosition::<4, 2>::cv(r).map_err(|e| fail(0, "SensorError", &e))?,
            ),
            Plots::Polar {
                sigma_range,
                sigma_azimuth,
                origin,
            } => Reader::Polar(
                UnbiasedPolarConversion::new(sigma_range, sigma_azimuth)
                    .map_err(|e| fail(0, "SensorError", &e))?,
                Vector::<2>::new(origin[0], origin[1]),
            ),
        };
        for (k, dt) in dts.iter().enumerate() {
            let (z, meas) = match &reader {
                Reader::Cartesian(meas) => {
                    (Vector::<2>::new(plots[2 * k], plots[2 * k + 1]), *meas)
                }
                Reader::Polar(conv, origin) => {
                    let c = conv
                        .convert(plots[2 * k], plots[2 * k + 1])
                        .map_err(|e| fail(k, "SensorError", &e))?;
                    let meas = CartesianPosition::<4, 2>::cv(c.covariance)
                        .map_err(|e| fail(k, "SensorError", &e))?;
                    (c.position + origin, meas)
                }
            };
            if *dt == 0.0 {
                let upd = self.imm.update(&est.into_prediction(), &meas, &z);
                est = upd.map_err(|e| fail(k, "ImmError", &e))?.estimate;
            } else {
                // In place: the estimate is copied once per cycle, not three times
                // (`Imm::step`'s working copy, its result and this assignment); on an
                // error the run stops, so the restored estimate is not used.
                self.imm
                    .step_in_place(&mut est, *dt, &meas, &z)
                    .map_err(|e| fail(k, "ImmError", &e))?;
            }
            let c = est.combined().map_err(|e| fail(k, "ImmError", &e))?;
            push(&mut out, &c, &est.mode_probabilities());
        }
        Ok(out)
    }
}

/// Seed 000's multi-IMM with `K` noise hypotheses.
pub(crate) struct Multi<const R: usize, const K: usize> {
    pub(crate) multi: MultiImm<Kf<PlanarModel>, 4, R, K>,
    pub(crate) origin: [f64; 2],
    pub(crate) reference: NoiseVariances,
}

impl<const R: usize, const K: usize> DynImm for Multi<R, K> {
    fn modes(&self) -> usize {
        R
    }

    fn run(
        &self,
        start: (&[f64], &[f64], &[f64]),
        dts: &[f64],
        plots: &[f64],
    ) -> Result<ImmOut, ImmFail> {
        let conv = conversion(self.origin)?;
        let mut est = MultiImmEstimate::<4, R, K>::new(start_estimate::<R>(start)?, self.reference);
        let mut out = ImmOut::with_capacity(dts.len(), R, true);
        for (k, dt) in dts.iter().enumerate() {
            let plot = polar(plots, k)?;
            est = self
                .multi
                .step(&est, *dt, &plot, &conv)
                .map_err(|e| fail(k, "ImmError", &e))?
                .estimate;
            let c = est.combined().map_err(|e| fail(k, "ImmError", &e))?;
            push(&mut out, &c, &est.mode_probabilities());
            let v = est.reference();
            if let Some(n) = out.noise.as_mut() {
                n.extend([v.range().sqrt(), v.azimuth().sqrt()]);
            }
        }
        Ok(out)
    }
}

/// The difference estimator around one IMM.
pub(crate) struct Difference<const R: usize> {
    pub(crate) imm: DifferenceNoiseImm<Kf<PlanarModel>, 4, R>,
    pub(crate) origin: [f64; 2],
    pub(crate) initial: NoiseVariances,
    pub(crate) prior_count: f64,
}

impl<const R: usize> DynImm for Difference<R> {
    fn modes(&self) -> usize {
        R
    }

    fn run(
        &self,
        start: (&[f64], &[f64], &[f64]),
        dts: &[f64],
        plots: &[f64],
    ) -> Result<ImmOut, ImmFail> {
        let conv = conversion(self.origin)?;
        let mut est =
            DifferenceEstimate::new(start_estimate::<R>(start)?, self.initial, self.prior_count)
                .map_err(|e| ImmFail::Start("prior_count".into(), e))?;
        let mut out = ImmOut::with_capacity(dts.len(), R, true);
        for (k, dt) in dts.iter().enumerate() {
            let plot = polar(plots, k)?;
            let (next, _) = self
                .imm
                .step(&est, *dt, &plot, &conv)
                .map_err(|e| fail(k, "ImmError", &e))?;
            est = next;
            let c = est.imm().combined().map_err(|e| fail(k, "ImmError", &e))?;
            push(&mut out, &c, &est.imm().mode_probabilities());
            let v = est.variances().map_err(|e| fail(k, "ImmError", &e))?;
            if let Some(n) = out.noise.as_mut() {
                n.extend([v.range().sqrt(), v.azimuth().sqrt()]);
            }
        }
        Ok(out)
    }
}
