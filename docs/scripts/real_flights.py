#!/usr/bin/env python3
"""Issue 18's single-real-flight comparison and the aircraft IMM's tuning search
(docs/real-traffic.md, "Single real flights"; docs/aircraft-imm.md, "Tuning on real flights").

    python3 docs/scripts/real_flights.py [--argus target/release/argus] [--work DIR]
        [--config A.toml ...] [--random N] [--refine N]

For each seed 1-3: `argus simulate real-traffic --seed S`; the plots of the twelve longest
flights of seed 1 (the same twelve flights at every seed, each flight's own plots, no
clutter) go one flight at a time through `argus track` with seed 000's IMM (CV 0.1 m/s^2 +
CT +-3 deg/s, converted plots with the true R) and with each aircraft-IMM configuration
(default docs/examples/aircraft.toml). The RMS position error at the rows' times against
the ADS-B truth (linear between its 1-s samples), after the first five rows, is pooled over
flights; the ratio is the aircraft IMM's over seed 000's on the same plots. Flights are split
into two halves by length rank (A: 1st, 3rd, ...; B: 2nd, 4th, ...): --random draws N
tunings (fixed RNG seed), ranks them by A and reports B as the held-out half; --refine
perturbs the best one coordinate at a time for N steps, by the objective over all twelve
(an in-sample ceiling, not a tuning to adopt). Standard library only.
"""
import argparse, bisect, csv, json, math, os, random, subprocess, tempfile
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FLIGHTS = 12
SKIP = 5
SEEDS = (1, 2, 3)
SENSOR = """[[sensor]]
id = 1
position = [0.0, 0.0]
sigma_range = 70.0
sigma_azimuth_deg = 0.08
"""
SEED000 = SENSOR + """
[estimator]
kind = "imm"
models = [
  { kind = "cv", sigma_a = 0.1 },
  { kind = "ct", sigma_a = 0.5, rate_deg = 3.0 },
  { kind = "ct", sigma_a = 0.5, rate_deg = -3.0 },
]
markov = [[0.95, 0.025, 0.025], [0.05, 0.95, 0.0], [0.05, 0.0, 0.95]]
"""
# AircraftTuning::default(), the Markov matrix as stay probabilities and splits of the rest
DEFAULT = dict(cvq=0.3, cvm=2.0, cta=0.5, om=0.1, pqq=0.95, fq=0.6, pmm=0.8, fm=0.5, pcc=0.9,
               fc=0.5, mu0=0.6, so=2.0, mixing="unbiased", msig=0.5)


def prepare(argus, work):
    flights = None
    for s in SEEDS:
        d = os.path.join(work, f"s{s}")
        os.makedirs(d, exist_ok=True)
        p = os.path.join(work, f"P{s}.csv")
        subprocess.run([argus, "simulate", "real-traffic", "--seed", str(s), "--out", p],
                       check=True, capture_output=True)
        plots = {}
        for r in csv.DictReader(open(p)):
            if r["origin"].startswith("target:"):
                plots.setdefault(int(r["origin"][7:]), []).append(r)
        names, truth = [], {}
        for r in csv.DictReader(open(p[:-4] + ".truth.csv")):
            if not names or names[-1] != r["target"]:
                names.append(r["target"])
                truth[len(names) - 1] = []
            truth[len(names) - 1].append((float(r["t"]), float(r["x"]), float(r["y"])))
        if flights is None:
            flights = sorted(plots, key=lambda k: (-len(plots[k]), k))[:FLIGHTS]
        for k in flights:
            with open(os.path.join(d, f"f{k}.csv"), "w") as g:
                g.write("t,sensor,range,azimuth\n")
                for r in plots[k]:
                    g.write(f"{r['t']},{r['sensor']},{r['range']},{r['azimuth']}\n")
            json.dump(truth[k], open(os.path.join(d, f"f{k}.truth.json"), "w"))
    return flights


class Flights:
    def __init__(self, argus, work, flights):
        self.argus, self.work, self.flights = argus, work, flights
        self.a, self.b = flights[0::2], flights[1::2]
        self.truth = {}
        for s in SEEDS:
            for k in flights:
                rows = json.load(open(os.path.join(work, f"s{s}", f"f{k}.truth.json")))
                self.truth[(s, k)] = ([r[0] for r in rows], rows)
        self.ref = None

    def at(self, s, k, t):
        ts, rows = self.truth[(s, k)]
        i = bisect.bisect_right(ts, t)
        if i == 0 or i >= len(ts):
            return rows[min(i, len(ts) - 1)][1:]
        a, b = rows[i - 1], rows[i]
        w = (t - a[0]) / (b[0] - a[0])
        return (a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2]))

    def one(self, cfg, s, k):
        fd, out = tempfile.mkstemp(suffix=".csv", dir=self.work)
        os.close(fd)
        plots = os.path.join(self.work, f"s{s}", f"f{k}.csv")
        subprocess.run([self.argus, "track", "--config", cfg, "--plots", plots, "--out", out],
                       check=True, capture_output=True)
        lines = open(out).read().splitlines()
        os.unlink(out)
        h = lines[0].split(",")
        it, ix, iy = h.index("t"), h.index("x"), h.index("y")
        se = 0.0
        for line in lines[1 + SKIP:]:
            c = line.split(",")
            x, y = self.at(s, k, float(c[it]))
            se += (float(c[ix]) - x) ** 2 + (float(c[iy]) - y) ** 2
        return se, len(lines) - 1 - SKIP

    def run(self, text):
        fd, cfg = tempfile.mkstemp(suffix=".toml", dir=self.work)
        os.write(fd, text.encode())
        os.close(fd)
        jobs = [(s, k) for s in SEEDS for k in self.flights]
        with ThreadPoolExecutor(2) as ex:
            res = dict(zip(jobs, ex.map(lambda j: self.one(cfg, *j), jobs)))
        os.unlink(cfg)
        return res

    @staticmethod
    def pooled(res, seeds, flights):
        se = sum(res[(s, k)][0] for s in seeds for k in flights)
        return math.sqrt(se / sum(res[(s, k)][1] for s in seeds for k in flights))

    def score(self, text):
        if self.ref is None:
            self.ref = self.run(SEED000)
        r = self.run(text)
        ratio = lambda seeds, fl: self.pooled(r, seeds, fl) / self.pooled(self.ref, seeds, fl)
        o = {f"s{s}": ratio([s], self.flights) for s in SEEDS}
        o.update(A=ratio(SEEDS, self.a), B=ratio(SEEDS, self.b), all=ratio(SEEDS, self.flights))
        o.update({f"rmse_s{s}": self.pooled(r, [s], self.flights) for s in SEEDS})
        o.update({f"ref_s{s}": self.pooled(self.ref, [s], self.flights) for s in SEEDS})
        return o


