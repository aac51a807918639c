"""Compliant models, integrated with scipy only when a scene asks for them.

Two effects, each optional:

``rod-compliance``
    A barbell's rod becomes a spring of stiffness ``rod_stiffness`` between its two point
    masses (rest length 2L). This is the paper's thought experiment of section 2: the ball
    pushes sphere A along +x only; A gains its -y velocity afterwards, from the rod.
``contact-compliance``
    The contact becomes a spring-dashpot along the line of impact between the two material
    points that touch at O: force ``max(0, k d + c d')`` for penetration d > 0. It can push
    but never pull, so it lets go when ``k d + c d'`` reaches zero, before d does; the
    textbook formula ``e = exp(-pi z / sqrt(1 - z^2))`` does not hold for it.
    :func:`restitution_of` gives e of the isolated contact from the damping ratio z in
    closed form, and :func:`damping_ratio_for` inverts it. e falls like 1/(4 z^2): e = 0
    would need infinite damping, so z is capped at ``MAX_DAMPING_RATIO`` and the e reached
    is reported.

Without ``contact-compliance`` the contact stays rigid: each time the touching points
approach, Newton's e acts in an instant (which can happen again as a springy rod rings).
Without ``rod-compliance`` every body moves rigidly.

Examples
--------
>>> round(restitution_of(0.0), 12), round(restitution_of(1.0), 12)
(1.0, 0.135335283237)
>>> round(damping_ratio_for(restitution_of(0.3)), 12)
0.3
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import MAX_DAMPING_RATIO, damping_ratio_for, restitution_of
from rigidimpact.laws.law import Smooth
from rigidimpact.model.bodies import Body
from rigidimpact.model.shapes import is_round
from rigidimpact.scenes.scene import Scene
from rigidimpact.simulate.numbers import as_array, as_float
from rigidimpact.simulate.outcome import Outcome
from rigidimpact.simulate.planner import Plan

__all__ = ["restitution_of", "damping_ratio_for", "run_compliant", "prepare", "Model",
           "Trajectory", "MAX_DAMPING_RATIO", "choose_integrator"]

SETTLE_PERIODS = 3  # after the last contact, watch this many of the slowest periods
MAX_SEGMENTS = 2000  # contact changes (or instant impacts) before giving up
MAX_STEPS = 200_000  # an estimate above this is refused: the run would take minutes
# an explicit method's step of the barbell's compliant model took about 0.3 ms here
# (80,030 steps in 23 s): above this estimate (about 12 s) the run is refused
MAX_EXPLICIT_STEPS = 40_000
# a run whose right-hand side has been evaluated this often, times the size of its
# state, is stopped in one line: a budget of work, so the same scene stops at the same
# place on every machine at any load (the stiffest run of the tests, a stiffness ratio
# of 1e8 under LSODA, makes 154,813 evaluations of 13 equations: 2.0e6)
MAX_RHS_WORK = 10_000_000
STEPS_PER_PERIOD = 4  # explicit methods step at most a quarter of the fastest period
SAMPLES_PER_PERIOD = 40  # plot samples per fastest period, from the dense output
MAX_SAMPLES = 4000  # per segment between events


# ---- the model ------------------------------------------------------------------------

@dataclass(frozen=True)
class Trajectory:
    """Sampled states of a run, for plots: ``points(name)`` gives (t, positions)."""

    t: np.ndarray
    y: np.ndarray
    parts: tuple
    # the contact point in the scene's frame: the run is followed seen from it
    origin: np.ndarray = field(default_factory=lambda: np.zeros(2))

    def points(self) -> dict[str, np.ndarray]:
        """Each body's tracked points over time, in the scene's frame: name -> array
        (samples, 2)."""
        out = {}
        for p in self.parts:
            s = p.slot
            if p.kind == "spring":
                out[f"{p.name}.A"] = self.y[:, s:s + 2] + self.origin
                out[f"{p.name}.B"] = self.y[:, s + 2:s + 4] + self.origin
            else:
                out[p.name] = self.y[:, s:s + 2] + self.origin
        return out

    def contact_velocity(self, name: str) -> np.ndarray:
        """Velocity of a body's touching point (sphere A for a sprung barbell)."""
        for p in self.parts:
            if p.name == name:
                return np.array([_contact_point(p, row)[1] for row in self.y])
        raise KeyError(name)


