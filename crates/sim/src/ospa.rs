//! Multi-target distances between a truth set and an estimate set: OSPA and GOSPA.
//!
//! Both need the optimal assignment of estimates to truths. It is solved with the
//! [`lsap`] crate: a Rust port of SciPy's `linear_sum_assignment` (Crouse's shortest
//! augmenting path form of Jonker–Volgenant), which takes rectangular `f64` cost
//! matrices directly. The better-known `pathfinding::kuhn_munkres` needs `Ord` weights
//! (integers or ordered floats) and documents that it does not support floating-point
//! weights because of rounding, so scaled integer costs would make the "optimal"
//! assignment only approximately optimal; `lapjv` needs square matrices and `ndarray`.
//! `lsap` is small, has no `unsafe`, and its algorithm is SciPy's, which is widely
//! exercised. Its one limitation — it rejects infinite costs — does not matter here:
//! every cost is a cut-off distance, finite by construction.

use argus_core_math::Vector;

use crate::error::{SimError, positive};

/// The optimal assignment minimising `Σ cost[i][π(i)]` for a row-major `rows × cols`
/// matrix of finite costs: `(row, col)` pairs, `min(rows, cols)` of them.
pub(crate) fn optimal_assignment(
    rows: usize,
    cols: usize,
    cost: &Vec<f64>,
) -> Result<Vec<(usize, usize)>, SimError> {
    if rows == 0 || cols == 0 {
        return Ok(Vec::new());
    }
    let (r, c) = lsap::solve(rows, cols, cost, false).map_err(|_| SimError::InvalidParameter {
        what: "assignment cost matrix",
        value: cost.iter().copied().find(|v| !v.is_finite()).unwrap_or(0.0),
        reason: "the assignment solver rejected it (non-finite cost)",
    })?;
    Ok(r.into_iter().zip(c).collect())
}

/// Checks every coordinate of every point.
fn check_points<const D: usize>(points: &[Vector<D>], what: &'static str) -> Result<(), SimError> {
    for p in points {
        for &v in p.iter() {
            if !v.is_finite() {
                return Err(SimError::InvalidParameter {
                    what,
                    value: v,
                    reason: "every coordinate must be finite",
                });
            }
        }
    }
    Ok(())
}

/// The cut-off cost matrix `min(‖xᵢ − yⱼ‖, c)^p`, row-major over truths × estimates.
fn cutoff_costs<const D: usize>(
    truth: &[Vector<D>],
    estimates: &[Vector<D>],
    cutoff: f64,
    order: f64,
) -> Vec<f64> {
    let mut cost = Vec::with_capacity(truth.len() * estimates.len());
    for x in truth {
        for y in estimates {
            cost.push((x - y).norm().min(cutoff).powf(order));
        }
    }
    cost
}

/// The OSPA metric of Schuhmacher, Vo & Vo with cut-off `c` and order `p`.
///
/// For sets `X = {x₁..x_m}`, `Y = {y₁..y_n}` with `m ≤ n` (swap otherwise) and
/// `d⁽ᶜ⁾(x, y) = min(c, ‖x − y‖)`:
///
/// `d_p⁽ᶜ⁾(X, Y) = ( (1/n) ( min_π Σᵢ d⁽ᶜ⁾(xᵢ, y_π(i))^p + c^p (n − m) ) )^{1/p}`,
///
/// `0` when both sets are empty and `c` when exactly one is. It splits into a
/// localisation part `((1/n) min_π Σ d⁽ᶜ⁾^p)^{1/p}` and a cardinality part
/// `((1/n) c^p (n − m))^{1/p}` whose `p`-th powers add up to the whole.
///
/// # References
/// D. Schuhmacher, B.-T. Vo, B.-N. Vo, "A consistent metric for performance evaluation
/// of multi-object filters", IEEE Trans. Signal Processing 56(8), 2008, eq. (3)–(4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ospa {
    cutoff: f64,
    order: f64,
}

/// One OSPA value with its split.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OspaValue {
    /// The OSPA distance (same unit as the positions).
    pub distance: f64,
    /// The localisation component.
    pub localisation: f64,
    /// The cardinality component.
    pub cardinality: f64,
}

impl Ospa {
    /// OSPA with cut-off `cutoff` (> 0, position units) and order `order` (≥ 1).
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-finite or non-positive cut-off or an
    /// order below 1 or non-finite.
    pub fn new(cutoff: f64, order: f64) -> Result<Self, SimError> {
        positive("OSPA cut-off c", cutoff)?;
        check_order("OSPA order p", order)?;
        Ok(Self { cutoff, order })
    }

