"""The Rust extension of the ``strand`` package (see the package docstring)."""

from pathlib import Path
from typing import Callable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class SceneError(ValueError):
    """A scene the validator rejects; ``field`` is the JSON path of the fault."""

    field: str

class Scene:
    """A scene validated by the ``strand`` command's validator."""

    def __init__(self, text: str) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def length(self) -> float: ...
    @property
    def law_name(self) -> str: ...
    @property
    def models(self) -> list[str]: ...
    def summary_json(self) -> str: ...
    def state_len(self, law: Optional[str] = None) -> int: ...
    def section_point_json(
        self, strain: float, curvature: float, at: float, law: Optional[str] = None
    ) -> str: ...
    def section(
        self,
        strain: npt.NDArray[np.float64],
        curvature: npt.NDArray[np.float64],
        x: npt.NDArray[np.float64],
        state: npt.NDArray[np.float64],
        law: Optional[str] = None,
    ) -> Tuple[npt.NDArray[np.float64], ...]: ...
    def run(
        self,
        out: Union[str, Path],
        models: Sequence[str],
        vtk: bool = False,
        max_steps: Optional[int] = None,
        threads: Optional[int] = None,
        progress: Optional[Callable[[str, float], object]] = None,
    ) -> list[str]: ...
    def bend(
        self,
        out: Union[str, Path],
        tension: float,
        curvatures: Sequence[float],
        pitches: int = 6,
        segments_per_pitch: int = 12,
        threads: Optional[int] = None,
        progress: Optional[Callable[[str, float], object]] = None,
    ) -> str: ...
    def law_bend(
        self,
        out: Union[str, Path],
        tension: float,
        amplitude: Optional[float] = None,
        steps: int = 100,
    ) -> str: ...
