"""``strand.section``: the equivalent model's section law over NumPy arrays."""

from __future__ import annotations

from typing import Any, Dict, Mapping, Optional, Union

import numpy as np
import numpy.typing as npt

from .scene import PathLike, Scene

ArrayLike = Union[float, npt.ArrayLike]


def _flat(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64).reshape(-1)


def section(
    scene: Union[Scene, Mapping[str, Any], PathLike],
    curvature: ArrayLike,
    strain: ArrayLike = 0.0,
    x: ArrayLike = 0.0,
    state: Optional[npt.ArrayLike] = None,
    *,
    law: Optional[str] = None,
) -> Dict[str, Any]:
    """Evaluates the scene's section law (or ``law``) in planar bending at every point of the
    broadcast arrays ``curvature`` (signed kappa_z, 1/m, as ``strand section --curvature``),
    ``strain`` (-) and ``x`` (material coordinate, m), each from ``state``.

    ``state`` is the hysteretic law's committed state, shape ``curvature.shape + (n,)`` with
    ``n = result["state"].shape[-1]`` (zeros, the straight unslipped strand, when ``None``;
    ``n`` is 0 for the laws without state). The trial state comes back as ``result["state"]``:
    pass it in again to continue a loading path.

    Returns a dict of arrays of the broadcast shape: ``axial_force`` (N), ``moment`` (N m),
    ``tangent`` (dM/dkappa, N m^2), ``energy`` (stored energy density, J/m), ``slip_work``
    (J/m, from ``state`` to the trial), ``slipping`` (wires slipping), ``state``; and
    ``derived``, the derived quantities ``strand section`` prints (``Scene.summary()``).
    Each point is the law of ``strand section`` and of the models, bit for bit.
    """
    sc = Scene.coerce(scene)
    k = np.asarray(curvature, dtype=np.float64)
    e = np.asarray(strain, dtype=np.float64)
    at = np.asarray(x, dtype=np.float64)
    if k.shape == e.shape == at.shape:
        shape = k.shape
    else:
        k, e, at = np.broadcast_arrays(k, e, at)
        shape = k.shape
    core = sc._core
    n = core.state_len(law)
    size = k.size
    if state is None:
        s = np.zeros(size * n)
    else:
        s = np.asarray(state, dtype=np.float64)
        if s.shape != shape + (n,):
            try:
                s = np.broadcast_to(s, shape + (n,))
            except ValueError:
                raise ValueError(f"state: shape {s.shape}, expected {shape + (n,)}") from None
        s = _flat(s)
    force, moment, tangent, energy, slip_work, slipping, trial = core.section(_flat(e), _flat(k), _flat(at), s, law)
    return {
        "axial_force": force.reshape(shape),
        "moment": moment.reshape(shape),
        "tangent": tangent.reshape(shape),
        "energy": energy.reshape(shape),
        "slip_work": slip_work.reshape(shape),
        "slipping": slipping.reshape(shape),
        "state": trial.reshape(shape + (n,)),
        "derived": sc.summary(),
    }


def section_point(
    scene: Union[Scene, Mapping[str, Any], PathLike],
    strain: float,
    curvature: float,
    at: float = 0.0,
    *,
    law: Optional[str] = None,
) -> Dict[str, Any]:
    """What ``strand section SCENE --strain E --curvature K --at X --json`` prints: the
    derived quantities, then the point (moment, secant and tangent stiffness, first and full
    slip curvature, the per-wire table), from a state without slip."""
    import json

    sc = Scene.coerce(scene)
    out = sc.summary()
    out.update(json.loads(sc._core.section_point_json(float(strain), float(curvature), float(at), law)))
    return out
