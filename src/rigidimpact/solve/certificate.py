"""Every Solution checks itself: the residual of each law it must obey, computed from the
bodies before and after and the impulses alone, apart from the path that solved it.

One certificate serves the plane and space: the same conditions, computed by the same
code, for planar bodies (a spin about z, one tangent a contact) and for 3-D bodies (a
spin vector and an inertia tensor, two tangents a contact, hinges whose impulses include
moments). A planar answer written in space gets the same residuals (the tests hold the
two side by side).

The conditions, each a residual that is zero when it holds (a violation's size, never
negative):

- ``BODY.momentum_x``, ``BODY.momentum_y`` (and ``BODY.momentum_z`` in space): a free
  body's change of linear momentum less the impulses it received (a pivoted body's
  linear balance holds by definition: its pivot's reaction is that remainder);
- ``BODY.angular_momentum`` (in space ``BODY.angular_momentum_x``, ``_y``, ``_z``): its
  change of angular momentum about its centre (a pivoted body: about its pivot) less
  the moments of those impulses (and of a hinge's moments);
- ``CONTACT.pushes``: no pull, ``max(0, -P_n)``;
- ``CONTACT.opens``: no penetration after, ``max(0, -v_n+)`` (v_n the normal velocity of
  the second touching point relative to the first);
- ``CONTACT.cone``: Coulomb's cone, ``max(0, |P_t| - mu P_n)``; ``CONTACT.smooth``: a
  smooth contact's ``|P_t|``; ``CONTACT.sticks``: a sticking contact's slip after;
  ``CONTACT.rough``: Walton's law with no cone, the slip after against ``-beta`` times
  the slip before; ``CONTACT.tangential_law``: a user's law that none of these states,
  its own tangential conditions (its one face, ``linear_conditions``) at the totals;
- friction's direction and end (one contact's impact, or the simultaneous rule):
  ``CONTACT.against_slip`` (on the cone's edge, friction never acts along the slip
  after, or past Walton's target), ``CONTACT.slides`` (inside a Coulomb cone, the
  contact sticks or its slip reversed) and ``CONTACT.tangential_restitution`` (inside
  Walton's cone, the slip after is ``-beta`` times the slip before);
- under the simultaneous rule with Newton's law at the velocity level:
  ``CONTACT.restitution`` (an acting contact leaves at ``-e`` times its closing speed),
  ``CONTACT.released`` (a released one at least that fast) and
  ``CONTACT.complementarity`` (``P_n`` times the difference);
- one contact's own impact under a kinematic law (Newton's, or a user's): its normal
  velocity after, ``CONTACT.restitution``, whatever the path;
- one contact's own impact, along its impulse path (:func:`path_residuals`; in space,
  a smooth or sticking contact's straight path):
  ``CONTACT.path`` (each straight piece slides on Coulomb's cone against a slip of one
  sign, or sticks) and ``CONTACT.restitution`` (the restitution law's own end: Newton's
  velocity, Poisson's impulse ratio, the energetic work ratio);
- ``energy``: kinetic energy created, ``max(0, K+ - K-)``.

The arithmetic is chosen from the numbers: exact (SymPy's rationals, or the expressions
as they are) where the answer is exact, mpmath at 50 digits where it holds floats.

Which violations are a model's physical limits and which a numerical failure depends on
the rule and laws, so :func:`assess` sorts them: energy created (Newton's law at
coupled contacts, or with friction), a contact still closing under Poisson's law acting
together, and a sticking contact whose law needs a pull are limits the model has, said
in ``warnings``; any other residual above the tolerance means the answer is wrong, and
it is never given as an answer.

Examples
--------
>>> import rigidimpact as ri
>>> solution = ri.chain(3).simultaneous()
>>> max(solution.checks.values())
0
>>> solution.checks["c0.opens"], solution.checks["energy"]
(0, 0)
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy as sp
from sympy.polys.domains import QQ

from rigidimpact.errors import InputError
from rigidimpact.laws.cone import tangents
from rigidimpact.solve.registry import conduct
from rigidimpact.symbolic.evaluate import Unsupported, value_at

__all__ = ["residuals", "contact_residuals", "friction_residuals", "path_residuals",
           "assess", "as_sympy", "PHYSICAL_LIMITS", "FLOAT_TOLERANCE", "random_points",
           "coefficient_ranges", "SYMBOLIC_POINTS"]

DIGITS = 50
# a floating-point answer (a large problem's, or a compliant integration's) is trusted
# to this relative size; an exact one must be exactly zero; one rounded to 60 digits
# between steps, to 1e-40 (the sequential rule's settling threshold)
FLOAT_TOLERANCE = 1e-9
ROUNDED_TOLERANCE = mpmath.mpf(10) ** -35
PHYSICAL_LIMITS = ("energy", "opens", "pushes")
SETTLED = 1e-40  # the sequential rule stops once every closing speed is below this


def _perp(r: Sequence[Any]) -> tuple[Any, Any]:
    return -r[1], r[0]


def _cross(a: Sequence[Any], b: Sequence[Any]) -> list[Any]:
    """``a x b``: its one component (z) in the plane, three in space."""
    if len(a) == 2:
        return [a[0] * b[1] - a[1] * b[0]]
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _turn(w: Sequence[Any], r: Sequence[Any]) -> list[Any]:
    """``w x r``, the velocity a spin `w` (z alone in the plane) gives an arm `r`."""
    if len(w) == 1:
        return [-w[0] * r[1], w[0] * r[0]]
    return _cross(w, r)


def _dot(a: Sequence[Any], b: Sequence[Any]) -> Any:
    total = a[0] * b[0]
    for x, y in zip(a[1:], b[1:], strict=True):
        total += x * y
    return total


def _spatial(bodies: Sequence[Any]) -> bool:
    """Whether the bodies are in space (three components a position)."""
    return any(len(b.position) == 3 for b in bodies)


def _spin(state: Any) -> list[Any]:
    """A body's spin as components: z alone in the plane, three in space."""
    return list(state.spin) if isinstance(state.spin, (sp.MatrixBase, tuple)) \
        else [state.spin]


