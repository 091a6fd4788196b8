"""Argus's KF and IMM against FilterPy's KalmanFilter and IMMEstimator, step by step on
the same data, to 1e-9.

The models are set up identically on both sides: state [x, vx, y, vy]; CV transition
per axis [[1, T], [0, 1]]; the CT transition at a known rate ω of docs of
argus-motion-models (ct.rs) [[1, s/ω, 0, -(1-c)/ω], [0, c, 0, -s], [0, (1-c)/ω, 1, s/ω],
[0, s, 0, c]] with s = sin ωT, c = cos ωT; the process noise of both is the discrete
white acceleration Q = σ² Γ Γᵀ per axis, Γ = [T²/2, T] (FilterPy's
Q_discrete_white_noise with var = σ²); H selects (x, y); FilterPy's update is the Joseph
form, as Argus's default. Tolerance 1e-9 (relative, with an absolute floor of 1e-9 in
the state's units): the issue's; both sides compute the same formulas in float64, so
round-off differences stay near 1e-12 over these runs.
"""

from __future__ import annotations

import numpy as np
import pytest
from filterpy.common import Q_discrete_white_noise
from filterpy.kalman import IMMEstimator
from filterpy.kalman import KalmanFilter as FKalmanFilter

import argus_tracking as at

DT = 2.0
R = np.array([[400.0, 60.0], [60.0, 900.0]])
H = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])


def cv_f(dt: float) -> np.ndarray:
    f = np.eye(4)
    f[0, 1] = f[2, 3] = dt
    return f


def ct_f(omega: float, dt: float) -> np.ndarray:
    s, c = np.sin(omega * dt), np.cos(omega * dt)
    return np.array(
        [
            [1, s / omega, 0, -(1 - c) / omega],
            [0, c, 0, -s],
            [0, (1 - c) / omega, 1, s / omega],
            [0, s, 0, c],
        ]
    )


def q(sigma: float, dt: float) -> np.ndarray:
    return Q_discrete_white_noise(dim=2, dt=dt, var=sigma**2, block_size=2, order_by_dim=True)


def plots(n: int, seed: int) -> "tuple[np.ndarray, np.ndarray]":
    """A target turning gently, seen in Cartesian noise of covariance R."""
    rng = np.random.default_rng(seed)
    t = np.arange(1, n + 1) * DT
    truth = np.stack([10_000 + 150 * t, 5_000 + 2_000 * np.sin(t / 60)], axis=1)
    z = truth + rng.multivariate_normal(np.zeros(2), R, size=n)
    return t, z


X0 = np.array([10_000.0, 140.0, 5_000.0, 20.0])
P0 = np.diag([500.0, 100.0, 500.0, 100.0])


def fkf(f: np.ndarray, qm: np.ndarray) -> FKalmanFilter:
    k = FKalmanFilter(dim_x=4, dim_z=2)
    k.x, k.P, k.F, k.Q, k.H, k.R = X0.copy(), P0.copy(), f, qm, H, R
    return k


def close(a, b, what: str) -> None:
    np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9, err_msg=what)


def test_kf_step_by_step_and_batch_equal_filterpy():
    t, z = plots(200, seed=11)
    sigma = 1.5
    ours = at.KalmanFilter("cv", q=sigma, R=R)
    ref = fkf(cv_f(DT), q(sigma, DT))
    x, p = X0, P0
    for k in range(len(t)):
        ref.predict()
        x, p = ours.predict(x, p, DT)
        close(x, ref.x, f"predicted x at step {k}")
        close(p, ref.P, f"predicted P at step {k}")
        ref.update(z[k])
        x, p = ours.update(x, p, z[k])
        close(x, ref.x, f"updated x at step {k}")
        close(p, ref.P, f"updated P at step {k}")
    run = ours.run(t, z, X0, P0, t0=0.0)
    close(run.x[-1], ref.x, "batch run's last x")
    close(run.P[-1], ref.P, "batch run's last P")
    # The one-call step equals predict + update.
    x1, p1 = ours.step(X0, P0, DT, z[0])
    close(x1, run.x[0], "step() against run()[0]")
    close(p1, run.P[0], "step() P against run()[0]")


