"""A 1,000-point sweep of the section law from Python against the same loop in Rust.

    cargo build --release -p strand-scene --example section_sweep
    python crates/strand-py/bench/section_speed.py

Times `strand.section(scene, curvature, 1e-3)` over 1,000 curvatures from -20 to 20 1/m at
x = 0 (the whole call: arrays in, the result dict out) and runs the Rust example
`section_sweep`, which times `strand_scene::section_batch::evaluate_planar` over the same
points with the law built once. Both report the median over 2,000 repetitions.
"""

import re
import subprocess
import time
from pathlib import Path

import numpy as np

import strand

ROOT = Path(__file__).resolve().parents[3]
SCENE = ROOT / "examples" / "nylon-1x8-hanging.json"


def python_median(scene, law, repeats=2000):
    k = np.linspace(-20.0, 20.0, 1000)
    strand.section(scene, k, 1e-3, law=law)  # the law is built on the first call
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        strand.section(scene, k, 1e-3, law=law)
        times.append(time.perf_counter() - t)
    return float(np.median(times))


def main():
    scene = strand.Scene.from_file(SCENE)
    exe = ROOT / "target" / "release" / "examples" / "section_sweep"
    rust = subprocess.run([str(exe), str(SCENE)], capture_output=True, text=True, check=True).stdout
    for law in ["continuous", "hysteretic"]:
        py = python_median(scene, law)
        m = re.search(rf"{law}\s+1000 points: median ([0-9.]+) us", rust)
        rs = float(m.group(1)) * 1e-6
        print(f"{law:<11} 1000 points: Python {py * 1e6:6.1f} us, Rust {rs * 1e6:6.1f} us, ratio {py / rs:.2f}")


if __name__ == "__main__":
    main()
