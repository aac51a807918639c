"""Free flight after an impact at several contacts, until one of them closes again.

The impact itself is the scene's rule (:mod:`rigidimpact.solve.collision`), solved exactly.
After it no force acts but gravity (when asked for), so each body's centre follows a
parabola and its orientation turns steadily: positions are written down, not integrated.
The run ends at the time asked for, or earlier at the first time one of the scene's own
contacts closes again (after that the free flight would let the bodies pass through one
another, so the run stops there and says so). What is watched, per contact:

- two round bodies (disc, ring, sphere): never again on their own. Both fall alike, so
  their relative motion is a straight line, and the distance between the centres is a
  convex function of time: once it grows it never comes back;
- a body against a fixed one: the contact's material point (for a round body, its
  surface) against the fixed body's plane through the contact point. The gap
  ``g(t) = n . (x(t) - x0)`` (sign chosen so that opening is positive) has bounded rate
  and curvature on a finite window, so the search of :mod:`rigidimpact.simulate.flight`
  certifies every interval it skips;
- a point (particle) against a barbell, rod or round body: the exact search of
  :mod:`rigidimpact.simulate.flight`.

Other pairs (two free bodies with no shape, a pair that is not one of the scene's
contacts) are not watched; a run past the impact is refused for the first and the
documentation says so for the second.

Examples
--------
>>> from rigidimpact.scenes.scene import load_scene
>>> import rigidimpact
>>> from pathlib import Path
>>> root = Path(rigidimpact.__file__).parents[2]
>>> outcome = run_several(load_scene(root / "derivations" / "rod-lands-flat.toml"))
>>> outcome.final["rod.vy"], outcome.final["rod.omega"]
(1.0, -0.5)
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.model.shapes import is_round, is_segment
from rigidimpact.scenes.scene import Scene
from rigidimpact.simulate.flight import Flyer, _certified_first_root, first_contact
from rigidimpact.simulate.outcome import FlightTrack, Outcome, finite, flyer
from rigidimpact.simulate.planner import make_plan
from rigidimpact.solve.derivation import physics_warnings, read_values
from rigidimpact.solve.solution import Solution

__all__ = ["run_several", "scene_numbers", "Watch", "watches", "SeveralTrack"]

@dataclass(frozen=True)
class Watch:
    """How one contact is watched after the impact: the first time it closes again."""

    touch: str
    first_touch: Callable[[float], float | None]  # horizon -> first closing time or None
    how: str


@dataclass(frozen=True)
class SeveralTrack:
    """Closed-form flight of every moving body from the impact to ``t_end``.

    ``points()`` gives what a one-contact run's track gives (each body's centre, a
    segment's ends) and, for a body without a drawn shape (``rigid``), its contact points
    too, so a rod given by its inertia shows its ends.
    """

    flyers: tuple[Flyer, ...]
    marks: tuple[tuple[str, int, tuple[float, ...]], ...]  # (label, flyer index, offset)
    t_end: float

    @property
    def _track(self):
        return FlightTrack(self.flyers, self.t_end)

    @property
    def t(self) -> np.ndarray:
        return self._track.t

    def points(self) -> dict[str, np.ndarray]:
        out = self._track.points()
        for label, index, offset in self.marks:
            f = self.flyers[index]
            out[label] = np.array([f.carried(offset, t) for t in self.t])
        return out


def _flyer(body: Body, gravity: float) -> Flyer:
    """A body just after the impact (exact numbers) as a float flyer in the world frame."""
    return replace(flyer(body, {}), gravity=gravity)


def _against_fixed(touch: Contact, f: Flyer, sign: float, round_body: bool) -> Watch:
    """The gap between a moving body's contact point and a fixed body's plane."""
    n = sign * np.array([float(c) for c in touch.unit_normal])  # opening direction
    point = np.array([float(c) for c in touch.point])
    offset = (0.0, 0.0) if round_body else tuple(point - np.asarray(f.position, float))
    x0 = np.asarray(f.position, float) + offset  # the watched point at the impact
    reach = math.hypot(*offset)
    w = float(f.spin)
    v0 = np.asarray(f.velocity, float)
    down = -f.gravity * n[1]  # the gap's acceleration from gravity (n . (0, -g))

    def gap(t: float) -> float:
        return float(n @ (f.carried(offset, t) - x0))

    def rate(t: float) -> float:  # n . (v(t) + omega z x r(t))
        r = f.carried(offset, t) - f.at(t)[0]
        return float(n @ (f.velocity_at(t) + w * np.array([-r[1], r[0]])))

    def centre(t: float) -> float:  # the centre's opening coordinate, a parabola
        return float(n @ (np.asarray(f.position, float) - x0)) + float(n @ v0) * t \
            + 0.5 * down * t * t

    def bound(horizon: float) -> float:
        """A time by which a first touch, if any, must have come: the flight's own, at
        most the horizon (so the search's scales do not grow with a far horizon)."""
        return min(horizon, natural())

    def natural() -> float:
        """The time past which the contact cannot close: the centre's parabola has fallen
        more than the reach below the plane, or risen past it for good."""
        a, b, c0 = 0.5 * down, float(n @ v0), centre(0.0) + reach
        if a < 0.0:  # gravity closes the gap: the centre's parabola falls below -reach
            return (-b - math.sqrt(b * b - 4 * a * c0)) / (2 * a)
        if a == 0.0 and b < 0.0:
            return c0 / -b
        if a == 0.0 and b == 0.0:
            return 2 * math.pi / abs(w) if w else 0.0
        # opening for good: past the time the centre is more than reach away, none
        far = centre(0.0) - reach
        if a == 0.0:
            return max(0.0, -far / b)
        return max(0.0, (-b + math.sqrt(max(b * b - 4 * a * far, 0.0))) / (2 * a))

    def first_touch(horizon: float) -> float | None:
        stop = bound(horizon)
        speed = float(np.linalg.norm(v0)) + abs(down) * stop
        curvature = w * w * reach + abs(down) + 1e-300
        slope = rate(0.0)
        if slope <= 1e-12 * max(speed, abs(w) * reach, 1e-300):
            # not opening: the contact stays closed if the gap bends inward at once
            if -w * w * float(n @ np.asarray(offset)) + down < 0.0 or \
                    stop > 0.0 and gap(1e-9 * stop) < 0:
                return 0.0
            start = 1e-9 * stop
        if not stop > 0.0:
            return None
        else:
            start = min(slope / curvature, stop)
        if start >= stop:
            return None
        return _certified_first_root(gap, rate, start, stop, speed + abs(w) * reach,
                                     curvature, 1e-14 * max(stop, 1.0))

    what = "surface" if round_body else "contact point"
    return Watch(touch.name, first_touch, f"the {what} of {f.name} against the fixed plane")


def watches(touches: Sequence[Contact], flyers: Mapping[str, Flyer],
            shapes: Mapping[str, str]) -> tuple[Watch, ...]:
    """One watch per contact (see the module's notes), or an InputError for a pair that
    cannot be watched."""
    out = []
    for touch in touches:
        a, b = shapes[touch.first], shapes[touch.second]
        if "fixed" in (a, b):
            moving = touch.second if a == "fixed" else touch.first
            sign = 1.0 if a == "fixed" else -1.0
            out.append(_against_fixed(touch, flyers[moving], sign,
                                      is_round(shapes[moving])))
        elif is_round(a) and is_round(b):
            out.append(Watch(touch.name, lambda horizon: None,
                             "round bodies: never again on their own"))
        elif "particle" in (a, b) and (is_round(a) or is_round(b) or is_segment(a)
                                       or is_segment(b)):
            ball = flyers[touch.first if a == "particle" else touch.second]
            other = flyers[touch.second if a == "particle" else touch.first]

            def first_touch(horizon, ball=ball, other=other):
                hit = first_contact(ball, other, horizon)
                return None if hit is None else hit.t

            out.append(Watch(touch.name, first_touch, f"{ball.name} against {other.name}"))
        else:
            raise InputError("simulate.until", f"after the impact, contact {touch.name} "
                             f"({a} against {b}) cannot be watched for a next touch: "
                             "give until = \"separation\", or give the bodies shapes "
                             "(round, or a particle against a rod or barbell, or a fixed "
                             "body)")
    return tuple(out)


def _fly(scene: Scene, outcome: Solution, until: str | float, gravity: float):
    """The flight after one rule's impact: flyers, the events, the end time and why."""
    shapes = {b.name: b.shape for b in scene.bodies}
    moving = [b for b in outcome.after if b.support != "fixed"]
    flyers = {b.name: _flyer(b, gravity) for b in moving}
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0,
                                     "acted": list(outcome.acted)}]
    if until == "separation":
        return flyers, events, 0.0, "the bodies separate at the impact (until = separation)"
    horizon = math.inf if until == "restrike" else float(until)
    found = []
    for watch in watches(scene.contacts, flyers, shapes):
        t = watch.first_touch(horizon)
        if t is not None and t <= horizon:
            found.append((t, watch))
    if found:
        t = min(when for when, _ in found)
        tied = [w for when, w in found if when <= t + 1e-12 * max(t, 1e-300)]
        names = [w.touch for w in tied]
        if t == 0.0:
            events.append({"kind": "stays-closed", "t": 0.0, "contacts": names})
            return flyers, events, 0.0, (f"contact {', '.join(names)} does not open: it "
                                         "would need a lasting contact force, which free "
                                         "flight does not have")
        events.append({"kind": "restrike", "t": t, "contacts": names})
        return flyers, events, t, (f"contact {', '.join(names)} closes again "
                                   f"({'; '.join(w.how for w in tied)}); the flight cannot "
                                   "go on through it")
    if math.isfinite(horizon):
        return flyers, events, horizon, f"reached until = {horizon:g} s"
    return flyers, events, 0.0, "no contact of the scene closes again"


