"""Independent count of argus-adsb's cleaning rules (docs/adsb.md) on the extract.

pandas for rules 1-7, plain loops for 8-9; the Rust test asserts these numbers.
    python cleaning_counts.py quickstart-busiest-hour.csv.gz
"""

import sys

import numpy as np
import pandas as pd

A, F = 6378137.0, 1 / 298.257223563
E2 = F * (2 - F)
MAX_V, MAX_VZ, GAP, MIN_N = 350.0, 100.0, 60.0, 10


def surface(lat, lon):
    la, lo = np.radians(lat), np.radians(lon)
    n = A / np.sqrt(1 - E2 * np.sin(la) ** 2)
    return np.stack([n * np.cos(la) * np.cos(lo), n * np.cos(la) * np.sin(lo), n * (1 - E2) * np.sin(la)], 1)


def main(path):
    df = pd.read_csv(path, dtype={"icao24": str, "callsign": str})
    c = {"records": len(df), "aircraft": df.icao24.nunique()}
    df = df.sort_values(["icao24", "timestamp"], kind="stable")
    m = df.latitude.isna() | df.longitude.isna()
    c["missing_position"] = int(m.sum()); df = df[~m]
    m = df.onground == True  # noqa: E712
    c["on_ground"] = int(m.sum()); df = df[~m]
    m = df.altitude.isna()
    c["missing_altitude"] = int(m.sum()); df = df[~m]
    m = (df.altitude < -2000) | (df.altitude > 60000)
    c["altitude_out_of_bounds"] = int(m.sum()); df = df[~m]
    # Rules 5 and 6 compare with the previous *kept* record: loop per aircraft.
    keep, dup, stale = [], 0, 0
    for _, g in df.groupby("icao24", sort=True):
        prev = None
        for i, t, la, lo in zip(g.index, g.timestamp, g.latitude, g.longitude):
            if prev is not None and t == prev[0]:
                dup += 1; continue
            if prev is not None and la == prev[1] and lo == prev[2]:
                stale += 1; continue
            keep.append(i); prev = (t, la, lo)
    c["duplicate_time"], c["stale_position"] = dup, stale
    df = df.loc[keep]
    df["seg"] = (df.groupby("icao24").timestamp.diff() > GAP).groupby(df.icao24).cumsum()
    c["gap_splits"] = int((df.groupby("icao24").timestamp.diff() > GAP).sum())
    spk_h = spk_v = short = kept = flights = 0
    ac = set()
    for (icao, _), g in df.groupby(["icao24", "seg"], sort=True):
        t = g.timestamp.to_numpy(float); z = g.altitude.to_numpy(float) * 0.3048
        s = surface(g.latitude.to_numpy(), g.longitude.to_numpy())

        def jump(a, b):
            dt = abs(t[b] - t[a])
            if np.linalg.norm(s[a] - s[b]) > MAX_V * dt:
                return "h"
            if abs(z[b] - z[a]) > MAX_VZ * dt:
                return "v"
            return None

        n, out = len(t), []
        for k in range(n):
            p = out[-1] if out else None
            nx = k + 1 if k + 1 < n else None
            if p is not None and nx is not None:
                j = jump(p, k) if jump(k, nx) else None
            elif p is not None:
                j = jump(p, k) if len(out) >= 2 and jump(out[-2], p) is None else None
            elif nx is not None:
                j = jump(k, nx) if nx + 1 < n and jump(nx, nx + 1) is None else None
            else:
                j = None
            if j == "h":
                spk_h += 1
            elif j == "v":
                spk_v += 1
            else:
                out.append(k)
        if len(out) < MIN_N:
            short += len(out)
        else:
            kept += len(out); flights += 1; ac.add(icao)
    c.update(position_spike=spk_h, altitude_spike=spk_v, short_segment=short,
             kept=kept, flights=flights, aircraft_kept=len(ac))
    for k, v in c.items():
        print(f"{k}: {v}")


if __name__ == "__main__":
    main(sys.argv[1])
