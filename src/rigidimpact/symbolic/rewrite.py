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

import functools

import sympy as sp

from rigidimpact.symbolic.flint_poly import expand_polynomial, factor, flint_polynomials

__all__ = ["tidy", "recognise", "solve_linear", "polynomial_roots", "pythagorean"]


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
    expr = sp.sympify(expr)
    if expr.is_Rational or expr.is_Float:  # nothing to put over one denominator
        return expr
    # each expression is rewritten once a process: a derivation and the checks that
    # follow it tidy the same results again (not with floats in it: SymPy counts two
    # Floats of one value and different precisions as equal)
    exact = not expr.has(sp.Float)
    if exact and expr in _TIDIED:
        return _TIDIED[expr]
    shielded, back = _shield(expr)
    if back:
        out = _positive_lead(sp.together(_tidy(shielded).xreplace(back)))
    else:
        out = _tidy(expr)
    if exact and len(_TIDIED) < _KEPT:
        _TIDIED[expr] = out
    return out


_TIDIED: dict[sp.Expr, sp.Expr] = {}  # what tidy gave for each exact expression
_KEPT = 20_000  # at most this many are kept (a long session's memory stays bounded)


def _shield(expr: sp.Expr) -> tuple[sp.Expr, dict[sp.Dummy, sp.Expr]]:
    """Irrational constants such as sqrt(2) as positive stand-in symbols.

    ``cancel`` and ``factor`` over an algebraic extension (the rationals with sqrt(2)
    adjoined) are orders of magnitude slower than over the rationals; with stand-ins the
    algebra stays rational, and putting the constants back evaluates what they fix
    (``sqrt(2)**2 -> 2``).

    Examples
    --------
    >>> shielded, back = _shield(sp.sqrt(2) * sp.Symbol("x"))
    >>> shielded.has(sp.sqrt(2)), list(back.values()), shielded.xreplace(back)
    (False, [sqrt(2)], sqrt(2)*x)
    """
    constants = sorted((a for a in expr.atoms(sp.Pow)  # radicals of rationals only:
                        if a.base.is_Rational and a.exp.is_Rational  # sin(1)**2 must stay
                        and not a.exp.is_Integer and a.is_positive),  # for sin^2 + cos^2
                       key=sp.default_sort_key)
    if not constants:
        return expr, {}
    stand_ins = {c: sp.Dummy(f"c{k}", positive=True) for k, c in enumerate(constants)}
    return expr.xreplace(stand_ins), {d: c for c, d in stand_ins.items()}


def _tidy(expr: sp.Expr) -> sp.Expr:
    # SymPy's factorisation, made in FLINT (the one fraction and its factors) where the
    # expression is a rational function of symbols and their sines and cosines, and by
    # SymPy with its polynomials of several variables factored by FLINT elsewhere: the
    # same answer, in compiled code (flint_poly's notes)
    with flint_polynomials():
        return _tidied(expr)


def _tidied(expr: sp.Expr) -> sp.Expr:
    # ``factor`` puts the expression over one denominator and factors both sides, so
    # common factors cancel without a separate (and as costly) ``cancel`` first
    best = _positive_lead(factor(expr))
    # a numeric angle under a square root (Stronge's law with the data in numbers) makes
    # each trial factorisation cost seconds; such a formula is left as factored
    radicals = any(not p.exp.is_Integer and p.base.has(sp.sin, sp.cos)
                   for p in best.atoms(sp.Pow))
    angles = {f.args[0] for f in best.atoms(sp.sin, sp.cos)
              if not (radicals and f.args[0].is_number)}
    for angle in sorted(angles, key=sp.default_sort_key):
        s, c = sp.sin(angle), sp.cos(angle)
        expanded = _expanded(best)
        for old, new in ((c, s), (s, c)):
            swapped = _pythagoras(expanded, old, new)
            if swapped == expanded:  # no power of `old` to rewrite
                continue
            candidate = _positive_lead(factor(swapped))
            if sp.count_ops(candidate) < sp.count_ops(best):
                best, expanded = candidate, _expanded(candidate)
    return best


def _expanded(factored: sp.Expr) -> sp.Expr:
    """A factored fraction with its numerator and denominator multiplied out: each
    power of sin or cos is then in sight of :func:`_pythagoras`. Its factors are
    already coprime, so no gcd is needed (``cancel`` would seek one). The rewrite
    ``cos^2 -> 1 - sin^2`` maps numerator and denominator alike, so what ``factor``
    makes of the result does not depend on how the fraction was written.

    Examples
    --------
    >>> x, t = sp.Symbol("x"), sp.Symbol("t", real=True)
    >>> _expanded((x + 1) * sp.cos(t) / (x * (x - sp.cos(t))))
    (x*cos(t) + cos(t))/(x**2 - x*cos(t))
    """
    numerator, denominator = sp.fraction(factored)
    return expand_polynomial(numerator) / expand_polynomial(denominator)


def _pythagoras(expr: sp.Expr, old: sp.Expr, other: sp.Expr) -> sp.Expr:
    """Write every power ``old**n`` with ``|n| >= 2`` as ``(1 - other**2)**(n//2)`` times
    ``old`` for odd n, so no square root (an absolute value in disguise) ever appears.

    Examples
    --------
    >>> t = sp.Symbol("t", real=True)
    >>> _pythagoras(sp.sin(t)**3, sp.sin(t), sp.cos(t))
    (1 - cos(t)**2)*sin(t)
    """

    def is_power(p: sp.Basic) -> bool:
        return (isinstance(p, sp.Pow) and p.base == old and p.exp.is_Integer
                and abs(p.exp) >= 2)

    def rewrite(p: sp.Pow) -> sp.Expr:
        pairs, odd = divmod(abs(int(p.exp)), 2)
        return ((1 - other**2) ** pairs * old**odd) ** (1 if p.exp > 0 else -1)

    return expr.replace(is_power, rewrite)


