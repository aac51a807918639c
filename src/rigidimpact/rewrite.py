"""Targeted rewriting of exact results: one denominator, factors, named groups.

Library code never calls a blanket ``simplify``: these rewrites are each meant for one
job, so output is fast and stable from one SymPy release to the next.

Examples
--------
>>> x = sp.Symbol("x")
>>> tidy(x / (x + x**2))
1/(x + 1)
"""

from __future__ import annotations

import sympy as sp

__all__ = ["tidy", "recognise"]


def tidy(expr: sp.Expr) -> sp.Expr:
    """Put an expression over one denominator, factor it, and use sin^2 + cos^2 = 1.

    ``cancel`` removes common factors; ``factor`` then shows the structure the paper
    writes (``(e + 1)``, ``2M + m(1 + sin^2)``). For each angle, trying
    ``cos^2 -> 1 - sin^2`` (and the reverse) and keeping the shorter form is the only
    trig rewrite made: targeted, fast and deterministic, unlike a blanket ``simplify``.

    Examples
    --------
    >>> x, t = sp.Symbol("x"), sp.Symbol("t", real=True)
    >>> tidy((x**2 - 1) / (x - 1) + 1)
    x + 2
    >>> tidy(x / (x * sp.sin(t)**2 + x * sp.cos(t)**2 + x))
    1/2
    """
    best = sp.factor(sp.cancel(sp.sympify(expr)))
    angles = {f.args[0] for f in best.atoms(sp.sin, sp.cos)}
    for angle in sorted(angles, key=sp.default_sort_key):
        s, c = sp.sin(angle), sp.cos(angle)
        for old, new in ((c**2, 1 - s**2), (s**2, 1 - c**2)):
            candidate = sp.factor(sp.cancel(best.subs(old, new)))
            if sp.count_ops(candidate) < sp.count_ops(best):
                best = candidate
    return best


def recognise(expr: sp.Expr, name: sp.Symbol, definition: sp.Expr,
              eliminate: sp.Symbol) -> sp.Expr:
    """Rewrite `expr` in terms of the group ``name = definition`` by eliminating a symbol.

    The group must be linear in `eliminate` (as the paper's f is in e); the result is
    tidied, and it no longer contains `eliminate`.

    Examples
    --------
    >>> m, M, e, v, f = sp.symbols("m M e v f", positive=True)
    >>> recognise(m * v * (e + 1) / (2 * M + m), f, (e + 1) * m / (2 * M + m), e)
    f*v
    """
    (replacement,) = sp.solve(sp.Eq(name, definition), eliminate, dict=False)
    return tidy(expr.subs(eliminate, replacement))
