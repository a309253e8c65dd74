"""The last full cycle of a probe's moment-curvature loop, per run folder: what the loop
chart of `strand run --plot` draws in full colour (the frames between the last two upward
crossings of the middle of the curvature's range over the second half of the run), with its
curvature and moment ranges, its area (trapezoidal M dkappa, J/m) and the largest second
difference of the moment between frames (N m: a period-2 chatter shows as a value far above the
smooth loop's).

    python examples/python/loop_figures.py 0.02 out-800 out-1600 out-3200
"""

import sys
from pathlib import Path

import numpy as np


def last_cycle(v):
    late = v[len(v) // 2 :]
    level = 0.5 * (late.min() + late.max())
    up = [k for k in range(1, len(v)) if v[k - 1] < level <= v[k]]
    if len(up) < 2:
        return None
    return up[-2] - 1, up[-1]


def main():
    s = sys.argv[1]
    print("run, model, t0, t1, curvature min, max (1/m), moment min, max (N m), area (J/m), max |d2M| (N m)")
    for run in sys.argv[2:]:
        for probe in sorted(Path(run).glob(f"*/probe_{s}.csv")):
            p = np.genfromtxt(probe, delimiter=",", names=True)
            c = last_cycle(p["curvature"])
            if c is None:
                print(f"{run}, {probe.parent.name}: no cycle")
                continue
            k = p["curvature"][c[0] : c[1] + 1]
            m = p["moment"][c[0] : c[1] + 1]
            area = np.sum(0.5 * (m[1:] + m[:-1]) * np.diff(k))
            d2 = np.abs(m[2:] - 2 * m[1:-1] + m[:-2]).max()
            t = p["t"]
            print(
                f"{run}, {probe.parent.name}, {t[c[0]]:.4f}, {t[c[1]]:.4f}, {k.min():.4e}, "
                f"{k.max():.4e}, {m.min():.4f}, {m.max():.4f}, {area:.4e}, {d2:.3e}"
            )


if __name__ == "__main__":
    main()