def _positive_lead(expr: sp.Expr) -> sp.Expr:
    """Move a leading minus sign into a sum in the numerator: -(a - b) c -> (b - a) c.

    Examples
    --------
    >>> a, b, c = sp.symbols("a b c", positive=True)
    >>> _positive_lead(-(a - b) * c)
    c*(-a + b)
    """
    coeff, rest = expr.as_coeff_Mul()
    if not (coeff.is_negative and isinstance(rest, sp.Mul)):
        return expr
    factors = list(rest.args)
    sums = [k for k, f in enumerate(factors) if isinstance(f, sp.Add)]
    if not sums:
        return expr

    def negativity(k: int) -> tuple[int, bool]:
        terms = factors[k].args
        negative = sum(1 for t in terms if t.could_extract_minus_sign())
        constant = factors[k].as_coeff_Add()[0]
        return 2 * negative - len(terms), bool(constant.is_negative)

    flip = max(sums, key=negativity)  # the sum that reads best with its sign reversed
    if negativity(flip)[0] < 0:  # reversing it would add minus signs
        return expr
    factors[flip] = -factors[flip]
    return -coeff * sp.Mul(*factors)


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
    line = _numerator_poly(name - definition, eliminate)
    if line.degree() != 1:
        raise ValueError(f"{name} = {definition} is not linear in {eliminate}")
    slope, offset = line.all_coeffs()
    return tidy(expr.xreplace({eliminate: -offset / slope}))


def solve_linear(equations, unknowns) -> dict[sp.Symbol, sp.Expr]:
    """The unique solution of equations linear in `unknowns` (expressions equal to zero),
    each value tidied; no general-purpose solver, so no blanket simplification.

    Examples
    --------
    >>> x, y, a = sp.symbols("x y a")
    >>> solve_linear([x + y - a, x - y], [x, y])
    {x: a/2, y: a/2}
    """
    unknowns = list(unknowns)
    matrix, rhs = sp.linear_eq_to_matrix(list(equations), unknowns)
    if matrix.shape[0] != matrix.shape[1] or tidy(matrix.det()) == 0:
        raise ValueError("the equations do not fix every unknown once")
    return {u: tidy(v) for u, v in zip(unknowns, matrix.LUsolve(rhs), strict=True)}


def polynomial_roots(expr: sp.Expr, x: sp.Symbol) -> list[sp.Expr]:
    """The distinct roots in `x` of the numerator of `expr`, a polynomial in `x`, each in
    closed form; an error when some root has none (a general solver would hand back an
    implicit root object instead).

    Examples
    --------
    >>> x, a = sp.symbols("x a", positive=True)
    >>> polynomial_roots((x**2 - a**2) / x, x)
    [-a, a]
    """
    line = _numerator_poly(expr, x)
    if line.degree() < 1:
        return []
    found = sp.roots(line)
    if sum(found.values()) != line.degree():
        raise ArithmeticError(f"not every root of {line.as_expr()} in {x} has a closed form")
    return sorted(found, key=sp.default_sort_key)


@functools.lru_cache(maxsize=256)
def _numerator_poly(expr: sp.Expr, x: sp.Symbol) -> sp.Poly:
    """The numerator of `expr` over one denominator, as a polynomial in `x` (made once
    for each expression: a group is recognised in each result of a derivation)."""
    return sp.Poly(sp.expand(sp.fraction(sp.together(expr))[0]), x)


def pythagorean(expr: sp.Expr) -> sp.Expr:
    """`expr` simplified by sin^2 + cos^2 = 1 alone, fast, where it is a polynomial in
    the sines and cosines of its angles (a 3-D body's contact rows: products of
    direction cosines): its remainder on division by sin(a)^2 + cos(a)^2 - 1 for each
    angle a, sines first (a Groebner basis, so the remainder is the one normal form of
    the expression modulo those identities). Where that remainder is of degree at most
    one in every sine and cosine it is kept: on a turned body's rows along its frame's
    axes it is ``trigsimp``'s own answer, found in milliseconds where ``trigsimp`` takes
    seconds (along another direction an equal form); elsewhere, and for anything
    else, ``trigsimp``.

    Examples
    --------
    >>> a, b = sp.symbols("a b")
    >>> pythagorean(sp.sin(a)**2 * sp.sin(b) + sp.cos(a)**2 * sp.sin(b))
    sin(b)
    """
    expr = sp.expand(sp.sympify(expr))
    angles = sorted({f.args[0] for f in expr.atoms(sp.sin, sp.cos)}, key=sp.default_sort_key)
    if not angles:
        return expr
    gens = [f(a) for a in angles for f in (sp.sin, sp.cos)]
    try:
        poly = sp.Poly(expr, *gens)
    except sp.PolynomialError:
        return sp.trigsimp(expr)
    if any(g.free_symbols & set().union(*(a.free_symbols for a in angles))
           for g in poly.free_symbols_in_domain):
        return sp.trigsimp(expr)  # an angle's symbol outside its sine and cosine
    identities = [sp.sin(a) ** 2 + sp.cos(a) ** 2 - 1 for a in angles]
    _, remainder = sp.reduced(poly.as_expr(), identities, *gens, order="lex")
    reduced = sp.Poly(remainder, *gens)
    if any(d > 1 for monomial in reduced.monoms() for d in monomial):
        return sp.trigsimp(expr)
    return sp.expand(remainder)
