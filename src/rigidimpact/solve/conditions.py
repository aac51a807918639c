"""When a case holds: the signs of its relations, its conditions simplified, exact
solutions of small linear systems, tidy forms, and sample points for symbols.

Shared by the rules (:mod:`rigidimpact.solve.rules`) and the impulse problem
(:mod:`rigidimpact.solve.problem`).
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from typing import Any

import sympy as sp

from rigidimpact.symbolic.rewrite import tidy

FLIPPED = {sp.GreaterThan: sp.LessThan, sp.LessThan: sp.GreaterThan,
           sp.StrictGreaterThan: sp.StrictLessThan, sp.StrictLessThan: sp.StrictGreaterThan}


def sign_of(relation: sp.Basic) -> sp.Basic:
    """``expr OP 0`` with every factor of known sign taken out (a positive mass, 1 + e),
    so what is left is the condition itself.

    Examples
    --------
    >>> m, v = sp.Symbol("m", positive=True), sp.Symbol("v", real=True)
    >>> sign_of(sp.Ge(-3 * m * v / (m + 1), 0))
    v <= 0
    """
    if relation in (sp.true, sp.false):
        return relation
    if isinstance(relation, (sp.And, sp.Or)):  # a regime's compound condition
        return type(relation)(*(sign_of(r) for r in relation.args))
    if isinstance(relation, sp.Not):
        return sp.Not(sign_of(relation.args[0]))
    if not isinstance(relation, sp.core.relational.Relational):
        return relation
    op = type(relation)
    expr = sp.factor(relation.lhs - relation.rhs)
    numerator, denominator = sp.fraction(expr)
    kept = []
    for factor in sp.Mul.make_args(numerator) + sp.Mul.make_args(denominator):
        if factor.is_positive:
            continue
        if factor.is_negative:
            op = FLIPPED[op]
            continue
        kept.append(factor)
    return op(sp.Mul(*kept), 0)


def case_conditions(relations: Sequence[sp.Basic]) -> tuple[sp.Basic, ...]:
    """Relations with the ones that always hold dropped: ``(True,)`` when none is left,
    ``(False,)`` when they cannot all hold, or hold only on a boundary (an equality,
    where the neighbouring case gives the same numbers)."""
    kept = []
    for relation in relations:
        relation = sign_of(relation)
        if relation == sp.false:
            return (sp.false,)
        if relation != sp.true and relation not in kept:
            kept.append(relation)
    if not kept:
        return (sp.true,)
    region = _on_a_line(kept)
    if region is not None:
        return region
    if any(not (a.lhs - a.rhs).is_rational_function(*a.free_symbols)
           for r in kept for a in r.atoms(sp.core.relational.Relational)):
        # roots of the symbols (the energetic law's courses): SymPy's simplification of
        # their conjunction ran for minutes; each condition is given as it is
        return tuple(kept)
    try:
        joint = sp.simplify(sp.And(*kept))
    except (TypeError, ValueError, NotImplementedError):  # SymPy's simplification gave
        return tuple(kept)  # up (a NaN compared at a radical's branch): kept as they are
    if joint == sp.false or isinstance(joint, sp.Eq) or (
            isinstance(joint, sp.And) and any(isinstance(a, sp.Eq) for a in joint.args)):
        return (sp.false,)
    return tuple(joint.args) if isinstance(joint, sp.And) else (joint,)


def exact_solve(matrix: sp.Matrix, rhs: sp.Matrix) -> sp.Matrix | None:
    """The unique solution of a square linear system of numbers, or None when it is
    singular. The numbers are taken into their own field (the rationals with sqrt(2)
    adjoined, say), where elimination is exact and fast; SymPy's general expressions
    would be factored at every step.

    Examples
    --------
    >>> exact_solve(sp.Matrix([[1, sp.sqrt(2)], [0, 2]]), sp.Matrix([1, 2])).T
    Matrix([[1 - sqrt(2), 1]])
    """
    augmented = sp.Matrix.hstack(matrix, rhs).to_DM(extension=True)
    reduced, pivots = augmented.rref()
    size = matrix.shape[1]
    if tuple(pivots) != tuple(range(size)):
        return None
    return reduced.to_Matrix()[:, size]


def tidied(x: Any) -> sp.Expr:
    """`tidy`, with a number left as it is (most of them, at scale)."""
    x = sp.sympify(x)
    return x if x.is_Number else tidy(x)


def sample_points(symbols: set[sp.Symbol]) -> list[dict[sp.Symbol, sp.Expr]]:
    """Points at which to test an identity in `symbols`: none needed (one empty point)
    without symbols, else two seeded random rational points that respect each symbol's
    sign assumptions."""
    if not symbols:
        return [{}]
    rng = random.Random(32)
    points = []
    for _ in range(2):
        point = {}
        for s in sorted(symbols, key=str):
            x = sp.Rational(rng.randint(101, 997), 311)
            point[s] = -x if s.is_negative else x
        points.append(point)
    return points


def _on_a_line(relations: Sequence[sp.Basic]) -> tuple[sp.Basic, ...] | None:
    """Relations in one real symbol as the set of its values where all hold, found
    exactly (each relation's real roots isolated by SymPy's univariate solver, the sets
    intersected) within what the symbol's assumptions allow: ``(False,)`` where it is
    empty, ``(True,)`` where it is all the symbol may be, else its bounds (none that the
    assumptions give already). None where the relations hold several symbols or roots
    of it, the solver cannot decide them, or they hold at single points only: a blanket
    simplification of their conjunction took tens of seconds for three contacts'
    courses in one symbol.

    Examples
    --------
    >>> mu = sp.Symbol("mu", positive=True)
    >>> _on_a_line([sp.Le(3 * mu - 2, 0), sp.Gt(mu, sp.Rational(1, 2))])
    (mu <= 2/3, mu > 1/2)
    >>> _on_a_line([sp.Le(mu, 1), sp.Gt(mu, 2)])
    (False,)
    """
    from sympy.solvers.inequalities import solve_univariate_inequality

    names = set().union(*(r.free_symbols for r in relations))
    if len(names) != 1:
        return None
    (x,) = names
    atoms = set().union(*(r.atoms(sp.core.relational.Relational) for r in relations))
    if not x.is_real or not all((r.lhs - r.rhs).is_rational_function(x) for r in atoms):
        return None  # roots of x (the energetic law's courses)
    allowed = sp.Interval.open(0, sp.oo) if x.is_positive else \
        sp.Interval(0, sp.oo) if x.is_nonnegative else sp.Reals

    def where(condition: sp.Basic) -> sp.Set:
        if isinstance(condition, sp.And):
            return sp.Intersection(*(where(a) for a in condition.args))
        if isinstance(condition, sp.Or):
            return sp.Union(*(where(a) for a in condition.args))
        if isinstance(condition, sp.Not):
            return allowed - where(condition.args[0])
        return solve_univariate_inequality(condition, x, relational=False, domain=allowed)

    try:
        region = sp.Intersection(allowed, *(where(r) for r in relations))
    except (NotImplementedError, ValueError, TypeError, AttributeError):
        return None
    if region.is_empty:
        return (sp.false,)
    if isinstance(region, sp.FiniteSet) or region.measure == 0:
        return None  # single points: a boundary between courses, or the one value where
        # a case holds (e = 1): told apart as before
    if region == allowed:
        return (sp.true,)
    pieces = region.args if isinstance(region, sp.Union) else (region,)
    if not all(isinstance(p, sp.Interval) for p in pieces):
        return None
    bounds = [_bounds(p, x, allowed) for p in pieces]
    if len(bounds) == 1:
        return tuple(sp.And(*bounds[0]).args) if len(bounds[0]) > 1 else bounds[0]
    return (sp.Or(*(sp.And(*b) for b in bounds)),)


def _bounds(piece: sp.Interval, x: sp.Symbol, allowed: sp.Set) -> tuple[sp.Basic, ...]:
    """An interval of `x` as its bounds, leaving out an end that `allowed` has too."""
    low_given = isinstance(allowed, sp.Interval) and piece.start == allowed.start and \
        piece.left_open == allowed.left_open
    out = []
    if piece.start.is_finite and not low_given:
        out.append(sp.Gt(x, piece.start) if piece.left_open else sp.Ge(x, piece.start))
    if piece.end.is_finite:
        out.append(sp.Lt(x, piece.end) if piece.right_open else sp.Le(x, piece.end))
    return tuple(out)
