"""``strand.sweep``: a parameter study, each point a scene edited by field paths, run on local
processes, a Dask cluster or Ray, gathered into one DataFrame and resumable from its folder."""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import itertools
import json
import multiprocessing
import os
import tempfile
import time
import traceback
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import pandas as pd

from ._strand import SceneError
from .scene import PathLike, Scene

#: The file of finished points in ``out_dir``: one JSON object per line, one line per point.
RESULTS_FILE = "results.jsonl"

#: The table of the whole sweep in ``out_dir``, written when it ends (the DataFrame returned).
TABLE_FILE = "results.csv"

#: The summary figures of a point's row, per model (from its ``summary.json``).
FIGURES = (
    "steps",
    "newton_iterations",
    "wall_time_s",
    "cpu_time_s",
    "energy_balance_error",
    "energy_balance_relative",
    "dissipated",
    "non_potential_work",
)


def _points(axes: Optional[Mapping[str, Sequence[Any]]], points: Optional[Iterable[Mapping[str, Any]]]) -> List[Dict[str, Any]]:
    if (axes is None) == (points is None):
        raise ValueError("give either axes (a product of values per field path) or points (a list of dicts)")
    if points is not None:
        return [dict(p) for p in points]
    assert axes is not None
    names = list(axes)
    values = [list(axes[n]) for n in names]
    for n, v in zip(names, values):
        if not v:
            raise ValueError(f"{n}: no values")
    return [dict(zip(names, combo)) for combo in itertools.product(*values)]


