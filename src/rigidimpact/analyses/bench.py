"""What accuracy costs in time: every way the toolkit computes the ball-barbell collision.

All methods run side by side in one process, on one problem (``derivations/barbell.toml``:
m = 1, M = 2, L = 0.5, theta = 30 deg, e = 0.5, v_ix = 1, and for the re-strike theta = 10
deg, e = 0, m = M). Each row is a method at one setting, with its error against the exact
answer and the median of repeated wall-clock timings. The families:

* ``symbolic``: the exact results, substituted and evaluated to 17 digits by SymPy;
* ``float64``: the vectorised kernel (one point per call);
* ``mpmath``: the same stable form at several precisions;
* ``compliant``: the compliant simulation (rod and contact springs) over a grid of
  contact stiffness, rod stiffness (1e2 and 1e4 times the contact's), integrator and
  tolerance — its error against the rigid closed form is mostly the model's own;
* ``integration``: the compliant scene at fixed stiffness, each integrator and rtol
  against a tightly converged run of the same model: the error the settings control;
  the ``auto`` row is what ``simulate`` picks for the scene's tolerance;
* ``restrike-event``, ``restrike-sweep`` and ``restrike-fixed-step``: the re-strike time by
  the certified event search, by the vectorised sweep over 10^4 initial angles (time per
  angle), and by fixed-step time marching (stopping at the first crossing, which is
  interpolated linearly);
* ``pymunk``: the same collision in a game-physics engine, when it is installed.

Errors are the largest relative error over v_fx, V_x and omega_z (the turn at the
re-strike for the re-strike rows). An error of 0 is drawn at ``FLOOR``.

Examples
--------
>>> rows = [r for r in run_bench(quick=True, families=("float64", "mpmath"))["rows"]]
>>> sorted({r["method"] for r in rows})
['float64', 'mpmath']
"""

from __future__ import annotations

import functools
import math
import statistics
import time
from collections.abc import Callable, Iterable
from dataclasses import replace
from pathlib import Path
from typing import Any

import mpmath
import numpy as np
import sympy as sp

from rigidimpact.analyses import restrike
from rigidimpact.analyses.baselines import (
    CRADLE_SCENE,
    _interleaved,
    dask_against_one,
    dask_draws_against_one,
    run_against_plain,
    start_against_sympy,
    verify_against_plain,
)
from rigidimpact.analyses.contacts import contacts_family, rough_exact_against_floating
from rigidimpact.errors import InputError
from rigidimpact.outputs.atomic import write_file
from rigidimpact.outputs.plots import accuracy_vs_time
from rigidimpact.paper.problems import derive
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.simulate import run
from rigidimpact.simulate.flight import first_contact
from rigidimpact.simulate.outcome import flyer
from rigidimpact.symbolic.notation import symbol
from rigidimpact.symbolic.numeric import fused, has_numba, kernels

__all__ = ["run_bench", "pareto", "throughput", "write_outputs", "symbolic_ladder",
           "verify_against_plain", "start_against_sympy", "dask_against_one",
           "dask_draws_against_one",
           "ladder_scene", "CRADLE_SCENE", "FAMILIES", "FLOOR"]

FLOOR = 1e-18
FAMILIES = ("symbolic", "float64", "mpmath", "compliant", "integration", "restrike-event",
            "restrike-sweep", "restrike-fixed-step", "pymunk", "ladder", "contacts")
KEYS = ("v_fx", "V_x", "omega_z")
VALUES = {"m": 1, "M": 2, "L": sp.Rational(1, 2), "theta": sp.pi / 6, "e": sp.Rational(1, 2),
          "v_ix": 1}

SCENE = """
title = "bench: ball strikes a barbell"
[values]
m = 1
M = 2
L = 0.5
theta = "30 deg"
e = 0.5
v_ix = 1
[[bodies]]
name = "ball"
shape = "particle"
mass = "m"
velocity = ["v_ix", "0"]
[[bodies]]
name = "barbell"
shape = "barbell"
mass = "M"
half_length = "L"
angle = "theta"
[contact]
bodies = ["ball", "barbell"]
restitution = "e"
[simulate]
effects = ["rod-compliance", "contact-compliance"]
"""


def _median_time(fn: Callable[[], Any], repeats: int, inner: int = 1) -> float:
    """Median over `repeats` of the mean time of `inner` calls."""
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(inner):
            fn()
        samples.append((time.perf_counter() - start) / inner)
    return statistics.median(samples)


REFERENCE_DIGITS = 260  # above the highest mpmath precision benchmarked (200)


def _exact() -> dict[str, mpmath.mpf]:
    results = derive("barbell").results
    subs = {symbol(k): v for k, v in VALUES.items()}
    with mpmath.workdps(REFERENCE_DIGITS):
        return {k: mpmath.mpf(str(sp.N(results[k].subs(subs), REFERENCE_DIGITS))) for k in KEYS}


