"""Progress reports of long runs: a callback ``(model, fraction)``, or a tqdm bar."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Union

ProgressArg = Union[None, bool, Callable[[str, float], Any]]


class _Bars:
    """One tqdm bar per model (a line on standard error where tqdm is not installed)."""

    def __init__(self) -> None:
        try:
            from tqdm.auto import tqdm  # type: ignore[import-not-found]
        except ImportError:
            tqdm = None
        self._tqdm = tqdm
        self._bar: Any = None
        self._model: Optional[str] = None

    def __call__(self, model: str, fraction: float) -> None:
        if model != self._model:
            self.close()
            self._model = model
            if self._tqdm is not None:
                self._bar = self._tqdm(total=1000, desc=model, unit="‰")
        done = int(max(0.0, min(1.0, fraction)) * 1000)
        if self._bar is not None:
            self._bar.update(done - self._bar.n)
        else:
            print(f"\r{model:>12} {100 * fraction:5.1f}%", end="", file=sys.stderr, flush=True)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        elif self._model is not None:
            print(file=sys.stderr)


def resolve(progress: ProgressArg) -> tuple[Optional[Callable[[str, float], Any]], Callable[[], None]]:
    """The callback to hand to the run and what to call when it ends: ``None``/``False`` is
    quiet, ``True`` a tqdm bar (a status line without tqdm), a callable is called as is."""
    if progress is None or progress is False:
        return None, lambda: None
    if progress is True:
        bars = _Bars()
        return bars, bars.close
    if callable(progress):
        return progress, lambda: None
    raise TypeError("progress is None, True or a callable (model, fraction)")
