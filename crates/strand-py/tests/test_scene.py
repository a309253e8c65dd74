"""Scenes from Python are validated by the command's validator: the same errors, naming the
field path."""

import pytest

import strand

BAD = [
    # (field path, value, start of the message)
    ("strand.layers[0].wires", -3, "strand.layers[0].wires:"),
    ("strand.layers[0].lay_direction", "up", "strand.layers[0].lay_direction:"),
    ("strand.core.diameter", 0.0, "strand.core.diameter:"),
    ("analysis.kind", "quasi-static", "analysis.kind:"),
    ("strand.friction", -0.1, "strand.friction:"),
    ("strand.layers[0].lay_angle_deg", 95.0, "strand.layers[0]"),
]


@pytest.mark.parametrize("path,value,start", BAD)
def test_errors_name_the_field_as_the_command_does(static_scene, scene_file, cli, path, value, start):
    bad = strand.Scene(static_scene).to_dict()
    strand.scene.set_field(bad, path, value)
    with pytest.raises(strand.SceneError) as e:
        strand.Scene(bad)
    assert isinstance(e.value, ValueError)
    assert str(e.value).startswith(start), str(e.value)
    assert e.value.field.startswith(start.rstrip(":"))
    # The command reads the same scene from a file and says the same, after the file's path.
    f = scene_file(bad)
    r = cli("section", f, check=False)
    assert r.returncode != 0
    with pytest.raises(strand.SceneError) as from_file:
        strand.Scene.from_file(f)
    assert r.stderr.strip() == f"error: {from_file.value}"
    assert str(from_file.value) == f"{f}: {e.value}"


def test_unknown_field_is_named(static_scene):
    with pytest.raises(strand.SceneError, match=r"^strand\.frictio: unknown field `frictio`"):
        strand.Scene(static_scene).with_values({"strand.frictio": 0.2})


def test_missing_parent_and_index_are_named_before_validation(static_scene):
    s = strand.Scene(static_scene)
    with pytest.raises(strand.SceneError, match=r"^strand\.layers\[3\]\.wires: no such field"):
        s.with_values({"strand.layers[3].wires": 6})
    with pytest.raises(strand.SceneError, match=r"^section\.slip_limit: no such field"):
        s.with_values({"section.slip_limit": "paper"})
    with pytest.raises(ValueError, match="not a field path"):
        s.with_values({"strand..friction": 0.2})


def test_keywords_dicts_files_and_edits(static_scene, scene_file):
    s = strand.Scene(**static_scene)
    assert s == strand.Scene(static_scene) == strand.Scene.from_file(scene_file(static_scene))
    assert s.name == "nylon-1x8-hanging" and s.models == ["equivalent", "traditional"]
    t = s.with_values({"strand.friction": 0.1, "strand.layers[0].lay_angle_deg": 15.0})
    assert t.get("strand.friction") == 0.1 and s.get("strand.friction") == 0.25
    assert t.summary()["lay_angle_deg"] == pytest.approx(15.0, rel=1e-12)
    u = strand.Scene(static_scene, name="renamed")
    assert u.name == "renamed"
    with pytest.raises(strand.SceneError, match="^name: must not be empty"):
        strand.Scene(static_scene, name=" ")


def _leaves(node, path=""):
    """Every (field path, value) of a scene dict down to its numbers and strings."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _leaves(v, f"{path}.{k}" if path else k)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _leaves(v, f"{path}[{i}]")
    else:
        yield path, node


def test_field_paths_reach_every_value_and_only_those(static_scene, dynamic_scene):
    """Property over every leaf of two scenes: the path of a value gets it back, setting it
    changes that value alone, and a path with a wrong separator is rejected."""
    for d in (static_scene, dynamic_scene):
        leaves = list(_leaves(d))
        assert len(leaves) > 20
        for path, value in leaves:
            assert strand.scene.get_field(d, path) == value
            e = strand.Scene(d).to_dict()
            strand.scene.set_field(e, path, "marker")
            changed = [p for p, v in _leaves(e) if v == "marker"]
            assert changed == [path]
            if "." in path:
                with pytest.raises(ValueError, match="not a field path"):
                    strand.scene.parse_field_path(path.replace(".", "..", 1))
            if "]." in path:  # a name straight after an index, without its dot
                with pytest.raises(ValueError, match="not a field path"):
                    strand.scene.parse_field_path(path.replace("].", "]", 1))
            if path.endswith("]"):
                with pytest.raises(ValueError, match="not a field path"):
                    strand.scene.parse_field_path(path + "x")
