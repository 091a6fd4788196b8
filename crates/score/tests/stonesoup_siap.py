#!/usr/bin/env python3
"""Stone Soup's own SIAP (and GOSPA) on a tracks CSV and a truth CSV, for comparison with
argus-score (docs/scoring.md, "Check against Stone Soup").

    python3 -m venv /tmp/score-venv && /tmp/score-venv/bin/pip install stonesoup
    /tmp/score-venv/bin/python crates/score/tests/stonesoup_siap.py \
        crates/score/tests/data/surv-kf-gnn.tracks.csv crates/score/tests/data/surv.truth.csv

Both files are put on argus-score's grid by an independent implementation of its rules
(docs/scoring.md): grid from the earliest to the latest truth sample at STEP; truth
interpolated linearly between samples at most MAX_TRUTH_GAP apart; a track present when its
last row at or before the grid time is `confirmed` and at most MAX_TRACK_AGE old, its state
predicted with constant velocity. The resampled paths and tracks are then handed to Stone
Soup, which associates them (two of its associators) and computes SIAP and GOSPA itself.
"""

import bisect
import csv
import datetime
import sys

import numpy as np
import stonesoup
from ordered_set import OrderedSet
from scipy.optimize import linear_sum_assignment
from stonesoup.dataassociator.tracktotrack import TrackToTruth
from stonesoup.measures import Euclidean
from stonesoup.metricgenerator.manager import MultiManager
from stonesoup.metricgenerator.ospametric import GOSPAMetric
from stonesoup.metricgenerator.tracktotruthmetrics import SIAPMetrics
from stonesoup.types.association import AssociationSet, SingleTimeAssociation
from stonesoup.types.groundtruth import GroundTruthPath, GroundTruthState
from stonesoup.types.state import State
from stonesoup.types.track import Track

STEP = 5.0
CUTOFF = 1000.0
MAX_TRACK_AGE = 15.0
MAX_TRUTH_GAP = 10.0
GOSPA_P = 2.0
EPOCH = datetime.datetime(2000, 1, 1)


def read_groups(path, key, fields):
    groups = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            groups.setdefault(row[key], []).append(
                [float(row["t"])] + [row.get(c, "confirmed") if c == "status" else float(row[c])
                                     for c in fields])
    return groups


def stamp(t):
    return EPOCH + datetime.timedelta(seconds=t)


