"""Results over a grid of parameter sets, chunk by chunk, in bounded memory.

``rigidimpact sweep`` evaluates a derivation's results at every point of a grid: the
product of ranges such as ``theta=0:pi/2:10000`` and ``M=0.1:10:10000`` (10^8 sets), the
other symbols fixed by ``--set`` or the scene's ``[values]``. The fused kernel
(:class:`rigidimpact.symbolic.numeric.Fused`) runs one chunk at a time: the inputs of a chunk are
made from its indices (the grid itself is never built), and each result is written
into a memory-mapped ``.npy`` file, so memory stays bounded however many sets there are.
The folder is written whole or not at all, with ``summary.json`` (the grid, each
result's least and greatest value and how many values were not finite, the time) and,
up to :data:`MAX_TABLE` sets, ``table.csv``: one row a set, the swept symbols' values
then each result (:func:`write_table`).

Examples
--------
>>> from rigidimpact.paper.problems import derive
>>> grid = parse_grid(["theta=0:pi/2:3"], {"theta": derive("barbell").symbols["theta"]})
>>> [round(float(x), 6) for x in grid["theta"]]
[0.0, 0.785398, 1.570796]
"""

from __future__ import annotations

import json
import shutil
import tempfile
import time
from collections.abc import Callable, Mapping, Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.outputs.atomic import replace_folder
from rigidimpact.outputs.workers import dask_client, guided, local_or_here
from rigidimpact.scenes.scene import load_scene
from rigidimpact.symbolic.expr import parse_expression
from rigidimpact.symbolic.numeric import fused

__all__ = ["parse_grid", "run_sweep", "sweep_block", "run_point_sweep", "point_block",
           "write_table", "MAX_SETS", "BLOCK", "MAX_POINTS", "POINTS", "MAX_TABLE", "TABLE"]

BLOCK = 1 << 20  # sets a Dask task
MAX_POINTS = 10**6  # scenes solved with numbers: each set is one solve (a compliant
POINTS = 64  # run takes about 0.1 s); sets a block in one process (a step of progress)
FEWEST = 8  # sets the smallest Dask task takes (its blocks shrink as the work ends)

MAX_SETS = 10**9  # beyond this a sweep runs for many minutes and writes 8 GB per result
MAX_TABLE = 10**6  # rows of table.csv at most (about 25 bytes a value); past it, .npy only
TABLE = "table.csv"


def parse_grid(specs: Sequence[str], symbols: Mapping[str, sp.Symbol]) -> dict[str, np.ndarray]:
    """``NAME=START:STOP:COUNT`` ranges (endpoints included; START and STOP are exact
    expressions such as ``pi/2``, read by the safe expression parser)."""

    grid: dict[str, np.ndarray] = {}
    for spec in specs:
        name, eq, text = spec.partition("=")
        name = name.strip()
        where = f"--grid {name or spec}"
        parts = text.split(":")
        if not eq or not name or len(parts) != 3:
            raise InputError("--grid", f"expected NAME=START:STOP:COUNT, got {spec!r}")
        if name not in symbols:
            raise InputError(where, f"not a symbol here; the symbols are "
                             f"{', '.join(sorted(symbols)) or 'none'}")
        if name in grid:
            raise InputError(where, "given twice")
        ends = []
        for part in parts[:2]:
            value = parse_expression(part, where)
            if not value.is_number or not value.is_real:
                raise InputError(where, f"{part!r} is not a real number")
            ends.append(float(value))
        try:
            count = int(parts[2])
        except ValueError:
            raise InputError(where, f"COUNT must be a whole number, got {parts[2]!r}") \
                from None
        if not 1 <= count <= MAX_SETS:
            raise InputError(where, f"COUNT must lie between 1 and {MAX_SETS:.0e}")
        grid[name] = np.linspace(ends[0], ends[1], count)
    total = int(np.prod([len(a) for a in grid.values()], dtype=object)) if grid else 0
    if total > MAX_SETS:
        raise InputError("--grid", f"{total:.2e} parameter sets; at most {MAX_SETS:.0e}")
    return grid


