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
random polynomials), and SymPy's own code sorts and assembles it. FLINT is a fast path,
never the only one: wherever one of its steps fails (it has raised OverflowError while
sorting the factors of a polynomial with large coefficients), the answer is SymPy's own.
:func:`flint_polynomials` puts the two in for the duration of a block and puts SymPy's
back after. :func:`factor` goes further where an expression is a rational function of
symbols, pi and sines and cosines of symbols: the one fraction is made in FLINT too, not
by SymPy's ``together``.

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
from math import lcm
from typing import Any

import sympy as sp
from flint import fmpq, fmpq_mpoly_ctx, fmpz_mpoly_ctx
from sympy.core.exprtools import _keep_coeff
from sympy.polys import euclidtools, factortools
from sympy.polys.densebasic import dmp_from_dict, dmp_to_dict
from sympy.polys.factortools import _sort_factors
from sympy.polys.polytools import _factors_product
from sympy.polys.polyutils import _sort_gens, basic_from_dict

__all__ = ["flint_polynomials", "zz_factor", "zz_gcd", "factor", "rational_zero",
           "expand_polynomial"]

# what a step in FLINT may raise (an overflow in its sort key, a value it cannot take):
# SymPy's own routine answers instead; ZeroDivisionError is the fractions' own signal
_FLINT_FAILURES = (OverflowError, ValueError, TypeError, NotImplementedError,
                   RuntimeError, MemoryError, AssertionError)

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
    try:
        ctx = _context(u)
        poly = _to_flint(f, u, K, ctx)
        if poly == 0:
            return K.zero, []
        content, found = poly.factor()
        return K(int(content)), _sort_factors([(_from_flint(g, u, K), int(k))
                                               for g, k in found])
    except _FLINT_FAILURES:
        return _SYMPY["factor"](f, u, K)


def zz_gcd(f: Any, g: Any, u: int, K: Any) -> tuple[Any, Any, Any]:
    """``dmp_zz_heu_gcd(f, g, u, K)``'s answer by FLINT: the gcd of `f` and `g` in
    ``K[X]`` (ZZ) with a positive leading coefficient, and the cofactors ``f / h`` and
    ``g / h``."""
    if not u:
        return _SYMPY["gcd"](f, g, u, K)
    try:
        ctx = _context(u)
        a, b = _to_flint(f, u, K, ctx), _to_flint(g, u, K, ctx)
        h = a.gcd(b)
        if h == 0:
            return _from_flint(h, u, K), f, g
        return _from_flint(h, u, K), _from_flint(a / h, u, K), _from_flint(b / h, u, K)
    except _FLINT_FAILURES:
        return _SYMPY["gcd"](f, g, u, K)


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


def factor(expr: Any) -> Any:
    """``sympy.factor(expr)``, the same expression, made in FLINT where `expr` is a
    rational function of symbols, pi and sines and cosines of symbols with rational
    coefficients; by SymPy itself otherwise (:func:`_rational_factor` says where).

    SymPy puts `expr` over one denominator (``together``, whose term-by-term gcds cost
    as much as the factoring) and factors each polynomial it finds. Here the one
    fraction is made in FLINT's rational polynomials (a sum over its terms' least
    common denominator), reduced by one gcd, and its
    numerator and denominator are factored over the integers; SymPy's own helpers then
    assemble the answer from the same primitive factors (each with a positive leading
    coefficient in the lexicographic order of SymPy's sorted generators) and the same
    rational coefficient. A factorisation into primitive irreducible factors so
    normalised is unique, so the answer is SymPy's to the last term (a test holds the
    two side by side).

    Examples
    --------
    >>> import sympy as sp
    >>> x, y, t = sp.Symbol("x"), sp.Symbol("y"), sp.Symbol("t", real=True)
    >>> expr = (x**2 - y**2) / (2 * y - 2 * x) + sp.sin(t) ** 2 / (x + y)
    >>> factor(expr) == sp.factor(expr)
    True
    """
    try:
        fast = _rational_factor(sp.sympify(expr))
    except _FLINT_FAILURES:
        fast = None
    return sp.factor(expr) if fast is None else fast