def toml(p):
    m = [[p["pqq"], (1 - p["pqq"]) * p["fq"], (1 - p["pqq"]) * (1 - p["fq"])],
         [(1 - p["pmm"]) * p["fm"], p["pmm"], (1 - p["pmm"]) * (1 - p["fm"])],
         [(1 - p["pcc"]) * p["fc"], (1 - p["pcc"]) * (1 - p["fc"]), p["pcc"]]]
    mu = [p["mu0"], (1 - p["mu0"]) / 2, (1 - p["mu0"]) / 2]
    s = SENSOR + '\n[estimator]\nkind = "aircraft-imm"\n'
    s += f"cv_sigma_a = [{p['cvq']!r}, {p['cvm']!r}]\nct_sigma_a = {p['cta']!r}\n"
    s += f"ct_sigma_omega_deg = {p['om']!r}\n"
    s += "markov = " + json.dumps([[round(v, 12) for v in row] for row in m]) + "\n"
    s += "initial = " + json.dumps([round(v, 12) for v in mu]) + "\n"
    s += f"start_sigma_omega_deg = {p['so']!r}\nmixing = \"{p['mixing']}\"\n"
    if p["mixing"] == "fixed":
        s += f"mixing_sigma_omega_deg = {p['msig']!r}\n"
    return s


def fmt(o):
    return " ".join(f"{k} {v:.4f}" for k, v in o.items() if not k.startswith(("rmse", "ref")))


def draw(rng):
    lu = lambda a, b: math.exp(rng.uniform(math.log(a), math.log(b)))
    return dict(pqq=1 - lu(0.005, 0.1), fq=rng.uniform(0.1, 0.9), pmm=rng.uniform(0.5, 0.95),
                fm=rng.uniform(0.1, 0.9), pcc=rng.uniform(0.7, 0.98), fc=rng.uniform(0.1, 0.9),
                cvq=lu(0.05, 0.6), cvm=lu(0.7, 5), cta=lu(0.2, 3), om=lu(0.03, 0.6),
                so=lu(0.5, 5), mixing=rng.choice(["unbiased", "unbiased", "fixed"]),
                msig=lu(0.1, 3), mu0=rng.uniform(0.3, 0.9))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--argus", default=os.path.join(ROOT, "target/release/argus"))
    ap.add_argument("--work", default=None)
    ap.add_argument("--config", nargs="*", default=[os.path.join(ROOT, "docs/examples/aircraft.toml")])
    ap.add_argument("--random", type=int, default=0)
    ap.add_argument("--refine", type=int, default=0)
    a = ap.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="real_flights.")
    fl = Flights(a.argus, work, prepare(a.argus, work))
    print("flights (seed-1 plot counts order):", fl.flights, "A:", fl.a, "B:", fl.b)
    for c in a.config:
        o = fl.score(open(c).read())
        print(c, fmt(o))
        print("  RMSE per seed (aircraft / seed 000):",
              ", ".join(f"{o[f'rmse_s{s}']:.1f} / {o[f'ref_s{s}']:.1f} m" for s in SEEDS))
    if a.random or a.refine:
        rng = random.Random(18)
        best = (fl.score(toml(DEFAULT)), DEFAULT)
        print("default", fmt(best[0]))
        for i in range(a.random):
            p = draw(rng)
            o = fl.score(toml(p))
            print("random", i, fmt(o), json.dumps(p), flush=True)
            if o["A"] < best[0]["A"]:
                best = (o, p)
        print("best by A:", fmt(best[0]), json.dumps(best[1]))
        o, q = best
        for i in range(a.refine):
            k = rng.choice(["pqq", "fq", "pmm", "fm", "pcc", "fc", "cvq", "cvm", "cta", "om", "so", "msig"])
            r = dict(q)
            if k == "pqq":
                r[k] = 1 - (1 - q[k]) * math.exp(rng.gauss(0, 0.4))
            elif k in ("fq", "fm", "fc", "pmm", "pcc"):
                r[k] = min(0.99, max(0.01, q[k] + rng.gauss(0, 0.08)))
            else:
                r[k] = q[k] * math.exp(rng.gauss(0, 0.3))
            s = fl.score(toml(r))
            if s["all"] < o["all"]:
                o, q = s, r
                print("refine", i, k, fmt(o), json.dumps(q), flush=True)
        if a.refine:
            print("refined over all twelve (in-sample):", fmt(o), json.dumps(q))


if __name__ == "__main__":
    main()
