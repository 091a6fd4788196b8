"""Long calls release the GIL: two batch runs in two threads take about the time of one
(CI has 2 cores), not the time of two."""

from __future__ import annotations

import threading
import time

import numpy as np

import argus_tracking as at


def _inputs(n: int):
    rng = np.random.default_rng(0)
    t = np.arange(1, n + 1, dtype=float)
    r = 20_000 + 50 * t % 10_000
    plots = np.stack([r + rng.normal(scale=20, size=n), 0.3 + rng.normal(scale=0.001, size=n)], axis=1)
    return t, plots


def test_two_batch_runs_in_two_threads_run_concurrently():
    f = at.UnscentedKalmanFilter("cv", q=1.0, sigma_range=20.0, sigma_azimuth=0.001)
    t, plots = _inputs(150_000)
    x0 = np.array([20_000 * np.cos(0.3), 0.0, 20_000 * np.sin(0.3), 0.0])
    p0 = np.diag([1e4, 1e3, 1e4, 1e3])

    def call():
        f.run(t, plots, x0, p0, t0=0.0)

    best = np.inf
    for _ in range(3):  # best of three: the machine may be busy with something else
        start = time.perf_counter()
        call()
        one = time.perf_counter() - start
        threads = [threading.Thread(target=call) for _ in range(2)]
        start = time.perf_counter()
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        two = time.perf_counter() - start
        best = min(best, two / one)
        if best < 1.5:
            break
    # Serialised by the GIL the ratio would be ≥ 2; concurrent on 2 cores it is ≈ 1
    # (plus the array conversions, which hold the GIL). 1.5 is the bound.
    assert best < 1.5, f"two threads took {best:.2f}× one call"