def _error(values: dict[str, Any], exact: dict[str, mpmath.mpf]) -> float:
    with mpmath.workdps(REFERENCE_DIGITS):
        worst = max(abs(mpmath.mpf(values[k]) - exact[k]) / abs(exact[k]) for k in KEYS)
    return float(worst)


# what each family's error is measured on; the others answer the collision itself
PROBLEM = {"restrike-event": "restrike", "restrike-fixed-step": "restrike",
           "restrike-sweep": "restrike", "integration": "integration"}


def _row(method: str, setting: str, error: float, seconds: float, **extra: Any) -> dict:
    return {"method": method, "setting": setting, "error": error, "seconds": seconds,
            "problem": PROBLEM.get(method, "collision"), **extra}


def _timed_run(scene, repeats: int):
    """Run a scene; the median wall time over `repeats` runs, the first included.

    A run the simulation refuses (say, an integrator too loose to see the contact end)
    gives ``(None, message)``: the bench reports it rather than stopping.
    """
    start = time.perf_counter()
    try:
        outcome = run(scene)
    except InputError as exc:
        return None, str(exc)
    samples = [time.perf_counter() - start]
    samples += [_median_time(lambda: run(scene), 1) for _ in range(repeats - 1)]
    return outcome, statistics.median(samples)


def _symbolic(exact, repeats: int) -> list[dict]:
    results = derive("barbell").results
    subs = {symbol(k): v for k, v in VALUES.items()}

    def evaluate():
        return {k: sp.N(results[k].subs(subs), 17) for k in KEYS}

    values = {k: str(v) for k, v in evaluate().items()}
    return [_row("symbolic", "exact, then 17 digits", _error(values, exact),
                 _median_time(evaluate, repeats))]


def _float_values() -> dict[str, float]:
    return {k: float(v) for k, v in VALUES.items()}


def _float64(exact, repeats: int) -> list[dict]:
    compiled = kernels(derive("barbell").results)
    point = _float_values()

    def evaluate():
        return {k: compiled[k](**{n: point[n] for n in compiled[k].arguments}) for k in KEYS}

    values = {k: repr(float(v)) for k, v in evaluate().items()}
    return [_row("float64", "stable-form kernel, one point", _error(values, exact),
                 _median_time(evaluate, repeats, inner=200))]


def _mpmath(exact, repeats: int, precisions: Iterable[int]) -> list[dict]:
    compiled = kernels(derive("barbell").results)
    rows = []
    for dps in precisions:
        with mpmath.workdps(dps + 5):
            point = {k: mpmath.mpf(str(sp.N(v, dps + 5))) for k, v in VALUES.items()}

        def evaluate(dps=dps, point=point):
            return {k: compiled[k].mp(dps, **{n: point[n] for n in compiled[k].arguments})
                    for k in KEYS}

        rows.append(_row("mpmath", f"dps={dps}", _error(evaluate(), exact),
                         _median_time(evaluate, repeats, inner=20)))
    return rows


def _compliant_values(outcome) -> dict[str, float]:
    f = outcome.final
    return {"v_fx": f["ball.vx"], "V_x": f["barbell.vx"], "omega_z": f["barbell.omega"]}


def _scene(**table: Any):
    scene = parse_scene(SCENE, "bench")
    return replace(scene, simulate={**scene.simulate, **table})


def _compliant(exact, repeats: int, stiffnesses, rod_factors, methods, tolerances, progress,
               failed: list[dict]) -> list[dict]:
    rows = []
    for k_c in stiffnesses:
        for factor in rod_factors:
            for method in methods:
                for tol in tolerances:
                    k_rod = factor * k_c
                    setting = f"k_c={k_c:.0e}, k_rod={k_rod:.0e}, {method}, tol={tol:.0e}"
                    scene = _scene(contact_stiffness=k_c, rod_stiffness=k_rod,
                                   integrator=method, tolerance=tol)
                    outcome, seconds = _timed_run(scene, repeats)
                    if outcome is None:
                        failed.append({"method": "compliant", "setting": setting,
                                       "message": seconds})
                        progress(f"compliant {setting} (failed)")
                        continue
                    rows.append(_row("compliant", setting,
                                     _error(_compliant_values(outcome), exact), seconds,
                                     ode_steps=outcome.ode_steps))
                    progress(f"compliant {setting}")
    return rows


def _integration(repeats: int, methods, tolerances, progress, scene_tolerance: float,
                 failed: list[dict]):
    """Each integrator setting against a converged run of the same compliant model."""
    base = dict(contact_stiffness=1e5, rod_stiffness=1e8)
    converged = _compliant_values(run(_scene(**base, integrator="DOP853", tolerance=1e-12)))
    with mpmath.workdps(30):
        reference = {k: mpmath.mpf(v) for k, v in converged.items()}
    rows = []
    settings = [(m, t) for m in methods for t in tolerances] + [("auto", scene_tolerance)]
    for method, tol in settings:
        scene = _scene(**base, integrator=method, tolerance=tol)
        outcome, seconds = _timed_run(scene, repeats)
        if outcome is None:
            failed.append({"method": "integration", "setting": f"{method}, tol={tol:.0e}",
                           "message": seconds})
            progress(f"integration {method} tol={tol:.0e} (failed)")
            continue
        picked = outcome.details["integrator"]["method"]
        rows.append(_row("integration", f"{method}{' -> ' + picked if method == 'auto' else ''}"
                         f", tol={tol:.0e}", _error(_compliant_values(outcome), reference),
                         seconds, ode_steps=outcome.ode_steps, tolerance=tol,
                         auto=method == "auto"))
        progress(f"integration {method} tol={tol:.0e}")
    return rows


