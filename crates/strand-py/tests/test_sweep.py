"""`strand.sweep`: points as scenes edited by field paths, on local processes and on a real
Dask cluster; failures are rows; an interrupted sweep resumes without re-running."""

import json
import signal
import subprocess
import sys
import textwrap
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pandas as pd
import pytest

import strand

AXES = {"strand.friction": [0.1, 0.3], "strand.layers[0].lay_angle_deg": [12.0, 20.0]}


@pytest.fixture
def pendulum(dynamic_scene):
    return strand.Scene(dynamic_scene).with_values({"analysis.duration": 0.1})


def single_runs(scene, points):
    """The reference: each point run on its own with strand.run."""
    out = []
    for p in points:
        r = strand.run(scene.with_values(p), threads=1)
        out.append(r.summary["equivalent"])
    return out


def test_product_sweep_on_local_processes(pendulum):
    df = strand.sweep(pendulum, AXES, workers=2)
    assert len(df) == 4 and list(df["status"]) == ["ok"] * 4
    assert list(df["strand.friction"]) == [0.1, 0.1, 0.3, 0.3]
    assert list(df["strand.layers[0].lay_angle_deg"]) == [12.0, 20.0, 12.0, 20.0]
    ref = single_runs(pendulum, [{"strand.friction": f, "strand.layers[0].lay_angle_deg": a} for f, a in [(0.1, 12.0), (0.1, 20.0), (0.3, 12.0), (0.3, 20.0)]])
    for (_, row), s in zip(df.iterrows(), ref):
        assert [row.tip_x, row.tip_y, row.tip_z] == s["tip"]
        assert row.energy_balance_error == s["energy_balance_error"]
        assert row.dissipated == s["dissipated"]
        assert row.steps == s["steps"]
    # The lay angle changes the section law: different points, different tips.
    assert len(set(df["tip_y"])) == 4


def test_a_bad_path_is_named_before_anything_runs(pendulum, tmp_path):
    with pytest.raises(strand.SceneError, match=r"sweep point 0 .*strand\.layers\[1\]\.wires: no such field"):
        strand.sweep(pendulum, {"strand.layers[1].wires": [6]}, out_dir=tmp_path / "s")
    with pytest.raises(strand.SceneError, match=r"sweep point 1 .*strand\.friction: "):
        strand.sweep(pendulum, points=[{"strand.friction": 0.2}, {"strand.friction": -1.0}], out_dir=tmp_path / "s")
    assert not (tmp_path / "s" / "results.jsonl").exists()


def test_a_failed_point_is_a_row_with_its_reason(pendulum, tmp_path):
    # A step limit below the run's 200 steps: the runner refuses that point (step-limit).
    # A point whose files cannot be written (a file where its folder should be) raises in
    # its worker: a row with the exception.
    out = tmp_path / "s"
    out.mkdir()
    pts = [{"analysis.max_steps": 10}, {"analysis.max_steps": 100000}]
    df = strand.sweep(pendulum, points=pts, out_dir=out, executor=ThreadPoolExecutor(2))
    assert list(df["status"]) == ["failed", "ok"]
    assert df["reason"][0] == "step-limit" and "max_steps" in df["error"][0]
    (out / "points").write_text("not a folder")
    df = strand.sweep(pendulum, points=[{"strand.friction": 0.2}], out_dir=out, keep_files=True, executor=ThreadPoolExecutor(1))
    assert df["status"][0] == "failed" and df["reason"][0] == "error"
    assert "RuntimeError" in df["error"][0]


