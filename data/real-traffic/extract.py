"""Extract the busiest hour of the `traffic` 2.13 quickstart sample as a compact CSV.

Run in a venv with `pip install traffic==2.13` (pandas comes with it):
    python extract.py > quickstart-busiest-hour.csv   (then gzip -9n)
Only the quickstart sample is read.
"""

import sys
from pathlib import Path

import pandas as pd
import traffic

SAMPLE = (
    Path(traffic.__file__).parent / "data" / "samples" / "collections" / "quickstart.json.gz"
)


def busiest_hour(df: pd.DataFrame) -> pd.Timestamp:
    """Start of the one-hour window [s, s + 1 h) with the most distinct icao24 that
    have a position, over starts on every whole minute; ties go to the earliest."""
    pos = df[df.latitude.notna() & df.longitude.notna()]
    start, last = pos.timestamp.min().floor("min"), pos.timestamp.max().ceil("min")
    best = None
    s = start
    while s + pd.Timedelta(hours=1) <= last:
        w = pos[(pos.timestamp >= s) & (pos.timestamp < s + pd.Timedelta(hours=1))]
        n = w.icao24.nunique()
        if best is None or n > best[0]:
            best = (n, s)
        s += pd.Timedelta(minutes=1)
    print(f"busiest hour starts {best[1]} UTC: {best[0]} aircraft", file=sys.stderr)
    return best[1]


def main() -> None:
    df = pd.read_json(SAMPLE, dtype={"icao24": str})
    s = busiest_hour(df)
    w = df[(df.timestamp >= s) & (df.timestamp < s + pd.Timedelta(hours=1))]
    w = w.sort_values(["timestamp", "icao24"], kind="stable")
    out = pd.DataFrame(
        {
            # The sample's timestamps are epoch milliseconds, UTC, on whole seconds.
            "timestamp": (w.timestamp - pd.Timestamp("1970-01-01")) // pd.Timedelta(seconds=1),
            "icao24": w.icao24,
            "latitude": w.latitude.round(6),
            "longitude": w.longitude.round(6),
            "altitude": w.altitude.astype("Int64"),
            "groundspeed": w.groundspeed.astype("Int64"),
            "track": w.track.round(3),
            "vertical_rate": w.vertical_rate.astype("Int64"),
            "callsign": w.callsign,
            "onground": w.onground.map({True: "true", False: "false"}),
        }
    )
    assert (w.timestamp.dt.microsecond == 0).all()
    for c in ("altitude", "groundspeed", "vertical_rate"):
        v = w[c].dropna()
        assert (v == v.round()).all(), c
    out.to_csv(sys.stdout, index=False)


if __name__ == "__main__":
    main()
