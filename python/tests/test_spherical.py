"""Spherical radar (range, azimuth, elevation) on the 3-D models: the EKF and UKF updates
against an independent numpy computation of the same equations, the Cartesian 3-D KF
against the linear KF in numpy, and the batch run against the step-by-step calls.

The equations (argus_sensors::Spherical3D): Δ = p − s, r = |Δ|, ψ = atan2(Δy, Δx),
θ = atan2(Δz, √(Δx² + Δy²)); R = diag(σr², σψ², σθ²); angle residuals wrapped to
(−π, π]. EKF: S = H P Hᵀ + R, K = P Hᵀ S⁻¹, x = x⁻ + K ν, Joseph
P = (I − K H) P (I − K H)ᵀ + K R Kᵀ. UKF (α = 1, β = 2, κ = 0: λ = 0, W₀ᵐ = 0,
W₀ᶜ = 2, Wᵢ = 1/(2n)): sigma points x ± √n L (L the Cholesky factor), measurement
offsets taken relative to h(x) with wrapped angles, P = P⁻ − K S Kᵀ.
"""

from __future__ import annotations

import numpy as np
import pytest

import argus_tracking as at

SENSOR = np.array([100.0, -200.0, 30.0])
SIGMAS = np.array([25.0, 0.003, 0.004])
IDX = [0, 2, 4]
X = np.array([9_000.0, -120.0, 6_000.0, 80.0, 3_000.0, 5.0])
P = np.diag([900.0, 100.0, 1600.0, 64.0, 400.0, 9.0])
P[0, 2] = P[2, 0] = 300.0
Z = np.array([11_250.0, 0.5775, 0.2633])


def wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


def h(x):
    d = x[IDX] - SENSOR
    return np.array([np.linalg.norm(d), np.arctan2(d[1], d[0]), np.arctan2(d[2], np.hypot(d[0], d[1]))])


def residual(a, b):
    r = a - b
    r[1:] = wrap(r[1:])
    return r


def jacobian(x):
    dx, dy, dz = x[IDX] - SENSOR
    rho2 = dx * dx + dy * dy
    rho, r2 = np.sqrt(rho2), rho2 + dz * dz
    r = np.sqrt(r2)
    H = np.zeros((3, 6))
    H[0, IDX] = [dx / r, dy / r, dz / r]
    H[1, IDX] = [-dy / rho2, dx / rho2, 0.0]
    H[2, IDX] = [-dx * dz / (r2 * rho), -dy * dz / (r2 * rho), rho / r2]
    return H


def close(a, b, rel, what):
    a, b = np.asarray(a), np.asarray(b)
    scale = np.maximum(np.abs(b), 1e-6 * np.abs(b).max())
    assert np.all(np.abs(a - b) <= rel * scale + 1e-12), (what, a, b)


def spherical(cls, **kw):
    return cls("cv3", q=1.0, sensor="spherical", sigma_range=SIGMAS[0], sigma_azimuth=SIGMAS[1],
               sigma_elevation=SIGMAS[2], sensor_position=SENSOR, **kw)


def test_ekf_spherical_update_equals_numpy():
    f = spherical(at.ExtendedKalmanFilter)
    x, p = f.update(X, P, Z)
    H, R = jacobian(X), np.diag(SIGMAS**2)
    S = H @ P @ H.T + R
    K = P @ H.T @ np.linalg.inv(S)
    nu = residual(Z, h(X))
    IKH = np.eye(6) - K @ H
    # 1e-9 relative: the same formulas in float64 (Cholesky solve against inv on a 3 × 3
    # S of condition ~1e11 from metres against radians: round-off ~1e-11 relative).
    close(x, X + K @ nu, 1e-9, "x")
    close(p, IKH @ P @ IKH.T + K @ R @ K.T, 1e-9, "P")
    f.set_state(X, P)
    f.update(Z)
    close(f.nis, nu @ np.linalg.solve(S, nu), 1e-9, "nis")


