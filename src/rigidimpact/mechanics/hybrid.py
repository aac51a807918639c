"""Hybrid simulation through impacts: flow, an event on a gap function, the impact map,
relabelling, and the Poincare map at the impacts with its fixed point and eigenvalues.

The flow is integrated from the system's own equations of motion (``mass_matrix_full``
and ``forcing_full`` of a ``KanesMethod`` or ``System``), generated once as numeric code
(lambdify with common subexpressions), never evaluated symbolically inside the
integrator. An event is a gap function of the coordinates (the height of a foot above the
ground, say) crossing zero downward, with an optional guard that says whether a crossing
is an impact (a swing foot passing the stance foot mid-stride is not). At each impact a
`jump` maps the state before to the state after: the impact map of
:mod:`rigidimpact.mechanics.impact`, and whatever relabelling the model needs (a walker's
legs swap at heel strike).

Examples
--------
A ball dropped from height 1 onto a floor with e = 1/2 (g = 1): each bounce's peak is a
quarter of the one before, so the bounces come at t = sqrt(2) (1 + 1 + 1/2 + ...).

>>> import numpy as np
>>> ball = Hybrid(lambda t, x: np.array([x[1], -1.0]), lambda x: x[0],
...               lambda x: np.array([0.0, -0.5 * x[1]]))
>>> walk = ball.simulate(np.array([1.0, 0.0]), impacts=3)
>>> [round(t, 9) for t in walk.impact_times]
[1.414213562, 2.828427125, 3.535533906]
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.mechanics.impact import system_matrix
from rigidimpact.solve.collision import whole_number
from rigidimpact.symbolic.given import given_values

__all__ = ["Hybrid", "Walk", "flow_of", "FixedPoint"]

State = np.ndarray


def flow_of(system: Any, constants: dict) -> Callable:
    """``f(t, x)`` for ``x = [q, u]`` from a ``KanesMethod`` (after ``kanes_equations``) or
    ``System`` (after ``form_eoms``), with numbers for its constants: the full mass
    matrix and forcing, generated once as numeric code.

    Raises
    ------
    InputError
        When the system is not one or its equations are not formed, or a constant is
        left without a number or given one that is not a real, finite number (text is
        refused, never read).
    """
    M = sp.Matrix(system_matrix(system, "mass_matrix_full"))
    F = sp.Matrix(system_matrix(system, "forcing_full"))
    # no check of signs: a walker's point foot is a length declared positive, set to 0
    constants = given_values(constants, "constants", signs=False)
    states = list(system.q) + list(system.u)
    M, F = M.xreplace(constants), F.xreplace(constants)
    time = {s for s in (M.free_symbols | F.free_symbols) if s.name == "t"}
    left = (M.free_symbols | F.free_symbols) - time
    if left:
        raise InputError("constants", "simulation needs numbers for "
                         f"{', '.join(sorted(map(str, left)))}")
    symbols = sp.symbols(f"x0:{len(states)}")
    plain = dict(zip(states, symbols, strict=True))
    M_num = sp.lambdify([symbols], M.xreplace(plain), "numpy", cse=True)
    F_num = sp.lambdify([symbols], F.xreplace(plain), "numpy", cse=True)

    def rhs(_t: float, x: State) -> State:
        x = np.asarray(x)
        if x.shape != (len(states),) or x.dtype.kind not in "iuf":
            raise InputError("x", f"must be the state [q, u] of {len(states)} real "
                             f"numbers, not an array of {x.dtype} of shape {x.shape}")
        return np.linalg.solve(np.asarray(M_num(x), float),
                               np.asarray(F_num(x), float).ravel())

    return rhs


MAX_REFINEMENTS = 40  # times a flow's steps are shortened to find a stepped-over crossing
ZENO_RATIO = 1e-6  # intervals this small next to the first are a pile-up, not a gait


def _piling_up(times: Sequence[float]) -> float | None:
    """The time impacts accumulate at, when the last five intervals between them shrink
    by one ratio r < 1 (to 1 per cent) and have fallen below 1e-6 of the first: the
    remaining intervals sum to ``dt r / (1 - r)``. None otherwise."""
    if len(times) < 7:
        return None
    gaps = np.diff(times)
    ratios = gaps[-5:] / gaps[-6:-1]
    r = float(np.median(ratios))
    if not 0 < r < 0.999 or np.any(np.abs(ratios - r) > 0.01 * r) or \
            gaps[-1] > ZENO_RATIO * gaps[0]:
        return None
    return float(times[-1] + gaps[-1] * r / (1 - r))


@dataclass(frozen=True)
class _Piece:
    """The part of an integration kept before a stepped-over crossing."""

    t: np.ndarray
    y: np.ndarray


@dataclass
class Walk:
    """A simulated run: its trajectory and, at each impact, the time and the states just
    before and just after the jump."""

    times: list[np.ndarray] = field(default_factory=list)
    states: list[np.ndarray] = field(default_factory=list)
    impact_times: list[float] = field(default_factory=list)
    before: list[State] = field(default_factory=list)
    after: list[State] = field(default_factory=list)
    stopped: str = ""  # "impacts", "time", "fell", "zeno" or "budget"
    accumulation: float | None = None  # with "zeno": the time the impacts pile up at


@dataclass(frozen=True)
class FixedPoint:
    """A fixed point of the Poincare map and the eigenvalues of its Jacobian there
    (stable when every one lies inside the unit circle)."""

    state: np.ndarray
    eigenvalues: np.ndarray
    residual: float
    iterations: int

    @property
    def stable(self) -> bool:
        return bool(np.all(np.abs(self.eigenvalues) < 1))


@dataclass(frozen=True)
class Hybrid:
    """Flow ⇄ impact map.

    Parameters
    ----------
    rhs : callable ``(t, x) -> dx/dt``
    gap : callable ``x -> float``
        An impact when it crosses zero downward.
    jump : callable ``x -> x``
        The state after an impact from the state before (impact map, relabelling).
    guard : callable ``x -> bool``, optional
        Whether a crossing is an impact (default: every one).
    fallen : callable ``x -> bool``, optional
        Ends a run (a walker falls).
    max_step_time : float
        The longest flow between impacts before a run is declared never to impact.
    """

    rhs: Callable[[float, State], State]
    gap: Callable[[State], float]
    jump: Callable[[State], State]
    guard: Callable[[State], bool] | None = None
    fallen: Callable[[State], bool] | None = None
    max_step_time: float = 20.0
    rtol: float = 1e-11
    atol: float = 1e-12

    def step(self, x0: State, t0: float = 0.0) -> tuple[float, State, Any]:
        """Flow from `x0` to the next impact: (its time, the state just before, the
        integration's output)."""
        def event(_t: float, x: State) -> float:
            return float(self.gap(x))

        event.terminal = True  # type: ignore[attr-defined]
        event.direction = -1.0  # type: ignore[attr-defined]
        from scipy.integrate import solve_ivp  # scipy on first use

        start, x, pieces = t0, np.asarray(x0, float), []
        end = t0 + self.max_step_time
        # where a hop was stepped over, the stretch to search again with shorter steps
        finest, stretch = np.inf, end
        refinements = 0
        while True:
            run = solve_ivp(self.rhs, (start, stretch), x, method="DOP853",
                            events=event, rtol=self.rtol, atol=self.atol, dense_output=False,
                            max_step=finest)
            if run.status == -1:
                raise InputError("simulate", f"the integration failed: {run.message}")
            passed = self._passed_through(run)
            if passed is not None:  # a hop shorter than a step: go back, smaller steps
                refinements += 1
                if refinements > MAX_REFINEMENTS:
                    raise InputError("simulate", f"the gap went negative near t = "
                                     f"{run.t[passed]:.6g} without a crossing the steps "
                                     f"could find ({MAX_REFINEMENTS} times shorter steps "
                                     "tried): the contact would be passed through")
                back = max(passed - 1, 0)
                width = float(run.t[passed] - run.t[back])
                finest = max(width / 20, 1e-14 * (1 + abs(start)))
                stretch = min(float(run.t[passed]) + width, end)
                kept = run.t[: back + 1], run.y[:, : back + 1]
                pieces.append(_Piece(*kept))
                start, x = float(run.t[back]), run.y[:, back]
                continue
            pieces.append(run)
            if not run.t_events[0].size and stretch < end:  # the stretch was clear
                start, x = float(run.t[-1]), run.y[:, -1]
                finest, stretch = np.inf, end
                continue
            if not run.t_events[0].size:
                raise InputError("simulate", f"no impact within {self.max_step_time:g} s "
                                 "of flow: the gap never crosses zero")
            t, x = float(run.t_events[0][0]), run.y_events[0][0]
            if self.fallen is not None and self.fallen(x):
                return t, x, pieces
            if self.guard is None or self.guard(x):
                return t, x, pieces
            start = t + 1e-9  # a crossing that is no impact (a foot scuffing): go on
            x = solve_ivp(self.rhs, (t, start), x, rtol=self.rtol, atol=self.atol).y[:, -1]

    def _passed_through(self, run: Any) -> int | None:
        """The first step of `run` (before its event) at which the gap is negative past
        rounding, or None: a crossing the event search stepped over."""
        gaps = np.array([float(self.gap(run.y[:, k])) for k in range(run.y.shape[1])])
        end = len(gaps) - 1 if run.t_events[0].size else len(gaps)
        tol = 1e-9 * (1.0 + float(np.max(np.abs(gaps))))
        below = np.flatnonzero(gaps[:end] < -tol)
        if below.size and self.guard is not None and not self.guard(run.y[:, below[0]]):
            return None  # a crossing the guard says is no impact (a foot scuffing)
        return int(below[0]) if below.size else None

    def simulate(self, x0: State, impacts: int = 10, until: float = np.inf,
                 steps: int = 1_000_000) -> Walk:
        """Flow and jump until `impacts` impacts, the time `until`, a fall, impacts that
        pile up at one time (Zeno: the intervals between them shrinking geometrically;
        `accumulation` is that time, by the geometric series), or `steps` integration
        steps of work (``stopped == "budget"``: counted, so a run stops at the same place
        on every machine at any load).

        Examples
        --------
        A ball dropped onto a floor with e = 1/2 bounces infinitely often before
        t = sqrt(2) (1 + 2 (1/2) / (1 - 1/2)) = 3 sqrt(2):

        >>> ball = Hybrid(lambda t, x: np.array([x[1], -1.0]), lambda x: x[0],
        ...               lambda x: np.array([0.0, -0.5 * x[1]]))
        >>> walk = ball.simulate(np.array([1.0, 0.0]), impacts=10**6)
        >>> walk.stopped, round(walk.accumulation, 6), round(3 * 2 ** 0.5, 6)
        ('zeno', 4.242641, 4.242641)
        """
        whole_number("impacts", impacts, 1)
        if not (isinstance(until, (int, float)) and until > 0) or np.isnan(until):
            raise InputError("until", f"must be a positive time (or inf), not {until!r}")
        whole_number("steps", steps, 1)
        x = np.asarray(x0, float)
        if x.ndim != 1 or not np.all(np.isfinite(x)):
            raise InputError("x0", "must be a state of finite numbers")
        walk, t = Walk(), 0.0
        taken = 0
        for _ in range(impacts):
            if taken >= steps:
                walk.stopped = "budget"
                return walk
            try:
                t_hit, before, pieces = self.step(x, t)
            except InputError as refusal:
                gaps = np.diff(walk.impact_times)
                if len(gaps) >= 4 and np.all(np.diff(gaps[-4:]) < 0):
                    raise InputError(refusal.field, f"{refusal.message}; the impacts were "
                                     f"piling up (the last {len(gaps[-4:])} intervals "
                                     f"shrinking, the last {gaps[-1]:.3g} s): past their "
                                     "pile-up the contact stays closed, which a flow "
                                     "between impacts does not follow") from None
                raise
            for run in pieces:
                walk.times.append(run.t)
                walk.states.append(run.y)
                taken += max(len(run.t) - 1, 1)
            if t_hit > until:
                walk.stopped = "time"
                return walk
            if self.fallen is not None and self.fallen(before):
                walk.stopped = "fell"
                return walk
            x, t = np.asarray(self.jump(before), float), t_hit
            if x.shape != before.shape or not np.all(np.isfinite(x)):
                raise InputError("jump", f"the impact map gave no finite state at t = "
                                 f"{t_hit:.6g} (from {np.round(before, 6).tolist()}): is "
                                 "the contact approaching there?")
            walk.impact_times.append(t_hit)
            walk.before.append(before)
            walk.after.append(x)
            piling = _piling_up(walk.impact_times)
            if piling is not None:
                walk.stopped, walk.accumulation = "zeno", piling
                return walk
        walk.stopped = "impacts"
        return walk

    def poincare(self, x: State) -> State:
        """The state just after the next impact, from a state just after an impact."""
        _, before, _ = self.step(x)
        return np.asarray(self.jump(before), float)

    def fixed_point(self, guess: State, free: Sequence[int], tol: float = 1e-11,
                    max_iterations: int = 30, h: float = 1e-6,
                    complete: Callable[[State], State] | None = None) -> FixedPoint:
        """The fixed point of the Poincare map by Newton's method, over the entries
        `free` of the state just after impact (the others follow from them through
        `complete`, as a walker's swing angle follows from its stance angle at heel
        strike), and the eigenvalues of the map's Jacobian (central differences)."""
        free = list(free)

        def full(z: np.ndarray) -> State:
            x = np.array(guess, float)
            x[free] = z
            return complete(x) if complete is not None else x

        def g(z: np.ndarray) -> np.ndarray:
            return self.poincare(full(z))[free]

        def jacobian(z: np.ndarray) -> np.ndarray:
            columns = []
            for i in range(len(z)):
                d = np.zeros_like(z)
                d[i] = h
                columns.append((g(z + d) - g(z - d)) / (2 * h))
            return np.array(columns).T

        z, iterations = np.asarray(guess, float)[free], 0
        first = self.step(full(z))[0]
        while np.max(np.abs(r := g(z) - z)) >= tol:
            if iterations == max_iterations:
                raise InputError("fixed_point", f"Newton's method did not converge in "
                                 f"{max_iterations} iterations (residual "
                                 f"{np.max(np.abs(r)):.3g})")
            z, iterations = z - np.linalg.solve(jacobian(z) - np.eye(len(z)), r), iterations + 1
        if self.step(full(z))[0] < ZENO_RATIO * first:
            raise InputError("fixed_point", "Newton's method went to a state with no flight "
                             "between impacts (the impacts pile up: Zeno's limit), where the "
                             "map is not smooth; that is no fixed point of the motion")
        return FixedPoint(full(z), np.linalg.eigvals(jacobian(z)), float(np.max(np.abs(r))),
                          iterations)
