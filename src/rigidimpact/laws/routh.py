"""Coulomb friction at one contact, exactly: Routh's method in impulse space.

During an impact the contact's relative velocity is linear in the impulse,
``v(p) = v- + W p`` (see :mod:`rigidimpact.model.impulse`), so taking the normal impulse p_n
as the clock, the velocity is piecewise linear in it: while the touching points slip in
direction s (the sign of the tangential velocity) the tangential impulse grows at
``-mu s`` per unit normal impulse; when they stick it grows at ``-W_tn / W_tt``, which
keeps the tangential velocity at zero, and that is possible only if
``|W_tn| <= mu W_tt``; otherwise slip restarts the other way (slip reversal). Slip can
stop at most once, so the path has at most two straight pieces, and every event (slip
stops, compression ends, the impact ends) is found in closed form (E. J. Routh,
Dynamics of a System of Rigid Bodies, 1905; W. J. Stronge, Impact Mechanics, 2000).

The impact ends by the restitution law:

- ``newton`` (kinematic): when the normal velocity reaches ``-e`` times its value
  before; with slip reversal it can create energy (the Kane-Levinson paradox);
- ``poisson`` (kinetic): when the normal impulse reaches ``1 + e`` times its value at
  the end of compression;
- ``energetic`` (Stronge's): when the work of the normal impulse during restitution
  reaches ``e^2`` times minus its work during compression.

Without a change of slip the three agree. Each possible course of the impact is a
:class:`Regime` with the conditions under which it happens, in closed form.

Examples
--------
>>> from rigidimpact.laws.law import NewtonRestitution
>>> W = sp.Matrix([[2, 0], [0, 2]])   # a particle of mass 1/2 on a fixed floor
>>> (regime,) = regimes(W, sp.Matrix([-1, 1]), sp.Rational(1, 4), NewtonRestitution(1))
>>> regime.name, regime.impulse
('slip', (1, -1/4))
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model.impulse import TouchingPair
from rigidimpact.symbolic.flint_poly import rational_zero
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Regime", "regimes", "singular", "diagram", "Diagram", "LAWS", "SLIP", "STICK",
           "REVERSAL"]

LAWS = ("newton", "poisson", "energetic")
SLIP, STICK, REVERSAL = "slip", "slip-stick", "slip-reversal"


@dataclass(frozen=True)
class Regime:
    """One course of a frictional impact and the conditions under which it happens.

    Parameters
    ----------
    name : str
        ``slip`` (slip throughout), ``slip-stick`` (slip stops, then the points stick),
        ``slip-reversal`` (slip stops, then restarts the other way), ``stick`` (no slip
        from the start), with ``", in compression"`` or ``", in restitution"`` where the
        law makes it matter.
    conditions : tuple of relationals
        All hold exactly when this course is the one taken.
    impulse : (P_n, P_t)
        The total impulse the first body gives the second, contact frame.
    path : tuple of (P_n, P_t)
        The impulse at each event, from (0, 0) to the end: Routh's diagram.
    """

    name: str
    conditions: tuple[sp.Basic, ...]
    impulse: tuple[sp.Expr, sp.Expr]
    path: tuple[tuple[sp.Expr, sp.Expr], ...]

    def holds(self, values: dict | None = None) -> bool | None:
        """True, False, or None when the conditions cannot be decided.

        Examples
        --------
        >>> Regime("slip", (sp.Symbol("x") > 0,), (0, 0), ()).holds({sp.Symbol("x"): 2})
        True
        """
        verdict: bool | None = True
        for condition in self.conditions:
            value = condition.subs(values) if values else condition
            if value is sp.false or value is False:
                return False
            if value is not sp.true and value is not True:
                verdict = None
        return verdict


@dataclass(frozen=True)
class _Piece:
    """A straight piece of the path: from normal impulse `start`, the tangential impulse
    grows at `slope` per unit normal impulse and the velocity at `rate` (a 2-vector)."""

    start: sp.Expr
    slope: sp.Expr
    rate: sp.Matrix


def regimes(W: sp.MatrixBase, v_before: sp.MatrixBase, mu: sp.Expr,
            law: Any) -> tuple[Regime, ...]:
    """Every course a frictional impact can take, each with its conditions.

    Parameters
    ----------
    W : 2x2 matrix
        The contact's inverse effective mass in (normal, tangent) coordinates.
    v_before : 2-vector
        Relative velocity of the touching points before (second minus first); its normal
        component is negative (the bodies approach).
    mu : expr
        Coulomb's friction coefficient.
    law : restitution law object (:mod:`rigidimpact.laws.law`)
        Its coefficient ``e``; ``splits_on_compression``, whether the end of a bent
        impulse path depends on slip stopping in compression or in restitution; and
        ``end_of_bent_path(first, second, v_n, in_restitution)``, that end.

    Returns
    -------
    tuple of Regime
        With numbers, only the one that happens.

    Examples
    --------
    >>> from rigidimpact.laws.law import PoissonRestitution
    >>> W = sp.Matrix([[2, 1], [1, 2]])
    >>> [r.name for r in regimes(W, sp.Matrix([-1, 1]), 2, PoissonRestitution(1))]
    ['slip-stick, in compression']
    """
    W = sp.Matrix(W).applyfunc(sp.cancel)
    v_n, v_t = (sp.cancel(c) for c in v_before)
    mu = sp.sympify(mu)
    # the normal velocity the law asks after a straight path (its one face): -e v_n for
    # Newton's, and for Poisson's and the energetic law, which agree with it there
    target = sp.cancel(law.leaving(v_n))
    if singular(W):
        return _one_freedom(W, v_n, v_t, mu, target, law)
    if v_t.is_zero:
        return _from_rest(W, v_n, mu, target, law)
    signs = [1] if v_t.is_positive else [-1] if v_t.is_negative else [1, -1]
    found: list[Regime | None] = []
    for s in signs:
        side = () if len(signs) == 1 else (sp.Gt(s * v_t, 0),)
        found += _slipping(W, v_n, v_t, mu, target, law, s, side)
    decided = [r for r in found if r is not None and r.holds() is not False]
    if not decided:
        raise InputError("contact", "no course of the impact fits these values: the "
                         "contact jams (the normal velocity would fall while slipping)")
    return tuple(decided)


def singular(W: sp.Matrix) -> bool:
    """Whether W is singular: exactly, or, in floating point (a system solved at 50
    digits), to within the rounding of its entries (a determinant below 1e-35 of the
    product of its diagonal, which is where a rank-one W's lands)."""
    # a 2 x 2 W's determinant by its formula; its zero decided in FLINT where the
    # entries are rational functions of symbols (and of sines and cosines of them)
    det = W[0, 0] * W[1, 1] - W[0, 1] * W[1, 0] if W.shape == (2, 2) else W.det()
    zero = None if W.has(sp.Float) else rational_zero(det)
    if zero is not None:
        return zero
    det = sp.cancel(det)
    if det.is_zero:
        return True
    if W.has(sp.Float) and det.is_number and (W[0, 0] * W[1, 1]).is_number:
        return bool(abs(det) <= sp.Float(1e-35) * abs(W[0, 0] * W[1, 1]))
    return False


def _one_freedom(W, v_n, v_t, mu, target, law) -> tuple[Regime, ...]:
    """Friction where the touching points have one degree of freedom (W singular: a body
    that can only turn, against a fixed one). Their velocity keeps one direction, so the
    normal velocity and the slip vanish together: slip runs throughout compression, then
    either reverses with the normal velocity (the restitution impulse along the other
    edge of the friction cone still separates the points) or the contact locks at rest
    (that edge would drive them together: the impact ends with compression).

    Examples
    --------
    A pendulum's bob on a rod of length 1 from a hinge at (-1/2, sqrt(3)/2) meets a floor
    (normal (0, -1) in scene terms; here the contact frame): W = a a^T / I with
    a = (1/2, sqrt(3)/2), I = 1.

    >>> from rigidimpact.laws.law import NewtonRestitution
    >>> a = sp.Matrix([sp.Rational(1, 2), sp.sqrt(3) / 2])
    >>> (r,) = regimes(a * a.T, -a, sp.Rational(1, 10), NewtonRestitution(1))
    >>> r.name
    'slip-reversal'
    """
    if sp.cancel(W[0, 0]).is_zero:
        raise InputError("contact", "the touching points cannot move along the normal "
                         "here: no impulse can change their approach")
    if v_t.is_zero:
        raise InputError("contact.friction", "the touching points can only move straight "
                         "across the contact here (a body that can only turn, against a "
                         "fixed one), so friction does no work and its impulse is not fixed "
                         "by the laws: the motion after is the smooth contact's; state "
                         "tangential = \"smooth\" for it")
    signs = [1] if v_t.is_positive else [-1] if v_t.is_negative else [1, -1]
    found: list[Regime] = []
    for s in signs:
        side = () if len(signs) == 1 else (sp.Gt(s * v_t, 0),)
        compression = _Piece(sp.Integer(0), -mu * s, _rates(W, -mu * s))
        p_c = sp.cancel(-v_n / compression.rate[0])  # the normal velocity and slip stop
        restitution = _Piece(p_c, mu * s, _rates(W, mu * s))
        separates = sp.Gt(restitution.rate[0], 0)
        reversal = _finish((compression, restitution), v_n, target, law, REVERSAL,
                           (*side, separates))
        locked = tuple(c for c in map(_simplified, (*side, sp.Not(separates)))
                       if c is not sp.true)
        end = (_tidy_number(p_c), _tidy_number(-mu * s * p_c))
        found += [r for r in (reversal, Regime("slip-lock", locked, end,
                                                ((sp.Integer(0), sp.Integer(0)), end)))
                  if r is not None and r.holds() is not False]
    return tuple(found)


def _rates(W: sp.Matrix, slope: sp.Expr) -> sp.Matrix:
    return (W * sp.Matrix([1, slope])).applyfunc(sp.cancel)


def _from_rest(W, v_n, mu, target, law) -> tuple[Regime, ...]:
    """No slip before: the points stick throughout if friction can hold them, otherwise
    they start to slip the way the impulse drives them."""
    stick_slope = sp.cancel(-W[1, 0] / W[1, 1])
    holds = sp.Le(sp.Abs(W[1, 0]), mu * W[1, 1])
    found = [_finish((_Piece(sp.Integer(0), stick_slope, _rates(W, stick_slope)),), v_n,
                     target, law, "stick", (holds,))]
    for s in (1, -1):  # it slips toward sign(W_tn)
        slope = -mu * s
        found.append(_finish((_Piece(sp.Integer(0), slope, _rates(W, slope)),), v_n, target,
                             law, SLIP, (sp.Not(holds), sp.Gt(s * W[1, 0], 0))))
    return tuple(r for r in found if r is not None and r.holds() is not False)


def _slipping(W, v_n, v_t, mu, target, law, s, side) -> list[Regime | None]:
    """The courses that start slipping in direction s.

    Where slip stops is told by the normal velocity then, ``v_n(p*)``: below zero, in
    compression; between zero and the end of a straight impact (``-e v_n-``), in
    restitution; beyond it, the impact has ended first. While slipping the normal
    velocity may even fall (strong friction pulling the points together); the impact
    then goes on until slip stops.
    """
    slope = -mu * s
    rate = _rates(W, slope)
    first = _Piece(sp.Integer(0), slope, rate)
    stops = sp.Lt(s * rate[1], 0)  # the tangential velocity runs down to zero
    if stops is sp.false:  # it never does (no friction, nothing coupling it): one piece
        return [_finish((first,), v_n, target, law, SLIP, (*side, sp.Gt(rate[0], 0)))]
    p_star = sp.cancel(-v_t / rate[1])
    at_stop = sp.cancel(v_n + rate[0] * p_star)
    ended = sp.Ge(at_stop, target)  # a straight impact would have ended by then
    found: list[Regime | None] = [_finish((first,), v_n, target, law, SLIP,
                     (*side, sp.Gt(rate[0], 0), sp.Or(sp.Not(stops), ended)))]
    stick_slope = sp.cancel(-W[1, 0] / W[1, 1])
    can_stick = sp.Le(sp.Abs(W[1, 0]), mu * W[1, 1])
    for name, second_slope, condition in ((STICK, stick_slope, can_stick),
                                          (REVERSAL, mu * s, sp.Not(can_stick))):
        second = _Piece(p_star, second_slope, _rates(W, second_slope))
        rising = () if name == STICK else (sp.Gt(second.rate[0], 0),)
        common = (*side, stops, condition, *rising, sp.Not(ended))
        if not law.splits_on_compression:  # the end does not depend on where
            # compression ends (Newton's law)
            found.append(_finish((first, second), v_n, target, law, name, common))
            continue
        found.append(_finish((first, second), v_n, target, law, f"{name}, in compression",
                             (*common, sp.Lt(at_stop, 0))))
        found.append(_finish((first, second), v_n, target, law, f"{name}, in restitution",
                             (*common, sp.Ge(at_stop, 0))))
    return found


def _finish(pieces: tuple[_Piece, ...], v_n, target, law, name,
            conditions) -> Regime | None:
    """Follow the path to the end the law sets, in the regime's own ordering of events:
    with two pieces, slip stops inside the impact (and, by the name, in compression or
    in restitution)."""
    conditions = tuple(c for c in map(_simplified, conditions) if c is not sp.true)
    if sp.false in conditions:  # this course cannot happen: its path is never built
        return None
    if len(pieces) == 1:
        piece = pieces[0]
        p_f = (target - v_n) / piece.rate[0]  # one straight piece: the three laws agree
        ends = [p_f]
    else:
        first, second = pieces
        p_f = law.end_of_bent_path(first, second, v_n, name.endswith("restitution"))
        ends = [second.start, p_f]
    ends = [_tidy_number(p) for p in ends]
    path = [(sp.Integer(0), sp.Integer(0))]
    tangential = sp.Integer(0)
    for piece, end in zip(pieces, ends, strict=True):
        tangential += piece.slope * (end - piece.start)
        path.append((end, _tidy_number(tangential)))
    return Regime(name, conditions, path[-1], tuple(path))


def _tidy_number(expr: sp.Expr) -> sp.Expr:
    """`tidy` for formulas; a floating-point number is left as SymPy evaluated it
    (factoring one is slow and shows nothing)."""
    expr = sp.sympify(expr)
    if expr.is_number and expr.has(sp.Float):
        return expr
    return tidy(expr)


def newton_end(first: _Piece, second: _Piece, v_n: sp.Expr, target: sp.Expr) -> sp.Expr:
    """A kinematic law on a bent path (Newton's, or a user's): where the normal velocity
    reaches the law's `target` (Newton's ``-e v_n``)."""
    at_stop = v_n + first.rate[0] * second.start  # the normal velocity when slip stops
    return second.start + (target - at_stop) / second.rate[0]


def poisson_end(first: _Piece, second: _Piece, v_n: sp.Expr, e: sp.Expr,
                stop_in_restitution: bool) -> sp.Expr:
    """Poisson's law on a bent path: 1 + e times the normal impulse at the end of
    compression (in the first piece if slip stopped in restitution, else the second)."""
    at_stop = v_n + first.rate[0] * second.start
    p_c = (-v_n / first.rate[0] if stop_in_restitution
           else second.start - at_stop / second.rate[0])
    return (1 + e) * p_c


def energetic_end(first: _Piece, second: _Piece, v_n, e, stop_in_restitution) -> sp.Expr:
    """Where the restitution work reaches e^2 times minus the compression work."""
    p_star = second.start
    a, b = first.rate[0], second.rate[0]
    at_stop = v_n + a * p_star
    if stop_in_restitution:  # compression within the first piece
        compression = -v_n**2 / (2 * a)
        p_c = -v_n / a
        done = a * (p_star - p_c) ** 2 / 2  # restitution work before slip stops
        rest = -e**2 * compression - done
        return p_star + (-at_stop + sp.sqrt(at_stop**2 + 2 * b * rest)) / b
    compression = v_n * p_star + a * p_star**2 / 2 - at_stop**2 / (2 * b)
    p_c = p_star - at_stop / b
    return p_c + sp.sqrt(-2 * e**2 * compression / b)


def _simplified(condition: sp.Basic) -> sp.Basic:
    """A condition with each side over one denominator (numbers decide at once)."""
    if isinstance(condition, sp.core.relational.Relational):
        return type(condition)(sp.cancel(condition.lhs - condition.rhs), 0)
    if isinstance(condition, (sp.Or, sp.And, sp.Not)):
        return type(condition)(*(_simplified(c) for c in condition.args))
    return condition


@dataclass(frozen=True)
class Diagram:
    """What Routh's diagram of one frictional impact shows, as exact numbers.

    Attributes: the contact-space matrix ``W``, the velocity before, ``mu``, ``e``, the
    restitution ``law`` and the regime taken (with its impulse path).
    """

    W: sp.Matrix
    v_before: sp.Matrix
    mu: sp.Expr
    e: sp.Expr
    law: str
    regime: Regime


def diagram(impact, values: dict) -> Diagram:
    """Routh's diagram of a frictional impact at numbers for its symbols.

    Parameters
    ----------
    impact : Impact
        With a ``coulomb`` contact.
    values : mapping of Symbol to number
        Exact numbers for every symbol of the impact.

    Examples
    --------
    >>> from rigidimpact.model.bodies import Body
    >>> from rigidimpact.laws.contact import Contact
    >>> from rigidimpact.solve.impact import Impact
    >>> ball = Body.particle(1, (1, 1), "ball")
    >>> d = diagram(Impact(ball, Body.fixed("floor"), Contact(restitution=1,
    ...             tangential="coulomb", friction=sp.Rational(1, 4))), {})
    >>> d.regime.name, d.regime.path[-1]
    ('slip', (2, 1/2))
    """

    contact = impact.contact
    if contact.laws[1].coulomb() is None:
        raise InputError("contact.tangential", "Routh's diagram is drawn for a Coulomb "
                         "contact (tangential = \"coulomb\")")
    core = TouchingPair(impact.before)

    numbers = {k: sp.sympify(v) for k, v in values.items()}

    def at(x):
        return sp.sympify(x).xreplace(impact.stand_ins).xreplace(numbers)

    W = core.W.applyfunc(at)
    v = core.velocity_before.applyfunc(at)
    mu, e = at(contact.friction), at(contact.restitution)
    leftover = set().union(W.free_symbols, v.free_symbols, mu.free_symbols, e.free_symbols)
    if leftover:
        names = ", ".join(sorted(str(s) for s in leftover))
        raise InputError("values", f"Routh's diagram needs numbers for {names}")
    restitution = replace(contact.laws[0], e=e)
    (regime,) = regimes(W, v, mu, restitution)
    return Diagram(W, v, mu, e, restitution.name, regime)