@dataclass
class _Part:
    """One body in the state vector: a point, a rigid body, or a sprung barbell."""

    name: str
    kind: str  # "point" | "rigid" | "spring"
    slot: int  # first index in the state vector
    mass: float
    inertia: float = 0.0
    contact: np.ndarray | None = None  # rigid: the touching point relative to the centre
    round: bool = False  # disc, ring, sphere: the touching point stays on the normal
    rest: float = 0.0  # spring: rest length
    stiffness: float = 0.0

    @property
    def size(self) -> int:
        return {"point": 4, "rigid": 6, "spring": 8}[self.kind]


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    """z component of the cross product of two plane vectors."""
    return float(a[0] * b[1] - a[1] * b[0])


def _build(body: Body, slot: int, values: Mapping, plan: Plan) -> tuple[_Part, list[float]]:
    mass, position = as_float(body.mass, values), as_array(body.position, values)
    velocity, spin = as_array(body.velocity, values), as_float(body.spin, values)
    if body.shape == "barbell" and "rod-compliance" in plan.effects:
        a, b = (as_array(p.position, values) for p in body.parts)
        va, vb = (velocity + spin * np.array([-(r - position)[1], (r - position)[0]])
                  for r in (a, b))
        part = _Part(body.name, "spring", slot, mass, as_float(body.inertia, values),
                     rest=float(np.linalg.norm(b - a)),
                     stiffness=plan.settings["rod_stiffness"])
        return part, [*a, *b, *va, *vb]
    inertia = as_float(body.inertia, values)
    if inertia == 0.0:
        return _Part(body.name, "point", slot, mass), [*position, *velocity]
    # a round body touches at the surface point facing the other body, whatever its spin:
    # that point does not turn with the material, so a normal force there has no torque
    # about the centre when the normal passes through it
    return (_Part(body.name, "rigid", slot, mass, inertia, contact=-position,
                  round=is_round(body.shape)),
            [*position, 0.0, *velocity, spin])