def _rational_factor(expr: Any) -> Any:
    """The fast path of :func:`factor`, None where it does not apply (a float, a radical,
    a function other than sin and cos, a sine of anything but a symbol, two generators
    of one name)."""
    found = _fraction(expr)
    if found is None:
        return None
    order, num, den = found
    if len({str(g) for g in order}) < len(order):
        return None  # two names alike (their order is no one's): SymPy's own
    if num == 0:
        return sp.Integer(0)
    common = num.gcd(den)
    num, den = num / common, den / common
    coeff = sp.Integer(1)
    factors: list[tuple[Any, Any]] = []
    for part, sign in ((num, 1), (den, -1)):
        whole, scale = _integral(part)
        content, pieces = whole.factor()
        c = sp.Rational(int(content), scale)
        coeff *= c if sign == 1 else 1 / c
        for f, k in pieces:
            rep = {m: sp.Integer(int(v)) for m, v in f.to_dict().items()}
            factors.append((basic_from_dict(rep, *order), sign * int(k)))
    return _keep_coeff(coeff, _factors_product(factors))


def rational_zero(expr: Any, half_angle: bool = False) -> bool | None:
    """Whether `expr`, a rational function of symbols, pi and sines and cosines of
    symbols (each taken as a variable of its own), is identically zero: its one
    fraction's numerator, made in FLINT, is zero. None where `expr` is not such a
    function, or a denominator in it vanishes identically.

    With `half_angle`, each angle's sine, cosine and tangent are first written in
    ``t = tan(angle/2)`` (``2t/(1 + t^2)``, ``(1 - t^2)/(1 + t^2)``, ``2t/(1 - t^2)``),
    one variable for each angle: then the answer decides every rational identity of
    the trig functions too (sin^2 + cos^2 = 1 among them), as the substitution made in
    SymPy would, without building the substituted expression.

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> rational_zero(1 / (x - y) + 1 / (y - x)), rational_zero(x / y - 1)
    (True, False)
    >>> t = sp.Symbol("t", real=True)
    >>> rational_zero(sp.sin(t)**2 + sp.cos(t)**2 - 1, half_angle=True)
    True
    >>> rational_zero(sp.tan(t) * sp.cos(t) - sp.sin(t), half_angle=True)
    True
    """
    try:
        found = _fraction(sp.sympify(expr), half_angle)
    except _FLINT_FAILURES:
        return None  # undecided here: the callers' other tests decide
    return None if found is None else found[1] == 0


_TRIG = (sp.sin, sp.cos)


def _generators(expr: Any, half_angle: bool) -> set[Any] | None:
    """The variables of `expr` as a rational function (each symbol and pi, and each sine
    or cosine of a symbol; with `half_angle`, a ``tan(angle/2)`` stand-in for each
    angle's trig functions), each distinct subtree looked at once; None where it holds
    anything else."""
    gens: set[Any] = set()
    visited: set[Any] = set()
    stack = [expr]
    trig = (sp.sin, sp.cos, sp.tan) if half_angle else _TRIG
    while stack:
        node = stack.pop()
        if node in visited:
            continue
        visited.add(node)
        if node.is_Symbol or node is sp.pi:  # pi, transcendental, is SymPy's variable too
            gens.add(node)
        elif isinstance(node, trig):
            if not node.args[0].is_Symbol:
                return None
            gens.add(_half(node.args[0]) if half_angle else node)
        elif node.is_Rational:
            continue
        elif node.is_Add or node.is_Mul:
            stack.extend(node.args)
        elif node.is_Pow:
            if not node.exp.is_Integer:
                return None
            stack.append(node.base)
        else:
            return None
    return gens


def _half(angle: Any) -> Any:
    """The variable standing for ``tan(angle/2)``: the same one for every call, so a
    generator's place in SymPy's sorted order is fixed."""
    return _HALVES.setdefault(angle, sp.Dummy(f"t_{angle}", real=True))


_HALVES: dict[Any, Any] = {}


