"""What an impact leaves, for one contact or many: the one result type.

A :class:`Solution` is a self-contained value: the bodies as given and just after, every
contact's normal and tangential impulse, every pivot's reaction, the energies, the rule
that acted (and in which order), the case or regime with its conditions, and the labelled
equations that were solved. The one-contact core (:class:`~rigidimpact.solve.impact.Impact`)
and every rule for several contacts (:class:`~rigidimpact.solve.collision.Collision`)
give this same type, so what reads one reads the other.

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
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any

import sympy as sp
from sympy.core.function import AppliedUndef

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.model.bodies import Body
from rigidimpact.solve.certificate import as_sympy, assess, residuals
from rigidimpact.symbolic.notation import aligned, result_lhs, to_latex
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Solution", "certified", "read_back"]

EYE = sp.ImmutableMatrix.eye(2)


@dataclass(frozen=True, kw_only=True)
class Solution:
    """The solved impact: one type for one contact and for several, for every rule.

    Parameters
    ----------
    before, after : tuple of Body
        The bodies as given and just after the impact (scene frame).
    impulses : mapping
        Contact name -> its normal impulse (on the second body, along the unit normal).
    tangential : mapping
        Contact name -> its tangential impulse (along the normal turned by +90 degrees);
        empty when the rule ran without friction (every one is then zero).
    contacts : tuple of Contact
        The contacts, with their laws.
    rule, order, acted, passes : str, tuple, tuple, int
        The rule that acted (``simultaneous``, ``sequential``, ``compliant``; the
        one-contact core says ``simultaneous``: with one contact every rule gives its
        answer), the order of a sequential rule, the contacts that pushed, and the
        passes in which some contact acted.
    equations, unknowns, values : tuple, tuple, mapping
        The labelled equations solved (contact frame for one contact), what they were
        solved for and their values (for one contact; see
        :meth:`~rigidimpact.solve.collision.Collision.equations` for several).
    conditions : tuple
        With symbols: when this is the rule's outcome (relations; empty: always).
    regime, regimes, path, courses :
        Friction: the course the impact took (``slip``, ``slip-stick``, ...); with
        symbols every course it can take as ``(name, conditions, Solution)`` (the fields
        above are then ``Piecewise`` over them); the impulse at each event (Routh's
        diagram); what each step of a sequential rule did.
    frame : 2x2 matrix
        One contact: the rotation from scene to contact coordinates.
    approach_speed : Expr or None
        One contact: how fast the touching points closed along the normal.
    energies : (K before, lost, lost / K before) or None
        Given by the one-contact core from the work of the impulse (Kelvin's theorem: an
        impulse P at a point changes a body's kinetic energy by P times the mean of that
        point's velocities before and after), exact and compact; otherwise taken from the
        bodies' kinetic energies.
    pivot_reactions : mapping
        Pivoted body name -> its pivot's reaction impulse (scene frame).
    warnings : tuple of str
        What the model could not honour here (a contact that would pull, energy
        created), said where the solver knew it.
    speeds_before, speeds_after :
        A sympy.physics.mechanics system's generalized speeds u before (its own
        symbols) and their closed forms after, in q and the speeds before (the
        impact's bodies are then the system's, not listed in `before` and `after`).
    notes, method, energy_tolerance, history :
        What the rule could not settle, how a large problem was solved, the relative
        energy error an integration carries, and a compliant run's record when asked.
    """

    before: tuple[Body, ...]
    after: tuple[Body, ...]
    impulses: Mapping[str, sp.Expr]
    tangential: Mapping[str, sp.Expr] = field(default_factory=dict)
    contacts: tuple[Contact, ...] = ()
    rule: str = "simultaneous"
    order: tuple[str, ...] = ()
    acted: tuple[str, ...] = ()
    passes: int = 1
    equations: tuple[Equation, ...] = ()
    unknowns: tuple[sp.Symbol, ...] = ()
    values: Mapping[sp.Symbol, sp.Expr] = field(default_factory=dict)
    conditions: tuple[Any, ...] = ()
    regime: str | None = None
    regimes: tuple[tuple[str | None, tuple[sp.Basic, ...], Solution], ...] = ()
    path: tuple[tuple[sp.Expr, sp.Expr], ...] = ()
    courses: tuple[str, ...] = ()
    frame: sp.ImmutableMatrix = EYE
    approach_speed: sp.Expr | None = None
    energies: tuple[sp.Expr, sp.Expr, sp.Expr] | None = field(default=None, repr=False)
    pivot_reactions: Mapping[str, tuple[sp.Expr, sp.Expr]] = field(default_factory=dict,
                                                                   repr=False)
    # joints (bodies pinned together): each one, and the impulse (x, y) it gave its
    # second body in the scene frame (the first received the opposite)
    joints: tuple[Any, ...] = field(default=(), repr=False)
    joint_impulses: Mapping[str, tuple[sp.Expr, ...]] = field(default_factory=dict,
                                                                  repr=False)
    # a 3-D contact: its tangential impulse's components along its tangents t1, t2
    tangent_impulses: Mapping[str, tuple[sp.Expr, sp.Expr]] = field(default_factory=dict,
                                                                    repr=False)
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    speeds_before: tuple[Any, ...] = ()
    speeds_after: sp.ImmutableMatrix | None = None
    method: str = field(default="", repr=False)
    energy_tolerance: float | None = field(default=None, repr=False)
    history: Any = field(default=None, repr=False, compare=False)
    # a model whose Solution lists no bodies (a mechanics system) gives its own residuals
    given_checks: Mapping[str, Any] | None = field(default=None, repr=False, compare=False)

    @cached_property
    def _certificate(self) -> dict[str, Any]:
        if self.given_checks is not None:
            # a model's own residuals: floating point unless they say otherwise
            return {"_exact": False, "_floats": True, **self.given_checks}
        if self.speeds_after is not None or not self.contacts:
            return {}  # a mechanics system's: its own coordinates
        locked = {c.split(":")[0] for c in self.courses if "lock" in c}
        if self.regime and "lock" in self.regime:
            locked |= set(self.acted)
        return residuals(self.before, self.after, self.contacts, self.impulses,
                         self.tangential, self.rule, self.acted, tuple(locked),
                         self.joints, self.joint_impulses, self.conditions, self.path)

    @property
    def checks(self) -> dict[str, Any]:
        """Each law's residual, computed from the bodies and impulses alone (see
        :mod:`rigidimpact.solve.certificate`): zero where it holds, exact where the
        answer is exact; empty with symbols left (the closed forms are checked where
        they are derived). A mechanics system gives its own, from its bodies' kinetic
        energy and its points' velocities, apart from the M and J it was solved with
        (:meth:`rigidimpact.mechanics.impact.SystemImpact._checks`).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> checks = Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...                 Contact(restitution=1)).solve().checks
        >>> checks["a.momentum_x"], checks["contact.opens"], checks["energy"]
        (0, 0, 0)
        """
        return {k: as_sympy(v) for k, v in self._certificate.items() if not k.startswith("_")}

    def assessed(self) -> tuple[list[str], list[str]]:
        """(warnings, failures) of :attr:`checks`: the model's physical limits here,
        and the conditions broken beyond the arithmetic's tolerance."""
        return assess(self._certificate, self.rule, self.contacts)

    @property
    def contact(self) -> Contact:
        """The (first) contact."""
        return self.contacts[0]

    @property
    def contact_impulse(self) -> tuple[sp.Expr, sp.Expr]:
        """The first contact's impulse (normal, tangential) in its own frame."""
        name = self.contact.name
        return self.impulses[name], self.tangential.get(name, sp.Integer(0))

    @cached_property
    def kinetic_energy_before(self) -> sp.Expr:
        """Total kinetic energy just before the impact."""
        if self.energies is not None:
            return self.energies[0]
        return sum((b.kinetic_energy for b in self.before), sp.Integer(0))

    @cached_property
    def energy_lost(self) -> sp.Expr:
        """Kinetic energy lost (negative: the model created energy)."""
        if self.energies is not None:
            return self.energies[1]
        after = sum((b.kinetic_energy for b in self.after), sp.Integer(0))
        return tidy(self.kinetic_energy_before - after)

    @cached_property
    def energy_loss_fraction(self) -> sp.Expr:
        """``(K_i - K_f) / K_i``, the paper's eq. (7) for the barbell; negative when the
        model created energy."""
        if self.energies is not None:
            return self.energies[2]
        after = sum((b.kinetic_energy for b in self.after), sp.Integer(0))
        return tidy(1 - after / self.kinetic_energy_before)

    @property
    def frictional(self) -> bool:
        """Whether the rule ran with friction (its tangential impulses are kept)."""
        return bool(self.tangential) and any(c.laws[1].grips for c in self.contacts)

    @property
    def matrix(self) -> sp.Matrix:
        """A mechanics system's H with ``u+ = H u-`` (linear in the speeds before for
        every law except friction whose course depends on them).

        Examples
        --------
        >>> u = sp.Symbol("u")
        >>> Solution(before=(), after=(), impulses={}, speeds_before=(u,),
        ...          speeds_after=sp.ImmutableMatrix([-u / 2])).matrix
        Matrix([[-1/2]])
        """
        if self.speeds_after is None:
            raise ValueError("only an impact of generalized speeds has this matrix")
        return self.speeds_after.jacobian(sp.Matrix(self.speeds_before))

    @property
    def label(self) -> str:
        """``simultaneous`` or ``sequential left, right``."""
        return self.rule if not self.order else f"{self.rule} {', '.join(self.order)}"

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
        return (f"Solution({self.label!r}, bodies={[b.name for b in self.before]}, "
                f"acted={list(self.acted)})")

    def _repr_latex_(self) -> str:
        r"""The results, typeset in the paper's notation (Jupyter); a mechanics system's
        speeds after as ``u^+ = ...``.

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> from rigidimpact.laws.contact import Contact
        >>> from rigidimpact.solve.impact import Impact
        >>> print(Impact(Body.particle(1, (2, 0), "a"), Body.particle(1, name="b"),
        ...       Contact(restitution=1)).solve()._repr_latex_()[:43])
        $$\begin{aligned} v_{x,\mathrm{a}}^{+} &= 0
        """

        if self.speeds_after is not None:
            rows = " \\\\ ".join(f"{sp.latex(u)}^{{+}} &= {sp.latex(v)}" for u, v in
                                 zip(self.speeds_before, self.speeds_after, strict=True))
            return f"$$\\begin{{aligned}} {rows} \\end{{aligned}}$$"
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
        normal, along = self.contact_impulse
        if self.frame != EYE:  # the one-contact core's own frame (a tilt kept symbolic)
            return (self.frame.T * sp.ImmutableMatrix([normal, along])).applyfunc(tidy)
        c = self.contact
        if tuple(c.normal) == (1, 0):
            return sp.ImmutableMatrix([normal, along])
        return (normal * c.unit_normal + along * c.tangent).applyfunc(tidy)

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
        momentum less the contact impulses it received.

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
        if body.name in self.pivot_reactions:
            return sp.ImmutableMatrix(self.pivot_reactions[body.name])
        if len(self.contacts) != 1:
            raise ValueError(f"no pivot reaction was found for {body.name}")
        names = [b.name for b in self.before]
        index = names.index(body.name)
        second = self.contact.second if self.contact.bodies else names[1]
        given = self.impulse if body.name == second else -self.impulse
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
        (not for a fixed body), ``impulse`` (the first contact's normal impulse) and
        ``energy_loss_fraction`` (and ``impulse_t`` when one contact sticks),
        ``CONTACT.normal_impulse`` and ``CONTACT.tangential_impulse`` for every contact,
        ``BODY.pivot_impulse_x``, ``BODY.pivot_impulse_y`` for a pivoted body, and
        ``JOINT.impulse_x``, ``JOINT.impulse_y`` for a joint (what it gave its second body);
        in 3-D, ``BODY.vz`` and ``BODY.omega_x`` ... ``_z`` among the speeds, and
        ``CONTACT.tangential_impulse_1``, ``_2`` along the contact's tangents (its
        ``tangential_impulse`` is then the size).

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
        if self.speeds_after is not None:  # a mechanics system: its speeds after
            for speed, value in zip(self.speeds_before, self.speeds_after, strict=True):
                results[str(speed.func if isinstance(speed, AppliedUndef) else speed)] = value
        for body in self.after:
            if body.support == "fixed":
                continue
            results[f"{body.name}.vx"] = body.velocity[0]
            results[f"{body.name}.vy"] = body.velocity[1]
            results[f"{body.name}.omega"] = sp.sympify(body.spin)
        first = next(iter(self.impulses))
        results["impulse"] = self.impulses[first]
        if len(self.contacts) == 1 and self.contact.laws[1].unknown_tangential \
                and self.speeds_after is None:
            results["impulse_t"] = self.tangential_impulse
        results["energy_loss_fraction"] = self.energy_loss_fraction
        for name, impulse in self.impulses.items():
            results[f"{name}.normal_impulse"] = impulse
            results[f"{name}.tangential_impulse"] = self.tangential.get(name, sp.Integer(0))
        for body in self.before:
            if body.support == "pivot":
                reaction = self.pivot_impulse(body)
                results[f"{body.name}.pivot_impulse_x"] = reaction[0]
                results[f"{body.name}.pivot_impulse_y"] = reaction[1]
        for name, parts in self.joint_impulses.items():  # (x, y) in the plane; (x, y, z)
            for axis, x in zip("xyz", parts[:3], strict=False):  # in space, then a hinge's
                results[f"{name}.impulse_{axis}"] = x  # moments across its axis
            for k, x in enumerate(parts[3:], start=1):
                results[f"{name}.moment_{k}"] = x
        for name, (t1, t2) in self.tangent_impulses.items():
            results[f"{name}.tangential_impulse_1"] = t1
            results[f"{name}.tangential_impulse_2"] = t2
        return results


