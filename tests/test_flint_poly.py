"""FLINT's multivariate factorisation and gcds stand in for SymPy's only where they give
SymPy's own answer: held side by side on seeded random polynomials (1 to 4 variables,
repeated factors, signs, constants, zero), as SymPy's low-level results and through
``sympy.factor`` and ``sympy.cancel`` of rational functions."""

from __future__ import annotations

import random

import pytest
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


@pytest.mark.parametrize("count", [150, pytest.param(400, marks=pytest.mark.slow)])
def test_flints_factors_and_gcds_are_sympys_own(count):
    rng = random.Random(46)
    for _ in range(count):
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


@pytest.mark.parametrize("count", [50, pytest.param(150, marks=pytest.mark.slow)])
def test_sympys_factor_and_cancel_are_unchanged_within_the_block(count):
    rng = random.Random(47)
    xs = sp.symbols("a b c d")

    def polynomial():
        return sp.Add(*(rng.randint(-5, 5) * sp.Mul(*(x ** rng.randint(0, 2) for x in xs))
                        for _ in range(rng.randint(1, 4))))

    for _ in range(count):
        expr = sp.Mul(*(polynomial() ** rng.randint(1, 2)
                        for _ in range(rng.randint(1, 3)))) / polynomial()
        own = (sp.factor(expr), sp.cancel(expr))
        with flint_polynomials():
            fast = (sp.factor(expr), sp.cancel(expr))
        assert [str(x) for x in fast] == [str(x) for x in own], expr
    assert sp.polys.factortools.dmp_zz_factor is dmp_zz_factor  # put back after


@pytest.mark.parametrize("count", [100, pytest.param(500, marks=pytest.mark.slow)])
def test_factor_made_in_flint_is_sympys_factor(count):
    # flint_poly.factor makes the one fraction and its factors in FLINT where the
    # expression is a rational function of symbols and of sines and cosines of
    # symbols; SymPy's own factor is the reference, side by side on seeded nested
    # expressions (sums of fractions, powers, negative powers, signs, common factors,
    # names that SymPy sorts specially: x, y, t, e, m, M; pi, one of its variables)
    from rigidimpact.symbolic.flint_poly import _rational_factor, factor

    rng = random.Random(48)
    t = sp.Symbol("t", real=True)
    atoms = [*sp.symbols("x y e m M"), sp.Symbol("theta", real=True), sp.sin(t), sp.cos(t),
             sp.pi]

    def polynomial():
        return sp.Add(*(sp.Rational(rng.randint(-6, 6), rng.randint(1, 3)) * sp.Mul(
            *(rng.choice(atoms) ** rng.randint(0, 2) for _ in range(2)))
                        for _ in range(rng.randint(1, 3))))

    fast = 0
    for _ in range(count):
        expr = polynomial() ** rng.randint(-1, 2) * polynomial() + polynomial() / (
            polynomial() * rng.choice(atoms)) if rng.random() < 0.7 else \
            sp.Mul(polynomial(), polynomial()) / polynomial() ** 2
        if expr.has(sp.zoo, sp.nan):
            continue
        fast += _rational_factor(expr) is not None
        assert factor(expr) == sp.factor(expr), expr
    assert fast > count * 4 // 5
    # out of its reach it is SymPy's own: a radical, a float, a sine of a sum, E
    x = sp.Symbol("x")
    for expr in (sp.E * x + x**2, sp.sqrt(x) + x, 0.5 * x + x**2,
                 sp.sin(x + 1) ** 2 / (x - 1) + 1, sp.Integer(4)):
        assert _rational_factor(expr) is None
        assert factor(expr) == sp.factor(expr)


def test_a_zero_decided_in_flint_is_decided_as_sympy_decides_it():
    # verify's symbolic zero: every sine and cosine as a rational function of
    # tan(angle/2), then the one fraction's numerator; made in FLINT it must say what
    # SymPy's together and expand say, on differences that vanish (an expression less
    # its own rewriting, sin^2 + cos^2 = 1 inside) and on ones that do not
    from rigidimpact.symbolic.compare import _rational_trig, symbolic_zero
    from rigidimpact.symbolic.flint_poly import rational_zero

    rng = random.Random(49)
    t = sp.Symbol("t", real=True)
    x, m, e = sp.symbols("x m e", positive=True)
    atoms = [x, m, e, sp.sin(t), sp.cos(t)]

    def part():
        return sp.Add(*(rng.randint(-4, 4) * sp.Mul(*(rng.choice(atoms) ** rng.randint(0, 2)
                                                      for _ in range(2)))
                        for _ in range(rng.randint(1, 3)))) + rng.randint(1, 3) * x

    seen = {True: 0, False: 0}
    for _ in range(60):
        a, b = part(), part()
        if sp.expand(b) == 0:
            continue
        expr = a / b + (1 - sp.sin(t) ** 2 - sp.cos(t) ** 2) * a
        other = sp.expand(a) / sp.expand(b)
        for difference in (expr - other, expr - other + x / b ** 2):
            rational = _rational_trig(difference)
            own = sp.expand(sp.fraction(sp.together(rational))[0]) == 0
            assert rational_zero(rational) is own and symbolic_zero(difference) is own
            # the same decision with the half-angle forms made as the tree is read
            assert rational_zero(difference, half_angle=True) is own
            seen[own] += 1
    assert seen[True] >= 50 and seen[False] >= 50


@pytest.mark.parametrize("count", [60, pytest.param(150, marks=pytest.mark.slow)])
def test_a_polynomial_multiplied_out_in_flint_is_sympys_expand(count):
    # rewrite's trial of sin^2 = 1 - cos^2 multiplies a factored fraction's parts out in
    # FLINT; SymPy's expand is the reference, the same expression to the last term
    from rigidimpact.symbolic.flint_poly import expand_polynomial

    rng = random.Random(50)
    t = sp.Symbol("t", real=True)
    atoms = [*sp.symbols("x y e m M"), sp.sin(t), sp.cos(t), sp.pi]

    def polynomial():
        return sp.Add(*(sp.Rational(rng.randint(-6, 6), rng.randint(1, 3)) * sp.Mul(
            *(rng.choice(atoms) ** rng.randint(0, 2) for _ in range(2)))
                        for _ in range(rng.randint(1, 3))))

    for _ in range(count):
        expr = sp.Mul(*(polynomial() ** rng.randint(1, 3) for _ in range(rng.randint(1, 3))))
        ours = expand_polynomial(expr)
        assert ours == sp.expand(expr) and str(ours) == str(sp.expand(expr)), expr
    x = sp.Symbol("x")
    for expr in (x / (x + 1), sp.sqrt(x) * (x + 1), 0.5 * (x + 1) ** 2, sp.Integer(3)):
        assert expand_polynomial(expr) == sp.expand(expr)
