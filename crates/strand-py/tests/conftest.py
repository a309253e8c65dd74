"""Shared fixtures: the repository's scenes, shortened to run in well under a second, and the
`strand` command to compare with."""

import copy
import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]


def load(name):
    return json.loads((ROOT / "examples" / name).read_text())


@pytest.fixture
def static_scene():
    """The nylon 1+8 cantilever hanging under gravity (statics, both beam models)."""
    return load("nylon-1x8-hanging.json")


@pytest.fixture
def dynamic_scene():
    """The steel 1+9 pendulum released under gravity, 0.2 s on 8 equivalent elements."""
    d = load("steel-1x9-swing.json")
    d["analysis"]["duration"] = 0.2
    d["models"] = {"equivalent": {"elements": 8}}
    return d


def cli_path():
    """The `strand` command: $STRAND_CLI, else the workspace's release build."""
    p = os.environ.get("STRAND_CLI") or str(ROOT / "target" / "release" / "strand")
    if not Path(p).exists():
        found = shutil.which("strand")
        if found is None:
            pytest.fail(
                f"the strand command is not at {p}: build it with `cargo build --release -p strand-cli` "
                "or set STRAND_CLI"
            )
        p = found
    return p


@pytest.fixture
def cli():
    """Runs the `strand` command with the given arguments; returns the CompletedProcess."""
    exe = cli_path()

    def run(*args, check=True):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and r.returncode != 0:
            raise AssertionError(f"strand {' '.join(map(str, args))} failed: {r.stderr}")
        return r

    return run


@pytest.fixture
def scene_file(tmp_path):
    """Writes a scene dict as a scene file; returns its path."""

    def write(d, name="scene.json"):
        p = tmp_path / name
        p.write_text(json.dumps(copy.deepcopy(d), indent=2))
        return p

    return write