def _restrike_reference() -> tuple[float, mpmath.mpf]:
    angle = math.radians(10.0)
    with mpmath.workdps(40):
        return angle, restrike.restrike_turn(mpmath.radians(10), 0, 1)


def _restrike_flyers(angle: float):
    """Ball and barbell after a perfectly inelastic hit with m = M at `angle`, as numbers."""
    text = SCENE.replace("e = 0.5", "e = 0").replace("M = 2", "M = 1")
    scene = parse_scene(text, "restrike")
    values = {**scene.values, symbol("theta"): sp.Float(angle, 30)}
    solution = scene.impact().solve()
    return [flyer(b, values) for b in (solution.first_after, solution.second_after)]


def _restrike_event(repeats: int) -> list[dict]:
    angle, exact = _restrike_reference()
    ball, bar = _restrike_flyers(angle)
    hit = first_contact(ball, bar)
    assert hit is not None  # at 10 degrees the barbell strikes the ball again
    turn = hit.t * bar.spin
    with mpmath.workdps(40):
        error = float(abs(mpmath.mpf(turn) - exact) / exact)
    return [_row("restrike-event", "certified search", error,
                 _median_time(lambda: first_contact(ball, bar), repeats, inner=20))]


def _fixed_step_turn(angle: float, step: float, block: int = 1 << 20) -> float:
    """March the turn tau in fixed steps until the ball changes side of the rod (within
    reach), in blocks so memory stays bounded; the crossing is interpolated linearly."""
    k = 1.0  # e = 0: the ball drifts at omega L sin(theta) relative to C
    sin, cos = math.sin(angle), math.cos(angle)
    block = min(block, int(2.2 * np.pi / step) + 2)  # a coarse march needs no more
    start = 0
    while start * step < 2.2 * np.pi:
        tau = (np.arange(block + 1) + start + 1) * step
        px, py = -cos + k * tau * sin, -sin
        side = np.cos(angle + tau) * py - np.sin(angle + tau) * px
        inside = px * px + py * py <= 1.0
        change = np.flatnonzero((np.sign(side[1:]) != np.sign(side[:-1])) & inside[1:])
        if change.size:
            j = change[0]
            return float(tau[j] + step * side[j] / (side[j] - side[j + 1]))
        start += block
    raise ArithmeticError("no crossing: the angle is above the critical angle")


def _restrike_fixed(repeats: int, steps: Iterable[float]) -> list[dict]:
    angle, exact = _restrike_reference()
    rows = []
    for h in steps:
        turn = _fixed_step_turn(angle, h)
        with mpmath.workdps(40):
            error = float(abs(mpmath.mpf(turn) - exact) / exact)
        rows.append(_row("restrike-fixed-step", f"h={h:.0e}", error,
                         _median_time(functools.partial(_fixed_step_turn, angle, h),
                                      repeats if h >= 1e-5 else 1)))
    return rows


def _restrike_sweep(repeats: int, count: int = 10_000) -> list[dict]:
    """The vectorised sweep over `count` initial angles: time per angle, worst error at
    every 200th angle that is struck again (against the 40-digit turn)."""
    angles = np.radians(np.linspace(0.01, 179.99, count))
    swept = restrike.sweep(angles)
    sample = np.flatnonzero(swept.hit)[::200]
    with mpmath.workdps(40):
        worst = max(float(abs(mpmath.mpf(swept.turn[j]) - restrike.restrike_turn(angles[j]))
                          / restrike.restrike_turn(angles[j])) for j in sample)
    seconds = _median_time(lambda: restrike.sweep(angles), repeats)
    return [_row("restrike-sweep", f"{count} angles at once (time per angle)", worst,
                 seconds / count, total_seconds=seconds)]


