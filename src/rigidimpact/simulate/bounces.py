"""A sphere's life among fixed planes in space: flight under gravity, the next contact
found exactly, each impact under that contact's laws, and, where a bounce leaves it
lying on a plane that gravity presses it into, its sliding until it rolls.

Each plane is a contact of the scene between a fixed body and the sphere: its `point`
lies on the plane and its `normal` is the plane's (pointing into the sphere's side when
the sphere is the contact's second body). Between impacts the centre flies on a
parabola and the spin is kept (:func:`rigidimpact.simulate.sphere.flight`); the sphere
meets a plane when its centre comes within its radius of it, the earlier root of a
quadratic in time, taken while approaching. Each impact is the one-contact answer of
:class:`~rigidimpact.solve.space.SpaceCollision` at that instant, certified as every
answer is. A bounce that leaves no normal speed on a plane gravity presses the sphere
into ends the flight: the sphere slides there by Coulomb's friction until it rolls
(:func:`rigidimpact.simulate.sphere.sliding`), then rolls on.

The run stops after a stated number of impacts or at a stated time (``horizon``), and
its events up to any time are the same whatever later horizon was asked. The times are
exact where every root is rational; from the first that is not, the run goes on in
40-digit floating point and says so.

Examples
--------
Garwin's superball (perfectly rough and elastic) thrown along the floor under a table
whose underside is 3 above the floor, gravity neglected: it rises to the table, falls
back, and after three bounces comes back at 333/343 of its speed.

>>> import sympy as sp
>>> from rigidimpact.laws.contact import Contact
>>> from rigidimpact.model.space import Body3
>>> ball = Body3.sphere(1, 1, (0, 0, 1), (1, 0, -1), name="ball")
>>> rough = dict(restitution=1, tangential="rough", tangential_restitution=1)
>>> floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
...                 name="floor", **rough)
>>> table = Contact(normal=(0, 0, -1), bodies=("table", "ball"), point=(0, 0, 3),
...                 name="table", **rough)
>>> run = bounces(ball, (floor, table), gravity=(0, 0, 0), impacts=3)
>>> [(e.t, e.plane) for e in run.events]
[(0, 'floor'), (1, 'table'), (2, 'floor')]
>>> run.velocity.T
Matrix([[-333/343, 0, 1]])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.space import Body3
from rigidimpact.simulate.sphere import flight, sliding
from rigidimpact.solve.space import SpaceCollision

__all__ = ["Event", "Bounces", "bounces", "MAX_IMPACTS", "DIGITS"]

MAX_IMPACTS = 1000  # a budget of impacts: past it a run is refused, never cut short
# a bounce off a plane that gravity presses the sphere into, rising at less than this
# fraction of the fastest landing so far, is taken as the sphere coming to lie there
# (with e < 1 the bounces pile up at a finite time, Zeno-like, with ever smaller ones)
SETTLE = sp.Rational(1, 10**12)
DIGITS = 40  # the floating point a run goes on in once a time is irrational


@dataclass(frozen=True)
class Event:
    """What happened at time `t`: ``impact`` on `plane` (its course), ``rolls`` (the
    sliding on `plane` has ended), with the sphere's state just after."""

    t: sp.Expr
    kind: str
    plane: str
    position: sp.Matrix
    velocity: sp.Matrix
    spin: sp.Matrix
    course: str = ""


@dataclass(frozen=True)
class Bounces:
    """A run: its events, the state where it stopped, and why it stopped (``impacts``,
    ``horizon``, ``rolling`` on a plane with no horizon, or ``flying`` with no plane
    ahead)."""

    events: tuple[Event, ...]
    t: sp.Expr
    position: sp.Matrix
    velocity: sp.Matrix
    spin: sp.Matrix
    stopped: str
    exact: bool


def _planes(ball: Body3, planes: Sequence[Contact]) -> list[tuple[Contact, sp.Matrix,
                                                                     sp.Matrix]]:
    """Each contact with its plane's point and unit normal toward the sphere's side."""
    found = []
    for c in planes:
        if not isinstance(c, Contact) or not c.spatial or c.bodies is None:
            raise InputError("planes", "each plane is a 3-D contact naming its two bodies")
        if ball.name not in c.bodies:
            raise InputError(f"{c.name}.bodies", f"must name the sphere {ball.name!r}")
        n = sp.Matrix(c.normal)
        n = n / sp.sqrt(n.dot(n))
        found.append((c, sp.Matrix(c.point), n if c.second == ball.name else -n))
    return found


def _first_root(a: sp.Expr, b: sp.Expr, c: sp.Expr, after: sp.Expr) -> sp.Expr | None:
    """The earliest time t > `after` (relative time 0 excluded) at which
    ``a t^2 + b t + c`` reaches 0 going down (the gap closing), or None."""
    roots: list[sp.Expr] = []
    if a == 0:
        if b != 0:
            roots = [-c / b]
    else:
        disc = b * b - 4 * a * c
        if disc < 0:
            return None
        root = sp.sqrt(disc)
        roots = [(-b - root) / (2 * a), (-b + root) / (2 * a)]
    best = None
    for t in roots:
        t = sp.nsimplify(t) if t.is_Rational else t
        closing = 2 * a * t + b
        if t > after and closing < 0 and (best is None or t < best):
            best = t
    return best