    /// The cut-off `c`.
    #[must_use]
    pub fn cutoff(&self) -> f64 {
        self.cutoff
    }

    /// The order `p`.
    #[must_use]
    pub fn order(&self) -> f64 {
        self.order
    }

    /// The OSPA distance between the truth positions and the estimated positions.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] when a coordinate is not finite.
    pub fn distance<const D: usize>(
        &self,
        truth: &[Vector<D>],
        estimates: &[Vector<D>],
    ) -> Result<OspaValue, SimError> {
        check_points(truth, "OSPA truth position")?;
        check_points(estimates, "OSPA estimated position")?;
        let (small, large) = if truth.len() <= estimates.len() {
            (truth, estimates)
        } else {
            (estimates, truth)
        };
        let (m, n) = (small.len(), large.len());
        if n == 0 {
            return Ok(OspaValue {
                distance: 0.0,
                localisation: 0.0,
                cardinality: 0.0,
            });
        }
        let cost = cutoff_costs(small, large, self.cutoff, self.order);
        let loc_sum: f64 = optimal_assignment(m, n, &cost)?
            .iter()
            .map(|&(i, j)| cost[i * n + j])
            .sum();
        let card_sum = self.cutoff.powf(self.order) * (n - m) as f64;
        let inv_p = 1.0 / self.order;
        let nf = n as f64;
        Ok(OspaValue {
            distance: ((loc_sum + card_sum) / nf).powf(inv_p),
            localisation: (loc_sum / nf).powf(inv_p),
            cardinality: (card_sum / nf).powf(inv_p),
        })
    }
}

fn check_order(what: &'static str, order: f64) -> Result<(), SimError> {
    if order.is_finite() && order >= 1.0 {
        Ok(())
    } else {
        Err(SimError::InvalidParameter {
            what,
            value: order,
            reason: "must be finite and at least 1",
        })
    }
}

/// The GOSPA metric with `α = 2` (Rahmathullah, García-Fernández & Svensson), cut-off
/// `c` and order `p`, split into localisation, missed-target and false-target costs.
///
/// With `α = 2` it is the minimum over assignments `γ` of pairs `(i, j)` with
/// `‖xᵢ − yⱼ‖ < c` of
///
/// `d = ( Σ_{(i,j)∈γ} ‖xᵢ − yⱼ‖^p + (c^p/2) (|X| − |γ|) + (c^p/2) (|Y| − |γ|) )^{1/p}`,
///
/// where `X` is the truth and `Y` the estimates: an unassigned truth is a *missed*
/// target, an unassigned estimate a *false* target, each costing `c^p/2`. It is the
/// same as the minimum of `Σ min(d, c)^p` over full assignments plus `c^p/2` per
/// cardinality difference, which is how it is computed; an assigned pair at `d ≥ c`
/// is then counted as one missed and one false target.
///
/// # References
/// A. S. Rahmathullah, Á. F. García-Fernández, L. Svensson, "Generalized optimal
/// sub-pattern assignment metric", FUSION 2017, Proposition 1 (α = 2 form) and §IV
/// (the split into localisation, missed and false).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gospa {
    cutoff: f64,
    order: f64,
}

/// One GOSPA value with its split. The three costs are `p`-th powers: they add up to
/// `distance^p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GospaValue {
    /// The GOSPA distance `(localisation + missed + false)^{1/p}`.
    pub distance: f64,
    /// `Σ ‖xᵢ − yⱼ‖^p` over the assigned pairs.
    pub localisation: f64,
    /// `c^p/2` times the number of missed truths.
    pub missed: f64,
    /// `c^p/2` times the number of false estimates.
    pub false_targets: f64,
    /// Number of assigned pairs (closer than `c`).
    pub assigned: usize,
    /// Number of missed truths.
    pub missed_count: usize,
    /// Number of false estimates.
    pub false_count: usize,
}

impl Gospa {
    /// GOSPA (α = 2) with cut-off `cutoff` (> 0) and order `order` (≥ 1).
    ///
    /// # Errors
    /// As [`Ospa::new`].
    pub fn new(cutoff: f64, order: f64) -> Result<Self, SimError> {
        positive("GOSPA cut-off c", cutoff)?;
        check_order("GOSPA order p", order)?;
        Ok(Self { cutoff, order })
    }

