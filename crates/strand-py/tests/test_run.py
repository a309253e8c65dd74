"""`strand.run` gives the numbers `strand run` writes, bit for bit; long runs release the GIL,
report progress and stop on Ctrl-C."""

import csv
import json
import math
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import strand

# Figures of summary.json that are timings of the process, not results.
TIMINGS = {"wall_time_s", "cpu_time_s"}


def read_cli_csv(path):
    """A CSV file read with the standard library (Python's float() is correctly rounded), as
    an independent reader of the command's files."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    cols = {}
    for j, name in enumerate(header):
        vals = [r[j] for r in body]
        try:
            cols[name] = np.array([float(v) if v != "" else math.nan for v in vals])
        except ValueError:
            cols[name] = vals
    return header, cols


def same_bits(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.int64), b.view(np.int64))


def compare_with_cli(scene, scene_file, cli, tmp_path, models=None):
    f = scene_file(scene)
    out = tmp_path / "cli"
    args = ["run", f, "--out", out] + sum((["--model", m] for m in (models or [])), [])
    cli(*args)
    result = strand.run(scene, models=models)
    assert set(result) == {p.name for p in out.iterdir() if p.is_dir()}
    for model, r in result.models.items():
        d = out / model
        with open(d / "summary.json") as fh:
            expected = json.load(fh)
        got = {k: v for k, v in r.summary.items() if k not in TIMINGS}
        assert got == {k: v for k, v in expected.items() if k not in TIMINGS}
        files = sorted(p.stem for p in d.glob("*.csv") if not p.stem.startswith("probe_"))
        assert files == sorted(n for n in strand.results.FRAMES if getattr(r, n) is not None)
        probes = sorted(p.stem for p in d.glob("probe_*.csv"))
        assert probes == sorted(f"probe_{s}" for s in r.probes)
        for name in files + probes:
            header, cols = read_cli_csv(d / f"{name}.csv")
            df = r.probes[name[len("probe_") :]] if name.startswith("probe_") else getattr(r, name)
            assert list(df.columns) == header, name
            for c in header:
                if isinstance(cols[c], list):
                    assert list(df[c].astype(str)) == cols[c], (name, c)
                else:
                    assert same_bits(df[c].to_numpy(dtype=np.float64), cols[c]), (model, name, c)
    return result


def test_static_run_matches_the_command_bit_for_bit(static_scene, scene_file, cli, tmp_path):
    r = compare_with_cli(static_scene, scene_file, cli, tmp_path)
    assert set(r) == {"equivalent", "traditional"}
    assert r["equivalent"].summary["status"] == "ok"
    # The tip of summary.json is the last centreline point (an independent record of it).
    c = r["equivalent"].centerline
    assert r.summary["equivalent"]["tip"] == pytest.approx([c.x.iloc[-1], c.y.iloc[-1], c.z.iloc[-1]], abs=1e-12)


def test_dynamic_run_matches_the_command_bit_for_bit(dynamic_scene, scene_file, cli, tmp_path):
    r = compare_with_cli(dynamic_scene, scene_file, cli, tmp_path)
    e = r["equivalent"]
    assert e.tip is not None and e.energy is not None and len(e.tip) == 41
    assert r.tip.columns[0] == "model"


def test_model_selection_matches_the_command(static_scene, scene_file, cli, tmp_path):
    r = compare_with_cli(static_scene, scene_file, cli, tmp_path, models=["traditional"])
    assert list(r) == ["traditional"]
    with pytest.raises(ValueError, match="the scene has no models.fine"):
        strand.run(static_scene, models="fine")
    with pytest.raises(ValueError, match="unknown model"):
        strand.run(static_scene, models="fancy")


def test_out_keeps_the_files(static_scene, tmp_path):
    r = strand.run(static_scene, models="equivalent", out=tmp_path / "o")
    assert (tmp_path / "o" / "equivalent" / "centerline.csv").exists()
    assert r["equivalent"].directory == tmp_path / "o" / "equivalent"


def test_progress_callback_and_its_exception(dynamic_scene):
    calls = []
    strand.run(dynamic_scene, progress=lambda m, f: calls.append((m, f)))
    assert calls and all(m == "equivalent" and 0.0 <= f <= 1.0 for m, f in calls)
    assert calls[-1][1] == pytest.approx(1.0, abs=0.02)

    class Stop(Exception):
        pass

    def stop(m, f):
        raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        strand.run(dynamic_scene, progress=stop)
    # The interpreter and the package are fine afterwards.
    assert strand.run(dynamic_scene)["equivalent"].status == "ok"


def test_a_run_releases_the_gil(dynamic_scene):
    long = strand.Scene(dynamic_scene).with_values({"analysis.duration": 2.0})
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.perf_counter()
    strand.run(long, threads=1)
    took = time.perf_counter() - start
    done.set()
    t.join()
    during = [x for x in ticks if start < x < start + took]
    # With the GIL held for the whole run, the counter would not tick at all during it; it
    # ticks every ~1 ms when free (a loaded machine may slow it, hence a tenth of that).
    assert took > 0.05 and len(during) > 0.1 * took / 0.001, (took, len(during))


def test_ctrl_c_stops_a_run_and_the_interpreter_goes_on(dynamic_scene, tmp_path):
    long = strand.Scene(dynamic_scene).with_values({"analysis.duration": 500.0, "analysis.max_steps": 10**8})
    script = tmp_path / "interrupt.py"
    script.write_text(textwrap.dedent(f"""
        import json, sys, time, strand
        scene = strand.Scene(json.loads({long.to_json(indent=None)!r}))
        print("start", flush=True)
        t = time.perf_counter()
        try:
            strand.run(scene)
            print("finished")
        except KeyboardInterrupt:
            print("interrupted after", round(time.perf_counter() - t, 2), flush=True)
        short = scene.with_values({{"analysis.duration": 0.05}})
        print("after:", strand.run(short)["equivalent"].status, flush=True)
    """))
    p = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "start"
    time.sleep(1.0)
    sent = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=60)
    stopped = time.perf_counter() - sent
    assert "interrupted after" in out, (out, err)
    assert "after: ok" in out, (out, err)
    assert "panicked" not in err, err
    # The 500 s run takes minutes; the stop comes within a progress report (a step).
    assert stopped < 20.0


def test_probes_and_ranges_match_the_command_bit_for_bit(dynamic_scene, scene_file, cli, tmp_path):
    scene = dict(dynamic_scene, output={"probes": [0.5, 1.0], "range_window": [0.05, 0.2]})
    r = compare_with_cli(scene, scene_file, cli, tmp_path)
    eq = r["equivalent"]
    assert sorted(eq.probes) == ["0.5", "1"]
    assert eq.range is not None and len(eq.range) == len(eq.centerline)
