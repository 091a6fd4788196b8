"""Metrics against their definitions, and the polar filters' behaviour."""

from __future__ import annotations

import numpy as np
import pytest

import argus_tracking as at


def test_nees_and_nis_are_the_quadratic_forms():
    rng = np.random.default_rng(1)
    a = rng.normal(size=(50, 4, 4))
    p = a @ a.transpose(0, 2, 1) + 4 * np.eye(4)
    x, truth = rng.normal(size=(50, 4)), rng.normal(size=(50, 4))
    e = x - truth
    want = np.einsum("ni,ni->n", e, np.linalg.solve(p, e[..., None])[..., 0])
    # 1e-10 relative: a Cholesky solve against LU on well-conditioned 4 × 4 matrices.
    np.testing.assert_allclose(at.nees(x, p, truth), want, rtol=1e-10)
    np.testing.assert_allclose(at.nis(e, p), want, rtol=1e-10)


def test_chi2_interval_matches_the_table():
    # Bar-Shalom, Li & Kirubarajan (2001) §5.4.2: n = 2, 50 runs, 95 %: χ²_100 quantiles
    # 74.222 and 129.561 over 50 (table values to 3 decimals, hence 1e-4).
    lo, hi = at.chi2_interval(2, 50, 0.95)
    assert abs(lo - 74.222 / 50) < 1e-4 and abs(hi - 129.561 / 50) < 1e-4


def test_ospa_and_gospa_by_hand():
    truth = np.array([[0.0, 0.0], [100.0, 0.0]])
    est = np.array([[3.0, 4.0]])
    # OSPA p = 1, c = 50: (5 + 50 · 1) / 2 = 27.5 (Schuhmacher et al. 2008 eq. (3)).
    o = at.ospa(truth, est, cutoff=50.0, order=1.0)
    assert abs(o["distance"] - 27.5) < 1e-12
    # GOSPA p = 2, c = 50, α = 2: (5² + 50²/2 · 1 missed)^{1/2}.
    g = at.gospa(truth, est, cutoff=50.0, order=2.0)
    assert abs(g["distance"] - np.sqrt(25 + 1250)) < 1e-9
    assert (g["assigned"], g["missed_count"], g["false_count"]) == (1, 1, 0)


@pytest.mark.parametrize("cls", [at.ExtendedKalmanFilter, at.UnscentedKalmanFilter])
def test_polar_filters_track_a_cv_target_consistently(cls):
    # 40 seeded runs of 60 plots of a CV target seen by a polar radar.
    rng = np.random.default_rng(7)
    sr, sa, dt, n, runs = 30.0, 0.002, 1.0, 60, 40
    f = cls("cv", q=0.5, sigma_range=sr, sigma_azimuth=sa)
    total = np.zeros(n)
    for _ in range(runs):
        x = np.array([8000.0, -50.0, 6000.0, 30.0])
        truth, plots = [], []
        for _ in range(n):
            w = rng.normal(scale=0.5, size=2)
            x = x + np.array([x[1] * dt + w[0] * dt**2 / 2, w[0] * dt, x[3] * dt + w[1] * dt**2 / 2, w[1] * dt])
            truth.append(x)
            plots.append([np.hypot(x[0], x[2]) + rng.normal(scale=sr), np.arctan2(x[2], x[0]) + rng.normal(scale=sa)])
        truth, plots = np.array(truth), np.array(plots)
        p0 = np.diag([900.0, 400.0, 900.0, 400.0])
        x0 = truth[0] + rng.multivariate_normal(np.zeros(4), p0)
        run = f.run(np.arange(1, n + 1) * dt, plots, x0, p0, t0=0.0)
        total += at.nees(run.x, run.P, truth)
    # Per step, the ANEES over the runs against its 95 % interval (chi-square with 4 · 40
    # dof): about 95 % of the steps after the start-up should fall inside; ≥ 85 % allows
    # for the steps' correlation in time; a wrong Jacobian or residual puts most outside.
    anees = total[10:] / runs
    lo, hi = at.chi2_interval(4, runs, 0.95)
    inside = np.mean((anees > lo) & (anees < hi))
    assert inside >= 0.85, (inside, anees.mean())


def test_multi_imm_and_difference_estimate_the_noise():
    # A straight CV target seen with σr = 60 m, σa = 0.004 rad while both estimators
    # start from half those values: after 300 plots each estimate is within 25 % of the
    # truth (the paper's estimates converge to within ~10 %; 25 % leaves room for one run).
    rng = np.random.default_rng(3)
    n, dt = 300, 2.0
    t = np.arange(1, n + 1) * dt
    x = np.stack([20_000 - 100 * t, 15_000 + 60 * t], axis=1)
    plots = np.stack(
        [np.hypot(x[:, 0], x[:, 1]) + rng.normal(scale=60.0, size=n),
         np.arctan2(x[:, 1], x[:, 0]) + rng.normal(scale=0.004, size=n)], axis=1)
    x0 = np.array([20_000.0, -100.0, 15_000.0, 60.0])
    p0 = np.diag([1e4, 400.0, 1e4, 400.0])
    models, m = [("cv", 0.5), ("cv", 5.0)], [[0.95, 0.05], [0.05, 0.95]]
    for est in (
        at.MultiImm(models, m, sigma_range=30.0, sigma_azimuth=0.002, n=5, p=0.1),
        at.DifferenceImm(models, m, sigma_range=30.0, sigma_azimuth=0.002),
    ):
        run = est.run(t, plots, x0, p0, t0=0.0)
        assert run.noise.shape == (n, 2) and run.mode_probabilities.shape == (n, 2)
        np.testing.assert_allclose(run.mode_probabilities.sum(axis=1), 1.0, rtol=1e-12)
        assert abs(run.noise[-1, 0] / 60.0 - 1) < 0.25, (type(est).__name__, run.noise[-1])
        assert abs(run.noise[-1, 1] / 0.004 - 1) < 0.25, (type(est).__name__, run.noise[-1])