def _contact_point(part: _Part, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity of the part's touching point: the material point that touched
    at O, or for a round body the surface point facing along the original normal."""
    s = part.slot
    if part.kind == "point":
        return y[s:s + 2], y[s + 2:s + 4]
    if part.kind == "spring":  # the struck sphere comes first
        return y[s:s + 2], y[s + 4:s + 6]
    c, phi, v, w = y[s:s + 2], y[s + 2], y[s + 3:s + 5], y[s + 5]
    assert part.contact is not None  # a rigid part keeps its touching point
    if part.round:
        r = part.contact
    else:
        rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        r = rot @ part.contact
    return c + r, v + w * np.array([-r[1], r[0]])


def _application_point(first: _Part, second: _Part, y: np.ndarray) -> np.ndarray:
    """The one point where the contact force acts on both bodies (same line of action, so
    the pair's angular momentum is kept): a point mass's place, else a round body's
    surface point, else midway between the two touching points."""
    for part in (first, second):
        if part.kind in ("point", "spring"):
            return _contact_point(part, y)[0]
    for part in (first, second):
        if part.round:
            return _contact_point(part, y)[0]
    return (_contact_point(first, y)[0] + _contact_point(second, y)[0]) / 2


def _apply(part: _Part, dy: np.ndarray, y: np.ndarray, force: np.ndarray,
           point: np.ndarray) -> None:
    """Add a force acting at `point` to the part's accelerations."""
    s = part.slot
    if part.kind == "point":
        dy[s + 2:s + 4] += force / part.mass
    elif part.kind == "spring":
        dy[s + 4:s + 6] += force / (part.mass / 2)
    else:
        dy[s + 3:s + 5] += force / part.mass
        dy[s + 5] += _cross(point - y[s:s + 2], force) / part.inertia


def _free(part: _Part, y: np.ndarray, dy: np.ndarray, g: float = 0.0) -> None:
    """Kinematics, gravity (along -y) and the rod spring's forces."""
    s = part.slot
    if part.kind == "point":
        dy[s:s + 2] = y[s + 2:s + 4]
        dy[s + 3] -= g
    elif part.kind == "rigid":
        dy[s:s + 3] = y[s + 3:s + 6]
        dy[s + 4] -= g
    else:
        dy[s:s + 4] = y[s + 4:s + 8]
        dy[s + 5] -= g
        dy[s + 7] -= g
        d = y[s + 2:s + 4] - y[s:s + 2]
        length = math.hypot(*d)
        pull = part.stiffness * (length - part.rest) * d / length  # on A toward B
        each = part.mass / 2
        dy[s + 4:s + 6] += pull / each
        dy[s + 6:s + 8] -= pull / each


def _effective_mass(part: _Part, y: np.ndarray, normal: np.ndarray,
                    point: np.ndarray | None = None) -> float:
    """The mass a normal impulse at `point` (default: the touching point) meets."""
    if part.kind == "point":
        return part.mass
    if part.kind == "spring":
        return part.mass / 2
    if point is None:
        point, _ = _contact_point(part, y)
    arm = _cross(point - y[part.slot:part.slot + 2], normal)
    return 1.0 / (1.0 / part.mass + arm * arm / part.inertia)


def _rigid_effective_mass(part: _Part, y: np.ndarray, normal: np.ndarray) -> float:
    """Effective mass at the touching point with the body held rigid (a sprung rod too)."""
    if part.kind != "spring":
        return _effective_mass(part, y, normal)
    s = part.slot
    centre = (y[s:s + 2] + y[s + 2:s + 4]) / 2
    arm = _cross(y[s:s + 2] - centre, normal)
    return 1.0 / (1.0 / part.mass + arm * arm / part.inertia)


def _energy(parts: list[_Part], y: np.ndarray, g: float = 0.0) -> tuple[float, float]:
    """Kinetic energy, and the energy stored in rod springs and in height (gravity)."""
    kinetic = stored = 0.0
    for p in parts:
        s = p.slot
        if p.kind == "point":
            kinetic += 0.5 * p.mass * float(y[s + 2:s + 4] @ y[s + 2:s + 4])
            stored += p.mass * g * y[s + 1]
        elif p.kind == "rigid":
            kinetic += 0.5 * p.mass * float(y[s + 3:s + 5] @ y[s + 3:s + 5])
            kinetic += 0.5 * p.inertia * y[s + 5] ** 2
            stored += p.mass * g * y[s + 1]
        else:
            kinetic += 0.25 * p.mass * float(y[s + 4:s + 8] @ y[s + 4:s + 8])
            stretch = math.hypot(*(y[s + 2:s + 4] - y[s:s + 2])) - p.rest
            stored += 0.5 * p.stiffness * stretch**2
            stored += 0.5 * p.mass * g * (y[s + 1] + y[s + 3])
    return kinetic, stored


def _final(part: _Part, y: np.ndarray, origin: np.ndarray) -> dict[str, float]:
    """Centre velocity and spin (angular momentum about the centre over rigid inertia),
    and the centre in the scene's frame (the run's seen from the contact point `origin`)."""
    s = part.slot
    if part.kind == "point":
        v, w, c = y[s + 2:s + 4], 0.0, y[s:s + 2]
    elif part.kind == "rigid":
        v, w, c = y[s + 3:s + 5], y[s + 5], y[s:s + 2]
    else:
        a, b, va, vb = y[s:s + 2], y[s + 2:s + 4], y[s + 4:s + 6], y[s + 6:s + 8]
        c, v = (a + b) / 2, (va + vb) / 2
        each = part.mass / 2
        w = each * (_cross(a - c, va - v) + _cross(b - c, vb - v)) / part.inertia
    return {f"{part.name}.vx": float(v[0]), f"{part.name}.vy": float(v[1]),
            f"{part.name}.omega": float(w), f"{part.name}.x": float(c[0] + origin[0]),
            f"{part.name}.y": float(c[1] + origin[1])}


def choose_integrator(fast: float, slow: float, tolerance: float) -> dict[str, Any]:
    """An integrator and tolerances for time scales `fast` < `slow` (seconds).

    Examples
    --------
    >>> choose_integrator(1e-6, 1e-2, 1e-6)["method"]
    'LSODA'
    >>> choose_integrator(1e-3, 1e-2, 1e-6)["method"]
    'DOP853'
    """
    ratio = (slow / fast) ** 2  # the stiffness ratio: squared ratio of natural frequencies
    rtol = max(tolerance * 1e-2, 1e-12)
    if ratio > 1e4:
        return {"method": "LSODA", "rtol": rtol, "stiffness_ratio": ratio,
                "why": f"stiffness ratio {ratio:.1e} > 1e4: LSODA switches to BDF when the "
                       "stiff mode dominates and back to Adams when it does not"}
    return {"method": "DOP853", "rtol": rtol, "stiffness_ratio": ratio,
            "why": f"stiffness ratio {ratio:.1e} <= 1e4: an explicit 8th-order method is "
                   "cheapest"}


@dataclass(frozen=True)
class Model:
    """A compliant model ready to integrate: its parts, initial state and time scales."""

    parts: tuple
    y0: np.ndarray
    normal: np.ndarray
    e: float
    k_c: float
    c_c: float
    fast: float
    slow: float
    integrator: dict
    contact: dict


def prepare(scene: Scene, plan: Plan, values: Mapping) -> Model:
    """Build the compliant model of a scene and pick its integrator (nothing is run).

    Raises
    ------
    InputError
        For a question the compliant models cannot answer.
    """
    if plan.until == "restrike":
        raise InputError("simulate.until", "the re-strike search runs on rigid bodies; "
                         "drop the compliance effects or ask for a time")
    if "rod-compliance" in plan.effects and not any(b.shape == "barbell"
                                                    for b in scene.bodies):
        raise InputError("simulate.effects", "rod-compliance needs a barbell in the scene")
    if scene.contact.laws[1].grips:
        raise InputError("contact.tangential", "the compliant models have a smooth contact")
    parts, state, slot = [], [], 0
    for body in scene.pair:  # seen from the contact point
        part, initial = _build(body, slot, values, plan)
        parts.append(part)
        state += initial
        slot += part.size
    state.append(0.0)  # work done by the contact force on the bodies
    normal = as_array(scene.contact.frame[0, :], values)
    normal /= np.linalg.norm(normal)
    first, second = parts
    e = as_float(scene.contact.restitution, values)
    y0 = np.array(state)
    # the isolated contact: the two bodies as rigid, meeting at O (a stiff rod is rigid
    # on the contact's time scale); its damping returns the requested e
    mu = 1.0 / (1.0 / _rigid_effective_mass(first, y0, normal)
                + 1.0 / _rigid_effective_mass(second, y0, normal))
    periods = []
    contact_info: dict[str, Any] = {"requested_e": e}
    k_c = c_c = 0.0
    if "contact-compliance" in plan.effects:
        k_c = plan.settings["contact_stiffness"]
        z = damping_ratio_for(e)
        c_c = 2 * z * math.sqrt(k_c * mu)
        contact_info |= {"model": "push-only spring-dashpot", "stiffness": k_c,
                         "damping_ratio": z, "damping": c_c,
                         "reached_e": restitution_of(z)}
        if z == MAX_DAMPING_RATIO and e < contact_info["reached_e"]:
            contact_info["note"] = (f"e = {e:g} needs unbounded damping; capped at "
                                    f"z = {MAX_DAMPING_RATIO:g}, giving e = "
                                    f"{contact_info['reached_e']:.2g}")
        periods.append(2 * math.pi * math.sqrt(mu / k_c))
        if z > 0:
            periods.append(mu / c_c)  # the dashpot's own time
    else:
        contact_info |= {"model": "rigid: Newton's e in an instant", "reached_e": e}
    for p in parts:
        if p.kind == "spring":
            periods.append(2 * math.pi * math.sqrt(p.mass / 4 / p.stiffness))
    approach = float(normal @ (_contact_point(first, y0)[1] - _contact_point(second, y0)[1]))
    if approach <= 0:
        raise InputError("bodies", "the bodies are not approaching at O")
    fast, slow = min(periods), max(periods)
    springs = any(p.kind == "spring" for p in parts)
    watched = SETTLE_PERIODS * slow if plan.until == "separation" else float(plan.until)
    # the fast mode is followed as long as a rod spring rings, else only while touching
    estimate = STEPS_PER_PERIOD * (watched if springs else SETTLE_PERIODS * slow) / fast
    integrator = choose_integrator(fast, slow, plan.settings["tolerance"])
    if plan.integrator != "auto":
        integrator |= {"method": plan.integrator, "why": "asked for by the scene"}
    # an explicit method takes about the estimated steps; an implicit one far fewer on a
    # stiff problem, where the run's own budget of work (MAX_RHS_WORK) is the bound
    explicit = integrator["method"] in ("RK45", "DOP853")
    if estimate > (MAX_EXPLICIT_STEPS if explicit else MAX_STEPS):
        raise InputError("simulate", f"this run would take about {estimate:.1e} integration "
                         f"steps (the fastest period is {fast:.2e} s, followed for "
                         f"{watched:.3g} s); ask for a shorter time or stiffnesses closer "
                         "together")
    return Model(tuple(parts), y0, normal, e, k_c, c_c, fast, slow, integrator, contact_info)


def _apart_after(parts: list[_Part], y: np.ndarray, normal: np.ndarray) -> float | None:
    """How long from now the touching points of rigid bodies in free flight may still
    meet, or None if no bound holds (they do not draw apart).

    Gravity moves both bodies alike, so the penetration ``n . (p1 - p2)`` is linear in
    time plus one sinusoid per spinning body, each no larger than that body's arm:
    once the linear part has fallen below minus the arms' sum, it stays negative.
    """
    first, second = parts
    level, rate, reach = 0.0, 0.0, 0.0
    for part, sign in ((first, 1.0), (second, -1.0)):
        s = part.slot
        if part.kind == "point":
            level += sign * float(normal @ y[s:s + 2])
            rate += sign * float(normal @ y[s + 2:s + 4])
            continue
        assert part.kind == "rigid" and part.contact is not None
        point, _ = _contact_point(part, y)
        arm = point - y[s:s + 2]
        rate += sign * float(normal @ y[s + 3:s + 5])
        if part.round or y[s + 5] == 0.0:
            level += sign * float(normal @ point)
        else:
            level += sign * float(normal @ y[s:s + 2])
            reach += float(np.linalg.norm(arm))
    if rate >= 0.0:
        return None
    return max(0.0, (level + reach) / -rate)


def _fly(parts: list[_Part], y: np.ndarray, dt: float, g: float) -> np.ndarray:
    """Rigid bodies (and points) in free flight for `dt`, in closed form."""
    y = y.copy()
    for part in parts:
        s = part.slot
        place, speed = (slice(s, s + 2), slice(s + 2, s + 4)) if part.kind == "point" \
            else (slice(s, s + 2), slice(s + 3, s + 5))
        y[place] += y[speed] * dt + np.array([0.0, -0.5 * g * dt * dt])
        y[speed] += np.array([0.0, -g * dt])
        if part.kind == "rigid":
            y[s + 2] += y[s + 5] * dt
    return y


class _OutOfTime(Exception):
    """Raised from the right-hand side when a run passes its budget of work."""

    def __init__(self, t: float) -> None:
        super().__init__(t)
        self.t = t


def _scales(parts: list[_Part], y0: np.ndarray, normal: np.ndarray,
            fast: float) -> np.ndarray:
    """The size of each state component, for absolute tolerances: positions on the scale
    of the contact's squeeze (speed times the fastest period), velocities on the speed's,
    angles and spins through each body's arm, the work on the energy's. One scale for
    all would let a large spin loosen the squeeze that sets e."""
    first, second = parts
    speed = abs(float(normal @ (_contact_point(first, y0)[1] - _contact_point(second, y0)[1])))
    squeeze = speed * fast / (2 * math.pi)
    scales = np.empty_like(y0)
    for p in parts:
        s = p.slot
        if p.kind == "point":
            scales[s:s + 4] = [squeeze, squeeze, speed, speed]
        elif p.kind == "spring":
            scales[s:s + 8] = [squeeze] * 4 + [speed] * 4
        else:
            assert p.contact is not None  # a rigid part keeps its touching point
            arm = float(np.linalg.norm(p.contact)) or 1.0
            scales[s:s + 6] = [squeeze, squeeze, squeeze / arm, speed, speed, speed / arm]
    scales[-1] = sum(_energy(parts, y0)) or 1.0
    return scales


def _max_step(parts: list[_Part], y: np.ndarray, fast: float, resolving: bool,
              explicit: bool) -> float:
    """The longest step that cannot skip a contact event.

    While the contact acts or a rod spring rings, an explicit method steps at most a
    quarter of the fastest period. In free flight of rigid bodies the gap between the
    touching points is linear in time plus one sinusoid per spinning body, so an eighth
    of the fastest turn is short enough to see it change sign.
    """
    if resolving:
        return fast / STEPS_PER_PERIOD if explicit else np.inf
    spins = [abs(y[p.slot + 5]) for p in parts if p.kind == "rigid" and not p.round]
    fastest = max(spins, default=0.0)
    return math.pi / 4 / fastest if fastest > 0 else np.inf


def run_compliant(scene: Scene, plan: Plan, values: Mapping, start: float):
    """Integrate the compliant model until the bodies have separated (or the set time)."""
    model = prepare(scene, plan, values)
    parts, y0, normal = list(model.parts), model.y0, model.normal
    first, second = parts
    k_c, c_c, fast, slow = model.k_c, model.c_c, model.fast, model.slow
    integrator, contact_info = model.integrator, model.contact
    compliant_contact = "contact-compliance" in plan.effects
    atol = integrator["rtol"] * _scales(parts, y0, normal, fast)

    def penetration(y: np.ndarray) -> tuple[float, float]:
        (p1, v1), (p2, v2) = _contact_point(first, y), _contact_point(second, y)
        return float(normal @ (p1 - p2)), float(normal @ (v1 - v2))

    g = plan.settings["g"] if "gravity" in plan.effects else 0.0

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        dy = np.zeros_like(y)
        for p in parts:
            _free(p, y, dy, g)
        if compliant_contact:
            d, rate = penetration(y)
            push = k_c * d + c_c * rate if d > 0 else 0.0
            if push > 0:
                point = _application_point(first, second, y)
                _apply(second, dy, y, push * normal, point)
                _apply(first, dy, y, -push * normal, point)
                dy[-1] = -push * rate
        return dy

    touches, lets_go = _contact_events(penetration, k_c, c_c)

    law = scene.contact.laws[0]

    def impulse(y: np.ndarray) -> np.ndarray:
        return _rigid_impulse(parts, normal, law, values, y, penetration(y)[1])

    calls = [0]
    most = MAX_RHS_WORK // max(len(y0), 1)

    def timed(t_now: float, y_now: np.ndarray) -> np.ndarray:
        calls[0] += 1
        if calls[0] > most:
            raise _OutOfTime(t_now)
        return rhs(t_now, y_now)

    horizon = math.inf if plan.until == "separation" else float(plan.until)
    touching = compliant_contact  # at t = 0 the points meet, approaching
    t, y = 0.0, y0 if compliant_contact else impulse(y0)
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0}]
    steps, quiet_since = 0, 0.0
    times, states = [0.0], [y.copy()]
    explicit = integrator["method"] in ("RK45", "DOP853")
    springs = any(p.kind == "spring" for p in parts)
    why = ""
    apart = None  # with rigid bodies apart for good: the time past which none can meet
    flown = None  # the state where the closed-form flight began
    for _ in range(MAX_SEGMENTS):
        if apart is not None and t >= apart and not touching:
            # no force acts and the touching points stay apart: closed form to the end
            flown, y = y, _flown_to(parts, y, horizon, t, g)
            times.append(horizon)
            states.append(y.copy())
            why = (f"reached until = {horizon:g} s (free flight from t = {t:.6g} s in "
                   "closed form: the touching points draw apart for good)")
            t = horizon
            break
        if touching:
            stop = min(horizon, t + SETTLE_PERIODS * slow)
        elif math.isfinite(horizon):
            stop = horizon
            if not springs:  # free flight: followed only while the points may meet
                wait = _apart_after(parts, y, normal)
                if wait is not None and t + wait < horizon:
                    stop = apart = t + wait
                    if wait == 0.0:
                        continue
                elif wait is None and (horizon - t) / _max_step(parts, y, fast, False,
                                                                explicit) > MAX_STEPS:
                    raise InputError("simulate.until", f"until = {horizon:g} s: after "
                                     f"t = {t:.3g} s the bodies do not draw apart, so they "
                                     "may touch again at any time, and following them that "
                                     "long would take more than "
                                     f"{MAX_STEPS} steps; ask for a shorter time")
        else:
            stop = quiet_since + SETTLE_PERIODS * slow
        if t >= stop:
            why = (f"reached until = {horizon:g} s" if t >= horizon else
                   f"separated, and no new contact within {SETTLE_PERIODS} of the slowest "
                   f"periods ({slow:.3g} s) after the last one")
            break
        from scipy.integrate import solve_ivp  # scipy on first use

        try:
            sol = solve_ivp(timed, (t, stop), y, method=integrator["method"],
                            rtol=integrator["rtol"], atol=atol,
                            events=[lets_go] if touching else [touches],
                            max_step=_max_step(parts, y, fast, touching or springs, explicit),
                            dense_output=True)
        except _OutOfTime as late:
            raise InputError("simulate", f"the run passed its budget of work ({most} "
                             f"evaluations of its {len(y0)} equations) at t = "
                             f"{late.t:.3g} s (until = {plan.until}) after about "
                             f"{steps} steps; ask for a shorter time, a looser tolerance or "
                             "stiffnesses closer together") from None
        if sol.status == -1:
            raise InputError("simulate", f"the integrator failed: {sol.message}")
        steps += len(sol.t) - 1
        # samples for plots from the solver's own interpolant: smooth curves, not the
        # (long) steps of an implicit method
        count = int(min(SAMPLES_PER_PERIOD * (sol.t[-1] - sol.t[0]) / fast, MAX_SAMPLES))
        fine = np.linspace(sol.t[0], sol.t[-1], max(count, 2))[1:-1]
        times += [*fine, sol.t[-1]]
        states += [*(sol.sol(fine).T if len(fine) else []), sol.y[:, -1]]
        t, y = float(sol.t[-1]), sol.y[:, -1].copy()
        if sol.status != 1:
            if touching and t < horizon:
                raise InputError("simulate", "the contact did not let go within "
                                 f"{SETTLE_PERIODS} of its periods with {integrator['method']} "
                                 f"at rtol {integrator['rtol']:.0e}; tighten the tolerance "
                                 "or choose another integrator")
            continue
        if touching:
            events.append({"kind": "contact-ends", "t": t})
            touching, quiet_since = False, t
        elif compliant_contact:
            events.append({"kind": "contact-begins", "t": t})
            touching = True
        else:
            events.append({"kind": "impact", "t": t})
            y, quiet_since = impulse(y), t
    else:
        raise InputError("simulate", f"more than {MAX_SEGMENTS} contacts: the bodies chatter"
                         " (a rigid contact with e near 0 sticks; ask for contact-compliance)")
    events.append({"kind": "end", "t": t, "why": why})
    origin = as_array(scene.contact.point, values)
    final: dict[str, float] = {}
    for p in parts:
        final |= _final(p, y, origin)
    final["t"] = t
    energy = _balance(parts, y0, y, flown, g)
    _check_balance(energy, plan.settings["tolerance"], integrator["method"])
    details = {"integrator": dict(integrator), "contact": contact_info, "energy": energy}
    track = Trajectory(np.array(times), np.array(states), tuple(parts), origin)
    return Outcome(plan, final, events, time.perf_counter() - start, steps, details, track)


