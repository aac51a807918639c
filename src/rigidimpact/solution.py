"""What an impact leaves: final velocities and spins, impulse, energy, contact velocities.

Examples
--------
>>> from rigidimpact.bodies import Body
>>> from rigidimpact.contact import Contact
>>> from rigidimpact.impact import Impact
>>> sol = Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
...              Contact(restitution=0)).solve()
>>> sol.energy_loss_fraction
1/2
>>> sol.impulse.T
Matrix([[1, 0]])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING

import sympy as sp

from rigidimpact.bodies import Body
from rigidimpact.rewrite import tidy

if TYPE_CHECKING:
    from rigidimpact.impact import Impact
    from rigidimpact.laws import Equation

__all__ = ["Solution"]


@dataclass(frozen=True)
class Solution:
    """The solved impact.

    Parameters
    ----------
    impact : Impact
        The problem that was solved.
    equations : tuple of Equation
        The laws used, in the contact frame.
    unknowns : tuple of Symbol
        What was solved for (contact-frame components).
    values : mapping
        Unknown -> exact expression.
    contact_impulse : pair of Expr, optional
        The impulse the first body gives the second, (normal, tangential) in the contact
        frame, as solved.
    """

    impact: Impact
    equations: tuple[Equation, ...]
    unknowns: tuple[sp.Symbol, ...]
    values: Mapping[sp.Symbol, sp.Expr]
    contact_impulse: tuple[sp.Expr, sp.Expr] | None = None

    def __repr__(self) -> str:
        return (f"Solution({self.impact.first.name!r}, {self.impact.second.name!r}, "
                f"unknowns={[str(u) for u in self.unknowns]})")

    def _final(self, index: int) -> Body:
        after = self.impact.after[index]
        if after.support == "fixed":
            return (self.impact.first, self.impact.second)[index]
        velocity = after.velocity.subs(self.values)
        spin = sp.sympify(after.spin).subs(self.values)
        original = (self.impact.first, self.impact.second)[index]
        back = self.impact.frame.T  # contact frame -> scene frame
        if self.impact.numeric:  # keep the body's data in the same 50-digit numbers
            numbers = self.impact.before[index]
            pivot = None if numbers.pivot is None else back * numbers.pivot
            original = replace(original, mass=numbers.mass, inertia=numbers.inertia,
                               position=back * numbers.position, pivot=pivot)
        return original.with_motion((back * velocity).applyfunc(tidy), tidy(spin))

    @cached_property
    def first_after(self) -> Body:
        """The first body just after the impact (scene frame)."""
        return self._final(0)

    @cached_property
    def second_after(self) -> Body:
        """The second body just after the impact (scene frame)."""
        return self._final(1)

    @cached_property
    def impulse(self) -> sp.ImmutableMatrix:
        """The impulse that the first body gives the second (scene frame).

        Examples
        --------
        >>> from rigidimpact.bodies import Body
        >>> from rigidimpact.contact import Contact
        >>> from rigidimpact.impact import Impact
        >>> Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...        Contact(restitution=1)).solve().impulse.T
        Matrix([[2, 0]])
        """
        if self.contact_impulse is not None:
            local = sp.ImmutableMatrix(self.contact_impulse)
            return (self.impact.frame.T * local).applyfunc(tidy)
        change = self.second_after.momentum - self.impact.second.momentum
        return change.applyfunc(tidy)

    def pivot_impulse(self, body: Body) -> sp.ImmutableMatrix:
        """The reaction impulse a pivot gives its body (scene frame): the body's change of
        momentum less the contact impulse it received.

        Examples
        --------
        >>> from rigidimpact.bodies import Body
        >>> from rigidimpact.contact import Contact
        >>> from rigidimpact.impact import Impact
        >>> rod = Body.rod(1, 3, sp.pi / 2, sp.Rational(1, 2), pivot=(0, 2), name="rod")
        >>> sol = Impact(Body.particle(1, (1, 0), "ball"), rod, Contact()).solve()
        >>> sol.pivot_impulse(rod).T  # struck at the centre of percussion, 2/3 down
        Matrix([[0, 0]])
        """
        index = (self.impact.first.name, self.impact.second.name).index(body.name)
        after = (self.first_after, self.second_after)[index]
        given = self.impulse if index == 1 else -self.impulse
        return (after.momentum - body.momentum - given).applyfunc(tidy)

    @cached_property
    def normal_impulse(self) -> sp.Expr:
        """The impulse along the normal, non-negative for an impact."""
        return tidy((self.impact.frame * self.impulse)[0])

    @cached_property
    def tangential_impulse(self) -> sp.Expr:
        """The impulse along the tangent (zero for a smooth contact)."""
        return tidy((self.impact.frame * self.impulse)[1])

    @cached_property
    def kinetic_energy_before(self) -> sp.Expr:
        """Total kinetic energy just before the impact."""
        first, second = self.impact.before  # numbers already, in numeric mode
        return tidy(first.kinetic_energy + second.kinetic_energy)

    @cached_property
    def energy_lost(self) -> sp.Expr:
        """Kinetic energy lost, from the work of the impulse (Kelvin's theorem).

        An impulse P at a point changes a body's kinetic energy by P times the mean of
        that point's velocity before and after. Summed over the pair, with u the
        velocity of body 2's contact point relative to body 1's, the loss is
        ``-(P . (u_before + u_after)) / 2``: exact, and linear in the compact impulse,
        where ``K_i - K_f`` from squared velocities swells.
        """
        frame = self.impact.frame
        first, second = self.impact.before  # already in the contact frame
        u_before = second.contact_velocity - first.contact_velocity
        u_after = frame * (self.contact_velocities_after[1] - self.contact_velocities_after[0])
        impulse = frame * self.impulse
        return tidy(-impulse.dot(u_before + u_after) / 2)

    @cached_property
    def kinetic_energy_after(self) -> sp.Expr:
        """Total kinetic energy just after the impact, the bracket of eq. (6)."""
        return tidy(self.kinetic_energy_before - self.energy_lost)

    @cached_property
    def energy_loss_fraction(self) -> sp.Expr:
        """``(K_i - K_f) / K_i``, the paper's eq. (7) for the barbell."""
        return tidy(self.energy_lost / self.kinetic_energy_before)

    @cached_property
    def contact_velocities_after(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """Velocities of the two material points at O just after (eq. 11)."""
        return (self.first_after.contact_velocity.applyfunc(tidy),
                self.second_after.contact_velocity.applyfunc(tidy))

    def results(self) -> dict[str, sp.Expr]:
        """Results under the keys of docs/scenes.md: ``BODY.vx``, ``BODY.vy``, ``BODY.omega``
        (not for a fixed body), ``impulse`` and ``energy_loss_fraction`` (and ``impulse_t``
        when sticking), ``contact.normal_impulse`` and ``contact.tangential_impulse``, and
        ``BODY.pivot_impulse_x``, ``BODY.pivot_impulse_y`` for a pivoted body.

        Examples
        --------
        >>> from rigidimpact.bodies import Body
        >>> from rigidimpact.contact import Contact
        >>> from rigidimpact.impact import Impact
        >>> sorted(Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...               Contact()).solve().results())  # doctest: +NORMALIZE_WHITESPACE
        ['a.omega', 'a.vx', 'a.vy', 'b.omega', 'b.vx', 'b.vy', 'contact.normal_impulse',
         'contact.tangential_impulse', 'energy_loss_fraction', 'impulse']
        """
        results: dict[str, sp.Expr] = {}
        for body in (self.first_after, self.second_after):
            if body.support == "fixed":
                continue
            results[f"{body.name}.vx"] = body.velocity[0]
            results[f"{body.name}.vy"] = body.velocity[1]
            results[f"{body.name}.omega"] = body.spin
        results["impulse"] = self.normal_impulse
        if self.impact.contact.tangential == "stick":
            results["impulse_t"] = self.tangential_impulse
        results["energy_loss_fraction"] = self.energy_loss_fraction
        results["contact.normal_impulse"] = self.normal_impulse
        results["contact.tangential_impulse"] = self.tangential_impulse
        for body in (self.impact.first, self.impact.second):
            if body.support == "pivot":
                reaction = self.pivot_impulse(body)
                results[f"{body.name}.pivot_impulse_x"] = reaction[0]
                results[f"{body.name}.pivot_impulse_y"] = reaction[1]
        return results
