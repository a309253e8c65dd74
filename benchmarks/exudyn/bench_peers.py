"""Side-by-side benchmark of strand and Exudyn on the section-3 pendulum (`cargo xtask
bench-peers` builds the strand binaries and runs this; see README.md beside it).

For each law (`constant`: the traditional beam's EI and EA; `continuous`: the equivalent beam's
stick/slip law, an Exudyn user function) it

1. runs each program's reference runs: the same mesh at another step (a quarter of it for
   `constant`; twice it for `continuous`, which has no converged run, see STEP_REFERENCE), and
   twice the elements at the benchmark step (strand's step reference with Newton converged to
   1e-12 L);
2. times the benchmark run (the step and mesh of the README's speed table, each program's
   default Newton settings) in interleaved rounds, strand then Exudyn, each run a fresh process;
3. checks that the two programs' tips agree over the swing within the sum of both programs' own
   discretisation errors, each estimated by refining that program alone (step and mesh);
4. writes target/bench-peers/report.{md,json} with the machine, the settings of both sides, the
   median and fastest solve times, and each row's tip error against the converged run of the
   same law and program.

Exit status: 0 when every agreement check passes, 1 when one fails, 2 on a set-up error.
"""

import argparse
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time

import strand_law
from strand_law import setup_error

HERE = os.path.dirname(os.path.abspath(__file__))


def last_json(stdout):
    """The last line of a run's standard output, as JSON (Exudyn prints a banner first)."""
    lines = [x for x in stdout.splitlines() if x.strip()]
    return json.loads(lines[-1])


def run(cmd, what):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        setup_error(f"{what} failed ({' '.join(cmd)}):\n{p.stderr.strip()}")
    out = last_json(p.stdout)
    out["process_wall_s"] = wall
    return out


def distance(a, b):
    """Largest tip distance (m) over the common output times of two runs."""
    worst = 0.0
    for p, q in zip(a["tip"], b["tip"]):
        if abs(p[0] - q[0]) > 1e-9:
            setup_error(f"output times differ: {p[0]} and {q[0]}")
        worst = max(worst, math.hypot(p[1] - q[1], p[2] - q[2]))
    return worst


class Programs:
    def __init__(self, a):
        self.a = a

    def strand(self, law, step, elements, tight):
        cmd = [
            self.a.strand_bin, self.a.scene, "--law", law, "--step", repr(step),
            "--elements", str(elements), "--spectral-radius", repr(self.a.spectral_radius),
        ]
        if tight:
            cmd += ["--increment", "1e-12"]
        return run(cmd, "strand")

    def exudyn(self, law, step, elements, tight):
        # `tight` keeps Exudyn's defaults: its Newton test is on the residual relative to the
        # step's first one, and below the default 1e-8 (1e-10, 1e-12) it stops converging
        # within round-off and halves the step again and again (a quarter-step run of the
        # constant law at 1e-12 took 454,555 steps and ended 2.4e-3 m away).
        del tight
        cmd = [
            self.a.python, os.path.join(HERE, "exudyn_pendulum.py"), self.a.constants_file,
            "--law", law, "--step", repr(step), "--elements", str(elements),
            "--spectral-radius", repr(self.a.spectral_radius), "--scale-ei", repr(self.a.scale_ei),
        ]
        return run(cmd, "exudyn")


def machine():
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {
        "cpu": cpu,
        "logical_cores": os.cpu_count(),
        "os": platform.platform(),
        "python": platform.python_version(),
        "load_average": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
    }


def commit():
    try:
        return subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=HERE
        ).stdout.strip()
    except OSError:
        return ""


# The step of each law's step reference, as a multiple of the benchmark step: `constant`
# converges in the step (second order: a quarter step leaves about 1/16 of the error), so its
# rows' error is against h/4. `continuous` has no converged run: at steps that resolve the
# strand's 2 kHz axial-bending mode (below about 0.5 ms) its strain-dependent moment feeds energy
# in and the trajectory moves away as the step shrinks (README, "Finding"), so its step error is
# estimated from twice the step, |x(h) - x(2h)| (three times the second-order estimate).
STEP_REFERENCE = {"constant": 0.25, "continuous": 2.0}