def bounces(ball: Body3, planes: Sequence[Contact], gravity: Sequence[Any] = (0, 0, -9.81),
            impacts: int | None = None, horizon: Any = None) -> Bounces:
    """Follow `ball` (a :class:`~rigidimpact.model.space.Body3` sphere) among the fixed
    `planes` under `gravity` until `impacts` impacts or time `horizon` (see the module's
    text); at least one of the two must be given."""
    if ball.radius is None or ball.support == "fixed":
        raise InputError("bodies", "a bounce run follows one free sphere")
    if impacts is None and horizon is None:
        raise InputError("simulate.until", "give a number of impacts or a time")
    if impacts is not None and (isinstance(impacts, bool) or not isinstance(impacts, int)
                                or not 1 <= impacts <= MAX_IMPACTS):
        raise InputError("simulate.impacts", f"a whole number from 1 to {MAX_IMPACTS}")
    end = None if horizon is None else sp.sympify(horizon)
    if end is not None and not (end.is_number and end > 0):
        raise InputError("simulate.until", f"a positive time, not {horizon!r}")
    a = sp.Matrix([sp.sympify(x) for x in gravity])
    if a.shape != (3, 1) or not all(x.is_number for x in a):
        raise InputError("simulate.gravity", "three numbers [gx, gy, gz]")
    flats = _planes(ball, planes)
    R = ball.radius
    k = ball.inertia[0, 0] / (ball.mass * R ** 2)
    t = sp.Integer(0)
    c, v, w = (sp.Matrix(x) for x in (ball.position, ball.velocity, ball.spin))
    exact = all(x.is_Rational for x in (*c, *v, *w, *a, R))
    events: list[Event] = []
    count = 0
    fastest = sp.Integer(0)
    while True:
        touching = [(cn, p, n) for cn, p, n in flats
                    if sp.simplify(n.dot(c - p) - R) == 0 and n.dot(v) < 0]
        if touching:  # an impact now (the contact that closes fastest, if several)
            cn, p, n = min(touching, key=lambda f: f[2].dot(v))
            moved = replace(ball, position=sp.ImmutableMatrix(c),
                            velocity=sp.ImmutableMatrix(v), spin=sp.ImmutableMatrix(w))
            fixed = cn.first if cn.second == ball.name else cn.second
            solved = SpaceCollision((Body3.fixed(fixed), moved), (replace(
                cn, point=sp.ImmutableMatrix(c - R * n)),)).solve()
            fastest = max(fastest, -n.dot(v))
            assert solved.speeds_after is not None  # a 3-D answer: its six speeds
            after = list(solved.speeds_after)
            v, w = sp.Matrix(after[:3]), sp.Matrix(after[3:])
            count += 1
            course = solved.regime or ""
            if n.dot(a) < 0 and 0 < n.dot(v) <= SETTLE * fastest:
                v = v - n.dot(v) * n
                course += (f"; the rebound is below {float(SETTLE):g} of the fastest "
                           "landing: the sphere comes to lie on the plane")
            events.append(Event(t, "impact", cn.name, c, v, w, course))
            if impacts is not None and count >= impacts:
                return Bounces(tuple(events), t, c, v, w, "impacts", exact)
            if count >= MAX_IMPACTS:
                raise InputError("simulate.until", f"more than {MAX_IMPACTS} impacts before "
                                 "the run ends: give a number of impacts or an earlier time")
            if n.dot(v) == 0 and n.dot(a) < 0:  # it lies on the plane, pressed into it
                return _slides(events, cn, n, t, c, v, w, a, R, k, end, exact)
            continue
        # the next plane the centre comes within R of, approaching it
        nearest = None
        for cn, p, n in flats:
            when = _first_root(n.dot(a) / 2, n.dot(v), n.dot(c - p) - R, sp.Integer(0))
            if when is not None and (nearest is None or when < nearest[0]):
                nearest = (when, cn)
        if nearest is None or (end is not None and t + nearest[0] >= end):
            if end is None:
                return Bounces(tuple(events), t, c, v, w, "flying", exact)
            c, v, w = flight(c, v, w, a, end - t)
            return Bounces(tuple(events), end, c, v, w, "horizon", exact)
        step = nearest[0]
        if exact and not step.is_Rational:  # from here on in floating point
            exact = False
        if not exact:
            step = sp.N(step, DIGITS)
        c, v, w = flight(c, v, w, a, step)
        if not exact:
            c, v, w = (x.applyfunc(lambda y: sp.N(y, DIGITS)) for x in (c, v, w))
        t = t + step
        # land exactly on the plane the root found (its rounding left aside)
        cn = nearest[1]
        _, p, n = next(f for f in flats if f[0] is cn)
        c = c - (n.dot(c - p) - R) * n


def _slides(events: list[Event], contact: Contact, n: sp.Matrix, t: sp.Expr,
            c: sp.Matrix, v: sp.Matrix, w: sp.Matrix, a: sp.Matrix, R: sp.Expr,
            k: sp.Expr, end: sp.Expr | None, exact: bool) -> Bounces:
    """After a bounce that leaves the sphere lying on a plane: it slides by Coulomb's
    friction until it rolls, then rolls (to the horizon, or stops there with none)."""
    if contact.friction is None:
        raise InputError(f"{contact.name}.friction", "a sphere left lying on a plane "
                         "slides by Coulomb's friction: give the contact's friction")
    g = -n.dot(a)
    run = sliding(v, w, R, k, contact.friction, g, tuple(n))
    rolls = t + run.t
    if end is not None and end <= rolls:
        p, vel, spin = run.at(end - t)
        return Bounces(tuple(events), end, c + p, vel, spin, "horizon", exact)
    p, vel, spin = run.at(run.t)
    events.append(Event(rolls, "rolls", contact.name, c + p, vel, spin, "rolls"))
    if end is None:
        return Bounces(tuple(events), rolls, c + p, vel, spin, "rolling", exact)
    return Bounces(tuple(events), end, c + p + vel * (end - rolls), vel, spin, "horizon",
                   exact)