def _inertia(body: Any) -> list[list[Any]]:
    """A body's central inertia as a matrix: 1 x 1 in the plane, 3 x 3 in space."""
    if isinstance(body.inertia, sp.MatrixBase):
        return [[body.inertia[i, j] for j in range(3)] for i in range(3)]
    if isinstance(body.inertia, tuple):  # a 3-D body's at a point, mpmath numbers in it
        return [list(row) for row in body.inertia]
    return [[body.inertia]]


class _Lists:
    """Each vector's components as a list, read once per certificate (a body's velocity
    and position enter each of its contacts, and reading a SymPy matrix's entries one
    by one is the certificate's largest cost on a thousand contacts)."""

    def __init__(self) -> None:
        self.read: dict[int, tuple[Any, list[Any]]] = {}

    def __call__(self, vector: Any) -> list[Any]:
        found = self.read.get(id(vector))
        if found is None:
            found = self.read[id(vector)] = (vector, list(vector))
        return found[1]


def _arithmetic(numbers: Sequence[Any]) -> str:
    """"exact" (rationals), "mp" (numbers with floats or irrationals), or "symbolic"."""
    kinds = set()
    for x in numbers:
        x = sp.sympify(x)
        if x.free_symbols:
            return "symbolic"
        kinds.add("exact" if x.is_Rational else "mp")
    return "mp" if "mp" in kinds else "exact"


def _components(value: Any) -> list[Any]:
    """A tangential impulse as its components: one in the plane, (t1, t2) in space."""
    if isinstance(value, (tuple, list, sp.MatrixBase)):
        return list(value)
    return [value]


def residuals(before: Sequence[Any], after: Sequence[Any], contacts: Sequence[Any],
              impulses: Mapping[str, Any], tangential: Mapping[str, Any], rule: str,
              acted: Sequence[str], locked: Sequence[str] = (), joints: Sequence[Any] = (),
              joint_impulses: Mapping[str, Any] | None = None,
              conditions: Sequence[Any] = (),
              path: Sequence[tuple[Any, Any]] = ()) -> dict[str, Any]:
    """Each condition's residual (see the module's notes) as a number (exact, or an
    mpmath number) or, with symbols left, a SymPy expression.

    The same conditions in the plane and in space: `before` and `after` are the bodies
    (planar :class:`~rigidimpact.model.bodies.Body`, or
    :class:`~rigidimpact.model.space.Body3`), `tangential` each contact's tangential
    impulse (a number in the plane, its components along the tangents (t1, t2) in
    space). `locked` names the contacts whose impact ended locked at rest (Routh's
    method where the touching points have one degree of freedom and the restitution
    impulse would drive them together): their law is a normal velocity of zero after,
    not restitution's. `joints` and their `joint_impulses` (given to the second body;
    a hinge in space adds its two moments across its axis) enter the momentum
    balances, and each joint's two points must move together after (``JOINT.holds``).
    `path`, for one contact's own impact in the plane, is its impulse path (the corners
    ``(P_n, P_t)`` from (0, 0) to the end, straight between them; empty for a straight
    path): each straight piece is checked against friction's law and the end against
    the restitution law's (``CONTACT.path`` and ``CONTACT.restitution``, see
    :func:`path_residuals`). A smooth or sticking contact's path is straight, in space
    as in the plane."""
    joint_impulses = joint_impulses or {}
    bodies = {b.name: b for b in before}
    later = {b.name: b for b in after}
    spatial = _spatial(before)
    flat = _Lists()
    data: list[Any] = []
    for b in before:
        if b.support == "fixed":
            continue
        a = later[b.name]
        data += [b.mass, *(x for row in _inertia(b) for x in row), *flat(b.position),
                 *flat(b.velocity), *_spin(b), *flat(a.velocity), *_spin(a)]
        if b.support == "pivot":
            data += list(b.pivot)
    for j in joints:
        data += [*j.point, *joint_impulses[j.name]]
        if j.axis is not None:  # a hinge's moments act across its axis
            data += [x for t in tangents(list(j.axis))[1:] for x in t]
    for c in contacts:
        data += [*flat(c.point), *(c.frame if spatial else flat(c.normal)), impulses[c.name],
                 *_components(tangential.get(c.name, 0)), c.restitution]
        if c.laws[1].cone() is not None:
            data.append(c.laws[1].cone())
        if getattr(c.laws[1], "beta", None) is not None:
            data.append(c.laws[1].beta)
    for corner in path:
        data += list(corner)
    how = _arithmetic(data)
    if how == "symbolic":
        return _at_points(before, after, contacts, impulses, tangential, rule, locked,
                          joints, joint_impulses, conditions)
    # rounded data (a Float given), not an mpmath number a symbolic answer took at a point
    floats = any(not isinstance(x, mpmath.mpf) and sp.sympify(x).has(sp.Float)
                 for x in data)
    if spatial and how == "exact" and not all(x.is_Rational for c in contacts
                                              for x in c.frame):
        how = "mp"  # a frame's square roots: at 50 digits
    if how == "exact" and (spatial or all(
            sp.sqrt(sum(x * x for x in flat(c.normal))).is_Rational for c in contacts)):
        # every number rational: in SymPy's QQ (python-flint's or gmpy's where present),
        # each converted once (a body's numbers enter each of its contacts)
        rationals: dict[Any, Any] = {}

        def num(x: Any) -> Any:
            try:
                return rationals[x]
            except KeyError:
                y = sp.sympify(x)
                rationals[x] = value = QQ(int(y.p), int(y.q))
                return value
            except TypeError:  # not hashable
                y = sp.sympify(x)
                return QQ(int(y.p), int(y.q))

        def root(x: Any) -> Any:
            value = sp.sqrt(QQ.to_sympy(x))
            return QQ(int(value.p), int(value.q))
    elif how == "exact":  # a normal of irrational length: SymPy's own numbers
        def num(x: Any) -> Any:
            return sp.sympify(x)

        def root(x: Any) -> Any:
            return sp.sqrt(x)
    else:  # each number evaluated once (a body's position enters each of its contacts)
        known: dict[Any, Any] = {}

        def num(x: Any) -> Any:
            if isinstance(x, mpmath.mpf):
                return x
            if x not in known:
                known[x] = mpmath.mpf(sp.N(x, digits + 10)._to_mpmath(mpmath.mp.prec))
            return known[x]

        def root(x: Any) -> Any:
            return mpmath.sqrt(x)

    # 50 digits, and as many more as the data span orders of magnitude (a length of 1e100
    # puts 1e200 beside 1 in an angular momentum): rounding never passes for a broken law
    digits = DIGITS + _span(data) if how == "mp" else DIGITS
    with mpmath.workdps(digits):
        found = _residuals(bodies, later, contacts, impulses, tangential, rule, acted, num,
                           root, how, locked, joints, joint_impulses, flat)
        straight = len(contacts) == 1 and not contacts[0].laws[1].solved_by_regimes
        if len(contacts) == 1 and not joints and not locked and (path or straight):
            (c,) = contacts
            end = (impulses[c.name], *_components(tangential.get(c.name, 0)))
            found.update(path_residuals(bodies, c, path or ((0,) * len(end), end), num,
                                        root, how == "exact", end))
    found["_floats"] = floats
    return found


