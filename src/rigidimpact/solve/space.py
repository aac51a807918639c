"""Impacts in three dimensions: bodies with six speeds each and contacts, each with its
normal and two tangents.

The model is the same as in the plane, one dimension up: the speeds u of every free
body (``vx, vy, vz, omega_x, omega_y, omega_z``), ``M^-1`` block diagonal
(``1/m`` three times, then the inverse of the inertia tensor in the world frame), the
contact's three rows J in its own frame (n, t1, t2: :func:`rigidimpact.laws.cone.tangents`),
``v = J u`` and ``W = J M^-1 J^T``. The contact's laws give the impulse P in contact space
(:func:`rigidimpact.laws.cone.cone_impact` for Coulomb's circular cone), and
``u+ = u- + M^-1 J^T P``. Several contacts: where one strikes and the others rest, the
impact is followed in the striking one's normal impulse (:meth:`SpaceCollision.driven`);
where several strike, the simultaneous rule: the plane's one implementation on the
problem of rows (:class:`SpaceRows`), exact for smooth contacts and with Coulomb's
circular cone in floating point, or with the cone as a pyramid of a stated number of
edges (``facets``; the rule's own, as in the plane).

What comes back is the one :class:`~rigidimpact.solve.solution.Solution`: its speeds are
named ``BODY.vx`` ... ``BODY.omega_z`` (the result keys), each contact's tangential
impulse has its two components (``CONTACT.tangential_impulse_1``, ``_2``, along t1 and
t2; ``CONTACT.tangential_impulse`` is its size), and its residuals are computed here,
from the bodies' momenta, apart from the path that solved them.

Examples
--------
A solid sphere landing on a floor with spin (the case of the 3-D issue: m = 1, radius 1,
velocity (1, 1/2, -2), spin (3, -1, 2), Newton's e = 1/2, mu = 1/5):

>>> from rigidimpact.laws.contact import Contact
>>> from rigidimpact.model.space import Body3
>>> half, fifth = sp.Rational(1, 2), sp.Rational(1, 5)
>>> ball = Body3.sphere(1, 1, (0, 0, 1), (1, half, -2), (3, -1, 2), name="ball")
>>> floor = Contact(normal=(0, 0, 1), restitution=half, tangential="coulomb",
...                 friction=fifth, bodies=("floor", "ball"), point=(0, 0, 0))
>>> out = SpaceCollision((Body3.fixed("floor"), ball), (floor,)).solve()
>>> r = out.results()
>>> r["ball.vz"], r["contact.normal_impulse"], out.regime
(1, 3, 'slides throughout')
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.cone import tangents
from rigidimpact.laws.contact import Contact
from rigidimpact.lazy import deferred
from rigidimpact.model.impulse import kinetic_energy
from rigidimpact.model.joints import Joint
from rigidimpact.model.space import SPEEDS, Body3
from rigidimpact.solve.certificate import residuals
from rigidimpact.solve.problem import RowsProblem, check_facets
from rigidimpact.solve.registry import conduct
from rigidimpact.solve.rules import (
    Compliant,
    Driven,
    Rule,
    RuleSettings,
    Sequential,
    Simultaneous,
    rule_named,
)
from rigidimpact.solve.solution import Solution, read_back
from rigidimpact.symbolic.given import given_values
from rigidimpact.symbolic.notation import Given

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["SpaceCollision"]


@dataclass(frozen=True)
class SpaceCollision:
    """Bodies in space (:class:`~rigidimpact.model.space.Body3`) and the contacts where
    they meet (each a :class:`~rigidimpact.laws.contact.Contact` with a 3-D normal and
    point, and its two bodies named).

    `tolerance` asks for the contact's path to be integrated numerically with that
    relative tolerance even where a closed form exists (to measure the integration).
    """

    bodies: tuple[Body3, ...]
    contacts: tuple[Contact, ...]
    tolerance: float | None = None
    facets: int | None = None  # several contacts striking at once: the cone itself
    # (None) or a pyramid of this many edges
    # how several contacts act: a Rule, or its name (the registry's: ``rule_named``);
    # None is the default rule, the same as in the plane; `order` goes with a name
    rule: Rule | str | None = None
    order: tuple[str, ...] | None = None
    # ball joints and hinges (:class:`~rigidimpact.model.joints.Joint` in space): their
    # bilateral rows G are eliminated by the projected inverse mass, as in the plane
    joints: tuple[Joint, ...] = ()
    # the compliant rule's stiffness (one, or one per contact) and whether Hertz's
    compliance: tuple[tuple[float, ...], bool] = ((1e6,), False)

    def __post_init__(self) -> None:
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            raise InputError("bodies", "two bodies share a name")
        tolerance = self.tolerance
        if tolerance is not None and (isinstance(tolerance, bool) or not isinstance(
                tolerance, (int, float)) or not 1e-14 <= tolerance <= 1e-2):
            # NaN fails the comparison too: a NaN tolerance never ends an integration
            raise InputError("impact.tolerance", f"a number in [1e-14, 1e-2], not "
                             f"{tolerance!r}")
        if not self.contacts:
            raise InputError("contacts", "at least one contact is needed")
        if not isinstance(self.rule, Rule):
            if self.order is not None and (self.rule != Sequential.name or sorted(
                    self.order) != sorted(c.name for c in self.contacts)):
                raise InputError("impact.order", "with rule = \"sequential\": every "
                                 "contact's name, each once")
            object.__setattr__(self, "rule", rule_named(self.rule, RuleSettings(
                self.order, compliance=self.compliance, tolerance=self.tolerance)))
        if len({c.name for c in self.contacts}) != len(self.contacts):
            raise InputError("contacts", "two contacts share a name")
        for c in self.contacts:
            if not c.spatial:
                raise InputError(f"{c.name}.normal", "a 3-D scene's contact needs a normal "
                                 "with three components")
            if c.bodies is None or not set(c.bodies) <= set(names):
                raise InputError(f"{c.name}.bodies", "must name two of the bodies")
        check_facets(self.facets)
        by_name = {b.name: b for b in self.bodies}
        for c in self.contacts:
            for name in c.bodies or ():
                _touches_its_surface(by_name[name], c)
        free = [b for b in self.bodies if b.support != "fixed"]
        if not free:
            raise InputError("bodies", "at least one body must be free to move")
        if self.joints:
            self._check_joints(names, by_name)

    def _check_joints(self, names: list[str], by_name: Mapping[str, Body3]) -> None:
        """Each joint is in space, names two of the bodies (one at least free to move)
        and a name of its own, lies within a sphere it joins, holds before the impact
        (its two points, and a hinge's turn across its axis, move together), and the
        joints together leave the bodies some freedom."""
        taken = set(names) | {c.name for c in self.contacts}
        for j in self.joints:
            if not isinstance(j, Joint) or not j.spatial:
                raise InputError("joints", "each must be a Joint with a point [x, y, z]")
            if j.name in taken:
                raise InputError(f"{j.name}.name", "a joint's name must differ from every "
                                 "body's, contact's and other joint's")
            taken.add(j.name)
            for side in j.bodies:
                if side not in by_name:
                    raise InputError(f"{j.name}.bodies", f"no body named {side!r}")
                body = by_name[side]
                if body.radius is not None:
                    arm = sp.Matrix(j.point) - sp.Matrix(body.position)
                    reach = arm.dot(arm) - body.radius ** 2
                    if reach.is_number and reach > 0:
                        raise InputError(f"{j.name}.point", f"not on {side}: it is "
                                         f"{sp.sqrt(arm.dot(arm))} from the centre, past the "
                                         f"radius {body.radius}")
            if all(by_name[side].support == "fixed" for side in j.bodies):
                raise InputError(f"{j.name}.bodies", "a joint between two fixed bodies "
                                 "holds nothing: at least one must move")
        G = self.G
        drift = G * self.u_before
        row = 0
        for j in self.joints:
            size = 3 if j.axis is None else 5
            gap = drift[row:row + size, 0]
            row += size
            if all(x.is_number for x in gap) and any(abs(sp.N(x, 30)) > 1e-20 * (
                    1 + max(abs(sp.N(u, 30)) for u in self.u_before)) for x in gap):
                what = "point" if j.axis is None else "point, then turn across the axis,"
                raise InputError(j.name, f"its two bodies do not move together at "
                                 f"{list(j.point)} before the impact (the second's {what} "
                                 f"less the first's: {[_simplified(x) for x in gap]}): give "
                                 "velocities and spins that keep the joint together")
        block = G * self._free_M_inverse * G.T
        if all(x.is_number for x in block) and block.rank() < block.rows:
            raise InputError("joints", "the joints are not independent (a closed loop or a "
                             "body held twice over): their impulses are not fixed")

    @cached_property
    def G(self) -> sp.Matrix:
        """The joints' bilateral rows, ``G u = 0``: each joint's second body's point
        less the first's along x, y and z, and a hinge's relative spin along the two
        directions across its axis (:func:`rigidimpact.laws.cone.tangents`)."""
        rows: list[sp.Matrix] = []
        for j in self.joints:
            for d in (sp.eye(3)[:, i] for i in range(3)):
                rows.append(self._relative_row(j.bodies, j.point, d, turn=False))
            if j.axis is not None:
                _, t1, t2 = tangents(list(j.axis))
                for d in (t1, t2):
                    rows.append(self._relative_row(j.bodies, j.point, d, turn=True))
        return sp.Matrix.vstack(*rows) if rows else sp.zeros(0, 6 * len(self.free))

    def _relative_row(self, bodies: Sequence[str], point: Any, direction: sp.Matrix,
                      turn: bool) -> sp.Matrix:
        """The row taking u to the second body's point velocity (or, with `turn`, its
        spin) less the first's, along `direction`."""
        row = sp.zeros(1, 6 * len(self.free))
        for k, body in enumerate(self.free):
            sign = 1 if body.name == bodies[1] else -1 if body.name == bodies[0] else 0
            if sign:
                part = sp.Matrix([[0, 0, 0, *direction]]) if turn else \
                    body.row(point, direction)
                row[0, 6 * k:6 * k + 6] = sign * part
        return row

    @cached_property
    def free(self) -> tuple[Body3, ...]:
        return tuple(b for b in self.bodies if b.support != "fixed")

    @cached_property
    def speeds(self) -> tuple[sp.Symbol, ...]:
        """The generalized speeds' names: ``BODY.vx`` ... ``BODY.omega_z``."""
        return tuple(sp.Symbol(f"{b.name}.{s}") for b in self.free for s in SPEEDS)

    @cached_property
    def u_before(self) -> sp.Matrix:
        return sp.Matrix([x for b in self.free for x in b.speeds])

    @cached_property
    def _free_M_inverse(self) -> sp.Matrix:
        return sp.diag(*[b.mass_inverse() for b in self.free])

    @cached_property
    def M(self) -> sp.Matrix:
        """The free bodies' mass matrix, block diagonal: each body's mass (three times)
        and its inertia tensor about its centre in the world frame."""
        return sp.diag(*[sp.diag(b.mass, b.mass, b.mass, sp.Matrix(b.inertia))
                         for b in self.free])

    @cached_property
    def M_inverse(self) -> sp.Matrix:
        """``M^-1`` of the free bodies, block diagonal; with joints, projected onto the
        speeds that keep them: ``M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1``."""
        free = self._free_M_inverse
        if not self.joints:
            return free
        G = self.G
        across = free * G.T
        return (free - across * (G * across).inv() * across.T).applyfunc(_simplified)

    def joint_impulses(self, generalized: sp.Matrix) -> dict[str, tuple[sp.Expr, ...]]:
        """Each joint's impulse on its second body, ``(x, y, z)`` and, for a hinge, its
        moments along the two directions across its axis, from the contacts'
        generalized impulse ``J^T P``: ``lambda = -(G M^-1 G^T)^-1 G M^-1 J^T P``."""
        if not self.joints:
            return {}
        G, free = self.G, self._free_M_inverse
        lam = -(G * free * G.T).LUsolve(G * free * generalized)
        out, row = {}, 0
        for j in self.joints:
            size = 3 if j.axis is None else 5
            out[j.name] = tuple(_simplified(x) if not x.has(sp.Float) else x
                                for x in lam[row:row + size, 0])
            row += size
        return out

    def rows(self, contact: Contact) -> sp.Matrix:
        """The contact's rows (n, t1, t2): the second body's touching point's velocity
        less the first's, in the contact frame."""
        frame = sp.Matrix(contact.frame)
        J = sp.zeros(3, 6 * len(self.free))
        for k, body in enumerate(self.free):
            sign = 1 if body.name == contact.second else -1 if body.name == contact.first \
                else 0
            if sign == 0:
                continue
            for i in range(3):
                J[i, 6 * k:6 * k + 6] = sign * body.row(contact.point, frame[i, :].T)
        return J

    def W(self, contact: Contact) -> sp.Matrix:
        """The contact's block ``J M^-1 J^T`` in its frame (n, t1, t2)."""
        J = self.rows(contact)
        return (J * self.M_inverse * J.T).applyfunc(_simplified)

    def solve(self) -> Solution:
        """The impact under the contact's laws (see the module's text); several contacts:
        by the collision's rule (the default rule where none is given, as in the plane).
        Where the rule gives several outcomes (the sequential rule in every order), the
        first; :meth:`outcomes` gives each."""
        return self.outcomes()[0]

    def outcomes(self) -> tuple[Solution, ...]:
        """What the collision's rule makes of it through the one door
        (:meth:`~rigidimpact.solve.rules.base.Rule.answer`): one outcome, or one per
        order; one contact, its own answer under every rule."""
        if len(self.contacts) == 1:
            (c,) = self.contacts
            v = (self.rows(c) * self.u_before)[0]
            if sp.sympify(v).is_number and not v < 0:
                raise InputError("bodies", f"the touching points at {c.name} are not "
                                 f"approaching (their normal velocity is {_simplified(v)}, "
                                 f"along the normal from {c.first} into {c.second})")
        elif not self._numbers()[2]:
            raise InputError("contacts", "several 3-D contacts are solved where one or more "
                             "of them approach; here none approaches")
        assert isinstance(self.rule, Rule)  # made one in __post_init__
        found = self.rule.answer(SpaceRows.of(self))
        return tuple(self._every_contact(o) for o in found)

    def _certificate(self, acting: Sequence[Contact], P: Mapping[str, Sequence[Any]],
                     u_after: Any, pinned: Mapping[str, Sequence[Any]], rule: str,
                     acted: Sequence[str], integrated: float | None
                     ) -> dict[str, Any] | None:
        """The one certificate (:func:`rigidimpact.solve.certificate.residuals`), the
        plane's, on the bodies before and after and each acting contact's impulse in
        its frame (n, t1, t2): momentum and angular momentum, no pull, no
        penetration, the cone and friction's direction, each law's end, the joints,
        the energy; a closed form with symbols at seeded random rational points. An
        `integrated` answer (its integrator's relative tolerance) is held to 1000 times
        that tolerance; None where no point of a closed form's symbols is an impact."""
        moved = {b.name: b.moved(u_after[6 * k:6 * k + 6]) for k, b in enumerate(self.free)}
        after = [moved.get(b.name, b) for b in self.bodies]
        found = residuals(self.bodies, after, acting,
                          {c.name: P[c.name][0] for c in acting},
                          {c.name: tuple(P[c.name][1:]) for c in acting}, rule, acted,
                          joints=self.joints, joint_impulses=pinned)
        if not found:
            return None
        if integrated is not None:
            found["_tolerance"] = max(1e-8, 1000 * integrated)
        return found

    def _every_contact(self, solved: Solution) -> Solution:
        """The answer with every contact in the scene's order, a contact that took no part
        with zero impulses (``impulse`` is the first contact's, as in the plane)."""
        zero = sp.Integer(0)
        return replace(solved, contacts=self.contacts, impulses={
            c.name: solved.impulses.get(c.name, zero) for c in self.contacts},
            tangential={c.name: solved.tangential.get(c.name, zero) for c in self.contacts},
            tangent_impulses={c.name: solved.tangent_impulses.get(c.name, (zero, zero))
                              for c in self.contacts})

    def _numbers(self) -> tuple[dict[str, np.ndarray], np.ndarray, list[Contact],
                                list[Contact]]:
        """Each contact's rows and the speeds before in floating point, and the contacts
        approaching and those touching at rest (several 3-D contacts are solved at
        numbers)."""
        numbers = [*self.u_before, *self.M_inverse, *(x for c in self.contacts
                                                       for x in self.rows(c))]
        if not all(sp.sympify(x).is_number for x in numbers) or not all(
                sp.sympify(c.friction or 0).is_number for c in self.contacts):
            raise InputError("contacts", "several 3-D contacts are followed numerically: "
                             "give numbers for every symbol")
        rows = {c.name: np.array(self.rows(c).evalf(30), dtype=float) for c in self.contacts}
        u = np.array(self.u_before.evalf(30), dtype=float).ravel()
        speeds = {name: J @ u for name, J in rows.items()}
        size = max(float(np.abs(u).max()), 1e-300)
        approaching = [c for c in self.contacts if speeds[c.name][0] < -1e-12 * size]
        resting = [c for c in self.contacts if abs(speeds[c.name][0]) <= 1e-12 * size]
        return rows, u, approaching, resting

    def simultaneous(self) -> Solution:
        """Several contacts acting together at the velocity level (Newton's law, Coulomb's
        circular cone by the plane's rule, or the pyramid of ``facets`` edges): the
        plane's one implementation on the problem of rows."""
        return replace(self, rule=Simultaneous()).solve()

    def sequential(self, order: Sequence[str]) -> Solution:
        """One contact at a time in `order`, each its own impact under its own laws,
        passes repeated until none approaches: the plane's rule, at numbers."""
        return replace(self, rule=Sequential(tuple(order))).solve()

    def compliant(self, stiffness: Sequence[float] | float = 1e6,
                  hertz: bool = False) -> Solution:
        """Every contact a push-only spring-dashpot (or an elastic Hertz spring),
        integrated until all let go: the plane's rule, smooth contacts, at numbers."""
        springs = tuple(stiffness) if isinstance(stiffness, Sequence) else stiffness
        return replace(self, rule=Compliant(springs, hertz)).solve()

    def driven(self) -> Solution:
        """The one contact that approaches strikes, the others rest (the plane's rule,
        :func:`rigidimpact.solve.rules.driven.driven`, in floating point)."""
        return replace(self, rule=Driven(self.tolerance)).solve()

    def at(self, values: Mapping[sp.Symbol, Any]) -> SpaceCollision:
        """The collision with numbers put in for its symbols (Python or SymPy numbers,
        each checked: :func:`~rigidimpact.symbolic.given.given_values`)."""
        values = given_values(values)
        return SpaceCollision(tuple(b.at(dict(values)) for b in self.bodies),
                              tuple(c.at(values) for c in self.contacts), self.tolerance,
                              self.facets, self.rule, self.order,
                              tuple(j.at(dict(values)) for j in self.joints), self.compliance)


