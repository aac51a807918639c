"""The hard-case suite: float64 kernels against 50-digit references at extreme inputs.

Every case evaluates each result in float64 (by every backend: each result's own kernel,
the fused kernel of all results, and the fused numba loop when numba is installed) and
compares it with the *exact* expression evaluated by mpmath at 50 digits from the same
float inputs (taken exactly, so the reference answers the question the float code was
asked). Two errors are reported per quantity, the worst over the backends:

* ``rel_error``: ``|float - exact| / |exact|``;
* ``scaled_error``: ``|float - exact| / magnitude``, where the magnitude is the exact
  expression with every sum's terms in absolute value (:func:`numeric.magnitude`). Their
  ratio ``magnitude / |exact|`` is the condition number: 1 where nothing cancels, large
  where a result changes sign (v_fx). Float64 can promise a few ulps of the magnitude,
  and ``worst`` reports the largest scaled error, which equals the relative error for
  every quantity without cancellation.

Examples
--------
>>> report = run_suite(problems=("discs",))
>>> report["worst"]["rel_error"] < 1e-13
True
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import mpmath
import numpy as np

from rigidimpact.paper.problems import derive
from rigidimpact.scenes.scene import load_scene
from rigidimpact.symbolic.numeric import Kernel, fused, has_numba, kernels

__all__ = ["Case", "CASES", "run_suite", "BOUND", "available_backends"]

BOUND = 1e-13  # a few units in the last place of float64, relative to the magnitude
DIGITS = 50

RATIOS = (1e-12, 1e-6, 1.0, 1e6, 1e12)
NEAR = 1e-9
ANGLES = (NEAR, 0.3, math.pi / 2 - NEAR, math.pi / 2, math.pi / 2 + NEAR, 2.5,
          math.pi - NEAR)
RESTITUTIONS = (0.0, 1e-12, 0.5, 1.0 - 1e-12, 1.0)
LENGTHS = (1e-6, 1.0, 1e6)


@dataclass(frozen=True)
class Case:
    """A problem and the grid of inputs it is checked on."""

    problem: str
    grid: Mapping[str, Sequence[float]]
    note: str


def _two_body_grid() -> dict[str, Sequence[float]]:
    return {"m_1": (1.0,), "m_2": RATIOS, "I_1": (1e-6, 1.0, 1e6), "I_2": (1e-12, 1.0, 1e12),
            "R_1x": (-1.0,), "R_1y": (0.0, 1e-9, 0.7), "R_2x": (1.0,), "R_2y": (-2.0, 1e-9),
            "V_1ix": (1.0,), "V_1iy": (0.3,), "omega_1iz": (0.0, 1e-3),
            "V_2ix": (-1.0, 0.0), "V_2iy": (-0.5,), "omega_2iz": (0.0,), "e": RESTITUTIONS}


CASES: tuple[Case, ...] = (
    Case("barbell", {"m": (1.0,), "M": RATIOS, "L": LENGTHS, "theta": ANGLES,
                     "e": RESTITUTIONS, "v_ix": (1.0, 1e-3)},
         "mass ratios 1e-12..1e12, theta within 1e-9 of 0, 90, 180 degrees, e within 1e-12 "
         "of 0 and 1, L from 1e-6 to 1e6"),
    Case("sticking", {"m": (1.0,), "M": RATIOS, "L": LENGTHS, "theta": ANGLES,
                      "v_ix": (1.0,)},
         "the clay ball over the same ratios, angles and lengths"),
    Case("discs", {"V_1ix": (1.0, 1e6), "V_2ix": (-1.0, 0.0, 0.999999999999, 1e-12),
                   "V_1iy": (0.5,), "V_2iy": (-0.25,), "e": RESTITUTIONS},
         "equal discs, nearly equal speeds and e near 0 and 1"),
    Case("two-body", _two_body_grid(),
         "general bodies: mass ratios 1e-12..1e12, inertias over 24 decades, nearly central"),
)


def _scene_cases() -> tuple[Case, ...]:
    """Scenes from derivations/ when they are there (source checkouts)."""
    folder = Path(__file__).resolve().parents[3] / "derivations"
    cases = (
        Case(str(folder / "disc-rod.toml"),
             {"m_d": (1.0,), "m_r": RATIOS, "r": (1e-6, 0.05), "l": LENGTHS,
              "k": (1e-9, 0.25, 0.5), "v": (3.0,), "omega": (0.0, 40.0), "e": RESTITUTIONS},
             "scene disc-rod.toml: a spinning disc on a rod, rod-to-disc mass ratios "
             "1e-12..1e12, contact near the rod's centre and end"),
        Case(str(folder / "sticking.toml"),
             {"m": (1.0,), "M": RATIOS, "L": LENGTHS, "theta": ANGLES, "v_ix": (1.0,)},
             "scene sticking.toml: the clay ball through the sticking contact law, "
             "tangential impulse included"),
    )
    return tuple(c for c in cases if Path(c.problem).exists())


def _results(problem: str) -> Mapping:
    if problem.endswith(".toml"):

        return load_scene(problem).derivation().results
    return derive(problem).results


def _approaching(problem: str, point: Mapping[str, float]) -> bool:
    """Keep only inputs that describe an impact (contact points closing along x)."""
    if problem == "discs":
        return point["V_1ix"] > point["V_2ix"]
    if problem == "two-body":
        v1 = point["V_1ix"] + point["omega_1iz"] * point["R_1y"]
        v2 = point["V_2ix"] + point["omega_2iz"] * point["R_2y"]
        return v1 > v2
    return True


def _references(kernel: Kernel, points: list[dict[str, float]]) -> list[tuple]:
    """(exact value, magnitude) at each point, at 50 digits."""
    rows = []
    for p in points:
        args = {n: p[n] for n in kernel.arguments}
        rows.append((kernel.reference(DIGITS, **args), kernel.scale(DIGITS, **args)))
    return rows


def _floats(results: Mapping, points: list[dict[str, float]],
            backends: Sequence[str]) -> dict[str, dict[str, np.ndarray]]:
    """Every backend's float64 values of every result at the points."""
    out: dict[str, dict[str, np.ndarray]] = {}
    single = kernels(results)
    for backend in backends:
        if backend == "kernel":  # each result its own kernel
            out[backend] = {}
            for key, kernel in single.items():
                arrays = {n: np.array([p[n] for p in points]) for n in kernel.arguments}
                out[backend][key] = np.broadcast_to(kernel(**arrays), (len(points),))
            continue
        together = fused(results, "numpy" if backend == "fused" else backend)
        out[backend] = together(**{n: np.array([p[n] for p in points])
                                   for n in together.arguments})
    return out


