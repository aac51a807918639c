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


class _Failing:
    """Stands in for FLINT's polynomial contexts: every step raises, as fmpz_mpoly's
    factor did with OverflowError in its sort key on large coefficients."""

    @staticmethod
    def get(*_args, **_kwargs):
        raise OverflowError("value too large to convert to int")


def test_every_flint_step_falls_back_to_sympys_own(monkeypatch):
    from rigidimpact.symbolic import flint_poly

    monkeypatch.setattr(flint_poly, "fmpz_mpoly_ctx", _Failing)
    monkeypatch.setattr(flint_poly, "fmpq_mpoly_ctx", _Failing)
    x, y = sp.symbols("x y")
    t = sp.Symbol("t", real=True)
    expr = (x**2 - y**2) / (2 * y - 2 * x) + sp.sin(t) ** 2 / (x + y)
    assert flint_poly.factor(expr) == sp.factor(expr)
    poly = (x + sp.cos(t)) ** 2 * (2 * x - 3)
    assert flint_poly.expand_polynomial(poly) == sp.expand(poly)
    assert flint_poly.rational_zero(1 / (x - y) + 1 / (y - x)) is None  # undecided here
    f = dmp_from_dict({(2, 0): ZZ(1), (0, 2): ZZ(-1)}, 1, ZZ)  # x^2 - y^2
    g = dmp_from_dict({(1, 0): ZZ(1), (0, 1): ZZ(1)}, 1, ZZ)  # x + y
    assert zz_factor(f, 1, ZZ) == dmp_zz_factor(f, 1, ZZ)
    assert zz_gcd(f, g, 1, ZZ) == dmp_zz_heu_gcd(f, g, 1, ZZ)
    with flint_polynomials():
        assert sp.factor(x**2 - y**2) == (x - y) * (x + y)


_OVERFLOWING = """
[[bodies]]
name = "b"
shape = "rigid"
mass = "0.1537*sqrt(3)"
inertia = "1.683"
position = ["-0.7618", "1.2811"]
velocity = ["-2.662", "-2.463"]
spin = "5"
[[bodies]]
name = "s"
shape = "sphere"
mass = "2.3108*sqrt(3)"
radius = "1"
velocity = ["-1", "-15/7"]
spin = "70/12"
[contact]
bodies = ["b", "s"]
restitution = "1/2"
tangential = "stick"
"""


def test_a_closed_form_flint_cannot_factor_is_answered(tmp_path, capsys):
    """FLINT's factor raised OverflowError on this scene's closed form (its sort key);
    the answer, SymPy's, is held against the laws solved apart in NumPy: the normal
    x through O, where the sphere touches b's contact point; Newton's law with e = 1/2
    and no slip after."""
    import numpy as np

    from helpers import evaluated, scene_file

    got = evaluated(capsys, ["evaluate", scene_file(tmp_path, _OVERFLOWING)])
    m_b, i_b, m_s = 0.1537 * 3**0.5, 1.683, 2.3108 * 3**0.5
    i_s = 0.4 * m_s
    rho_b, rho_s = np.array([0.7618, -1.2811]), np.array([-1.0, 0.0])  # centre to point
    u = np.array([-2.662, -2.463, 5, -1, -15 / 7, 70 / 12])
    minv = np.diag([1 / m_b, 1 / m_b, 1 / i_b, 1 / m_s, 1 / m_s, 1 / i_s])

    def cross(r, d):
        return r[0] * d[1] - r[1] * d[0]

    def row(d):  # the relative velocity of the points (s's less b's) along d
        return np.array([-d[0], -d[1], -cross(rho_b, d), d[0], d[1], cross(rho_s, d)])

    jn, jt = row(np.array([1.0, 0])), row(np.array([0, 1.0]))
    big_j = np.array([jn, jt])
    w = big_j @ minv @ big_j.T
    impulse = np.linalg.solve(w, np.array([-(1 + 0.5) * jn @ u, -jt @ u]))
    after = u + minv @ big_j.T @ impulse
    keys = ["b.vx", "b.vy", "b.omega", "s.vx", "s.vy", "s.omega"]
    assert np.allclose([got[k] for k in keys], after, rtol=1e-12, atol=1e-12)
    assert np.isclose(got["impulse"], impulse[0], rtol=1e-12)
