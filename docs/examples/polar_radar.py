"""Tracking a polar radar's plots from Python with argus_tracking.

    pip install ./python            # from the repository root (matplotlib optional)
    python docs/examples/polar_radar.py [--plot tracks.png]

Simulates a target flying a straight leg then a 3°/s turn past a radar at the origin
(range σ 50 m, azimuth σ 0.1°), tracks it with an EKF and with a CV / CT IMM on the raw
(range, azimuth) plots, prints the RMS position errors and, with --plot, draws the truth,
the plots and both tracks (matplotlib needed only for that). Then runs the multi-target
tracker of docs/examples/tracker.toml over docs/examples/two-targets.csv.
"""

from __future__ import annotations

import argparse
import pathlib

import numpy as np

import argus_tracking as at

HERE = pathlib.Path(__file__).resolve().parent


def simulate(rng: np.random.Generator, dt: float = 2.0, n: int = 150):
    """Truth [x, vx, y, vy] and polar plots every dt seconds."""
    x = np.array([30_000.0, -120.0, 5_000.0, 60.0])
    omega = np.deg2rad(3.0)
    truth = []
    for k in range(n):
        if k >= n // 2:  # coordinated turn: rotate the velocity
            c, s = np.cos(omega * dt), np.sin(omega * dt)
            vx, vy = x[1], x[3]
            x[0] += (s * vx - (1 - c) * vy) / omega
            x[2] += ((1 - c) * vx + s * vy) / omega
            x[1], x[3] = c * vx - s * vy, s * vx + c * vy
        else:
            x[0] += x[1] * dt
            x[2] += x[3] * dt
        truth.append(x.copy())
    truth = np.array(truth)
    sr, sa = 50.0, np.deg2rad(0.1)
    plots = np.stack(
        [np.hypot(truth[:, 0], truth[:, 2]) + rng.normal(scale=sr, size=n),
         np.arctan2(truth[:, 2], truth[:, 0]) + rng.normal(scale=sa, size=n)], axis=1)
    times = dt * np.arange(1, n + 1)
    return times, truth, plots, sr, sa


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--plot", help="write a figure (needs matplotlib)")
    args = ap.parse_args()
    times, truth, plots, sr, sa = simulate(np.random.default_rng(1))
    r0, a0 = plots[0]
    x0 = np.array([r0 * np.cos(a0), 0.0, r0 * np.sin(a0), 0.0])
    p0 = np.diag([200.0**2, 150.0**2, 200.0**2, 150.0**2])

    ekf = at.ExtendedKalmanFilter("cv", q=1.0, sigma_range=sr, sigma_azimuth=sa)
    imm = at.Imm([("cv", 0.5), ("ct", 0.5, np.deg2rad(3.0)), ("ct", 0.5, -np.deg2rad(3.0))],
                 [[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]],
                 sigma_range=sr, sigma_azimuth=sa)
    e = ekf.run(times[1:], plots[1:], x0, p0, t0=times[0])
    i = imm.run(times[1:], plots[1:], x0, p0, t0=times[0])
    for name, x in (("EKF", e.x), ("IMM", i.x)):
        err = np.hypot(x[20:, 0] - truth[21:, 0], x[20:, 2] - truth[21:, 2])
        print(f"{name}: RMS position error {np.sqrt(np.mean(err**2)):.1f} m")
    print(f"IMM turn-mode probability at the end: {i.mode_probabilities[-1, 1:].sum():.2f}")

    # The multi-target tracker, configured exactly like `argus track`.
    import csv

    with open(HERE / "two-targets.csv") as f:
        rows = list(csv.DictReader(f))
    dtype = [("t", "f8"), ("sensor", "i8"), ("range", "f8"), ("azimuth", "f8")]
    table = np.array([(float(r["t"]), int(r["sensor"]), float(r["range"]), float(r["azimuth"]))
                      for r in rows], dtype=dtype)
    tracks = at.track(table, HERE / "tracker.toml")
    confirmed = np.unique(tracks["track"][tracks["status"] == "confirmed"])
    print(f"tracker: {len(tracks)} rows, confirmed tracks {confirmed.tolist()}")

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        xy = np.stack([plots[:, 0] * np.cos(plots[:, 1]), plots[:, 0] * np.sin(plots[:, 1])], 1)
        fig, ax = plt.subplots(figsize=(7, 5))
        ax.plot(xy[:, 0] / 1e3, xy[:, 1] / 1e3, ".", ms=3, color="0.6", label="plots")
        ax.plot(truth[:, 0] / 1e3, truth[:, 2] / 1e3, "k-", label="truth")
        ax.plot(e.x[:, 0] / 1e3, e.x[:, 2] / 1e3, label="EKF")
        ax.plot(i.x[:, 0] / 1e3, i.x[:, 2] / 1e3, label="IMM")
        ax.set_xlabel("x (km)")
        ax.set_ylabel("y (km)")
        ax.set_aspect("equal")
        ax.legend()
        fig.savefig(args.plot, dpi=120, bbox_inches="tight")
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
