//! The batch run of a linear Kalman filter with a time-invariant model, reusing the
//! covariance recursion.
//!
//! For the KF on a linear motion model whose `Q(dt)` does not depend on the state, with a
//! linear sensor of constant `R` (the package's Cartesian sensor), the predicted
//! covariance, `S`, its factor, the gain `K` and the posterior covariance of a step are
//! functions of `(dt, P_prior)` only — not of the plots. When a step's `dt` and prior
//! covariance are bit-identical to an earlier step's, those matrices are bit-identical to
//! that step's, so they are taken from a small table instead of being computed again
//! (memoisation, not an approximation: the same floating-point operations would give the
//! same bits). The mean is computed as the full step computes it — `x⁻ = f(x, dt)`
//! (`propagate`, which is `predict_moments`' mean for these models), `ν = z ⊖ h(x⁻)`,
//! `x = x⁻ + K ν` (`kernels::mul`) and `NIS = νᵀ S⁻¹ ν` through the same factor — so a run
//! equals the step-by-step run bit for bit (tested from Python). Any step whose mean or
//! residual fails a check is recomputed by the full step, which raises its error.
//!
//! A converged recursion in float64 reaches a fixed point or a short cycle (measured: the
//! 2-D CV, CA and CT KFs within ~100 steps, cycles of 1 to 3 steps; the 3-D CV a 6-step
//! cycle; the 3-D CA none within 6 000 steps, so it gains nothing). After
//! [`GIVE_UP_NEW_DT`] consecutive steps with intervals not seen before, or [`GIVE_UP`]
//! consecutive misses, the run finishes with the full step alone.

use argus_core_math::{Gaussian, Matrix, Vector, kernels};
use argus_filters::{FilterError, GaussianFilter, MeasurementPrediction};
use argus_sensors::MeasurementModel;

use crate::run_io::{RunFail, RunSlices};

/// How many `(dt, P_prior)` keys are kept: a converged recursion reaches a fixed point or
/// a short cycle of round-off; interleaved intervals need one key each.
const SLOTS: usize = 8;

/// Consecutive steps whose interval matches no stored key after which the run stops
/// looking up and storing keys and finishes with the full step alone: with intervals that
/// never repeat exactly (a radar's jittered times) the table only costs (+40 % on 10⁵
/// jittered CV steps before this rule). Misses with a known interval (the transient before
/// the recursion settles, ~100 steps) do not count here.
const GIVE_UP_NEW_DT: usize = 64;

/// Consecutive misses of any kind after which the run gives up the table likewise (a
/// recursion that does not settle into a short cycle, as the 3-D CA's).
const GIVE_UP: usize = 4096;

/// What a step computes from its key `(dt, P_prior)` alone.
struct Entry<const N: usize, const M: usize> {
    /// `dt`'s bits (0 for an update without a prediction).
    dt: u64,
    /// The prior covariance (compared bit for bit).
    prior: Matrix<N, N>,
    /// The measurement prediction (its gain and the factor of `S`); its `ẑ` is not used.
    mp: MeasurementPrediction<N, M>,
    /// The posterior covariance (checked positive definite when it was computed).
    post: Matrix<N, N>,
    /// `post` transposed: its column-major storage is the row-major output.
    post_rows: Matrix<N, N>,
    /// The entry that followed this one, with that step's `dt` bits: its prior is this
    /// entry's posterior (compared once, when the link was made).
    next: Option<(u64, usize)>,
}

/// Whether two matrices have the same bits (`==` would equate `0.0` and `-0.0`).
#[inline(always)]
fn same<const N: usize>(a: &Matrix<N, N>, b: &Matrix<N, N>) -> bool {
    a.as_slice()
        .iter()
        .zip(b.as_slice())
        .all(|(u, v)| u.to_bits() == v.to_bits())
}

/// The covariance the current estimate has: its own, or a table entry's posterior.
enum Cov<const N: usize> {
    /// A fully computed estimate.
    Own(Gaussian<N>),
    /// Entry `i`'s posterior covariance, with the current mean.
    Entry(usize, Vector<N>),
}