def certified(solution: Solution, limits: bool = True) -> Solution:
    """`solution` with the physical limits its checks show among its warnings (unless
    `limits` is False: a model that words its own), or one line refusing it when it
    breaks a condition its rule imposed (a numerical failure: the answer would be
    wrong)."""
    warnings, failures = solution.assessed()
    if failures:
        raise InputError("impact", f"the {solution.rule} rule's answer fails its own "
                         f"check ({'; '.join(failures[:3])}): it is not given; please "
                         "report the scene")
    if not limits:
        return solution
    new = tuple(w for w in warnings if w not in solution.warnings)
    return replace(solution, warnings=solution.warnings + new) if new else solution


def read_back(contacts: Any, impulses: Mapping[str, Any], *, certify: bool = True,
              limits: bool = True, **fields: Any) -> Solution:
    """The one builder of a :class:`Solution`, which every source's reading back ends
    in (the planar shapes' bodies after, a 3-D collision's and a mechanics system's
    speeds after; the paper's two-body core keeps its own, with the paper's notation):
    the contacts and each one's normal impulse, the rest as the Solution takes them
    (`acted`, unless given, is every contact that pushed). Certified on the way out
    (:func:`certified`, `limits` as it takes it) unless `certify` is False: a closed
    form no point of whose symbols is an impact has nothing to be checked at."""
    if fields.get("acted") is None:
        fields["acted"] = tuple(name for name, p in impulses.items() if p != 0)
    for key in ("acted", "courses", "speeds_before", "order"):
        if key in fields:
            fields[key] = tuple(fields[key])
    if fields.get("speeds_after") is not None:
        fields["speeds_after"] = sp.ImmutableMatrix(fields["speeds_after"])
    solution = Solution(before=fields.pop("before", ()), after=fields.pop("after", ()),
                        impulses=dict(impulses), contacts=tuple(contacts), **fields)
    return certified(solution, limits=limits) if certify else solution
