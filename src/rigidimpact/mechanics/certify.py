"""The certificate of a mechanics system's impact: the residuals of the laws at an
answer, computed apart from the path that solved it and from the M and J it solved
with, from the system's own bodies and points (its kinetic energy, with q' from its
kinematic equations, and its contact points' velocities). A closed form (symbols left)
is checked the same way at seeded random rational points of its symbols.

Each function takes the :class:`~rigidimpact.mechanics.impact.SystemImpact` it checks.
"""

from __future__ import annotations

from typing import Any

import mpmath
import sympy as sp
import sympy.physics.mechanics as me

from rigidimpact.errors import InputError
from rigidimpact.model.impulse import kinetic_energy
from rigidimpact.solve.certificate import (
    SYMBOLIC_POINTS,
    coefficient_ranges,
    contact_residuals,
    random_points,
)
from rigidimpact.solve.registry import conduct

__all__ = ["checks", "FLOAT_DIGITS", "CHECK_TOLERANCE", "wide"]

FLOAT_DIGITS = 50  # numbers out of the rationals are solved at this precision
# a residual of the checks beyond this (relative to the largest speed or impulse) is a
# wrong answer: the exact paths give zero, the floating ones about 1e-45
CHECK_TOLERANCE = 1e-30


def wide(x: Any) -> sp.Expr:
    """`x` with every float in it at the solve's precision and more (SymPy rounds a
    product of floats, or the sine of one, to its narrowest operand's digits)."""
    x = sp.sympify(x)
    return x.xreplace({f: sp.Float(f, FLOAT_DIGITS + 10) for f in x.atoms(sp.Float)})


def checks(system: Any, u_after: sp.Matrix, P: sp.Matrix,
            rule: str = "simultaneous", conditions: Any = ()) -> dict[str, Any] | None:
    """The residuals of the laws, apart from the path that solved them and from the
    M and J it solved with: the system's own bodies and points (:func:`_own`) give
    the generalized momentum balance (``dT/du`` after less before, less each contact
    impulse's generalized impulse ``P . dv/du``), each contact's velocity before and
    after in its frame, and the energy. Each contact's laws are the built-in shapes'
    certificate's own (:func:`rigidimpact.solve.certificate.contact_residuals`): no
    pull, no closing after (a sequential run within the rule's own settling line, as
    the built-in shapes'), the cone or smoothness or sticking, friction's direction and
    end, the restitution law's end where the velocities fix it. A system built without
    its bodies is checked with M and J themselves; a closed form (symbols left) at
    seeded random rational points (:func:`_at_points`) where its `conditions` hold
    (a case of the simultaneous rule with symbols is checked where it is the answer)."""
    numbers = [*u_after, *P, *system.u_before, *system.M, *system.J]
    if not all(sp.sympify(x).is_number for x in numbers):
        return _at_points(system, u_after, P, rule, conditions)
    with mpmath.workdps(FLOAT_DIGITS):
        def num(x: Any) -> Any:
            return mpmath.mpf(sp.N(x, FLOAT_DIGITS + 10)._to_mpmath(mpmath.mp.prec))

        p = mpmath.matrix([num(x) for x in P])
        own = _own(system, u_after, P, num)
        if own is None:
            balance, v, v0, kinetic = _by_M_and_J(system, u_after, P, num)
        else:
            balance, v, v0, kinetic = own
        width = len(P) // len(system.contacts)
        scale = max([abs(x) for x in v0] + [abs(x) for x in p] + [mpmath.mpf(1e-300)])
        out: dict[str, Any] = {"momentum": max(abs(x) for x in balance)}
        for i, c in enumerate(system.contacts):
            k = width * i
            # each contact's laws, stated once for every model (the built-in shapes'
            # certificate's own): from its impulse and its relative velocity before
            # and after, in its frame (normal, then its tangents)
            out.update(contact_residuals(
                c.name, c.laws.laws, p[k], [p[k + j] for j in range(1, width)],
                [v0[k + j] for j in range(width)], [v[k + j] for j in range(width)], num,
                exact=False, speed=scale, acted=p[k] > 0,
                whole_impact=len(system.contacts) == 1 or conduct(rule).whole_impact,
                rule=rule, alone=len(system.contacts) == 1))
        out["energy"] = max(0, kinetic[1] - kinetic[0])
        out["_scale"] = scale
        out["_kinetic"] = kinetic[0]
        out["_tolerance"] = CHECK_TOLERANCE
    return out

