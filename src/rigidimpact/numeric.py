"""Numbers from exact results: float64 NumPy kernels and mpmath at a chosen precision.

Before compiling, each expression is put in a form that float64 evaluates stably; the
rewrites and why each is there:

* one fraction, cancelled and factored (``tidy``): a difference of two nearly equal
  quotients, such as v_fx = v_ix - 2M V_x / m when m << M, becomes one numerator in
  which the cancellation, if any, is exact in the data;
* ``1 - e**2`` as ``(1 - e)(1 + e)`` (``factor``): 1 - e is exact in float64 for e
  near 1 (Sterbenz), 1 - e*e is not;
* ``1 - sin(x)**2`` back to ``cos(x)**2`` (and the reverse): the subtraction loses
  every digit near x = 90 degrees (or 0), the square does not;
* the kinetic energy lost from the work of the impulse (see ``Solution.energy_lost``),
  never as K_i - K_f, which cancels as e -> 1.

Examples
--------
>>> from rigidimpact.problems import derive
>>> k = Kernel.from_expr(derive("barbell").results["V_x"])
>>> k.arguments
('M', 'e', 'm', 'theta', 'v_ix')
>>> float(k(M=1.0, e=1.0, m=2.0, theta=0.0, v_ix=1.0))
1.0
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import mpmath
import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.rewrite import tidy

__all__ = ["stable_form", "magnitude", "Kernel", "kernels", "evaluate"]


def _reverse_pythagoras(expr: sp.Expr) -> sp.Expr:
    """``a - a sin(x)^2 -> a cos(x)^2`` and ``a - a cos(x)^2 -> a sin(x)^2`` in any sum."""

    def fix(node: sp.Add) -> sp.Expr:
        squares = [p for p in node.atoms(sp.Pow)
                   if p.exp == 2 and isinstance(p.base, (sp.sin, sp.cos))]
        for power in sorted(squares, key=sp.default_sort_key):
            coeff = node.coeff(power)
            if coeff == 0 or coeff.has(power.base):
                continue
            rest = sp.expand(node - coeff * power)
            remainder = sp.expand(rest + coeff)
            if len(sp.Add.make_args(remainder)) < len(sp.Add.make_args(rest)):
                other = sp.cos if isinstance(power.base, sp.sin) else sp.sin
                return -coeff * other(power.base.args[0]) ** 2 + remainder
        return node

    return expr.replace(lambda n: isinstance(n, sp.Add), fix)


def stable_form(expr: sp.Expr) -> sp.Expr:
    """The expression rewritten for stable float64 evaluation (see the module notes).

    Examples
    --------
    >>> e = sp.Symbol("e", nonnegative=True)
    >>> stable_form(1 - e**2)
    (1 - e)*(e + 1)
    >>> x = sp.Symbol("x", real=True)
    >>> stable_form(3 - 3 * sp.sin(x)**2)
    3*cos(x)**2
    """
    return _reverse_pythagoras(tidy(expr))


def magnitude(expr: sp.Expr) -> sp.Expr:
    """The expression with every sum's terms replaced by their absolute values.

    Float64 evaluation of a sum errs by about one rounding of the sum of the terms'
    magnitudes, so ``magnitude(x) / |x|`` is the condition number that multiplies the
    rounding error; where nothing cancels, ``magnitude(x) == |x|``. For the paper's
    v_fx it is ``|v_ix| (m(1 + sin^2) + 2Me) / (2M + m(1 + sin^2))``.

    Examples
    --------
    >>> a, b = sp.symbols("a b", positive=True)
    >>> magnitude((a - b) / (a + b))  # a - b may cancel: its scale is a + b
    1
    >>> magnitude(a - 2 * b).subs({a: 2, b: 1})  # the value is 0, the scale 4
    4
    """
    def absolute_terms(node: sp.Basic) -> sp.Basic:
        return sp.Add(*(sp.Abs(t) for t in node.args), evaluate=False)

    numerator, denominator = sp.fraction(sp.factor(expr))
    numerator = numerator.replace(lambda n: isinstance(n, sp.Add), absolute_terms)
    return sp.Abs(numerator) / sp.Abs(denominator)


@dataclass(frozen=True)
class Kernel:
    """An exact expression compiled for float64 (vectorised) and for mpmath.

    Call it with keyword arguments (NumPy arrays broadcast); ``.mp(dps=50, **values)``
    evaluates the same stable form with mpmath at `dps` digits, and ``.reference``
    evaluates the *exact* expression with mpmath (for checking the float path).
    """

    expr: sp.Expr
    stable: sp.Expr
    arguments: tuple[str, ...]
    size: sp.Expr  # magnitude(expr): the scale float64 errors are measured against

    @classmethod
    def from_expr(cls, expr: sp.Expr) -> Kernel:
        expr = sp.sympify(expr)
        arguments = tuple(sorted(s.name for s in expr.free_symbols))
        return cls(expr, stable_form(expr), arguments, magnitude(expr))

    def _symbols(self, expr: sp.Expr) -> list[sp.Symbol]:
        by_name = {s.name: s for s in expr.free_symbols}
        return [by_name.get(n, sp.Symbol(n)) for n in self.arguments]

    @property
    def _float(self):
        return _compiled(self.stable, tuple(self._symbols(self.stable)), "numpy")

    def __call__(self, **values: Any) -> Any:
        return self._float(*(np.asarray(values[n], dtype=np.float64) for n in self.arguments))

    def mp(self, dps: int = 50, **values: Any) -> mpmath.mpf:
        """The stable form in mpmath at `dps` significant digits."""
        fn = _compiled(self.stable, tuple(self._symbols(self.stable)), "mpmath")
        with mpmath.workdps(dps):
            return +fn(*(values[n] if isinstance(values[n], mpmath.mpf)
                         else mpmath.mpf(values[n]) for n in self.arguments))

    def reference(self, dps: int = 50, **values: Any) -> mpmath.mpf:
        """The exact (unrewritten) expression at `dps` digits, inputs taken exactly."""
        fn = _compiled(self.expr, tuple(self._symbols(self.expr)), "mpmath")
        with mpmath.workdps(dps):
            return +fn(*(mpmath.mpf(values[n]) for n in self.arguments))

    def scale(self, dps: int = 50, **values: Any) -> mpmath.mpf:
        """``magnitude`` of the exact expression at the inputs (see :func:`magnitude`)."""
        fn = _compiled(self.size, tuple(self._symbols(self.expr)), "mpmath")
        with mpmath.workdps(dps):
            return +fn(*(mpmath.mpf(values[n]) for n in self.arguments))


_CACHE: dict[tuple, Any] = {}


def _compiled(expr: sp.Expr, symbols: tuple[sp.Symbol, ...], module: str):
    key = (expr, symbols, module)
    if key not in _CACHE:
        # the generated code sees only fresh dummies: a scene's symbol named like one of
        # its own names (mpf, sin, select) would otherwise shadow it
        dummies = [sp.Dummy(f"x{k}") for k in range(len(symbols))]
        safe = expr.xreplace(dict(zip(symbols, dummies, strict=True)))
        _CACHE[key] = sp.lambdify(dummies, safe, module)
    return _CACHE[key]


def kernels(results: Mapping[str, sp.Expr]) -> dict[str, Kernel]:
    """A kernel per result.

    Examples
    --------
    >>> from rigidimpact.problems import derive
    >>> sorted(kernels(derive("discs").results))[:2]
    ['V_1fx', 'V_1fy']
    """
    return {key: Kernel.from_expr(expr) for key, expr in results.items()}


FALLBACK_DIGITS = 40  # where float64 cannot hold a result or a step toward it
_FLOAT_MAX = np.finfo(np.float64).max
_FLOAT_TINY = np.finfo(np.float64).tiny


def _float_point(kernel: Kernel, args: Mapping[str, Any]) -> float | None:
    """The float64 kernel at one point, or None where float64 overflows, underflows or
    divides by zero on the way (the answer would be wrong, not merely inexact)."""
    try:
        with np.errstate(over="raise", under="raise", invalid="raise", divide="raise"):
            value = float(kernel(**{n: float(v) for n, v in args.items()}))
    except (OverflowError, FloatingPointError, ZeroDivisionError):
        return None
    return value if np.isfinite(value) else None


def _mp_point(kernel: Kernel, key: str, args: Mapping[str, Any], dps: int) -> mpmath.mpf:
    """The stable form in mpmath; refuse a result that is undefined at these values."""
    with mpmath.workdps(dps + 10):
        exact = {n: mpmath.mpf(sp.N(v, dps + 10)) if isinstance(v, sp.Basic) else v
                 for n, v in args.items()}
    try:
        value = kernel.mp(dps, **exact)
    except (ZeroDivisionError, OverflowError, ValueError):
        value = mpmath.nan
    if not mpmath.isfinite(value):
        raise InputError(key, "undefined at these values (a division by zero or an "
                         "infinite result); the geometry or data are degenerate")
    return value


def evaluate(results: Mapping[str, sp.Expr], values: Mapping[str, Any],
             dps: int | None = None) -> dict[str, Any]:
    """Evaluate every result at `values` (name -> number): float64, or mpmath at `dps`.

    The float64 path never returns NaN or an infinity: where float64 would overflow or
    underflow on the way, the result is computed with mpmath at 40 digits instead, and
    returned as a float when it fits in float64 (else as the mpmath number). A result
    that is undefined at the values raises :class:`InputError`. This is the unchecked
    core: :meth:`rigidimpact.problems.Derivation.evaluate` checks the values first.

    Examples
    --------
    >>> from rigidimpact.problems import derive
    >>> evaluate(derive("discs").results, {"V_1ix": 1.0, "V_2ix": 0.0, "V_1iy": 0.0,
    ...                                    "V_2iy": 0.0, "e": 1.0})["V_2fx"]
    1.0
    >>> big = {"V_1ix": sp.Integer(10)**100, "V_2ix": 0, "V_1iy": 0, "V_2iy": 0, "e": 1}
    >>> evaluate({"square": derive("discs").results["V_2fx"]**4}, big)["square"]
    mpf('1.0e+400')
    """
    out: dict[str, Any] = {}
    for key, kernel in kernels(results).items():
        args = {n: values[n] for n in kernel.arguments}
        if dps:
            out[key] = _mp_point(kernel, key, args, dps)
            continue
        value = _float_point(kernel, args)
        if value is None:
            precise = _mp_point(kernel, key, args, FALLBACK_DIGITS)
            fits = precise == 0 or _FLOAT_TINY <= abs(precise) <= _FLOAT_MAX
            value = float(precise) if fits else precise
        out[key] = value
    return out