def scene_numbers(scene: Scene, values: Mapping[sp.Symbol, Any] | None = None
                  ) -> dict[sp.Symbol, sp.Expr]:
    """The scene's [values] (or `values`), checked through the one door, exact; every
    symbol of its data must have one, or one line says which do not."""
    raw = dict(scene.values if values is None else values)
    exact = read_values({k.name: v for k, v in raw.items()}, {}, scene.data_symbols,
                        scene.roles, scene.name)
    missing = sorted(set(scene.data_symbols) - {s.name for s in exact})
    if missing:
        raise InputError("values", f"simulate needs numbers for: {', '.join(missing)}")
    return dict(exact)


def run_several(scene: Scene, values: Mapping[sp.Symbol, Any] | None = None):
    """Simulate a several-contact scene: its rule's impact, then free flight.

    With the sequential rule and no order, every order is flown; ``final`` is the first
    order's and ``orders`` in the details gives each one's.
    """
    start = time.perf_counter()
    plan = make_plan(scene.simulate)
    if any(step.model == "compliant" for step in plan.steps):
        raise InputError("simulate.effects", "with several contacts the impact's own "
                         "compliance is chosen by [impact] rule = \"compliant\"; the "
                         "compliance effects are for one contact")
    exact = scene_numbers(scene, values)
    outcomes = scene.outcomes(exact)
    g = plan.settings["g"] if "gravity" in plan.effects else 0.0
    runs = [(o, *_fly(scene, o, plan.until, g)) for o in outcomes]
    outcome, flyers, events, t_end, why = runs[0]
    events.append({"kind": "end", "t": t_end, "why": why})
    details: dict[str, Any] = {"rule": outcome.label, "acted": list(outcome.acted)}
    if len(runs) > 1:
        details["orders"] = [{"order": list(o.order), "acted": list(o.acted),
                              "final": _final(f, t), "ends": w} for o, f, _, t, w in runs]
    energy = {"energy_loss_fraction": float(outcome.energy_loss_fraction)}
    warnings = (*physics_warnings(energy, None, f"the {scene.rule} rule",
                                  outcome.energy_tolerance), *outcome.notes)
    if warnings:
        details["warnings"] = list(warnings)
    order = list(flyers)
    marks = []
    for touch in scene.contacts:
        for name in (touch.first, touch.second):
            body = next(b for b in scene.bodies if b.name == name)
            if name in flyers and body.shape == "rigid":
                offset = tuple(float(c) for c in touch.point - body.position)
                marks.append((f"{name}@{touch.name}", order.index(name), offset))
    track = SeveralTrack(tuple(flyers.values()), tuple(marks), t_end)
    return finite(Outcome(plan, _final(flyers, t_end), events,
                           time.perf_counter() - start, details=details, trajectory=track))


def _final(flyers: Mapping[str, Flyer], t_end: float) -> dict[str, float]:
    final: dict[str, float] = {}
    for body in flyers.values():
        place, turn = body.at(t_end)
        velocity = body.velocity_at(t_end)
        final |= {f"{body.name}.vx": float(velocity[0]), f"{body.name}.vy": float(velocity[1]),
                  f"{body.name}.omega": float(body.spin), f"{body.name}.x": float(place[0]),
                  f"{body.name}.y": float(place[1]), f"{body.name}.turn": turn}
    final["t"] = t_end
    return final
