"""Walton's rough law at one contact, with one tangent (the plane) or two (space).

Walton's algebraic law sets the velocities after directly: the touching points leave
with the normal velocity the restitution law asks (``-e v_n`` for Newton's) and with
``-beta`` times their tangential velocity before, if Coulomb's friction (mu; none when
mu is None) can supply the tangential impulse that needs. Otherwise they slip
throughout, the friction at ``mu`` times the normal impulse against the slip, and the
normal ends as the restitution law asks (O. R. Walton, in Particulate Two-Phase Flow,
1993). The law does not follow a slip that stops or turns during the impact.

The contact's relative velocity is ``v = v- + W P`` in its own frame (normal first, then
the tangents), so both courses are one linear solve each; this module is the law's one
implementation, and the planar contact (one tangent) and the 3-D one (two) both call it.

The slip direction is the tangential velocity before; with none, the way the normal
impulse drives the points (W's coupling column), as in Routh's course from rest, so a
mirrored problem gets the mirrored answer. With one tangent and symbols, each sign of
the slip is its own course with its condition.

Examples
--------
A solid sphere of mass 1 on a floor, slipping at 1, e = 1, beta = 1: its tangential
velocity reverses.

>>> W = sp.Matrix([[1, 0], [0, sp.Rational(7, 2)]])
>>> (r,) = walton(W, sp.Matrix([-1, 1]), 1, None, 1)
>>> r.name, r.impulse
('tangential restitution', (2, -4/7))

The same sphere in space, slipping along the first tangent, gets the same impulse:

>>> (r,) = walton(sp.diag(1, sp.Rational(7, 2), sp.Rational(7, 2)), sp.Matrix([-1, 1, 0]),
...               1, None, 1)
>>> r.impulse
(2, -4/7, 0)
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.routh import SLIP, Regime, _simplified
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["walton", "RESTITUTION"]

RESTITUTION = "tangential restitution"


def walton(W: sp.MatrixBase, v_before: sp.MatrixBase, beta: Any, mu: Any | None,
           leaving: Any) -> tuple[Regime, ...]:
    """Every course of Walton's law at one contact, each with its conditions; with
    numbers, the one taken.

    Parameters
    ----------
    W : 2x2 or 3x3 matrix
        The contact's inverse mass in its frame (normal first).
    v_before : vector
        The relative velocity before, in the same frame.
    beta : the tangential restitution, in [-1, 1].
    mu : Coulomb's coefficient, or None for unlimited friction.
    leaving : the normal velocity after the restitution law asks (``-e v_n``).
    """
    W = sp.Matrix(W).applyfunc(sp.cancel)
    v = sp.Matrix(list(v_before)).applyfunc(sp.cancel)
    n = W.rows
    beta, leaving = sp.sympify(beta), sp.sympify(leaving)
    if sp.cancel(W.det()).is_zero:
        raise InputError("contact.tangential_restitution", "the touching points cannot "
                         f"meet {n} velocity conditions here (W is singular: they have "
                         "fewer degrees of freedom)")
    zero = (sp.Integer(0),) * n
    wanted = tuple(tidy(x) for x in W.LUsolve(sp.Matrix(
        [leaving - v[0], *(-(1 + beta) * t for t in v[1:])])))
    if mu is None:
        return (Regime(RESTITUTION, (), wanted, (zero, wanted)),)
    mu = sp.sympify(mu)
    tangential = sp.Abs(wanted[1]) if n == 2 else sp.sqrt(sum(t ** 2 for t in wanted[1:]))
    within = _simplified(sp.Le(tangential, mu * wanted[0]))
    found = [Regime(RESTITUTION, (within,), wanted, (zero, wanted))]
    for side, direction in _slip_directions(W, v):
        slip = sp.Matrix([1, *(-mu * d for d in direction)])
        rate = sp.cancel((W * slip)[0])
        p_n = tidy((leaving - v[0]) / rate)
        end = tuple(tidy(p_n * s) for s in slip)
        conditions = tuple(c for c in map(_simplified, (*side, sp.Not(within),
                                                         sp.Gt(rate, 0)))
                           if c is not sp.true)
        found.append(Regime(SLIP, conditions, end, (zero, end)))
    decided = tuple(r for r in found if r.holds() is not False)
    if not decided:
        raise InputError("contact", "no course of the impact fits these values: the "
                         "contact jams (the normal velocity would fall while slipping)")
    return decided


def _slip_directions(W: sp.Matrix, v: sp.Matrix) -> list[tuple[tuple, tuple]]:
    """The ways the points can slip, each a (conditions, unit tangent) pair: along the
    slip before, or with none, along W's coupling column; none when neither moves them."""
    drive = sp.Matrix(v[1:])
    if all(x.is_zero for x in drive):
        drive = sp.Matrix(W[1:, 0])
    if all(x.is_zero for x in drive):
        return []
    if len(drive) == 1:
        (d,) = drive
        if d.is_positive:
            return [((), (1,))]
        if d.is_negative:
            return [((), (-1,))]
        return [((sp.Gt(s * d, 0),), (s,)) for s in (1, -1)]
    speed = sp.sqrt(sum(x ** 2 for x in drive))
    return [((), tuple(sp.radsimp(x / speed) for x in drive))]

