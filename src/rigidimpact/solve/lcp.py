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

Lemke's dense tableau costs n^2 per pivot, too much at a thousand contacts. There the
problem is solved in floating point by block principal pivoting (Judice and Pires,
Comput. Oper. Res. 21, 1994), each step one sparse factorisation of the acting contacts'
block of W by SciPy's SuperLU (a chain's W is banded, a cluster's sparse), falling back
to Murty's one-at-a-time rule, which always ends for a positive definite W, when the
block steps stop gaining. Its answer comes with a certificate, the largest violation of
the three conditions relative to the largest closing speed; with rational data the
acting set it found is then solved again exactly (:func:`solve_exactly`, a sparse
elimination in reverse Cuthill-McKee order) and the three conditions checked exactly, so
the answer is exact when the check passes.

Examples
--------
>>> from fractions import Fraction as F
>>> lemke([[F(2), F(1)], [F(1), F(2)]], [F(-1), F(-1)])
[Fraction(1, 3), Fraction(1, 3)]
>>> lemke([[F(1)]], [F(2)])  # already separating: no impulse
[Fraction(0, 1)]
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import mpmath
import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.matrices import DomainMatrix

from rigidimpact.lazy import deferred
from rigidimpact.symbolic.rewrite import tidy

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["lemke", "NoSolution", "pivoting", "proximal", "residual", "solve_exactly", "confirm",
           "least_norm", "sparse_solve", "confirm_by_rows"]


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


def lemke_float(M: np.ndarray, q: np.ndarray, max_pivots: int | None = None
                ) -> np.ndarray | None:
    """Lemke's method in floating point (a dense tableau, one rank-one update a pivot):
    the z it ends with, or None where it ends on a ray or runs past its pivots. Its
    answer is a guess of which unknowns are positive, to be confirmed exactly
    (:func:`confirm_support`)."""
    n = len(q)
    if (q >= 0).all():
        return np.zeros(n)
    T = np.hstack([np.eye(n), -M, -np.ones((n, 1)), q.reshape(-1, 1)]).astype(float)
    basis = list(range(n))
    artificial, last = 2 * n, 2 * n + 1
    entering, row = artificial, int(np.argmin(q))
    scale = max(1.0, float(np.abs(T).max()))
    for _ in range(max_pivots or 50 * n + 100):
        T[row] /= T[row, entering]
        column = T[:, entering].copy()
        column[row] = 0.0
        T -= np.outer(column, T[row])
        left, basis[row] = basis[row], entering
        if left == artificial:
            z = np.zeros(n)
            for i, b in enumerate(basis):
                if n <= b < 2 * n:
                    z[b - n] = T[i, last]
            return z
        entering = left + n if left < n else left - n
        a = T[:, entering]
        candidates = np.nonzero(a > 1e-12 * scale)[0]
        if not len(candidates):
            return None
        ratios = T[candidates, last] / a[candidates]
        least = ratios.min()
        tied = candidates[ratios <= least + 1e-11 * max(1.0, abs(least))]
        for j in range(n):  # ties broken lexicographically, as in the exact tableau
            if len(tied) == 1:
                break
            column = T[tied, j] / a[tied]
            smallest = column.min()
            tied = tied[column <= smallest + 1e-11 * max(1.0, abs(smallest))]
        row = int(tied[0])
    return None


