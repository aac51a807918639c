"""An expression's value at a rational point, without building SymPy objects.

``expr.xreplace(point).evalf(n)`` rebuilds every node of the tree with numbers in it
(each Add and Mul canonicalised again) before evaluating anything: for the checks that
evaluate a derived answer at a few random points (the certificate's, the comparisons'
spot checks) that rebuilding is most of their cost. :func:`value_at` walks the tree once
instead, each distinct subtree once:

* where every leaf is rational and every operation is field arithmetic (or an exact
  root of a rational, as SymPy itself takes it: ``sqrt(9/4)`` is ``3/2``; or a function
  of a multiple of pi, left to SymPy, which knows ``sin(pi/6)`` is ``1/2``), the value
  is exact, a SymPy ``Rational``: the same number ``xreplace`` would give;
* elsewhere (a sine of a rational angle, pi, a root that is not exact) it is an mpmath
  number, computed with the working precision `dps` at every step.

A node it does not know (a Float, a Piecewise, a function of its own) raises
:class:`Unsupported`, and the caller evaluates that expression SymPy's way: a Float in
particular must stay a Float, since it says the data were rounded.

Examples
--------
>>> x, t = sp.symbols("x t")
>>> value_at((x**2 + 1) / (x - 3), {x: sp.Rational(1, 2)})
-1/2
>>> value_at(sp.sqrt(x**2 + 2 * x + 1), {x: sp.Rational(5, 4)})
9/4
>>> print(mpmath.nstr(value_at(sp.sin(t)**2 + sp.cos(t)**2, {t: sp.Rational(3, 7)}), 30))
1.0
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import mpmath
import sympy as sp
from sympy import integer_nthroot
from sympy.external.gmpy import MPQ

__all__ = ["Unsupported", "value_at"]


class Unsupported(ValueError):
    """A node :func:`value_at` does not evaluate: the caller evaluates it SymPy's way."""


_FUNCTIONS: dict[type, Callable[[Any], Any]] = {
    sp.sin: mpmath.sin, sp.cos: mpmath.cos, sp.tan: mpmath.tan, sp.exp: mpmath.exp,
    sp.log: mpmath.log, sp.atan: mpmath.atan, sp.asin: mpmath.asin, sp.acos: mpmath.acos,
    sp.sinh: mpmath.sinh, sp.cosh: mpmath.cosh, sp.tanh: mpmath.tanh,
}
_AT_ZERO = {sp.sin: 0, sp.tan: 0, sp.cos: 1, sp.exp: 1, sp.atan: 0, sp.asin: 0,
            sp.sinh: 0, sp.tanh: 0, sp.cosh: 1}  # exact values SymPy gives at 0


def _mp(x: Any) -> mpmath.mpf:
    return mpmath.mpf(int(x.numerator)) / int(x.denominator) if isinstance(x, MPQ) else x


def _root(q: Any, n: int) -> Any:
    """The positive n-th root of a nonnegative rational, exact where it is rational."""
    top, exact_top = integer_nthroot(int(q.numerator), n)
    bottom, exact_bottom = integer_nthroot(int(q.denominator), n)
    if exact_top and exact_bottom:
        return MPQ(top, bottom)
    return mpmath.root(_mp(q), n)


def _integer_power(base: Any, k: int) -> Any:
    if k < 0 and isinstance(base, MPQ) and base == 0:
        raise ZeroDivisionError("zero to a negative power")
    return base ** k


def _power(base: Any, exponent: sp.Expr) -> Any:
    if exponent.is_Integer:
        return _integer_power(base, int(exponent))
    if exponent.is_Rational and isinstance(base, MPQ) and base >= 0:
        return _integer_power(_root(base, int(exponent.q)), int(exponent.p))
    power = mpmath.power(_mp(base), _mp(_leaf(exponent)))
    if isinstance(power, mpmath.mpc):
        raise Unsupported("a complex power")
    return power


def _leaf(node: sp.Expr) -> Any:
    if node.is_Rational:
        return MPQ(int(node.p), int(node.q))
    if node is sp.pi:
        return +mpmath.pi
    if node is sp.E:
        return +mpmath.e
    raise Unsupported(f"no value for {node}")


def value_at(expr: Any, point: Mapping[Any, Any], dps: int = 60) -> Any:
    """The value of `expr` where each symbol takes its rational value in `point`: an
    exact ``sympy.Rational`` where the whole evaluation stays rational, else an
    ``mpmath.mpf`` computed at `dps` digits. Raises :class:`Unsupported` for a node it
    does not evaluate, or a symbol `point` does not give; ``ZeroDivisionError`` where
    a denominator vanishes."""
    given = {s: MPQ(int(v.p), int(v.q)) for s, v in point.items()}
    seen: dict[sp.Basic, Any] = {}

    def walk(node: sp.Basic) -> Any:
        found = seen.get(node)
        if found is not None:
            return found
        if node.is_Symbol:
            try:
                value = given[node]
            except KeyError:
                raise Unsupported(f"no value for the symbol {node}") from None
        elif node.is_Atom:
            value = _leaf(node)
        elif node.is_Add or node.is_Mul:
            parts = [walk(a) for a in node.args]
            if not all(isinstance(p, MPQ) for p in parts):
                parts = [_mp(p) for p in parts]
            value = parts[0]
            for p in parts[1:]:
                value = value + p if node.is_Add else value * p
        elif node.is_Pow:
            value = _power(walk(node.base), node.exp)
        elif type(node) in _FUNCTIONS and node.args[0].has(sp.pi):
            # sin(pi x) at x = 1/6 is 1/2 to SymPy, exactly: its own evaluation
            found = node.xreplace(point)
            if found.is_Rational:
                value = MPQ(int(found.p), int(found.q))
            elif found.is_number and found.is_real:
                value = found.evalf(dps)._to_mpmath(mpmath.mp.prec)
            else:
                raise Unsupported(f"no real value for {found}")
        elif type(node) in _FUNCTIONS:
            (arg,) = node.args
            x = walk(arg)
            if isinstance(x, MPQ) and x == 0 and type(node) in _AT_ZERO:
                value = MPQ(_AT_ZERO[type(node)])
            else:
                value = _FUNCTIONS[type(node)](_mp(x))
                if isinstance(value, mpmath.mpc):  # log of a negative, asin past 1
                    raise Unsupported(f"no real value for {node} there")
        elif isinstance(node, sp.Abs):
            value = abs(walk(node.args[0]))
        else:
            raise Unsupported(f"no value for {type(node).__name__}")
        seen[node] = value
        return value

    with mpmath.workdps(dps):
        value = walk(sp.sympify(expr))
    if isinstance(value, MPQ):
        return sp.Rational(int(value.numerator), int(value.denominator))
    return value