def test_keep_files_and_resume_in_process(pendulum, tmp_path):
    out = tmp_path / "s"
    seen = []
    df = strand.sweep(pendulum, AXES, out_dir=out, keep_files=True, executor=ThreadPoolExecutor(2), on_point=seen.append)
    assert len(seen) == 4
    for key in df["key"]:
        assert (out / "points" / key / "equivalent" / "tip.csv").exists()
    again = []
    df2 = strand.sweep(pendulum, AXES, out_dir=out, keep_files=True, executor=ThreadPoolExecutor(2), on_point=again.append)
    assert again == []  # nothing ran again
    assert df2.equals(df)
    table = pd.read_csv(out / "results.csv")
    assert list(table["tip_y"]) == list(df["tip_y"]) and list(table["key"]) == list(df["key"])
    # One more lay angle: only its two points run.
    more = dict(AXES, **{"strand.layers[0].lay_angle_deg": [12.0, 20.0, 16.0]})
    df3 = strand.sweep(pendulum, more, out_dir=out, executor=ThreadPoolExecutor(2), on_point=again.append)
    assert len(again) == 2 and len(df3) == 6
    assert (out / "results.jsonl").read_text().count("\n") == 6


def test_resume_after_an_interrupted_sweep(dynamic_scene, tmp_path):
    """A sweep in another process is killed (SIGKILL: no cleanup at all) once some points are
    written; the re-run keeps them as they are and runs only the others."""
    base = strand.Scene(dynamic_scene).with_values({"analysis.duration": 1.0})
    out = tmp_path / "s"
    axes = {"strand.friction": [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4]}
    script = tmp_path / "sweep.py"
    script.write_text(textwrap.dedent(f"""
        import json, strand
        from concurrent.futures import ThreadPoolExecutor
        base = strand.Scene(json.loads({base.to_json(indent=None)!r}))
        strand.sweep(base, {axes!r}, out_dir={str(out)!r}, executor=ThreadPoolExecutor(1))
    """))
    p = subprocess.Popen([sys.executable, str(script)])
    results = out / "results.jsonl"
    deadline = time.time() + 120
    while time.time() < deadline and not (results.exists() and results.read_text().count("\n") >= 2):
        time.sleep(0.01)
    p.send_signal(signal.SIGKILL)
    p.wait()
    before = [json.loads(line) for line in results.read_text().splitlines() if line.strip()]
    assert 2 <= len(before) < 8, "the sweep was not interrupted mid-way; make its points longer"
    ran = []
    df = strand.sweep(base, axes, out_dir=out, executor=ThreadPoolExecutor(1), on_point=ran.append)
    assert len(ran) == 8 - len(before)
    assert len(df) == 8 and (df["status"] == "ok").all()
    for rec in before:
        row = df[df["key"] == rec["key"]].iloc[0]
        # Its wall time is the one recorded before the kill: the point did not run again.
        assert row.point_wall_time_s == rec["record"]["wall_time_s"]
        assert row["strand.friction"] == rec["params"]["strand.friction"]


def test_sweep_on_a_dask_local_cluster(pendulum, tmp_path):
    import distributed  # a test dependency: missing, the test fails rather than skips
    ref = strand.sweep(pendulum, AXES, executor=ThreadPoolExecutor(1))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            df = strand.sweep(pendulum, AXES, executor=client, out_dir=tmp_path / "d")
            workers = client.run(lambda: __import__("os").getpid())
    assert len(workers) == 2
    assert (df["status"] == "ok").all()
    cols = ["tip_x", "tip_y", "tip_z", "energy_balance_error", "dissipated", "steps"]
    assert np.array_equal(df[cols].to_numpy(), ref[cols].to_numpy())
    assert (tmp_path / "d" / "results.jsonl").read_text().count("\n") == 4


def test_sweep_on_ray_where_installed(pendulum):
    """Ray is optional (not a test dependency of .ci/run): skipped where it is not installed."""
    ray = pytest.importorskip("ray")
    ref = strand.sweep(pendulum, AXES, executor=ThreadPoolExecutor(1))
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        df = strand.sweep(pendulum, AXES, executor="ray")
    finally:
        ray.shutdown()
    cols = ["tip_x", "tip_y", "tip_z", "energy_balance_error", "dissipated", "steps"]
    assert (df["status"] == "ok").all()
    assert np.array_equal(df[cols].to_numpy(), ref[cols].to_numpy())
