"""`strand.bend`: the virtual bending test of `strand bend`, the same numbers."""

import os
import subprocess

import numpy as np

import strand
from conftest import cli_path
from test_run import read_cli_csv, same_bits


def test_bend_matches_the_command_and_lies_between_the_bounds(static_scene, scene_file, tmp_path):
    f = scene_file(static_scene)
    out = tmp_path / "cli"
    args = [cli_path(), "bend", str(f), "--tension", "50", "--curvatures", "0.5,1,2", "--pitches", "3",
            "--segments-per-pitch", "8", "--out", str(out)]
    # One Rust thread on both sides, so that the sums of the fine model add in the same order.
    subprocess.run(args, check=True, capture_output=True, env=dict(os.environ, RAYON_NUM_THREADS="1"))
    r = strand.bend(static_scene, 50.0, [0.5, 1.0, 2.0], pitches=3, segments_per_pitch=8, threads=1)
    header, cols = read_cli_csv(out / "bending.csv")
    assert list(r.points.columns) == header
    for c in header:
        assert same_bits(r.points[c].to_numpy(dtype=np.float64), cols[c]), c
    # The measured secant stiffness lies between the all-slip and all-stick bounds.
    s = r.summary
    k = r.points["moment"] / r.points["curvature"]
    assert ((k > s["k_min"]) & (k < s["k_max"])).all()


def test_equivalent_bend_matches_the_command_and_its_loop_area_is_the_slip_work(static_scene, scene_file, tmp_path):
    """`strand.bend(model="equivalent")` writes what `strand bend --model equivalent` writes, bit
    for bit, and the hysteretic law's loop returns its stored energy: over the closed part of
    the path (-a -> a -> -a is not closed, but 0 -> a -> -a -> a ends where the first reversal
    started) the loop area the summary reports equals the slip work within the trapezoid
    rule's error: per step of dk = a / n at most K_max dk^2 (the moment's change over a step is
    at most K_max dk), over the 5 n steps of the path."""
    scene = dict(static_scene, law="hysteretic")
    f = scene_file(scene)
    out = tmp_path / "cli"
    args = [cli_path(), "bend", str(f), "--model", "equivalent", "--tension", "50", "--steps", "40", "--out", str(out)]
    subprocess.run(args, check=True, capture_output=True)
    r = strand.bend(scene, 50.0, model="equivalent", steps=40)
    header, cols = read_cli_csv(out / "law-bending.csv")
    assert list(r.points.columns) == header
    for c in header:
        assert same_bits(r.points[c].to_numpy(dtype=np.float64), cols[c]), c
    s = r.summary
    assert s["dissipated"] > 0.0
    a, n = s["amplitude"], 40
    bound = 5 * n * s["k_max"] * (a / n) ** 2
    assert abs(s["loop_area"] - s["dissipated"]) <= bound, (s["loop_area"], s["dissipated"], bound)
    try:
        strand.bend(scene, 50.0, model="coarse")
    except ValueError as e:
        assert "model" in str(e)
    else:
        raise AssertionError("an unknown model was accepted")
