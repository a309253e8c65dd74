"""Scenes: the JSON of a scene file as a Python dict, validated by the ``strand`` command's
validator, and edited by field paths such as ``strand.layers[0].lay_angle_deg``."""

from __future__ import annotations

import copy
import json
import os
import re
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Union

from . import _strand
from ._strand import SceneError

PathLike = Union[str, "os.PathLike[str]"]

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_STEP = re.compile(r"\.([A-Za-z_][A-Za-z0-9_]*)|\[(\d+)\]")


def parse_field_path(path: str) -> List[Union[str, int]]:
    """The steps of a field path: ``"strand.layers[0].lay_angle_deg"`` gives
    ``["strand", "layers", 0, "lay_angle_deg"]``. Raises ``ValueError`` on a malformed path."""
    first = _NAME.match(path)
    if first is None:
        raise ValueError(f"{path}: not a field path (expected e.g. strand.layers[0].wires)")
    steps: List[Union[str, int]] = [first.group(0)]
    pos = first.end()
    while pos < len(path):
        m = _STEP.match(path, pos)
        if m is None:
            raise ValueError(f"{path}: not a field path (expected e.g. strand.layers[0].wires)")
        steps.append(m.group(1) if m.group(1) is not None else int(m.group(2)))
        pos = m.end()
    return steps


def _missing(path: str, at: str, why: str) -> SceneError:
    err = SceneError(f"{path}: no such field in the scene ({why} at `{at}`)")
    err.field = path
    return err


def set_field(data: Dict[str, Any], path: str, value: Any) -> None:
    """Sets the field at ``path`` of the scene dict ``data`` in place. Every step but the last
    must exist; the last may be a field the scene leaves out (the validator then checks its
    name). Raises ``SceneError`` naming the path."""
    steps = parse_field_path(path)
    node: Any = data
    done = ""
    for i, step in enumerate(steps):
        last = i == len(steps) - 1
        here = f"{done}[{step}]" if isinstance(step, int) else (f"{done}.{step}" if done else step)
        if isinstance(step, int):
            if not isinstance(node, list):
                raise _missing(path, done, "not a list")
            if step >= len(node):
                raise _missing(path, here, f"index out of range, {len(node)} entries")
        else:
            if not isinstance(node, dict):
                raise _missing(path, done, "not an object")
            if step not in node and not last:
                raise _missing(path, here, "absent")
        if last:
            node[step] = value
        else:
            node = node[step]
        done = here


def get_field(data: Mapping[str, Any], path: str) -> Any:
    """The value at ``path`` of the scene dict; ``SceneError`` naming the path if absent."""
    node: Any = data
    for step in parse_field_path(path):
        try:
            node = node[step]
        except (KeyError, IndexError, TypeError):
            raise _missing(path, str(step), "absent") from None
    return node


class Scene:
    """A scene (SPEC 6), validated by the same code as ``strand run``.

    Build one from a dict of the scene file's JSON, keyword arguments of its top-level fields,
    or both (the keywords win)::

        s = strand.Scene(name="rope", strand={...}, analysis={"kind": "static"},
                         models={"equivalent": {"elements": 20}})
        s = strand.Scene.from_file("examples/nylon-1x8-hanging.json")
        t = s.with_values({"strand.friction": 0.1, "strand.layers[0].lay_angle_deg": 15})

    A rejected scene raises :class:`strand.SceneError` (a ``ValueError``) whose message is the
    command's and names the field path, e.g. ``strand.layers[0].wires: ...``; its ``field``
    attribute holds the path. A Scene is immutable: edits return a new one.
    """

    __slots__ = ("_data", "_core", "_summary")

    def __init__(self, data: Optional[Mapping[str, Any]] = None, /, **fields: Any) -> None:
        if isinstance(data, Scene):
            data = data._data
        merged: Dict[str, Any] = copy.deepcopy(dict(data)) if data is not None else {}
        merged.update(copy.deepcopy(fields))
        self._data = merged
        self._core = _strand.Scene(json.dumps(merged))
        self._summary: Optional[Dict[str, Any]] = None

    @classmethod
    def from_json(cls, text: str) -> "Scene":
        """A scene from the text of a scene file."""
        _strand.Scene(text)  # the command's errors, before Python's JSON reader sees the text
        return cls(json.loads(text))

    @classmethod
    def from_file(cls, path: PathLike) -> "Scene":
        """A scene from a scene file; errors start with the file's path, as the command's."""
        p = Path(path)
        try:
            text = p.read_text()
        except OSError as e:
            err = SceneError(f"{p}: cannot read {p}: {e}")
            err.field = ""
            raise err from None
        try:
            return cls.from_json(text)
        except SceneError as e:
            err = SceneError(f"{p}: {e}")
            err.field = getattr(e, "field", "")
            raise err from None

    @classmethod
    def coerce(cls, scene: Union["Scene", Mapping[str, Any], PathLike]) -> "Scene":
        """``scene`` as a Scene: a Scene, a dict of the JSON, or the path of a scene file."""
        if isinstance(scene, Scene):
            return scene
        if isinstance(scene, Mapping):
            return cls(scene)
        if isinstance(scene, (str, os.PathLike)):
            return cls.from_file(scene)
        raise TypeError(f"a scene is a strand.Scene, a dict or a file path, not {type(scene).__name__}")

    @property
    def name(self) -> str:
        """Scene name."""
        return self._core.name

    @property
    def length(self) -> float:
        """Strand length (m)."""
        return self._core.length

    @property
    def law(self) -> str:
        """The equivalent model's section law (``continuous``, ``paper``, ``hysteretic``)."""
        return self._core.law_name

    @property
    def models(self) -> List[str]:
        """The models the scene runs, in the order they run."""
        return list(self._core.models)

    def to_dict(self) -> Dict[str, Any]:
        """A copy of the scene's JSON as a dict."""
        return copy.deepcopy(self._data)

    def to_json(self, indent: Optional[int] = 2) -> str:
        """The scene file's text."""
        return json.dumps(self._data, indent=indent)

    def write(self, path: PathLike) -> Path:
        """Writes the scene file (for ``strand run``); returns its path."""
        p = Path(path)
        p.write_text(self.to_json() + "\n")
        return p

    def get(self, path: str) -> Any:
        """The value at a field path, e.g. ``scene.get("strand.layers[0].wires")``."""
        return copy.deepcopy(get_field(self._data, path))

    def with_values(self, values: Mapping[str, Any]) -> "Scene":
        """A new scene with the fields at the given paths set, validated. A path whose parent
        does not exist, or a value the validator rejects, raises ``SceneError`` naming it."""
        data = self.to_dict()
        for path, value in values.items():
            set_field(data, path, value)
        return Scene(data)

    def summary(self) -> Dict[str, Any]:
        """The derived quantities ``strand section`` prints (helix radius, pitch, lay angle,
        EA, K_min, K_max, ...; SI units), as ``strand section --json`` gives them."""
        if self._summary is None:
            self._summary = json.loads(self._core.summary_json())
        return dict(self._summary)

    def __reduce__(self):  # pickles as its JSON (for process pools and clusters)
        return (Scene, (self._data,))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and other._data == self._data

    def __hash__(self) -> int:
        return hash(json.dumps(self._data, sort_keys=True))

    def __repr__(self) -> str:
        return f"strand.Scene(name={self.name!r}, law={self.law!r}, models={self.models!r})"
