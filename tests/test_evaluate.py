"""An expression's value at a rational point, walked once (symbolic/evaluate.py), is the
value SymPy's own substitution and evalf give: the same Rational where SymPy's is
rational, the same number to the digits asked for elsewhere. Its callers (the
certificate's points, the comparisons' spot checks) depend on both."""

from __future__ import annotations

import random

import mpmath
import pytest
import sympy as sp

from rigidimpact.symbolic.evaluate import Unsupported, value_at


def _expressions(rng: random.Random, count: int):
    x, y = sp.symbols("x y")
    t = sp.Symbol("t", real=True)
    m = sp.Symbol("m", positive=True)
    leaves = [x, y, m, t, sp.Integer(2), sp.Rational(-3, 7), sp.pi]

    def tree(depth: int) -> sp.Expr:
        if depth == 0:
            return rng.choice(leaves)
        kind = rng.choice(["add", "mul", "pow", "root", "trig", "abs", "leaf"])
        if kind == "add":
            return tree(depth - 1) + tree(depth - 1)
        if kind == "mul":
            return tree(depth - 1) * tree(depth - 1)
        if kind == "pow":
            return tree(depth - 1) ** rng.choice([-2, -1, 2, 3])
        if kind == "root":  # a root of something positive: a square, or m
            inner = tree(depth - 1)
            return sp.sqrt(inner**2 + rng.choice([0, m])) if rng.random() < 0.7 \
                else sp.Pow(m + inner**2, sp.Rational(1, 3))
        if kind == "trig":
            return rng.choice([sp.sin, sp.cos, sp.tan, sp.exp])(tree(depth - 1))
        if kind == "abs":
            return sp.Abs(tree(depth - 1))
        return rng.choice(leaves)

    for _ in range(count):
        yield tree(rng.randint(1, 4)), {x: sp.Rational(rng.randint(-40, 40), 7),
                                        y: sp.Rational(rng.randint(-40, 40), 11),
                                        m: sp.Rational(rng.randint(1, 40), 3),
                                        t: sp.Rational(rng.randint(-40, 40), 13)}


def test_a_value_walked_once_is_sympys_own():
    rng = random.Random(45)
    exact = approximate = 0
    for expr, point in _expressions(rng, 400):
        theirs = expr.xreplace(point)
        if theirs.has(sp.zoo, sp.nan, sp.oo, -sp.oo, sp.I):
            continue  # a pole or a complex value there: no value to compare
        try:
            ours = value_at(expr, point, 80)
        except (ZeroDivisionError, Unsupported):
            continue
        if theirs.is_Rational:  # the same exact number, as the exact certificate needs
            assert ours == theirs and isinstance(ours, sp.Rational), (expr, point)
            exact += 1
        else:
            with mpmath.workdps(80):
                reference = mpmath.mpmathify(theirs.evalf(80))
                assert not isinstance(ours, sp.Rational), (expr, point)
                scale = max(abs(reference), mpmath.mpf(1))
                assert abs(ours - reference) <= scale * mpmath.mpf(10) ** -60, (expr, point)
            approximate += 1
    assert exact >= 60 and approximate >= 100


def test_what_it_does_not_evaluate_it_leaves_to_sympy():
    x, y = sp.symbols("x y")
    for expr in (0.5 * x, sp.Piecewise((x, x > 0), (0, True)), sp.Function("g")(x), x + y):
        with pytest.raises(Unsupported):  # a Float must stay a Float: SymPy's way
            value_at(expr, {x: sp.Rational(1, 2)})
    for expr in (sp.log(x), sp.asin(x)):  # no real value there: SymPy's way, not complex
        with pytest.raises(Unsupported):
            value_at(expr, {x: sp.Integer(-2)})
    with mpmath.workdps(60):  # a constant at the digits asked for
        assert abs(value_at(sp.E * x, {x: sp.Integer(1)}, 60) - mpmath.e) < \
            mpmath.mpf(10) ** -55
    with pytest.raises(ZeroDivisionError):
        value_at(1 / (x - 1), {x: sp.Integer(1)})
    # SymPy's exact values of its functions, kept exact
    assert value_at(sp.cos(x) + sp.sin(x), {x: sp.Integer(0)}) == 1
    irrational = value_at(sp.sin(sp.pi * x) + sp.cos(sp.pi * x), {x: sp.Rational(1, 6)})
    with mpmath.workdps(60):
        assert abs(irrational - (1 + mpmath.sqrt(3)) / 2) < mpmath.mpf(10) ** -55
    assert value_at(sp.sin(sp.pi * x) * y, {x: sp.Rational(1, 6), y: sp.Integer(4)}) == 2