def test_kf_batch_run_equals_filterpy_every_step():
    t, z = plots(300, seed=12)
    ours = at.KalmanFilter("ct", q=0.8, R=R, omega=0.01)
    ref = fkf(ct_f(0.01, DT), q(0.8, DT))
    run = ours.run(t, z, X0, P0, t0=0.0)
    for k in range(len(t)):
        ref.predict()
        ref.update(z[k])
        close(run.x[k], ref.x, f"x at step {k}")
        close(run.P[k], ref.P, f"P at step {k}")
        # NIS = yᵀ S⁻¹ y from FilterPy's innovation y and S.
        nis = float(ref.y @ np.linalg.solve(ref.S, ref.y))
        np.testing.assert_allclose(run.nis[k], nis, rtol=1e-9, err_msg=f"NIS at step {k}")


@pytest.mark.parametrize("modes", [2, 3])
def test_imm_equals_filterpy_imm_estimator(modes):
    t, z = plots(250, seed=13)
    omega = np.deg2rad(3.0)
    models = [("cv", 0.5), ("ct", 0.5, omega), ("ct", 0.5, -omega)][:modes]
    if modes == 2:
        m = np.array([[0.95, 0.05], [0.05, 0.95]])
        mu0 = np.array([0.7, 0.3])
    else:  # seed 000 eq (20)
        m = np.array([[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]])
        mu0 = np.array([0.8, 0.1, 0.1])
    ours = at.Imm(models, m, R=R)
    filters = [fkf(cv_f(DT), q(0.5, DT))] + [
        fkf(ct_f(w, DT), q(0.5, DT)) for w in (omega, -omega)
    ][: modes - 1]
    ref = IMMEstimator(filters, mu0, m)
    run = ours.run(t, z, X0, P0, mu0=mu0, t0=0.0)
    for k in range(len(t)):
        ref.predict()
        ref.update(z[k])
        close(run.x[k], ref.x, f"combined x at step {k}")
        close(run.P[k], ref.P, f"combined P at step {k}")
        close(run.mode_probabilities[k], ref.mu, f"mode probabilities at step {k}")
    assert run.noise is None


@pytest.mark.parametrize("cls", ["kf", "ukf"])
def test_rts_smoother_equals_filterpy_rts_smoother(cls):
    # Issue 19: Argus's fixed-interval RTS smoother (the unscented RTS for the UKF, which
    # on a linear model equals the RTS to round-off) against FilterPy's rts_smoother on
    # the same forward pass, to 1e-9.
    t, z = plots(150, seed=14)
    sigma = 1.0
    if cls == "kf":
        ours = at.KalmanFilter("cv", q=sigma, R=R)
    else:
        ours = at.UnscentedKalmanFilter("cv", q=sigma, sensor="cartesian", R=R)
    ref = fkf(cv_f(DT), q(sigma, DT))
    xs, ps = [], []
    for k in range(len(t)):
        ref.predict()
        ref.update(z[k])
        xs.append(ref.x.copy())
        ps.append(ref.P.copy())
    sx, sp, _, _ = ref.rts_smoother(np.array(xs), np.array(ps))
    sm = ours.smooth(t, z, X0, P0, t0=0.0)
    # UKF: its sigma-point moments equal the KF's to round-off on a linear model
    # (~1e-12 relative), well inside 1e-9.
    for k in range(len(t)):
        close(sm.x[k], sx[k], f"smoothed x at step {k}")
        close(sm.P[k], sp[k], f"smoothed P at step {k}")
    # Smoothing never increases the variance (the filtered P minus the smoothed is PSD).
    filt = ours.run(t, z, X0, P0, t0=0.0)
    for k in range(len(t)):
        assert np.linalg.eigvalsh(filt.P[k] - sm.P[k]).min() > -1e-9
