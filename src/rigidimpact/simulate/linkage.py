"""After the impact, a linkage flies on: bodies pinned together by joints (and to the
world by pivots) move under gravity, the joints held by their constraint forces, until a
contact with a fixed body closes again (a re-strike) or the time asked for.

The motion is integrated in the bodies' own coordinates (a free body's centre and angle,
a pivoted body's angle about its pivot), where M is constant and diagonal; each step
solves for the accelerations and the joints' forces together,
``[M G^T; G 0] [a; -lambda] = [F; -G' u]`` (``G u = 0`` the joints' velocity conditions,
``G' u`` their centripetal part), with a Baumgarte term that pulls any drift of the
joints' positions back. The largest drift of a joint over the run is reported. A contact
between two moving bodies is not followed for a re-strike yet (said in one line).

Examples
--------
>>> import rigidimpact
>>> from pathlib import Path
>>> from rigidimpact.scenes.scene import load_scene
>>> root = Path(rigidimpact.__file__).parents[2]
>>> out = run_linkage(load_scene(root / "derivations" / "double-pendulum-wall.toml"))
>>> out.events[-1]["kind"], round(out.final["t"], 3), out.details["joint_drift"] < 1e-8
('restrike', 4.573, True)
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import Scene
from rigidimpact.simulate.outcome import Outcome, finite
from rigidimpact.simulate.planner import make_plan
from rigidimpact.simulate.several import scene_numbers

__all__ = ["run_linkage", "LinkageTrack", "RESTRIKE_HORIZON"]

RESTRIKE_HORIZON = 100.0  # seconds: past it, "until = restrike" ends and says so
BAUMGARTE = 10.0  # 1/s: how fast a joint's drift is pulled back (both gains)


@dataclass(frozen=True)
class _Part:
    """A moving body as the integrator sees it: its coordinates' place in the state,
    its mass and inertia (about its pivot for a pivoted body) and its geometry."""

    name: str
    index: int  # first coordinate
    pivot: np.ndarray | None
    mass: float
    inertia: float  # about the centre (free) or the pivot
    arm: np.ndarray  # centre from the pivot at the impact (pivoted), else zero

    @property
    def size(self) -> int:
        return 1 if self.pivot is not None else 3


def _point(part: _Part, q: np.ndarray, r0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A material point of the body, `r0` from its axis at the impact: where it is now
    (from the axis, turned by the body's angle), and the axis (centre or pivot)."""
    turn = q[part.index + (0 if part.pivot is not None else 2)]
    c, s = math.cos(turn), math.sin(turn)
    r = np.array([c * r0[0] - s * r0[1], s * r0[0] + c * r0[1]])
    axis = part.pivot if part.pivot is not None else q[part.index:part.index + 2]
    return r, axis