def _frame(contact: Any, num: Any, root: Any, spatial: bool,
           flat: Any = list) -> list[list[Any]]:
    """The contact's unit normal and tangents, in the residuals' arithmetic: in the
    plane from its normal (the tangent turned +90 degrees), in space its frame's rows."""
    if spatial:
        return [[num(x) for x in contact.frame.row(i)] for i in range(3)]
    n = [num(x) for x in flat(contact.normal)]
    length = root(n[0] * n[0] + n[1] * n[1])
    n = [n[0] / length, n[1] / length]
    return [n, list(_perp(n))]


def _residuals(bodies, later, contacts, impulses, tangential, rule, acted, num, root,
               how, locked, joints, joint_impulses, flat) -> dict[str, Any]:
    zero = num(0)
    spatial = _spatial(list(bodies.values()))
    dimension = 3 if spatial else 2
    received: dict[str, list[Any]] = {
        name: [zero] * (6 if spatial else 3) for name in bodies}
    out: dict[str, Any] = {}
    # friction's direction is a law of each contact's whole impact where the contact is
    # loaded throughout: one contact's own impact (Routh's, whatever the rule's name), and
    # the simultaneous rule (a law of the velocities after). Under the sequential rule a
    # contact's total is a sum of steps, under the driven rule a resting contact may be
    # unloaded (and its slip turn freely) for part of the impact, and a compliant run's
    # friction follows its own springs: their laws hold step by step, not in the totals
    whole_impact = len(contacts) == 1 or conduct(rule).whole_impact
    approaching = False  # whether some contact approached before: an impact to check
    speed = None if how == "exact" else _scale(bodies, later, impulses, tangential, num,
                                               zero, flat)

    seen: dict[int, tuple[list[Any], list[Any], list[Any]]] = {}

    def motion(state: Any) -> tuple[list[Any], list[Any], list[Any]]:
        """A body's velocity, spin and position in the residuals' arithmetic, each
        converted once (a body enters each of its contacts)."""
        key = id(state)
        if key not in seen:
            seen[key] = ([num(x) for x in flat(state.velocity)],
                         [num(x) for x in _spin(state)],
                         [num(x) for x in flat(state.position)])
        return seen[key]

    def velocity(body: Any, state: Any, point: Sequence[Any]) -> list[Any]:
        if body.support == "fixed":
            return [zero] * dimension
        v, w, centre = motion(state)
        r = [point[k] - centre[k] for k in range(dimension)]
        turn = _turn(w, r)
        return [v[k] + turn[k] for k in range(dimension)]

    def receive(first: str, second: str, at: Sequence[Any], push: list[Any],
                couple: Sequence[Any] = ()) -> None:
        """An impulse `push` at `at` (and a `couple`, a hinge's moments), given to
        `second` and taken from `first`: into each movable body's linear and angular
        momentum (about its pivot or centre)."""
        for name, sign in ((second, 1), (first, -1)):
            body = bodies[name]
            if body.support == "fixed":
                continue
            axis = [num(x) for x in body.pivot] if body.support == "pivot" else \
                motion(body)[2]
            arm = [at[k] - axis[k] for k in range(dimension)]
            moment = _cross(arm, push)
            for k in range(dimension):
                received[name][k] += sign * push[k]
            for k, x in enumerate(moment):
                received[name][dimension + k] += sign * (x + (couple[k] if couple else 0))

    def relative(states: Mapping[str, Any], first: str, second: str, point: Sequence[Any],
                 frame: Sequence[Sequence[Any]]) -> list[Any]:
        """The second touching point's velocity less the first's, along each of
        `frame`'s rows."""
        a = velocity(bodies[first], states[first], point)
        b = velocity(bodies[second], states[second], point)
        d = [y - x for x, y in zip(a, b, strict=True)]
        return [_dot(d, row) for row in frame]

    for c in contacts:
        first, second = c.bodies if c.bodies else tuple(bodies)[:2]
        frame = _frame(c, num, root, spatial, flat)
        p_n = num(impulses[c.name])
        p_t = [num(x) for x in _components(tangential.get(c.name, 0))]
        if len(p_t) < len(frame) - 1:  # a planar answer's tangential of a 3-D contact
            p_t += [zero] * (len(frame) - 1 - len(p_t))
        push = [p_n * frame[0][k] + sum((p * row[k] for p, row in zip(p_t, frame[1:],
                                                                      strict=True)), zero)
                for k in range(dimension)]
        at = [num(x) for x in flat(c.point)]
        receive(first, second, at, push)

        earlier, now = (relative(states, first, second, at, frame)
                        for states in (bodies, later))
        approaching = approaching or earlier[0] < 0
        out.update(contact_residuals(
            c.name, c.laws, p_n, p_t, earlier, now, num,
            exact=how == "exact", speed=speed, acted=c.name in acted,
            whole_impact=whole_impact, locked=c.name in locked, rule=rule,
            alone=len(contacts) == 1))
    for j in joints:  # a hinge between two bodies: its impulse, any sign; no gap after
        parts = [num(x) for x in joint_impulses[j.name]]
        across = _hinge_axes(j, num) if j.axis is not None else []
        couple = [sum((m * t[k] for m, t in zip(parts[3:], across, strict=True)), zero)
                  for k in range(3)] if across else []
        at = [num(x) for x in j.point]
        receive(j.first, j.second, at, parts[:dimension], couple)
        gap = [a - b for a, b in zip(velocity(bodies[j.second], later[j.second], at),
                                     velocity(bodies[j.first], later[j.first], at),
                                     strict=True)]
        turning = [zero] * len(across)
        for name, sign in ((j.second, 1), (j.first, -1)):
            if bodies[name].support == "fixed":
                continue
            w = motion(later[name])[1]
            turning = [x + sign * _dot(w, t) for x, t in zip(turning, across, strict=True)]
        out[f"{j.name}.holds"] = max(abs(x) for x in (*gap, *turning))
    kinetic = [zero, zero]
    for name, body in bodies.items():
        if body.support == "fixed":
            continue
        after = later[name]
        m = num(body.mass)
        inertia = [[num(x) for x in row] for row in _inertia(body)]
        (v0, w0, centre), (v1, w1, _) = motion(body), motion(after)
        dv = [a - b for a, b in zip(v1, v0, strict=True)]
        dw = [a - b for a, b in zip(w1, w0, strict=True)]
        spun = [_dot(row, dw) for row in inertia]  # I dw
        got = received[name]
        if body.support != "pivot":
            for k, axis in enumerate("xyz"[:dimension]):
                out[f"{name}.momentum_{axis}"] = abs(m * dv[k] - got[k])
            if spatial:
                for k, axis in enumerate("xyz"):
                    out[f"{name}.angular_momentum_{axis}"] = abs(spun[k] - got[3 + k])
            else:
                out[f"{name}.angular_momentum"] = abs(spun[0] - got[2])
        else:  # about the pivot: I_c dw + m (R - pivot) x dV
            arm = [centre[k] - num(body.pivot[k]) for k in range(2)]
            out[f"{name}.angular_momentum"] = abs(spun[0] + m * _cross(arm, dv)[0]
                                                  - got[2])
        for k, (v, w) in enumerate(((v0, w0), (v1, w1))):
            kinetic[k] += (m * _dot(v, v) + _dot(w, [_dot(row, w) for row in inertia])) / 2
    out["energy"] = max(zero, kinetic[1] - kinetic[0])
    out["_scale"] = _scale(bodies, later, impulses, tangential, num, zero, flat)
    out["_kinetic"] = kinetic[0]
    out["_exact"] = how == "exact"
    out["_approaching"] = approaching
    return out


