"""The stateful filters (FilterPy's form: the object owns x and P) and the batch run that
reuses the KF's covariance recursion.

- Stateful predict(dt) / update(z) equal FilterPy 2.0.0's KalmanFilter.predict() /
  update(z) step by step to 1e-9 (the issue's tolerance; both compute the same float64
  formulas, see test_filterpy.py), and equal the functional predict(x, P, dt) /
  update(x, P, z) bit for bit (the same Rust stages).
- Bad input raises the typed exception and leaves x, P and nis as they were.
- run(reuse_gain=True) equals run(reuse_gain=False) bit for bit (the memoisation is
  exact), on every model and both covariance forms, with repeated and changing intervals.
"""

from __future__ import annotations

import numpy as np
import pytest
from filterpy.common import Q_discrete_white_noise
from filterpy.kalman import KalmanFilter as FKalmanFilter

import argus_tracking as at

R = np.array([[400.0, 60.0], [60.0, 900.0]])
H = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])
X0 = np.array([10_000.0, 150.0, 5_000.0, 0.0])
P0 = np.diag([900.0, 400.0, 900.0, 400.0])


def cv_f(dt: float) -> np.ndarray:
    f = np.eye(4)
    f[0, 1] = f[2, 3] = dt
    return f


def plots(n: int, seed: int, dt: float = 2.0) -> "tuple[np.ndarray, np.ndarray]":
    rng = np.random.default_rng(seed)
    t = np.arange(1, n + 1) * dt
    truth = np.stack([10_000 + 150 * t, 5_000 + 2_000 * np.sin(t / 60)], axis=1)
    return t, truth + rng.multivariate_normal(np.zeros(2), R, size=n)


def close(a, b, what):
    # 1e-9 relative with a 1e-9 floor: the tolerance (see test_filterpy.py).
    a, b = np.asarray(a), np.asarray(b)
    assert np.all(np.abs(a - b) <= 1e-9 * np.maximum(1.0, np.abs(b))), (what, a, b)


def test_stateful_kf_equals_filterpy_step_by_step():
    dt, q = 2.0, 0.7
    ours = at.KalmanFilter("cv", q=q, R=R, x=X0, P=P0)
    ref = FKalmanFilter(dim_x=4, dim_z=2)
    ref.x, ref.P, ref.F, ref.H, ref.R = X0.copy(), P0.copy(), cv_f(dt), H, R
    ref.Q = Q_discrete_white_noise(dim=2, dt=dt, var=q**2, block_size=2, order_by_dim=True)
    _, z = plots(60, 1, dt)
    for k in range(len(z)):
        ours.predict(dt)
        ref.predict()
        close(ours.x, ref.x, f"predicted x, step {k}")
        close(ours.P, ref.P, f"predicted P, step {k}")
        ours.update(z[k])
        ref.update(z[k])
        close(ours.x, ref.x, f"x, step {k}")
        close(ours.P, ref.P, f"P, step {k}")
        # FilterPy's NIS: yᵀ S⁻¹ y of its own residual and S.
        close(ours.nis, ref.y @ np.linalg.solve(ref.S, ref.y), f"nis, step {k}")