def _contact_events(penetration: Any, k_c: float, c_c: float) -> tuple[Any, Any]:
    """The integrator's two events: the touching points meet (the depth turns positive),
    and the compliant contact lets go (its push falls to zero)."""
    def touches(_t: float, y: np.ndarray) -> float:
        return penetration(y)[0]

    def lets_go(_t: float, y: np.ndarray) -> float:
        d, rate = penetration(y)
        return k_c * d + c_c * rate if d > 0 else -1.0

    # solve_ivp reads these attributes of an event function
    touches.terminal = True  # type: ignore[attr-defined]
    lets_go.terminal = True  # type: ignore[attr-defined]
    touches.direction = 1.0  # type: ignore[attr-defined]
    lets_go.direction = -1.0  # type: ignore[attr-defined]
    return touches, lets_go


def _flown_to(parts: list[_Part], y: np.ndarray, horizon: float, t: float,
              g: float) -> np.ndarray:
    """The state at `horizon` of a free flight from `t` in closed form, refused in one
    line where it leaves float64's range."""
    y = _fly(parts, y, horizon - t, g)
    try:  # its state and energies must stay within float64
        with np.errstate(over="raise", invalid="raise"):
            fits = bool(np.all(np.isfinite(y))) and \
                bool(np.isfinite(sum(_energy(parts, y, g))))
    except FloatingPointError:
        fits = False
    if not fits:
        raise InputError("simulate.until", f"until = {horizon:g} s: the free flight after "
                         "the contact leaves float64's range by then; ask for a shorter "
                         "time")
    return y


