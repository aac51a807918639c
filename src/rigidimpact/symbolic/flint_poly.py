"""Multivariate factorisation and gcds over the integers by python-flint, in SymPy's own
terms.

SymPy factors a polynomial in several variables by Wang's algorithm and takes gcds by a
heuristic, both in pure Python (``dmp_zz_factor``, ``dmp_zz_heu_gcd``): the largest
single cost of deriving and verifying the paper's results. python-flint (FLINT's
``fmpz_mpoly``) computes the same answers in compiled code. Both state them alike: a
factorisation as the content with its sign and the irreducible primitive factors, each
with a positive leading coefficient in lexicographic order of the variables (the first
the main one); a gcd with a positive leading coefficient and the two exact cofactors. So
the answer is SymPy's to the last term (the tests hold the two side by side on seeded
random polynomials), and SymPy's own code sorts and assembles it.
:func:`flint_polynomials` puts the two in for the duration of a block and puts SymPy's
back after.

Examples
--------
>>> import sympy as sp
>>> x, y, z = sp.symbols("x y z")
>>> expr = (x**2 - y**2) * (3 * x * z + 2)**2 / (y - x)
>>> with flint_polynomials():
...     fast = sp.factor(expr)
>>> fast == sp.factor(expr), fast
(True, -(x + y)*(3*x*z + 2)**2)
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

from sympy.polys import euclidtools, factortools
from sympy.polys.densebasic import dmp_from_dict, dmp_to_dict
from sympy.polys.factortools import _sort_factors

__all__ = ["flint_polynomials", "zz_factor", "zz_gcd"]

from flint import fmpz_mpoly_ctx

_SYMPY = {"factor": factortools.dmp_zz_factor, "gcd": euclidtools.dmp_zz_heu_gcd}


def _context(u: int) -> Any:
    return fmpz_mpoly_ctx.get(tuple(f"x{i}" for i in range(u + 1)), "lex")


def _to_flint(f: Any, u: int, K: Any, ctx: Any) -> Any:
    return ctx.from_dict({m: int(c) for m, c in dmp_to_dict(f, u, K).items()})


def _from_flint(p: Any, u: int, K: Any) -> Any:
    return dmp_from_dict({m: K(int(c)) for m, c in p.to_dict().items()}, u, K)


def zz_factor(f: Any, u: int, K: Any) -> tuple[Any, list[tuple[Any, int]]]:
    """``dmp_zz_factor(f, u, K)``'s answer by FLINT: the content of `f` in `K` (ZZ) with
    the sign that leaves the primitive part's leading coefficient positive, and the
    irreducible factors with their multiplicities (dense, u + 1 variables), in the
    order SymPy sorts them to (Wang's algorithm finds them in no fixed order; every
    caller sorts them)."""
    if not u:  # one variable: SymPy's own
        return _SYMPY["factor"](f, u, K)
    ctx = _context(u)
    poly = _to_flint(f, u, K, ctx)
    if poly == 0:
        return K.zero, []
    content, found = poly.factor()
    return K(int(content)), _sort_factors([(_from_flint(g, u, K), int(k))
                                           for g, k in found])


def zz_gcd(f: Any, g: Any, u: int, K: Any) -> tuple[Any, Any, Any]:
    """``dmp_zz_heu_gcd(f, g, u, K)``'s answer by FLINT: the gcd of `f` and `g` in
    ``K[X]`` (ZZ) with a positive leading coefficient, and the cofactors ``f / h`` and
    ``g / h``."""
    if not u:
        return _SYMPY["gcd"](f, g, u, K)
    ctx = _context(u)
    a, b = _to_flint(f, u, K, ctx), _to_flint(g, u, K, ctx)
    h = a.gcd(b)
    if h == 0:
        return _from_flint(h, u, K), f, g
    return _from_flint(h, u, K), _from_flint(a / h, u, K), _from_flint(b / h, u, K)


@contextlib.contextmanager
def flint_polynomials() -> Iterator[None]:
    """Within the block, SymPy factors polynomials of several variables over the
    integers by :func:`zz_factor` and takes their gcds by :func:`zz_gcd`; SymPy's own
    routines are put back after."""
    if factortools.dmp_zz_factor is zz_factor:  # within a block already
        yield
        return
    factortools.dmp_zz_factor, euclidtools.dmp_zz_heu_gcd = zz_factor, zz_gcd
    try:
        yield
    finally:
        factortools.dmp_zz_factor, euclidtools.dmp_zz_heu_gcd = (_SYMPY["factor"],
                                                                 _SYMPY["gcd"])
