"""Commands timed against their baselines, each a fresh process, the candidates timed
in turn so that a shared machine's slow spells fall on all of them alike: ``verify``
and ``make run``'s job against a plain SymPy script, the command line's start against
``import sympy``, and two local Dask workers against one process and against two plain
processes side by side (the machine's own limit), on compliant runs and on closed-form
draws. :mod:`rigidimpact.analyses.bench` runs them in the full bench.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from rigidimpact.lazy import SHORT_RUN_THRESHOLD
from rigidimpact.outputs.workers import REPAYS
from rigidimpact.symbolic.distributions import combine

__all__ = ["verify_against_plain", "run_against_plain", "start_against_sympy",
           "dask_against_one", "dask_draws_against_one", "CRADLE_SCENE", "PLAIN_BARBELL"]


def _interleaved(candidates: dict[str, Callable[[], Any]], repeats: int) -> dict[str, float]:
    """Median time of each candidate, timed in turn (A, B, C, A, B, C, ...) so that a
    shared machine's slow spells fall on all of them alike."""
    samples: dict[str, list[float]] = {k: [] for k in candidates}
    for _ in range(repeats):
        for name, fn in candidates.items():
            start = time.perf_counter()
            fn()
            samples[name].append(time.perf_counter() - start)
    return {k: statistics.median(v) for k, v in samples.items()}


# the command as its console script runs it, in a fresh Python (output captured)
COMMAND = "from rigidimpact.__main__ import run\nrun({argv!r})"

PLAIN_BARBELL = """
import sympy as sp
m, M, L, th, e, v = sp.symbols("m M L theta e v_ix", positive=True)
vf, V, w = sp.symbols("v_fx V_x omega_z")
laws = [sp.Eq(m * v, m * vf + 2 * M * V),                      # (1)
        sp.Eq(0, 2 * M * L**2 * w - 2 * M * L * V * sp.sin(th)),  # (2)
        sp.Eq(V + L * w * sp.sin(th) - vf, e * v)]                # (4)
s = sp.solve(laws, [vf, V, w], dict=True)[0]
kinetic = m * s[vf]**2 / 2 + M * s[V]**2 + M * L**2 * s[w]**2
print(sp.simplify((m * v**2 / 2 - kinetic) / (m * v**2 / 2)))
"""