def _rigid_impulse(parts: list[_Part], normal: np.ndarray, law: Any, values: Mapping,
                   y: np.ndarray, rate: float) -> np.ndarray:
    """The state after the contact's restitution law acts in an instant between the
    touching points, closing at `rate` (a rigid contact, smooth: the smooth law's one
    face, :meth:`~rigidimpact.laws.law.ContactLaw.impulse`, whose normal entry of W is
    the sum of the two effective masses' inverses; no tangential impulse); the contact's
    work is added to the last entry."""
    if rate <= 0:
        return y
    first, second = parts
    point = _application_point(first, second, y)
    m1 = _effective_mass(first, y, normal, point)
    m2 = _effective_mass(second, y, normal, point)
    face = Smooth().impulse(sp.diag(sp.Float(1 / m1 + 1 / m2, 30), 1),
                            sp.Matrix([sp.Float(-rate, 30), 0]), law)
    j = as_float(face.impulse[0], values)
    before = _energy(parts, y)[0]
    y = y.copy()
    for part, sign in ((first, -1.0), (second, 1.0)):
        dy = np.zeros_like(y)
        _apply(part, dy, y, sign * j * normal, point)
        s, n = part.slot, part.size
        vel = slice(s + n // 2, s + n)
        y[vel] += dy[vel]
    y[-1] += _energy(parts, y)[0] - before
    return y


def _balance(parts: list[_Part], y0: np.ndarray, y: np.ndarray, flown: Any,
             g: float) -> dict[str, float]:
    """The run's energies: at the start, kinetic and stored at the end, the contact's
    work (integrated alongside), and what the balance of them misses."""
    kinetic0, stored0 = _energy(parts, y0, g)
    kinetic, stored = _energy(parts, y, g)
    # a closed-form flight keeps its energy exactly: the balance is taken where it began
    # (far on, kinetic and potential energy are large and cancel in float64)
    balanced = sum(_energy(parts, flown, g)) if flown is not None else kinetic + stored
    return {"initial": kinetic0 + stored0, "kinetic": kinetic, "stored": stored,
            "contact_work": float(y[-1]),
            "balance_error": balanced - (kinetic0 + stored0) - float(y[-1])}


def _check_balance(energy: Mapping[str, float], tolerance: float, method: str) -> None:
    """Refuse a run whose energy does not balance: kinetic + stored at the end must equal
    the start plus the work the contact did (integrated alongside). Runs that follow the
    model balanced to within 0.4 times the tolerance on a sample of the bench's grid, and
    to 4e-5 at tolerance 1e-6 with e = 0 (the capped dashpot, hardest to integrate); an
    integrator that strays from the model does not (SciPy's Radau on the bench's barbell:
    off by 15 to 40 per cent at tolerances 1e-5 to 1e-9). The limit, 100 times the
    tolerance but at least 0.1 per cent and at most 5 per cent, catches such gross
    departures only."""
    size = abs(energy["initial"]) + abs(energy["contact_work"])
    off = abs(energy["balance_error"]) / size if size > 0 else 0.0
    if off > min(max(100 * tolerance, 1e-3), 0.05):
        raise InputError("simulate", f"the energy of this run does not balance (off by "
                         f"{off:.1e} of the energy, against a tolerance of {tolerance:g}): "
                         f"{method} did not follow the model here; use integrator = "
                         '"auto" or another method')
