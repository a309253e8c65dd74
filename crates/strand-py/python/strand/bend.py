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
    pitches: int = 6,
    segments_per_pitch: int = 12,
    out: Optional[PathLike] = None,
    threads: Optional[int] = None,
    progress: ProgressArg = None,
) -> BendResult:
    """The fine model of the scene's strand pulled to ``tension`` (N) and bent along arcs of
    the given ``curvatures`` (1/m, increasing; default 10 values from 0.2 to 20 times the
    law's first slip curvature), as ``strand bend``. ``out`` keeps the files (default: a
    temporary folder). Releases the GIL; Ctrl-C raises ``KeyboardInterrupt``."""
    sc = Scene.coerce(scene)
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