def _pymunk(exact, repeats: int, steps: Iterable[float]) -> list[dict]:
    """The collision in pymunk: circles of radius 1e-3 for the ball and spheres."""
    try:
        import pymunk
    except ImportError:
        return []
    v = _float_values()
    m, big, half, angle, e = v["m"], v["M"], v["L"], v["theta"], v["e"]
    radius = 1e-3

    def collide(dt: float) -> dict[str, float]:
        space = pymunk.Space()
        space.iterations = 50
        ball = pymunk.Body(m, pymunk.moment_for_circle(m, 0, radius))
        ball.position = (-2 * radius - 1e-9, 0.0)
        ball.velocity = (v["v_ix"], 0.0)
        ball_shape = pymunk.Circle(ball, radius)
        ball_shape.elasticity, ball_shape.friction = e, 0.0
        bar = pymunk.Body(2 * big, 2 * big * half * half)
        bar.position = (half * math.cos(angle), half * math.sin(angle))
        spheres = []
        for sign in (-1, 1):  # spheres A and B, in the barbell's own frame
            shape = pymunk.Circle(bar, radius, offset=(sign * half, 0.0))
            shape.elasticity, shape.friction = 1.0, 0.0
            spheres.append(shape)
        bar.angle = angle
        space.add(ball, ball_shape, bar, *spheres)
        for _ in range(int(round(0.01 / dt))):
            space.step(dt)
        return {"v_fx": ball.velocity.x, "V_x": bar.velocity.x,
                "omega_z": bar.angular_velocity}

    rows = []
    for dt in steps:
        values = collide(dt)
        rows.append(_row("pymunk", f"dt={dt:.0e}, {pymunk.version}", _error(values, exact),
                         _median_time(functools.partial(collide, dt), repeats)))
    return rows


BARBELL_FOUR = ("v_fx", "V_x", "omega_z", "energy_loss_fraction")


def _barbell_sets(count: int) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(20070301)
    return {"m": rng.uniform(0.1, 10, count), "M": rng.uniform(0.1, 10, count),
            "theta": rng.uniform(0, np.pi, count), "e": rng.uniform(0, 1, count),
            "v_ix": np.ones(count), "L": np.ones(count)}


def _barbell_by_hand(m, M, theta, e, v_ix, L):
    """The four barbell results as a careful NumPy user writes them: the sine and the
    denominator of eq. (5) shared, the stable arrangements of the paper's forms."""
    s = np.sin(theta)
    k = m * (1 + s * s)
    d = 2 * M + k
    V = (1 + e) * m * v_ix / d
    return {"v_fx": v_ix * (k - 2 * M * e) / d, "V_x": V, "omega_z": V * s / L,
            "energy_loss_fraction": 2 * M * (1 - e) * (1 + e) / d}


def throughput(count: int = 10**6, repeats: int = 5,
               backends: Iterable[str] = ("numpy", "numba")) -> dict[str, float]:
    """All four barbell results over `count` parameter sets, side by side in one run.

    ``kernel_per_s``: the fused kernel (NumPy backend, chunked); ``numpy_per_s``:
    hand-written NumPy of the same four results over whole arrays; ``ratio``: fused time
    over hand-written time (below 1 is faster); ``per_result_per_s``: the four results
    through their separate kernels; ``numba_per_s`` (when numba is installed) and
    ``numba_speedup`` over hand-written NumPy; ``sine_bound_per_s``: np.sin alone over the
    same angles, one core, times the cores numba uses (the pace of one sine per set);
    ``max_difference``: the largest relative difference between the fused kernel and
    the hand-written results. With numba, the ``*_into_*`` keys time the loop and np.sin
    writing into memory given once (:meth:`Fused.into`), and ``sine_spread_per_s`` is
    np.sin spread over the loop's threads: how far the cores really scale.

    Examples
    --------
    >>> sorted(throughput(1000, 1, backends=("numpy",)))[:4]
    ['cores', 'kernel_per_s', 'max_difference', 'numpy_per_s']
    """
    results = derive("barbell").results
    four = {k: results[k] for k in BARBELL_FOUR}
    sets = _barbell_sets(count)
    kernel = fused(four)
    separate = kernels(four)

    def by_fused():
        return kernel(**sets)

    def by_hand():
        return _barbell_by_hand(**sets)

    def by_separate():
        return {k: c(**{n: sets[n] for n in c.arguments}) for k, c in separate.items()}

    def sine():
        return np.sin(sets["theta"])

    candidates = {"fused": by_fused, "hand": by_hand, "separate": by_separate, "sine": sine}
    numba_kernel = fused(four, "numba") if "numba" in backends and has_numba() else None
    if numba_kernel is not None:
        numba_kernel(**{k: v[:10] for k, v in sets.items()})  # compile before timing
        buffers = {k: np.empty(count) for k in numba_kernel.keys}
        sines = np.empty(count)

        def sine_spread():  # np.sin over the numba backend's threads and chunks
            numba_kernel._chunks(count, lambda a, b: np.sin(sets["theta"][a:b],
                                                            out=sines[a:b]), None)

        candidates |= {"numba": lambda: numba_kernel(**sets),
                       "numba_into": lambda: numba_kernel.into(buffers, **sets),
                       "sine_into": lambda: np.sin(sets["theta"], out=sines),
                       "sine_spread": sine_spread}
    times = _interleaved(candidates, repeats)
    fused_s, hand_s, separate_s, sine_s = (times[k] for k in ("fused", "hand", "separate",
                                                              "sine"))
    hand, got = by_hand(), by_fused()
    report = {"kernel_per_s": count / fused_s, "numpy_per_s": count / hand_s,
              "ratio": fused_s / hand_s, "per_result_per_s": count / separate_s,
              "sets": count, "cores": 1, "sine_bound_per_s": count / sine_s,
              # relative to the size of the inputs' terms (v_fx passes through zero)
              "max_difference": max(float(np.max(np.abs(got[k] - hand[k])
                                                 / np.maximum(np.abs(hand[k]), 1.0)))
                                    for k in BARBELL_FOUR)}
    if numba_kernel is not None:
        import numba

        numba_s, into_s = times["numba"], times["numba_into"]
        cores = numba.get_num_threads()
        bound_into = cores * count / times["sine_into"]
        report |= {"numba_per_s": count / numba_s, "numba_speedup": hand_s / numba_s,
                   "cores": cores, "sine_bound_per_s": cores * count / sine_s,
                   "numba_of_sine_bound": (count / numba_s) / (cores * count / sine_s),
                   # the same, with every output written into memory given once (no
                   # fresh pages to fault in and zero, for the loop or for np.sin)
                   "numba_into_per_s": count / into_s,
                   "sine_bound_into_per_s": bound_into,
                   "numba_into_of_sine_bound": (count / into_s) / bound_into,
                   # what np.sin itself reaches over the same threads: the cores' real
                   # parallel pace, which the ideal bound above assumes to be `cores` x
                   "sine_spread_per_s": count / times["sine_spread"],
                   "sine_spread_scaling": times["sine_into"] / times["sine_spread"],
                   "numba_into_of_sine_spread": times["sine_spread"] / into_s}
    return report