def study(law, a, progs, log):
    h, n = a.step, a.elements
    ratio = STEP_REFERENCE[law]
    sides = {"strand": progs.strand, "exudyn": progs.exudyn}
    res = {"law": law, "step": h, "elements": n, "step_reference": ratio * h, "sides": {}}
    # Reference runs of each program on its own: another step, and twice the elements.
    refs = {}
    for name, prog in sides.items():
        log(f"{law}: {name} references (step {ratio * h:g} s; {2 * n} elements)")
        refs[name] = {
            "step": prog(law, ratio * h, n, True),
            "mesh": prog(law, h, 2 * n, False),
        }
    # Interleaved timed rounds.
    runs = {name: [] for name in sides}
    for r in range(a.rounds):
        for name, prog in sides.items():
            out = prog(law, h, n, False)
            runs[name].append(out)
            log(f"{law}: round {r + 1}/{a.rounds} {name} solve {out['solve_s']:.4g} s")
    for name in sides:
        rs = runs[name]
        times = sorted(x["solve_s"] for x in rs)
        first = rs[0]
        step_ref, mesh_ref = refs[name]["step"], refs[name]["mesh"]
        res["sides"][name] = {
            "version": first["version"],
            "solve_median_s": statistics.median(times),
            "solve_fastest_s": times[0],
            "solve_s": [x["solve_s"] for x in rs],
            "setup_median_s": statistics.median(x["setup_s"] for x in rs),
            "steps": first["steps"],
            "newton_iterations": first["newton_iterations"],
            "jacobians": first["jacobians"],
            "dofs": first["dofs"],
            "bending_points_per_element": first["bending_points_per_element"],
            "settings": {
                k: first[k]
                for k in first
                if (k.startswith("newton_") and k != "newton_iterations")
                or k in ("spectral_radius", "modified_newton", "step_halving")
            },
            "balance_error": first.get("balance_error"),
            # Same program and mesh, the reference step: the step and Newton error.
            "step_error": distance(first, step_ref),
            "step_reference_steps": step_ref["steps"],
            "step_reference_balance_error": step_ref.get("balance_error"),
            # Same program and step, twice the elements: the mesh error.
            "mesh_error": distance(first, mesh_ref),
            "tip_final": first["tip"][-1],
            # Runs of one program must give one trajectory, whatever the load.
            "rounds_spread": max(distance(first, x) for x in rs),
        }
    s, e = res["sides"]["strand"], res["sides"]["exudyn"]
    d = distance(runs["strand"][0], runs["exudyn"][0])
    tol = s["step_error"] + e["step_error"] + s["mesh_error"] + e["mesh_error"]
    res["agreement"] = {
        "distance": d,
        "tolerance": tol,
        # Both programs at the step reference: with `constant`, what is left once the step
        # error is gone (the formulations' difference on the 30-element mesh).
        "distance_at_step_reference": distance(refs["strand"]["step"], refs["exudyn"]["step"]),
        "pass": d <= tol,
    }
    res["speedup_median"] = e["solve_median_s"] / s["solve_median_s"]
    res["speedup_fastest"] = e["solve_fastest_s"] / s["solve_fastest_s"]
    return res


def fmt_time(t):
    return f"{t * 1e3:.1f} ms" if t < 1 else f"{t:.2f} s"


