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
into ends the flight (so does starting on such a plane at rest across it): the sphere
slides there by Coulomb's friction until it rolls
(:func:`rigidimpact.simulate.sphere.sliding`), then rolls on, its path a quadratic in
time in which the next plane (a cushion, a wall) is found as in flight. Struck while
lying, that plane strikes and the one it lies on rests (the driven rule, integrated);
after it the sphere lies on, or leaves the plane and flies. A plane that gravity does
not press the sphere straight into (a slope) is refused in one line.

The run stops after a stated number of impacts or at a stated time (``horizon``), and
its events up to any time are the same whatever later horizon was asked. The times are
exact where every root is rational; from the first that is not, the run goes on in
40-digit floating point and says so; after an integrated impact it is good to that
impact's tolerance (``Bounces.tolerance``).

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
from rigidimpact.laws.cone import TOLERANCE
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
    ahead); `exact` where every number is, else 40-digit floating point, and where an
    impact was integrated (a cushion struck with the floor resting), `tolerance`."""

    events: tuple[Event, ...]
    t: sp.Expr
    position: sp.Matrix
    velocity: sp.Matrix
    spin: sp.Matrix
    stopped: str
    exact: bool
    tolerance: float | None = None  # where an impact was integrated: its stated accuracy


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
    # a sphere that starts lying on a plane gravity presses it into slides or rolls there
    lying = next((f for f in flats if _gap(f, c, R) == 0 and f[2].dot(v) == 0
                  and f[2].dot(a) < 0), None)

    tolerance: list[float] = []  # the accuracy of each integrated impact

    def finish(stopped: str, when: sp.Expr, c: sp.Matrix, v: sp.Matrix,
               w: sp.Matrix) -> Bounces:
        return Bounces(tuple(events), when, c, v, w, stopped, exact,
                       max(tolerance) if tolerance else None)

    def settled(v: sp.Matrix, w: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
        """The state in the run's arithmetic: exact, or 40-digit floats from an impact
        given in floats on."""
        nonlocal exact
        if exact and any(x.has(sp.Float) for x in (*v, *w)):
            exact = False
        if not exact:
            v, w = (x.applyfunc(lambda y: sp.N(y, DIGITS)) for x in (v, w))
        return v, w

    def budget() -> None:
        if count >= MAX_IMPACTS:
            raise InputError("simulate.until", f"more than {MAX_IMPACTS} impacts before "
                             "the run ends: give a number of impacts or an earlier time")

    while True:
        if lying is not None:  # on a plane: sliding until it rolls, then rolling
            cn, p, n = lying
            phase = _on_plane(cn, n, v, w, a, R, k, max(tolerance) if tolerance else None)
            if getattr(phase, "rolling", phase.t == 0) and (
                    not events or events[-1].kind != "rolls"):
                # it comes to lie already rolling: said once, as a rolling that starts
                events.append(Event(t, "rolls", cn.name, c, v, w, "rolls"))
            rolls = phase.t if phase.t > 0 else None
            dv = phase.rates[0]
            nearest = None
            for f in flats:
                if f[0] is cn:
                    continue
                when = _first_root(f[2].dot(dv) / 2, f[2].dot(v), _gap(f, c, R), sp.Integer(0))
                if when is not None and (rolls is None or when < rolls) and (
                        nearest is None or when < nearest[0]):
                    nearest = (when, f)
            ahead = [x for x in (nearest[0] if nearest else None, rolls,
                                 None if end is None else end - t) if x is not None]
            if not ahead:  # rolling (or sliding on a smooth plane) for ever
                return finish("rolling", t, c, v, w)
            step = min(ahead)
            strikes = nearest is not None and step == nearest[0]  # decided before rounding
            if exact and not step.is_Rational:
                exact = False
            if not exact:
                step = sp.N(step, DIGITS)
            moved, v, w = phase.at(step)
            c = c + moved
            if not exact:
                c, v, w = (x.applyfunc(lambda y: sp.N(y, DIGITS)) for x in (c, v, w))
            c = c - (_gap(lying, c, R)) * n  # on the plane, its rounding left aside
            v = v - n.dot(v) * n
            t = t + step
            if end is not None and t >= end:
                return finish("horizon", end, c, v, w)
            if strikes:
                assert nearest is not None
                # a plane met while lying on this one: the struck plane strikes and
                # this one rests (closed while it pushes): the driven rule
                struck = nearest[1]
                budget()
                v, w, course, accuracy = _impact(ball, (struck, lying), c, v, w, R,
                                                 rule="driven")
                tolerance.extend([accuracy] if accuracy else [])
                v, w = settled(v, w)
                count += 1
                events.append(Event(t, "impact", struck[0].name, c, v, w, course))
                if n.dot(v) > 0:  # it leaves the plane it lay on
                    lying = None
                else:
                    v = v - n.dot(v) * n
                if impacts is not None and count >= impacts:
                    return finish("impacts", t, c, v, w)
                continue
            events.append(Event(t, "rolls", cn.name, c, v, w, "rolls"))
            continue
        touching = [f for f in flats if sp.simplify(_gap(f, c, R)) == 0 and f[2].dot(v) < 0]
        if touching:  # an impact now (the contact that closes fastest, if several)
            f = min(touching, key=lambda f: f[2].dot(v))
            cn, p, n = f
            budget()
            fastest = max(fastest, -n.dot(v))
            v, w, course, accuracy = _impact(ball, (f,), c, v, w, R)
            tolerance.extend([accuracy] if accuracy else [])
            v, w = settled(v, w)
            count += 1
            if n.dot(a) < 0 and 0 < n.dot(v) <= SETTLE * fastest:
                v = v - n.dot(v) * n
                course += (f"; the rebound is below {float(SETTLE):g} of the fastest "
                           "landing: the sphere comes to lie on the plane")
            events.append(Event(t, "impact", cn.name, c, v, w, course))
            if n.dot(v) == 0 and n.dot(a) < 0:  # it lies on the plane, pressed into it
                lying = f
            if impacts is not None and count >= impacts:
                return finish("impacts", t, c, v, w)
            continue
        # the next plane the centre comes within R of, approaching it
        nearest = None
        for f in flats:
            when = _first_root(f[2].dot(a) / 2, f[2].dot(v), _gap(f, c, R), sp.Integer(0))
            if when is not None and (nearest is None or when < nearest[0]):
                nearest = (when, f)
        if nearest is None or (end is not None and t + nearest[0] >= end):
            if end is None:
                return finish("flying", t, c, v, w)
            c, v, w = flight(c, v, w, a, end - t)
            return finish("horizon", end, c, v, w)
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
        _, p, n = nearest[1]
        c = c - _gap(nearest[1], c, R) * n


def _gap(flat: tuple[Contact, sp.Matrix, sp.Matrix], c: sp.Matrix, R: sp.Expr) -> sp.Expr:
    """How far the sphere's surface is from the plane (0: touching)."""
    _, p, n = flat
    return n.dot(c - p) - R