def contact_residuals(name: str, laws: tuple[Any, Any], p_n: Any, p_t: Sequence[Any],
                      before: Sequence[Any], after: Sequence[Any], num: Any, exact: bool,
                      speed: Any, acted: bool, whole_impact: bool, rule: str,
                      alone: bool, locked: bool = False) -> dict[str, Any]:
    """One contact's conditions, from its impulse (normal `p_n`, tangential `p_t`: one
    component in the plane, two in space) and its relative velocity before and after
    in its frame (``[v_n, slip...]``), in the caller's arithmetic: the one statement of
    a contact's laws for every model (planar and 3-D bodies, and a mechanics system's
    points). `acted`: the contact took part (a rule's acting set); `whole_impact`:
    friction's direction is a law of the totals (one contact's own impact, or the
    simultaneous rule); `alone`: the contact is the impact's only one; `locked`: its
    impact ended locked at rest (Routh's one-freedom course)."""
    restitution, friction = laws
    zero = num(0)
    v_before, slip_before = before[0], list(before[1:])
    v_after, slip = after[0], list(after[1:])
    out: dict[str, Any] = {f"{name}.pushes": max(zero, -p_n),
                           f"{name}.opens": max(zero, -v_after)}
    mu = friction.cone()
    beta = getattr(friction, "beta", None)
    if not friction.grips:
        out[f"{name}.smooth"] = max(abs(x) for x in p_t)
    elif mu is not None:
        out[f"{name}.cone"] = _beyond(p_t, num(mu) * p_n, exact, zero)
    if friction.unknown_tangential and acted:
        out[f"{name}.sticks"] = max(abs(x) for x in slip)
    if mu is None and beta is not None and friction.grips:  # Walton's, no cone
        out[f"{name}.rough"] = max(abs(a + num(beta) * b)
                                   for a, b in zip(slip, slip_before, strict=True))
    elif mu is None and friction.grips and not friction.unknown_tangential and acted \
            and whole_impact and not friction.solved_by_regimes:
        # a law none of the above states (a user's): its own tangential conditions,
        # asked of its one face at the totals
        def big(xs: Sequence[Any]) -> sp.Matrix:
            return sp.Matrix([as_sympy(x) for x in xs])

        rows = friction.linear_conditions(big(before), big(after), big([p_n, *p_t]),
                                          as_sympy(v_after))[1:]
        out[f"{name}.tangential_law"] = max([zero, *(abs(num(r)) for r in rows)])
    if mu is not None and friction.grips and p_n > 0 and whole_impact:
        out.update(friction_residuals(name, friction, num, p_n, p_t, slip_before, slip,
                                      exact, speed))
    if locked:  # the course's own law: at rest along the normal after
        out[f"{name}.restitution"] = abs(v_after)
    elif conduct(rule).whole_impact and restitution.together == "velocity":
        # the law's own normal velocity after, from the closing one (a new law is
        # one class: the check asks it, as the rule does)
        target = num(restitution.leaving(as_sympy(min(v_before, zero))))
        if acted:
            out[f"{name}.restitution"] = abs(v_after - target)
        else:
            out[f"{name}.released"] = max(zero, target - v_after)
        out[f"{name}.complementarity"] = abs(p_n * (v_after - target))
    elif alone and not restitution.splits_on_compression:
        # a kinematic law's end is a velocity, whatever the path
        out[f"{name}.restitution"] = abs(
            v_after - num(restitution.leaving(as_sympy(min(v_before, zero)))))
    return out


