"""Comparing two results: an exact symbolic zero *and* agreement at high precision.

Two independent tests must both pass for a result to count as equal to a reference:

* symbolic: the difference is an exact zero after every sine, cosine and tangent of an
  angle is replaced by its rational form in ``t = tan(angle/2)`` and the whole is put
  over one denominator (a decision procedure for rational trig identities, where a
  weak simplifier could fail to see a zero; when the expanded difference cancels term
  by term, that is already the proof and the procedure is skipped);
* numeric: at seeded random points within the symbols' assumptions, both sides are
  evaluated to 50 significant digits and must agree to 40 (so a lucky rewrite cannot
  pass alone, nor a lucky sample).

This is the machinery every check list uses (``rigidimpact.verify``, the re-strike's
checks in ``rigidimpact.analyses.restrike``); it imports none of them.

Examples
--------
>>> t = sp.Symbol("t", real=True)
>>> agree(sp.sin(t)**2, 1 - sp.cos(t)**2).passed
True
>>> agree(sp.sin(t), sp.cos(t)).passed
False
"""

from __future__ import annotations

import random
from collections.abc import Iterable
from dataclasses import dataclass

import mpmath
import sympy as sp

from rigidimpact.symbolic.evaluate import Unsupported, value_at
from rigidimpact.symbolic.flint_poly import rational_zero
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Verdict", "agree", "same_equation", "symbolic_zero", "all_of", "DIGITS",
           "TOLERANCE", "SEED", "SAMPLES"]

DIGITS = 50
TOLERANCE = mpmath.mpf(10) ** -40
SEED = 20070301  # numeric spot checks are reproducible
SAMPLES = 6

@dataclass(frozen=True)
class Verdict:
    """Whether a comparison passed, and what it saw."""

    passed: bool
    detail: str


def _rational_trig(expr: sp.Expr) -> sp.Expr:
    """Replace sin, cos, tan of each angle by rational functions of tan(angle/2)."""
    replacements = {}
    for k, angle in enumerate(sorted({f.args[0] for f in expr.atoms(sp.sin, sp.cos, sp.tan)},
                                     key=sp.default_sort_key)):
        t = sp.Dummy(f"t{k}", real=True)
        replacements[sp.sin(angle)] = 2 * t / (1 + t**2)
        replacements[sp.cos(angle)] = (1 - t**2) / (1 + t**2)
        replacements[sp.tan(angle)] = 2 * t / (1 - t**2)
    return expr.xreplace(replacements)


def symbolic_zero(expr: sp.Expr) -> bool:
    """True when `expr` is exactly zero as a rational function of its symbols and trig.

    Examples
    --------
    >>> t = sp.Symbol("t", real=True)
    >>> symbolic_zero(sp.sin(t)**2 + sp.cos(t)**2 - 1)
    True
    """
    expr = sp.sympify(expr)
    # one fraction p / q: it is zero exactly where its numerator is zero (no gcd needed
    # to decide it), made in FLINT, each trig function put in tan(angle/2) as it is
    # read, where every angle is a symbol
    decided = rational_zero(expr, half_angle=True)
    if decided is not None:
        return decided
    rational = _rational_trig(expr)
    decided = rational_zero(rational)
    if decided is not None:
        return decided
    if sp.expand(expr) == 0:  # cancels term by term: a proof of zero, found cheaply
        return True
    numerator, _ = sp.fraction(sp.together(rational))
    return sp.expand(numerator) == 0


def _sample(sym: sp.Symbol, rng: random.Random) -> sp.Rational:
    """A random exact value allowed by the symbol's assumptions."""
    if sym.name == "e" or sym.is_nonnegative and not sym.is_positive:
        value = rng.uniform(0.0, 1.0)
    elif sym.is_positive:
        value = 10 ** rng.uniform(-0.7, 0.7)
    else:
        value = rng.uniform(-3.0, 3.0)
    return sp.Rational(repr(value))