def _at_points(system: Any, u_after: sp.Matrix, P: sp.Matrix, rule: str,
               conditions: Any = ()) -> dict[str, Any] | None:
    """The residuals of a closed form (symbols left), at seeded random rational
    points of its symbols and coordinates where the impact happens: each constant
    within its assumptions (a restitution coefficient in [0, 1], a friction
    coefficient in [0, 2]), each coordinate and speed in [-3/2, 3/2]; the worst of
    each residual over :data:`SYMBOLIC_POINTS` points where the answer's own
    `conditions` hold (a case's: its acting set, its signs), relative to that point's
    scale (the energy to its kinetic energy). The system's own kinematics check
    each point (:func:`_own`), apart from the M and J the closed form came from.
    None where no point drawn (:func:`~rigidimpact.solve.certificate.random_points`)
    is an impact."""
    laws = sp.Tuple(*(x for c in system.contacts for x in (
        c.laws.restitution, c.laws.friction or 0, c.laws.tangential_restitution or 0)))
    data = sp.Tuple(*system.M, *system.J, *system.u_before, *u_after, *P, laws)
    constants = set(data.free_symbols - {me.dynamicsymbols._t})
    functions = {*system.q, *system.u} & data.atoms(sp.Function)
    # the certificate's one draw: each coefficient within its range, each coordinate
    # and speed in [-3/2, 3/2], every other symbol of its sign
    ranges = {**coefficient_ranges([c.laws for c in system.contacts]),
              **{f: (-sp.Rational(3, 2), sp.Rational(3, 2)) for f in functions}}
    worst: dict[str, Any] = {}
    checked = 0
    for point in random_points(constants | functions, ranges):
        if checked == SYMBOLIC_POINTS:
            break
        if not all(sp.sympify(c).xreplace(point) is sp.true for c in conditions):
            continue  # outside the case: another case is the answer here
        try:
            # a speed's value before: its draw, or the expression given for it (its
            # symbols drawn too)
            here = system.at({k: v for k, v in point.items() if k not in system.u} |
                           {u: point.get(u, sp.sympify(b).xreplace(point)) for u, b in
                            zip(system.u, system.u_before, strict=True)})
            normals = here.J * here.u_before
            if not any(normals[2 * i] < 0 for i in range(len(system.contacts))):
                continue  # no impact at this point
            found = checks(here, u_after.xreplace(point), P.xreplace(point), rule)
        except (InputError, ZeroDivisionError, TypeError, ValueError):
            continue
        if found is None:
            continue
        checked += 1
        for key, value in found.items():
            if key.startswith("_"):
                continue
            size = value / (found["_kinetic"] if key == "energy" else found["_scale"])
            worst[key] = max(worst.get(key, 0), size)
    if not checked:
        return None
    return {**worst, "_scale": 1, "_kinetic": 1, "_tolerance": CHECK_TOLERANCE,
            "_points": checked}

def _by_M_and_J(system: Any, u_after: sp.Matrix, P: sp.Matrix, num: Any) -> tuple:
    """The balance, the contact velocities after and before and the kinetic energies
    from the M and J the solve used (a system given without its bodies)."""
    M = mpmath.matrix([[num(x) for x in system.M.row(i)] for i in range(system.M.rows)])
    J = system.J if len(P) == system.J.rows else system.J_plane
    J = mpmath.matrix([[num(x) for x in J.row(i)] for i in range(J.rows)])
    after = mpmath.matrix([num(x) for x in u_after])
    before = mpmath.matrix([num(x) for x in system.u_before])
    balance = M * (after - before) - J.T * mpmath.matrix([num(x) for x in P])
    kinetic = [kinetic_energy(M, x) for x in (before, after)]
    return balance, J * after, J * before, kinetic

def _own(system: Any, u_after: sp.Matrix, P: sp.Matrix, num: Any) -> tuple | None:
    """The system's own view of an answer, from its bodies and points alone: the
    generalized momentum balance along the independent speeds, each contact's
    velocity after and before in its own frame (normal, then tangents), and the
    kinetic energy before and after. None for a system given without bodies."""
    if not system.bodies:
        return None
    speeds = list(system.fold[0] if system.fold is not None else system.u)
    kinematics, values = dict(system.kinematics), dict(system.values)

    values = {k: wide(v) for k, v in values.items()}

    def ready(x: Any) -> sp.Expr:  # q' as the speeds give it, then the numbers
        x = sp.sympify(x)
        if kinematics:
            x = x.subs(kinematics)
        return wide(x).xreplace(values)

    def at(x: sp.Expr, state: sp.Matrix) -> Any:
        return num(x.xreplace({s: wide(v) for s, v in zip(speeds, state, strict=True)}))

    states = [system._all(sp.Matrix(system.u_before)), system._all(sp.Matrix(u_after))]
    energy = ready(sum((b.kinetic_energy(system.frame) for b in system.bodies),
                       sp.Integer(0)))
    momentum = [energy.diff(s) for s in speeds]
    width = len(P) // len(system.contacts)
    generalized = [mpmath.mpf(0)] * len(speeds)
    seen: list[list[Any]] = [[], []]
    for i, c in enumerate(system.contacts):
        velocity = c.point.vel(system.frame)
        if c.other is not None:
            velocity = velocity - c.other.vel(system.frame)
        axes = system._plane(c) if width == 3 else system._unit(c)
        push = sum((P[width * i + j] * axes[j] for j in range(width)), me.Vector(0))
        for j, s in enumerate(speeds):
            generalized[j] += num(ready(push.dot(velocity.diff(s, system.frame))))
        for k, state in enumerate(states):
            seen[k] += [at(ready(velocity.dot(axis)), state) for axis in axes]
    change = [at(x, states[1]) - at(x, states[0]) - g
              for x, g in zip(momentum, generalized, strict=True)]
    # along the independent speeds' partial velocities (the velocity constraints'
    # reactions do no work there)
    fold = sp.eye(len(speeds)) if system.fold is None else system.fold[1]
    balance = [sum((num(fold[j, r]) * change[j] for j in range(len(speeds))),
                   mpmath.mpf(0)) for r in range(fold.cols)]
    kinetic = [at(energy, state) for state in states]
    return balance, seen[1], seen[0], kinetic