@pytest.mark.parametrize(
    "make",
    [
        lambda: at.KalmanFilter("ca", q=0.3, R=R),
        lambda: at.KalmanFilter("ct", q=0.5, R=R, omega=0.02, joseph=False),
        lambda: at.ExtendedKalmanFilter("cv", q=0.5, sigma_range=20.0, sigma_azimuth=0.002),
        lambda: at.UnscentedKalmanFilter("ct", q=0.5, sigma_range=20.0, sigma_azimuth=0.002, omega=-0.01),
    ],
)
def test_stateful_equals_functional_bit_for_bit(make):
    f = make()
    n = f.dim_x
    x = np.zeros(n)
    x[0], x[n // 2] = 8_000.0, 6_000.0
    p = np.eye(n) * 400.0
    f.set_state(x, p)
    rng = np.random.default_rng(3)
    for k in range(30):
        dt = 1.0 + 0.5 * (k % 3)
        x, p = f.predict(x, p, dt)
        f.predict(dt)
        truth = np.array([8_000.0 + 50 * k, 6_000.0 - 20 * k])
        if isinstance(f, (at.ExtendedKalmanFilter, at.UnscentedKalmanFilter)):  # polar
            z = np.array([np.hypot(*truth), np.arctan2(truth[1], truth[0])]) + rng.normal(scale=[20, 0.002])
        else:
            z = truth + rng.normal(scale=20.0, size=2)
        x, p = f.update(x, p, z)
        f.update(list(z) if k % 2 else tuple(z))  # sequences take the fast path too
        assert np.array_equal(f.x, x) and np.array_equal(f.P, p), k


def test_z_forms_and_strided_arrays_give_the_same_update():
    base = at.KalmanFilter("cv", q=1.0, R=R, x=X0, P=P0)
    zs = np.array([[10_010.0, 0.0, 4_990.0], [0.0, 0.0, 0.0]])
    forms = [np.array([10_010.0, 4_990.0]), [10_010.0, 4_990.0], (10_010, 4_990), zs[0, ::2],
             np.array([[10_010.0], [4_990.0]]).ravel(), np.array([10_010, 4_990], dtype=np.int32)]
    results = []
    for z in forms:
        base.set_state(X0, P0)
        base.update(z)
        results.append((base.x, base.P))
    for x, p in results[1:]:
        assert np.array_equal(x, results[0][0]) and np.array_equal(p, results[0][1])


def test_bad_input_raises_and_leaves_the_state_unchanged():
    f = at.KalmanFilter("cv", q=1.0, R=R, x=X0, P=P0)
    f.predict(1.0)
    f.update([10_150.0, 5_000.0])
    x, p, nis = f.x, f.P, f.nis
    bad = [
        (lambda: f.update([np.nan, 1.0]), "entry [0] is NaN"),
        (lambda: f.update([1.0, 2.0, 3.0]), "expected shape (2,)"),
        (lambda: f.update(np.ones((2, 2))), "expected shape (2,)"),
        (lambda: f.update(["a", "b"]), "argument 'z'"),
        (lambda: f.predict(-1.0), "dt"),
        (lambda: f.predict(0.0), "dt"),
        (lambda: f.predict(float("inf")), "dt"),
        (lambda: f.predict("soon"), "argument 'dt'"),
        (lambda: setattr(f, "P", np.diag([1.0, -1.0, 1.0, 1.0])), "argument 'P'"),
        (lambda: setattr(f, "P", np.ones((3, 3))), "expected shape (4, 4)"),
        (lambda: setattr(f, "x", [1.0, 2.0, np.inf, 4.0]), "entry [2] is inf"),
        (lambda: f.set_state(X0, np.ones((4, 4))), "argument 'P'"),
        (lambda: f.predict(X0, None, 1.0), "predict takes"),
    ]
    for call, text in bad:
        with pytest.raises(at.InvalidInputError) as info:
            call()
        assert text in str(info.value), (text, str(info.value))
        assert isinstance(info.value, ValueError)
        assert np.array_equal(f.x, x) and np.array_equal(f.P, p) and f.nis == nis, text


def test_numerical_failure_leaves_the_state_unchanged():
    # A prediction overflowing to inf (dt = 1e300): NumericalError, state as before.
    f = at.KalmanFilter("cv", q=1.0, R=R, x=X0, P=P0)
    with pytest.raises(at.NumericalError):
        f.predict(1e300)
    assert np.array_equal(f.x, X0) and np.array_equal(f.P, P0)


def test_default_state_is_filterpys():
    f = at.UnscentedKalmanFilter("ca3", q=1.0, sensor="cartesian", R=np.eye(3))
    assert np.array_equal(f.x, np.zeros(9)) and np.array_equal(f.P, np.eye(9)) and f.nis is None


def irregular_times(n: int) -> np.ndarray:
    # Long stretches of one interval (where the recursion converges and is reused),
    # alternating intervals, equal times (an update without prediction) and a gap.
    dts = np.concatenate([np.full(n // 2, 2.0), np.tile([1.0, 3.0], n // 8), [0.0, 0.0, 40.0],
                          np.full(n - n // 2 - 2 * (n // 8) - 3, 2.0)])
    return np.cumsum(dts) + 2.0


@pytest.mark.parametrize("model,joseph", [("cv", True), ("cv", False), ("ca", True), ("ct", True),
                                          ("ct", False), ("cv3", True), ("ca3", False)])
def test_run_reusing_gain_is_bit_identical(model, joseph):
    n = 1200
    dim = 3 if model.endswith("3") else 2
    r = np.eye(dim) * 400.0 + 50.0
    f = at.KalmanFilter(model, q=0.5, R=r, omega=0.01, joseph=joseph)
    t = irregular_times(n)
    rng = np.random.default_rng(5)
    z = np.cumsum(rng.normal(scale=30.0, size=(n, dim)), axis=0) + 1_000.0
    x0 = np.zeros(f.dim_x)
    p0 = np.eye(f.dim_x) * 1e4
    a = f.run(t, z, x0, p0, t0=0.0)
    b = f.run(t, z, x0, p0, t0=0.0, reuse_gain=False)
    assert np.array_equal(a.x, b.x) and np.array_equal(a.P, b.P) and np.array_equal(a.nis, b.nis)
    if (model, joseph) not in {("ca", True), ("ca3", False)}:
        # The recursion did converge to the bit (so the reuse was exercised): over the
        # long constant-interval stretch the posterior covariance repeats exactly with a
        # period of at most 8 steps (the table's size). Whether float64 round-off settles
        # into such a cycle depends on the model and the path: measured here, the two CA
        # cases do not within 600 steps (they still agree bit for bit).
        k = n // 2 - 1
        assert any(np.array_equal(a.P[k], a.P[k - c]) for c in range(1, 9))
    # Jittered intervals (never equal): the run gives up the table and still agrees.
    tj = np.cumsum(2.0 + np.random.default_rng(6).uniform(0.0, 0.01, n))
    a = f.run(tj, z, x0, p0, t0=0.0)
    b = f.run(tj, z, x0, p0, t0=0.0, reuse_gain=False)
    assert np.array_equal(a.x, b.x) and np.array_equal(a.P, b.P) and np.array_equal(a.nis, b.nis)


def test_run_reusing_gain_reports_the_same_errors():
    f = at.KalmanFilter("cv", q=0.5, R=R)
    t, z = plots(500, 2)
    for reuse in (True, False):
        with pytest.raises(at.InvalidInputError, match=r"argument 'plots': entry \[300, 1\] is NaN"):
            bad = z.copy()
            bad[300, 1] = np.nan
            f.run(t, bad, X0, P0, t0=0.0, reuse_gain=reuse)
    # A step failing inside the run (an overflowing interval late in a converged run).
    t2 = t.copy()
    t2[400:] += 1e300
    errors = []
    for reuse in (True, False):
        with pytest.raises(at.NumericalError) as info:
            f.run(t2, z, X0, P0, t0=0.0, reuse_gain=reuse)
        errors.append(str(info.value))
    assert errors[0] == errors[1] and "step 400" in errors[0]