def run_sweep(results: Mapping[str, sp.Expr], grid: Mapping[str, np.ndarray],
              fixed: Mapping[str, float], folder: Path, backend: str = "numpy",
              progress: Callable[[int, int], None] | None = None,
              kept: Sequence[str] | None = None, workers: int | None = None,
              scheduler: str | None = None, processes: bool = True) -> dict[str, Any]:
    """Evaluate `results` over `grid` into ``folder/KEY.npy`` files; return the summary.
    With `kept`, only those keys are written; the others are evaluated for their
    statistics and warnings only (in a scratch folder removed at the end). With
    `workers` or a `scheduler` the grid is cut into blocks of :data:`BLOCK` sets, one
    Dask task each (:func:`sweep_block`), written in place as they come back: the
    same numbers as in one process, since each set is computed alone.

    Raises
    ------
    InputError
        A symbol with neither a range nor a value, or an output folder that cannot be
        written (see :func:`rigidimpact.outputs.atomic.replace_folder`).
    """

    kernel = fused(results, backend)
    missing = [n for n in kernel.arguments if n not in grid and n not in fixed]
    if missing:
        raise InputError("--set", f"give a range (--grid) or a value (--set) for "
                         f"{', '.join(missing)}")
    unused = sorted(set(grid) - set(kernel.arguments))
    if unused:
        raise InputError(f"--grid {unused[0]}", "the results do not depend on it")
    shape = tuple(len(a) for a in grid.values())
    total = int(np.prod(shape)) if shape else 1
    need = 8 * total * len(kernel.keys)
    parent = Path(folder).resolve().parent
    while not parent.exists():
        parent = parent.parent
    free = shutil.disk_usage(parent).free
    if need > 0.9 * free:
        raise InputError("--out", f"the results need {need / 1e9:.1f} GB and "
                         f"{str(parent)!r} has {free / 1e9:.1f} GB free; sweep fewer sets "
                         "or fewer --keys")
    workers, note = local_or_here(total, "sets", workers, scheduler)
    summary: dict[str, Any] = {"workers": note} if note else {}

    written = [k for k in kernel.keys if kept is None or k in kept]
    scratch = tempfile.TemporaryDirectory(prefix="sweep-") if len(written) < len(
        kernel.keys) else None

    def fill(staging: Path) -> list[str]:
        outputs = {k: np.lib.format.open_memmap(
            (staging if k in written or scratch is None else Path(scratch.name))
            / f"{k}.npy", mode="w+", dtype=np.float64, shape=(total,))
            for k in kernel.keys}
        start = time.perf_counter()
        grid_or_point = dict(grid) if grid else {}
        if grid_or_point and (workers is not None or scheduler is not None):
            with dask_client(workers, scheduler, processes) as client:
                from dask.distributed import as_completed

                blocks = [(start, min(start + BLOCK, total))
                          for start in range(0, total, BLOCK)]
                futures = {client.submit(sweep_block, dict(results), grid_or_point,
                                         dict(fixed), backend, a, b, pure=False): (a, b)
                           for a, b in blocks}
                done = 0
                for future in as_completed(futures):
                    a, b = futures[future]
                    for k, values in future.result().items():
                        outputs[k][a:b] = values
                    done += b - a
                    if progress:
                        progress(done, total)
        elif grid_or_point:
            kernel.sweep(grid_or_point, fixed, outputs, progress)
        else:
            one = kernel(**fixed)
            for k in kernel.keys:
                outputs[k][:] = one[k].reshape(-1)
        seconds = time.perf_counter() - start
        stats = {}
        for k, out in outputs.items():
            stats[k] = _stats(out)
            out.flush()
        summary.update({
            "grid": {n: {"start": float(a[0]), "stop": float(a[-1]), "count": len(a)}
                     for n, a in grid.items()},
            "fixed": {n: float(v) for n, v in fixed.items() if n in kernel.arguments},
            "order": list(grid), "shape": list(shape), "sets": total, "backend": backend,
            "seconds": seconds, "sets_per_s": total / seconds if seconds > 0 else None,
            "results": stats, "warnings": sweep_warnings(stats, total)})
        table = write_table(staging / TABLE, grid, {k: outputs[k] for k in written})
        summary["table"] = TABLE if table else None
        del outputs
        (staging / "summary.json").write_text(json.dumps(summary, indent=2) + "\n",
                                              encoding="utf-8")
        return [f"{k}.npy" for k in written] + ["summary.json"] + ([TABLE] if table else [])

    try:
        replace_folder(Path(folder), fill, (".npy", ".json", ".csv"))
    finally:
        if scratch is not None:
            scratch.cleanup()
    return summary