def test_ukf_spherical_update_equals_numpy():
    f = spherical(at.UnscentedKalmanFilter)
    x, p = f.update(X, P, Z)
    n = 6
    L = np.linalg.cholesky(P) * np.sqrt(n)
    pts = [X + L[:, i] for i in range(n)] + [X - L[:, i] for i in range(n)]
    z0 = h(X)
    d = np.array([residual(h(s), z0) for s in pts])
    w = 1.0 / (2 * n)
    m = w * d.sum(axis=0)
    zhat = z0 + m
    # Σ Wᵢ (dᵢ − m)(dᵢ − m)ᵀ + W₀ᶜ m mᵀ = Σ Wᵢ dᵢ dᵢᵀ − m mᵀ + 2 m mᵀ (β − α² = 1).
    S = w * d.T @ d + (2.0 - 1.0) * np.outer(m, m) + np.diag(SIGMAS**2)
    Pxz = w * sum(np.outer(s - X, di) for s, di in zip(pts, d))
    K = Pxz @ np.linalg.inv(S)
    nu = residual(Z, zhat)
    # 1e-8 relative: the sums are accumulated in another order than Argus's on the fly.
    close(x, X + K @ nu, 1e-8, "x")
    close(p, P - K @ S @ K.T, 1e-8, "P")


def test_cartesian_3d_kf_equals_numpy():
    r = np.array([[400.0, 30.0, 0.0], [30.0, 500.0, 10.0], [0.0, 10.0, 900.0]])
    f = at.KalmanFilter("cv3", q=0.5, R=r)
    z = X[IDX] + np.array([20.0, -15.0, 40.0])
    x, p = f.update(X, P, z)
    H = np.zeros((3, 6))
    H[[0, 1, 2], IDX] = 1.0
    S = H @ P @ H.T + r
    K = P @ H.T @ np.linalg.inv(S)
    IKH = np.eye(6) - K @ H
    close(x, X + K @ (z - H @ X), 1e-10, "x")
    close(p, IKH @ P @ IKH.T + K @ r @ K.T, 1e-10, "P")


@pytest.mark.parametrize("cls", [at.ExtendedKalmanFilter, at.UnscentedKalmanFilter])
def test_spherical_run_equals_the_step_by_step_calls(cls):
    f = spherical(cls)
    rng = np.random.default_rng(11)
    t = np.arange(1, 41) * 2.0
    pos = X[IDX] + np.outer(t, X[[1, 3, 5]])
    zs = np.array([h(np.array([p[0], 0, p[1], 0, p[2], 0])) for p in pos]) + rng.normal(scale=SIGMAS, size=(40, 3))
    run = f.run(t, zs, X, P, t0=0.0)
    f.set_state(X, P)
    prev = 0.0
    for k in range(len(t)):
        f.predict(t[k] - prev)
        f.update(zs[k])
        prev = t[k]
        assert np.array_equal(f.x, run.x[k]) and np.array_equal(f.P, run.P[k]), k
        assert f.nis == run.nis[k]
    # The filter follows the target: the last position error within 4 σ of its own P
    # (a tolerance, not a consistency test: one seeded run).
    err = run.x[-1][IDX] - pos[-1]
    assert err @ np.linalg.solve(run.P[-1][np.ix_(IDX, IDX)], err) < 16 * 3


def test_sensor_and_model_mismatches_are_rejected():
    with pytest.raises(at.InvalidInputError, match="spherical radar needs a 3-D model"):
        at.ExtendedKalmanFilter("cv", sensor="spherical", sigma_range=1.0, sigma_azimuth=0.1,
                                sigma_elevation=0.1)
    with pytest.raises(at.InvalidInputError, match="polar radar needs a planar model"):
        at.UnscentedKalmanFilter("ca3", sensor="polar", sigma_range=1.0, sigma_azimuth=0.1)
    with pytest.raises(at.InvalidInputError, match="sigma_elevation"):
        at.ExtendedKalmanFilter("cv3", sensor="spherical", sigma_range=1.0, sigma_azimuth=0.1)
    with pytest.raises(at.InvalidInputError, match="sensor_position"):
        at.ExtendedKalmanFilter("cv3", sensor="spherical", sigma_range=1.0, sigma_azimuth=0.1,
                                sigma_elevation=0.1, sensor_position=(0.0, 0.0))
    with pytest.raises(at.InvalidInputError, match=r"expected shape \(3, 3\)"):
        at.KalmanFilter("cv3", R=np.eye(2))