def _beyond(p_t: Sequence[Any], limit: Any, exact: bool, zero: Any) -> Any:
    """How far a tangential impulse lies outside Coulomb's cone of radius `limit`:
    ``max(0, |P_t| - limit)``, one tangent or two."""
    size = abs(p_t[0]) if len(p_t) == 1 else _root(_dot(p_t, p_t), exact)
    return max(zero, size - limit)


def _hinge_axes(joint: Any, num: Any) -> list[list[Any]]:
    """The two directions across a hinge's axis its moments act along, as its rows
    are built (:func:`rigidimpact.laws.cone.tangents`)."""
    return [[num(x) for x in t] for t in tangents(list(joint.axis))[1:]]


SYMBOLIC_POINTS = 3  # seeded random rational points a closed form is checked at
SYMBOLIC_TRIES = 12  # points drawn to find them (a point where nothing approaches is no
# impact, and one outside a coefficient's range is no law: neither is a check)


def _span(data: Sequence[Any]) -> int:
    """Twice the orders of magnitude the nonzero numbers of `data` span (at most 1000)."""
    exponents = []
    for x in data:
        try:
            value = abs(float(x))
        except (OverflowError, TypeError):  # past float64's range: SymPy's own number
            value = abs(sp.N(x, 15))
        if value and value != float("inf"):
            exponents.append(math.floor(math.log10(value)) if isinstance(value, float)
                             else int(mpmath.floor(mpmath.log10(mpmath.mpf(value)))))
    return min(2 * (max(exponents) - min(exponents)), 1000) if exponents else 0


def _at_points(before, after, contacts, impulses, tangential, rule, locked, joints,
               joint_impulses, conditions=()) -> dict[str, Any]:
    """The residuals of a symbolic answer, exact, at seeded random rational points of its
    symbols where the impact happens: each symbol drawn within its assumptions (a
    restitution coefficient in [0, 1], a friction coefficient at least 0, Walton's beta in
    [-1, 1]), kept where some contact approaches and the answer's own `conditions` (a
    case's) hold. Each key holds the worst over the
    points, relative to that point's scale (energy: to its kinetic energy); ``_points``
    says how many points were checked."""
    symbols: set[sp.Symbol] = set()
    for b in before:
        symbols |= sp.Tuple(b.mass, *(x for row in _inertia(b) for x in row),
                            *b.position, *b.velocity, *_spin(b),
                            *(b.pivot if b.support == "pivot" else ())).free_symbols
    for b in after:
        symbols |= sp.Tuple(*b.velocity, *_spin(b)).free_symbols
    ranges = coefficient_ranges(contacts)
    for c in contacts:
        symbols |= sp.Tuple(*c.point, *c.normal, impulses[c.name],
                            *_components(tangential.get(c.name, 0)),
                            c.restitution).free_symbols
        for x in (c.friction, c.tangential_restitution):
            if x is not None:
                symbols |= sp.sympify(x).free_symbols
    for j in joints:
        symbols |= sp.Tuple(*j.point, *joint_impulses[j.name],
                            *(j.axis if j.axis is not None else ())).free_symbols
    for c in conditions:
        symbols |= sp.sympify(c).free_symbols
    worst: dict[str, Any] = {}
    checked, exact, floats = 0, True, False
    for point in random_points(symbols, ranges):
        if checked == SYMBOLIC_POINTS:
            break
        if not all(sp.sympify(c).xreplace(point) is sp.true for c in conditions):
            continue  # another case's ground
        try:
            found = _at_point(point, before, after, contacts, impulses, tangential, rule,
                              locked, joints, joint_impulses)
        except (InputError, ZeroDivisionError, TypeError, ValueError):
            continue  # no impact there (a body of no mass, a contact apart, ...)
        if found is None:
            continue
        checked += 1
        exact, floats = exact and found["_exact"], floats or found["_floats"]
        scale = found["_scale"] or 1
        kinetic = found["_kinetic"] or 1
        for key, value in found.items():
            if key.startswith("_"):
                continue
            size = as_sympy(value) / as_sympy(kinetic if key == "energy" else scale)
            worst[key] = max(worst.get(key, 0), size)
    if not checked:
        return {}
    return {**worst, "_scale": 1, "_kinetic": 1, "_exact": exact, "_floats": floats,
            "_points": checked, "_symbolic": True}


def coefficient_ranges(contacts: Sequence[Any]) -> dict[sp.Symbol, tuple[int, int]]:
    """Where a contact's coefficient left a symbol may lie: a restitution coefficient in
    [0, 1], a friction coefficient in [0, 2], Walton's beta in [-1, 1]."""
    ranges: dict[sp.Symbol, tuple[int, int]] = {}
    for c in contacts:
        for x, span in ((c.restitution, (0, 1)), (c.friction, (0, 2)),
                        (c.tangential_restitution, (-1, 1))):
            if isinstance(x, sp.Symbol):
                ranges[x] = span
    return ranges


