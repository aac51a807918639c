"""``simulate`` for a 3-D scene: the impact as an instant, a sphere's bounce on a fixed
flat through a tangentially compliant contact (``effects = ["tangential-compliance"]``),
or, asked past separation (``until`` a time, or ``impacts`` a count), a sphere's life
among the scene's fixed planes: flight (under gravity along -z with
``effects = ["gravity"]``), each impact under its contact's laws, and sliding until it
rolls (:func:`rigidimpact.simulate.bounces.bounces`).

The compliant bounce of a sphere on a flat is planar, whatever its spin: the sphere's
tangential mobility is isotropic (``1/m + R^2/I`` in every direction across the
normal), the spring's stretch starts at zero and grows along the slip, and every force
on the slip is along the stretch or along the slip; so the slip, the stretch and the
tangential force stay on the line of the first slip, ``s``. Across s nothing acts: the
centre's velocity across s and the spin's part that moves the touching point across s
keep their values, and so does the spin about the normal (the lumped contact has no
twisting spring). Along s the bounce is the planar one of
:func:`rigidimpact.laws.compliance.tangential_bounce`, in the plane of n and s. A
sphere that meets the flat without slipping has nothing to turn and keeps its
tangential motion.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import tangential_bounce
from rigidimpact.model.space import SPEEDS
from rigidimpact.scenes.space import SpaceScene
from rigidimpact.simulate.bounces import MAX_IMPACTS, Bounces, bounces
from rigidimpact.simulate.outcome import Outcome
from rigidimpact.simulate.planner import make_plan
from rigidimpact.simulate.tangential import STEPS

__all__ = ["run_space", "BounceTrack"]


def run_space(scene: SpaceScene, values: dict | None = None) -> Outcome:
    """Simulate a 3-D scene as its ``[simulate]`` table asks (see the module's text):
    until separation, the rigid impact alone or with tangential compliance."""
    start = time.perf_counter()
    plan = make_plan(scene.simulate)
    values = dict(scene.values) if values is None else values
    effects = set(plan.effects)
    missing = sorted(str(s) for s in scene.used if s not in values)
    if missing:
        raise InputError("values", f"give a value for {', '.join(missing)}")
    if plan.until != "separation" or "impacts" in scene.simulate:
        return _bouncing(scene, values, plan, start)
    if not effects <= {"tangential-compliance"}:
        raise InputError("simulate.effects", "until separation a 3-D scene is the rigid "
                         "impact, or with effects = [\"tangential-compliance\"] a sphere's "
                         "compliant bounce; gravity acts past it (give until a time or "
                         "impacts a count)")
    solution = scene.collision(values).solve()
    rigid = {k: float(sp.N(v, 17)) for k, v in solution.results().items()
             if any(k.endswith(f".{s}") for s in SPEEDS)}
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0}]
    if not effects:
        events.append({"kind": "end", "t": 0.0, "why": "the contact separates (a rigid "
                       "impact is an instant)"})
        return Outcome(plan, {**rigid, "t": 0.0}, events, time.perf_counter() - start, 0,
                       {"warnings": list(solution.warnings)})
    final = _compliant_sphere(scene, values, plan.settings["stiffness_ratio"])
    events.append({"kind": "end", "t": 0.0, "why": "the sphere separates from the flat "
                   "(the contact's duration is not resolved in time: only k_t/k_n enters)"})
    details = {"contact": {"model": "tangentially compliant: a normal spring with the "
                                    "dashpot that returns e, a tangential spring capped by "
                                    "Coulomb (linear, so only k_t/k_n matters), in the "
                                    "plane of the normal and the first slip",
                           "stiffness_ratio": plan.settings["stiffness_ratio"],
                           "steps_per_period": STEPS},
               "rigid": rigid}
    return Outcome(plan, {**final, "t": 0.0}, events, time.perf_counter() - start, 0,
                   details)


def _compliant_sphere(scene: SpaceScene, values: dict, ratio: float) -> dict[str, float]:
    """The sphere's speeds after its tangentially compliant bounce on the flat."""
    if len(scene.contacts) != 1:
        raise InputError("simulate.effects", "tangential-compliance takes one contact (a "
                         "sphere on a fixed flat) so far")
    (contact,) = scene.contacts
    if contact.tangential != "coulomb" or contact.law != "newton":
        raise InputError("simulate.effects", "tangential-compliance needs Newton's e and "
                         "a Coulomb contact (tangential = \"coulomb\", friction = mu)")
    ball = _the_sphere(scene, values, "simulate.effects", "tangential-compliance needs one "
                       "sphere and one fixed body")

    def number(x: Any) -> float:
        return float(sp.N(sp.sympify(x).xreplace(values), 17))

    R, m = number(ball.radius), number(ball.mass)
    inertia = number(ball.inertia[0]) / (m * R * R)  # in units of m R^2
    n = np.array([number(x) for x in contact.normal])
    n /= np.linalg.norm(n)
    if ball.name == contact.first:  # the normal from the flat into the sphere
        n = -n
    v = np.array([number(x) for x in ball.velocity])
    w = np.array([number(x) for x in ball.spin])
    vn = float(v @ n)
    if vn >= 0:
        raise InputError("bodies", f"{ball.name} is not approaching the flat")
    v_t = v - vn * n
    spin_slip = R * np.cross(w, -n)  # the touching point at -R n moves at w x (-R n)
    slip = v_t + spin_slip
    size = float(np.linalg.norm(slip))
    e, mu = number(contact.restitution), number(contact.friction)
    if size == 0.0:  # nothing to stretch the spring: the tangential motion is kept
        s = np.zeros(3)
        along_v = along_w = 0.0
    else:
        s = slip / size
        along_v, along_w = float(v_t @ s), float(spin_slip @ s)
    vt_after, vn_after, turn = tangential_bounce(along_v, vn, along_w, mu, e, ratio,
                                                 inertia, STEPS)
    v_after = v + (float(vn_after) - vn) * n + (float(vt_after) - along_v) * s
    # the spin's change: the tangential force F s at -R n turns the sphere about
    # (-R n) x s; its slip along s changes by R (w x (-n)) . s, which is turn - along_w
    axis = np.cross(-n, s)
    w_after = w + (float(turn) - along_w) / R * axis
    return {f"{ball.name}.{k}": float(x) for k, x in
            zip(SPEEDS, (*v_after, *w_after), strict=True)}


def _the_sphere(scene: SpaceScene, values: dict, where: str, why: str) -> Any:
    """The scene's one free body, a sphere, at `values`; else `why` in one line."""
    free = [b for b in scene.bodies if b.support != "fixed"]
    if len(free) != 1 or free[0].radius is None:
        raise InputError(where, why)
    return free[0].at(values)


def _bouncing(scene: SpaceScene, values: dict, plan: Any, start: float) -> Outcome:
    """A sphere among the scene's fixed planes (every contact a plane it may strike),
    until a time or a count of impacts."""
    if not set(plan.effects) <= {"gravity"}:
        raise InputError("simulate.effects", "past separation a 3-D scene takes "
                         "effects = [\"gravity\"] or none (tangential-compliance is one "
                         "bounce, until = \"separation\")")
    ball = _the_sphere(scene, values, "bodies", "a 3-D scene is followed past its impact "
                       "for one free sphere among fixed planes so far")
    # the contacts at the impact are planes too (struck again later), then [[planes]]
    planes = tuple(c.at(values) for c in (*scene.contacts, *scene.planes))
    for c in planes:
        other = c.first if c.second == ball.name else c.second
        if ball.name not in (c.first, c.second) or \
                next(b for b in scene.bodies if b.name == other).support != "fixed":
            raise InputError(f"{c.name}.bodies", "each contact is a fixed plane the sphere "
                             "may strike: name the sphere and a fixed body")
    impacts = scene.simulate.get("impacts")
    if impacts is not None and (isinstance(impacts, bool) or not isinstance(impacts, int)
                                or not 1 <= impacts <= MAX_IMPACTS):
        raise InputError("simulate.impacts", f"a whole number from 1 to {MAX_IMPACTS}, "
                         f"got {impacts!r}")
    g = sp.Rational(str(plan.settings["g"])) if "gravity" in plan.effects else 0
    horizon = None if plan.until == "separation" else sp.Rational(str(plan.until))
    run = bounces(ball, planes, (0, 0, -g), impacts, horizon)
    events: list[dict[str, Any]] = []
    for e in run.events:
        event: dict[str, Any] = {"kind": e.kind, "t": float(e.t), "plane": e.plane}
        if e.kind == "impact":
            event["course"] = e.course
        events.append(event)
    events.append({"kind": "end", "t": float(run.t), "why": {
        "impacts": f"{impacts} impact{'s' if impacts != 1 else ''}, as asked",
        "horizon": "the time asked", "rolling": "it rolls on the plane for ever",
        "flying": "no plane lies ahead"}[run.stopped]})
    name = ball.name
    final = {f"{name}.{k}": float(sp.N(x, 17)) for k, x in zip(
        ("x", "y", "z", *SPEEDS), (*run.position, *run.velocity, *run.spin), strict=True)}
    details = {"exact": run.exact, "impacts": sum(e.kind == "impact" for e in run.events),
               "gravity": [0.0, 0.0, -float(g)], "stopped": run.stopped}
    if run.tolerance is not None:
        details["tolerance"] = run.tolerance
        details["notes"] = [f"a plane was struck with the sphere lying on another (the "
                            f"driven rule, integrated to a relative tolerance of "
                            f"{run.tolerance:g}): from there on the run is good to that"]
    elif not run.exact:
        details["notes"] = ["a time of the run is irrational: from there on it is "
                            "followed in 40-digit floating point"]
    return Outcome(plan, {**final, "t": float(run.t)}, events, time.perf_counter() - start,
                   0, details, BounceTrack(ball, run))


@dataclass(frozen=True)
class BounceTrack:
    """A bounce run's path for pictures. Every phase of it (flight under gravity,
    sliding under Coulomb's constant friction, rolling) moves the centre with a constant
    acceleration, so each phase is the quadratic fixed by its start, its starting
    velocity and its end; no physics is repeated here."""

    ball: Any
    run: Bounces

    def states(self) -> list[tuple[float, np.ndarray, np.ndarray]]:
        """(t, centre, velocity) at the start, after each event, and at the end."""
        def vec(x: Any) -> np.ndarray:
            return np.array([float(sp.N(y, 17)) for y in x])
        out = [(0.0, vec(self.ball.position), vec(self.ball.velocity))]
        out += [(float(e.t), vec(e.position), vec(e.velocity)) for e in self.run.events]
        out.append((float(self.run.t), vec(self.run.position), vec(self.run.velocity)))
        return out

    def sampled(self, count: int = 400) -> tuple[np.ndarray, np.ndarray]:
        """Times and the centre (x, y, z) at each, `count` samples spread over the run
        and every event's own instant."""
        states = self.states()
        end = states[-1][0]
        times = np.union1d(np.linspace(0.0, end, count) if end > 0 else np.zeros(1),
                           [s[0] for s in states])
        points = np.empty((len(times), 3))
        for i, t in enumerate(times):
            k = max(j for j in range(len(states) - 1) if states[j][0] <= t) \
                if t < end else len(states) - 2
            (t0, c0, v0), (t1, c1, _) = states[k], states[k + 1]
            span = t1 - t0
            tau = t - t0
            a = 2 * (c1 - c0 - v0 * span) / span ** 2 if span > 0 else np.zeros(3)
            points[i] = c0 + v0 * tau + a * tau ** 2 / 2
        return times, points