@dataclass(frozen=True)
class SpaceRows(RowsProblem):
    """A 3-D collision as the one problem of rows every rule reads: its six speeds a
    free body, its projected M^-1 and each contact's rows (n, t1, t2). What a rule makes
    of it comes back as the 3-D Solution, checked by the one certificate
    (:meth:`SpaceCollision._certificate`)."""

    space: Any = None

    @classmethod
    def of(cls, space: SpaceCollision) -> SpaceRows:
        """The one assembly of a 3-D collision into the problem of rows."""
        rows = [space.rows(c) for c in space.contacts]
        return cls(space.contacts, speeds=tuple(map(str, space.speeds)),
                   velocities=sp.ImmutableMatrix(space.u_before),
                   inverse_mass=sp.ImmutableMatrix(space.M_inverse),
                   normal_rows=sp.ImmutableMatrix([list(J[0, :]) for J in rows]),
                   tangent_rows=sp.ImmutableMatrix([list(J[1, :]) for J in rows]),
                   second_tangent_rows=sp.ImmutableMatrix([list(J[2, :]) for J in rows]),
                   facets=space.facets, tolerance=space.tolerance, space=space)

    def numbers_only(self, rule: str) -> None:
        """Checked already: several 3-D contacts are solved at numbers."""

    def smooth_only(self, where: str) -> None:
        rough = [c.name for c in self.contacts if c.laws[1].grips]
        if rough:
            raise InputError(f"{rough[0]}.tangential", "the compliant rule's springs act "
                             f"along the normals (smooth contacts), not {where} with "
                             "friction: use the driven, simultaneous or sequential rule")

    def outcome(self, rule: str, order: Sequence[str], u: sp.Matrix,
                impulses: Mapping[str, sp.Expr], acted: Sequence[str], passes: int = 1,
                **more: Any) -> Solution:
        """The 3-D reading back: each contact's impulse in its frame (n, t1, t2) and the
        size of its tangential part, the speeds after, the energies from M, the joints'
        impulses, certified by the one certificate (exactly, or within 1000 times the
        integration's tolerance). One contact's closed form is tidied as a formula;
        an answer in floating point is given to 17 digits."""
        space = self.space
        exact = not any(sp.sympify(x).has(sp.Float) for x in u)
        one = len(self.contacts) == 1
        # floats as the rule gave them (a sequential run rounded to 60 digits keeps them)
        u_after = sp.Matrix([sp.piecewise_fold(sp.radsimp(sp.expand(x))) if exact and one
                             else sp.sympify(x) for x in u])
        zero = sp.Integer(0)
        sideways = more.get("tangent_impulses") or {}
        P = {c.name: [sp.sympify(x) for x in (impulses[c.name],
                                              *sideways.get(c.name, (zero, zero)))]
             for c in self.contacts}
        if exact and one:
            P = {name: [sp.radsimp(x) for x in parts] for name, parts in P.items()}
        before = kinetic_energy(space.M, space.u_before)
        lost = before - kinetic_energy(space.M, u_after)
        pinned = space.joint_impulses(sum(
            (space.rows(c).T * sp.Matrix(P[c.name]) for c in self.contacts),
            sp.zeros(6 * len(space.free), 1))) if space.joints else {}
        checks = space._certificate(list(self.contacts), P, u_after, pinned, rule, acted,
                                    None if exact else space.tolerance or 1e-10)
        courses = tuple(more.get("courses") or (
            f"{c.name}: {'acts' if c.name in acted else 'released'}" for c in self.contacts))
        notes = list(more.get("notes", ()))
        if conduct(rule).summary:
            notes.append(conduct(rule).summary)
        elif exact and conduct(rule).whole_impact and not one:
            notes.append("every contact smooth: the simultaneous rule's one "
                         "implementation (the plane's), exact")
        written = exact and not any(x.has(sp.Float) for p in P.values() for x in p)
        tidied = sp.simplify if written and one else sp.radsimp
        if written:
            speeds_after, lost = sp.ImmutableMatrix(list(u_after)), tidied(lost)
            fraction = tidied(lost / before)
        else:
            speeds_after = sp.ImmutableMatrix([x if isinstance(x, sp.Float) else
                                               sp.Float(x, 17) for x in u_after])
            pinned = {name: tuple(sp.Float(x, 17) for x in parts)
                      for name, parts in pinned.items()}
            fraction = lost / before
        sizes = {c.name: (sp.simplify if written and one else sp.sympify)(
            sp.sqrt(P[c.name][1] ** 2 + P[c.name][2] ** 2)) for c in self.contacts}
        return read_back(
            self.contacts, {c.name: P[c.name][0] for c in self.contacts},
            certify=checks is not None, tangential=sizes, speeds_before=space.speeds,
            speeds_after=speeds_after, energies=(before, lost, fraction), courses=courses,
            regime=_course_of(courses[0], self.contacts[0].name) if one
            else "; ".join(courses), given_checks=checks, acted=acted, notes=tuple(notes),
            tangent_impulses={c.name: (P[c.name][1], P[c.name][2]) for c in self.contacts},
            joint_impulses=pinned, rule=rule, order=order, passes=passes,
            method=more.get("method", ""))  # assessed under its own rule