def pareto(rows: list[dict]) -> list[dict]:
    """The rows no other row beats in both error and time (ties kept), fastest first.

    Examples
    --------
    >>> [r["setting"] for r in pareto([_row("a", "x", 1e-3, 1.0), _row("a", "y", 1e-6, 2.0),
    ...                                  _row("a", "z", 1e-3, 3.0)])]
    ['x', 'y']
    """
    front: list[dict] = []
    for row in sorted(rows, key=lambda r: (r["seconds"], r["error"])):
        if not front or max(row["error"], FLOOR) < max(front[-1]["error"], FLOOR):
            front.append(row)
    return front


def auto_choice(rows: list[dict]) -> dict[str, Any]:
    """Does the automatic pick meet its tolerance within 2x the cheapest that does?"""
    auto = [r for r in rows if r.get("auto")]
    if not auto:
        return {}
    pick = auto[0]
    meeting = [r for r in rows if r["method"] == "integration" and not r.get("auto")
               and r["error"] <= pick["tolerance"]]
    cheapest = min(meeting, key=lambda r: r["seconds"]) if meeting else None
    return {"setting": pick["setting"], "tolerance": pick["tolerance"],
            "error": pick["error"], "seconds": pick["seconds"],
            "meets_tolerance": pick["error"] <= pick["tolerance"],
            "cheapest": None if cheapest is None else cheapest["setting"],
            "cheapest_seconds": None if cheapest is None else cheapest["seconds"],
            "cost_ratio": None if cheapest is None else pick["seconds"] / cheapest["seconds"]}


# ---- the symbolic ladder: derive time against the number of free symbols ---------------

LADDER_SCENE = """
[symbols]
phi = {{ real = true }}
[[bodies]]
name = "body1"
shape = "rigid"
mass = "{m_1}"
inertia = "{I_1}"
position = ["{R_1x}", "{R_1y}"]
velocity = ["{V_1ix}", "{V_1iy}"]
spin = "{omega_1iz}"
[[bodies]]
name = "body2"
shape = "rigid"
mass = "{m_2}"
inertia = "{I_2}"
position = ["{R_2x}", "{R_2y}"]
velocity = ["{V_2ix}", "{V_2iy}"]
spin = "{omega_2iz}"
[contact]
bodies = ["body1", "body2"]
normal = ["cos({phi})", "sin({phi})"]
restitution = "{e}"
tangential = "{tangential}"
"""
# the numbers a symbol takes while it is not yet free (the bodies approach along phi)
LADDER_NUMBERS = {"phi": "3/10", "e": "1/2", "m_1": "2", "m_2": "3", "V_1ix": "2",
                  "V_2ix": "-1", "R_1x": "-1", "R_2y": "1/2", "I_1": "1", "I_2": "2",
                  "R_1y": "1/4", "R_2x": "1", "V_1iy": "1/2", "V_2iy": "0",
                  "omega_1iz": "1", "omega_2iz": "-1"}
LADDER_ORDER = tuple(LADDER_NUMBERS)  # the tilt first, then the rest

PLAIN_LADDER = """
import sys, time
import sympy as sp
from rigidimpact.scenes.scene import parse_scene
impact = parse_scene(sys.stdin.read()).impact()
equations = [eq.as_sympy() for eq in impact.equations()]
start = time.perf_counter()
solved = sp.solve(equations, impact.unknowns, dict=True)[0]
simplified = [sp.simplify(x) for x in solved.values()]
print(time.perf_counter() - start)
"""