def _python(script: str, stdin: str = "", limit: float = 60.0) -> float | None:
    """Wall time of a fresh Python running `script`, or None past `limit` seconds."""
    import subprocess
    import sys

    start = time.perf_counter()
    try:
        subprocess.run([sys.executable, "-c", script], input=stdin, text=True, check=True,
                       capture_output=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return None
    return time.perf_counter() - start


def verify_against_plain(repeats: int = 3) -> dict[str, float]:
    """``rigidimpact verify`` end to end against a plain SymPy script that solves only the
    barbell (eqs. 1, 2 and 4) and simplifies its energy loss; medians of fresh processes."""
    times = _interleaved({  # in turn, so a slow spell of the machine falls on both
        "ours": lambda: _python(COMMAND.format(argv=['verify'])),
        "plain": lambda: _python(PLAIN_BARBELL)}, repeats)
    return {"verify_s": times["ours"], "plain_barbell_s": times["plain"],
            "ratio": times["ours"] / times["plain"]}


def run_against_plain(repeats: int = 1, limit: float = 900.0) -> dict[str, float] | None:
    """``make run``'s job (``derivations/run_all.py``: every derivation, ``verify``, the
    LaTeX, the figures and animations, its result cache off) end to end against the
    plain SymPy barbell script, timed in turn; None where the package runs outside its
    repository (no ``derivations/`` beside ``src/``) or the job runs past `limit` s."""
    import os
    import subprocess
    import sys
    import tempfile

    script = Path(__file__).resolve().parents[3] / "derivations" / "run_all.py"
    if not script.is_file():
        return None
    env = {**os.environ, "RIGIDIMPACT_CACHE": "off"}
    with tempfile.TemporaryDirectory() as out:
        def job() -> None:
            subprocess.run([sys.executable, str(script), "--out", out], check=True,
                           capture_output=True, timeout=limit, env=env)

        try:
            times = _interleaved({"run": job, "plain": lambda: _python(PLAIN_BARBELL)},
                                 repeats)
        except subprocess.TimeoutExpired:
            return None
    return {"run_s": times["run"], "plain_barbell_s": times["plain"],
            "ratio": times["run"] / times["plain"]}


def start_against_sympy(repeats: int = 3) -> dict[str, float]:
    """The command line's start against importing SymPy alone: ``rigidimpact --help`` and
    ``rigidimpact derive barbell`` (derived afresh: its result cache off) beside
    ``python -c "import sympy"``; medians of fresh processes, timed in turn.

    The command runs as a process of its own (:func:`rigidimpact.__main__.run`), which tunes
    Python's cyclic collector for a short run; ``import sympy`` is timed twice, as
    Python runs it and under the same collector settings, so that the ratio against the
    second (``derive_ratio_same_collector``) says what the package's own work costs."""
    import os

    collector = (f"import gc\ngc.set_threshold({SHORT_RUN_THRESHOLD}, "
                 "*gc.get_threshold()[1:])\nimport sympy\ngc.freeze()")
    kept = os.environ.get("RIGIDIMPACT_CACHE")
    os.environ["RIGIDIMPACT_CACHE"] = "off"  # the children's: each derives afresh
    try:
        times = _interleaved({
            "derive": lambda: _python(COMMAND.format(argv=["derive", "barbell"])),
            "help": lambda: _python(COMMAND.format(argv=["--help"])),
            "sympy": lambda: _python("import sympy"),
            "collector": lambda: _python(collector)}, repeats)
    finally:
        if kept is None:
            del os.environ["RIGIDIMPACT_CACHE"]
        else:
            os.environ["RIGIDIMPACT_CACHE"] = kept
    return {"derive_barbell_s": times["derive"], "help_s": times["help"],
            "import_sympy_s": times["sympy"],
            "derive_ratio": times["derive"] / times["sympy"],
            "help_ratio": times["help"] / times["sympy"],
            "import_sympy_same_collector_s": times["collector"],
            "derive_ratio_same_collector": times["derive"] / times["collector"]}


CRADLE_SCENE = """title = "Three-ball cradle through the compliant contact"
[values]
e = 0.9
[[bodies]]
name = "first"
shape = "sphere"
mass = "1"
radius = "1/2"
position = ["-1/2", "0"]
velocity = ["1", "0"]
[[bodies]]
name = "middle"
shape = "sphere"
mass = "1"
radius = "1/2"
position = ["1/2", "0"]
[[bodies]]
name = "last"
shape = "sphere"
mass = "1"
radius = "1/2"
position = ["3/2", "0"]
[[contacts]]
name = "left"
bodies = ["first", "middle"]
point = ["0", "0"]
restitution = "e"
[[contacts]]
name = "right"
bodies = ["middle", "last"]
point = ["1", "0"]
restitution = "e"
[impact]
rule = "compliant"
"""


def dask_against_one(repeats: int = 3, solves: int = 1000) -> dict[str, float] | None:
    """What two local Dask workers gain on this machine, and what two cores could gain
    at most on the same work: `solves` compliant runs of a three-ball cradle
    (``rigidimpact sweep`` over its restitution) in one process, on ``--workers 2``,
    and as two independent processes side by side, each sweeping half (no Dask: the
    machine's own limit, which counts what two busy cores cost each other). Each a
    whole fresh command, the three timed in turn; medians. The one-process and the
    two-worker runs must give the same numbers, bit for bit (else RuntimeError). None
    without Dask; `solves` at least what repays starting local workers
    (:data:`rigidimpact.outputs.workers.REPAYS`), else ValueError."""
    import os
    import subprocess
    import sys
    import tempfile
    from concurrent.futures import ThreadPoolExecutor

    if solves < REPAYS["solves"]:
        raise ValueError(f"{solves} solves: local workers start for {REPAYS['solves']} "
                         "or more")
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        return None
    with tempfile.TemporaryDirectory(prefix="bench-dask-") as folder:
        scene = Path(folder) / "cradle.toml"
        scene.write_text(CRADLE_SCENE, encoding="utf-8")
        half = solves // 2
        # the whole grid of e from 0.1 to 1, and its two halves (the same sets)
        whole = f"e=0.1:1:{solves}"
        parts = [f"e=0.1:{0.1 + 0.9 * (half - 1) / (solves - 1)!r}:{half}",
                 f"e={0.1 + 0.9 * half / (solves - 1)!r}:1:{solves - half}"]

        def sweep(grid: str, out: str, *more: str) -> None:
            subprocess.run([sys.executable, "-m", "rigidimpact", "sweep", str(scene),
                            "--grid", grid, "--out", str(Path(folder) / out), "--json",
                            *more], check=True, capture_output=True, timeout=3600,
                           env={**os.environ, "RIGIDIMPACT_CACHE": "off"})

        def side_by_side() -> None:
            with ThreadPoolExecutor(2) as pool:
                list(pool.map(lambda k: sweep(parts[k], f"half{k}"), (0, 1)))

        times = _interleaved({"one": lambda: sweep(whole, "one"),
                              "workers": lambda: sweep(whole, "two", "--workers", "2"),
                              "apart": side_by_side}, repeats)
        for key in ("first.vx", "middle.vx", "last.vx"):  # the same numbers, bit for bit
            one, two = (np.load(Path(folder) / run / f"{key}.npy") for run in ("one", "two"))
            if not np.array_equal(one, two):
                raise RuntimeError(f"{key}: two Dask workers gave other numbers than one "
                                   "process")
    return {"solves": float(solves), "one_process_s": times["one"],
            "two_workers_s": times["workers"], "two_processes_apart_s": times["apart"],
            "dask_gain": times["one"] / times["workers"],
            "two_core_limit": times["one"] / times["apart"]}


HALF_DRAWS = """import json, sys
from rigidimpact.analyses.distributions import CHUNK
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.symbolic.distributions import chunk_sizes, draw_plan
from rigidimpact.symbolic.drawn import plan_run
scene = parse_scene(open(sys.argv[1], encoding="utf-8").read())
g = scene.derivation().results["barbell.vy"]
inputs = dict(scene.random.inputs)
values = {s: v for s, v in scene.values.items() if s not in inputs}
sizes = chunk_sizes(scene.random.samples, CHUNK)
start, stop = (0, len(sizes) // 2) if sys.argv[2] == "0" else (len(sizes) // 2, len(sizes))
plan = draw_plan(g, inputs, values)
print(json.dumps(plan_run(plan, scene.random.seed, start, sizes[start:stop])))
"""


def dask_draws_against_one(repeats: int = 3, samples: int = 10**9
                           ) -> dict[str, float] | None:
    """What two local Dask workers gain on the closed-form Monte Carlo, and what two
    cores could gain at most: ``rigidimpact derive`` of the dropped barbell
    (``derivations/random-barbell.toml``) with `samples` draws, in one process and on
    ``--workers 2``, and two independent processes side by side, each parsing and
    deriving the scene and drawing half of the same chunks (no Dask, no closed form:
    the machine's own limit on the draws). Each a fresh process, the three timed in
    turn; medians. The one-process and two-worker Monte Carlos must agree bit for bit,
    and the two halves' sums, added in order, must give the same mean (else
    RuntimeError). None without Dask or outside the repository; `samples` at least
    what repays starting local workers
    (:data:`rigidimpact.outputs.workers.REPAYS`), else ValueError."""
    import json
    import os
    import subprocess
    import sys
    import tempfile
    from concurrent.futures import ThreadPoolExecutor

    if samples < REPAYS["draws"]:
        raise ValueError(f"{samples} draws: local workers start for {REPAYS['draws']} "
                         "or more")
    shipped = Path(__file__).resolve().parents[3] / "derivations" / "random-barbell.toml"
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        return None
    if not shipped.is_file():
        return None
    text = shipped.read_text(encoding="utf-8")
    if "samples = 1000000\n" not in text:
        raise RuntimeError(f"{shipped.name}: no line 'samples = 1000000' to change")
    env = {**os.environ, "RIGIDIMPACT_CACHE": "off"}
    found: dict[str, list] = {"one": [], "workers": [], "apart": []}
    with tempfile.TemporaryDirectory(prefix="bench-draws-") as folder:
        scene = Path(folder) / "dropped.toml"
        scene.write_text(text.replace("samples = 1000000\n", f"samples = {samples}\n"),
                         encoding="utf-8")

        def derive(key: str, *more: str) -> None:
            done = subprocess.run([sys.executable, "-m", "rigidimpact", "derive",
                                   str(scene), "--json", *more], check=True,
                                  capture_output=True, text=True, timeout=3600, env=env)
            found[key].append(json.loads(done.stdout)["distributions"]["barbell.vy"]
                              ["monte_carlo"])

        def half(k: int) -> list:
            done = subprocess.run([sys.executable, "-c", HALF_DRAWS, str(scene), str(k)],
                                  check=True, capture_output=True, text=True,
                                  timeout=3600, env=env)
            return json.loads(done.stdout)

        def side_by_side() -> None:
            with ThreadPoolExecutor(2) as pool:
                parts = list(pool.map(half, (0, 1)))
            found["apart"].append(combine([tuple(x) for p in parts for x in p], samples))

        times = _interleaved({"one": lambda: derive("one"),
                              "workers": lambda: derive("workers", "--workers", "2"),
                              "apart": side_by_side}, repeats)
    def drawn(x: dict) -> dict:  # the numbers drawn, not who drew them
        return {k: v for k, v in x.items() if k != "workers"}

    one = drawn(found["one"][0])
    if any(drawn(x) != one for x in found["one"] + found["workers"]):
        raise RuntimeError("two Dask workers gave another Monte Carlo than one process")
    if any(x.get("workers") != 2 for x in found["workers"]):
        raise RuntimeError("--workers 2 did not draw on two Dask workers")
    if any(x["mean"] != one["mean"] for x in found["apart"]):
        raise RuntimeError("the two halves' draws gave another mean than one process")
    return {"samples": float(samples), "one_process_s": times["one"],
            "two_workers_s": times["workers"], "two_processes_apart_s": times["apart"],
            "dask_gain": times["one"] / times["workers"],
            "two_core_limit": times["one"] / times["apart"]}
