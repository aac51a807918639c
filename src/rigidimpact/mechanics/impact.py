"""The impact map of a sympy.physics.mechanics system.

sympy.physics.mechanics builds the equations of motion of a multibody system (a
``KanesMethod``, or a ``System`` after ``form_eoms``) but has no impulsive events. An
impact at a point of such a system is the same problem as for the built-in shapes, in
generalized speeds u instead of body velocities:

- the mass matrix M(q) of the speeds is the system's own (``mass_matrix``);
- each contact point's velocity, relative to the other body (or the fixed ground), is
  linear in u: its components along the contact's unit normal and tangent give the
  contact's two Jacobian rows, ``v = J u`` (sympy's partial velocities);
- an impulse P at the contacts changes the speeds by ``M (u+ - u-) = J^T P``, so the
  contact velocities change by ``W P`` with ``W = J M^-1 J^T``;
- each contact's laws (the same objects as everywhere in rigidimpact: Newton's, Poisson's
  or the energetic restitution, smooth, stick, Coulomb or rough) fix P in contact space.

The normal of a contact points out of the surface, toward the system's point (the
direction in which the contact pushes it); the tangent is the normal turned by +90
degrees about the frame's z axis. A contact approaches when ``n . (v_point - v_other)`` is
negative.

Examples
--------
A pendulum (a particle of mass m on a massless rod of length l hinged at O) strikes a
wall at its lowest point with Newton's e: its rate reverses and is scaled by e.

>>> import sympy as sp
>>> import sympy.physics.mechanics as me
>>> q, u = me.dynamicsymbols("q u")
>>> m, l, e = sp.symbols("m l e", positive=True)
>>> N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
>>> A.orient_axis(N, N.z, q)
>>> A.set_ang_vel(N, u * N.z)
>>> O = me.Point("O"); O.set_vel(N, 0)
>>> bob = O.locatenew("bob", -l * A.y)
>>> bob.v2pt_theory(O, N, A)
l*u(t)*A.x
>>> kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
>>> _ = kane.kanes_equations([me.Particle("P", bob, m)], [])
>>> hit = impact(kane, [contact(bob, N.x, restitution=e)], frame=N)
>>> hit.solve().speeds_after[0].subs(q, 0)
-e*u(t)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import mpmath
import sympy as sp
import sympy.physics.mechanics as me
from sympy.polys.constructor import construct_domain
from sympy.polys.matrices import DomainMatrix

from rigidimpact.errors import InputError
from rigidimpact.laws.cone import tangents
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.mechanics.certify import FLOAT_DIGITS
from rigidimpact.mechanics.certify import checks as certify_checks
from rigidimpact.mechanics.certify import wide as _wide
from rigidimpact.mechanics.kernel import MapKernel
from rigidimpact.mechanics.rows import SystemRows
from rigidimpact.model.impulse import kinetic_energy
from rigidimpact.solve.collision import (
    MAX_ENUMERATED,
    Rule,
    Simultaneous,
)
from rigidimpact.solve.lcp import least_norm
from rigidimpact.solve.registry import conduct
from rigidimpact.solve.rules.simultaneous import simultaneous_cases
from rigidimpact.solve.solution import Solution, read_back
from rigidimpact.symbolic.notation import labelled
from rigidimpact.symbolic.rewrite import pythagorean

# a closed form (symbols left) is sought where its work is at most this: the symbols
# times the product of the linear system's rows' terms (a bound on the fraction-free
# solve's terms). A chain of four point masses on links (3.9e5) solves in 8 s, the compass
# gait (6.5e6) in seconds; a chain of five (1.4e7) ran past 200 s
MAX_SYMBOLIC_TERMS = 10**7

__all__ = ["PointContact", "contact", "SystemImpact", "ImpactMap", "impact", "system_matrix"]


@dataclass(frozen=True)
class PointContact:
    """A point of a mechanics system meeting the ground or another of its points.

    Parameters
    ----------
    point : sympy.physics.mechanics.Point
        The system's point that strikes (its velocity must be set in the frame).
    normal : sympy.physics.mechanics.Vector
        Out of the surface, toward `point` (any nonzero length).
    laws : Contact
        The contact's restitution and tangential laws (their coefficients).
    other : Point, optional
        The point it strikes on another body of the system; None for the fixed ground.
    """

    point: Any
    normal: Any
    laws: Contact
    other: Any = None

    @property
    def name(self) -> str:
        return self.laws.name


def contact(point: Any, normal: Any, *, other: Any = None, restitution: Any = 0,
            tangential: str = "smooth", law: str = "newton", friction: Any = None,
            tangential_restitution: Any = None, name: str = "contact") -> PointContact:
    """A contact of a mechanics system with its laws (as for a scene's ``[contact]``).

    Examples
    --------
    >>> import sympy.physics.mechanics as me
    >>> N = me.ReferenceFrame("N")
    >>> contact(me.Point("foot"), N.y, restitution=0, tangential="stick").laws
    Contact(normal=(1, 0), restitution=0, tangential='stick', law='newton')
    """
    if not isinstance(name, str) or not name:
        raise InputError("name", f"must be a contact's name (text), not {name!r}")
    for what, value in (("point", point), ("other", other)):
        if (value is not None or what == "point") and not isinstance(value, me.Point):
            raise InputError(f"{name}.{what}", "must be a sympy.physics.mechanics Point, "
                             f"not {type(value).__name__} {value!r}")
    if not isinstance(normal, me.Vector):
        raise InputError(f"{name}.normal", "must be a sympy.physics.mechanics Vector (such "
                         f"as N.y), not {type(normal).__name__} {normal!r}")
    if normal == me.Vector(0):
        raise InputError(f"{name}.normal", "must not be the zero vector")
    laws = Contact(restitution=restitution, tangential=tangential, law=law, name=name,
                   friction=friction, tangential_restitution=tangential_restitution)
    return PointContact(point, normal, laws, other)


ImpactMap = Solution  # what an impact does to a mechanics system: the one result type


@dataclass(frozen=True)
class SystemImpact:
    """The impact problem of a mechanics system: M(q), one (normal, tangent) Jacobian row
    pair per contact, and the contacts' laws. See :func:`impact`."""

    frame: Any
    q: tuple[Any, ...]
    u: tuple[Any, ...]
    M: sp.ImmutableMatrix
    contacts: tuple[PointContact, ...]
    before: tuple[Any, ...] | None = None  # the speeds' values before (None: u itself)
    # rows (normal, tangent) of every contact in turn, v = J u; formed from the points'
    # partial velocities when not given (at() gives it with numbers put in)
    J: Any = None
    # dependent speeds (a nonholonomic system): every speed, independent first, and T
    # with u_all = T u (the velocity constraints solved for the dependent ones)
    fold: tuple[tuple[Any, ...], sp.ImmutableMatrix] | None = None
    # at numbers out of the rationals (sin(3/10), sqrt(2)): every number as a Float of
    # this many digits, chosen before any case analysis (None: exact)
    digits: int | None = None
    # rows (n, t1, t2) of every contact in turn where a rough or sticking contact's point
    # can slide across a tangent plane (a 3-D contact; laws.cone.tangents gives t1, t2)
    J_plane: Any = None
    # the system's own bodies, its kinematic equations (q' as the speeds give it) and the
    # numbers put in by at(): the certificate's independent view of the same system (its
    # kinetic energy and its points' velocities), apart from the M and J solved with
    bodies: tuple[Any, ...] = ()
    kinematics: tuple[tuple[Any, Any], ...] = ()
    values: tuple[tuple[Any, Any], ...] = ()

    @property
    def u_before(self) -> sp.Matrix:
        return sp.Matrix(self.before if self.before is not None else self.u)

    def __post_init__(self) -> None:
        if self.J is None:
            for c in self.contacts:
                self._check_linear(c)
            # a gripping contact across a tangent plane has the rows (n, t1, t2): its
            # (n, t) pair is their first two, simplified once
            across = {c.name: c.laws.laws[1].grips and self._across(c)
                      for c in self.contacts}
            planes = {c.name: self._plane_rows(c) for c in self.contacts
                      if across[c.name]}
            rows: list[list[sp.Expr]] = []
            for c in self.contacts:
                rows += planes[c.name][:2] if across[c.name] else list(self._rows(c))
            object.__setattr__(self, "J", sp.ImmutableMatrix(rows))
            if planes:
                plane: list[list[sp.Expr]] = []
                for c in self.contacts:
                    plane += planes.get(c.name) or self._plane_rows(c)
                object.__setattr__(self, "J_plane", sp.ImmutableMatrix(plane))
        for i, c in enumerate(self.contacts):
            if all(x == 0 for x in self.J[2 * i:2 * i + 2, :]):
                raise InputError(f"{c.name}.point", "its velocity does not depend on the "
                                 "system's speeds: nothing there can be struck")

    def _unit(self, c: PointContact) -> tuple[Any, Any]:
        n = c.normal
        length = sp.sqrt(sp.trigsimp(n.dot(n)))
        if length == 0:
            raise InputError(f"{c.name}.normal", "must not be the zero vector")
        n = n / length
        return n, self.frame.z.cross(n)

    def _rows(self, c: PointContact) -> tuple[list[sp.Expr], list[sp.Expr]]:
        """The contact's (normal, tangent) rows in the plane of its normal and the
        frame's z (a gripping contact across a tangent plane takes its first two
        rows of :meth:`_plane_rows` instead)."""
        partials = self._partials(c)
        n, t = self._unit(c)
        rows = sp.Matrix([[p.dot(n) for p in partials], [p.dot(t) for p in partials]])
        if self.fold is not None:  # along the independent speeds: v = J_all T u
            rows = rows * self.fold[1]
        return ([_no_tan(sp.trigsimp(x)) for x in rows.row(0)],
                [_no_tan(sp.trigsimp(x)) for x in rows.row(1)])

    def _velocity(self, c: PointContact) -> Any:
        """The contact point's velocity (relative to the other point's)."""
        try:
            velocity = c.point.vel(self.frame)
            if c.other is not None:
                velocity = velocity - c.other.vel(self.frame)
        except ValueError:
            raise InputError(f"{c.name}.point", f"its velocity in {self.frame} is not "
                             "defined (set_vel or v2pt_theory)") from None
        return velocity

    def _partials(self, c: PointContact) -> list[Any]:
        """The contact point's partial velocities."""
        speeds = self.u if self.fold is None else self.fold[0]
        return me.partial_velocity([self._velocity(c)], list(speeds), self.frame)[0]

    def _check_linear(self, c: PointContact) -> None:
        """Refuse a contact point whose velocity is not linear in the speeds."""
        speeds = self.u if self.fold is None else self.fold[0]
        velocity = self._velocity(c)
        rest = (velocity - sum((p * s for p, s in zip(self._partials(c), speeds,
                                                          strict=True)),
                               me.Vector(0))).simplify()
        if rest != me.Vector(0) and any(x != 0 for x in rest.to_matrix(self.frame)):
            raise InputError(f"{c.name}.point", "its velocity has a part that is not linear "
                             "in the speeds (a driven or moving constraint): not supported")

    def _across(self, c: PointContact) -> bool:
        """Whether the contact's point can slide in two directions across its normal (a
        tangent plane: a 3-D contact), not along one tangent only."""
        n, t = self._unit(c)
        if all(sp.trigsimp(x) == 0 for x in t.to_matrix(self.frame)):
            return True  # the normal along the frame's z: no tangent in the x-y plane
        across = n.cross(t)
        return any(pythagorean(p.dot(across)) != 0 for p in self._partials(c))

    def _plane(self, c: PointContact) -> tuple[Any, Any, Any]:
        """The contact's frame (n, t1, t2) as vectors (:func:`rigidimpact.laws.cone.tangents`
        applied to the normal's components in the system's frame)."""
        axes = (self.frame.x, self.frame.y, self.frame.z)
        return tuple(sum((x * a for x, a in zip(column, axes, strict=True)), me.Vector(0))
                     for column in tangents(c.normal.to_matrix(self.frame)))

    def _plane_rows(self, c: PointContact) -> list[list[sp.Expr]]:
        partials = self._partials(c)
        rows = sp.Matrix([[p.dot(d) for p in partials] for d in self._plane(c)])
        if self.fold is not None:
            rows = rows * self.fold[1]
        return [[_no_tan(pythagorean(x)) for x in rows.row(i)] for i in range(3)]

    def _in_plane(self, after: sp.Matrix, P: sp.Matrix, courses: dict[str, str],
                  rule: str = "simultaneous", exact: bool = True,
                  notes: tuple[str, ...] = ()) -> Solution:
        """The Solution of contacts with tangent planes: the speeds after, each
        contact's impulse (n, t1, t2 in turn, its tangential part's size reported),
        checked from the system's own bodies and points."""
        M = sp.Matrix(self.M)
        before = kinetic_energy(M, self.u_before)
        lost = _small(before - kinetic_energy(M, after))
        checks = certify_checks(self, after, P, rule)
        if checks is not None and not exact:
            checks["_tolerance"] = 1e-8
        names = [c.name for c in self.contacts]
        return read_back(
            (c.laws for c in self.contacts), {n: P[3 * i] for i, n in enumerate(names)},
            certify=checks is not None,
            tangential={n: _small(sp.sqrt(P[3 * i + 1] ** 2 + P[3 * i + 2] ** 2))
                        for i, n in enumerate(names)},
            speeds_before=self._speeds, speeds_after=self._all(after),
            energies=(before, lost, lost / before),
            courses=(f"{n}: {courses[n]}" for n in names),
            regime=courses[names[0]] if len(names) == 1 else None, given_checks=checks,
            tangent_impulses={n: (P[3 * i + 1], P[3 * i + 2]) for i, n in enumerate(names)},
            notes=notes, rule=rule)

    @property
    def _speeds(self) -> tuple[Any, ...]:
        """The speeds the answer reports: every speed (independent and dependent)."""
        return tuple(self.u) if self.fold is None else tuple(self.fold[0])

    @cached_property
    def _stand_ins(self) -> dict[sp.Basic, sp.Dummy]:
        """A symbol for every sin and cos of a coordinate (and every coordinate and speed)
        in M and J: the solve is then rational arithmetic, exact and fast, and the
        trigonometric identities are applied once to the results (as the one-contact core
        does for a symbolic tilt)."""
        atoms = (self.M.atoms(sp.sin, sp.cos) | self.J.atoms(sp.sin, sp.cos)
                 | set(self.q) | set(self.u))
        return {a: sp.Dummy(f"s{i}") for i, a in enumerate(
            sorted(atoms, key=lambda a: (a.count_ops(), sp.default_sort_key(a)), reverse=True))}

    def _in(self, matrix: sp.MatrixBase) -> sp.Matrix:
        return sp.Matrix(matrix).xreplace(self._stand_ins)

    def _out(self, matrix: sp.MatrixBase) -> sp.Matrix:
        back = {v: k for k, v in self._stand_ins.items()}
        return sp.Matrix(matrix).xreplace(back)

    @cached_property
    def _solved(self) -> tuple[sp.Matrix, sp.Matrix]:
        """``M^-1 J^T`` and ``W`` in the stand-ins, solved in the field of rational
        functions of the stand-ins and constants (each entry one reduced fraction)."""
        M, J = self._in(self.M), self._in(self.J)
        gens = sorted(M.free_symbols | J.free_symbols, key=sp.default_sort_key)
        domain = sp.QQ.frac_field(*gens) if gens else sp.QQ
        dm, dj = (DomainMatrix.from_Matrix(x).convert_to(domain) for x in (M, J))
        x = dm.lu_solve(dj.transpose())
        return x.to_Matrix(), (dj * x).to_Matrix()

    @property
    def _numbers(self) -> bool:
        return not (self.M.free_symbols or self.J.free_symbols)

    @cached_property
    def _M_inv_JT(self) -> sp.Matrix:
        if self._numbers:  # at numbers (floats allowed): solved as they are
            return self.M.LUsolve(self.J.T)
        return self._out(self._solved[0])

    @cached_property
    def W(self) -> sp.Matrix:
        """``J M^-1 J^T``: how the contacts' impulses change their velocities."""
        if self._numbers:
            return self.J * self._M_inv_JT
        return self._out(self._solved[1]).applyfunc(_one_fraction)

    def solve(self, rule: Rule | None = None) -> Solution:
        """The speeds after, each contact's impulse, the equations and the energy lost,
        as the one :class:`~rigidimpact.solve.solution.Solution` of rigidimpact.

        One contact: its own exact answer under its laws (Routh's method for Coulomb,
        Walton's for rough; with symbols a friction law's course must be decided by
        numbers), whatever the rule. Several contacts at numbers: `rule` itself, the
        one implementation the built-in shapes use (see :meth:`outcomes`): the
        simultaneous rule (the default) under every restitution law, with Coulomb
        friction at the velocity level; the sequential rule in an order, each contact
        its own impact under its own laws. With symbols, the simultaneous rule's case in
        which every contact acts (smooth or sticking, Newton's law), the first of
        :meth:`cases` (every contact approaching, where the data let them), with the
        conditions under which it is the answer; :meth:`cases` gives every case.
        """
        if rule is not None and not isinstance(rule, Rule):
            raise InputError("rule", "must be a rule object (ri.Simultaneous() or "
                             f"ri.Sequential(order)), not {type(rule).__name__} {rule!r}")
        v = self.J * self.u_before
        normals = [v[2 * i] for i in range(len(self.contacts))]
        if all(x.is_number and x >= 0 for x in normals):
            raise InputError("contacts", "no contact is approaching (normal velocities "
                             f"{', '.join(f'{float(x):.6g}' for x in normals)} >= 0): "
                             "there is no impact")
        laws = [c.laws.laws for c in self.contacts]
        rule = Simultaneous() if rule is None else rule
        if len(self.contacts) == 1:  # the one door: the contact's own answer
            return rule.answer(SystemRows.of(self))[0]
        if self._numbers and all(x.is_number for x in self.u_before):
            found = self.outcomes(rule)
            if len(found) > 1:
                raise InputError("rule", f"the {rule.name} rule gives {len(found)} outcomes "
                                 "here (every order, or a sample of them): ask "
                                 "SystemImpact.outcomes(rule) for all of them")
            return found[0]
        if not isinstance(rule, Simultaneous) or self.J_plane is not None:
            raise InputError("rule", f"the {rule.name} rule at a mechanics system needs "
                             "numbers" + (" where contacts slide across tangent planes "
                                          "(3-D)" if self.J_plane is not None else "")
                             + ": SystemImpact.at(...) with q, the speeds and the "
                             "constants")
        for c, (restitution, tangential) in zip(self.contacts, laws, strict=True):
            if tangential.solved_by_regimes:
                raise InputError(f"{c.name}.tangential", f"the {tangential.name} law "
                                 "(by regimes) has no closed form for several contacts of "
                                 "a mechanics system acting together: give numbers "
                                 "(SystemImpact.at), or use smooth or stick there")
            if restitution.newtons_e() is None:
                raise InputError(f"{c.name}.law", f"{restitution.name}'s law has no closed "
                                 "form for several contacts of a mechanics system acting "
                                 "together here: give numbers (SystemImpact.at), or use "
                                 "Newton's")
        names = {c.name for c in self.contacts}
        every = [c for c in self.cases() if set(c.acted) == names]
        if not every:
            raise InputError("contacts", "no case of the simultaneous rule has every "
                             "contact acting here: SystemImpact.cases() gives the cases "
                             "there are, each with its conditions")
        return every[0]

    def cases(self) -> tuple[Solution, ...]:
        """The simultaneous rule with symbols (several contacts): one outcome per set
        of acting contacts and pattern of signs before, each with the conditions under
        which it is the answer. It is the built-in shapes' own implementation
        (:func:`rigidimpact.solve.rules.simultaneous.simultaneous_cases`), run on this
        system's speeds, M and contact rows; at numbers it is the rule's one answer."""
        if len(self.contacts) < 2:
            raise InputError("contacts", "the cases are those of several contacts; one "
                             "contact has its own answer: SystemImpact.solve()")
        if self.J_plane is not None:
            raise InputError("rule", "the cases of contacts sliding across tangent planes "
                             "(3-D) need numbers: SystemImpact.at(...) with q, the speeds "
                             "and the constants")
        if any(x.free_symbols for x in (*self.M, *self.J, *self.u_before)):
            self._linear_system()  # its work's budget: refused past it
        return simultaneous_cases(SystemRows.of(self))

    def outcomes(self, rule: Rule) -> tuple[Solution, ...]:
        """What `rule` makes of several contacts at numbers: the built-in rules
        themselves (:class:`~rigidimpact.solve.collision.Collision`'s simultaneous rule
        with every restitution law and Coulomb friction at the velocity level, the
        sequential rule in an order, every order or a seeded sample of orders), run on
        this system's speeds, M and contact rows; one Solution per outcome."""
        if not isinstance(rule, Rule):
            raise InputError("rule", "must be a rule object (ri.Simultaneous() or "
                             f"ri.Sequential(order)), not {type(rule).__name__} {rule!r}")
        if not (self._numbers and all(x.is_number for x in self.u_before)):
            raise InputError("values", "the rules run at numbers: SystemImpact.at(...) with "
                             "q, the speeds and the constants")
        if len(self.contacts) > MAX_ENUMERATED:
            raise InputError("contacts", f"a mechanics system is solved with at most "
                             f"{MAX_ENUMERATED} contacts so far")
        return rule.answer(SystemRows.of(self))

    def _linear_system(self) -> tuple[sp.Matrix, sp.Matrix, list[sp.Symbol]]:
        """``A x = b`` in the speeds after and the impulses, ``M u+ - J^T P = M u-`` with
        each contact's two linear conditions (every contact acting), each row over one
        denominator; its symbols (the stand-ins and constants) ordered. Refused where
        its closed form's work is past :data:`MAX_SYMBOLIC_TERMS`."""
        n, k = len(self.u), len(self.contacts)
        M, J = self._in(self.M), self._in(self.J)
        u = self._in(self.u_before)
        after = sp.Matrix(sp.symbols(f"x0:{n}"))
        P = sp.Matrix(sp.symbols(f"p0:{2 * k}"))
        rows = list(M * after - J.T * P - M * u)
        for i, c in enumerate(self.contacts):
            restitution, tangential = c.laws.laws
            pair = slice(2 * i, 2 * i + 2)
            closing = (J[i * 2, :] * u)[0]
            if closing.is_number:  # a contact at rest or opening leaves at rest or faster
                closing = min(closing, 0)
            rows += tangential.linear_conditions(J[pair, :] * u, J[pair, :] * after,
                                                 P[pair, 0], restitution.leaving(closing))
        # each row over one denominator, kept as its numerator (a nonholonomic system's
        # folded mass matrix has 1/cos in it): polynomials for the fraction-free solve
        rows = [sp.fraction(sp.together(sp.expand(r)))[0] for r in rows]
        A, b = sp.linear_eq_to_matrix([sp.expand(r) for r in rows], list(after) + list(P))
        gens = sorted(A.free_symbols | b.free_symbols, key=sp.default_sort_key)
        if gens:  # the exact solve's terms: at most the product of the rows' terms
            bound = len(gens) * math.prod(max(1, sum(len(sp.Add.make_args(x))
                                                     for x in A.row(i) if x != 0))
                                          for i in range(A.rows))
            if bound > MAX_SYMBOLIC_TERMS:
                raise InputError("values", f"the closed form of this impact costs about "
                                 f"{bound:.2g} units of work, past the budget of "
                                 f"{MAX_SYMBOLIC_TERMS:.0e} (it grows with every speed "
                                 "and symbol): give numbers with SystemImpact.at (q, the "
                                 "speeds and the constants), or fewer symbols")
        return A, b, gens

    def _linear(self) -> Solution:
        """One contact under a linear law (smooth or sticking): its law's pair of linear
        conditions with ``M u+ - J^T P = M u-`` (:meth:`_linear_system`), solved
        fraction-free over the polynomials of the stand-ins (no gcd until the end,
        where each result is reduced once)."""
        n, k = len(self.u), len(self.contacts)
        M, J = self._in(self.M), self._in(self.J)
        u = self._in(self.u_before)
        A, b, gens = self._linear_system()
        if self.digits is not None and not gens:
            return self._floating(A, b, n, M, u)
        # numbers alone: the rationals, with the one square root _exact_enough allows
        # adjoined where the data hold it (sqrt(3) of a 60 degree angle)
        ring = sp.QQ[tuple(gens)] if gens else construct_domain(
            [*A, *b], extension=True)[0]
        dA, db = (DomainMatrix.from_Matrix(x).convert_to(ring) for x in (A, b))
        notes: tuple[str, ...] = ()
        if dA.det() != ring.zero:
            numerators, denominator = dA.solve_den(db)
            field = ring.get_field()
            x = [field.convert_from(numerators[i, 0].element, ring)
                 / field.convert_from(denominator, ring) for i in range(n + 2 * k)]
            solved = sp.Matrix([field.to_sympy(v) for v in x])
            # twice the energy lost, u-.M u- - u+.M u+ = -(u+ - u-).M (u+ + u-), is the
            # impulses' work -P.J (u- + u+) (M (u+ - u-) = J^T P): k rows of J, not M's
            # n x n products, in the field
            dJ = DomainMatrix.from_Matrix(J).convert_to(field)
            du = DomainMatrix.from_Matrix(u).convert_to(field)
            dx = DomainMatrix([[v] for v in x[:n]], (n, 1), field)
            dP = DomainMatrix([[v] for v in x[n:]], (2 * k, 1), field)
            twice = field.to_sympy(-(dP.transpose() * (dJ * (du + dx)))[0, 0].element)
        else:  # more conditions than freedoms: with numbers, consistent or not at all
            found = None if gens else least_norm(A, b)
            if found is None:
                raise InputError("contacts", "the contacts' conditions do not fix the "
                                 "impulses (more conditions than the system has freedoms)"
                                 + ("" if gens else " and contradict one another"))
            solved = found  # the motion is fixed (W's null vectors are J^T's)
            twice = 2 * (kinetic_energy(M, u) - kinetic_energy(M, solved[:n, :]))
            notes = ("more contact conditions than freedoms: the motion after is unique but "
                     "the impulses are not; shown: the least-norm impulses",)
        u_after, impulse = solved[:n, :], solved[n:, :]
        courses = {c.name: c.laws.laws[1].name for c in self.contacts}
        solution = self._map(u_after, impulse, courses, twice / 2)
        if notes:
            solution = replace(solution, notes=notes)
        return solution

    def _floating(self, A: sp.Matrix, b: sp.Matrix, n: int, M: sp.Matrix,
                  u: sp.Matrix) -> Solution:
        """The linear system at numbers in floating point (:attr:`digits`): the
        least-norm solution by mpmath's SVD, singular values below 1e-40 of the largest
        taken as zero (dependent conditions: the motion fixed, the impulses not), with
        the residual of the system in a note; None-consistent systems refused."""
        digits = self.digits or FLOAT_DIGITS
        with mpmath.workdps(digits + 10):
            A_ = mpmath.matrix([[mpmath.mpf(sp.N(x, digits)._to_mpmath(mpmath.mp.prec))
                                 for x in A.row(i)] for i in range(A.rows)])
            b_ = mpmath.matrix([mpmath.mpf(sp.N(x, digits)._to_mpmath(mpmath.mp.prec))
                                for x in b])
            U, S, V = mpmath.svd_r(A_)
            cut = max(S) * mpmath.mpf(10) ** -40
            rank = sum(1 for s in S if s > cut)
            x = mpmath.matrix(A_.cols, 1)
            for j in range(rank):
                coefficient = sum(U[i, j] * b_[i] for i in range(A_.rows)) / S[j]
                for i in range(A_.cols):
                    x[i] += coefficient * V[j, i]
            error = mpmath.norm(A_ * x - b_) / max(mpmath.norm(b_), mpmath.mpf(1))
        if error > mpmath.mpf(10) ** -30:
            raise InputError("contacts", "the contacts' conditions contradict one another "
                             f"(more conditions than the system has freedoms; residual "
                             f"{float(error):.1e})")
        solved = sp.Matrix([sp.Float(x[i], digits) for i in range(A_.cols)])
        u_after, impulse = solved[:n, :], solved[n:, :]
        twice = 2 * (kinetic_energy(M, u) - kinetic_energy(M, u_after))
        courses = {c.name: c.laws.laws[1].name for c in self.contacts}
        notes: tuple[str, ...] = (
            f"solved in {digits}-digit floating point (the numbers are out of the "
            f"rationals): the system's residual is {float(error):.1e} of its size",)
        if rank < A_.cols:
            notes += ("more contact conditions than freedoms: the motion after is unique "
                      "but the impulses are not; shown: the least-norm impulses",)
        return replace(self._map(u_after, impulse, courses, twice / 2), notes=notes)

    def _course_needs_numbers(self) -> None:
        """One contact whose law picks its course from the numbers (Coulomb by Routh's
        method, rough by Walton's) is solved where W, the velocities before and the
        law's coefficients are numbers: otherwise one line saying which is missing (a
        course that holds for some values only is never printed as if it held for all)."""
        c = self.contacts[0]
        tangential = c.laws.laws[1]
        W, v = self.W, (self.J * self.u_before)
        if not (all(x.is_number for x in W) and all(x.is_number for x in v)):
            raise InputError(f"{c.name}.tangential", f"the {tangential.name} law's course "
                             "depends on the numbers: give numbers for q, the speeds and "
                             "the constants first (SystemImpact.at and the speeds' values)")
        coefficients = sp.Tuple(*(x for x in (c.laws.restitution, c.laws.friction,
                                              c.laws.tangential_restitution)
                                   if x is not None))
        if coefficients.free_symbols:  # the course (slip, stick, reversal) turns on them
            name = sorted(map(str, coefficients.free_symbols))[0]
            raise InputError(f"{c.name}.tangential", f"the {tangential.name} law's course "
                             f"depends on {name}: give it a number in SystemImpact.at (a "
                             "course that holds for some values only is not printed as "
                             "if it held for all)")

    def _map(self, after: sp.Matrix, impulse: sp.Matrix, courses: dict[str, str],
             energy: sp.Expr, summed: bool = False, how: str | None = None,
             rule: str = "simultaneous", conditions: Sequence[Any] = ()) -> Solution:
        """The result, from the stand-ins back to q, the speeds and their sines, checked
        against `rule`'s own laws and tolerance."""
        back = self._out
        P = back(impulse)
        normal = {c.name: _small(P[2 * i]) for i, c in enumerate(self.contacts)}
        along = {c.name: _small(P[2 * i + 1]) for i, c in enumerate(self.contacts)}
        v = self.J * self.u_before
        equations, unknowns = self._equations(v, courses, normal, along, summed, how)
        lost = _small(back(sp.Matrix([energy]))[0])
        warnings = self._warnings(normal)
        before = kinetic_energy(self.M, self.u_before)
        if lost.is_number and before.is_number and lost < -sp.Float(1e-12) * before:
            laws = ", ".join(f"{c.laws.law} with {c.laws.tangential}" for c in self.contacts)
            warnings += (f"the impact created kinetic energy ({float(-lost):.6g}, "
                         f"{float(-lost / before):.3%} of the energy before): the laws "
                         f"({laws}) cannot honour the energy balance here (Newton's law "
                         "where the slip reverses: Kane and Levinson's paradox; stick with "
                         "e > 0 where the contact's directions are coupled)",)
        one = len(self.contacts) == 1
        checks = certify_checks(self, back(after), P, rule, conditions)
        integrated = conduct(rule).stated_tolerance is not None and any(
            sp.sympify(x).has(sp.Float) for x in (*after, *P))
        if checks is not None and integrated:  # followed in floating point: the rule's
            checks.pop("_tolerance")  # own tolerance (its integrator's), not the exact paths'
        # its energy warning is its own (above): only a broken condition is acted on
        return read_back(
            (c.laws for c in self.contacts), normal, certify=checks is not None,
            limits=False, tangential=along, speeds_before=self._speeds,
            speeds_after=self._all(back(after)).applyfunc(_small),
            energies=(before, lost, lost / before),
            courses=(f"{n}: {c}" for n, c in courses.items()),
            regime=next(iter(courses.values())) if one else None, given_checks=checks,
            equations=equations, unknowns=unknowns, warnings=warnings, notes=(
                f"solved in {self.digits}-digit floating point (the numbers are out of the "
                "rationals)",) if self.digits else (), rule=rule)

    def _all(self, independent: sp.Matrix) -> sp.Matrix:
        """Every speed from the independent ones (the dependent ones by the velocity
        constraints, which hold after the impact as before)."""
        return independent if self.fold is None else self.fold[1] * independent

    def kernel(self, values: dict | None = None) -> MapKernel:
        """The impact map where every contact acts, as one NumPy kernel over arrays of
        states (:mod:`rigidimpact.mechanics.kernel`): `values` gives the constants (a
        dict like :meth:`at`'s, without q and the speeds); the kernel is called with q
        and u. Smooth and sticking contacts under Newton's law (the map of a robotics
        library's impulse dynamics); the rest is refused in one line, for
        :meth:`solve`. A state where a contact would pull or energy is created gives
        NaN speeds, counted in the result's warnings.

        Examples
        --------
        The pendulum of the module's example, hitting the wall with e = 1/2 at rate -2
        (and, at a second state, moving away from it: no impact there):

        >>> import sympy as sp, sympy.physics.mechanics as me
        >>> q, u = me.dynamicsymbols("q u")
        >>> N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
        >>> A.orient_axis(N, N.z, q); A.set_ang_vel(N, u * N.z)
        >>> O = me.Point("O"); O.set_vel(N, 0)
        >>> bob = O.locatenew("bob", -A.y); _ = bob.v2pt_theory(O, N, A)
        >>> kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
        >>> _ = kane.kanes_equations([me.Particle("P", bob, 3)], [])
        >>> found = impact(kane, [contact(bob, N.x, restitution=sp.Rational(1, 2))],
        ...                frame=N).kernel()([[0.0], [0.0]], [[-2.0], [2.0]])
        >>> found.speeds_after.ravel().tolist(), found.warnings[0][:38]
        ([1.0, nan], 'at 1 of 2 states a contact would pull ')
        """
        return MapKernel.of(self, values)

    def at(self, values: dict) -> SystemImpact:
        """The same impact with numbers (or expressions) for q, the constants and (keyed
        by the speeds) the speeds before."""
        if not isinstance(values, dict):
            raise InputError("values", "must be a dict of symbols (q, the constants, the "
                             f"speeds) to numbers, not {type(values).__name__}")
        used = self.M.free_symbols | self.J.free_symbols | set(self.u) | set().union(
            *(sp.Tuple(c.laws.restitution, c.laws.friction or 0,
                       c.laws.tangential_restitution or 0).free_symbols
              for c in self.contacts))
        for key, value in values.items():
            _check_value(key, value, key in used)
        # SymPy numbers (a Python int or float put in by xreplace stays one), a float
        # widened to the solve's digits: cos(0.3) put in at 15 digits would be evaluated
        # there, and the 50-digit solve would answer for a rounded M and J
        put = {k: _wide(v) for k, v in values.items() if k not in self.u}
        speeds = tuple(_wide(values.get(s, b)) for s, b in
                       zip(self.u, self.u_before, strict=True))
        contacts = tuple(PointContact(c.point, c.normal, c.laws.at(put), c.other)
                         for c in self.contacts)
        fold = None if self.fold is None else (self.fold[0], self.fold[1].xreplace(put))
        M, J = self.M.xreplace(put), self.J.xreplace(put)
        plane = None if self.J_plane is None else self.J_plane.xreplace(put)
        numbers = [*M, *J, *speeds]
        digits = None
        if all(sp.sympify(x).is_number for x in numbers) and not _exact_enough(numbers):
            # the arithmetic is chosen here, before any course or acting set is tried:
            # exact algebra over sines of numbers (or nested roots) costs minutes where
            # 50-digit floats cost milliseconds; the residuals say what they lose
            digits = FLOAT_DIGITS

            def num(x: Any) -> Any:
                return sp.N(x, digits)

            M, J = M.applyfunc(num), J.applyfunc(num)
            plane = None if plane is None else plane.applyfunc(num)
            speeds = tuple(num(x) for x in speeds)
            if fold is not None:
                fold = (fold[0], fold[1].applyfunc(num))
        return SystemImpact(self.frame, self.q, self.u, M, contacts, speeds, J, fold,
                            digits, plane, self.bodies, self.kinematics,
                            self.values + tuple(put.items()))

    def _equations(self, v: sp.Matrix, courses: dict[str, str],
                   normal: dict[str, sp.Expr], along: dict[str, sp.Expr],
                   summed: bool = False, rule: str | None = None
                   ) -> tuple[tuple[Equation, ...], tuple]:
        after = [sp.Symbol(f"{_name(s)}^+") for s in self.u]
        pushes = []
        for c in self.contacts:
            pushes += [labelled("P", "n", c.name), labelled("P", "t", c.name)]
        U, U0, P = sp.Matrix(after), self.u_before, sp.Matrix(pushes)
        balance = self.M * (U - U0)
        generalized = self.J.T * P
        found = [Equation(f"generalized momentum along {_name(s)}: M (u+ - u-) = J^T P", "",
                          balance[i], generalized[i], law="momentum")
                 for i, s in enumerate(self.u)]
        v_after = self.J * U
        for i, c in enumerate(self.contacts):
            restitution, tangential = c.laws.laws
            course = courses[c.name]
            if summed or course == "released":
                how = (f"{c.name}'s impulse by the {rule}" if summed and rule else
                       f"the sum of {c.name}'s impulses in turn (each its own impact)"
                       if summed else f"{c.name} released: no impulse")
                found += [Equation(how, "", P[2 * i], normal[c.name], law="rule"),
                          Equation(how + ", tangential", "", P[2 * i + 1], along[c.name],
                                   law="rule")]
                continue
            if not tangential.solved_by_regimes or course == "stick":
                # the law's own target, as the solve asked it (a law whose e depends on
                # the closing speed prints the e it used)
                closing = v[2 * i]
                if closing.is_number:
                    closing = min(closing, 0)
                found.append(Equation(f"restitution at {c.name} ({restitution.name}'s law "
                                      "on a straight impulse path)", "", v_after[2 * i],
                                      restitution.leaving(closing), law="restitution"))
            if course == "stick":
                found.append(Equation(f"{c.name} sticks: no slip after", "",
                                      v_after[2 * i + 1], 0, law="tangential"))
            elif not tangential.grips:
                found.append(Equation(f"{c.name} is smooth: no tangential impulse", "",
                                      P[2 * i + 1], 0, law="tangential"))
            else:  # Routh's (or Walton's) exact impulse for the course taken
                how = f"{c.name} alone by the {tangential.name} law, course {course}"
                found += [Equation(how, "", P[2 * i], normal[c.name], law="tangential"),
                          Equation(how + ", tangential", "", P[2 * i + 1],
                                   along[c.name], law="tangential")]
        return tuple(found), tuple(after + pushes)

    def _warnings(self, impulses: dict[str, sp.Expr]) -> tuple[str, ...]:
        found = []
        for name, normal in impulses.items():
            if normal.is_number and normal < 0:
                found.append(f"{name} would pull (normal impulse {float(normal):.6g}): "
                             "the model cannot honour a push-only contact here")
        return tuple(found)


def _check_value(key: Any, value: Any, used: bool = True) -> None:
    """One value for :meth:`SystemImpact.at`: a finite real number (or an expression),
    positive where its symbol is declared positive (a mass, a length) and used."""
    where = f"values.{key}"
    if isinstance(value, bool) or not isinstance(value, (int, float, sp.Basic)):
        raise InputError(where, f"must be a number or a SymPy expression, not "
                         f"{type(value).__name__} {value!r}")
    value = sp.sympify(value)
    if value.is_number:
        if value.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or not value.is_finite:
            raise InputError(where, f"must be finite, not {value}")
        if value.is_real is False:
            raise InputError(where, f"must be real, not {value}")
        if used and getattr(key, "is_positive", None) and not value.is_positive:
            raise InputError(where, f"must be positive (the symbol is declared positive), "
                             f"not {value}")
        if used and getattr(key, "is_nonnegative", None) and value.is_negative:
            raise InputError(where, f"must not be negative, not {value}")


def _exact_enough(numbers: Sequence[Any]) -> bool:
    """Whether numbers are solved exactly: rationals, or rationals with one square root
    (sqrt(3) of a 60 degree angle) adjoined; sines of other numbers, pi, or several
    roots (whose fields cost seconds to build and nest at each step) are not."""
    radicals: set[sp.Basic] = set()
    for x in numbers:
        x = sp.sympify(x)
        if x.is_Rational:
            continue
        if x.atoms(sp.Function, sp.NumberSymbol, sp.Float):
            return False
        radicals |= {p for p in x.atoms(sp.Pow) if p.base.is_Rational
                     and p.exp.is_Rational and not p.exp.is_Integer}
    return len({sp.sqrt(r.base).as_coeff_Mul()[1] for r in radicals
                if r.exp.q == 2}) <= 1 and all(r.exp.q == 2 for r in radicals)


def _no_tan(expr: Any) -> sp.Expr:
    """tan written as sin/cos (the solver's stand-ins are sines and cosines)."""
    return sp.sympify(expr).replace(sp.tan, lambda a: sp.sin(a) / sp.cos(a))


def _small(expr: sp.Expr) -> sp.Expr:
    """sin^2 + cos^2 folded where the expression is small enough for that to be quick."""
    return _one_fraction(expr) if sp.count_ops(expr) < 150 else expr


def _one_fraction(expr: sp.Expr) -> sp.Expr:
    """One rational function, with sin^2 + cos^2 folded."""
    return sp.trigsimp(sp.cancel(sp.expand(expr)))


def _name(speed: Any) -> str:
    """``u1`` for ``u1(t)``."""
    return str(getattr(speed, "func", speed))


def impact(system: Any, contacts: Sequence[PointContact], frame: Any = None) -> SystemImpact:
    """The impact problem of a sympy.physics.mechanics ``KanesMethod`` (after
    ``kanes_equations``) or ``System`` (after ``form_eoms``) at `contacts`.

    `frame` is the inertial frame (a ``System``'s own frame by default; for a
    ``KanesMethod`` the frame of the first contact's normal).
    """
    M = sp.ImmutableMatrix(system_matrix(system, "mass_matrix"))
    q, u = tuple(system.q), tuple(system.u)
    dependent = getattr(system, "u_dep", None)
    if dependent is None:  # a KanesMethod keeps them here
        dependent = getattr(system, "_udep", ())
    if M.shape != (len(u), len(u)):
        raise InputError("system", f"its mass matrix is {M.shape[0]}x{M.shape[1]} for "
                         f"{len(u)} speeds")
    fold = None
    if dependent is not None and len(dependent):
        M, u, fold = _folded(M, u, tuple(dependent))
    if isinstance(contacts, PointContact) or not isinstance(contacts, (list, tuple)) \
            or not contacts:
        raise InputError("contacts", "give a list of contacts made by "
                         "ri.mechanics.contact(point, normal, ...)")
    for k, c in enumerate(contacts):
        if not isinstance(c, PointContact):
            raise InputError(f"contacts[{k}]", "must be made by ri.mechanics.contact(point, "
                             f"normal, ...), not {type(c).__name__} {c!r}")
    names = [c.name for c in contacts]
    if len(set(names)) != len(names):
        twice = next(n for n in names if names.count(n) > 1)
        raise InputError("contacts", f"two contacts are named {twice!r}: give each its own "
                         "name (name=...), or their impulses are reported as one")
    if frame is not None and not isinstance(frame, me.ReferenceFrame):
        raise InputError("frame", "must be a sympy.physics.mechanics ReferenceFrame, not "
                         f"{type(frame).__name__}")
    if frame is None:
        frame = getattr(system, "frame", None)
    if frame is None:
        frame = contacts[0].normal.args[0][1]
    return SystemImpact(frame, q, u, M, tuple(contacts), fold=fold,
                        bodies=tuple(getattr(system, "bodies", None) or ()),
                        kinematics=_kinematics(system))


def system_matrix(system: Any, name: str) -> Any:
    """The matrix `name` (``mass_matrix``, ``forcing_full``, ...) of a
    sympy.physics.mechanics ``KanesMethod`` or ``System``, or InputError naming the
    system: one that is not such a system, or whose equations of motion are not formed
    yet (sympy's own "Need to compute Fr, Fr* first" is not passed on)."""
    kind = type(system)
    if not all(isinstance(getattr(kind, a, None), property) for a in ("q", "u", name)):
        raise InputError("system", "must be a sympy.physics.mechanics KanesMethod or "
                         f"System, not {kind.__name__}")
    try:
        return getattr(system, name)
    except (AttributeError, ValueError, TypeError):
        call = "form_eoms()" if isinstance(system, me.System) else \
            "kanes_equations(bodies, loads)"
        raise InputError("system", f"its equations of motion are not formed yet: call "
                         f"{call} first") from None


def _kinematics(system: Any) -> tuple[tuple[Any, Any], ...]:
    """The system's q' in terms of its speeds (its kinematic differential equations), as
    pairs: a body's angular velocity may be written in q' where its points' are in u."""
    for source in (system, getattr(system, "eom_method", None)):
        try:
            return tuple(source.kindiffdict().items())  # type: ignore[union-attr]
        except (AttributeError, ValueError, TypeError):
            continue
    return ()


def _folded(M: sp.MatrixBase, u: tuple, dependent: tuple
            ) -> tuple[sp.ImmutableMatrix, tuple, tuple[tuple, sp.ImmutableMatrix]]:
    """A nonholonomic system in its independent speeds.

    Kane's method orders the speeds independent first and stacks its mass matrix as
    ``[k_d; k_nh]``: the generalized inertia along the independent (nonholonomic)
    partial velocities, ``k_d = T^T M_all``, over the velocity constraints' own
    coefficients ``k_nh`` (``k_nh u_all + f_nh = 0``). The constraints give the dependent
    speeds' changes from the independent ones, ``u_all = T u`` with ``T = [I; A]``,
    ``A = -k_nh,dep^-1 k_nh,ind``; they hold through the impact (their impulsive
    reactions do no work), so the impact's generalized momentum balance in the
    independent speeds has the mass matrix ``k_d T = T^T M_all T`` and the contacts'
    Jacobian ``J_all T``.
    """
    p = len(u) - len(dependent)
    if tuple(u[p:]) != dependent:
        raise InputError("system", "the dependent speeds must come last among its speeds "
                         "(as Kane's method orders them)")
    k_d, k_nh = sp.Matrix(M[:p, :]), sp.Matrix(M[p:, :])
    block = k_nh[:, p:]
    if sp.simplify(block.det()) == 0:
        raise InputError("system", "its velocity constraints do not fix the dependent "
                         "speeds from the independent ones")
    def plain(x: sp.Expr) -> sp.Expr:  # tan as sin/cos: the solver's stand-ins see them
        return _no_tan(sp.cancel(_no_tan(sp.trigsimp(_no_tan(x)))))

    k_d, k_nh = k_d.applyfunc(plain), k_nh.applyfunc(plain)
    block = k_nh[:, p:]
    A = (-block.LUsolve(k_nh[:, :p])).applyfunc(plain)
    T = sp.ImmutableMatrix(sp.Matrix.vstack(sp.eye(p), A))
    folded = sp.ImmutableMatrix((k_d * T).applyfunc(plain))
    return folded, tuple(u[:p]), (tuple(u), T)
