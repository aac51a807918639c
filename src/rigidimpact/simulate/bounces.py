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
lying, that plane strikes and the one it lies on rests (the driven rule: the struck
plane's own impact where it leaves the other open, else integrated); after it the
sphere lies on, or leaves the plane and flies. A plane that gravity does not press the
sphere straight into (a slope) is refused in one line.

Several spheres (:func:`spheres`) each live so, every one striking every plane; two
meet when the distance of their centres, each on its own quadratic path, comes down to
the sum of their radii: the first root of odd multiplicity of a quartic in time, exact
where its coefficients are rational. They meet by their pair's laws, the planes they lie
on resting (the driven rule again). Rolling resistance slows a rolling sphere at
``mu_r g`` until it stops, and pivoting friction wears its spin about the plane's normal
at ``mu_p g / (k R)`` until it ends: each a constant rate, so every phase stays a
quadratic in time with its end found in closed form.

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
>>> from rigidimpact.model.space import SPEEDS, Body3
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

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import sphere_bounce
from rigidimpact.laws.cone import TOLERANCE
from rigidimpact.laws.contact import Contact
from rigidimpact.model.space import SPEEDS, Body3
from rigidimpact.simulate.sphere import flight, sliding
from rigidimpact.simulate.tangential import STEPS
from rigidimpact.simulate.zeno import Tail, bounce_map, geometric_tail
from rigidimpact.solve.space import SpaceCollision
from rigidimpact.symbolic.given import given_number

__all__ = ["Event", "Bounces", "bounces", "spheres", "MAX_IMPACTS", "DIGITS"]

MAX_IMPACTS = 1000  # a budget of impacts: past it a run is refused, never cut short
# a bounce off a plane that gravity presses the sphere into, rising at less than this
# fraction of the fastest landing so far, is taken as the sphere coming to lie there
# (with e < 1 the bounces pile up at a finite time, Zeno-like, with ever smaller ones)
SETTLE = sp.Rational(1, 10**12)
DIGITS = 40  # the floating point a run goes on in once a time is irrational
SUMMED = 10_000  # a budget: bounces summed in closed form up to a horizon inside a pile-up


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
    ball: str = ""  # the sphere (the first of a pair) whose state this is
    other: str = ""  # where two spheres meet: the second


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
    # every sphere's (position, velocity, spin) where the run stopped
    states: dict[str, tuple[sp.Matrix, sp.Matrix, sp.Matrix]] = field(default_factory=dict)
    # (t, each sphere's (position, velocity, spin)) at the start, after each event and at
    # the end
    snapshots: tuple = ()
    # each distinct plane of the run: (name, a point on it, its unit normal)
    planes: tuple = ()
    summed: int = 0  # bounces summed in closed form up to the horizon (a pile-up's)
    # (sphere, start, end) of each span of bounces summed, for pictures
    piles: tuple = ()


def _planes(balls: Sequence[Body3], planes: Sequence[Contact]) -> list[tuple]:
    """Each contact with its plane's point, its unit normal toward the spheres' side (the
    side of the sphere it names: every sphere of the run may strike every plane), the
    spheres' names, and the name the scene gave the plane's contact with each sphere it
    names (one plane written twice, as the cloth under each ball, keeps both names)."""
    names = {b.name for b in balls}
    found: list[tuple] = []
    for c in planes:
        if not isinstance(c, Contact) or not c.spatial or c.bodies is None:
            raise InputError("planes", "each plane is a 3-D contact naming its two bodies")
        if not names & set(c.bodies):
            raise InputError(f"{c.name}.bodies", "must name the sphere of the run ("
                             + ", ".join(sorted(names)) + ")")
        if set(c.bodies) <= names:
            raise InputError(f"{c.name}.bodies", "a plane belongs to a fixed body: two "
                             "spheres meet by a pair's laws (pairs)")
        n = sp.Matrix(c.normal)
        n = n / sp.sqrt(n.dot(n))
        n = n if c.second in names else -n
        p = sp.Matrix(c.point)
        same = next((f for f in found if sp.simplify((f[2] - n).norm()) == 0
                     and sp.simplify(n.dot(p - f[1])) == 0), None)
        own = {b: c.name for b in c.bodies if b in names}
        if same is not None:  # one plane written twice (the cloth under each ball)
            if _laws(same[0]) != _laws(c):
                raise InputError(f"{c.name}.bodies", f"is the plane of {same[0].name} with "
                                 "other laws: a plane has one set of laws")
            for ball, name in own.items():
                same[4].setdefault(ball, name)
            continue
        found.append((c, p, n, frozenset(names), own))
    return found


def _named(flat: tuple, ball: str) -> str:
    """The plane's contact with sphere `ball` by the name the scene gave it, else the
    plane's own name."""
    return flat[4].get(ball, flat[0].name)


def _label(flat: tuple) -> str:
    """The plane as a picture names it: every name the scene gave it, once each."""
    return ", ".join(dict.fromkeys([flat[0].name, *flat[4].values()]))


def _laws(c: Contact) -> tuple:
    return (c.restitution, c.law, c.tangential, c.friction, c.tangential_restitution)


def _pairs(balls: Sequence[Body3], pairs: Sequence[Contact]) -> dict[frozenset, Contact]:
    """The laws of each two spheres that may meet, by the pair of their names."""
    names = {b.name for b in balls}
    found: dict[frozenset, Contact] = {}
    for c in pairs:
        if not isinstance(c, Contact) or not c.spatial or c.bodies is None or \
                not set(c.bodies) <= names or c.first == c.second:
            raise InputError(f"{getattr(c, 'name', 'pairs')}.bodies", "a pair names two "
                             "spheres of the run")
        key = frozenset(c.bodies)
        if key in found:
            raise InputError(f"{c.name}.bodies", f"{c.first} and {c.second} have laws "
                             f"twice ({found[key].name})")
        found[key] = c
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
        # the two roots as q/a and c/q: the textbook formula loses the small root to
        # cancellation in floating point when b^2 is much larger than |4 a c|
        q = -(b + (1 if b >= 0 else -1) * sp.sqrt(disc)) / 2
        roots = [q / a, c / q] if q != 0 else [sp.Integer(0)]
    best = None
    for t in roots:
        t = sp.nsimplify(t) if t.is_Rational else t
        closing = 2 * a * t + b
        if t > after and closing < 0 and (best is None or t < best):
            best = t
    return best


def _meeting(d: sp.Matrix, u: sp.Matrix, acc: sp.Matrix, reach: sp.Expr,
             exact: bool) -> sp.Expr | None:
    """The earliest time t > 0 at which two centres, `d` apart (second less first), the
    second moving at `u` and accelerating at `acc` relative to the first, come within
    `reach` of each other: the first root of odd multiplicity (a crossing, not a graze)
    of the quartic ``|d + u t + acc t^2/2|^2 - reach^2`` where the distance is closing
    (:func:`first_closing_root`). Exact (rational, or an algebraic root to
    :data:`DIGITS` digits) where the data are rational; else the root of the quartic
    whose coefficients are the floats' own values, to :data:`DIGITS` digits."""
    def rational(x: sp.Expr) -> sp.Rational:
        """A datum as an exact rational: itself, a float's own binary value, or an
        algebraic number to DIGITS + 10 digits."""
        x = x if x.is_Rational or x.is_Float else sp.N(x, DIGITS + 10)
        if not (x.is_Rational or (x.is_Float and x.is_finite)):
            raise InputError("bodies", "two spheres' paths are not finite real numbers")
        return sp.Rational(x)

    exact = exact and all(x.is_Rational for x in (*d, *u, *acc, reach))
    d, u, acc = (sp.Matrix([rational(x) for x in y]) for y in (d, u, acc))
    # |d + u t + acc t^2/2|^2 - reach^2, its coefficients from the highest power down
    coeffs = [acc.dot(acc) / 4, u.dot(acc), u.dot(u) + d.dot(acc), 2 * d.dot(u),
              d.dot(d) - rational(reach) ** 2]
    return first_closing_root(coeffs, factor=exact)


def first_closing_root(coeffs: Sequence[Any], factor: bool = True) -> sp.Expr | None:
    """The first root t > 0 of the polynomial with these coefficients (highest power
    first; exact rationals, or floats taken at their exact binary values) at which it
    goes from positive to negative: a crossing of odd multiplicity, never a graze.

    The real roots are isolated exactly (SymPy's real-root isolation on the
    square-free factors, no numerical root finder that may fail to converge), and the
    root is a rational where it is one (with `factor`, the factors irreducible over
    the rationals) or else refined by bisection to :data:`DIGITS` digits.

    Examples
    --------
    >>> first_closing_root([1, -5, 6])   # (t - 2)(t - 3): below zero from 2 to 3
    2
    >>> first_closing_root([1, -2, 1])   # (t - 1)^2 touches zero and rises: a graze
    >>> first_closing_root([-1, 0, 2])   # 2 - t^2 goes down through sqrt(2)
    1.414213562373095048801688724209698078570
    """
    t = sp.Dummy("t")
    poly = sp.Poly([sp.Rational(x) for x in coeffs], t, domain=sp.QQ)
    if poly.is_zero or poly.degree() < 1:
        return None
    factors = poly.factor_list()[1] if factor else poly.sqf_list()[1]
    odd = [part for part, times in factors if times % 2]  # even roots: grazes
    if not odd:
        return None
    # the sign just after t = 0: the lowest-order term that is not zero
    sign = next(sp.sign(c) for c in reversed(poly.all_coeffs()) if c != 0)
    # isolated together, so the intervals of different factors do not overlap
    for (lo, hi), which in sp.intervals(odd):
        if hi <= 0:
            continue
        if sign > 0:
            part = odd[next(iter(which))]
            if part.degree() == 1:  # a rational root, exactly
                low, high = part.all_coeffs()
                return -high / low
            return lo if lo == hi else _refined(part, lo, hi)
        sign = -sign
    return None


def _refined(part: sp.Poly, lo: sp.Rational, hi: sp.Rational) -> sp.Float:
    """The one root of the square-free `part` in (lo, hi), hi > 0, to DIGITS digits:
    the interval halved until its width is below 10^-(DIGITS + 5) of its upper end."""
    lo = max(lo, sp.Integer(0))
    while hi - lo > hi * sp.Rational(1, 10 ** (DIGITS + 5)):
        lo, hi = part.refine_root(lo, hi, steps=8)
        if lo == hi:
            return sp.Float(lo, DIGITS)
    return sp.Float((lo + hi) / 2, DIGITS)


class _Sphere:
    """One sphere's state in a run: centre, velocity, spin, the plane it lies on (or
    None while it flies), its fastest landing so far, and whether its rolling was said."""

    def __init__(self, body: Body3) -> None:
        self.body = body
        self.name = body.name
        assert body.radius is not None  # a sphere
        self.R: sp.Expr = body.radius
        self.k = body.inertia[0, 0] / (body.mass * self.R ** 2)
        self.c, self.v, self.w = (sp.Matrix(x) for x in (body.position, body.velocity,
                                                          body.spin))
        self.lying: tuple | None = None
        self.fastest = sp.Integer(0)
        self.said = False  # its rolling on the plane it lies on has been said
        self.regime: tuple = ()  # (plane, regime) of its last bounce the tail's laws gave

    def moved(self) -> Body3:
        return replace(self.body, position=sp.ImmutableMatrix(self.c),
                       velocity=sp.ImmutableMatrix(self.v), spin=sp.ImmutableMatrix(self.w))


def bounces(ball: Body3, planes: Sequence[Contact], gravity: Sequence[Any] = (0, 0, -9.81),
            impacts: int | None = None, horizon: Any = None) -> Bounces:
    """Follow `ball` (a :class:`~rigidimpact.model.space.Body3` sphere) among the fixed
    `planes` under `gravity` until `impacts` impacts or time `horizon` (see the module's
    text); at least one of the two must be given."""
    return spheres((ball,), planes, (), gravity, impacts, horizon)


def spheres(balls: Sequence[Body3], planes: Sequence[Contact], pairs: Sequence[Contact] = (),
            gravity: Sequence[Any] = (0, 0, -9.81), impacts: int | None = None,
            horizon: Any = None, rolling_resistance: Any = 0,
            pivot_friction: Any = 0, compliance: float | None = None) -> Bounces:
    """Follow the free spheres `balls` among the fixed `planes` under `gravity` until
    `impacts` impacts or time `horizon`, two spheres meeting by their pair's laws
    (`pairs`: contacts naming the two, whose point and normal are found where they
    meet); two spheres whose paths cross with no laws given are refused in one line.
    A sphere lying on a plane is slowed while it rolls by `rolling_resistance` (a
    force mu_r m g against its velocity, rolling kept, until it stops) and its spin
    about the normal is worn by `pivot_friction` (a moment mu_p m g R, until it ends),
    where they are given. With `compliance` (k_t/k_n), a flying sphere's bounce on a
    plane goes through the tangentially compliant contact
    (:func:`rigidimpact.laws.compliance.sphere_bounce`, integrated to first order with
    :data:`~rigidimpact.simulate.tangential.STEPS` steps a period); a cushion struck
    while lying and the meeting of two spheres stay rigid. The answer's `position`,
    `velocity` and `spin` are the first sphere's; `states` has every sphere's.

    Examples
    --------
    Two equal balls of radius 1/10 lie on a smooth cloth 1 apart; the first slides at 1
    into the second, which it meets when the gap of 4/5 is closed, and, the meeting
    elastic and smooth, stops there while the second goes on at 1:

    >>> r = sp.Rational(1, 10)
    >>> a = Body3.sphere(1, r, (0, 0, r), (1, 0, 0), name="a")
    >>> b = Body3.sphere(1, r, (1, 0, r), name="b")
    >>> cloth = Contact(normal=(0, 0, 1), bodies=("table", "a"), point=(0, 0, 0),
    ...                 name="cloth", restitution=0)
    >>> meeting = Contact(normal=(1, 0, 0), bodies=("a", "b"), name="balls", restitution=1)
    >>> run = spheres((a, b), (cloth,), (meeting,), gravity=(0, 0, -10), horizon=2)
    >>> [(e.t, e.ball, e.other) for e in run.events]
    [(4/5, 'a', 'b')]
    >>> run.states["a"][1].T, run.states["b"][1].T
    (Matrix([[0, 0, 0]]), Matrix([[1, 0, 0]]))
    """
    if not balls or any(b.radius is None or b.support == "fixed" for b in balls):
        raise InputError("bodies", "a bounce run follows free spheres")
    if len({b.name for b in balls}) != len(balls):
        raise InputError("bodies", "two spheres share a name")
    return _Run(balls, planes, pairs, impacts,
                _run_settings(impacts, horizon, gravity, rolling_resistance, pivot_friction,
                              compliance)).run()


class _Run:
    """One run of :func:`spheres`: the spheres, planes and pairs' laws, the time, the
    arithmetic (exact, or :data:`DIGITS`-digit floats from the first irrational time
    on), the events and snapshots so far and the impacts counted. :meth:`run`
    alternates the impacts due now (:meth:`_plane_impact`, :meth:`_pair_impact`) and
    the phase up to the next event (:meth:`_advance`)."""

    def __init__(self, balls: Sequence[Body3], planes: Sequence[Contact],
                 pairs: Sequence[Contact], impacts: int | None, settings: tuple) -> None:
        self.end, self.a, self.resistance, self.pivot, self.compliance = settings
        self.impacts = impacts
        self.flats = _planes(balls, planes)
        self.laws = _pairs(balls, pairs)
        self.ones = [_Sphere(b) for b in balls]
        self.couples = [(p, q) for i, p in enumerate(self.ones) for q in self.ones[i + 1:]]
        for p, q in self.couples:
            d = q.c - p.c
            if d.dot(d) < (p.R + q.R) ** 2:
                raise InputError("bodies", f"{p.name} and {q.name} overlap at the start")
        self.t: sp.Expr = sp.Integer(0)
        self.exact = all(x.is_Rational for s in self.ones
                         for x in (*s.c, *s.v, *s.w, s.R)) and \
            all(x.is_Rational for x in self.a)
        _not_through(self.ones, self.flats, self.exact)
        self.events: list[Event] = []
        self.snapshots: list[tuple[sp.Expr, dict[str, tuple[sp.Matrix, ...]]]] = []
        self.count = self.summed = 0
        self.piles: list[tuple[str, sp.Expr, sp.Expr]] = []
        # a sphere that starts lying on a plane gravity presses it into slides or rolls
        for s in self.ones:
            s.lying = next((f for f in self.flats if _gap(f, s.c, s.R) == 0
                            and f[2].dot(s.v) == 0 and f[2].dot(self.a) < 0), None)
        self.tolerance: list[float] = []  # the accuracy of each integrated impact
        self.due: tuple | None = None  # the impact the last step was taken to

    def run(self) -> Bounces:
        """Impacts now, else the phase to the next event, until the run stops."""
        self.snap()
        while True:
            now = self._impacts_now()
            self.due = None
            if not now:
                stopped = self._advance()
                if stopped is not None:
                    return stopped
                continue
            if self.count >= MAX_IMPACTS:
                raise InputError("simulate.until", f"more than {MAX_IMPACTS} impacts before "
                                 "the run ends: give a number of impacts or an earlier time")
            _, what = min(now, key=lambda x: x[0])
            if what[0] == "plane":
                self._plane_impact(what[1], what[2])
            else:
                self._pair_impact(what[1], what[2])
            self.snap()
            if self.impacts is not None and self.count >= self.impacts:
                return self.finish("impacts", self.t)

    def snap(self) -> None:
        self.snapshots.append((self.t, {s.name: (s.c, s.v, s.w) for s in self.ones}))

    def finish(self, stopped: str, when: sp.Expr) -> Bounces:
        first = self.ones[0]
        return Bounces(tuple(self.events), when, first.c, first.v, first.w, stopped,
                       self.exact, max(self.tolerance) if self.tolerance else None,
                       {s.name: (s.c, s.v, s.w) for s in self.ones}, tuple(self.snapshots),
                       tuple((_label(f), f[1], f[2]) for f in self.flats), self.summed,
                       tuple(self.piles))

    @staticmethod
    def floats(*xs: sp.Matrix) -> tuple[sp.Matrix, ...]:
        return tuple(x.applyfunc(lambda y: sp.N(y, DIGITS)) for x in xs)

    def settled(self, s: _Sphere) -> None:
        """The state in the run's arithmetic: exact, or 40-digit floats from an impact
        given in floats on."""
        if self.exact and any(x.has(sp.Float) for x in (*s.v, *s.w)):
            self.exact = False
        if not self.exact:
            s.v, s.w = self.floats(s.v, s.w)

    def struck(self, who: Sequence[_Sphere], contacts: Sequence[Contact],
               rule: str | None) -> str:
        """Each of `who` after the impact at `contacts` (the first strikes; the planes
        the spheres lie on rest, by the driven rule): its course."""
        try:
            after, course, accuracy = _impact([s.moved() for s in who], contacts, rule)
        except InputError as error:
            if "none approaches" not in str(error):
                raise
            raise InputError("simulate", f"at t = {float(self.t):.6g} s {who[0].name} meets "
                             f"{contacts[0].name} moving toward it too slowly to tell from "
                             "rounding, next to the speeds in play: the run's speeds span "
                             "more than its arithmetic can follow") from None
        self.tolerance.extend([accuracy] if accuracy else [])
        for s in who:
            s.v, s.w = after[s.name]
            self.settled(s)
            s.said = False
        return course

    def touching(self, gap: sp.Expr, scale: sp.Expr) -> bool:
        """Whether a gap (a plane's, or two centres' squared distance less its least)
        is none: exactly, or once the run is in floating point, within its rounding (a
        gap the rounding closed a little too far must not let two bodies pass through
        each other)."""
        gap = sp.simplify(gap) if self.exact else gap
        if gap == 0:
            return True
        return not self.exact and abs(gap) <= sp.Float(10) ** (5 - DIGITS) * scale

    @staticmethod
    def leave_or_lie(s: _Sphere) -> None:
        """After an impact struck while lying, the sphere lies on or leaves its plane."""
        if s.lying is not None:
            n = s.lying[2]
            if n.dot(s.v) > 0:
                s.lying = None
            else:
                s.v = s.v - n.dot(s.v) * n

    def _impacts_now(self) -> list[tuple[sp.Expr, tuple]]:
        """The impacts due now, each with its closing speed (the fastest goes first)."""
        now: list[tuple[sp.Expr, tuple]] = []
        for s in self.ones:
            for f in self.flats:
                if f is s.lying or f[2].dot(s.v) >= 0:
                    continue
                if self.due == ("plane", s.name, f[0].name) or \
                        self.touching(_gap(f, s.c, s.R), 1 + max(abs(x) for x in s.c)):
                    now.append((f[2].dot(s.v), ("plane", s, f)))
        for p, q in self.couples:
            d = q.c - p.c
            closing = d.dot(q.v - p.v) / (p.R + q.R)
            if closing < 0 and (self.due == ("pair", p.name, q.name) or self.touching(
                    d.dot(d) - (p.R + q.R) ** 2,
                    (1 + max(abs(x) for x in (*p.c, *q.c))) ** 2)):
                now.append((closing, ("pair", p, q)))
        return now

    def _plane_impact(self, s: _Sphere, f: tuple) -> None:
        """Sphere s strikes plane f: struck while lying (the driven rule), or a bounce
        from flight (rigid or compliant), a rebound within rounding of none made none,
        and where it lands for good the bounces to come summed in closed form."""
        a = self.a
        landed = None  # the state it landed in from flight
        if s.lying is not None:  # struck while lying: the driven rule
            course = self.struck((s,), (_at_plane(f, s), _at_plane(s.lying, s)), "driven")
            self.leave_or_lie(s)
        else:
            n = f[2]
            landed = (s.v, s.w)
            s.fastest = max(s.fastest, -n.dot(s.v))
            if self.compliance is None:
                course = self.struck((s,), (_at_plane(f, s),), None)
            else:
                course = _compliant(s, f[0], n, self.compliance)
                self.exact = False
            # a rebound within rounding, or within 1000 times an integrated impact's
            # tolerance, of none is none
            settle = max(SETTLE, sp.Float(1000 * max(self.tolerance))) if self.tolerance \
                else SETTLE
            if n.dot(a) < 0 and n.dot(s.v) < 0 and \
                    -n.dot(s.v) <= settle * s.fastest:  # rounding's closing
                s.v = s.v - n.dot(s.v) * n
            if n.dot(a) < 0 and 0 < n.dot(s.v) <= settle * s.fastest:
                s.v = s.v - n.dot(s.v) * n
                course += (f"; the rebound is below {float(settle):g} of the fastest "
                           "landing: the sphere comes to lie on the plane")
            if n.dot(s.v) == 0 and n.dot(a) < 0:  # it lies there, pressed in
                s.lying = f
        self.count += 1
        self.events.append(Event(self.t, "impact", _named(f, s.name), s.c, s.v, s.w,
                                 course, s.name))
        s.regime = s.regime if s.lying is None else ()
        if landed is not None and s.lying is None and self.compliance is None and \
                len(self.ones) == 1:
            self._sum_the_rest(s, f, landed)

    def _sum_the_rest(self, s: _Sphere, f: tuple, landed: tuple) -> None:
        """A single sphere's bounces to come on plane f, summed where they pile up
        (:func:`_summed`, to the horizon)."""
        tail = _summed(f, s, landed, self.a, self.flats, self.exact,
                       None if self.end is None else self.end - self.t)
        if tail is None:
            return
        n = f[2]
        self.snap()
        self.piles.append((s.name, self.t, self.t + tail.t))
        self.t = self.t + tail.t
        s.c = s.c + tail.displacement
        s.v, s.w = tail.velocity, tail.spin
        if not self.exact:
            s.c, s.v, s.w = self.floats(s.c, s.v, s.w)
        if n.dot(s.v) == 0:
            s.lying, s.said = f, False
            self.events.append(Event(self.t, "settles", _named(f, s.name), s.c, s.v, s.w,
                                     f"infinitely many bounces summed ({tail.said}): it "
                                     "lies on the plane", s.name))
        else:
            self.summed += tail.bounces or 0

    def _pair_impact(self, p: _Sphere, q: _Sphere) -> None:
        """Spheres p and q meet by their pair's laws, the planes they lie on resting."""
        law = self.laws.get(frozenset((p.name, q.name)))
        if law is None:
            raise InputError("pairs", f"{p.name} and {q.name} meet at t = "
                             f"{float(self.t):.6g}: give the laws of their meeting (a "
                             "[[pairs]] entry naming the two)")
        one, two = (p, q) if law.first == p.name else (q, p)
        n = (two.c - one.c) / (one.R + two.R)
        meeting = replace(law, normal=sp.ImmutableMatrix(n),
                          point=sp.ImmutableMatrix(one.c + one.R * n))
        resting = tuple(_at_plane(s.lying, s, own=True) for s in (one, two) if s.lying)
        course = self.struck((one, two), (meeting, *resting), "driven" if resting else None)
        self.leave_or_lie(one)
        self.leave_or_lie(two)
        self.count += 1
        self.events.append(Event(self.t, "impact", law.name, one.c, one.v, one.w, course,
                                 one.name, two.name))

    def _phases(self) -> tuple[dict[str, Any], list[tuple[sp.Expr, tuple]]]:
        """Each lying sphere's phase on its plane (sliding until it rolls, rolling, at
        rest), a rolling that starts said once, and the events ahead: each phase's end,
        each sphere's next plane, each pair's meeting, the horizon."""
        phases: dict[str, Any] = {}
        ahead: list[tuple[sp.Expr, tuple]] = []
        for s in self.ones:
            if s.lying is None:
                continue
            phase = _on_plane(s.lying[0], s.lying[2], s.v, s.w, self.a, s.R, s.k,
                              max(self.tolerance) if self.tolerance else None,
                              self.resistance, self.pivot)
            phases[s.name] = phase
            if phase.rolling and not s.said:
                # it comes to lie already rolling: said once, as a rolling that starts
                # (a sphere at rest rests, said of nothing)
                if s.v != sp.zeros(3, 1):
                    self.events.append(Event(self.t, "rolls", _named(s.lying, s.name), s.c,
                                             s.v, s.w, "rolls", s.name))
                s.said = True
            if phase.t > 0:
                ahead.append((phase.t, ("changes", s, phase.ends)))
        rate = {s.name: phases[s.name].rates[0] if s.name in phases else self.a
                for s in self.ones}
        for s in self.ones:
            for f in self.flats:
                if f is s.lying:
                    continue
                when = _first_root(f[2].dot(rate[s.name]) / 2, f[2].dot(s.v),
                                   _gap(f, s.c, s.R), sp.Integer(0))
                if when is not None:
                    ahead.append((when, ("plane", s, f)))
        for p, q in self.couples:
            when = _meeting(q.c - p.c, q.v - p.v, rate[q.name] - rate[p.name], p.R + q.R,
                            self.exact)
            if when is not None:
                ahead.append((when, ("pair", p, q)))
        if self.end is not None:
            ahead.append((self.end - self.t, ("horizon",)))
        return phases, ahead

    def _advance(self) -> Bounces | None:
        """Every sphere moved on to the next event (a phase's end, a plane, a meeting,
        the horizon); the run's answer where it ends there, else None."""
        phases, ahead = self._phases()
        if not ahead:  # every sphere rolls (or flies) on for ever
            if all(s.lying and s.v == sp.zeros(3, 1) and s.w == sp.zeros(3, 1)
                   for s in self.ones):
                return self.finish("rest", self.t)
            return self.finish("rolling" if all(s.lying for s in self.ones) else "flying",
                               self.t)
        step = min(x[0] for x in ahead)
        first = next(x[1] for x in ahead if x[0] == step)  # decided before rounding
        if self.exact and not step.is_Rational:  # from here on in floating point
            self.exact = False
        if not self.exact:
            step = sp.N(step, DIGITS)
        for s in self.ones:
            if s.name in phases:
                moved, s.v, s.w = phases[s.name].at(step)
                s.c = s.c + moved
            else:
                s.c, s.v, s.w = flight(s.c, s.v, s.w, self.a, step)
            if not self.exact:
                s.c, s.v, s.w = self.floats(s.c, s.v, s.w)
            if s.lying is not None:  # on the plane, its rounding left aside
                n = s.lying[2]
                s.c = s.c - _gap(s.lying, s.c, s.R) * n
                s.v = s.v - n.dot(s.v) * n
        self.t = self.t + step
        if first[0] == "horizon" or (self.end is not None and self.t >= self.end):
            self.snap()
            return self.finish("horizon", self.end)
        if first[0] == "changes":
            _, s, kind = first
            assert s.lying is not None
            if kind == "stops":  # at rest: exactly, whatever the rounding
                s.v = sp.zeros(3, 1)
                s.w = s.lying[2].dot(s.w) * s.lying[2]
            elif kind == "stops spinning":
                s.w = s.w - s.lying[2].dot(s.w) * s.lying[2]
            self.events.append(Event(self.t, kind, _named(s.lying, s.name), s.c, s.v, s.w,
                                     kind, s.name))
            s.said = s.said or kind == "rolls"
            self.snap()
        elif first[0] == "plane":
            _, s, f = first
            s.c = s.c - _gap(f, s.c, s.R) * f[2]  # on the plane the root found
            self.due = ("plane", s.name, f[0].name)
        else:
            self.due = ("pair", first[1].name, first[2].name)
        return None


def _summed(f: tuple, s: _Sphere, landed: tuple[sp.Matrix, sp.Matrix], a: sp.Matrix,
            flats: Sequence[tuple], exact: bool, left: sp.Expr | None) -> Tail | None:
    """The bounces still to come of sphere `s`, just risen from plane `f` of the run
    after landing with velocity and spin `landed`, summed (:mod:`rigidimpact.simulate.zeno`)
    where gravity presses it into `f`, the bounce just solved is the one the tail's law
    gives (exactly, or to rounding once the run is in floating point) in the regime of
    the bounce before it, that regime holds for every bounce to come, and no other plane
    is within the tail's reach; with the time `left` to the horizon shorter than the
    tail's, the bounces before it."""
    n, contact = f[2], f[0]
    g = -n.dot(a)
    last, s.regime = s.regime, ()
    e = sp.sympify(contact.restitution)
    if not (g > 0 and n.dot(s.v) > 0 and e.is_number and 0 < e < 1) or \
            _across(a, n) != sp.zeros(3, 1):
        return None
    law = bounce_map(contact, n, *landed, s.R, s.k)
    if law is None:
        return None
    pairs = zip((*law[0], *law[1]), (*s.v, *s.w), strict=True)
    if exact:
        if any(x != y and sp.simplify(x - y) != 0 for x, y in pairs):
            return None
    else:
        scale = max(1, *(abs(x) for x in (*s.v, *(s.R * y for y in s.w))))
        if any(abs(sp.N(x - y, DIGITS)) > sp.Float(10) ** (5 - DIGITS) * scale
               for x, y in pairs):
            return None
    s.regime = (contact.name, law[2])
    if last != s.regime:  # the second bounce in a row of one regime
        return None
    rise = n.dot(s.v)
    whole = None  # the bounces before the horizon, where it comes first
    if left is not None and left * g * (1 - e) < 2 * rise:
        whole = _before(e, 2 * rise / g, left)
        if whole == 0:
            return None
    tail = geometric_tail(contact, n, g, s.v, s.w, s.R, s.k, whole)
    if tail is None or tail.regime != law[2]:
        return None
    # every centre of the tail lies within its highest rise plus the time times the
    # fastest it may move across n of where it rose (a bound, taken in float with room)
    u = _across(s.v, n)
    slip = u - s.R * s.w.cross(n)
    across = max(float(_length(u)), float(_length(_across(tail.velocity, n)))) + \
        2 * float(_length(slip) * s.k / (1 + s.k))
    reach = float(rise ** 2 / (2 * g)) + float(tail.t) * across
    if any(float(_gap(other, s.c, s.R)) <= 1.01 * reach + 1e-30 for other in flats
           if other is not f):
        return None
    return tail


def _before(e: sp.Expr, first: sp.Expr, left: sp.Expr) -> int:
    """How many whole flights of ``first, e first, e^2 first, ...`` end by time
    `left` (less than their sum): estimated by logarithms, then settled exactly."""
    def within(m: int) -> bool:
        return first * (1 - e ** m) / (1 - e) <= left
    estimate = math.log(max(1e-300, 1 - float(left * (1 - e) / first))) / math.log(float(e))
    m = max(0, int(estimate))
    if m > SUMMED:
        raise InputError("simulate.until", f"the time asked falls about {m} bounces into "
                         f"a pile-up of bounces (more than {SUMMED} to sum one by one): "
                         "ask for a time after they pile up, or an earlier one")
    while within(m + 1):
        m += 1
    while m > 0 and not within(m):
        m -= 1
    return m


def _across(x: sp.Matrix, n: sp.Matrix) -> sp.Matrix:
    return x - n.dot(x) * n


def _length(x: sp.Matrix) -> sp.Expr:
    return sp.sqrt(x.dot(x))


def _not_through(ones: Sequence[_Sphere], flats: Sequence[tuple], exact: bool) -> None:
    """Refuse, in one line naming the two, a sphere that starts through a plane: its
    centre nearer the plane than its radius, or on the far side (touching is lying)."""
    for s in ones:
        for f in flats:
            gap = _gap(f, s.c, s.R)
            slack = 0 if exact else sp.Float(10) ** (5 - DIGITS) * (1 + max(abs(x) for x in s.c))
            if gap < -slack:
                raise InputError(f"{f[0].name}.point", f"{s.name} starts through the plane "
                                 f"{f[0].name}: its centre is {float(gap + s.R):.6g} from "
                                 f"the plane on the sphere's side, less than its radius "
                                 f"{float(s.R):.6g}")


def _run_settings(impacts: Any, horizon: Any, gravity: Any, rolling_resistance: Any,
                  pivot_friction: Any, compliance: Any
                  ) -> tuple[Any, sp.Matrix, Any, Any, float | None]:
    """:func:`spheres`' settings checked, each refused in one line naming it (by its
    scene field where a scene gives it): the end time (or None), gravity, the rolling
    resistance and the pivoting friction, as SymPy, and the compliance as a float (or
    None); text is refused, never read."""
    if impacts is None and horizon is None:
        raise InputError("simulate.until", "give a number of impacts or a time")
    if impacts is not None and (isinstance(impacts, bool) or not isinstance(impacts, int)
                                or not 1 <= impacts <= MAX_IMPACTS):
        raise InputError("simulate.impacts", f"a whole number from 1 to {MAX_IMPACTS}")
    end = None if horizon is None else given_number(horizon, "simulate.until (horizon)")
    if end is not None and not (end.is_number and end > 0):
        raise InputError("simulate.until (horizon)", f"a positive time, not {horizon!r}")
    if isinstance(gravity, (str, bytes)) or not hasattr(gravity, "__len__") or \
            len(gravity) != 3:
        raise InputError("simulate.gravity", "three numbers [gx, gy, gz]")
    a = sp.Matrix([given_number(x, f"simulate.gravity[{i}]") for i, x in enumerate(gravity)])
    if not all(x.is_number for x in a):
        raise InputError("simulate.gravity", "three numbers [gx, gy, gz]")
    wear = []
    for name, given in (("simulate.rolling_resistance", rolling_resistance),
                        ("simulate.pivot_friction", pivot_friction)):
        x = given_number(given, name)
        x = sp.nsimplify(x) if isinstance(given, float) else x
        if not (x.is_number and x >= 0):
            raise InputError(name, f"a number at least 0, not {x}")
        wear.append(x)
    if compliance is not None:
        ratio = given_number(compliance, "compliance")
        if not (ratio.is_number and ratio > 0):
            raise InputError("compliance", "the stiffness ratio k_t/k_n must be a positive "
                             f"number, not {compliance!r}")
        compliance = float(ratio)
    return end, a, wear[0], wear[1], compliance


def _compliant(s: _Sphere, contact: Contact, n: sp.Matrix, ratio: float) -> str:
    """Sphere `s` bounces on `contact`'s plane through the tangentially compliant
    contact: its velocity and spin after, in 40-digit floats of the float64 answer;
    the course."""
    restitution, tangential = contact.laws
    if restitution.newtons_e() is None or not tangential.coulomb():
        raise InputError(f"{contact.name}.tangential", "tangential-compliance bounces a "
                         "sphere on a plane with Newton's e and Coulomb's friction "
                         "(tangential = \"coulomb\", friction = mu)")
    v, w = sphere_bounce([float(x) for x in s.v], [float(x) for x in s.w],
                         [float(x) for x in n], float(s.R), float(s.k),
                         float(contact.friction), float(contact.restitution), ratio, STEPS)
    s.v, s.w = (sp.Matrix([sp.Float(float(x), DIGITS) for x in y]) for y in (v, w))
    s.said = False
    return f"the compliant contact (k_t/k_n = {ratio:g}), integrated"


def _at_plane(flat: tuple, s: _Sphere,
              own: bool = False) -> Contact:
    """The plane's contact with sphere `s`, at its touching point (the sphere in place
    of the one the plane names, the normal's sense kept), by the name the scene gave
    it; a plane the scene names for other spheres only is named for the sphere too
    where `own` (several spheres touch it at once: their names must differ)."""
    c = flat[0]
    fixed = c.first if c.first not in flat[3] else c.second
    bodies = (fixed, s.name) if c.first == fixed else (s.name, fixed)
    name = flat[4].get(s.name) or (f"{c.name}_{s.name}" if own else c.name)
    return replace(c, point=sp.ImmutableMatrix(s.c - s.R * flat[2]), bodies=bodies,
                   name=name)


def _gap(flat: tuple, c: sp.Matrix, R: sp.Expr) -> sp.Expr:
    """How far the sphere's surface is from the plane (0: touching)."""
    return flat[2].dot(c - flat[1]) - R


def _on_plane(contact: Contact, n: sp.Matrix, v: sp.Matrix, w: sp.Matrix, a: sp.Matrix,
              R: sp.Expr, k: sp.Expr, tolerance: float | None = None,
              resistance: sp.Expr = 0, pivot: sp.Expr = 0) -> _Phase:
    """The sphere lying on `contact`'s plane until its motion changes: sliding by
    Coulomb's friction until it rolls (:func:`rigidimpact.simulate.sphere.sliding`);
    rolling (its slip zero, or rounding's size in floating point), slowed by rolling
    resistance where asked until it stops; its spin about the normal worn by pivoting
    friction where asked until it ends; on a smooth plane keeping its velocity and
    spin."""
    if (a - n.dot(a) * n) != sp.zeros(3, 1):
        raise InputError(f"{contact.name}.normal", "a sphere lying on a plane that gravity "
                         "does not press straight into (a slope) is not followed yet")
    slip = v + w.cross(-R * n)
    zero = sp.zeros(3, 1)
    rolling = slip == zero
    if not rolling and any(x.has(sp.Float) for x in (*v, *w)):  # floats: a slip at
        # their rounding, or within 1000 times an integrated impact's tolerance, is a
        # rolling sphere's
        scale = max(1, *(abs(x) for x in (*v, *(R * y for y in w))))
        floor = sp.Float(10) ** (5 - DIGITS) if tolerance is None else \
            sp.Float(1000 * tolerance)
        rolling = all(abs(x) <= floor * scale for x in slip)
    mu = contact.friction
    if not rolling and (mu is None or mu == 0):
        if contact.laws[1].grips and contact.laws[1].coulomb() is None:
            raise InputError(f"{contact.name}.friction", "a sphere left lying on a plane "
                             "slides by Coulomb's friction: give the contact's friction")
        return _Phase(v, w, zero, zero, sp.Integer(0), "", False)  # smooth: for ever
    g = -n.dot(a)
    # pivoting friction: a moment pivot m g R against the spin about the normal
    spin = n.dot(w)
    turning = (pivot * g / (k * R)) if pivot and spin != 0 else 0
    dw_pivot = -sp.sign(spin) * turning * n if turning else zero
    spun = abs(spin) / turning if turning else None
    if rolling:
        v = v - n.dot(v) * n
        w = n.cross(v) / R + spin * n  # rolling: the spin across n is the velocity's
        speed = sp.sqrt(v.dot(v))
        if resistance and speed != 0:  # slowed along its path, rolling kept
            dv = -resistance * g * v / speed
            dw = n.cross(dv) / R
            stop = speed / (resistance * g)
        else:
            dv, dw, stop = zero, zero, None
        ends: list[tuple[Any, str]] = [x for x in ((stop, "stops"), (spun, "stops spinning"))
                                       if x[0] is not None]
        if not ends:
            return _Phase(v, w, zero, zero, sp.Integer(0), "", True)
        t, why = min(ends, key=lambda x: x[0])
        return _Phase(v, w, dv, dw + dw_pivot, t, why, True)
    slide = sliding(v, w, R, k, mu, g, tuple(n))
    t, why = slide.t, "rolls"
    if spun is not None and spun < t:
        t, why = spun, "stops spinning"
    return _Phase(v, w, slide.rates[0], slide.rates[1] + dw_pivot, t, why, False)


@dataclass(frozen=True)
class _Phase:
    """A sphere lying on a plane between two changes of its motion: its velocity and
    spin change at the constant rates `dv` and `dw` until time `t` (0: never), when it
    `ends` (rolls, stops, stops spinning); `rolling` if it rolls throughout."""

    v: sp.Matrix
    w: sp.Matrix
    dv: sp.Matrix
    dw: sp.Matrix
    t: sp.Expr
    ends: str
    rolling: bool

    @property
    def rates(self) -> tuple[sp.Matrix, sp.Matrix]:
        return self.dv, self.dw

    def at(self, t: Any) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
        """(displacement, velocity, spin) a time t into the phase (t up to its end)."""
        return (self.v * t + self.dv * t ** 2 / 2, self.v + self.dv * t,
                self.w + self.dw * t)


def _impact(movers: Sequence[Body3], contacts: Sequence[Contact], rule: str | None
            ) -> tuple[dict[str, tuple[sp.Matrix, sp.Matrix]], str, float | None]:
    """Each of the spheres `movers` after the impact at `contacts` (the first strikes;
    the others rest, by the driven rule), the course, and the tolerance it was
    integrated to (None: exact, or a closed form)."""
    names = {b.name for b in movers}
    fixed = sorted({b for c in contacts for b in (c.first, c.second) if b not in names})
    solved = SpaceCollision((*(Body3.fixed(name) for name in fixed), *movers),
                            tuple(contacts), rule=rule).solve()
    results = solved.results()
    after = {b.name: (sp.Matrix([results[f"{b.name}.{k}"] for k in SPEEDS[:3]]),
                      sp.Matrix([results[f"{b.name}.{k}"] for k in SPEEDS[3:]]))
             for b in movers}
    stated = solved.method.split("integrated to ")[-1] \
        if solved.method.startswith("integrated to ") else None
    integrated = stated is not None or any("integrated" in note for note in solved.notes)
    return (after, solved.regime or "",
            (float(stated) if stated else TOLERANCE) if integrated else None)