def _points(exprs: Iterable[sp.Expr], seed: int) -> list[dict[sp.Symbol, sp.Rational]]:
    symbols = sorted(set().union(*(sp.sympify(x).free_symbols for x in exprs)),
                     key=lambda s: s.name)
    rng = random.Random(seed)
    return [{s: _sample(s, rng) for s in symbols} for _ in range(SAMPLES)]


def _value(expr: sp.Expr, point: dict) -> mpmath.mpf:
    """`expr` at `point`, in arithmetic of twice the digits compared (so that up to 50
    digits may cancel), or by evalf's adaptive evaluation where the tree has a node
    :func:`~rigidimpact.symbolic.evaluate.value_at` does not take."""
    with mpmath.workdps(DIGITS + 10):
        try:
            return mpmath.mpmathify(value_at(expr, point, 2 * DIGITS))
        except Unsupported:
            return mpmath.mpmathify(sp.sympify(expr).xreplace(point).evalf(DIGITS + 10))


def agree(derived: sp.Expr, reference: sp.Expr, seed: int = SEED) -> Verdict:
    """Do `derived` and `reference` agree symbolically *and* numerically?

    Examples
    --------
    >>> e = sp.Symbol("e", nonnegative=True)
    >>> agree(e * (1 + e), e + e**2)
    Verdict(passed=True, detail='symbolic zero; 6 points agree to 1e-40 (seed 20070301)')
    """
    derived, reference = sp.sympify(derived), sp.sympify(reference)
    exact = symbolic_zero(derived - reference)
    worst = mpmath.mpf(0)
    with mpmath.workdps(DIGITS + 10):
        for point in _points((derived, reference), seed):
            a, b = _value(derived, point), _value(reference, point)
            scale = max(abs(a), abs(b), mpmath.mpf(10) ** -30)
            worst = max(worst, abs(a - b) / scale)
    numeric = worst <= TOLERANCE
    detail = (f"{'symbolic zero' if exact else 'NOT a symbolic zero'}; "
              f"{SAMPLES} points {'agree to 1e-40' if numeric else 'differ by'}"
              f"{'' if numeric else ' ' + mpmath.nstr(worst, 3)} (seed {seed})")
    return Verdict(exact and numeric, detail)


def same_equation(derived: sp.Expr, reference: sp.Expr, unknowns: Iterable[sp.Symbol],
                  seed: int = SEED) -> Verdict:
    """Are ``derived = 0`` and ``reference = 0`` the same equation in the `unknowns`?

    They are when one is the other times a factor that is free of the unknowns and
    cannot vanish (by the symbols' assumptions).

    Examples
    --------
    >>> x, M = sp.Symbol("x"), sp.Symbol("M", positive=True)
    >>> same_equation(2 * M * x - 4 * M, x - 2, [x]).passed
    True
    >>> same_equation(x - 2, x - 3, [x]).passed
    False
    """
    ratio = tidy(_rational_trig(sp.sympify(derived) / sp.sympify(reference)))
    if ratio.free_symbols & set(unknowns) or not ratio.is_nonzero:
        return Verdict(False, f"not proportional: ratio {ratio}")
    verdict = agree(derived, ratio * reference, seed)
    return Verdict(verdict.passed, f"proportional with factor {ratio}; {verdict.detail}")


def all_of(verdicts: Iterable[tuple[str, Verdict]]) -> Verdict:
    """One verdict for several named ones: failed if any failed, naming each failure.

    Examples
    --------
    >>> all_of([("a", Verdict(True, "ok")), ("b", Verdict(False, "off"))]).detail
    'b: off'
    """
    verdicts = list(verdicts)
    failed = [f"{name}: {v.detail}" for name, v in verdicts if not v.passed]
    if failed:
        return Verdict(False, "; ".join(failed))
    return Verdict(True, "; ".join(f"{name}: {v.detail}" for name, v in verdicts[:1])
                   + (f" (and {len(verdicts) - 1} more)" if len(verdicts) > 1 else ""))