def available_backends() -> tuple[str, ...]:
    """``kernel`` (one per result), ``fused`` (NumPy) and ``numba`` when installed."""
    return ("kernel", "fused", "numba") if has_numba() else ("kernel", "fused")


def _errors(value: float, exact: mpmath.mpf, scale: mpmath.mpf) -> tuple[float, float]:
    with mpmath.workdps(DIGITS):
        diff = abs(mpmath.mpf(value) - exact)
        if not math.isfinite(value):
            return math.inf, math.inf
        rel = 0.0 if diff == 0 else (math.inf if exact == 0 else float(diff / abs(exact)))
        scaled = 0.0 if diff == 0 else (math.inf if scale == 0 else float(diff / scale))
    return rel, scaled


_REPORTS: dict[tuple, dict] = {}


def run_suite(problems: Iterable[str] | None = None,
              backends: Sequence[str] | None = None) -> dict:
    """Run the hard cases; return ``{"cases", "worst", "rows", "bound", "backends"}``.

    Each row is one quantity of one problem: the number of cases, the worst relative and
    scaled errors over every backend, the largest condition number met, the inputs of the
    worst case, and ``by_backend`` (each backend's worst errors). The 50-digit references
    are computed once and shared by the backends; a report is kept for the rest of the
    process, so asking twice costs nothing.
    """
    backends = tuple(backends or available_backends())
    key = (None if problems is None else tuple(sorted(problems)), backends)
    if key not in _REPORTS:
        _REPORTS[key] = _run(None if problems is None else set(problems), backends)
    return _REPORTS[key]


def _run(chosen: set[str] | None, backends: tuple[str, ...]) -> dict:
    cases = [c for c in CASES + _scene_cases()
             if chosen is None or c.problem in chosen or Path(c.problem).name in chosen]
    rows, total = [], 0
    for case in cases:
        names = list(case.grid)
        points = [dict(zip(names, combo, strict=True))
                  for combo in itertools.product(*case.grid.values())]
        points = [p for p in points if _approaching(case.problem, p)]
        total += len(points)
        results = _results(case.problem)
        floats = _floats(results, points, backends)
        for quantity, kernel in kernels(results).items():
            if not kernel.arguments:
                continue  # a constant (a spin that cannot change): nothing to round
            references = _references(kernel, points)
            worst_condition = max([1.0] + [float(scale / abs(exact))
                                           for exact, scale in references if exact != 0])
            by_backend, worst_at, worst_seen = {}, points[0], -1.0
            for backend in backends:
                worst_rel, worst_scaled = 0.0, 0.0
                values = floats[backend][quantity]
                for value, (exact, scale), point in zip(values, references, points,
                                                        strict=True):
                    rel, scaled = _errors(float(value), exact, scale)
                    worst_rel, worst_scaled = max(worst_rel, rel), max(worst_scaled, scaled)
                    if scaled >= worst_seen:  # the inputs of the worst case, any backend
                        worst_seen, worst_at = scaled, point
                by_backend[backend] = {"rel_error": worst_rel, "scaled_error": worst_scaled}
            worst_rel = max(b["rel_error"] for b in by_backend.values())
            worst_scaled = max(b["scaled_error"] for b in by_backend.values())
            rows.append({"problem": Path(case.problem).name if case.problem.endswith(".toml")
                         else case.problem, "quantity": quantity, "cases": len(points),
                         "rel_error": worst_rel, "scaled_error": worst_scaled,
                         "condition": worst_condition, "worst_at": worst_at,
                         "by_backend": by_backend, "passed": worst_scaled <= BOUND})
    worst = max(rows, key=lambda r: float(r["scaled_error"]))  # type: ignore[arg-type]
    return {"cases": total,
            "worst": {"quantity": f"{worst['problem']}.{worst['quantity']}",
                      "rel_error": worst["scaled_error"]},
            "bound": BOUND, "backends": list(backends), "rows": rows}
