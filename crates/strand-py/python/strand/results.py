"""``strand.run``: a scene's models run as ``strand run`` runs them, the results as pandas
DataFrames and the summaries as dicts."""

from __future__ import annotations

import json
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Union

import pandas as pd

from .progress import ProgressArg, resolve
from .scene import PathLike, Scene

_PANDAS_MAJOR = int(pd.__version__.split(".")[0])

#: The result files of a model's folder that become DataFrames (SPEC 6), by attribute.
FRAMES = ("centerline", "tip", "energy", "wires", "contacts", "range")


def read_csv(path: Path) -> pd.DataFrame:
    """A result CSV with every number exactly as written (the files hold the shortest text
    that reads back to the same double; an empty field, a non-finite value, reads as NaN).
    pandas 3 reads every number exactly by default; older versions need ``round_trip``."""
    if _PANDAS_MAJOR < 3:
        return pd.read_csv(path, float_precision="round_trip")
    return pd.read_csv(path)


@dataclass
class ModelResult:
    """One model's results: its ``summary.json`` as a dict and its CSV files as DataFrames
    (``None`` for a file the run does not write: ``tip``/``energy``/``range`` are dynamics
    only, ``contacts`` the fine model's). ``probes`` maps each probe's arc length, as the file
    ``probe_<s>.csv`` names it, to that file. Columns and units are those of the files (the
    manual's Results pages)."""

    model: str
    summary: Dict[str, Any]
    centerline: Optional[pd.DataFrame] = None
    tip: Optional[pd.DataFrame] = None
    energy: Optional[pd.DataFrame] = None
    wires: Optional[pd.DataFrame] = None
    contacts: Optional[pd.DataFrame] = None
    range: Optional[pd.DataFrame] = None
    probes: Dict[str, pd.DataFrame] = field(default_factory=dict)
    directory: Optional[Path] = None

    @property
    def status(self) -> str:
        """``ok`` or ``failed``."""
        return self.summary["status"]

    @property
    def failed(self) -> bool:
        """Whether the run failed (``summary["reason"]`` and ``["error"]`` say why)."""
        return self.status == "failed"

    @classmethod
    def load(cls, directory: Path, summary: Mapping[str, Any], keep: bool) -> "ModelResult":
        """The results in ``directory`` (a model folder of ``strand run``)."""
        frames = {}
        for name in FRAMES:
            p = directory / f"{name}.csv"
            frames[name] = read_csv(p) if p.exists() else None
        probes = {p.stem[len("probe_") :]: read_csv(p) for p in sorted(directory.glob("probe_*.csv"))}
        return cls(
            model=summary["model"],
            summary=dict(summary),
            directory=directory if keep else None,
            probes=probes,
            **frames,
        )


@dataclass
class Result:
    """The results of :func:`strand.run`: one :class:`ModelResult` per model, by name
    (``result["equivalent"].centerline``). ``summary`` maps each model to its summary dict;
    ``centerline``, ``tip``, ... stack the models' frames with a leading ``model`` column."""

    models: Dict[str, ModelResult] = field(default_factory=dict)
    directory: Optional[Path] = None

    def __getitem__(self, model: str) -> ModelResult:
        return self.models[model]

    def __iter__(self) -> Iterator[str]:
        return iter(self.models)

    def __len__(self) -> int:
        return len(self.models)

    @property
    def summary(self) -> Dict[str, Dict[str, Any]]:
        """Each model's ``summary.json``, by model."""
        return {m: r.summary for m, r in self.models.items()}

    @property
    def failed(self) -> List[str]:
        """The models whose run failed."""
        return [m for m, r in self.models.items() if r.failed]

    def _stack(self, name: str) -> Optional[pd.DataFrame]:
        parts = [getattr(r, name).assign(model=m) for m, r in self.models.items() if getattr(r, name) is not None]
        if not parts:
            return None
        df = pd.concat(parts, ignore_index=True)
        return df[["model"] + [c for c in df.columns if c != "model"]]

    @property
    def centerline(self) -> Optional[pd.DataFrame]:
        """``centerline.csv`` of every model: s, x, y, z, curvature, tension, ... (SI)."""
        return self._stack("centerline")

    @property
    def tip(self) -> Optional[pd.DataFrame]:
        """``tip.csv`` (dynamics): t, x, y, z, vx, vy, vz."""
        return self._stack("tip")

    @property
    def energy(self) -> Optional[pd.DataFrame]:
        """``energy.csv`` (dynamics): t, kinetic, gravity, elastic, dissipated, total, ..."""
        return self._stack("energy")

    @property
    def wires(self) -> Optional[pd.DataFrame]:
        """``wires.csv``: each wire's state along the strand."""
        return self._stack("wires")

    @property
    def contacts(self) -> Optional[pd.DataFrame]:
        """``contacts.csv`` (fine model)."""
        return self._stack("contacts")

    @property
    def range(self) -> Optional[pd.DataFrame]:
        """``range.csv`` (dynamics): min, max and mean of curvature, moment, tension and
        bending stiffness at every centreline point over the run (or ``output.range_window``)."""
        return self._stack("range")

    def __repr__(self) -> str:
        parts = ", ".join(f"{m}: {r.status}" for m, r in self.models.items())
        return f"strand.Result({parts})"


def run(
    scene: Union[Scene, Mapping[str, Any], PathLike],
    models: Union[None, str, Sequence[str]] = None,
    out: Optional[PathLike] = None,
    progress: ProgressArg = None,
    *,
    threads: Optional[int] = None,
    max_steps: Optional[int] = None,
    vtk: bool = False,
) -> Result:
    """Runs the scene's models (all, or those named in ``models``) with the code of
    ``strand run`` and returns their results.

    ``out``: the folder that keeps the files ``strand run --out`` writes (default: a temporary
    folder, removed after the files are read). ``progress``: ``True`` for a tqdm bar (where
    installed), or a callable ``(model, fraction)`` called at most every 0.1 s. ``threads``:
    size of the Rust thread pool (default: all cores). ``max_steps``: as ``--max-steps``.

    The run releases the GIL; Ctrl-C stops it and raises ``KeyboardInterrupt``. A model whose
    run fails is in the result with ``status == "failed"`` and its reason, as in the command.
    """
    scene = Scene.coerce(scene)
    names = [models] if isinstance(models, str) else list(models or [])
    callback, close = resolve(progress)
    tmp = tempfile.TemporaryDirectory(prefix="strand-run-") if out is None else None
    directory = Path(tmp.name) if tmp is not None else Path(out)  # type: ignore[arg-type]
    try:
        texts = scene._core.run(str(directory), names, vtk, max_steps, threads, callback)
        summaries = [json.loads(t) for t in texts]
        result = Result(directory=None if tmp else directory)
        for s in summaries:
            result.models[s["model"]] = ModelResult.load(directory / s["model"], s, keep=tmp is None)
        return result
    finally:
        close()
        if tmp is not None:
            tmp.cleanup()