def _fraction(expr: Any, half_angle: bool = False
              ) -> tuple[tuple[Any, ...], Any, Any] | None:
    """`expr` as one fraction of FLINT's rational polynomials, numerator and denominator,
    in SymPy's sorted generators (each symbol, each sine or cosine of a symbol); None
    where `expr` holds anything else (a float, a radical, another function, a sine of
    anything but a symbol), is a number, or divides by an identical zero. pi is a
    variable, as SymPy's factor takes it (it is transcendental: no polynomial with
    rational coefficients vanishes at it). With `half_angle`, the trig functions are
    rational functions of ``tan(angle/2)`` (:func:`rational_zero`)."""
    gens = _generators(expr, half_angle)
    if not gens:
        return None  # a number (SymPy's own), or not a rational function
    order = _sort_gens(tuple(gens))
    ctx = fmpq_mpoly_ctx.get(tuple(f"x{i}" for i in range(len(order))), "lex")
    one, zero = ctx.from_dict({}) + 1, ctx.from_dict({})
    place = dict(zip(order, ctx.gens(), strict=True))
    seen: dict[Any, tuple[Any, Any]] = {}

    def trig(node: Any) -> tuple[Any, Any]:
        t = place[_half(node.args[0])]
        if isinstance(node, sp.sin):
            return 2 * t, 1 + t * t
        if isinstance(node, sp.cos):
            return 1 - t * t, 1 + t * t
        return 2 * t, 1 - t * t

    def fraction(node: Any) -> tuple[Any, Any]:
        if node in place:
            return place[node], one
        if node in seen:
            return seen[node]
        if node.is_Rational:
            out = (one * fmpq(int(node.p), int(node.q)), one)
        elif half_angle and isinstance(node, (sp.sin, sp.cos, sp.tan)):
            out = trig(node)
        elif node.is_Add:  # over the least common denominator (the terms' gcds):
            num, den = zero, one  # a product of them all would swell with every term
            for term in node.args:
                n, d = fraction(term)
                if d == den:
                    num = num + n
                elif d == one:
                    num = num + n * den
                else:
                    common = den.gcd(d)
                    num, den = num * (d / common) + n * (den / common), den * (d / common)
            out = (num, den)
        elif node.is_Mul:
            num, den = one, one
            for factor_ in node.args:
                n, d = fraction(factor_)
                num, den = num * n, den * d
            out = (num, den)
        else:  # an integer power
            n, d = fraction(node.base)
            k = int(node.exp)
            if k < 0 and n == 0:
                raise ZeroDivisionError
            out = (n ** k, d ** k) if k >= 0 else (d ** -k, n ** -k)
        seen[node] = out
        return out

    try:
        num, den = fraction(expr)
    except ZeroDivisionError:
        return None
    return None if den == 0 else (order, num, den)


def expand_polynomial(expr: Any) -> Any:
    """``sympy.expand(expr)`` for a polynomial in symbols, pi and sines and cosines of
    symbols, multiplied out in FLINT: the same expression (SymPy's sum of monomials is
    canonical however it is built); by SymPy itself for anything else.

    Examples
    --------
    >>> import sympy as sp
    >>> x, t = sp.Symbol("x"), sp.Symbol("t", real=True)
    >>> poly = (x + sp.cos(t)) ** 2 * (2 * x - 3)
    >>> expand_polynomial(poly) == sp.expand(poly)
    True
    """
    try:
        found = _fraction(expr)
        if found is None or found[2] != 1:
            return sp.expand(expr)
        order, num, _ = found
        rep = {m: sp.Rational(int(c.p), int(c.q)) for m, c in num.to_dict().items()}
    except _FLINT_FAILURES:
        return sp.expand(expr)
    return basic_from_dict(rep, *order) if rep else sp.Integer(0)


def _integral(p: Any) -> tuple[Any, int]:
    """A rational polynomial as an integer one and the scale taken out: ``p = q / s``."""
    terms = p.to_dict()
    scale = lcm(*(int(c.q) for c in terms.values()))
    ctx = fmpz_mpoly_ctx.get(tuple(p.context().names()), "lex")
    return ctx.from_dict({m: int(c * scale) for m, c in terms.items()}), scale
