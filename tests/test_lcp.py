"""Lemke's method for contacts acting together: exact, the same answers as enumerating
the acting sets, and degenerate problems (contacts at rest before) settled."""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.collision import Collision, chain
from rigidimpact.solve.lcp import NoSolution, lemke, sparse_solve
from rigidimpact.solve.rules import simultaneous as rule


def _by_enumeration(M, q):
    """Every set of acting contacts tried (an independent, 2^n solver)."""
    n = len(q)
    for size in range(n + 1):
        for active in itertools.combinations(range(n), size):
            block = sp.Matrix([[M[i][j] for j in active] for i in active])
            if size and block.det() == 0:
                continue
            z = [Fraction(0)] * n
            if size:
                solved = block.LUsolve(sp.Matrix([-q[i] for i in active]))
                for k, i in enumerate(active):
                    z[i] = Fraction(int(solved[k].p), int(solved[k].q))
            w = [q[i] + sum(M[i][j] * z[j] for j in range(n)) for i in range(n)]
            if all(x >= 0 for x in z) and all(x >= 0 for x in w):
                return z
    raise AssertionError("no solution")


@pytest.mark.parametrize("seed", range(12))
def test_lemke_solves_random_positive_definite_problems_exactly(seed):
    rng = random.Random(seed)
    n = rng.randint(1, 7)
    A = [[Fraction(rng.randint(-5, 5)) for _ in range(n)] for _ in range(n)]
    M = [[sum(A[k][i] * A[k][j] for k in range(n)) + (Fraction(1) if i == j else 0)
          for j in range(n)] for i in range(n)]
    q = [Fraction(rng.randint(-9, 9), rng.randint(1, 4)) for _ in range(n)]
    z = lemke(M, q)
    w = [q[i] + sum(M[i][j] * z[j] for j in range(n)) for i in range(n)]
    assert all(x >= 0 for x in z) and all(x >= 0 for x in w)
    assert all(a * b == 0 for a, b in zip(z, w, strict=True))
    assert z == _by_enumeration(M, q)  # positive definite: the solution is unique


def test_a_degenerate_problem_does_not_cycle():
    # a cradle of ten at rest but the first: nine zeros in q
    c = chain(10)
    out = c.simultaneous().results()
    # momentum and the first contact's Newton law hold; nothing pulls
    assert sum(out[f"ball{k}.vx"] for k in range(10)) == 1
    assert all(out[f"c{k}.normal_impulse"] >= 0 for k in range(9))


def test_no_solution_is_said():
    with pytest.raises(NoSolution):
        lemke([[Fraction(-1)]], [Fraction(-1)])


@pytest.mark.parametrize("seed", range(16))
def test_the_simultaneous_rule_gives_enumerations_answer(seed):
    # random rational clusters: a striker among discs placed at rational points on its
    # rim (3-4-5 directions), every contact's impulses by Lemke and by enumeration
    rng = random.Random(seed)
    directions = [(1, 0), (0, 1), (-1, 0), (0, -1), (sp.Rational(3, 5), sp.Rational(4, 5)),
                  (sp.Rational(-4, 5), sp.Rational(3, 5)), (sp.Rational(4, 5), sp.Rational(-3, 5))]
    chosen = rng.sample(directions, rng.randint(2, 5))
    striker = Body.rigid(sp.Rational(rng.randint(1, 9), 3), 1, (0, 0),
                         (sp.Rational(rng.randint(-9, 9), 4), sp.Rational(rng.randint(-9, 9), 4)),
                         name="s")
    bodies, contacts = [striker], []
    for k, (x, y) in enumerate(chosen):
        bodies.append(Body.rigid(sp.Rational(rng.randint(1, 9), 2), 1, (2 * x, 2 * y),
                                 (0, 0), name=f"d{k}"))
        contacts.append(Contact((x, y), sp.Rational(rng.randint(0, 4), 4), name=f"c{k}",
                                bodies=("s", f"d{k}"), point=(x, y)))
    try:
        collision = Collision(tuple(bodies), tuple(contacts))
    except InputError as error:  # the striker moves away from every disc
        assert "no contact is approaching" in str(error)
        return
    v = collision.velocity_before
    e = sp.Matrix([c.restitution for c in contacts])
    target = sp.Matrix([-e[i] * min(v[i], 0) for i in range(len(v))])
    assert rule._lcp(collision, v, target) == (rule._complementarity(collision, v, target), (), "")


def test_a_long_enumeration_stops_in_one_line(monkeypatch):
    # irrational normals (no Lemke): the acting sets are tried within a budget of work
    monkeypatch.setattr(rule, "MAX_ENUMERATION_WORK", 0)
    r3 = sp.sqrt(3)
    bodies = (Body.rigid(1, 1, (0, 0), (1, 0), name="s"),
              Body.rigid(1, 1, (r3, 1), (0, 0), name="u"),
              Body.rigid(1, 1, (r3, -1), (0, 0), name="d"))
    contacts = (Contact((r3, 1), 1, name="a", bodies=("s", "u"), point=(r3 / 2, sp.S.Half)),
                Contact((r3, -1), 1, name="b", bodies=("s", "d"),
                        point=(r3 / 2, -sp.S.Half)))
    with pytest.raises(InputError, match="contacts: 2 contacts: 4 sets of acting contacts"):
        Collision(bodies, contacts).simultaneous()


@pytest.mark.parametrize("seed", range(8))
def test_markowitz_elimination_solves_sparse_unsymmetric_systems_exactly(seed):
    # a random sparse system that is not symmetric, with a zero diagonal here and there
    # (a pivot off the diagonal is needed), held against SymPy's dense LU solve
    rng = random.Random(seed)
    n = rng.randint(5, 30)
    rows = {i: {} for i in range(n)}
    for i in range(n):
        for j in rng.sample(range(n), rng.randint(1, 3)):
            rows[i][j] = Fraction(rng.randint(-9, 9) or 1, rng.randint(1, 5))
        rows[i][(i + 1) % n] = Fraction(rng.randint(1, 9))  # no row or column empty
    rhs = {i: Fraction(rng.randint(-9, 9), rng.randint(1, 4)) for i in range(n)}
    A = sp.Matrix(n, n, lambda i, j: sp.Rational(rows[i].get(j, 0)))
    if A.det() == 0:
        assert sparse_solve(rows, rhs, budget=10**6) is None
        return
    expected = A.LUsolve(sp.Matrix([sp.Rational(rhs[i]) for i in range(n)]))
    found = sparse_solve(rows, rhs, budget=10**6)
    assert found is not None
    assert [sp.Rational(found[j]) for j in range(n)] == list(expected)


def test_markowitz_elimination_says_none_when_singular_or_over_its_budget():
    half = Fraction(1, 2)
    singular = {0: {0: half, 1: Fraction(1)}, 1: {0: Fraction(1), 1: Fraction(2)}}
    assert sparse_solve(singular, {0: half}, budget=100) is None
    dense = {i: {j: Fraction(i + j + 1, 1 + (i == j)) for j in range(20)} for i in range(20)}
    assert sparse_solve(dense, {0: half}, budget=50) is None  # first pivot costs 400
    assert sparse_solve(dense, {0: half}, budget=10**6) is not None
