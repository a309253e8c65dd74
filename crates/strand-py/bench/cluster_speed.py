"""64 equivalent runs on a 2-worker Dask LocalCluster against the ideal: the sum of the
single-run times divided by 2.

    python crates/strand-py/bench/cluster_speed.py

The runs: the steel 1+9 pendulum of examples/steel-1x9-swing.json (1 s, 40 equivalent
elements), 8 frictions x 8 lay angles. First every point alone, one after the other in this
process on one Rust thread (the single-run times, measured around strand.run, and the
solve's own wall time from summary.json, without the Python around it); then the
sweep on LocalCluster(n_workers=2, threads_per_worker=1), timed from the call to the
DataFrame (the cluster is started before the clock).
"""

import os
import time
from pathlib import Path

import numpy as np
from distributed import Client, LocalCluster

import strand

ROOT = Path(__file__).resolve().parents[3]
AXES = {
    "strand.friction": list(np.linspace(0.05, 0.4, 8)),
    "strand.layers[0].lay_angle_deg": list(np.linspace(12.0, 19.0, 8)),
}


def main():
    load0 = os.getloadavg()[0]
    base = strand.Scene.from_file(ROOT / "examples" / "steel-1x9-swing.json")
    single, cpu, solve = [], [], []
    for mu in AXES["strand.friction"]:
        for alpha in AXES["strand.layers[0].lay_angle_deg"]:
            s = base.with_values({"strand.friction": mu, "strand.layers[0].lay_angle_deg": alpha})
            t = time.perf_counter()
            r = strand.run(s, models="equivalent", threads=1)
            single.append(time.perf_counter() - t)
            cpu.append(r.summary["equivalent"]["cpu_time_s"])
            solve.append(r.summary["equivalent"]["wall_time_s"])
    ideal = sum(single) / 2
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            client.run(lambda: __import__("strand"))  # import the package in the workers first
            t = time.perf_counter()
            df = strand.sweep(base, AXES, models="equivalent", executor=client)
            took = time.perf_counter() - t
    assert len(df) == 64 and (df.status == "ok").all(), df[df.status != "ok"]
    print(f"64 runs: single runs {sum(single):.2f} s in all (mean {np.mean(single):.3f} s), "
          f"ideal on 2 workers {ideal:.2f} s, LocalCluster {took:.2f} s, ratio {took / ideal:.2f}")
    print(f"against the solves alone (summary.json wall_time_s, no files read): ideal {sum(solve) / 2:.2f} s, "
          f"ratio {took / (sum(solve) / 2):.2f}")
    # On a machine shared with other work the wall times hold waits for a core: the CPU time
    # of the runs (summary.json's cpu_time_s) tells the cost of the work itself.
    print(f"CPU time of the runs: alone {sum(cpu):.2f} s, on the cluster {df.cpu_time_s.sum():.2f} s; "
          f"load average before/after {load0:.2f}/{os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
