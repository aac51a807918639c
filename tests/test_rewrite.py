"""The targeted rewriting of exact results (symbolic/rewrite.py)."""

from __future__ import annotations

import random

import sympy as sp

from rigidimpact.symbolic import rewrite
from rigidimpact.symbolic.flint_poly import flint_polynomials

t = sp.Symbol("theta", real=True)
m, M, e = sp.symbols("m M e", positive=True)


def _tidied_with_cancel(expr):
    """The trig rewrite as it was first written: each fraction multiplied out by
    ``cancel`` before ``cos^2 -> 1 - sin^2`` (and back) is tried. An independent
    statement of the same rule, to hold the faster one against."""
    best = rewrite._positive_lead(sp.factor(expr))
    angles = {f.args[0] for f in best.atoms(sp.sin, sp.cos)}
    for angle in sorted(angles, key=sp.default_sort_key):
        s, c = sp.sin(angle), sp.cos(angle)
        expanded = sp.cancel(best)
        for old, new in ((c, s), (s, c)):
            swapped = rewrite._pythagoras(expanded, old, new)
            if swapped == expanded:
                continue
            candidate = rewrite._positive_lead(sp.factor(swapped))
            if sp.count_ops(candidate) < sp.count_ops(best):
                best, expanded = candidate, sp.cancel(candidate)
    return best


def _polynomial(rng):
    s, c = sp.sin(t), sp.cos(t)
    monomials = [1, s, c, s**2, c**2, s * c, m, M, m * c**2, M * s**2, e * m, c**3, s**3]
    return sum(rng.randint(-3, 3) * rng.choice(monomials) for _ in range(rng.randint(1, 4)))


def test_the_trig_rewrite_gives_what_it_gave_after_cancel():
    # the rewrite multiplies a factored fraction out without seeking a gcd (its factors
    # are coprime already); cos^2 -> 1 - sin^2 maps numerator and denominator alike,
    # so factor's canonical answer is the same: side by side on seeded fractions and on
    # the barbell's and the discs' results, derived afresh
    from rigidimpact.paper import problems

    rng = random.Random(45)
    compared = 0
    exprs = []
    for _ in range(120):
        numerator, denominator = _polynomial(rng), _polynomial(rng)
        if denominator == 0 or numerator == 0:
            continue
        exprs.append(numerator * _polynomial(rng) / (denominator * (1 + m * sp.cos(t)**2)))
    solution = problems.barbell_impact().solve()
    exprs += [v for v in solution.values.values() if v.has(sp.sin, sp.cos)]
    assert len(exprs) > 100
    with flint_polynomials():
        for expr in exprs:
            assert rewrite._tidied(expr) == _tidied_with_cancel(expr), expr
            compared += expr.has(sp.sin, sp.cos)
    assert compared > 90
