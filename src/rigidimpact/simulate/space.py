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
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import sphere_bounce
from rigidimpact.model.space import SPEEDS, Body3
from rigidimpact.scenes.scene import Scene
from rigidimpact.scenes.space import SpaceScene
from rigidimpact.simulate.bounces import MAX_IMPACTS, Bounces, spheres
from rigidimpact.simulate.numbers import scene_values
from rigidimpact.simulate.outcome import Outcome
from rigidimpact.simulate.planner import goes_past_impact, make_plan
from rigidimpact.simulate.tangential import STEPS

__all__ = ["run_space", "run_in_plane", "bounces_in_plane", "BounceTrack"]


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
    if goes_past_impact(scene.simulate):
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


def bounces_in_plane(scene: Scene) -> bool:
    """Whether a planar scene is a round body (disc, ring, sphere) among fixed bodies,
    asked past its impact until a time: a bounce run (:func:`run_in_plane`)."""
    free = [b for b in scene.bodies if b.support != "fixed"]
    until = scene.simulate.get("until")
    return (len(free) == 1 and free[0].support == "free" and not scene.joints
            and free[0].shape in ("disc", "ring", "sphere")
            and isinstance(until, (int, float, str)) and not isinstance(until, bool)
            and until not in ("separation", "restrike"))


def run_in_plane(scene: Scene) -> Outcome:
    """A planar scene of one round body among fixed bodies (:func:`bounces_in_plane`),
    followed as the 3-D bounce run of the same scene written in space: the plane z = 0,
    each contact a plane through its point with its normal, the spin about z, gravity
    along -y (g, with ``effects = ["gravity"]``); reported in the plane's keys (``x, y,
    vx, vy, omega``). The body's motion stays in the plane: every impulse, velocity and
    normal does, and its one moment of inertia is the one about z."""
    start = time.perf_counter()
    plan = make_plan(scene.simulate)
    if not set(plan.effects) <= {"gravity"}:
        raise InputError("simulate.effects", "a round body among fixed bodies is followed "
                         "past its impact under gravity alone in the plane")

    def exact(x: Any) -> Any:  # a decimal as the number it spells
        return sp.Rational(str(x)) if isinstance(x, (float, sp.Float)) else x
    values = {k: exact(v) for k, v in scene_values(scene).items()}
    (body,) = (b.at(values) for b in scene.bodies if b.support != "fixed")
    radius = dict(body.dimensions)["radius"]
    ball = Body3.sphere(body.mass, radius, (*body.position, 0), (*body.velocity, 0),
                        (0, 0, body.spin), name=body.name, inertia=body.inertia)
    planes = []
    for c in scene.contacts or (scene.contact,):
        if body.name not in (c.first, c.second) or c.bodies is None:
            raise InputError(f"{c.name}.bodies", f"each contact is a fixed body's plane "
                             f"{body.name} may strike: name {body.name}")
        c = c.at(values)
        planes.append(replace(c, normal=(*c.normal, 0), point=(*c.point, 0)))
    g = sp.Rational(str(plan.settings["g"])) if "gravity" in plan.effects else 0
    if g:
        _slower_than_light((ball,))
    run = spheres((ball,), tuple(planes), (), (0, -g, 0), None, sp.Rational(str(plan.until)))
    return _reported(run, (ball,), None, (0, -g), plan, start,
                     ("x", "y", "vx", "vy", "omega"))


LIGHT = 299_792_458  # m/s: no rigid body's point moves this fast


def _slower_than_light(balls: tuple) -> None:
    """Refuse, in one line, a sphere whose centre or surface moves at the speed of light
    or faster: under gravity (in m/s^2) the run is in SI units, and a rigid body's
    mechanics means nothing there (its bounces would also run past any budget)."""
    for b in balls:
        v, w = sp.Matrix(b.velocity), sp.Matrix(b.spin)
        for what, part, speed in (("velocity", "centre", sp.sqrt(v.dot(v))),
                                  ("spin", "surface", sp.sqrt(w.dot(w)) * b.radius)):
            if speed >= LIGHT:
                raise InputError(f"{b.name}.{what}", f"{b.name} moves at "
                                 f"{float(speed):.3g} m/s (its {part}), not below the "
                                 f"speed of light ({LIGHT:.4g} m/s): rigid bodies' "
                                 "mechanics does not hold there")