    /// The GOSPA distance between the truth positions and the estimated positions.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] when a coordinate is not finite.
    pub fn distance<const D: usize>(
        &self,
        truth: &[Vector<D>],
        estimates: &[Vector<D>],
    ) -> Result<GospaValue, SimError> {
        check_points(truth, "GOSPA truth position")?;
        check_points(estimates, "GOSPA estimated position")?;
        let (m, n) = (truth.len(), estimates.len());
        let cost = cutoff_costs(truth, estimates, self.cutoff, self.order);
        let mut localisation = 0.0;
        let mut assigned = 0;
        for (i, j) in optimal_assignment(m, n, &cost)? {
            if (truth[i] - estimates[j]).norm() < self.cutoff {
                localisation += cost[i * n + j];
                assigned += 1;
            }
        }
        let half = 0.5 * self.cutoff.powf(self.order);
        let missed_count = m - assigned;
        let false_count = n - assigned;
        let missed = half * missed_count as f64;
        let false_targets = half * false_count as f64;
        Ok(GospaValue {
            distance: (localisation + missed + false_targets).powf(1.0 / self.order),
            localisation,
            missed,
            false_targets,
            assigned,
            missed_count,
            false_count,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p2(x: f64, y: f64) -> Vector<2> {
        Vector::<2>::new(x, y)
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn ospa_single_pair_is_the_distance() {
        // X = {(0,0)}, Y = {(3,4)}, c = 10, p = 1: one pair at d = 5, n = 1 → OSPA = 5.
        let o = Ospa::new(10.0, 1.0).unwrap();
        let v = o.distance(&[p2(0.0, 0.0)], &[p2(3.0, 4.0)]).unwrap();
        assert!(close(v.distance, 5.0, 1e-12));
        assert!(close(v.cardinality, 0.0, 1e-12));
    }

    #[test]
    fn ospa_cardinality_and_cutoff() {
        // X = {(0,0), (10,0)}, Y = {(1,0)}, c = 5, p = 2, m = 1, n = 2.
        // Best: (1,0)↔(0,0) at d = 1 (the other pair is 9, cut to 5).
        // OSPA² = (1² + 5²·(2 − 1)) / 2 = 13 → OSPA = √13;
        // localisation² = 1/2, cardinality² = 25/2.
        let o = Ospa::new(5.0, 2.0).unwrap();
        let v = o
            .distance(&[p2(0.0, 0.0), p2(10.0, 0.0)], &[p2(1.0, 0.0)])
            .unwrap();
        assert!(close(v.distance, 13f64.sqrt(), 1e-12));
        assert!(close(v.localisation, 0.5f64.sqrt(), 1e-12));
        assert!(close(v.cardinality, 12.5f64.sqrt(), 1e-12));
        // Symmetric in its arguments.
        let w = o
            .distance(&[p2(1.0, 0.0)], &[p2(0.0, 0.0), p2(10.0, 0.0)])
            .unwrap();
        assert!(close(w.distance, v.distance, 1e-12));
    }

    #[test]
    fn ospa_uses_the_optimal_not_the_greedy_assignment() {
        // On the x axis: X = {0, 2}, Y = {1.5, 4}, c = 10.
        // Greedy takes the closest pair (2, 1.5) at 0.5 first, then (0, 4) at 4.
        // Optimal: (0, 1.5) + (2, 4) → p = 1: 1.5 + 2 = 3.5 (greedy 4.5), OSPA = 3.5/2 = 1.75;
        // p = 2: 2.25 + 4 = 6.25 (greedy 16.25), OSPA = √(6.25/2).
        let x = [p2(0.0, 0.0), p2(2.0, 0.0)];
        let y = [p2(1.5, 0.0), p2(4.0, 0.0)];
        let v1 = Ospa::new(10.0, 1.0).unwrap().distance(&x, &y).unwrap();
        assert!(close(v1.distance, 1.75, 1e-12));
        let v2 = Ospa::new(10.0, 2.0).unwrap().distance(&x, &y).unwrap();
        assert!(close(v2.distance, (6.25f64 / 2.0).sqrt(), 1e-12));
    }

    #[test]
    fn ospa_empty_sets() {
        // Both empty: 0; one empty: c (Schuhmacher et al. 2008, definition).
        let o = Ospa::new(7.0, 2.0).unwrap();
        let none: [Vector<2>; 0] = [];
        assert!(close(o.distance(&none, &none).unwrap().distance, 0.0, 0.0));
        assert!(close(
            o.distance(&none, &[p2(1.0, 1.0)]).unwrap().distance,
            7.0,
            1e-12
        ));
        assert!(close(
            o.distance(&[p2(1.0, 1.0)], &none).unwrap().distance,
            7.0,
            1e-12
        ));
    }

    #[test]
    fn gospa_split_by_hand() {
        // c = 10, p = 2, α = 2: c^p/2 = 50.
        // X = {(0,0), (100,0)}, Y = {(3,4), (50,50), (60,60)}.
        // (0,0)↔(3,4) at 5 < c: localisation 25. (100,0) is more than c from every
        // estimate: missed, 50. (50,50) and (60,60) are unassigned: false, 2·50 = 100.
        // GOSPA = √(25 + 50 + 100) = √175.
        let g = Gospa::new(10.0, 2.0).unwrap();
        let v = g
            .distance(
                &[p2(0.0, 0.0), p2(100.0, 0.0)],
                &[p2(3.0, 4.0), p2(50.0, 50.0), p2(60.0, 60.0)],
            )
            .unwrap();
        assert!(close(v.localisation, 25.0, 1e-12));
        assert!(close(v.missed, 50.0, 1e-12));
        assert!(close(v.false_targets, 100.0, 1e-12));
        assert!(close(v.distance, 175f64.sqrt(), 1e-12));
        assert_eq!((v.assigned, v.missed_count, v.false_count), (1, 1, 2));
    }

    #[test]
    fn gospa_pair_beyond_cutoff_is_missed_plus_false() {
        // X = {(0,0)}, Y = {(12,0)}, c = 10, p = 1: 12 ≥ c, so one missed (5) and one
        // false (5): GOSPA = 10, localisation 0. At (9,0) it is assigned: GOSPA = 9.
        let g = Gospa::new(10.0, 1.0).unwrap();
        let v = g.distance(&[p2(0.0, 0.0)], &[p2(12.0, 0.0)]).unwrap();
        assert!(close(v.distance, 10.0, 1e-12));
        assert!(close(v.localisation, 0.0, 0.0));
        assert_eq!((v.assigned, v.missed_count, v.false_count), (0, 1, 1));
        let w = g.distance(&[p2(0.0, 0.0)], &[p2(9.0, 0.0)]).unwrap();
        assert!(close(w.distance, 9.0, 1e-12));
        assert_eq!(w.assigned, 1);
    }

    #[test]
    fn gospa_equals_n_times_ospa_for_equal_sizes_within_cutoff() {
        // With |X| = |Y| = n and all optimal distances below c, GOSPA^p = Σ d^p = n·OSPA^p
        // (both minimise the same sum; Rahmathullah et al. 2017, §III).
        let x = [p2(0.0, 0.0), p2(2.0, 0.0), p2(5.0, 5.0)];
        let y = [p2(1.5, 0.0), p2(4.0, 0.0), p2(5.0, 6.0)];
        let o = Ospa::new(10.0, 2.0).unwrap().distance(&x, &y).unwrap();
        let g = Gospa::new(10.0, 2.0).unwrap().distance(&x, &y).unwrap();
        assert!(close(g.distance.powi(2), 3.0 * o.distance.powi(2), 1e-9));
    }

    #[test]
    fn rejects_bad_parameters_and_points() {
        assert!(Ospa::new(0.0, 1.0).is_err());
        assert!(Ospa::new(f64::NAN, 1.0).is_err());
        assert!(Ospa::new(1.0, 0.5).is_err());
        assert!(Gospa::new(-1.0, 2.0).is_err());
        assert!(Gospa::new(1.0, f64::INFINITY).is_err());
        let o = Ospa::new(1.0, 1.0).unwrap();
        let err = o
            .distance(&[p2(f64::NAN, 0.0)], &[p2(0.0, 0.0)])
            .unwrap_err();
        assert!(matches!(
            err,
            SimError::InvalidParameter {
                what: "OSPA truth position",
                ..
            }
        ));
        let g = Gospa::new(1.0, 1.0).unwrap();
        assert!(
            g.distance(&[p2(0.0, 0.0)], &[p2(0.0, f64::INFINITY)])
                .is_err()
        );
    }
}