def point_key(scene: Mapping[str, Any], models: Sequence[str], max_steps: Optional[int]) -> str:
    """The identity of a point for resuming: a hash of its whole scene and run options, so a
    changed base scene never reuses a stale result."""
    text = json.dumps({"scene": scene, "models": list(models), "max_steps": max_steps}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _pin_threads(threads: int) -> None:
    """Process initializer of the local pool: the Rust threads of each worker."""
    os.environ["RAYON_NUM_THREADS"] = str(threads)


def run_point(
    scene: Dict[str, Any],
    models: Sequence[str],
    threads: int,
    max_steps: Optional[int],
    files: Optional[str],
) -> Dict[str, Any]:
    """Runs one point (in a worker) and returns its record: the models' summaries, or the
    error that stopped it. Never raises: a failure is a record."""
    start = time.perf_counter()
    try:
        # The runner alone: a sweep keeps the summaries, so the result files are not read
        # back into DataFrames (they stay in `files` when asked for).
        core = Scene(scene)._core
        with tempfile.TemporaryDirectory(prefix="strand-point-") as tmp:
            texts = core.run(files or tmp, list(models), False, max_steps, threads, None)
        return {"summaries": [json.loads(t) for t in texts], "wall_time_s": time.perf_counter() - start}
    except Exception as e:  # the point fails, the sweep goes on
        return {
            "error": f"{type(e).__name__}: {e}",
            "traceback": traceback.format_exc(limit=5),
            "wall_time_s": time.perf_counter() - start,
        }


def _rows(index: int, key: str, params: Mapping[str, Any], record: Mapping[str, Any]) -> List[Dict[str, Any]]:
    """The DataFrame rows of a finished point: one per model, or one for a point that failed
    before any model ran."""
    base = {"point": index, "key": key, **params, "point_wall_time_s": record.get("wall_time_s")}
    if "summaries" not in record:
        return [{**base, "model": None, "status": "failed", "reason": "error", "error": record.get("error")}]
    rows = []
    for s in record["summaries"]:
        tip = s.get("tip") or [None, None, None]
        row = {
            **base,
            "model": s["model"],
            "status": s["status"],
            "reason": s.get("reason"),
            "error": s.get("error"),
            "tip_x": tip[0],
            "tip_y": tip[1],
            "tip_z": tip[2],
        }
        row.update({f: s.get(f) for f in FIGURES})
        rows.append(row)
    return rows


class _Futures:
    """A ``concurrent.futures.Executor`` the caller owns."""

    def __init__(self, executor: cf.Executor) -> None:
        self.executor = executor
        self.pending: List[Any] = []

    def submit(self, *args: Any) -> Any:
        return self.executor.submit(run_point, *args)

    def as_completed(self, futures: List[Any]) -> Iterator[Any]:
        return cf.as_completed(futures)

    @staticmethod
    def result(future: Any) -> Dict[str, Any]:
        return future.result()

    def close(self, cancel: bool) -> None:
        if cancel:
            for f in self.pending:
                f.cancel()


class _Local(_Futures):
    """Local processes (concurrent.futures), ``workers`` of them, owned by the sweep."""

    def __init__(self, workers: Optional[int], threads: int) -> None:
        n = workers or max(1, (os.cpu_count() or 1) // threads)
        ctx = multiprocessing.get_context("spawn")
        super().__init__(
            cf.ProcessPoolExecutor(max_workers=n, mp_context=ctx, initializer=_pin_threads, initargs=(threads,))
        )

    def close(self, cancel: bool) -> None:
        self.executor.shutdown(wait=not cancel, cancel_futures=cancel)


class _Dask:
    """A ``dask.distributed.Client``: each point a task (``pure=False``: never cached)."""

    def __init__(self, client: Any) -> None:
        self.client = client
        self.futures: List[Any] = []

    def submit(self, *args: Any) -> Any:
        f = self.client.submit(run_point, *args, pure=False)
        self.futures.append(f)
        return f

    def as_completed(self, futures: List[Any]) -> Iterator[Any]:
        from distributed import as_completed

        return as_completed(futures)

    @staticmethod
    def result(future: Any) -> Dict[str, Any]:
        return future.result()

    def close(self, cancel: bool) -> None:
        if cancel and self.futures:
            self.client.cancel(self.futures)


class _Ray:
    """Ray (``executor="ray"`` or the ``ray`` module): each point a remote task."""

    def __init__(self) -> None:
        import ray  # type: ignore[import-not-found]

        if not ray.is_initialized():
            ray.init()
        self.ray = ray
        self.remote = ray.remote(num_cpus=1)(run_point)
        self.refs: List[Any] = []

    def submit(self, *args: Any) -> Any:
        ref = self.remote.remote(*args)
        self.refs.append(ref)
        return ref

    def as_completed(self, futures: List[Any]) -> Iterator[Any]:
        left = list(futures)
        while left:
            done, left = self.ray.wait(left, num_returns=1)
            yield from done

    def result(self, future: Any) -> Dict[str, Any]:
        return self.ray.get(future)

    def close(self, cancel: bool) -> None:
        if cancel:
            for r in self.refs:
                self.ray.cancel(r)


def _backend(executor: Any, workers: Optional[int], threads: int) -> Tuple[Any, bool]:
    """The backend of ``executor`` and whether the sweep owns it (and shuts it down)."""
    if executor is None or executor == "processes":
        return _Local(workers, threads), True
    if executor == "ray" or getattr(executor, "__name__", None) == "ray":
        return _Ray(), False
    mod = type(executor).__module__
    if mod.startswith("distributed") and hasattr(executor, "submit"):
        return _Dask(executor), False
    if isinstance(executor, cf.Executor):
        return _Futures(executor), False
    raise TypeError(
        "executor: None (local processes), a concurrent.futures.Executor, a dask.distributed.Client or 'ray'"
    )


def _load_finished(path: Path) -> Dict[str, Dict[str, Any]]:
    """The finished points of an earlier sweep in ``path``, by key; a line cut off by an
    interruption is skipped (its point runs again)."""
    done: Dict[str, Dict[str, Any]] = {}
    if not path.exists():
        return done
    for line in path.read_text().splitlines():
        try:
            rec = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(rec, dict) and "key" in rec:
            done[rec["key"]] = rec
    return done


def sweep(
    base: Union[Scene, Mapping[str, Any], PathLike],
    axes: Optional[Mapping[str, Sequence[Any]]] = None,
    points: Optional[Iterable[Mapping[str, Any]]] = None,
    executor: Any = None,
    out_dir: Optional[PathLike] = None,
    models: Union[None, str, Sequence[str]] = None,
    *,
    keep_files: bool = False,
    threads: int = 1,
    workers: Optional[int] = None,
    max_steps: Optional[int] = None,
    on_point: Optional[Callable[[pd.DataFrame], Any]] = None,
) -> pd.DataFrame:
    """Runs ``base`` at every point of a parameter study and returns one DataFrame of summary
    figures, one row per point and model.

    ``axes`` maps field paths to values and sweeps their product, e.g.
    ``{"strand.friction": [0.1, 0.3], "strand.layers[0].lay_angle_deg": [12, 20]}``; or
    ``points`` lists the points as dicts of field paths. Every point's scene is built and
    validated before anything runs: a path that is not in the scene, or a value the validator
    rejects, raises ``SceneError`` naming the path and the point.

    ``executor``: ``None`` for local processes (``workers`` of them, default cores /
    ``threads``), a ``concurrent.futures.Executor``, a ``dask.distributed.Client`` (the points
    run on its cluster), or ``"ray"``. Each point runs its Rust code on ``threads`` threads.

    Columns: ``point``, ``key``, the field paths, ``model``, ``status`` (``ok``/``failed``),
    ``reason`` and ``error`` of a failure, ``tip_x``, ``tip_y``, ``tip_z`` (m), the figures of
    ``summary.json`` (``wall_time_s``, ``energy_balance_error``, ``dissipated``, ...) and
    ``point_wall_time_s`` (the point's time in its worker). A point that fails, or whose
    worker raises, is a row with its reason: the sweep goes on.

    ``out_dir``: each finished point is appended to ``out_dir/results.jsonl`` as it completes
    (with ``keep_files``, its files go to ``out_dir/points/<key>/``, which a cluster's workers
    must be able to reach); a sweep run again with the same ``out_dir`` reads it and runs only
    the points not finished. The whole table is also written to ``out_dir/results.csv`` at the
    end. ``on_point(rows)`` is called with each finished point's rows.
    """
    sc = Scene.coerce(base)
    names = [models] if isinstance(models, str) else list(models or [])
    if threads < 1:
        raise ValueError("threads must be at least 1")
    if keep_files and out_dir is None:
        raise ValueError("keep_files needs an out_dir")
    plan = _points(axes, points)
    scenes = []
    for i, p in enumerate(plan):
        try:
            scenes.append(sc.with_values(p).to_dict())
        except SceneError as e:
            err = SceneError(f"sweep point {i} {p}: {e}")
            err.field = getattr(e, "field", "")
            raise err from None
    if names:
        missing = [m for m in names if m not in sc.models]
        if missing:
            raise ValueError(f"models: the scene has no models.{missing[0]}")
    keys = [point_key(s, names, max_steps) for s in scenes]

    out = Path(out_dir) if out_dir is not None else None
    finished: Dict[str, Dict[str, Any]] = {}
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        finished = _load_finished(out / RESULTS_FILE)
    first: Dict[str, int] = {}
    for i, key in enumerate(keys):
        first.setdefault(key, i)  # a point repeated in the plan runs once
    records: Dict[int, Dict[str, Any]] = {i: finished[k]["record"] for k, i in first.items() if k in finished}
    todo = [i for k, i in first.items() if k not in finished]

    if todo:
        backend, owned = _backend(executor, workers, threads)
        results_file = open(out / RESULTS_FILE, "a") if out is not None else None
        cancel = True
        try:
            futures = {}
            for i in todo:
                files = str(out / "points" / keys[i]) if (out is not None and keep_files) else None
                futures[backend.submit(scenes[i], names, threads, max_steps, files)] = i
            if isinstance(backend, _Futures):
                backend.pending = list(futures)
            for f in backend.as_completed(list(futures)):
                i = futures[f]
                try:
                    record = backend.result(f)
                except Exception as e:  # the worker died or the task was lost
                    record = {"error": f"{type(e).__name__}: {e}", "wall_time_s": None}
                records[i] = record
                if results_file is not None:
                    line = {"key": keys[i], "params": plan[i], "record": record}
                    results_file.write(json.dumps(line) + "\n")
                    results_file.flush()
                    os.fsync(results_file.fileno())
                if on_point is not None:
                    on_point(pd.DataFrame(_rows(i, keys[i], plan[i], record)))
            cancel = False
        finally:
            if results_file is not None:
                results_file.close()
            if owned:
                backend.close(cancel)
            elif cancel:
                backend.close(True)

    rows: List[Dict[str, Any]] = []
    for i, key in enumerate(keys):
        rec = records[first[key]]
        rows.extend(_rows(i, key, plan[i], rec))
    df = pd.DataFrame(rows)
    if out is not None:
        df.to_csv(out / TABLE_FILE, index=False)
    return df