def _compliant_sphere(scene: SpaceScene, values: dict, ratio: float) -> dict[str, float]:
    """The sphere's speeds after its tangentially compliant bounce on the flat."""
    if len(scene.contacts) != 1:
        raise InputError("simulate.effects", "tangential-compliance takes one contact (a "
                         "sphere on a fixed flat) so far")
    (contact,) = scene.contacts
    if contact.laws[1].coulomb() is None or contact.laws[0].newtons_e() is None:
        raise InputError("simulate.effects", "tangential-compliance needs Newton's e and "
                         "a Coulomb contact (tangential = \"coulomb\", friction = mu)")
    ball = _the_sphere(scene, values, "simulate.effects", "tangential-compliance needs one "
                       "sphere and one fixed body")

    def number(x: Any) -> float:
        return float(sp.N(sp.sympify(x).xreplace(values), 17))

    R, m = number(ball.radius), number(ball.mass)
    inertia = number(ball.inertia[0]) / (m * R * R)  # in units of m R^2
    n = np.array([number(x) for x in contact.normal])
    if ball.name == contact.first:  # the normal from the flat into the sphere
        n = -n
    v = np.array([number(x) for x in ball.velocity])
    w = np.array([number(x) for x in ball.spin])
    if float(v @ n) >= 0:
        raise InputError("bodies", f"{ball.name} is not approaching the flat")
    v_after, w_after = sphere_bounce(v, w, n, R, inertia, number(contact.friction),
                                     number(contact.restitution), ratio, STEPS)
    return {f"{ball.name}.{k}": float(x) for k, x in
            zip(SPEEDS, (*v_after, *w_after), strict=True)}


def _the_sphere(scene: SpaceScene, values: dict, where: str, why: str) -> Any:
    """The scene's one free body, a sphere, at `values`; else `why` in one line."""
    free = [b for b in scene.bodies if b.support != "fixed"]
    if len(free) != 1 or free[0].radius is None:
        raise InputError(where, why)
    return free[0].at(values)


def _bouncing(scene: SpaceScene, values: dict, plan: Any, start: float) -> Outcome:
    """The scene's spheres among its fixed planes (every contact of a sphere and a fixed
    body a plane any sphere may strike; of two spheres, their laws when they meet, as
    ``[[pairs]]`` give), until a time or a count of impacts."""
    if not set(plan.effects) <= {"gravity", "rolling-resistance", "pivot-friction",
                                 "tangential-compliance"}:
        raise InputError("simulate.effects", "past separation a 3-D scene takes gravity, "
                         "rolling-resistance, pivot-friction and tangential-compliance")
    free = [b for b in scene.bodies if b.support != "fixed"]
    if not free or any(b.radius is None for b in free):
        raise InputError("bodies", "a 3-D scene is followed past its impact for free "
                         "spheres among fixed planes so far")
    balls = tuple(b.at(values) for b in free)
    names = {b.name for b in balls}
    if any(not names & {c.first, c.second} for c in scene.contacts):
        raise InputError("contact.bodies", "each contact is a fixed plane a sphere may "
                         "strike, or two spheres: name a sphere")
    # the contacts at the impact are struck again later: planes, or two spheres' laws
    planes = tuple(c.at(values) for c in (*scene.contacts, *scene.planes)
                   if not {c.first, c.second} <= names)
    pairs = tuple(c.at(values) for c in (*scene.contacts, *scene.pairs)
                  if {c.first, c.second} <= names)
    impacts = scene.simulate.get("impacts")
    if impacts is not None and (isinstance(impacts, bool) or not isinstance(impacts, int)
                                or not 1 <= impacts <= MAX_IMPACTS):
        raise InputError("simulate.impacts", f"a whole number from 1 to {MAX_IMPACTS}, "
                         f"got {impacts!r}")
    g = sp.Rational(str(plan.settings["g"])) if "gravity" in plan.effects else 0
    if g:
        _slower_than_light(balls)
    horizon = None if plan.until == "separation" else sp.Rational(str(plan.until))
    wear = {key: sp.Rational(str(plan.settings[key])) if key in plan.settings else 0
            for key in ("rolling_resistance", "pivot_friction")}
    run = spheres(balls, planes, pairs, (0, 0, -g), impacts, horizon, **wear,
                  compliance=plan.settings["stiffness_ratio"]
                  if "tangential-compliance" in plan.effects else None)
    return _reported(run, balls, impacts, (0, 0, -g), plan, start)


