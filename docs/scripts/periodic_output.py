#!/usr/bin/env python3
"""Periodic output of a tracks file, emulated (docs/real-traffic.md, "How the tracks are written").

    python3 docs/scripts/periodic_output.py T.csv T.periodic.csv cv|imm

Adds to every confirmed track a row at each 5-s grid time after each of its rows (until its
next row, at most 20 s: the 4 misses before deletion) with the state predicted from that
row to the grid time — the output of a tracker that writes every confirmed track's
predicted state at each grid time (the sector ends that fall on the grid; the scorer reads
no others). `cv`: constant velocity (what `argus score` itself does with the last row, so
the scores must not change); `imm`: the aircraft IMM's combined prediction approximated
from the row's combined state, its CT probability `mu_3` and turn rate `turn_rate_deg`
((1 - mu_3) CV + mu_3 CT; the per-mode states are not in the file). Standard library only.
"""
import math
import sys

src, dst, mode = sys.argv[1], sys.argv[2], sys.argv[3]
lines = open(src).read().splitlines(); h = lines[0].split(","); I = {n: i for i, n in enumerate(h)}
tracks = {}
for l in lines[1:]:
    c = l.split(","); tracks.setdefault(c[I["track"]], []).append(c)
out = [lines[0]]
def pred(c, dt):
    x, vx, y, vy = (float(c[I[n]]) for n in ("x", "vx", "y", "vy"))
    cvx, cvy = x + vx*dt, y + vy*dt
    if mode == "cv": return cvx, vx, cvy, vy
    mu = float(c[I["mu_3"]]); w = math.radians(float(c[I["turn_rate_deg"]]))
    if abs(w) < 1e-9: ctx, cty, cvx2, cvy2 = cvx, cvy, vx, vy
    else:
        s, co = math.sin(w*dt), math.cos(w*dt)
        ctx = x + (s*vx - (1-co)*vy)/w; cty = y + ((1-co)*vx + s*vy)/w
        cvx2 = co*vx - s*vy; cvy2 = s*vx + co*vy
    return (1-mu)*cvx + mu*ctx, (1-mu)*vx + mu*cvx2, (1-mu)*cvy + mu*cty, (1-mu)*vy + mu*cvy2
rows = []
for name, rs in tracks.items():
    k = 0
    for i, c in enumerate(rs):
        t = float(c[I["t"]]); rows.append((t, 0, c))
        tn = float(rs[i+1][I["t"]]) if i + 1 < len(rs) else t + 20.0  # last row: coast ≤ 20 s (4 misses)
        if c[I["status"]] != "confirmed": continue
        g = math.floor(t/5.0)*5.0 + 5.0
        while g < tn and g - t <= 20.0:
            d = list(c); d[I["t"]] = repr(g)
            x, vx, y, vy = pred(c, g - t)
            d[I["x"]], d[I["vx"]], d[I["y"]], d[I["vy"]] = repr(x), repr(vx), repr(y), repr(vy)
            rows.append((g, 1, d)); g += 5.0
rows.sort(key=lambda r: (r[2][I["track"]] , r[0], r[1]))
out += [",".join(r[2]) for r in rows]
open(dst, "w").write("\n".join(out) + "\n")
