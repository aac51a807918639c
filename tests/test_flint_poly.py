"""FLINT's multivariate factorisation and gcds stand in for SymPy's only where they give
SymPy's own answer: held side by side on seeded random polynomials (1 to 4 variables,
repeated factors, signs, constants, zero), as SymPy's low-level results and through
``sympy.factor`` and ``sympy.cancel`` of rational functions."""

from __future__ import annotations

import random

import sympy as sp
from sympy.polys import ZZ
from sympy.polys.densearith import dmp_mul
from sympy.polys.densebasic import dmp_from_dict
from sympy.polys.euclidtools import dmp_zz_heu_gcd
from sympy.polys.factortools import _sort_factors, dmp_zz_factor

from rigidimpact.symbolic.flint_poly import flint_polynomials, zz_factor, zz_gcd


def _dense(rng: random.Random, u: int):
    terms = {tuple(rng.randint(0, 2) for _ in range(u + 1)): ZZ(rng.randint(-6, 6))
             for _ in range(rng.randint(0, 4))}
    return dmp_from_dict({m: c for m, c in terms.items() if c}, u, ZZ)


def test_flints_factors_and_gcds_are_sympys_own():
    rng = random.Random(46)
    for _ in range(400):
        u = rng.randint(1, 3)
        common = _dense(rng, u)
        f = dmp_mul(dmp_mul(_dense(rng, u), common, u, ZZ), common, u, ZZ)
        g = dmp_mul(_dense(rng, u), common, u, ZZ)
        # the same content and factors; their order is SymPy's sort's (its callers
        # sort them, and Wang's algorithm finds them in no fixed order)
        ours, theirs = zz_factor(f, u, ZZ), dmp_zz_factor(f, u, ZZ)
        assert ours[0] == theirs[0] and ours[1] == _sort_factors(theirs[1]), f
        try:
            gcd = dmp_zz_heu_gcd(f, g, u, ZZ)
        except Exception:  # SymPy's heuristic gave up (it then takes another way)
            continue
        assert zz_gcd(f, g, u, ZZ) == gcd, (f, g)


def test_sympys_factor_and_cancel_are_unchanged_within_the_block():
    rng = random.Random(47)
    xs = sp.symbols("a b c d")

    def polynomial():
        return sp.Add(*(rng.randint(-5, 5) * sp.Mul(*(x ** rng.randint(0, 2) for x in xs))
                        for _ in range(rng.randint(1, 4))))

    for _ in range(150):
        expr = sp.Mul(*(polynomial() ** rng.randint(1, 2)
                        for _ in range(rng.randint(1, 3)))) / polynomial()
        own = (sp.factor(expr), sp.cancel(expr))
        with flint_polynomials():
            fast = (sp.factor(expr), sp.cancel(expr))
        assert [str(x) for x in fast] == [str(x) for x in own], expr
    assert sp.polys.factortools.dmp_zz_factor is dmp_zz_factor  # put back after