def confirm_support(M: Sequence[dict[int, Any]], q: Sequence[Any],
                    support: Sequence[int], raised: Sequence[int] = (),
                    times: Callable[[list[Any]], list[Any]] | None = None
                    ) -> list[Any] | None:
    """The exact z whose positive part is on `support` (M given as sparse rows):
    ``(q + M z)_i = 0`` there, z zero elsewhere, solved in the rationals; each index in
    `raised` (an unknown the equations leave free, such as a released contact's slack)
    is then raised to the least value >= 0 that keeps every row it enters non-negative.
    None unless z >= 0, q + M z >= 0 and z (q + M z) = 0 hold exactly (then z solves
    the LCP). M's and q's entries are elements of SymPy's QQ (python-flint's fmpq where
    it is installed: the arithmetic of thousands of contacts stays in C) or Fractions;
    z comes back in QQ. `times`, where given, is M z by another way (the same numbers:
    a product through sparse factors of M, where M itself is dense)."""
    n = len(q)
    q = [_qq(x) for x in q]
    if any(not isinstance(x, QQ.dtype) for row in M for x in row.values()):
        M = [{j: _qq(x) for j, x in row.items()} for row in M]
    zero = QQ(0)
    support = list(support)
    z = [zero] * n
    if support:
        where = {j: k for k, j in enumerate(support)}
        size = len(support)
        entries = {k: {where[j]: x for j, x in M[i].items() if j in where}
                   for k, i in enumerate(support)}
        # a sparse block (a chain's, a cluster's) by elimination in Markowitz order,
        # within a share of the work a dense solve costs; a dense one (a fan's) by FLINT
        found = sparse_solve(entries, {k: -q[i] for k, i in enumerate(support)},
                                budget=size * size // 4 + 10_000)
        if found is None:
            block = DomainMatrix({k: row for k, row in entries.items() if row},
                                 (size, size), QQ)
            rhs = DomainMatrix({k: {0: -q[i]} for k, i in enumerate(support) if q[i]},
                               (size, 1), QQ)
            try:
                solved = block.to_dense().lu_solve(rhs.to_dense())
            except Exception:  # noqa: BLE001 - singular: the support does not fix z
                return None
            found = {k: solved[k, 0].element for k in range(size)}
        for k, i in enumerate(support):
            z[i] = found[k]
    if any(x < 0 for x in z):
        return None
    # w = q + M z, a sparse product in QQ; each raised unknown then enters its column
    if times is not None:
        w = [a + b for a, b in zip(q, times(z), strict=True)]
    else:
        rows = DomainMatrix({i: row for i, row in enumerate(M) if row}, (n, n), QQ)
        column = DomainMatrix({j: {0: x} for j, x in enumerate(z) if x}, (n, 1), QQ)
        product = (rows * column).to_sdm()
        w = [q[i] + product[i][0] if i in product else q[i] for i in range(n)]
    if raised:
        columns: dict[int, list[tuple[int, Any]]] = {k: [] for k in raised}
        for i, row in enumerate(M):
            for k in columns.keys() & row.keys():
                columns[k].append((i, row[k]))
        for k in raised:
            z[k] = max([zero, *(-w[i] / m for i, m in columns[k] if m > 0)])
            if z[k]:
                for i, m in columns[k]:
                    w[i] += m * z[k]
    if any(x < 0 for x in w) or any(z[i] and w[i] for i in range(n)):
        return None
    return z


def _qq(x: Any) -> Any:
    """x (a Fraction, an int or already QQ's) as an element of QQ."""
    if isinstance(x, Fraction):
        return QQ(x.numerator, x.denominator)
    return x if isinstance(x, QQ.dtype) else QQ(x)


# ---- floating point at scale, with an exact check ------------------------------------

def residual(W: Any, q: np.ndarray, z: np.ndarray) -> float:
    """The largest violation of ``z >= 0``, ``w = q + W z >= 0`` and ``z_i w_i = 0``
    (as ``|min(z_i, w_i)|``), relative to the largest ``|q_i|``: zero for an exact
    solution, about the rounding error for a good floating-point one."""
    w = q + W @ z
    scale = max(float(np.abs(q).max()), 1e-300)
    return float(np.abs(np.minimum(z, w)).max()) / scale if len(q) else 0.0


def pivoting(W: Any, q: np.ndarray, shift: float = 0.0, start: np.ndarray | None = None,
             max_steps: int | None = None) -> tuple[np.ndarray, int, np.ndarray]:
    """z >= 0 with ``q + (W + shift I) z >= 0``, complementary, for a sparse positive
    (semi)definite W and ``shift >= 0`` (positive for a singular W), by block principal
    pivoting from the acting set `start` (default: every contact); returns (z, steps,
    the acting set)."""
    import scipy.sparse as sps
    from scipy.sparse.linalg import splu

    n = len(q)
    A = sps.csc_matrix(W) + shift * sps.identity(n, format="csc")
    tol = 1e-13 * max(float(np.abs(q).max()), 1e-300)
    free = np.ones(n, dtype=bool) if start is None else start.copy()
    best, chances = n + 1, 3
    max_steps = max_steps or 10 * n + 50
    for step in range(1, max_steps + 1):
        z = np.zeros(n)
        index = np.flatnonzero(free)
        if len(index):
            block = A[index][:, index].tocsc()
            z[index] = splu(block, permc_spec="MMD_AT_PLUS_A").solve(-q[index])
        w = q + A @ z
        bad = (free & (z < -tol)) | (~free & (w < -tol))
        count = int(bad.sum())
        if count == 0:
            z[~free] = 0.0
            return np.maximum(z, 0.0), step, free
        if count < best:
            best, chances = count, 3
            free ^= bad
        elif chances > 0:
            chances -= 1
            free ^= bad
        else:  # Murty's rule: flip only the least infeasible index
            free[np.flatnonzero(bad)[0]] ^= True
    raise NoSolution(f"block principal pivoting did not end in {max_steps} steps")


def proximal(W: Any, q: np.ndarray, shift: float, tolerance: float = 1e-13,
             max_rounds: int = 500) -> tuple[np.ndarray, int]:
    """The problem of a singular positive semidefinite W by the proximal point method:
    each round solves the positive definite problem of ``W + shift I`` with ``q`` moved
    by ``-shift z`` of the round before, whose solutions converge to one of W's (the
    motion after is unique, the impulses are not; starting from zero they stay close to
    the least-norm ones). Returns (z, rounds) once :func:`residual` is below
    `tolerance`."""
    z = np.zeros(len(q))
    acting = None
    for rounds in range(1, max_rounds + 1):
        z, _, acting = pivoting(W, q - shift * z, shift, acting)
        if residual(W, q, z) < tolerance:
            return z, rounds
    return z, max_rounds


def solve_exactly(rows: dict[int, dict[int, Fraction]], rhs: dict[int, Fraction],
                  order: Sequence[int], budget: int = 20_000_000) -> dict[int, Fraction] | None:
    """The exact solution of a sparse symmetric system (``rows[i][j]``, indices in
    `order`), eliminated in that order without pivoting: None if a pivot is zero (the
    block is singular) or the work would pass `budget` entry updates (fill-in)."""
    rows = {i: dict(rows[i]) for i in order}
    rhs = {i: rhs.get(i, Fraction(0)) for i in order}
    position = {i: k for k, i in enumerate(order)}
    work = 0
    for i in order:
        pivot = rows[i].get(i, Fraction(0))
        if pivot == 0:
            return None
        later = [j for j in rows[i] if position[j] > position[i]]
        for j in later:
            factor = rows[j].get(i, Fraction(0)) / pivot
            if factor == 0:
                continue
            target = rows[j]
            for k, value in rows[i].items():
                if position[k] > position[i]:
                    target[k] = target.get(k, Fraction(0)) - factor * value
            target.pop(i, None)
            rhs[j] -= factor * rhs[i]
            work += len(rows[i])
            if work > budget:
                return None
    x: dict[int, Fraction] = {}
    for i in reversed(order):
        total = rhs[i] - sum((v * x[k] for k, v in rows[i].items()
                              if position[k] > position[i]), Fraction(0))
        x[i] = total / rows[i][i]
    return x


def sparse_solve(rows: dict[int, dict[int, Any]], rhs: dict[int, Any],
                 budget: int = 20_000_000) -> dict[int, Any] | None:
    """The exact solution of a square sparse system ``rows[i][j] x_j = rhs[i]`` (numbers
    of one exact field), not necessarily symmetric, by Gaussian elimination in Markowitz
    order: each step takes the equation with the fewest entries left and, in it, the
    unknown that the fewest other equations hold, so a banded system (a chain's) fills
    in nothing beyond its band. Exact numbers need no pivoting for size: any entry that
    is not zero serves. None when the system is singular or the work would pass
    `budget` entry updates (then a dense solve is the cheaper way).

    The same order makes a saddle-point system cheap: a disc touched by one contact is
    eliminated first, then that contact, and a body that touches every contact (a
    fan's striker) last, so a fan of k discs costs O(k), not the O(k^3) of its dense W;
    a zero diagonal needs no 2x2 pivot, an entry off the diagonal serves.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> sparse_solve({0: {1: F(2)}, 1: {0: F(1), 1: F(1)}}, {0: F(4), 1: F(3)}, 100)
    {0: Fraction(1, 1), 1: Fraction(2, 1)}
    >>> sparse_solve({0: {0: F(1), 1: F(1)}, 1: {0: F(2), 1: F(2)}}, {0: F(1)}, 100)
    """
    import heapq

    rows = {i: dict(r) for i, r in rows.items()}
    if any(not r for r in rows.values()):
        return None
    b = {i: rhs.get(i, 0) for i in rows}
    columns: dict[int, set[int]] = {}
    for i, row in rows.items():
        for j in row:
            columns.setdefault(j, set()).add(i)
    if len(columns) != len(rows):
        return None
    heap = [(len(r), i) for i, r in rows.items()]
    heapq.heapify(heap)
    done: list[tuple[int, dict[int, Any], Any]] = []
    work = 0
    while rows:
        length, p = heapq.heappop(heap)
        if p not in rows or length != len(rows[p]):
            continue  # a stale entry: p was pushed again with its new length
        row = rows.pop(p)
        if not row:  # a row of zeros left: singular
            return None
        c = min(row, key=lambda j: (len(columns[j]), j))
        holders = columns.pop(c)
        holders.discard(p)
        for j in row:
            if j != c:
                columns[j].discard(p)
        work += len(holders) * len(row)
        if work > budget:
            return None
        pivot = row[c]
        for i in sorted(holders):
            target = rows[i]
            factor = target.pop(c) / pivot
            for j, value in row.items():
                if j == c:
                    continue
                new = target.get(j, 0) - factor * value
                if new:
                    if j not in target:
                        columns[j].add(i)
                    target[j] = new
                elif j in target:
                    del target[j]
                    columns[j].discard(i)
            b[i] -= factor * b[p]
            heapq.heappush(heap, (len(target), i))
        done.append((c, row, b[p]))
    x: dict[int, Any] = {}
    for c, row, total in reversed(done):
        for j, value in row.items():
            if j != c:
                total -= value * x[j]
        x[c] = total / row[c]
    return x


def confirm_by_rows(J_rows: Sequence[Sequence[tuple[int, Any]]], inverse_mass: Sequence[Any],
                    q: Sequence[Any], acting: Sequence[int]) -> list[Any] | None:
    """:func:`confirm` without W: the acting contacts' saddle-point system
    ``[M J_A^T; J_A 0] [x; z] = [0; q_A]`` (x = -du, so ``J_A M^-1 J_A^T z = -q_A``)
    solved exactly by :func:`sparse_solve`, then ``z >= 0`` and every released contact's
    ``q_i - J_i x >= 0`` checked exactly. W is never formed: a contact set in which one
    body touches every contact (W dense) costs what its rows cost."""
    n, acting = len(q), list(acting)
    size = len(inverse_mass)
    rows: dict[int, dict[int, Any]] = {}
    for i in acting:
        for j, value in J_rows[i]:
            rows.setdefault(j, {j: 1 / inverse_mass[j]})[size + i] = value
            rows.setdefault(size + i, {})[j] = value
    rhs = {size + i: q[i] for i in acting}
    solved = sparse_solve(rows, rhs) if acting else {}
    if solved is None:
        return None
    z = [q[0] * 0 for _ in range(n)]
    for i in acting:
        if solved.get(size + i, 0) < 0:
            return None
        z[i] = solved.get(size + i, z[i])
    inside = set(acting)
    for i in range(n):
        if i not in inside:
            w = q[i] - sum((value * solved.get(j, 0) for j, value in J_rows[i]), q[0] * 0)
            if w < 0:
                return None
    return z


def confirm(W: dict[int, dict[int, Fraction]], q: Sequence[Fraction],
            acting: Sequence[int]) -> list[Fraction] | None:
    """The exact solution with these contacts acting, if it is one: the acting block
    solved exactly, then ``z >= 0`` and ``q + W z >= 0`` checked exactly. None when the
    block is singular, too costly, or the set is not the solution's."""
    import scipy.sparse as sps
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    acting = list(acting)
    inside = set(acting)
    n = len(q)
    z = [Fraction(0)] * n
    if acting:
        local = {i: k for k, i in enumerate(acting)}
        pattern = sps.csr_matrix(
            ([1.0 for i in acting for j in W[i] if j in inside],
             ([local[i] for i in acting for j in W[i] if j in inside],
              [local[j] for i in acting for j in W[i] if j in inside])),
            shape=(len(acting), len(acting)))
        order = [acting[k] for k in reverse_cuthill_mckee(pattern, symmetric_mode=True)]
        block = {i: {j: v for j, v in W[i].items() if j in inside} for i in acting}
        solved = solve_exactly(block, {i: -q[i] for i in acting}, order)
        if solved is None:
            return None
        for i, value in solved.items():
            if value < 0:
                return None
            z[i] = value
    for i in range(n):
        if i not in inside:
            w = q[i] + sum((v * z[j] for j, v in W[i].items() if j in inside), Fraction(0))
            if w < 0:
                return None
    return z


def least_norm(matrix: sp.Matrix, rhs: sp.Matrix) -> sp.Matrix | None:
    """The least-norm solution of a consistent singular system of numbers, exactly
    (``A^T (A A^T)^+``, from a basis of A's rows); None when it has no solution.

    Examples
    --------
    >>> least_norm(sp.Matrix([[1, 1], [2, 2]]), sp.Matrix([2, 4])).T
    Matrix([[1, 1]])
    >>> least_norm(sp.Matrix([[1, 1], [1, 1]]), sp.Matrix([2, 3])) is None
    True

    Floats (a 50-digit solve) are rounded, so their rank is read from the singular
    values, as exactly as their digits allow:

    >>> third = sp.Float(1, 50) / 3
    >>> [float(x) for x in least_norm(sp.Matrix([[third, third], [1, 1]]),
    ...                               sp.Matrix([third, 1]))]
    [0.5, 0.5]
    """
    if matrix.has(sp.Float) or rhs.has(sp.Float):
        return _least_norm_rounded(matrix, rhs)
    augmented = sp.Matrix.hstack(matrix, rhs).to_DM(extension=True)
    reduced, pivots = augmented.rref()
    size = matrix.shape[1]
    if size in pivots:  # a row 0 = c != 0: inconsistent
        return None
    rows = reduced.to_Matrix()[:len(pivots), :]
    A, b = rows[:, :size], rows[:, size]
    return (A.T * (A * A.T).inv() * b).applyfunc(tidy)


def _least_norm_rounded(matrix: sp.Matrix, rhs: sp.Matrix) -> sp.Matrix | None:
    """:func:`least_norm` of rounded numbers (:func:`rounded_solve`)."""
    return rounded_solve(matrix, rhs)[0]


def rounded_solve(matrix: sp.Matrix, rhs: sp.Matrix) -> tuple[sp.Matrix | None, bool]:
    """A square or singular system of rounded numbers solved by the pseudo-inverse from
    the singular values at the numbers' own precision and ten digits more, a singular
    value below 1e-35 of the largest taken as zero (an elimination in rounded numbers
    finds a pivot in a rounding error and a huge wrong answer); None when the system is
    inconsistent beyond that rounding; and whether the solution is the only one (no
    singular value taken as zero).

    Examples
    --------
    >>> third = sp.Float(1, 50) / 3
    >>> found, unique = rounded_solve(sp.Matrix([[third, third], [1, 1]]),
    ...                               sp.Matrix([third, 1]))
    >>> [float(x) for x in found], unique
    ([0.5, 0.5], False)
    """
    digits = max([getattr(x, "_prec", 53) for x in (*matrix, *rhs) if x.is_Float]
                 + [53]) * 3 // 10
    with mpmath.workdps(digits + 10):
        A = mpmath.matrix([[mpmath.mpf(sp.Float(x, digits + 10)._to_mpmath(mpmath.mp.prec))
                            for x in matrix.row(i)] for i in range(matrix.rows)])
        b = mpmath.matrix([mpmath.mpf(sp.Float(x, digits + 10)._to_mpmath(mpmath.mp.prec))
                           for x in rhs])
        U, S, V = mpmath.svd_r(A)
        cut = max(S) * mpmath.mpf(10) ** -min(35, digits * 7 // 10) if len(S) else 0
        x = mpmath.matrix(A.cols, 1)
        unique = len(S) == A.cols and all(S[k] > cut for k in range(len(S)))
        for k in range(len(S)):
            if S[k] > cut:
                along = sum(U[i, k] * b[i] for i in range(A.rows)) / S[k]
                for j in range(A.cols):
                    x[j] += V[k, j] * along
        scale = max([abs(v) for v in b] + [max(S) * max([abs(v) for v in x] + [0])]
                    + [mpmath.mpf(10) ** -300])
        if max(abs(v) for v in A * x - b) > cut / max(S) * scale * 10 if len(S) else False:
            return None, unique
        return sp.Matrix([sp.Float(v, digits) for v in x]), unique