class _Model:
    """The linkage's equations of motion after the impact."""

    def __init__(self, scene: Scene, solution: Any, g: float) -> None:
        after = {b.name: b for b in solution.after}
        self.parts: dict[str, _Part] = {}
        q0, u0, index = [], [], 0
        for body in scene.bodies:
            if body.support == "fixed":
                continue
            b = after[body.name]
            centre = np.array([float(x) for x in b.position])
            if body.support == "pivot":
                pivot = np.array([float(x) for x in b.pivot])
                arm = centre - pivot
                part = _Part(b.name, index, pivot, float(b.mass),
                             float(b.inertia) + float(b.mass) * float(arm @ arm), arm)
                q0 += [0.0]
                u0 += [float(b.spin)]
            else:  # a point mass's own angle is a spectator: any inertia keeps it still
                part = _Part(b.name, index, None, float(b.mass),
                             float(b.inertia) or 1.0, np.zeros(2))
                q0 += [*centre, 0.0]
                u0 += [float(b.velocity[0]), float(b.velocity[1]), float(b.spin)]
            self.parts[b.name] = part
            index += part.size
        self.n = index
        self.q0, self.u0 = np.array(q0), np.array(u0)
        diagonal = []
        for part in self.parts.values():
            diagonal += [part.inertia] if part.pivot is not None else \
                [part.mass, part.mass, part.inertia]
        self.M = np.diag(diagonal)
        self.g = g
        self.force = np.zeros(self.n)  # the weights of the free bodies (constant)
        for part in self.parts.values():
            if part.pivot is None:
                self.force[part.index + 1] = -part.mass * g
        # each joint: the point from each side's axis at the impact
        self.joints: list[tuple[str, list, np.ndarray]] = []
        placed = {j.name: j for j in solution.joints}  # with the numbers put in
        for j in scene.joints:
            point = np.array([float(x) for x in placed[j.name].point])
            sides: list[tuple[_Part | None, np.ndarray]] = []
            for name in j.bodies:
                side = self.parts.get(name)
                if side is None:  # a fixed side: its point stays where it is
                    sides.append((None, point))
                    continue
                axis = side.pivot if side.pivot is not None else self.q0[
                    side.index:side.index + 2]
                sides.append((side, point - axis))
            self.joints.append((j.name, sides, point))

    def _rows(self, q: np.ndarray, u: np.ndarray, part: _Part | None, r0: np.ndarray,
              fixed: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """For one side of a joint: its point's velocity rows (2 x n), the centripetal
        part of its acceleration, its place and its velocity."""
        rows = np.zeros((2, self.n))
        if part is None:
            return rows, np.zeros(2), fixed, np.zeros(2)
        r, axis = _point(part, q, r0)
        spin_col = part.index if part.pivot is not None else part.index + 2
        w = u[spin_col]
        rows[:, spin_col] = [-r[1], r[0]]
        velocity = w * np.array([-r[1], r[0]])
        if part.pivot is None:
            rows[0, part.index] = rows[1, part.index + 1] = 1.0
            velocity = velocity + u[part.index:part.index + 2]
        return rows, -w * w * r, axis + r, velocity

    def _forces(self, q: np.ndarray) -> np.ndarray:
        """The weights: constant on a free body's centre; on a pivoted body, the moment
        about its pivot, which turns with it."""
        force = self.force.copy()
        for part in self.parts.values():
            if part.pivot is not None:
                r, _ = _point(part, q, part.arm)
                force[part.index] = -part.mass * self.g * r[0]
        return force

    def accelerations(self, q: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, float]:
        """The accelerations with every joint held, and the largest joint drift."""
        force = self._forces(q)
        G, gamma, drift = [], [], 0.0
        for _, (first, second), point in self.joints:
            a = self._rows(q, u, first[0], first[1], point)
            b = self._rows(q, u, second[0], second[1], point)
            G.append(b[0] - a[0])
            gap, rate = b[2] - a[2], b[3] - a[3]
            drift = max(drift, float(np.max(np.abs(gap))))
            # G a = -(centripetal difference) - 2 k rate - k^2 gap
            gamma.append(-(b[1] - a[1]) - 2 * BAUMGARTE * rate - BAUMGARTE ** 2 * gap)
        if not G:
            return np.linalg.solve(self.M, force), drift
        Gm = np.vstack(G)
        k = Gm.shape[0]
        kkt = np.block([[self.M, Gm.T], [Gm, np.zeros((k, k))]])
        rhs = np.concatenate([force, np.concatenate(gamma)])
        return np.linalg.solve(kkt, rhs)[:self.n], drift

    def place(self, q: np.ndarray, name: str, r0: np.ndarray) -> np.ndarray:
        part = self.parts[name]
        r, axis = _point(part, q, r0)
        return axis + r


@dataclass(frozen=True)
class LinkageTrack:
    """The integrated run, sampled for plots: each body's centre (and a rod's ends)."""

    model: Any
    times: np.ndarray
    states: np.ndarray  # rows: q then u, one column per time
    ends: Mapping[str, tuple[np.ndarray, ...]]  # rod ends from the centre at the impact

    @property
    def t(self) -> np.ndarray:
        return self.times

    def points(self) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        n = self.model.n
        for name, part in self.model.parts.items():
            centre0 = (part.pivot + part.arm) if part.pivot is not None else \
                self.model.q0[part.index:part.index + 2]
            marks = self.ends.get(name, ())
            for label, offset in (("centre", np.zeros(2)), *(
                    (f"end {k + 1}", e) for k, e in enumerate(marks))):
                r0 = (centre0 + offset) - (part.pivot if part.pivot is not None else
                                            centre0)
                key = name if label == "centre" else f"{name}.{label}"
                out[key] = np.array([self.model.place(self.states[:n, i], name, r0)
                                     for i in range(len(self.times))])
        return out


def run_linkage(scene: Scene, values: Mapping[sp.Symbol, Any] | None = None) -> Outcome:
    """Simulate a scene with joints: its rule's impact, then the linkage's flight under
    gravity (when asked) until a contact with a fixed body closes again or the time in
    ``until``."""
    from scipy.integrate import solve_ivp

    start = time.perf_counter()
    plan = make_plan(scene.simulate)
    if any(step.model == "compliant" for step in plan.steps) or \
            set(plan.effects) - {"gravity"}:
        raise InputError("simulate.effects", "a linkage's flight takes gravity only so far")
    exact = scene_numbers(scene, values)
    outcomes = scene.outcomes(exact)
    if len(outcomes) > 1:
        raise InputError("impact.order", "simulate follows one outcome: give the "
                         "sequential rule its order")
    solution = outcomes[0]
    g = plan.settings["g"] if "gravity" in plan.effects else 0.0
    model = _Model(scene, solution, g)
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0}]
    watched = []
    for c in scene.contacts:
        sides = [b for b in scene.bodies if b.name in (c.first, c.second)]
        moving = [b for b in sides if b.support != "fixed"]
        if len(moving) == 2:
            if plan.until == "restrike":
                raise InputError("simulate.until", f"{c.name} is between two moving "
                                 "bodies: a linkage's re-strike is followed against fixed "
                                 "bodies only so far; give until a time")
            continue
        (body,) = moving
        part = model.parts[body.name]
        axis = part.pivot if part.pivot is not None else model.q0[part.index:part.index + 2]
        point = np.array([float(x.xreplace(exact)) for x in c.point])
        normal = np.array([float(x.xreplace(exact)) for x in c.unit_normal])
        toward = normal if body.name == c.first else -normal  # from the body into the other
        watched.append((c.name, body.name, point - axis, point, toward))
    if plan.until == "separation":
        t_end, why, ts, ys = 0.0, "separation", np.zeros(1), \
            np.concatenate([model.q0, model.u0])[:, None]
    else:
        horizon = RESTRIKE_HORIZON if plan.until == "restrike" else float(plan.until)

        def rhs(_t: float, y: np.ndarray) -> np.ndarray:
            q, u = y[:model.n], y[model.n:]
            return np.concatenate([u, model.accelerations(q, u)[0]])

        def gap_of(name, body, r0, point, toward):
            def gap(t: float, y: np.ndarray) -> float:
                # how far the body's point has come toward the other body, less a hair
                # (the contact is where it was at the impact): negative while apart
                if t < 1e-9:
                    return -1.0
                return float((model.place(y[:model.n], body, r0) - point) @ toward)
            gap.terminal, gap.direction = True, 1.0  # type: ignore[attr-defined]
            return gap

        found = solve_ivp(rhs, (0.0, horizon), np.concatenate([model.q0, model.u0]),
                          method="DOP853", rtol=1e-10, atol=1e-12, max_step=horizon / 200,
                          events=[gap_of(*w) for w in watched] or None, dense_output=True)
        if not found.success:
            raise InputError("simulate", f"the linkage's flight failed: {found.message}")
        t_end, why = float(found.t[-1]), ("time" if plan.until != "restrike" else
                                          f"no re-strike within {RESTRIKE_HORIZON:g} s")
        for k, times in enumerate(found.t_events or []):
            if len(times):
                t_end, why = float(times[0]), "restrike"
                events.append({"kind": "restrike", "t": t_end, "contact": watched[k][0]})
        ts = np.linspace(0.0, t_end, 200) if t_end > 0 else np.zeros(1)
        ys = found.sol(ts) if t_end > 0 else np.concatenate([model.q0, model.u0])[:, None]
    if why != "restrike":
        events.append({"kind": "end", "t": t_end, "why": why})
    y_end = ys[:, -1]
    q, u = y_end[:model.n], y_end[model.n:]
    drift = max(model.accelerations(ys[:model.n, i], ys[model.n:, i])[1]
                for i in range(ys.shape[1]))
    final: dict[str, float] = {}
    for name, part in model.parts.items():
        if part.pivot is not None:
            r, _ = _point(part, q, part.arm)
            w = u[part.index]
            place, velocity = part.pivot + r, w * np.array([-r[1], r[0]])
            turn = q[part.index]
        else:
            place, velocity, w = q[part.index:part.index + 2], u[part.index:part.index + 2], \
                u[part.index + 2]
            turn = q[part.index + 2]
        final |= {f"{name}.vx": float(velocity[0]), f"{name}.vy": float(velocity[1]),
                  f"{name}.omega": float(w), f"{name}.x": float(place[0]),
                  f"{name}.y": float(place[1]), f"{name}.turn": float(turn)}
    final["t"] = t_end
    ends = {}
    for body in solution.after:
        if body.shape == "rod":
            dims = {k: v.xreplace(exact) for k, v in body.dimensions}
            half = float(dims["length"]) / 2
            angle = float(dims["angle"])
            e = np.array([half * math.cos(angle), half * math.sin(angle)])
            ends[body.name] = (-e, e)
    details = {"rule": solution.label, "acted": list(solution.acted),
               "joint_drift": drift}
    if solution.warnings or solution.notes:
        details["warnings"] = [*solution.warnings, *solution.notes]
    track = LinkageTrack(model, ts, ys, ends)
    return finite(Outcome(plan, final, events, time.perf_counter() - start,
                          ode_steps=max(len(found.t) - 1, 0) if t_end > 0 else 0,
                          details=details, trajectory=track))