def sweep_block(results: Mapping[str, sp.Expr], grid: Mapping[str, np.ndarray],
                fixed: Mapping[str, float], backend: str, start: int,
                stop: int) -> dict[str, np.ndarray]:
    """Sets `start` to `stop` of the grid (flat, the last range fastest), every result
    at each: one Dask task of :func:`run_sweep`, its fused kernel built where it runs.
    The block is run in the kernel's own chunks, which line up with the one-process
    sweep's (a block starts at a multiple of the chunk), so every number is the same."""
    kernel = fused(results, backend)
    names = list(grid)
    axes = [np.asarray(grid[n], dtype=np.float64) for n in names]
    shape = tuple(len(a) for a in axes)
    out = {k: np.empty(stop - start) for k in kernel.keys}
    targets = [out[k] for k in kernel.keys]

    def work(a: int, b: int) -> None:
        coordinates = np.unravel_index(np.arange(start + a, start + b), shape)
        chunk = {n: x[c] for n, x, c in zip(names, axes, coordinates, strict=True)}
        inputs = [chunk[n] if n in chunk else float(fixed[n]) for n in kernel.arguments]
        kernel._run(inputs, [t[a:b] for t in targets])

    kernel._chunks(stop - start, work, None)
    return out


@lru_cache(maxsize=8)
def _scene(path: str, stamp: float) -> Any:
    """The scene at `path` as last modified at `stamp`, read once a process (a worker
    runs many blocks of one sweep)."""
    return load_scene(path)


def point_block(path: str, grid: Mapping[str, np.ndarray], fixed: Mapping[str, float],
                start: int, stop: int) -> dict[str, np.ndarray]:
    """Sets `start` to `stop` of the grid, each solved with numbers by the scene at
    `path` (its rule: the compliant one, or several contacts): one task of
    :func:`run_point_sweep`, the scene read where it runs. Every result key a set
    gives, as an array over the sets."""
    scene = _scene(path, Path(path).stat().st_mtime)
    names = list(grid)
    axes = [np.asarray(grid[n], dtype=np.float64) for n in names]
    shape = tuple(len(a) for a in axes)
    coordinates = np.unravel_index(np.arange(start, stop), shape)
    rows = []
    for k in range(stop - start):
        values: dict[str, Any] = {s.name: v for s, v in scene.values.items()}
        values.update({n: sp.Float(v, 17) for n, v in fixed.items()})
        values.update({n: sp.Float(float(a[c[k]]), 17)
                       for n, a, c in zip(names, axes, coordinates, strict=True)})
        sources = {n: f"--set {n}" for n in fixed} | {n: f"--grid {n}" for n in names}
        rows.append(scene.evaluate(values, sources, None).numbers)
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def run_point_sweep(path: str, grid: Mapping[str, np.ndarray], fixed: Mapping[str, float],
                    folder: Path, progress: Callable[[int, int], None] | None = None,
                    workers: int | None = None, scheduler: str | None = None,
                    processes: bool = True) -> dict[str, Any]:
    """A sweep of a scene that has no closed form (the compliant rule, several
    contacts): every set of `grid` solved with numbers, in this process (:data:`POINTS`
    sets a step of progress) or on Dask workers (`workers`, `scheduler`; blocks that
    shrink as the work ends, :func:`rigidimpact.outputs.workers.guided`), into
    ``folder/KEY.npy`` and ``summary.json`` as :func:`run_sweep` writes them. Each set is
    solved alone, so the numbers do not depend on where."""
    shape = tuple(len(a) for a in grid.values())
    total = int(np.prod(shape)) if shape else 1
    if total > MAX_POINTS:
        raise InputError("--grid", f"{total} sets, each a solve of its own: past the "
                         f"budget of {MAX_POINTS} for a scene without a closed form")
    point_block(path, grid, fixed, 0, 1)  # a bad value is said here, before any worker
    workers, note = local_or_here(total, "solves", workers, scheduler)
    parts: dict[tuple[int, int], dict[str, np.ndarray]] = {}
    start = time.perf_counter()
    if workers is None and scheduler is None:
        blocks = [(a, min(a + POINTS, total)) for a in range(0, total, POINTS)]
        for a, b in blocks:
            parts[a, b] = point_block(path, grid, fixed, a, b)
            if progress:
                progress(b, total)
    else:
        with dask_client(workers, scheduler, processes) as client:
            from dask.distributed import as_completed

            # blocks that shrink as the work ends, the last ones a few solves each
            count = len(client.scheduler_info().get("workers", {})) or 1
            blocks = guided(total, count, least=FEWEST)
            futures = {client.submit(point_block, path, dict(grid), dict(fixed), a, b,
                                     pure=False): (a, b) for a, b in blocks}
            done = 0
            for future in as_completed(futures):
                parts[futures[future]] = future.result()
                done += futures[future][1] - futures[future][0]
                if progress:
                    progress(done, total)
    seconds = time.perf_counter() - start
    keys = list(parts[blocks[0]])
    arrays = {k: np.concatenate([parts[block][k] for block in blocks]) for k in keys}
    stats = {k: _stats(v) for k, v in arrays.items()}
    summary = {"grid": {n: {"start": float(a[0]), "stop": float(a[-1]), "count": len(a)}
                        for n, a in grid.items()},
               "fixed": dict(fixed), "order": list(grid), "shape": list(shape),
               "sets": total, "backend": "solve a set at a time", "seconds": seconds,
               "sets_per_s": total / seconds if seconds > 0 else None,
               "results": stats, "warnings": sweep_warnings(stats, total),
               **({"workers": note} if note else {})}

    def fill(staging: Path) -> list[str]:
        for k, v in arrays.items():
            np.save(staging / f"{k}.npy", v)
        table = write_table(staging / TABLE, grid, arrays)
        summary["table"] = TABLE if table else None
        (staging / "summary.json").write_text(json.dumps(summary, indent=2) + "\n",
                                              encoding="utf-8")
        return [f"{k}.npy" for k in keys] + ["summary.json"] + ([TABLE] if table else [])

    replace_folder(Path(folder), fill, (".npy", ".json", ".csv"))
    return summary


