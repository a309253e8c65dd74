"""The package's surface: help texts, the extension's stubs, progress without a callback."""

import ast
from pathlib import Path

import strand
from strand import _strand

STUBS = Path(__file__).resolve().parents[1] / "python" / "strand" / "_strand.pyi"


def test_stubs_cover_the_extension():
    tree = ast.parse(STUBS.read_text())
    stub = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    assert set(stub) == {"SceneError", "Scene"}
    declared = {f.name for f in stub["Scene"].body if isinstance(f, ast.FunctionDef)} - {"__init__"}
    public = {n for n in dir(_strand.Scene) if not n.startswith("_")}
    assert declared == public


def test_public_functions_explain_themselves():
    for f in [strand.run, strand.section, strand.sweep, strand.bend, strand.Scene, strand.Scene.with_values]:
        assert f.__doc__ and len(f.__doc__) > 80, f
    assert "JSON path" in strand.SceneError.__doc__


def test_progress_true_reports(dynamic_scene, capsys, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_tqdm(name, *args, **kwargs):  # the status line used where tqdm is not installed
        if name.startswith("tqdm"):
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_tqdm)
    strand.run(dynamic_scene, progress=True)
    err = capsys.readouterr().err
    assert "equivalent" in err and "100.0%" in err