def _on_plane(contact: Contact, n: sp.Matrix, v: sp.Matrix, w: sp.Matrix, a: sp.Matrix,
              R: sp.Expr, k: sp.Expr, tolerance: float | None = None) -> Any:
    """The sphere lying on `contact`'s plane: sliding by Coulomb's friction until it
    rolls (:func:`rigidimpact.simulate.sphere.sliding`); rolling (its slip zero, or
    rounding's size in floating point), or on a smooth plane, keeping its velocity and
    spin."""
    if (a - n.dot(a) * n) != sp.zeros(3, 1):
        raise InputError(f"{contact.name}.normal", "a sphere lying on a plane that gravity "
                         "does not press straight into (a slope) is not followed yet")
    slip = v + w.cross(-R * n)
    if any(x.has(sp.Float) for x in (*v, *w)):  # floats: a slip at their rounding, or
        # within 1000 times an integrated impact's tolerance, is a rolling sphere's
        scale = max(1, *(abs(x) for x in (*v, *(R * y for y in w))))
        floor = sp.Float(10) ** (5 - DIGITS) if tolerance is None else \
            sp.Float(1000 * tolerance)
        if all(abs(x) <= floor * scale for x in slip):
            return _Smooth(v, w, rolling=True)
    mu = contact.friction
    if mu is None or mu == 0:
        if contact.tangential not in ("smooth", "coulomb"):
            raise InputError(f"{contact.name}.friction", "a sphere left lying on a plane "
                             "slides by Coulomb's friction: give the contact's friction")
        return _Smooth(v, w, rolling=False)
    return sliding(v, w, R, k, mu, -n.dot(a), tuple(n))


@dataclass(frozen=True)
class _Smooth:
    """Rolling, or lying on a smooth plane: nothing changes the velocity or the spin."""

    v: sp.Matrix
    w: sp.Matrix
    rolling: bool

    @property
    def t(self) -> sp.Expr:
        return sp.Integer(0)

    @property
    def rates(self) -> tuple[sp.Matrix, sp.Matrix]:
        return sp.zeros(3, 1), sp.zeros(3, 1)

    def at(self, t: Any) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
        return self.v * t, self.v, self.w


def _impact(ball: Body3, flats: Sequence[tuple[Contact, sp.Matrix, sp.Matrix]],
            c: sp.Matrix, v: sp.Matrix, w: sp.Matrix, R: sp.Expr,
            rule: str | None = None) -> tuple[sp.Matrix, sp.Matrix, str, float | None]:
    """The sphere's velocity and spin after striking the first of `flats` (the others
    resting, by the driven rule), each contact at its touching point, the course, and
    the tolerance it was integrated to (None: exact, or a closed form)."""
    moved = replace(ball, position=sp.ImmutableMatrix(c), velocity=sp.ImmutableMatrix(v),
                    spin=sp.ImmutableMatrix(w))
    fixed = sorted({f[0].first if f[0].second == ball.name else f[0].second for f in flats})
    contacts = tuple(replace(f[0], point=sp.ImmutableMatrix(c - R * f[2])) for f in flats)
    solved = SpaceCollision((*(Body3.fixed(name) for name in fixed), moved), contacts,
                            rule=rule).solve()
    assert solved.speeds_after is not None  # a 3-D answer: its six speeds
    after = list(solved.speeds_after)
    stated = solved.method.split("integrated to ")[-1] \
        if solved.method.startswith("integrated to ") else None
    integrated = stated is not None or any("integrated" in note for note in solved.notes)
    return (sp.Matrix(after[:3]), sp.Matrix(after[3:]), solved.regime or "",
            (float(stated) if stated else TOLERANCE) if integrated else None)
