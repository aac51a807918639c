"""A mechanics system as the rules see every source: the one problem of rows (its
independent speeds, its dense M^-1, each contact's normal and tangent rows), and the way
back from what a rule makes of it to the system's own Solution (through
:meth:`rigidimpact.mechanics.impact.SystemImpact._map` and ``_in_plane``)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import sympy as sp

from rigidimpact.model.impulse import kinetic_energy
from rigidimpact.solve.problem import RowsProblem
from rigidimpact.solve.registry import conduct
from rigidimpact.solve.solution import Solution

__all__ = ["SystemRows"]


@dataclass(frozen=True)
class SystemRows(RowsProblem):
    """A mechanics system at numbers as the rules see any source: the one problem of
    rows (its independent speeds, its dense M^-1, each contact's normal and tangent
    rows), so each rule runs its one implementation. What the rules make of it goes
    back through :meth:`SystemImpact._map`: the system's Solution, its equations and its
    own residuals."""

    system: Any = None

    @classmethod
    def of(cls, system: Any) -> SystemRows:
        """The one assembly of a system into the problem of rows: each contact's normal
        and tangent rows, and in 3-D (a contact sliding across a tangent plane) its
        second tangent's row too."""
        plane = system.J_plane
        rows = {} if plane is None else dict(
            normal_rows=sp.ImmutableMatrix(plane[::3, :]),
            tangent_rows=sp.ImmutableMatrix(plane[1::3, :]),
            second_tangent_rows=sp.ImmutableMatrix(plane[2::3, :]))
        return cls(tuple(c.laws for c in system.contacts), system=system,
                   speeds=tuple(str(u) for u in system.u),
                   velocities=sp.ImmutableMatrix(system.u_before),
                   inverse_mass=None,  # M^-1 when a rule asks for it (below)
                   **(rows or dict(normal_rows=sp.ImmutableMatrix(system.J[::2, :]),
                                   tangent_rows=sp.ImmutableMatrix(system.J[1::2, :]))))

    @cached_property
    def M_inverse(self) -> sp.Matrix:
        """The system's M^-1, formed when a rule asks for it (a one-contact closed form
        solves with M itself, fraction-free)."""
        return sp.Matrix(self.system.M).inv()

    @cached_property
    def symbols(self) -> frozenset[sp.Symbol]:
        return frozenset(sp.Matrix(self.velocities).free_symbols
                         | sp.Matrix(self.system.M).free_symbols
                         | sp.Matrix(self.normal_rows).free_symbols)

    def own_answer(self, rule: Any) -> Solution | None:
        """One contact in the plane of its normal and tangent under a law of linear
        conditions (smooth, stick): the system's own closed form, ``M u+ - J^T P = M u-``
        with the law's two conditions solved fraction-free (an arithmetic choice of
        the linear case, the system's equations printed; the door reports it under the
        rule asked). A law by
        regimes (Coulomb, rough) or a tangent plane: the rules' one-contact step, once
        the numbers its course turns on are given."""
        system = self.system
        tangential = self.contacts[0].laws[1]
        if system.J_plane is None and not tangential.solved_by_regimes:
            return system._linear()
        if tangential.solved_by_regimes:
            system._course_needs_numbers()
        return None

    def outcome(self, rule: str, order: Sequence[str], u: sp.Matrix,
                 impulses: dict[str, sp.Expr], acted: Sequence[str], passes: int = 1,
                 **more: Any) -> Solution:
        system = self.system
        along = more.pop("tangential", None) or {}
        if self.second_tangent_rows is not None:  # 3-D: each contact's n, t1, t2
            zero = sp.Integer(0)
            sideways = more.pop("tangent_impulses", None) or {}
            P = sp.Matrix([x for c in self.contacts for x in (
                impulses[c.name], *sideways.get(c.name, (along.get(c.name, zero), zero)))])
            states = dict(c.split(": ", 1) for c in more.pop("courses", ()))
            exact = not any(sp.sympify(x).has(sp.Float) for x in (*u, *P))
            solution = system._in_plane(
                sp.Matrix(u), P, {c.name: states.get(c.name, "acts" if c.name in acted
                                                     else "released")
                                  for c in self.contacts}, rule, exact,
                tuple(more.pop("notes", ())))
            return replace(solution, order=tuple(order), passes=passes,
                           method=more.pop("method", ""))
        P = sp.Matrix([x for c in self.contacts
                       for x in (impulses[c.name], along.get(c.name, 0))])
        states = dict(c.split(": ", 1) for c in more.pop("courses", ()))
        courses = {c.name: states.get(c.name, "released" if c.name not in acted else
                                      ("acts" if conduct(rule).whole_impact
                                       else "in turn"))
                   for c in self.contacts}
        M, u0 = system.M, sp.Matrix(system.u_before)
        energy = kinetic_energy(M, u0) - kinetic_energy(M, u)
        # the contact's own printed laws hold where the rule imposed them as they are
        # (Newton's law at each acting contact, smooth or sticking); otherwise the
        # rule's impulses are what is printed
        # (one contact: its own impact under every rule, its own laws printed)
        own = len(self.contacts) == 1 or conduct(rule).whole_impact and all(
            c.laws[0].together == "velocity" and courses[c.name] in ("acts", "released",
                                                                     "sticks")
            for c in self.contacts)
        for c in self.contacts:  # a contact that stuck prints its no-slip law
            if courses[c.name] == "sticks" or (courses[c.name] == "acts" and
                                               c.laws[1].unknown_tangential):
                courses[c.name] = "stick"
        conditions = tuple(c for c in more.pop("conditions", ()) if c is not sp.true)
        solution = system._map(sp.Matrix(u), P, courses, energy, summed=not own,
                               how=None if own else f"{rule} rule", rule=rule,
                               conditions=conditions)
        limits, _ = replace(solution, rule=rule).assessed()
        return replace(solution, rule=rule, order=tuple(order), passes=passes,
                       acted=tuple(acted), notes=solution.notes + more.pop("notes", ()),
                       conditions=conditions,
                       method=more.pop("method", ""),
                       warnings=solution.warnings + tuple(
                           w for w in limits if "still approaches" in w))
