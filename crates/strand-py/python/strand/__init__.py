"""strand from Python: stranded wire rope scenes, runs, section laws and parameter sweeps.

The package wraps the same Rust code as the ``strand`` command:

* :class:`Scene` -- a scene validated by the command's validator (errors raise
  :class:`SceneError` naming the field path);
* :func:`run` -- ``strand run``: the results as pandas DataFrames and the summary as a dict;
* :func:`section` -- the section law over NumPy arrays, and the derived quantities that
  ``strand section`` prints; :func:`section_point` -- all of ``strand section --json``;
* :func:`bend` -- ``strand bend``, the virtual bending test of the fine model beside the law, or the
  equivalent model's section law with a load reversal;
* :func:`sweep` -- a parameter study over field paths, on local processes, a Dask cluster or
  Ray, resumable from its output folder.
"""

from ._strand import SceneError, __version__
from .bend import BendResult, bend
from .results import ModelResult, Result, run
from .scene import Scene
from .section import section, section_point
from .sweep import sweep

__all__ = [
    "BendResult",
    "ModelResult",
    "Result",
    "Scene",
    "SceneError",
    "__version__",
    "bend",
    "run",
    "section",
    "section_point",
    "sweep",
]
