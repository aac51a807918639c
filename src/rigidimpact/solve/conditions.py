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
    joint = sp.simplify(sp.And(*kept))
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