def _course_of(line: str, name: str) -> str:
    """A contact's course without its name in front (a course with values in it stays
    a :class:`Given`, so the document sets them as mathematics)."""
    prefix = f"{name}: "
    if isinstance(line, Given) and line.template.startswith(prefix):
        return Given(line.template[len(prefix):], *line.values)
    return line.split(": ", 1)[1]


def _touches_its_surface(body: Body3, contact: Contact) -> None:
    """A sphere is touched on its surface, along a normal through its centre (as the
    plane asks of a disc): refused in one line otherwise, where the numbers say so."""
    if body.radius is None or body.support == "fixed":
        return
    arm = sp.Matrix(contact.point) - sp.Matrix(body.position)
    normal = sp.Matrix(contact.normal)
    reach = sp.sqrt(arm.dot(arm))
    across = arm.cross(normal)
    size = sp.sqrt(normal.dot(normal)) * body.radius
    if not all(sp.sympify(x).is_number for x in (*arm, *normal, body.radius)):
        return
    if abs(sp.N(reach - body.radius, 30)) > 1e-9 * sp.N(body.radius, 30):
        raise InputError(f"{contact.name}.point", f"is {sp.N(reach, 6)} from {body.name}'s "
                         f"centre, not its radius {sp.N(body.radius, 6)}: a sphere is "
                         "touched on its surface")
    if sp.N(sp.sqrt(across.dot(across)), 30) > 1e-9 * sp.N(size, 30):
        raise InputError(f"{contact.name}.normal", f"misses {body.name}'s centre: a "
                         "sphere's contact normal runs through its centre")


def _simplified(x: sp.Expr) -> sp.Expr:
    """Simplified with symbols; exact when rational; else 50 digits (sines of numbers)."""
    if not x.is_number:
        return sp.simplify(x)
    if x.is_Rational or not x.has(sp.sin, sp.cos):
        return sp.radsimp(x)
    return sp.N(x, 50)
