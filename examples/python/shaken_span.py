"""Writes examples/steel-1x7-span-50m-shaken.json: the 50 m 1+6 steel span of
examples/steel-1x7-span-50m.json on a vibration bench, its start clamped and shaken vertically.

* The end (pinned) is pulled 0.05 m along the strand over 0.25 s: strain 1e-3, T = EA_eq 1e-3
  = 26.4 kN, held.
* From t = 0.25 s the clamp moves y(t) = A w(t) sin(2 pi f (t - 0.25)), A = 6 mm, with the
  amplitude raised over 0.75 s by w = (1 - cos(pi tau / 0.75)) / 2 (a smooth start excites
  the span's free modes far less than a jump in velocity), then held at A to t = 2.25 s.
* f = 9.675 Hz = 6.25 c / (2 L), c = sqrt(T / m) = 154.8 m/s: a quarter of the way from the
  6th string mode to the 7th, where the clamp is neither at a node nor at an antinode of the
  standing wave (its slope there is A k cot(kL) = A k).
* No gravity: a bench sets the clamp at the span's static exit angle, so that the dead load
  bends the strand at the clamp by its catenary curvature w / T = 4e-4 1/m only, 4 % of the
  first slip curvature (1.2e-2 1/m at this tension).
* One row of the motion table per time step (1 ms): the support's velocity changes at the
  steps only.

    python examples/python/shaken_span.py [--elements N] [--step DT] [--out FILE]

The options write the same scene on another mesh or time step (the motion table then has a row
every DT), for the refinement study of the manual's page "Probes, envelopes and loops".
"""

import argparse
import json
import math
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

STEP = 1e-3
START = 0.25
RAMP = 0.75
END = 2.25
AMPLITUDE = 0.006
FREQUENCY = 9.675


def clamp_motion(step):
    rows = [[0.0, 0.0, 0.0, 0.0], [START, 0.0, 0.0, 0.0]]
    for i in range(1, round((END - START) / step) + 1):
        tau = i * step
        w = 0.5 * (1.0 - math.cos(math.pi * tau / RAMP)) if tau < RAMP else 1.0
        y = AMPLITUDE * w * math.sin(2.0 * math.pi * FREQUENCY * tau)
        rows.append([round(START + tau, 6), 0.0, float(f"{y:.6e}"), 0.0])
    return rows


def scene(elements=1600, step=STEP):
    steel = {"youngs_modulus": 1.95e11, "poisson_ratio": 0.3, "density": 7850.0}
    return {
        "name": "steel-1x7-span-50m-shaken",
        "strand": {
            "length": 50.0,
            "core": {"diameter": 0.0052, **steel},
            "layers": [{"wires": 6, "diameter": 0.005, "pitch": 0.22, **steel}],
            "friction": 0.4,
        },
        "law": "hysteretic",
        "supports": [
            {"at": "start", "kind": "clamped", "motion": clamp_motion(step)},
            {"at": "end", "kind": "pinned", "motion": [[START, 0.05, 0.0, 0.0]]},
        ],
        "analysis": {
            "kind": "dynamic",
            "duration": END,
            "integrator": "generalized-alpha",
            "time_step": step,
            "spectral_radius": 0.0,
            "output_interval": step,
        },
        "models": {"equivalent": {"elements": elements}},
        "output": {"probes": [0.02, 0.1, 30.0]},
    }


def main():
    args = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    args.add_argument("--elements", type=int, default=1600)
    args.add_argument("--step", type=float, default=STEP)
    args.add_argument("--out", default=ROOT / "examples" / "steel-1x7-span-50m-shaken.json")
    a = args.parse_args()
    text = json.dumps(scene(a.elements, a.step), indent=1)
    # One motion row a line.
    path = Path(a.out)
    path.write_text(compact_rows(text) + "\n")
    print(path)


def compact_rows(text):
    out = []
    row = None
    for line in text.splitlines():
        s = line.strip()
        if row is not None:
            row.append(s)
            if s.startswith("]"):
                out.append((indent + "".join(row).replace(",", ", ")).rstrip())
                row = None
            continue
        if s == "[":
            indent = line[: len(line) - len(line.lstrip())]
            row = [s]
            continue
        out.append(line)
    return "\n".join(out)


if __name__ == "__main__":
    main()