def write_table(path: Path, grid: Mapping[str, np.ndarray], results: Mapping[str, np.ndarray],
                block: int = 1 << 16) -> bool:
    """Write ``path`` as CSV: a header of the swept symbols then the result keys, one row
    a set in the grid's flat order (the last range fastest), each number in its shortest
    form that reads back exactly; a value that is not finite is ``nan``, ``inf`` or
    ``-inf``.
    Nothing is written past :data:`MAX_TABLE` sets (False); the ``.npy`` files hold them.

    Examples
    --------
    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> write_table(folder / "t.csv", {"x": np.array([0.0, 0.5])}, {"y": np.array([1.0, 2.0])})
    True
    >>> print((folder / "t.csv").read_text(), end="")
    x,y
    0.0,1.0
    0.5,2.0
    """
    names = list(grid)
    shape = tuple(len(a) for a in grid.values())
    total = int(np.prod(shape)) if shape else 1
    if total > MAX_TABLE:
        return False
    axes = [np.asarray(grid[n], dtype=np.float64) for n in names]
    with open(path, "w", encoding="utf-8", newline="") as out:
        out.write(",".join([*names, *results]) + "\n")
        for start in range(0, total, block):
            stop = min(start + block, total)
            coordinates = np.unravel_index(np.arange(start, stop), shape) if shape else ()
            columns = [a[c] for a, c in zip(axes, coordinates, strict=True)]
            columns += [np.asarray(v[start:stop], dtype=np.float64) for v in results.values()]
            out.writelines(",".join(map(repr, row)) + "\n"
                           for row in np.column_stack(columns).tolist())
    return True


NEGATIVE = 1e-12  # below this a value counts as negative (a warning), not as rounding


def _stats(values: np.ndarray, block: int = 1 << 22) -> dict[str, Any]:
    """Least and greatest finite value and the count of values that are not finite,
    read block by block (the array may be larger than memory)."""
    low, high, bad, negative = np.inf, -np.inf, 0, 0
    for start in range(0, len(values), block):
        part = np.asarray(values[start:start + block])
        finite = np.isfinite(part)
        bad += int(part.size - finite.sum())
        negative += int(np.count_nonzero(part[finite] < -NEGATIVE))
        if finite.any():
            low, high = min(low, float(part[finite].min())), max(high, float(part[finite].max()))
    return {"min": low if np.isfinite(low) else None,
            "max": high if np.isfinite(high) else None, "not_finite": bad,
            "negative": negative}


def sweep_warnings(stats: Mapping[str, Mapping[str, Any]], sets: int) -> list[str]:
    """What `evaluate` would warn at each point, counted over the grid: kinetic energy
    created (a negative energy lost) and contacts that would have to pull (a negative
    normal impulse), beyond rounding (1e-12).

    Examples
    --------
    >>> sweep_warnings({"energy_loss_fraction": {"negative": 3, "min": -0.165}}, 100)
    ['kinetic energy is created at 3 of 100 parameter sets (down to -0.165 of the energy before): the model cannot honour the physics there']
    """  # noqa: E501
    found = []
    for key, stat in stats.items():
        if not stat.get("negative"):
            continue
        if key == "energy_loss_fraction":
            found.append(f"kinetic energy is created at {stat['negative']} of {sets} "
                         f"parameter sets (down to {stat['min']:.6g} of the energy before): "
                         "the model cannot honour the physics there")
        elif key.endswith("normal_impulse") or key == "impulse":
            found.append(f"{key} is negative at {stat['negative']} of {sets} parameter "
                         f"sets (down to {stat['min']:.6g}): the contact would have to "
                         "pull; the model cannot honour the physics there")
    return found
