"""Several contacts closing at the same instant (smooth or with friction), under a stated
rule.

The bodies are placed in one world frame (origin O); each contact has its own point and
normal. The generalized-impulse core extends row by row: the Jacobian J maps the
generalized velocities u to the normal closing velocity of every contact (second minus
first along the contact's normal), and ``W = J M^-1 J^T`` couples the contacts. Three
rules say how the contacts act together:

- ``simultaneous``: all at once, with Newton's or Poisson's law at every contact, solved
  as a linear complementarity problem so that no contact pulls: each contact either
  pushes (P >= 0) and meets its law, or is released (P = 0) and separates at least as
  fast as the law asks. The result says which contacts acted.
- ``sequential``: one contact at a time in a given order, each a two-body impact with
  Newton's e, passes repeated in that order until no contact still approaches.
- every order: with ``sequential`` and no order given, each order is run and reported.
- ``compliant``: every contact a push-only spring-dashpot (or an elastic Hertz spring),
  integrated numerically until all contacts let go; the stiffnesses' ratios decide.

A contact may have Coulomb friction: the sequential rule then runs Routh's method at each
step (:mod:`rigidimpact.laws.routh`), the simultaneous rule solves friction at the velocity
level over every combination of contact states. With symbols left the simultaneous and
one-pass sequential rules give formulas, each with the conditions under which it holds.

The numbers are exact (rationals stay rationals), so the rules can be compared exactly.

Where things live: the model (u, M^-1, J, W, the bodies after, the printed equations) is
:class:`~rigidimpact.solve.problem.ImpactProblem`; each rule is one module of
:mod:`rigidimpact.solve.rules` working on it, whatever its source (the built-in shapes,
joints, a sympy.physics.mechanics system); :class:`Collision` is that problem with the
rules at hand, and the cradle, fan and cluster families are built here.

Examples
--------
>>> from rigidimpact.model.bodies import Body
>>> balls = [Body.rigid(1, 1, (2 * k, 0), (1 if k == 0 else 0, 0), name=f"b{k}")
...          for k in range(3)]
>>> touching = [Contact(restitution=1, name="left", bodies=("b0", "b1"), point=(1, 0)),
...             Contact(restitution=1, name="right", bodies=("b1", "b2"), point=(3, 0))]
>>> problem = Collision(tuple(balls), tuple(touching))
>>> [problem.simultaneous().results()[f"b{k}.vx"] for k in range(3)]
[-1/3, 2/3, 2/3]
>>> [problem.sequential(("left", "right")).results()[f"b{k}.vx"] for k in range(3)]
[0, 0, 1]
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.impact import Impact
from rigidimpact.solve.problem import MAX_ENUMERATED, ImpactProblem
from rigidimpact.solve.rules import (
    MAX_PASSES,
    RULE_LAWS,
    RULE_TYPES,
    RULES,
    Compliant,
    Rule,
    Sequential,
    Simultaneous,
    compliant,
    rule_laws,
    sequential,
    sequential_passes,
    simultaneous,
    whole_number,
)
from rigidimpact.solve.solution import Solution, certified
from rigidimpact.symbolic.notation import speed_names

__all__ = ["Collision", "ImpactProblem", "Outcome", "RULES", "RULE_LAWS", "MAX_PASSES",
           "MAX_ENUMERATED", "chain", "fan", "cluster", "sequential_passes", "certified",
           "whole_number", "Rule", "Simultaneous", "Sequential", "Compliant", "RULE_TYPES",
           "rule_laws"]

Outcome = Solution  # the one result type (the name several-contact code used first)


@dataclass(frozen=True)
class Collision(ImpactProblem):
    """Bodies in the world frame, the contacts that close together and the joints that
    pin bodies to each other: the impulse problem
    (:class:`~rigidimpact.solve.problem.ImpactProblem`, whose parameters it takes) with
    every rule at hand.
    """

    def simultaneous(self) -> Solution:
        """All contacts at once, none pulling, at numbers
        (:func:`rigidimpact.solve.rules.simultaneous.simultaneous`)."""
        return simultaneous.simultaneous(self)

    def simultaneous_cases(self) -> tuple[Solution, ...]:
        """The simultaneous rule with symbols: one outcome per case, each with its
        conditions (:func:`rigidimpact.solve.rules.simultaneous.simultaneous_cases`)."""
        return simultaneous.simultaneous_cases(self)

    def sequential(self, order: Sequence[str]) -> Solution:
        """One contact at a time in `order`, passes repeated until none approaches
        (:func:`rigidimpact.solve.rules.sequential.sequential`)."""
        return sequential.sequential(self, order)

    def sequential_pass(self, order: Sequence[str]) -> Solution:
        """One pass in `order` with symbols, with the conditions that make it the whole
        answer (:func:`rigidimpact.solve.rules.sequential.sequential_pass`)."""
        return sequential.sequential_pass(self, order)

    def sequential_cases(self, order: Sequence[str]) -> tuple[Solution, ...]:
        """The sequential rule in `order` with symbols, case by case
        (:func:`rigidimpact.solve.rules.sequential.sequential_cases`)."""
        return sequential.sequential_cases(self, order)

    def every_order(self) -> tuple[Solution, ...]:
        """The sequential rule in every order of the contacts."""
        return sequential.every_order(self)

    def sampled_orders(self, count: int, seed: int) -> tuple[Solution, ...]:
        """The sequential rule in `count` orders drawn with `seed`."""
        return sequential.sampled_orders(self, count, seed)

    def compliant(self, stiffness: Sequence[float] | float = 1e6, hertz: bool = False,
                  tolerance: float = 1e-10, record: bool = False) -> Solution:
        """Every contact a push-only spring, integrated until all let go
        (:func:`rigidimpact.solve.rules.compliant.compliant`)."""
        return compliant.compliant(self, stiffness, hertz, tolerance, record)

    def solve(self, rule: Rule) -> tuple[Solution, ...]:
        """What `rule` makes of the collision (see :class:`Rule`): the model is built once
        and the rule is an argument, as sympy's ``System.form_eoms`` takes its method.

        Examples
        --------
        >>> chain(3).solve(Sequential(("c0", "c1")))[0].results()["ball2.vx"]
        1
        """
        if not isinstance(rule, Rule):
            raise InputError("rule", "must be a rule object (Simultaneous(), "
                             "Sequential(order) or Compliant()), not "
                             f"{type(rule).__name__} {rule!r}")
        return tuple(replace(o, pivot_reactions=reactions)
                     if (reactions := self._pivot_reactions(o)) else o
                     for o in rule.answer(self))

    def own_answer(self, rule: Rule) -> Solution | None:
        """One contact without joints: the two-body core's answer (:meth:`alone`), with
        the paper's printed laws (the answer of every rule; the door reports it under
        the rule asked)."""
        return None if self.joints else self.alone()

    def alone(self) -> Solution:
        """The one contact's impact, exactly, by the two-body core
        (:class:`~rigidimpact.solve.impact.Impact`): its printed laws with the paper's
        unknown names, Routh's and Walton's regimes as ``Piecewise`` with symbols, the
        per-contact frame that keeps a symbolic tilt fast. The core works from the
        contact point; the solution is given back in this collision's frame, with every
        body that the contact does not touch as it was.

        Examples
        --------
        >>> ball = Body.particle(1, (2, 0), "ball")
        >>> hit = Collision((ball.shifted((5, 0)), Body.fixed("wall")), (Contact(
        ...     restitution=sp.Symbol("e"), bodies=("ball", "wall"), point=(5, 0)),))
        >>> hit.alone().results()["ball.vx"]
        -2*e
        """
        if len(self.contacts) != 1:
            raise ValueError("alone() solves a collision of one contact")
        (c,) = self.contacts
        point = sp.ImmutableMatrix(c.point)
        first, second = (self._body(n).shifted(-point) for n in (c.first, c.second))
        solution = Impact(first, second, c, unknown_names=(
            speed_names(first.name), speed_names(second.name))).solve()

        def world(s: Solution) -> Solution:
            after = {b.name: b.shifted(point) for b in s.after}
            return replace(s, before=self.bodies, contacts=(c,),
                           after=tuple(after.get(b.name, b) for b in self.bodies))

        solved = replace(world(solution), regimes=tuple(
            (name, conditions, world(r)) for name, conditions, r in solution.regimes))
        if self.symbols:  # closed forms: checked where they are derived (verify, tests)
            return solved
        pushed = sp.sympify(solved.impulses[c.name])
        return certified(replace(solved, acted=(c.name,) if pushed > 0 else ()))


# the builders' budget: bodies are made one SymPy object at a time, a few ms each (a
# 10,000-ball chain took 35 s to build and 19 s to solve here); past it, one line first
MAX_BUILT_CONTACTS = 3000


def _builder_size(name: str, value: Any, least: int) -> int:
    return whole_number(name, value, least, MAX_BUILT_CONTACTS,
                        f" (at most {MAX_BUILT_CONTACTS} contacts are built: each body is a SymPy "
                        "object, a few milliseconds each)")


def chain(n: int, restitution: Any = 1, speed: Any = 1) -> Collision:
    """Newton's cradle: n equal balls (mass 1, radius 1/2) in a line, touching, the first
    moving at `speed` into the rest.

    Examples
    --------
    >>> [chain(3).simultaneous().results()[f"ball{k}.vx"] for k in range(3)]
    [-1/3, 2/3, 2/3]
    """
    n = _builder_size("n", n, 2)
    bodies = tuple(Body.rigid(1, sp.Rational(1, 10), (k, 0), (speed if k == 0 else 0, 0),
                              name=f"ball{k}") for k in range(n))
    touches = tuple(Contact(restitution=restitution, name=f"c{k}",
                            bodies=(f"ball{k}", f"ball{k + 1}"),
                            point=(sp.Rational(2 * k + 1, 2), 0)) for k in range(n - 1))
    return Collision(bodies, touches)


def fan(k: int) -> Collision:
    """A striker meeting k touching discs at once, each at a rational direction on its rim
    (Pythagorean triples): W invertible and every number rational.

    Examples
    --------
    >>> [tuple(t.normal) for t in fan(2).contacts]
    [(3/5, 4/5), (5/13, 12/13)]
    """
    k = _builder_size("k", k, 1)
    directions: list[tuple[sp.Rational, sp.Rational]] = []
    outer = 2
    while len(directions) < k:
        for inner in range(1, outer):
            if len(directions) < k and (outer - inner) % 2 and math.gcd(outer, inner) == 1:
                a, b, c = outer**2 - inner**2, 2 * outer * inner, outer**2 + inner**2
                directions.append((sp.Rational(a, c), sp.Rational(b, c)))
        outer += 1
    bodies = [Body.rigid(1, 1, (0, 0), (1, sp.Rational(1, 3)), name="s")]
    contacts = []
    for i, (x, y) in enumerate(directions):
        bodies.append(Body.rigid(1, 1, (2 * x, 2 * y), (0, 0), name=f"b{i}"))
        contacts.append(Contact((x, y), sp.Rational(1, 2), name=f"c{i}", bodies=("s", f"b{i}"),
                                point=(x, y)))
    return Collision(tuple(bodies), tuple(contacts))


def cluster(rows: int, columns: int, restitution: Any = 1, speed: Any = 1) -> Collision:
    """A striker hitting a hexagonal cluster of equal discs (mass 1, radius 1/2), `rows`
    rows of `columns` each, every touching pair a contact; the striker, moving along x
    at `speed`, touches the middle row's first disc (and, where that row is one of the
    odd ones, half a disc to the right, the first discs of the rows either side: it
    lies in their notch).

    Examples
    --------
    >>> c = cluster(2, 2)
    >>> len(c.contacts), [t.name for t in c.contacts[:2]]
    (6, ['hit', 'd0_0_d0_1'])
    """
    rows, columns = whole_number("rows", rows, 1), whole_number("columns", columns, 1)
    if 3 * rows * columns > MAX_BUILT_CONTACTS:
        raise InputError("cluster", f"{rows} x {columns} discs make about "
                         f"{3 * rows * columns} contacts, past the budget of "
                         f"{MAX_BUILT_CONTACTS} (each body is a SymPy object)")
    half = sp.sqrt(3) / 2
    centres = {(i, j): (j + sp.Rational(i % 2, 2), i * half)
               for i in range(rows) for j in range(columns)}
    middle = (rows - 1) // 2
    first = centres[middle, 0]
    bodies = [Body.rigid(1, sp.Rational(1, 8), (first[0] - 1, first[1]), (speed, 0),
                         name="striker")]
    bodies += [Body.rigid(1, sp.Rational(1, 8), centres[k], (0, 0), name=f"d{k[0]}_{k[1]}")
               for k in sorted(centres)]
    touches = [Contact(restitution=restitution, name="hit",
                       bodies=("striker", f"d{middle}_0"),
                       point=(first[0] - sp.Rational(1, 2), first[1]))]
    striker = (first[0] - 1, first[1])
    for row in (middle - 1, middle + 1):  # an odd middle row sits half a disc right: the
        if middle % 2 and (row, 0) in centres:  # striker lies in the notch and also
            x, y = centres[row, 0]  # touches the first discs of the rows either side
            touches.append(Contact((x - striker[0], y - striker[1]), restitution,
                                   name=f"hit_d{row}_0", bodies=("striker", f"d{row}_0"),
                                   point=((x + striker[0]) / 2, (y + striker[1]) / 2)))
    for (i, j), (x, y) in sorted(centres.items()):  # right, then the two above
        shift = i % 2  # odd rows sit half a disc to the right
        for other in ((i, j + 1), (i + 1, j - 1 + shift), (i + 1, j + shift)):
            if other in centres:
                ox, oy = centres[other]
                touches.append(Contact((ox - x, oy - y), restitution,
                                       name=f"d{i}_{j}_d{other[0]}_{other[1]}",
                                       bodies=(f"d{i}_{j}", f"d{other[0]}_{other[1]}"),
                                       point=((x + ox) / 2, (y + oy) / 2)))
    return Collision(tuple(bodies), tuple(touches))
