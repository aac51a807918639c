"""What an impact leaves: final motion, impulses, energy, contact velocities.

A :class:`Solution` is a self-contained value: it holds the bodies as given and just
after, the contact, the impulse at O and the energies, and refers back to no solver.

Examples
--------
>>> from rigidimpact.model.bodies import Body
>>> from rigidimpact.laws.contact import Contact
>>> from rigidimpact.solve.impact import Impact
>>> sol = Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
...              Contact(restitution=0)).solve()
>>> sol.energy_loss_fraction
1/2
>>> sol.impulse.T
Matrix([[1, 0]])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.model.bodies import Body
from rigidimpact.symbolic.notation import aligned, result_lhs, to_latex
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Solution"]


@dataclass(frozen=True)
class Solution:
    """The solved impact.

    Parameters
    ----------
    before, after : pair of Body
        The two bodies as given and just after the impact (scene frame).
    contact : Contact
    frame : 2x2 matrix
        Rotation from scene to contact coordinates.
    equations : tuple of Equation
        The laws used, in the contact frame.
    unknowns : tuple of Symbol
        What was solved for (contact-frame components).
    values : mapping
        Unknown -> exact expression.
    contact_impulse : pair of Expr
        The impulse the first body gives the second, (normal, tangential) in the contact
        frame, as solved.
    kinetic_energy_before, energy_lost : Expr
        The energy lost comes from the work of the impulse (Kelvin's theorem): an impulse
        P at a point changes a body's kinetic energy by P times the mean of that point's
        velocity before and after, so the pair loses ``-P . (u_before + u_after) / 2``
        with u the closing velocity of the touching points; exact, and linear in the
        compact impulse, where ``K_i - K_f`` from squared velocities swells.
    energy_loss_fraction : Expr
        ``(K_i - K_f) / K_i``, the paper's eq. (7) for the barbell.
    approach_speed : Expr
        How fast the touching points closed along the normal.
    regime : str or None
        With friction and numbers, the course the impact took (``slip``,
        ``slip-stick``, ``slip-reversal``, ...).
    regimes : tuple of (name, conditions, Solution)
        With friction and symbols, every course the impact can take, each with the
        conditions under which it does and its own solution; the fields above are then
        ``Piecewise`` over them.
    path : tuple of (P_n, P_t)
        The impulse at each event of a frictional impact (Routh's diagram).
    """

    before: tuple[Body, Body]
    after: tuple[Body, Body]
    contact: Contact
    frame: sp.ImmutableMatrix
    equations: tuple[Equation, ...]
    unknowns: tuple[sp.Symbol, ...]
    values: Mapping[sp.Symbol, sp.Expr]
    contact_impulse: tuple[sp.Expr, sp.Expr]
    kinetic_energy_before: sp.Expr
    energy_lost: sp.Expr
    energy_loss_fraction: sp.Expr
    approach_speed: sp.Expr
    regime: str | None = None
    regimes: tuple[tuple[str | None, tuple[sp.Basic, ...], Solution], ...] = ()
    path: tuple[tuple[sp.Expr, sp.Expr], ...] = ()

    def regime_at(self, values: Mapping[sp.Symbol, Any]) -> str | None:
        """The course the impact takes at these values (None without friction).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...        Contact()).solve().regime_at({}) is None
        True
        """
        if not self.regimes:
            return self.regime
        for name, conditions, _ in self.regimes:
            if all(bool(c.subs(values)) for c in conditions):
                return name
        return None

    def __repr__(self) -> str:
        return (f"Solution({self.before[0].name!r}, {self.before[1].name!r}, "
                f"unknowns={[str(u) for u in self.unknowns]})")

    def _repr_latex_(self) -> str:
        r"""The results, typeset in the paper's notation (Jupyter).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> print(Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...       Contact(restitution=1)).solve()._repr_latex_()[:41])
        $$\begin{aligned} V_x^{(\mathrm{a})} &= 0
        """

        return aligned([(result_lhs(k), to_latex(v), "") for k, v in self.results().items()])

    @property
    def first_after(self) -> Body:
        """The first body just after the impact (scene frame)."""
        return self.after[0]

    @property
    def second_after(self) -> Body:
        """The second body just after the impact (scene frame)."""
        return self.after[1]

    @cached_property
    def impulse(self) -> sp.ImmutableMatrix:
        """The impulse that the first body gives the second (scene frame).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...        Contact(restitution=1)).solve().impulse.T
        Matrix([[2, 0]])
        """
        local = sp.ImmutableMatrix(self.contact_impulse)
        return local if self.frame == sp.eye(2) else \
            (self.frame.T * local).applyfunc(tidy)

    @property
    def normal_impulse(self) -> sp.Expr:
        """The impulse along the normal, non-negative for an impact that only pushes."""
        return self.contact_impulse[0]

    @property
    def tangential_impulse(self) -> sp.Expr:
        """The impulse along the tangent (the normal turned by +90 degrees)."""
        return self.contact_impulse[1]

    def pivot_impulse(self, body: Body) -> sp.ImmutableMatrix:
        """The reaction impulse a pivot gives its body (scene frame): the body's change of
        momentum less the contact impulse it received.

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> rod = Body.rod(1, 3, sp.pi / 2, sp.Rational(1, 2), pivot=(0, 2), name="rod")
        >>> sol = Impact(Body.particle(1, (1, 0), "ball"), rod, Contact()).solve()
        >>> sol.pivot_impulse(rod).T  # struck at the centre of percussion, 2/3 down
        Matrix([[0, 0]])
        """
        index = (self.before[0].name, self.before[1].name).index(body.name)
        given = self.impulse if index == 1 else -self.impulse
        change = self.after[index].momentum - self.before[index].momentum
        return (change - given).applyfunc(tidy)

    @property
    def kinetic_energy_after(self) -> sp.Expr:
        """Total kinetic energy just after the impact, the bracket of eq. (6)."""
        return tidy(self.kinetic_energy_before - self.energy_lost)

    @cached_property
    def contact_velocities_after(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """Velocities of the two material points at O just after (eq. 11), scene frame."""
        return (self.after[0].contact_velocity.applyfunc(tidy),
                self.after[1].contact_velocity.applyfunc(tidy))

    def results(self) -> dict[str, sp.Expr]:
        """Results under the keys of docs/scenes.md: ``BODY.vx``, ``BODY.vy``, ``BODY.omega``
        (not for a fixed body), ``impulse`` and ``energy_loss_fraction`` (and ``impulse_t``
        when sticking), ``contact.normal_impulse`` and ``contact.tangential_impulse``, and
        ``BODY.pivot_impulse_x``, ``BODY.pivot_impulse_y`` for a pivoted body.

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> sorted(Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...               Contact()).solve().results())  # doctest: +NORMALIZE_WHITESPACE
        ['a.omega', 'a.vx', 'a.vy', 'b.omega', 'b.vx', 'b.vy', 'contact.normal_impulse',
         'contact.tangential_impulse', 'energy_loss_fraction', 'impulse']
        """
        results: dict[str, sp.Expr] = {}
        for body in self.after:
            if body.support == "fixed":
                continue
            results[f"{body.name}.vx"] = body.velocity[0]
            results[f"{body.name}.vy"] = body.velocity[1]
            results[f"{body.name}.omega"] = body.spin
        results["impulse"] = self.normal_impulse
        if self.contact.tangential == "stick":
            results["impulse_t"] = self.tangential_impulse
        results["energy_loss_fraction"] = self.energy_loss_fraction
        results[f"{self.contact.name}.normal_impulse"] = self.normal_impulse
        results[f"{self.contact.name}.tangential_impulse"] = self.tangential_impulse
        for body in self.before:
            if body.support == "pivot":
                reaction = self.pivot_impulse(body)
                results[f"{body.name}.pivot_impulse_x"] = reaction[0]
                results[f"{body.name}.pivot_impulse_y"] = reaction[1]
        return results
