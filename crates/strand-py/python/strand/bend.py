"""``strand.bend``: the virtual bending test of ``strand bend``."""

from __future__ import annotations

import json
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Sequence, Union

import pandas as pd

from .progress import ProgressArg, resolve
from .results import read_csv
from .scene import PathLike, Scene


@dataclass
class BendResult:
    """A bending test: ``summary`` (``summary.json``: tension, strain, K_min, K_max, first slip
    curvature, wall time, ...) and ``points`` (``bending.csv``: the fine model's measured
    moment and stiffness beside the section law's at the same strain and curvature)."""

    summary: Dict[str, Any]
    points: pd.DataFrame
    directory: Optional[Path] = None


def bend(
    scene: Union[Scene, Mapping[str, Any], PathLike],
    tension: float,
    curvatures: Optional[Sequence[float]] = None,
    *,
    model: str = "fine",
    amplitude: Optional[float] = None,
    steps: int = 100,
    pitches: int = 6,
    segments_per_pitch: int = 12,
    out: Optional[PathLike] = None,
    threads: Optional[int] = None,
    progress: ProgressArg = None,
) -> BendResult:
    """The virtual bending test of ``strand bend`` at ``tension`` (N).

    ``model="fine"`` (default): the fine model of the scene's strand (one layer) pulled to
    ``tension`` and bent along arcs of the given ``curvatures`` (1/m, increasing; default 10
    values from 0.2 to 20 times the law's first slip curvature); ``points`` is
    ``bending.csv``. Releases the GIL; Ctrl-C raises ``KeyboardInterrupt``.

    ``model="equivalent"``: the section law of the equivalent beam, any number of layers,
    along 0 -> a -> -a -> a with one load reversal (``amplitude`` a in 1/m, default three times
    the largest critical curvature; ``steps`` steps from 0 to a), averaged over the longest
    pitch, as ``strand bend --model equivalent``; ``points`` is ``law-bending.csv``
    (curvature, moment, tangent) and the summary holds the slip work and the loop's area.

    ``out`` keeps the files (default: a temporary folder)."""
    if model not in ("fine", "equivalent"):
        raise ValueError(f"model must be 'fine' or 'equivalent', got {model!r}")
    sc = Scene.coerce(scene)
    if model == "equivalent":
        tmp_law = tempfile.TemporaryDirectory(prefix="strand-bend-") if out is None else None
        law_dir = Path(tmp_law.name) if tmp_law is not None else Path(out)  # type: ignore[arg-type]
        try:
            text = sc._core.law_bend(
                str(law_dir), float(tension), None if amplitude is None else float(amplitude), int(steps)
            )
            return BendResult(
                summary=json.loads(text),
                points=read_csv(law_dir / "law-bending.csv"),
                directory=None if tmp_law else law_dir,
            )
        finally:
            if tmp_law is not None:
                tmp_law.cleanup()
    callback, close = resolve(progress)
    tmp = tempfile.TemporaryDirectory(prefix="strand-bend-") if out is None else None
    directory = Path(tmp.name) if tmp is not None else Path(out)  # type: ignore[arg-type]
    try:
        text = sc._core.bend(
            str(directory), float(tension), [float(c) for c in (curvatures or [])],
            int(pitches), int(segments_per_pitch), threads, callback,
        )
        return BendResult(
            summary=json.loads(text),
            points=read_csv(directory / "bending.csv"),
            directory=None if tmp else directory,
        )
    finally:
        close()
        if tmp is not None:
            tmp.cleanup()
