#!/usr/bin/env python3
"""Stone Soup's standard multi-target tracker on a rotating radar's plot file, timed, for
docs/real-traffic.md ("Speed against Stone Soup").

    python3 -m venv /tmp/ss-venv && /tmp/ss-venv/bin/pip install stonesoup==1.9.1
    argus simulate real-traffic --seed 1 --out rt.csv
    /tmp/ss-venv/bin/python docs/peers/stonesoup_real_traffic.py rt.csv rt.stonesoup.tracks.csv

Stone Soup's trackers take one set of detections per time stamp (a scan), so the plots are
grouped by revolution (`floor((t - north_time) / period)`, each group stamped with its
revolution's start time): the re-stamping workaround of issue 18. Each plot is converted to
Cartesian with the unbiased conversion's covariance evaluated at the plot, as Argus's KF
tracks do; the tracker is GNN (`GNNWith2DAssignment` over a Mahalanobis
`DistanceHypothesiser`), a constant-velocity Kalman predictor and updater per track
(σa = 5 m/s², as real-traffic's KF), a `MultiMeasurementInitiator` (3 hits) and an
`UpdateTimeStepsDeleter` (3 misses), all Stone Soup's own. The script prints the wall
time of the tracking loop alone (reading and conversion excluded) and writes the tracks
in Argus's tracks columns so `argus score` can score them.
"""

import csv
import datetime
import math
import sys
import time

import numpy as np
from stonesoup.dataassociator.neighbour import GNNWith2DAssignment
from stonesoup.deleter.time import UpdateTimeStepsDeleter
from stonesoup.hypothesiser.distance import DistanceHypothesiser
from stonesoup.initiator.simple import MultiMeasurementInitiator
from stonesoup.measures import Mahalanobis
from stonesoup.models.measurement.linear import LinearGaussian
from stonesoup.models.transition.linear import (
    CombinedLinearGaussianTransitionModel,
    ConstantVelocity,
)
from stonesoup.predictor.kalman import KalmanPredictor
from stonesoup.tracker.simple import MultiTargetTracker
from stonesoup.types.array import CovarianceMatrix
from stonesoup.types.detection import Detection
from stonesoup.types.state import GaussianState
from stonesoup.updater.kalman import KalmanUpdater

PERIOD = 5.0
NORTH_TIME = 0.0
SIGMA_R = 70.0
SIGMA_AZ = math.radians(0.08)
SIGMA_A = 5.0
EPOCH = datetime.datetime(2021, 10, 7, 13, 33)


def unbiased(r, az):
    """Mo Longbin et al. (1998) unbiased conversion and its covariance at the plot
    (the formulas of argus_sensors::convert_polar's documentation, lambda = exp(-s^2/2),
    lambda' = lambda^4)."""
    lam = math.exp(-SIGMA_AZ**2 / 2.0)
    lam4 = lam**4
    c, n = math.cos(az), math.sin(az)
    x, y = r * c / lam, r * n / lam
    k = (lam**-2 - 2.0) * r * r
    h = 0.5 * (r * r + SIGMA_R**2)
    rxx = k * c * c + h * (1 + lam4 * math.cos(2 * az))
    ryy = k * n * n + h * (1 - lam4 * math.cos(2 * az))
    rxy = k * c * n + h * lam4 * math.sin(2 * az)
    return x, y, np.array([[rxx, rxy], [rxy, ryy]])


def main(plots_path, out_path):
    scans = {}
    with open(plots_path, newline="") as f:
        for row in csv.DictReader(f):
            t = float(row["t"])
            k = math.floor((t - NORTH_TIME) / PERIOD)
            scans.setdefault(k, []).append((float(row["range"]), float(row["azimuth"])))
    transition = CombinedLinearGaussianTransitionModel(
        [ConstantVelocity(SIGMA_A**2), ConstantVelocity(SIGMA_A**2)]
    )
    predictor = KalmanPredictor(transition)
    base_model = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.eye(2))
    updater = KalmanUpdater(base_model)
    hypothesiser = DistanceHypothesiser(
        predictor, updater, measure=Mahalanobis(), missed_distance=3
    )
    associator = GNNWith2DAssignment(hypothesiser)
    deleter = UpdateTimeStepsDeleter(time_steps_since_update=3)
    prior = GaussianState(
        np.zeros((4, 1)), CovarianceMatrix(np.diag([0.0, 300.0**2, 0.0, 300.0**2]))
    )
    initiator = MultiMeasurementInitiator(
        prior_state=prior,
        measurement_model=base_model,
        deleter=UpdateTimeStepsDeleter(time_steps_since_update=2),
        data_associator=associator,
        updater=updater,
        min_points=3,
    )
    feed = []
    for k in sorted(scans):
        stamp = EPOCH + datetime.timedelta(seconds=NORTH_TIME + k * PERIOD)
        dets = set()
        for r, az in scans[k]:
            x, y, cov = unbiased(r, az)
            model = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=cov)
            dets.add(Detection(np.array([[x], [y]]), timestamp=stamp, measurement_model=model))
        feed.append((stamp, dets))

    class Reader:
        def __iter__(self):
            return iter(feed)

        @property
        def detections_gen(self):
            return iter(feed)

    tracker = MultiTargetTracker(
        initiator=initiator,
        deleter=deleter,
        detector=Reader(),
        data_associator=associator,
        updater=updater,
    )
    rows = []
    start = time.perf_counter()
    for stamp, tracks in tracker:
        t = (stamp - EPOCH).total_seconds()
        for tr in tracks:
            s = tr.state_vector
            rows.append((t, id(tr), float(s[0]), float(s[1]), float(s[2]), float(s[3])))
    elapsed = time.perf_counter() - start
    with open(out_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "track", "status", "x", "vx", "y", "vy"])
        names = {}
        for t, tid, x, vx, y, vy in rows:
            w.writerow([t, names.setdefault(tid, len(names)), "confirmed", x, vx, y, vy])
    print(f"stonesoup tracking loop: {elapsed:.2f} s over {len(feed)} scans")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