/// One full step (the run's ordinary path): `estimate` becomes the posterior, and the
/// step's covariance-only results are returned for the table.
fn full_step<const N: usize, const M: usize, F, Me>(
    filter: &F,
    meas: &Me,
    estimate: &mut Gaussian<N>,
    dt: f64,
    z: &Vector<M>,
) -> Result<(MeasurementPrediction<N, M>, f64), FilterError>
where
    F: GaussianFilter<N>,
    Me: MeasurementModel<N, M>,
{
    // `GaussianFilter::update_in_place`'s own three stages (the KF does not override it),
    // keeping the measurement prediction.
    if dt != 0.0 {
        filter.predict_in_place(estimate, dt)?;
    }
    let mp = filter.predict_measurement(estimate, meas)?;
    let innov = mp.innovation(meas, z)?;
    mp.update_in_place(estimate, &innov.residual)?;
    Ok((mp, innov.nis))
}

/// The batch run of `filter` on `meas` from `start` (see the module's text), with
/// `propagate` the motion model's mean prediction `f(x, dt)`, written into `out`.
///
/// # Errors
/// [`RunFail::Step`] with the step's error, as the step-by-step run.
pub(crate) fn run_reusing_gain<const N: usize, const M: usize, F, Me>(
    filter: &F,
    propagate: impl Fn(&Vector<N>, f64) -> Vector<N>,
    meas: &Me,
    start: Gaussian<N>,
    dts: &[f64],
    plots: &[f64],
    out: RunSlices<'_>,
) -> Result<(), RunFail>
where
    F: GaussianFilter<N>,
    Me: MeasurementModel<N, M>,
{
    let mut table: Vec<Entry<N, M>> = Vec::with_capacity(SLOTS);
    let mut next_slot = 0;
    let mut misses = 0;
    let mut new_dts = 0;
    let mut cur = Cov::Own(start);
    let mut rows = out
        .x
        .chunks_exact_mut(N)
        .zip(out.p.chunks_exact_mut(N * N))
        .zip(out.nis.iter_mut())
        .zip(dts.iter().zip(plots.chunks_exact(M)));
    let mut k = 0;
    while let Some((((x_out, p_out), nis_out), (&dt, z))) = rows.next() {
        let z = Vector::<M>::from_column_slice(z);
        let hit = match &cur {
            // The link from the entry the estimate came from, when the interval is the
            // same; otherwise a search of the table.
            Cov::Entry(i, _) => match table[*i].next {
                Some((d, j)) if d == dt.to_bits() => Some(j),
                _ => find(&table, dt, &table[*i].post),
            },
            Cov::Own(g) => find(&table, dt, g.cov()),
        };
        if let Some(j) = hit {
            let mean = match &cur {
                Cov::Own(g) => g.mean(),
                Cov::Entry(_, m) => m,
            };
            if let Some((mean, nis)) = reused_step(&propagate, meas, &table[j], mean, dt, &z, x_out)
            {
                p_out.copy_from_slice(table[j].post_rows.as_slice());
                *nis_out = nis;
                if let Cov::Entry(i, _) = cur {
                    table[i].next = Some((dt.to_bits(), j));
                }
                cur = Cov::Entry(j, mean);
                misses = 0;
                new_dts = 0;
                k += 1;
                continue;
            }
        }
        // The full step, from the current estimate (rebuilt from a table entry: its
        // covariance was accepted when the entry was made, its mean was checked).
        let mut est = match cur {
            Cov::Own(g) => g,
            Cov::Entry(i, m) => Gaussian::from_lower_triangle(m, table[i].post)
                .map_err(|e| RunFail::Step(k, FilterError::Math(e)))?,
        };
        let prior = *est.cov();
        let (mp, nis) =
            full_step(filter, meas, &mut est, dt, &z).map_err(|e| RunFail::Step(k, e))?;
        x_out.copy_from_slice(est.mean().as_slice());
        let post = *est.cov();
        let post_rows = post.transpose();
        p_out.copy_from_slice(post_rows.as_slice());
        *nis_out = nis;
        misses += 1;
        if table.iter().any(|e| e.dt == dt.to_bits()) {
            new_dts = 0;
        } else {
            new_dts += 1;
        }
        k += 1;
        if misses >= GIVE_UP || new_dts >= GIVE_UP_NEW_DT {
            // The rest with the full step alone (the plain run's loop).
            for (i, (((x_out, p_out), nis_out), (&dt, z))) in rows.enumerate() {
                let (_, nis) = full_step(
                    filter,
                    meas,
                    &mut est,
                    dt,
                    &Vector::<M>::from_column_slice(z),
                )
                .map_err(|e| RunFail::Step(k + i, e))?;
                x_out.copy_from_slice(est.mean().as_slice());
                p_out.copy_from_slice(est.cov().transpose().as_slice());
                *nis_out = nis;
            }
            return Ok(());
        }
        if hit.is_none() {
            let entry = Entry {
                dt: dt.to_bits(),
                prior,
                mp,
                post,
                post_rows,
                next: None,
            };
            if table.len() < SLOTS {
                table.push(entry);
            } else {
                // A replaced entry's links (to it and from it) no longer hold.
                table[next_slot] = entry;
                for e in &mut table {
                    if e.next.is_some_and(|(_, j)| j == next_slot) {
                        e.next = None;
                    }
                }
                next_slot = (next_slot + 1) % SLOTS;
            }
        }
        cur = Cov::Own(est);
    }
    Ok(())
}

