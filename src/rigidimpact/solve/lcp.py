"""The linear complementarity problem of contacts acting together, by Lemke's method.

Find z >= 0 with w = q + M z >= 0 and z_i w_i = 0 for every i: the contacts' impulses z
with their velocities after w (less their targets), each contact either pushing and
meeting its law or released and separating. Enumerating the sets of acting contacts
costs 2^n; Lemke's complementary pivoting walks from one basis to the next and ends in
a number of pivots that grows with n, not 2^n, for the positive semidefinite M = W of
rigid contacts. The arithmetic is exact (Python's ``Fraction``), and ties in the ratio
test are broken lexicographically, so degenerate problems (contacts at rest before, as
in a cradle) cannot cycle. SciPy has no LCP solver and the maintained LCP packages are
floating point; exact answers are the point here, so it is written out (Lemke 1965;
Cottle, Pang and Stone, The Linear Complementarity Problem, section 4.4).

Examples
--------
>>> from fractions import Fraction as F
>>> lemke([[F(2), F(1)], [F(1), F(2)]], [F(-1), F(-1)])
[Fraction(1, 3), Fraction(1, 3)]
>>> lemke([[F(1)]], [F(2)])  # already separating: no impulse
[Fraction(0, 1)]
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

__all__ = ["lemke", "NoSolution"]


class NoSolution(ValueError):
    """Lemke's method ended on a ray: the problem has no solution (or M is not of the
    class it is sure to solve)."""


def lemke(M: Sequence[Sequence[Fraction]], q: Sequence[Fraction],
          max_pivots: int | None = None) -> list[Fraction]:
    """z >= 0 with q + M z >= 0 and complementary, for exact `M` and `q`."""
    n = len(q)
    if all(x >= 0 for x in q):
        return [Fraction(0)] * n
    # the tableau [I | -M | -d | q], d = 1: columns 0..n-1 are w, n..2n-1 are z, 2n is
    # the artificial z0; basis[i] is the column basic in row i
    rows = [[Fraction(int(i == j)) for j in range(n)] + [-M[i][j] for j in range(n)]
            + [Fraction(-1), Fraction(q[i])] for i in range(n)]
    basis = list(range(n))
    artificial, last = 2 * n, 2 * n + 1
    entering = artificial
    leaving_row = min(range(n), key=lambda i: (q[i], i))  # the most negative q
    limit = max_pivots if max_pivots is not None else 50 * n + 100
    for _ in range(limit):
        _pivot(rows, leaving_row, entering)
        left = basis[leaving_row]
        basis[leaving_row] = entering
        if left == artificial:
            break
        entering = left + n if left < n else left - n  # the complement of what left
        candidates = [i for i in range(n) if rows[i][entering] > 0]
        if not candidates:
            raise NoSolution("Lemke's method ended on a ray")
        leaving_row = _lexicographic_min(rows, candidates, entering, n)
    else:
        raise NoSolution(f"no solution within {limit} pivots")
    z = [Fraction(0)] * n
    for i, column in enumerate(basis):
        if n <= column < 2 * n:
            z[column - n] = rows[i][last]
    return z


def _pivot(rows: list[list[Fraction]], r: int, c: int) -> None:
    pivot = rows[r][c]
    top = [x / pivot if x else x for x in rows[r]]
    rows[r] = top
    nonzero = [j for j, x in enumerate(top) if x]  # rows stay sparse for chains
    for i, row in enumerate(rows):
        factor = row[c]
        if i != r and factor:
            for j in nonzero:
                row[j] -= factor * top[j]


def _lexicographic_min(rows: list[list[Fraction]], candidates: list[int], c: int,
                       n: int) -> int:
    """The leaving row: the least ratio q_i / a_ic, ties broken by the rows of the basis
    inverse (the identity's columns) divided by a_ic, compared in order."""
    last = len(rows[0]) - 1
    ratios = {i: rows[i][last] / rows[i][c] for i in candidates}
    least = min(ratios.values())
    tied = [i for i in candidates if ratios[i] == least]
    for j in range(n):
        if len(tied) == 1:
            break
        column = {i: rows[i][j] / rows[i][c] for i in tied}
        smallest = min(column.values())
        tied = [i for i in tied if column[i] == smallest]
    return tied[0]
