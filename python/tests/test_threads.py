"""Long calls release the GIL.

Two checks: (1) while a batch run is inside Rust, the main thread keeps running Python
code (were the GIL held for the call, the main thread could not run at all in the middle
of it); (2) two batch runs in two threads take about the time of one, not of two (the
issue's bound, 1.5×), checked when the machine is not busy with other work (1-minute
load average below 1.5 on CI's 2 cores), since two threads cannot run at once on cores
that other processes hold.
"""

from __future__ import annotations

import os
import threading
import time

import numpy as np

import argus_tracking as at


def _setup(n: int):
    rng = np.random.default_rng(0)
    t = np.arange(1, n + 1, dtype=float)
    r = 20_000 + 50 * t % 10_000
    plots = np.stack([r + rng.normal(scale=20, size=n), 0.3 + rng.normal(scale=0.001, size=n)], axis=1)
    f = at.UnscentedKalmanFilter("cv", q=1.0, sigma_range=20.0, sigma_azimuth=0.001)
    x0 = np.array([20_000 * np.cos(0.3), 0.0, 20_000 * np.sin(0.3), 0.0])
    p0 = np.diag([1e4, 1e3, 1e4, 1e3])
    return lambda: f.run(t, plots, x0, p0, t0=0.0)


def test_python_runs_while_a_batch_run_is_inside_rust():
    call = _setup(150_000)
    window = {}

    def worker():
        window["start"] = time.perf_counter()
        call()
        window["end"] = time.perf_counter()

    ticks = []
    th = threading.Thread(target=worker)
    th.start()
    while th.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    th.join()
    start, end = window["start"], window["end"]
    assert end - start > 0.05, "the call is too short to tell"
    # The middle half of the call: no Python thread could run there with the GIL held.
    lo, hi = start + 0.25 * (end - start), end - 0.25 * (end - start)
    inside = [x for x in ticks if lo < x < hi]
    assert len(inside) >= 3, f"{len(inside)} main-thread steps during the call's middle half"


def test_two_batch_runs_in_two_threads_run_concurrently():
    call = _setup(150_000)
    best = np.inf
    for _ in range(3):  # best of three
        start = time.perf_counter()
        call()
        one = time.perf_counter() - start
        threads = [threading.Thread(target=call) for _ in range(2)]
        start = time.perf_counter()
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        best = min(best, (time.perf_counter() - start) / one)
        if best < 1.5:
            break
    if os.getloadavg()[0] < 1.5:
        # Serialised by the GIL the ratio would be ≥ 2; concurrent on 2 cores ≈ 1 (plus
        # the array conversions, which hold the GIL).
        assert best < 1.5, f"two threads took {best:.2f}× one call"
    else:
        assert best < 2.6, f"two threads took {best:.2f}× one call on a busy machine"