def random_points(symbols: set[Any], ranges: Mapping[Any, tuple[Any, Any]]
                  ) -> Iterator[dict[Any, sp.Rational]]:
    """Seeded random rational points of `symbols` (the same on every machine): each
    within its range, or else in [-3, 3] ([0, 3] where it is positive or nonnegative),
    and of its sign; SYMBOLIC_TRIES of them, then SYMBOLIC_TRIES more with the symbols
    that have no range of their own drawn ten times as far out (a case of the
    simultaneous rule whose conditions ask for a spin past (3 + e)/(1 - e) is checked
    there, where the first points all lie outside it)."""
    rng = random.Random(44)
    for spread in (1, 10):
        for _ in range(SYMBOLIC_TRIES):
            point = {}
            for s in sorted(symbols, key=str):
                far = 3 * spread
                low, high = ranges.get(s, (-far, far) if not (s.is_positive
                                                              or s.is_nonnegative)
                                       else (0, far))
                x = sp.Rational(rng.randint(int(low * 311), int(high * 311)), 311)
                if s.is_positive and x <= 0 or s.is_negative and x >= 0:
                    x = sp.Rational(rng.randint(1, far * 311), 311) * (
                        -1 if s.is_negative else 1)
                point[s] = x
            yield point


@dataclass(frozen=True)
class _BodyAt:
    """A body's data at one point of its symbols: what the residuals read of a body,
    numbers put in (a planar body or a 3-D one), without building and validating the
    body again at every point."""

    name: str
    support: str
    mass: Any
    inertia: Any
    position: Any
    velocity: Any
    spin: Any
    pivot: Any = None
    inertia_inverse: Any = None  # a 3-D body's, where it was formed

    @classmethod
    def of(cls, body: Any, point: Mapping[Any, Any], dps: int) -> _BodyAt:
        def put(x: Any) -> Any:
            if x is None:
                return None
            if not isinstance(x, sp.MatrixBase):
                return _put(x, point, dps)
            values = [_put(y, point, dps) for y in x]
            if all(isinstance(y, sp.Basic) for y in values):
                return sp.ImmutableMatrix(x.rows, x.cols, values)
            if x.cols == 1:  # a vector with mpmath numbers in it: its components
                return tuple(values)
            return tuple(tuple(values[i * x.cols:(i + 1) * x.cols]) for i in range(x.rows))

        return cls(body.name, body.support, put(body.mass), put(body.inertia),
                   put(body.position), put(body.velocity), put(body.spin),
                   put(getattr(body, "pivot", None)),
                   put(getattr(body, "inertia_inverse", None)))

    @property
    def physical(self) -> bool:
        """A positive mass and a moment of inertia of no sign against it (the plane's),
        where they are numbers: a point of the symbols where the body is a body."""
        if self.support == "fixed":
            return True
        if _is_number(self.mass) and not self.mass > 0:
            return False
        return not (isinstance(self.inertia, (sp.Expr, mpmath.mpf))
                    and _is_number(self.inertia) and self.inertia < 0)


POINT_DIGITS = 2 * DIGITS  # an answer's irrational values at a point: these digits


def _is_number(x: Any) -> bool:
    return isinstance(x, mpmath.mpf) or sp.sympify(x).is_number


def _put(x: Any, point: Mapping[Any, Any], dps: int) -> Any:
    """`x` at `point`: walked once to its value (exact where rational), or, where it
    holds what that walk does not take (a Float above all, which must stay one),
    SymPy's own substitution."""
    try:
        return value_at(x, point, dps)
    except Unsupported:
        return sp.sympify(x).xreplace(point)


def _at_point(point, before, after, contacts, impulses, tangential, rule, locked, joints,
              joint_impulses) -> dict[str, Any] | None:
    """The residuals at one point of the symbols, or None where no contact approaches
    there (no impact to check). The answer's values there are exact rationals where
    they are rational, else mpmath numbers at POINT_DIGITS (more where the data span
    more orders of magnitude than the residuals' 50 digits leave room for)."""
    dps = POINT_DIGITS
    while True:
        at_before = tuple(_BodyAt.of(b, point, dps) for b in before)
        at_after = tuple(_BodyAt.of(b, point, dps) for b in after)
        pushes = {c.name: _put(impulses[c.name], point, dps) for c in contacts}
        along = {c.name: [_put(x, point, dps) for x in _components(tangential.get(c.name,
                                                                                  0))]
                 for c in contacts}
        values = [*pushes.values(), *(y for v in along.values() for y in v),
                  *(y for b in (*at_before, *at_after) for y in (
                      *_spin(b), *(b.velocity if b.support != "fixed" else ())))]
        if not all(_is_number(x) for x in values):
            return None
        data = [*values, *(y for b in at_before if b.support != "fixed" for y in (
            b.mass, *(x for row in _inertia(b) for x in row), *b.position))]
        needed = DIGITS + 10 + _span(data)
        if needed <= dps or not any(isinstance(x, mpmath.mpf) for x in values):
            break
        dps = needed
    before, after = at_before, at_after
    if not all(b.physical for b in before):
        return None  # a body of no mass (or less) there: no impact to check
    contacts = tuple(c.at(point) for c in contacts)
    along = {name: v if len(v) > 1 else v[0] for name, v in along.items()}
    found = residuals(before, after, contacts, pushes, along, rule,
                      tuple(c.name for c in contacts if pushes[c.name] > 0), locked,
                      tuple(j.at(point) for j in joints),
                      {j.name: tuple(sp.sympify(x).xreplace(point)
                                     for x in joint_impulses[j.name]) for j in joints})
    return found if found and found["_approaching"] else None