/// The entry of key `(dt, prior)`, if any.
#[inline]
fn find<const N: usize, const M: usize>(
    table: &[Entry<N, M>],
    dt: f64,
    prior: &Matrix<N, N>,
) -> Option<usize> {
    table
        .iter()
        .position(|e| e.dt == dt.to_bits() && same(&e.prior, prior))
}

/// A step from table entry `e`: `x⁻ = f(x, dt)`, `ν = z ⊖ h(x⁻)`, `x = x⁻ + K ν` and the
/// NIS, each as the full step computes it, the posterior mean also written to `x_out`;
/// `None` when a value is not finite (the full step then reports it).
#[inline(always)]
fn reused_step<const N: usize, const M: usize, Me: MeasurementModel<N, M>>(
    propagate: &impl Fn(&Vector<N>, f64) -> Vector<N>,
    meas: &Me,
    e: &Entry<N, M>,
    mean: &Vector<N>,
    dt: f64,
    z: &Vector<M>,
    x_out: &mut [f64],
) -> Option<(Vector<N>, f64)> {
    let predicted = if dt != 0.0 {
        propagate(mean, dt)
    } else {
        *mean
    };
    let residual = meas.residual(z, &meas.predict(&predicted));
    let correction = kernels::mul(e.mp.gain(), &residual);
    // Finiteness of `x⁻` and `ν` in one test: `0 v` is ±0 for a finite `v` and NaN
    // otherwise, so the sum is ±0 exactly when every entry is finite (vector arithmetic
    // instead of a bit test per entry through the integer registers, ~40 instructions of
    // this ~210-instruction step in callgrind).
    let probe = predicted
        .iter()
        .chain(residual.iter())
        .fold(0.0, |acc, v| acc + 0.0 * v);
    if probe != 0.0 {
        return None;
    }
    // `x⁻ + K ν` element by element (the sum the full step's vector addition makes),
    // stored to the output as each element is formed: copying a just-built vector out
    // reads it back with wider loads than its element stores, which stalls on store
    // forwarding (docs/STATUS.md, session 5) and was 40 % of this loop's time.
    let mut posterior = Vector::<N>::zeros();
    let mut probe = 0.0;
    for ((o, p), (a, b)) in x_out
        .iter_mut()
        .zip(posterior.iter_mut())
        .zip(predicted.iter().zip(correction.iter()))
    {
        let v = a + b;
        probe += 0.0 * v;
        *o = v;
        *p = v;
    }
    (probe == 0.0).then(|| (posterior, e.mp.nis(&residual)))
}
