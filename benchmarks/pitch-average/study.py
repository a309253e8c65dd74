#!/usr/bin/env python3
"""The pitch-averaged law (`section.pitch_samples`) against the resolved law.

Writes each variant of the three scenes of this folder (elements, phase samples, tension) as a
scene into OUT, runs it with the `strand` binary (a run whose summary.json exists is kept) and
prints the differences against the resolved law's finest run, next to the resolved law's own
refinement error. Usage:

    cargo build --release -p strand-cli
    python3 benchmarks/pitch-average/study.py span5|point|span400 [OUT]
"""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
STRAND = os.path.join(ROOT, "target", "release", "strand")


def variant(base, name, elements, samples, **edit):
    s = json.loads(json.dumps(base))
    s["name"] = name
    s["models"]["equivalent"]["elements"] = elements
    s.pop("section", None)
    if samples:
        s["section"] = {"pitch_samples": samples}
    for k, v in edit.items():
        s[k] = v
    return s


def run(out, scene):
    d = os.path.join(out, scene["name"])
    if not os.path.exists(os.path.join(d, "equivalent", "summary.json")):
        os.makedirs(out, exist_ok=True)
        path = os.path.join(out, scene["name"] + ".json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=1)
        subprocess.run([STRAND, "run", path, "--out", d], check=True,
                       stdout=subprocess.DEVNULL)
    return os.path.join(d, "equivalent")


def table(path, cols):
    rows = list(csv.DictReader(open(path)))
    return [np.array([float(r[c]) for r in rows]) for c in cols]


def summary(d):
    return json.load(open(os.path.join(d, "summary.json")))


def span5(out):
    """5 m Cardinal span, pretensioned, released under gravity (hysteretic, 1 s)."""
    base = json.load(open(os.path.join(HERE, "cardinal-5m-span.json")))
    runs = {}
    for v, s, ns in [("res", 0, [20, 40, 80]), ("pa4", 4, [10, 20, 40]), ("pa12", 12, [20, 40])]:
        for n in ns:
            runs[(v, n)] = run(out, variant(base, f"span5-{v}-{n}", n, s))
    ref = runs[("res", 80)]
    tr, yr = table(os.path.join(ref, "probe_2.5.csv"), ["t", "y"])
    print(f"midspan amplitude {np.abs(yr).max():.4e} m (resolved, 80 elements)")
    for k, d in sorted(runs.items()):
        t, y = table(os.path.join(d, "probe_2.5.csv"), ["t", "y"])
        te, di = table(os.path.join(d, "energy.csv"), ["t", "dissipated"])
        mean = y[len(y) // 2:].mean()
        up = [t[i] for i in range(1, len(y)) if y[i - 1] < mean <= y[i]]
        cyc = np.diff(np.interp(up, te, di))
        same = runs.get(("res", k[1]))
        dsame = ""
        if same and k[0] != "res":
            _, ys = table(os.path.join(same, "probe_2.5.csv"), ["t", "y"])
            dsame = f" | vs resolved at {k[1]}: {np.abs(y - ys).max():.2e} m"
        js = summary(d)
        print(f"{k[0]:5s} {k[1]:3d} el: midspan max|y - y_res80| {np.abs(y - yr).max():.2e} m, "
              f"dissipated {di[-1]:.5f} J, per cycle {np.array2string(cyc[:3], precision=4)} J, "
              f"Newton {js['newton_iterations']}, CPU {js['cpu_time_s']:.2f} s{dsame}")


def point(out):
    """3 m span, point force at midspan, continuous law, statics, at three tensions."""
    base = json.load(open(os.path.join(HERE, "cardinal-3m-point-load.json")))
    ei, ea, length = 1835.7, 4.221401e7, base["strand"]["length"]
    grid = np.linspace(0.0, length, 1201)
    for tension in [2000.0, 20000.0, 100000.0]:
        eps = tension / ea
        # Five times the outer layer's first-slip curvature (about 8.5 eps) under the force.
        force = 2 * 5 * 8.5 * eps * math.sqrt(ei * tension)
        edit = dict(
            supports=[{"at": "start", "kind": "pinned"},
                      {"at": "end", "kind": "pinned", "motion": [[1.0, eps * length, 0.0, 0.0]]}],
            loads={"points": [{"s": length / 2, "force": [0.0, -force, 0.0]}]},
        )
        runs = {}
        for v, s, ns in [("res", 0, [96, 192]), ("pa4", 4, [96, 192]), ("pa12", 12, [96])]:
            for n in ns:
                name = f"point-{int(tension)}-{v}-{n}"
                runs[(v, n)] = run(out, variant(base, name, n, s, **edit))

        def line(d):
            s, y, m = table(os.path.join(d, "centerline.csv"), ["s", "y", "moment"])
            return np.interp(grid, s, y), np.interp(grid, s, m)

        yr, mr = line(runs[("res", 192)])
        y96, m96 = line(runs[("res", 96)])
        lam = math.sqrt(ei / tension)
        print(f"T = {tension:.0f} N: lambda = sqrt(EI/T) = {lam:.3f} m, P/lambda = "
              f"{0.2104 / lam:.2f}; midspan deflection {abs(np.interp(length / 2, grid, yr)):.4e} m, "
              f"largest moment {np.abs(mr).max():.4e} N m")
        print(f"   resolved 96 against 192 elements: deflection {np.abs(y96 - yr).max():.2e} m, "
              f"moment {np.abs(m96 - mr).max() / np.abs(mr).max():.2e} of the largest")
        for k in [("pa4", 96), ("pa4", 192), ("pa12", 96)]:
            y, m = line(runs[k])
            ys, ms = line(runs[("res", k[1])])
            js = summary(runs[k])
            print(f"   {k[0]:5s} {k[1]:3d} against resolved at {k[1]}: deflection "
                  f"{np.abs(y - ys).max():.2e} m, moment {np.abs(m - ms).max() / np.abs(mr).max():.2e} "
                  f"of the largest; CPU {js['cpu_time_s']:.3f} s (resolved "
                  f"{summary(runs[('res', k[1])])['cpu_time_s']:.3f} s)")


def span400(out):
    """400 m Cardinal span, pretensioned, gravity: statics and a 2 s dynamic window."""
    base = json.load(open(os.path.join(ROOT, "examples", "cardinal-span-400m.json")))
    static = {"kind": "static", "load_steps": 20}
    for kind in ["static", "dynamic"]:
        runs = {}
        plan = ([("res", 0, [10, 20, 40, 80]), ("pa4", 4, [5, 10, 20, 40, 80])] if kind == "static"
                else [("res", 0, [40, 80]), ("pa4", 4, [20, 40, 80, 160])])
        for v, s, ns in plan:
            for n in ns:
                edit = {"analysis": static} if kind == "static" else {}
                runs[(v, n)] = run(out, variant(base, f"span400-{kind}-{v}-{n}", n, s, **edit))
        ref = runs[("res", 40)]
        for k, d in sorted(runs.items()):
            s, y, kap = table(os.path.join(d, "centerline.csv"), ["s", "y", "curvature"])
            sr, yr = table(os.path.join(ref, "centerline.csv"), ["s", "y"])
            js = summary(d)
            extra = ""
            if kind == "dynamic":
                t, yp = table(os.path.join(d, "probe_200.csv"), ["t", "y"])
                tr, ypr = table(os.path.join(ref, "probe_200.csv"), ["t", "y"])
                extra = (f", midspan history max|dy| {np.abs(yp - ypr).max():.2e} m, dissipated "
                         f"{js['dissipated']:.4f} J, balance {js['energy_balance_error']:.3f} J")
            print(f"{kind} {k[0]:4s} {k[1]:3d} el ({js['integration_points']} points each): "
                  f"midspan y {np.interp(200.0, s, y):.5f} m, max|y - y_res40| "
                  f"{np.abs(np.interp(sr, s, y) - yr).max():.2e} m, curvature at midspan "
                  f"{np.interp(200.0, s, kap):.3e} 1/m{extra}; Newton {js['newton_iterations']}, "
                  f"CPU {js['cpu_time_s']:.3f} s")


if __name__ == "__main__":
    study = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "target", "pitch-average")
    {"span5": span5, "point": point, "span400": span400}[study](out)