def _reported(run: Bounces, balls: tuple, impacts: Any, gravity: tuple, plan: Any,
              start: float, keys: tuple[str, ...] = ("x", "y", "z", *SPEEDS)) -> Outcome:
    """A bounce run as `simulate` reports it: its events, each sphere's state at the
    end in `keys` (a planar scene's lifted run: x, y and vx, vy, omega), and notes."""
    events: list[dict[str, Any]] = []
    for e in run.events:
        event: dict[str, Any] = {"kind": e.kind, "t": float(e.t), "plane": e.plane}
        if len(balls) > 1:
            event["ball"] = e.ball
        if e.other:
            event["with"] = e.other
        if e.kind in ("impact", "settles"):
            event["course"] = e.course
        events.append(event)
    events.append({"kind": "end", "t": float(run.t), "why": {
        "impacts": f"{impacts} impact{'s' if impacts != 1 else ''}, as asked",
        "horizon": "the time asked", "rolling": "it rolls on the plane for ever" if
        len(balls) == 1 else "every sphere rolls on for ever",
        "flying": "no plane lies ahead", "rest": "it comes to rest" if len(balls) == 1
        else "every sphere is at rest"}[run.stopped]})
    final: dict[str, float] = {}
    for name, state in run.states.items():
        final.update({f"{name}.{k}": float(sp.N(x, 17)) for k, x in zip(
            ("x", "y", "z", *SPEEDS), (*state[0], *state[1], *state[2]), strict=True)
            if k in keys})
    if "omega" in keys:  # in the plane: the spin about z
        final.update({f"{name}.omega": float(sp.N(state[2][2], 17))
                      for name, state in run.states.items()})
    details: dict[str, Any] = {"exact": run.exact,
                               "impacts": sum(e.kind == "impact" for e in run.events),
                               "gravity": [float(x) for x in gravity],
                               "stopped": run.stopped}
    if run.tolerance is not None:
        details["tolerance"] = run.tolerance
        details["notes"] = [f"an impact was struck with a sphere lying on a plane (the "
                            f"driven rule, integrated to a relative tolerance of "
                            f"{run.tolerance:g}): from there on the run is good to that"]
    elif not run.exact:
        details["notes"] = ["a time of the run is irrational: from there on it is "
                            "followed in 40-digit floating point"]
    if run.summed:
        details["summed"] = run.summed
        details.setdefault("notes", []).append(
            f"{run.summed} bounces before the time asked, in a pile-up of bounces, were "
            "summed in closed form (a geometric series)")
    settles = [e for e in run.events if e.kind == "settles"]
    if settles:
        details["settles"] = float(settles[0].t)
        details.setdefault("notes", []).append(
            "infinitely many bounces summed: with e < 1 the bounces on a plane gravity "
            "presses the sphere into pile up at a finite time (a geometric series, each "
            "flight e times the last), where it lies on the plane with the limit of its "
            "motion, in closed form")
    if "tangential-compliance" in plan.effects:
        details.setdefault("notes", []).append(
            f"each bounce of a flying sphere on a plane goes through the tangentially "
            f"compliant contact (k_t/k_n = {plan.settings['stiffness_ratio']:g}), "
            f"integrated to first order with {STEPS} steps a period, in float64; a "
            "cushion struck while lying and two spheres meeting stay rigid")
    track = (BounceTrack if len(keys) > 5 else PlaneTrack)(balls, run)
    return Outcome(plan, {**final, "t": float(run.t)}, events, time.perf_counter() - start,
                   0, details, track)


@dataclass(frozen=True)
class BounceTrack:
    """A bounce run's paths for pictures. Every phase of a sphere (flight under gravity,
    sliding under Coulomb's constant friction, rolling) moves its centre with a constant
    acceleration, and every change of phase is an event of the run; so between two of
    the run's snapshots each centre follows the quadratic fixed by its start, its
    starting velocity and its end. No physics is repeated here."""

    balls: tuple[Any, ...]
    run: Bounces

    @property
    def ball(self) -> Any:
        """The first sphere (the one a one-sphere run follows)."""
        return self.balls[0]

    def states(self, name: str | None = None) -> list[tuple[float, np.ndarray, np.ndarray]]:
        """(t, centre, velocity) of sphere `name` (the first by default) at the start,
        after each event, and at the end."""
        name = self.ball.name if name is None else name

        def vec(x: Any) -> np.ndarray:
            return np.array([float(sp.N(y, 17)) for y in x])
        return [(float(t), vec(each[name][0]), vec(each[name][1]))
                for t, each in self.run.snapshots]

    def sampled(self, count: int = 400, name: str | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
        """Times and the centre (x, y, z) of sphere `name` (the first by default) at
        each, `count` samples spread over the run and every event's own instant."""
        states = self.states(name)
        end = states[-1][0]
        # a span of bounces summed is drawn along the plane it piles up on
        piled = {(float(t0), float(t1)) for who, t0, t1 in self.run.piles
                 if who == (self.ball.name if name is None else name)}
        times = np.union1d(np.linspace(0.0, end, count) if end > 0 else np.zeros(1),
                           [s[0] for s in states])
        points = np.empty((len(times), 3))
        for i, t in enumerate(times):
            k = max(j for j in range(len(states) - 1) if states[j][0] <= t) \
                if t < end else len(states) - 2
            (t0, c0, v0), (t1, c1, _) = states[k], states[k + 1]
            span = t1 - t0
            tau = t - t0
            if (t0, t1) in piled:
                v0 = (c1 - c0) / span
            a = 2 * (c1 - c0 - v0 * span) / span ** 2 if span > 0 else np.zeros(3)
            points[i] = c0 + v0 * tau + a * tau ** 2 / 2
        return times, points

    def every(self, count: int = 400) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """Times and every sphere's centre at each, at the same instants."""
        times = self.sampled(count)[0]
        for b in self.balls[1:]:
            times = np.union1d(times, self.sampled(count, b.name)[0])
        points = {}
        for b in self.balls:
            own, path = self.sampled(count, b.name)
            points[b.name] = np.stack([np.interp(times, own, path[:, j]) for j in range(3)],
                                      axis=1)
        return times, points


@dataclass(frozen=True)
class PlaneTrack(BounceTrack):
    """A planar scene's bounce run (:func:`run_in_plane`) as a planar run's track: its
    times and each body's centre (x, y) at them."""

    @property
    def t(self) -> np.ndarray:
        return self.sampled(200)[0]

    def points(self) -> dict[str, np.ndarray]:
        return {self.ball.name: self.sampled(200)[1][:, :2]}