def ladder_scene(free: int, tangential: str = "smooth") -> str:
    """The two-body scene with its first `free` symbols (see ``LADDER_ORDER``) left free."""
    kept = set(LADDER_ORDER[:free])
    values = {name: (name if name in kept else number)
              for name, number in LADDER_NUMBERS.items()}
    return LADDER_SCENE.format(**values, tangential=tangential)


def _plain_solve_seconds(text: str, limit: float) -> float | None:
    """sympy.solve + simplify of the scene's own printed laws, timed inside a child."""
    import subprocess
    import sys

    try:
        done = subprocess.run([sys.executable, "-c", PLAIN_LADDER], input=text, text=True,
                              check=True, capture_output=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return None
    return float(done.stdout.strip().splitlines()[-1])


def symbolic_ladder(counts: Iterable[int] = (2, 4, 6, 8, 10, 12, 14, 16),
                    limit: float = 30.0, tangentials: Iterable[str] = ("smooth", "stick"),
                    progress: Callable[[str], None] | None = None) -> list[dict]:
    """Derive time against free symbols, beside plain SymPy on the same laws.

    Each row times ``Scene.derivation()`` in this process and, in a child process,
    ``sympy.solve`` of the same printed laws followed by ``simplify`` of every unknown
    (``None`` when it runs past `limit` seconds).
    """
    rows = []
    for tangential in tangentials:
        for free in counts:
            text = ladder_scene(free, tangential)
            start = time.perf_counter()
            parse_scene(text).derivation()
            ours = time.perf_counter() - start
            plain = _plain_solve_seconds(text, limit)
            rows.append({"free_symbols": free, "tangential": tangential, "derive_s": ours,
                         "plain_sympy_s": plain, "limit_s": limit})
            if progress is not None:
                progress(f"ladder {tangential} {free}")
    return rows


def run_bench(quick: bool = False, families: Iterable[str] = FAMILIES,
              progress: Callable[[int, int, str], None] | None = None) -> dict[str, Any]:
    """Run every family (or those named) and return ``{"rows", "throughput", ...}``."""
    families = tuple(families)
    unknown = set(families) - set(FAMILIES)
    if unknown:
        raise ValueError(f"unknown bench families: {sorted(unknown)}")
    started = time.perf_counter()
    repeats = 3 if quick else 5
    methods = ("DOP853", "LSODA") if quick else ("RK45", "DOP853", "Radau", "BDF", "LSODA")
    tolerances = (1e-4, 1e-8) if quick else (1e-3, 1e-5, 1e-7, 1e-9)
    stiffnesses = (1e4, 1e5) if quick else (1e3, 1e4, 1e5, 1e6)
    rod_factors = (1e3,) if quick else (1e2, 1e4)
    total = (len(stiffnesses) * len(rod_factors) * len(methods) * len(tolerances)
             * ("compliant" in families)
             + (len(methods) * len(tolerances) + 1) * ("integration" in families))
    done = [0]

    def tick(label: str) -> None:
        done[0] += 1
        if progress is not None:
            progress(done[0], total, label)

    exact = _exact()
    rows: list[dict] = []
    failed: list[dict] = []
    if "symbolic" in families:
        rows += _symbolic(exact, repeats)
    if "float64" in families:
        rows += _float64(exact, repeats)
    if "mpmath" in families:
        rows += _mpmath(exact, repeats, (15, 30, 50) if quick else (15, 30, 50, 100, 200))
    if "compliant" in families:
        rows += _compliant(exact, 1 if quick else 3, stiffnesses, rod_factors, methods,
                           tolerances, tick, failed)
    if "integration" in families:
        rows += _integration(1 if quick else 3, methods, tolerances, tick, 1e-6, failed)
    if "restrike-event" in families:
        rows += _restrike_event(repeats)
    if "restrike-sweep" in families:
        rows += _restrike_sweep(repeats)
    if "restrike-fixed-step" in families:
        rows += _restrike_fixed(repeats, (1e-2, 1e-3, 1e-4) if quick
                                else (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7))
    if "pymunk" in families:
        rows += _pymunk(exact, repeats, (1e-4,) if quick else (1e-3, 1e-4, 1e-5))
    fronts = {problem: pareto([r for r in rows if r["problem"] == problem])
              for problem in ("collision", "restrike", "integration")}
    report = {"rows": rows, "throughput": throughput(10**5 if quick else 10**7, repeats),
              "pareto": {problem: [[r["method"], r["setting"]] for r in front]
                         for problem, front in fronts.items()},
              "auto_choice": auto_choice(rows), "quick": quick, "failed": failed}
    report["pymunk"] = any(r["method"] == "pymunk" for r in rows)
    if "ladder" in families:
        report["ladder"] = symbolic_ladder((2, 8, 16) if quick else (2, 4, 6, 8, 10, 12, 14, 16),
                                           10.0 if quick else 30.0,
                                           ("smooth",) if quick else ("smooth", "stick"))
        report["verify_vs_plain"] = verify_against_plain(1 if quick else 3)
        report["start_vs_sympy"] = start_against_sympy(1 if quick else 5)
        if not quick:  # about 45 s a run: the full bench only
            report["run_vs_plain"] = run_against_plain(1)
            # three commands of 15 to 40 s each, three times: the full bench only
            report["dask_vs_one"] = dask_against_one(3)
            # the same for 10^9 draws: about 40, 20 and 20 s, three times
            report["dask_draws_vs_one"] = dask_draws_against_one(3)
    if "contacts" in families:
        report["contacts"] = contacts_family(quick)
        if not quick:  # about 15 s a round, three rounds: the full bench only
            report["rough_exact_vs_floating"] = rough_exact_against_floating(3)
    report["seconds"] = time.perf_counter() - started
    return report


def _dask_lines(report: dict[str, Any]) -> list[str]:
    """bench.md's paragraphs on Dask against one process (where the report has them).

    Examples
    --------
    >>> _dask_lines({"dask_draws_vs_one": {"samples": 1e9, "one_process_s": 40.0,
    ...     "two_workers_s": 25.0, "two_processes_apart_s": 20.0, "dask_gain": 1.6,
    ...     "two_core_limit": 2.0}})[1][:75]
    "Dask: 1,000,000,000 draws of the dropped barbell's rebound (`rigidimpact de"
    """
    lines: list[str] = []
    for key, work, command, share, unit in (
            ("dask_vs_one", "compliant runs of a three-ball cradle", "sweep",
             "sweeping half", "this work"),
            ("dask_draws_vs_one", "draws of the dropped barbell's rebound", "derive",
             "drawing half", "these draws")):
        dk = report.get(key)
        if dk:
            count = dk.get("solves", dk.get("samples"))
            lines += ["", f"Dask: {count:,.0f} {work} (`rigidimpact {command}`) took "
                          f"{dk['one_process_s']:.1f} s in one process and "
                          f"{dk['two_workers_s']:.1f} s on `--workers 2` (gain "
                          f"{dk['dask_gain']:.2f}); two independent processes, each "
                          f"{share}, took {dk['two_processes_apart_s']:.1f} s side by "
                          f"side: two cores here gain at most "
                          f"{dk['two_core_limit']:.2f} on {unit}."]
    return lines


def write_outputs(report: dict[str, Any], out: Path) -> list[Path]:
    """bench.json, bench.md and accuracy-vs-time.png in `out`; returns the paths."""
    import json


    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "bench.json", out / "bench.md", out / "accuracy-vs-time.png"]
    text = json.dumps(report, indent=2, allow_nan=False) + "\n"
    write_file(paths[0], lambda p: p.write_text(text, encoding="utf-8"))
    front = {tuple(x) for pairs in report["pareto"].values() for x in pairs}
    lines = ["Errors are relative, against the exact collision (problem `collision`), the "
             "exact re-strike turn (`restrike`), or a converged run of the same compliant "
             "model (`integration`); times are medians of repeated runs.", "",
             "| problem | method | setting | error | seconds | on its front |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {r['problem']} | {r['method']} | {r['setting']} | {r['error']:.2e} | "
              f"{r['seconds']:.3e} | {'yes' if (r['method'], r['setting']) in front else ''} |"
              for r in report["rows"]]
    tp = report["throughput"]
    lines += ["", f"Throughput (the barbell's four results over {tp['sets']:.0e} parameter "
                  f"sets, timed in turn): fused kernel {tp['kernel_per_s']:.3e}/s, "
                  f"hand-written NumPy {tp['numpy_per_s']:.3e}/s (fused time / hand-written "
                  f"time = {tp['ratio']:.2f}), one kernel per result "
                  f"{tp['per_result_per_s']:.3e}/s."]
    if "numba_per_s" in tp:
        lines += [f"numba loop {tp['numba_per_s']:.3e}/s = {tp['numba_speedup']:.1f} x "
                  f"hand-written NumPy and {100 * tp['numba_of_sine_bound']:.0f}% of the "
                  f"sine bound ({tp['sine_bound_per_s']:.3e}/s: np.sin alone over the same "
                  f"angles, times {tp['cores']} cores).",
                  f"Into memory given once (no fresh pages): numba loop "
                  f"{tp['numba_into_per_s']:.3e}/s = "
                  f"{100 * tp['numba_into_of_sine_bound']:.0f}% of the sine bound "
                  f"({tp['sine_bound_into_per_s']:.3e}/s) and "
                  f"{100 * tp['numba_into_of_sine_spread']:.0f}% of np.sin spread over the "
                  f"same {tp['cores']} threads ({tp['sine_spread_per_s']:.3e}/s, "
                  f"{tp['sine_spread_scaling']:.2f} x one core)."]
    auto = report.get("auto_choice") or {}
    if auto:
        lines += ["", f"Automatic choice for tolerance {auto['tolerance']:.0e}: "
                      f"{auto['setting']}, error {auto['error']:.2e} "
                      f"({'meets' if auto['meets_tolerance'] else 'MISSES'} it), "
                      f"{auto['seconds']:.3e} s; cheapest measured setting that meets it: "
                      f"{auto['cheapest']} at {auto['cheapest_seconds']:.3e} s "
                      f"(ratio {auto['cost_ratio']:.2f})."]
    if report.get("ladder"):
        lines += ["", "Symbolic ladder: derive time against free symbols (a two-body scene "
                      "with a tilted normal), beside sympy.solve + simplify of the same laws "
                      "in a fresh process:", "",
                  "| free symbols | contact | derive (s) | plain SymPy (s) |", "|---|---|---|---|"]
        lines += [f"| {r['free_symbols']} | {r['tangential']} | {r['derive_s']:.2f} | "
                  + (f"{r['plain_sympy_s']:.2f}" if r["plain_sympy_s"] is not None
                     else f"> {r['limit_s']:g}") + " |" for r in report["ladder"]]
        vp = report["verify_vs_plain"]
        lines += ["", f"`rigidimpact verify` end to end {vp['verify_s']:.2f} s against a plain "
                      f"SymPy barbell script {vp['plain_barbell_s']:.2f} s: ratio "
                      f"{vp['ratio']:.2f}."]
        st = report["start_vs_sympy"]
        lines += ["", f"The command line's start against `python -c \"import sympy\"` "
                      f"({st['import_sympy_s']:.2f} s): `rigidimpact derive barbell`, derived "
                      f"afresh, {st['derive_barbell_s']:.2f} s (ratio "
                      f"{st['derive_ratio']:.2f}); `rigidimpact --help` {st['help_s']:.2f} s "
                      f"(ratio {st['help_ratio']:.2f}). The command runs with Python's "
                      f"cyclic collector set for a short process; against `import sympy` "
                      f"under the same settings ({st['import_sympy_same_collector_s']:.2f} s) "
                      f"the derivation's ratio is {st['derive_ratio_same_collector']:.2f}."]
        rp = report.get("run_vs_plain")
        if rp:
            lines += ["", f"`make run`'s job (derivations/run_all.py, its result cache "
                          f"off) end to end {rp['run_s']:.1f} s against the plain SymPy "
                          f"barbell script {rp['plain_barbell_s']:.2f} s: ratio "
                          f"{rp['ratio']:.1f}."]
        lines += _dask_lines(report)
    if "contacts" in report:
        family = report["contacts"]
        lines += ["", "Several contacts, each rule against n (one run each; peak MiB of "
                      "Python allocations in a second run), with the baselines side by side: "
                      "trying every set of acting contacts, a plain dense solve_ivp of the same "
                      "Hertz chain, pymunk on the same cluster (blank: not run, past its limit "
                      "or not installed):", "",
                  "| case | rule | contacts | seconds | peak MiB | baseline | baseline (s) "
                  "| largest speed difference from pymunk (1,000 sweeps) |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in family["rows"]:
            key = next((k for k in ("enumeration_s", "dense_solve_ivp_s", "pymunk_s",
                                    "fraction_elimination_s", "pymunk_1000_s", "states_s")
                        if r.get(k) is not None), None)
            shown = "" if key is None else f"{r[key]:.3f}"
            peak = "" if r["peak_mib"] is None else f"{r['peak_mib']:.1f}"
            gap = "" if r.get("pymunk_1000_gap") is None else f"{r['pymunk_1000_gap']:.1e}"
            lines.append(f"| {r['case']} | {r['rule']} | {r['n']} | {r['seconds']:.3f} | "
                         f"{peak} | {(key or '')[:-2]} | {shown} | {gap} |")
        lines += ["", "Fitted exponents (seconds ~ n^k, n >= 16): " + ", ".join(
            f"{name} {k:.2f}" for name, k in family["exponents"].items()) + "."]
    for case, rx in report.get("rough_exact_vs_floating", {}).items():
        lines += ["", f"The {case} of 400 contacts exact (found in floating point, "
                      f"confirmed in the rationals) {rx['exact_s']:.2f} s against 1,000 "
                      f"contacts in floating point {rx['floating_s']:.2f} s: ratio "
                      f"{rx['ratio']:.2f} (the simultaneous rule alone, medians of three "
                      f"in turn)."]
    if "seconds" in report:
        lines += ["", f"This bench{' (--quick)' if report['quick'] else ''} took "
                      f"{report['seconds']:.0f} s."]
    if report.get("failed"):
        lines += ["", "Settings the simulation refused (not timed):"]
        lines += [f"- {f['method']} {f['setting']}: {f['message']}" for f in report["failed"]]
    write_file(paths[1], lambda p: p.write_text("\n".join(lines) + "\n", encoding="utf-8"))
    fronts = [pareto([r for r in report["rows"] if r["problem"] == p])
              for p in ("collision", "restrike")]
    figure = accuracy_vs_time(report["rows"], fronts, FLOOR)
    write_file(paths[2], lambda p: figure.savefig(p, format="png"))
    return paths