def markdown(report):
    m = report["machine"]
    h = report["step"]
    lines = [
        "# strand and Exudyn side by side: the section-3 pendulum",
        "",
        f"Machine: {m['cpu']}, {m['logical_cores']} logical cores, {m['os']}; load average "
        f"{m['load_average_start'][0]} at the start, {m['load_average_end'][0]} at the end; "
        f"{m['date']}. strand {report['commit']}, Exudyn {report['exudyn_version']} "
        f"(Python {m['python']}). `{report['command']}`: {report['wall_s'] / 60:.1f} min.",
        "",
        f"Pendulum: `{report['scene']}` (L = 1 m, pinned at x = 0, released horizontal, gravity "
        f"9.8 m/s^2, 1 s), {report['elements']} elements, generalized-alpha at {h * 1e3:g} ms, "
        f"spectral radius {report['spectral_radius']}. Solve: the integration after the model is "
        f"built, including each integrator's own start; median and, in brackets, fastest of "
        f"{report['rounds']} interleaved rounds (strand, Exudyn, strand, ...), each run a fresh "
        "process. Step error: the tip's largest distance over the output times (every 10 ms) to "
        "the same program's run of the same law at the reference step; mesh error: to its run "
        "with twice the elements.",
        "",
        "| law | program | solve | steps | Newton iterations (Jacobians) | step error | mesh error | Exudyn / strand |",
        "|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for r in report["laws"]:
        ref = r["step_reference"]
        for name in ("strand", "exudyn"):
            s = r["sides"][name]
            ratio = (
                f"{r['speedup_median']:.0f} ({r['speedup_fastest']:.0f})" if name == "exudyn" else ""
            )
            note = "" if ref < h else " (vs 2h: no converged run)"
            lines.append(
                f"| {r['law']} | {name} {s['version']} | {fmt_time(s['solve_median_s'])} "
                f"({fmt_time(s['solve_fastest_s'])}) | {s['steps']} | {s['newton_iterations']} "
                f"({s['jacobians']}) | {s['step_error']:.1e} m{note} | {s['mesh_error']:.1e} m | "
                f"{ratio} |"
            )
    lines += ["", "Agreement (largest tip distance between the programs over the output times):", ""]
    for r in report["laws"]:
        g = r["agreement"]
        lines.append(
            f"* {r['law']}: {g['distance']:.2e} m at {h * 1e3:g} ms, within {g['tolerance']:.2e} m "
            f"(the sum of both programs' step and mesh errors): {'pass' if g['pass'] else 'FAIL'}; "
            f"{g['distance_at_step_reference']:.2e} m at the reference step "
            f"({r['step_reference'] * 1e3:g} ms)."
        )
    lines += ["", "Settings of each side:", ""]
    for r in report["laws"]:
        for name in ("strand", "exudyn"):
            lines.append(f"* {r['law']}, {name}: `{json.dumps(r['sides'][name]['settings'])}`")
    lines.append("")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--strand-bin", required=True, help="the peer_pendulum example binary")
    p.add_argument("--strand-cli", required=True, help="the strand command")
    p.add_argument("--scene", default="validation/paper-fig14-pendulum.json")
    p.add_argument("--out", default="target/bench-peers")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--laws", default="constant,continuous")
    p.add_argument("--step", type=float, default=1e-3)
    p.add_argument("--elements", type=int, default=30)
    p.add_argument("--spectral-radius", type=float, default=0.9)
    p.add_argument("--scale-ei", type=float, default=1.0,
                   help="multiply Exudyn's bending stiffness (a wrong model, to see the check fail)")
    p.add_argument("--python", default=sys.executable)
    a = p.parse_args()
    if a.rounds < 1:
        setup_error("--rounds must be at least 1")

    started = time.perf_counter()
    load_start = list(os.getloadavg())
    os.makedirs(a.out, exist_ok=True)

    def log(msg):
        print(f"[{time.perf_counter() - started:6.0f} s] {msg}", flush=True)

    c = strand_law.section_constants(a.strand_cli, a.scene)
    a.constants_file = os.path.join(a.out, "constants.json")
    with open(a.constants_file, "w") as f:
        json.dump(c, f, indent=1)
    law_check = strand_law.check_against_cli(a.strand_cli, a.scene, c)
    log(f"continuous law in Python against `strand section`: {law_check['points']} points, "
        f"largest relative difference {law_check['largest_relative_difference']:.1e}")

    progs = Programs(a)
    laws = [x.strip() for x in a.laws.split(",") if x.strip()]
    results = [study(law, a, progs, log) for law in laws]

    import exudyn  # noqa: F401 (version only; the runs import it in their own processes)

    mach = machine()
    mach["load_average_start"] = [round(x, 1) for x in load_start]
    mach["load_average_end"] = [round(x, 1) for x in os.getloadavg()]
    report = {
        "command": "cargo xtask bench-peers" + (f" --rounds {a.rounds}" if a.rounds != 3 else ""),
        "machine": mach,
        "commit": commit(),
        "exudyn_version": exudyn.config.Version(),
        "scene": a.scene,
        "step": a.step,
        "elements": a.elements,
        "spectral_radius": a.spectral_radius,
        "rounds": a.rounds,
        "scale_ei": a.scale_ei,
        "law_check": law_check,
        "laws": results,
        "wall_s": time.perf_counter() - started,
    }
    with open(os.path.join(a.out, "report.json"), "w") as f:
        json.dump(report, f, indent=1)
    md = markdown(report)
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write(md)
    print(md)
    if not all(r["agreement"]["pass"] for r in results):
        print("bench-peers: the two programs' trajectories do not agree within the tolerance",
              file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