def friction_residuals(name: str, law: Any, num: Any, p_n: Any, p_t: Sequence[Any],
                       slip_before: Sequence[Any], slip_after: Sequence[Any],
                       exact: bool, speed: Any = None) -> dict[str, Any]:
    """Friction's own law at one pushing contact, from its impulses and slips alone
    (one tangent in the plane, two in space).

    On the cone's edge (``|P_t| = mu P_n``: exactly, or to 1e-9 of it in floating point)
    the contact slid throughout in one direction, and each law promises its own: Coulomb's
    friction aims at no slip after (``CONTACT.against_slip``: ``P_t`` has no part along
    the slip after); Walton's rough law puts the whole friction against the slip before
    (``CONTACT.against_slip_before``: ``P_t`` points straight back along it; where the
    normal couples to the slip, the slip after may pass its target ``-beta`` times the
    slip before, which the law allows); with no slip before, against the slip after,
    which keeps the way the normal impulse drove the points. Inside the cone, Walton's
    contact leaves at its target (``CONTACT.tangential_restitution``) and, in the plane,
    Coulomb's contact ends sticking or with its slip reversed (``CONTACT.slides``: no
    slip after in the direction of the slip before; in space the slip may turn). In
    floating point
    (`speed`, the answer's largest speed or impulse) friction's part along the slip
    after is measured against that speed, so a slip of rounding's size aims nowhere."""
    zero = num(0)
    size = abs(p_t[0]) if len(p_t) == 1 else _root(sum((x * x for x in p_t), zero), exact)
    slack = num(law.cone()) * p_n - size
    edge = slack <= 0 if exact else slack <= num(1e-9) * (abs(slack) + size)
    beta = getattr(law, "beta", None)
    aim = list(slip_after) if beta is None else [
        a + num(beta) * b for a, b in zip(slip_after, slip_before, strict=True)]
    before = list(slip_before)
    reach = abs(before[0]) if len(before) == 1 else _root(sum((b * b for b in before),
                                                              zero), exact)
    if edge and beta is not None and reach > 0:
        # |P_t| |s| + P_t . s is zero only when P_t opposes the slip before s (with no
        # slip before, the law slides against the way the normal impulse drives the
        # points, which the slip after then keeps: checked as Coulomb's, below)
        gap = size * reach + sum((x * b for x, b in zip(p_t, before, strict=True)), zero)
        return {f"{name}.against_slip_before": max(zero, gap) / (
            reach if speed is None else max(speed, reach))}
    if edge:
        along = sum((x * a for x, a in zip(p_t, aim, strict=True)), zero)
        reach = abs(aim[0]) if len(aim) == 1 else _root(sum((a * a for a in aim), zero),
                                                         exact)
        if speed is not None:  # floating point: a slip of rounding's size aims nowhere,
            # so friction's part along it counts in proportion to the answer's speeds
            return {f"{name}.against_slip": max(zero, along) / max(speed, reach)}
        return {f"{name}.against_slip": max(zero, along / reach) if reach > 0 else zero}
    if beta is not None:
        return {f"{name}.tangential_restitution": max((abs(a) for a in aim), default=zero)}
    if len(aim) == 1:
        turned = slip_after[0] * slip_before[0] > 0
        return {f"{name}.slides": abs(slip_after[0]) if turned else zero}
    return {}


def path_residuals(bodies: Mapping[str, Any], contact: Any,
                   path: Sequence[tuple[Any, ...]], num: Any, root: Any,
                   exact: bool, end: tuple[Any, ...]) -> dict[str, Any]:
    """One contact's own impact along its impulse path, from the bodies before and the
    path alone (the bodies' own response to each corner's impulse: a free body's
    ``m dv = P``, ``I dw = r x P``; a pivoted one's turn about its pivot). Each corner
    is ``(P_n, P_t)`` in the plane, ``(P_n, P_t1, P_t2)`` in space.

    - ``CONTACT.path``: each straight piece of a Coulomb contact's path either slides
      (on the cone's edge, ``|dP_t| = mu dP_n``, against a slip of one sign along the
      piece) or sticks (inside the cone, no slip at either end); the normal impulse
      never decreases, and the path ends at the impulse given;
    - ``CONTACT.restitution``: the end by the restitution law's own
      :meth:`~rigidimpact.laws.law.NewtonRestitution.end_residual` (Newton's velocity
      after, Poisson's impulse ratio, the energetic law's work ratio) on the normal
      velocity along the path.
    """
    zero = num(0)
    first, second = contact.bodies if contact.bodies else tuple(bodies)[:2]
    spatial = _spatial(list(bodies.values()))
    dimension = 3 if spatial else 2
    frame = _frame(contact, num, root, spatial)
    point = [num(x) for x in contact.point]

    def slide(name: str, sign: int, push: list[Any]) -> list[Any]:
        """The body's point velocity at the contact after `push` (given to `second`)."""
        body = bodies[name]
        if body.support == "fixed":
            return [zero] * dimension
        m = num(body.mass)
        v = [num(x) for x in body.velocity]
        w = [num(x) for x in _spin(body)]
        centre = [num(x) for x in body.position]
        if body.support == "pivot":
            inertia = num(body.inertia)
            pivot = [num(x) for x in body.pivot]
            arm, c = ([point[k] - pivot[k] for k in range(2)],
                      [centre[k] - pivot[k] for k in range(2)])
            w[0] += sign * _cross(arm, push)[0] / (inertia + m * _dot(c, c))
            return _turn(w, arm)
        r = [point[k] - centre[k] for k in range(dimension)]
        moment = _cross(r, push)
        if spatial:  # I^-1 (r x P), solved in the residuals' arithmetic
            inertia = sp.Matrix(body.inertia)
            inverse = body.inertia_inverse if body.inertia_inverse is not None else \
                inertia.inv()
            w = [w[i] + sign * _dot([num(x) for x in sp.Matrix(inverse).row(i)], moment)
                 for i in range(3)]
        elif num(body.inertia) != 0:
            w[0] += sign * moment[0] / num(body.inertia)
        turn = _turn(w, r)
        return [v[k] + sign * push[k] / m + turn[k] for k in range(dimension)]

    def relative(corner: Sequence[Any]) -> list[Any]:
        push = [sum((p * row[k] for p, row in zip(corner, frame, strict=True)), zero)
                for k in range(dimension)]
        a, b = slide(first, -1, push), slide(second, 1, push)
        d = [y - x for x, y in zip(a, b, strict=True)]
        return [_dot(d, row) for row in frame]

    corners = [[num(x) for x in corner] for corner in path]
    states = [relative(corner) for corner in corners]
    restitution, friction = contact.laws
    out: dict[str, Any] = {}
    worst = max(*(abs(x - num(y)) for x, y in zip(corners[-1], end, strict=True)),
                *(abs(x) for x in corners[0]))
    mu = friction.cone()
    coulomb = mu is not None and getattr(friction, "beta", None) is None and not spatial
    for (p0, t0), (p1, t1), (_, s0), (_, s1) in zip(
            corners, corners[1:], states, states[1:], strict=False) if not spatial else ():
        dn, dt = p1 - p0, t1 - t0
        if len(corners) > 2:  # the normal impulse never falls (a straight path's sign
            worst = max(worst, -dn)  # is CONTACT.pushes, a limit of the model)
        if not coulomb or dn <= 0:
            continue
        edge = abs(dt) - num(mu) * dn
        on_edge = edge >= 0 if exact else edge >= -num(1e-9) * (abs(dt) + dn)
        if on_edge:  # slides: one sign of slip along the piece, friction against it
            mid = (s0 + s1) / 2
            crossed = min(abs(s0), abs(s1)) if s0 * s1 < 0 else zero
            against = abs(mid) if dt * mid > 0 else zero
            worst = max(worst, crossed, against)
        else:  # inside the cone: sticks, no slip at either end
            worst = max(worst, abs(s0), abs(s1))
    out[f"{contact.name}.path"] = worst
    if hasattr(restitution, "end_residual") and states[0][0] < 0:
        out[f"{contact.name}.restitution"] = restitution.end_residual(
            [(corner[0], state[0]) for corner, state in zip(corners, states, strict=True)],
            num, as_sympy)
    return out