def main(tracks_path, truth_path):
    truth = read_groups(truth_path, "target", ["x", "vx", "y", "vy"])
    tracks = read_groups(tracks_path, "track", ["status", "x", "vx", "y", "vy"])
    lo = min(s[0][0] for s in truth.values())
    hi = max(s[-1][0] for s in truth.values())
    grid = [lo + k * STEP for k in range(int((hi - lo) / STEP + 1e-9) + 1)]

    paths = []
    for name, samples in truth.items():
        times = [s[0] for s in samples]
        path = GroundTruthPath(id=name)
        for t in grid:
            n = bisect.bisect_right(times, t)
            if n == 0:
                continue
            a = samples[n - 1]
            if a[0] == t:
                v = a[1:]
            elif n < len(samples) and samples[n][0] - a[0] <= MAX_TRUTH_GAP:
                b = samples[n]
                w = (t - a[0]) / (b[0] - a[0])
                v = [u + w * (z - u) for u, z in zip(a[1:], b[1:])]
            else:
                continue
            path.append(GroundTruthState([[v[0]], [v[1]], [v[2]], [v[3]]], timestamp=stamp(t)))
        if len(path):
            paths.append(path)

    track_list = []
    for name, rows in tracks.items():
        times = [r[0] for r in rows]
        track = Track(id=name)
        for t in grid:
            n = bisect.bisect_right(times, t)
            if n == 0:
                continue
            r = rows[n - 1]
            age = t - r[0]
            if r[1] != "confirmed" or age > MAX_TRACK_AGE:
                continue
            x, vx, y, vy = r[2:]
            track.append(State([[x + vx * age], [vx], [y + vy * age], [vy]], timestamp=stamp(t)))
        if len(track):
            track_list.append(track)

    pos = Euclidean(mapping=(0, 2))
    vel = Euclidean(mapping=(1, 3))
    print(f"Stone Soup {stonesoup.__version__}; grid {len(grid)} times, {len(paths)} truths, "
          f"{len(track_list)} tracks on the grid")
    associators = {
        # ClearMotAssociator (one-to-one, like argus-score) fails the same way on any match
        # that lasts one grid time, which every track file with a break has, so it is not
        # run. consec_pairs_confirm=1 makes one-instant associations, which Stone Soup 1.9.1
        # refuses (TimeRange "Must have left < right"); 2 is the smallest that runs.
        "TrackToTruth(threshold 1000, confirm 2, end 1)":
            TrackToTruth(association_threshold=CUTOFF, consec_pairs_confirm=2,
                         consec_misses_end=1),
    }
    for label, assoc in associators.items():
        siap = SIAPMetrics(position_measure=pos, velocity_measure=vel,
                           truths_key="truths", tracks_key="tracks")
        manager = MultiManager([siap], associator=assoc)
        manager.add_data({"tracks": track_list, "truths": paths})
        m = manager.generate_metrics()["siap_generator"]
        print(label)
        for title in ["SIAP Completeness", "SIAP Ambiguity", "SIAP Spuriousness",
                      "SIAP Position Accuracy", "SIAP Velocity Accuracy",
                      "SIAP Rate of Track Number Change", "SIAP Longest Track Segment"]:
            print(f"  {title}: {m[title].value:.6f}")

    # Stone Soup's SIAP formulas on a one-to-one association like argus-score's: at each
    # grid time, SciPy's linear_sum_assignment (the algorithm argus-sim's lsap ports) on
    # min(d, c), pairs at d < c kept, given to Stone Soup as SingleTimeAssociations. R and
    # LS need time-range associations, so only the per-time measures are summed, with
    # SIAPMetrics' own per-time methods.
    associations = set()
    by_time = {}
    for obj in paths:
        for st in obj:
            by_time.setdefault(st.timestamp, ([], []))[0].append((obj, st))
    for obj in track_list:
        for st in obj:
            by_time.setdefault(st.timestamp, ([], []))[1].append((obj, st))
    for ts, (truths_t, tracks_t) in by_time.items():
        if not truths_t or not tracks_t:
            continue
        cost = np.array([[min(pos(tr_st, tu_st), CUTOFF) for tr, tr_st in tracks_t]
                         for tu, tu_st in truths_t])
        for i, j in zip(*linear_sum_assignment(cost)):
            if cost[i, j] < CUTOFF:
                associations.add(SingleTimeAssociation(
                    OrderedSet((tracks_t[j][0], truths_t[i][0])), timestamp=ts))
    siap = SIAPMetrics(position_measure=pos, velocity_measure=vel,
                       truths_key="truths", tracks_key="tracks")
    manager = MultiManager([siap])
    manager.add_data({"tracks": track_list, "truths": paths})
    manager.association_set = AssociationSet(associations)
    sums = dict(J=0, JT=0, NA=0, N=0, PA=0.0, VA=0.0)
    for ts in manager.list_timestamps(siap):
        sums["J"] += siap.num_truths_at_time(paths, ts)
        sums["JT"] += siap.num_associated_truths_at_time(manager, paths, ts)
        sums["NA"] += siap.num_associated_tracks_at_time(manager, track_list, ts)
        sums["N"] += siap.num_tracks_at_time(track_list, ts)
        sums["PA"] += siap.accuracy_at_time(manager, ts, pos)
        sums["VA"] += siap.accuracy_at_time(manager, ts, vel)
    print("one-to-one optimal assignment per grid time (SciPy), SIAPMetrics' per-time sums")
    print(f"  sums: J {sums['J']}, JT {sums['JT']}, NA {sums['NA']}, N {sums['N']}")
    print(f"  SIAP Completeness: {sums['JT'] / sums['J']:.6f}")
    print(f"  SIAP Spuriousness: {(sums['N'] - sums['NA']) / sums['N']:.6f}")
    print(f"  SIAP Position Accuracy: {sums['PA'] / sums['NA']:.6f}")
    print(f"  SIAP Velocity Accuracy: {sums['VA'] / sums['NA']:.6f}")

    gospa = GOSPAMetric(c=CUTOFF, p=GOSPA_P, measure=pos, truths_key="truths",
                        tracks_key="tracks")
    manager = MultiManager([gospa])
    manager.add_data({"tracks": track_list, "truths": paths})
    g = manager.generate_metrics()["gospa_generator"]["GOSPA Metrics"].value
    n = len(g)
    for part in ["distance", "localisation", "missed", "false"]:
        mean = sum(v.value[part] for v in g) / n
        print(f"GOSPA mean {part} over {n} times: {mean:.6f}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