def _root(x: Any, exact: bool) -> Any:
    """A square root in the residual's own arithmetic; in rationals, a rational within
    1e-60 where the root is irrational (a cone's size: it decides no comparison a
    rational's root could tie, and only sizes a violation)."""
    if isinstance(x, mpmath.mpf):
        return mpmath.sqrt(x)
    if not exact or isinstance(x, sp.Basic):
        return sp.sqrt(x)
    value = sp.sqrt(QQ.to_sympy(x))
    if not value.is_Rational:
        value = sp.Rational(sp.N(value, 70))
    return QQ(int(value.p), int(value.q))


def as_sympy(value: Any) -> sp.Expr:
    """A residual as a SymPy number (exact Rational, or a 50-digit Float)."""
    if isinstance(value, (mpmath.mpf, float)):
        return sp.Float(value, DIGITS)
    try:
        return QQ.to_sympy(value)
    except (TypeError, AttributeError):
        return sp.sympify(value)


def _scale(bodies, later, impulses, tangential, num, zero, flat=list) -> Any:
    """The size residuals are measured against: the largest speed or spin (before or
    after) or impulse component."""
    sizes = [abs(num(x)) for states in (bodies, later) for name, b in states.items()
             if bodies[name].support != "fixed" for x in (*flat(b.velocity), *_spin(b))]
    sizes += [abs(num(x)) for name, p in impulses.items()
              for x in (p, *_components(tangential.get(name, 0)))]
    return max([zero, *sizes])


def assess(checks: Mapping[str, Any], rule: str,
           contacts: Sequence[Any]) -> tuple[list[str], list[str]]:
    """(warnings, failures): the physical limits the model shows here, and the
    conditions the answer breaks beyond its arithmetic's tolerance (an answer with any
    failure is wrong and must not be given). The tolerance, relative to the largest
    speed or impulse: zero for rationals, 1e-35 for irrational exact answers at 50
    digits, FLOAT_TOLERANCE for floats, or the checks' own ``_tolerance`` (a model that
    computed its residuals itself)."""
    if not checks:
        return [], []
    promised = conduct(rule)
    symbolic = checks.get("_symbolic", False)
    scale = checks["_scale"] or 1
    kinetic = checks["_kinetic"] or 1
    if "_tolerance" in checks:
        tolerance: Any = checks["_tolerance"]
    elif promised.stated_tolerance is not None:  # an integrating rule's own
        tolerance = promised.stated_tolerance
    elif checks["_exact"]:
        tolerance = 0
    elif checks["_floats"]:
        tolerance = FLOAT_TOLERANCE
    else:
        tolerance = ROUNDED_TOLERANCE
    poisson_together = promised.whole_impact and len(contacts) > 1 and any(
        c.laws[0].together == "impulse" for c in contacts)
    # a sticking law (no cone) fixes the normal impulse with the tangential one, and
    # with strong coupling that normal impulse pulls: the law's limit, not the solver's
    sticking = {c.name for c in contacts
                if c.laws[1].unknown_tangential and c.laws[1].cone() is None}
    warnings, failures = [], []
    for key, value in checks.items():
        if key.startswith("_"):
            continue
        size = value / (kinetic if key == "energy" else scale)
        allowed = tolerance
        if key.endswith(".opens"):  # a rule's passes may end below a closing speed
            allowed = max(tolerance, promised.settles)
        if not (size > 0 and (allowed == 0 or float(size) > allowed)):
            continue
        if symbolic and (key == "energy" or key.endswith((".opens", ".pushes"))):
            continue  # a limit at some values of the symbols: evaluate says where
        if key == "energy":
            warnings.append(f"kinetic energy is created: {float(value):.6g} more after "
                            f"than before ({float(size):.3g} of it)")
        elif key.endswith(".opens") and (poisson_together or promised.may_stay_closing):
            name = key.rsplit(".", 1)[0]
            warnings.append(f"{name} still approaches after the impact (normal velocity "
                            f"{-float(value):.6g}): the bodies would pass into each other")
        elif key.endswith(".pushes") and key.rsplit(".", 1)[0] in sticking:
            name = key.rsplit(".", 1)[0]
            warnings.append(f"{name} would pull (normal impulse {-float(value):.6g}): "
                            "sticking cannot be held by a push here; tangential = "
                            "\"coulomb\" follows the slip instead (Routh's method)")
        else:
            failures.append(f"{key} off by {float(size):.3g} (relative)")
    return warnings, failures
