"""Several smooth contacts closing at the same instant, under a stated rule.

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

import itertools
import math
import random
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from functools import cached_property
from typing import Any, ClassVar

import sympy as sp
from sympy.polys.domains import QQ

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import damping_ratio_for
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation, NewtonRestitution
from rigidimpact.model.bodies import Body
from rigidimpact.model.impulse import Coordinate, coordinates_of, jacobian, moving
from rigidimpact.model.joints import Joint, off_body
from rigidimpact.solve.impact import Impact
from rigidimpact.solve.lcp import (
    NoSolution,
    confirm,
    confirm_by_rows,
    least_norm,
    lemke,
    pivoting,
    proximal,
    residual,
)
from rigidimpact.solve.solution import Solution, certified
from rigidimpact.symbolic.geometry import perp
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Collision", "Outcome", "RULES", "RULE_LAWS", "MAX_PASSES", "chain",
           "sequential_passes", "certified", "whole_number",
           "Rule", "Simultaneous", "Sequential", "Compliant", "RULE_TYPES",
           "rule_laws"]

RULES = ("simultaneous", "sequential", "compliant")
FLOAT_DIGITS = 60  # where exact algebra would nest roots: floating point at this precision
# a sequential run still going after this long (and as much again per 100 contacts) is
# refused (a Routh step with numbers takes 5 to 60 ms here: two contacts ringing for
# 1000 passes took 50 to 115 s; a 1009-contact cluster settles in about 8 s)
MAX_SEQUENTIAL_SECONDS = 10.0
MAX_PASSES = 1000  # sequential passes before the rule is declared endless
# a sequence of one-at-a-time impacts can go on forever while converging (inelastic
# collapse); it is cut where every closing speed left is this small next to the first
SETTLED = sp.Rational(1, 10**40)
MAX_ORDERS = 720  # every order of up to six contacts
MAX_SAMPLED_ORDERS = 10000
MAX_SAMPLE_SECONDS = 60.0  # a sample of orders estimated to take longer is refused
# the simultaneous rule with symbols: a case (signs before x acting contacts) that can
# hold took 0.3 to 2.5 s here (64 cases of three contacts with symbolic speeds 40 s, 256
# past 5 minutes), one that cannot next to nothing (128 cases of a cradle in 1.6 s); so
# the cases are counted first and the work is given a time
MAX_SYMBOLIC_CASES = 4096
# the compliant rule integrates at rtol 1e-10; an elastic Hertz chain of 3 to 8 balls kept
# its energy to 6e-10 to 9e-10: a gain is reported only beyond 1000 times the rtol
COMPLIANT_ENERGY_TOLERANCE = 1e-7
MAX_SYMBOLIC_SECONDS = 20.0
# the simultaneous rule: Lemke's exact dense tableau up to this many contacts; past it
# (or past MAX_ENUMERATED with irrational numbers) floating point with an exact check
MAX_LEMKE = 64
MAX_ENUMERATED = 12
MAX_WINDOWS = 2000  # the compliant rule's integration windows before it gives up
# the compliant rule ends once no contact is pressed deeper than this many times the
# integrator's absolute tolerance and none closes faster than this many times its
# relative tolerance of the fastest closing speed before: less is the integration's
# own error (a long Hertz chain leaves such traces behind its wave, which would
# otherwise be followed for a thousand times as long)
NOISE = 1000
RULE_LAWS = {
    "simultaneous": "every contact smooth; the impulses P >= 0 act together, with the "
                    "restitution law at each contact that acts and no contact pulling "
                    "(v+ = v- + W P, a complementarity problem)",
    "sequential": "every contact smooth; one contact at a time in the order given, each a "
                  "two-body impact with Newton's e, repeated until no contact approaches",
    "compliant": "every contact a push-only spring-dashpot (linear, damping from e) or an "
                 "elastic Hertz spring, integrated until all let go (floating point)",
}
FRICTION_LAWS = {
    "simultaneous": "Coulomb friction at the velocity level: the impulses act together; "
                    "each contact is released, sticks (Newton's e across, no slip after, "
                    "|P_t| <= mu P_n) or slides (|P_t| = mu P_n against its slip after); "
                    "every combination solved exactly",
    "sequential": "one contact at a time in the order given, each that contact's own "
                  "impact under its own laws (Routh's method for Coulomb friction, "
                  "Walton's for a rough contact); repeated until no contact approaches",
}


_STATE = {"off": "released", "on": "acts", "stick": "sticks", "slide+": "slides",
          "slide-": "slides", "mixed": "differs between the solutions"}


def rule_laws(rule: str, frictional: bool = False) -> str:
    """The laws a rule imposes, in words (with friction when any contact has it)."""
    return FRICTION_LAWS[rule] if frictional and rule in FRICTION_LAWS else RULE_LAWS[rule]


Outcome = Solution  # the one result type (the name several-contact code used first)


@dataclass(frozen=True)
class Collision:
    """Bodies in the world frame and the smooth contacts that close together.

    Parameters
    ----------
    bodies : tuple of Body
        Positions (and pivots) from the world origin.
    contacts : tuple of Contact
        Each with its two `bodies` named and its `point` (world frame).
    joints : tuple of Joint
        Bodies pinned together (:mod:`rigidimpact.model.joints`): each adds two
        bilateral rows, eliminated by the projected inverse mass (:attr:`M_inverse`),
        and its impulse is reported.
    """

    bodies: tuple[Body, ...]
    contacts: tuple[Contact, ...]
    joints: tuple[Joint, ...] = ()

    def __post_init__(self) -> None:
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            raise InputError("bodies", "two bodies share a name")
        if len({t.name for t in self.contacts}) != len(self.contacts):
            raise InputError("contacts", "two contacts share a name")
        for touch in self.contacts:
            if touch.bodies is None:
                raise InputError(f"{touch.name}.bodies", "required: name the two bodies")
            for side in (touch.first, touch.second):
                if side not in names:
                    raise InputError(f"{touch.name}.bodies", f"no body named {side!r}")
            if all(self._body(side).support == "fixed" for side in (touch.first,
                                                                     touch.second)):
                raise InputError(f"{touch.name}.bodies", "two fixed bodies cannot collide: "
                                 "at least one must move")
            for side in (touch.first, touch.second):
                body = self._body(side)
                if body.inertia.is_zero and body.support != "fixed" and \
                        any(not c.is_zero for c in body.position - touch.point):
                    raise InputError(f"{touch.name}.point", f"{side} is a point mass: the "
                                     "contact must be where it is")
                why = off_body(body, touch.point)
                if why:
                    raise InputError(f"{touch.name}.point", f"not on {side}: {why}")
        if self.joints:
            self._check_joints(names)
        # in numbers (a closing speed may hold a sine: compared at 30 digits)
        if not self.symbols and all(sp.N(v, 30) >= 0 for v in self._velocity_before):
            raise InputError("bodies", "no contact is approaching: there is no impact")

    def _check_joints(self, names: list[str]) -> None:
        """Each joint names two bodies of the collision, at least one movable; its
        point is on both (where their shapes say where they are); its name is its own;
        the two bodies move together there before the impact; and the joints together
        leave the bodies some freedom (their rows are independent)."""
        taken = set(names) | {t.name for t in self.contacts}
        seen: set[str] = set()
        for j in self.joints:
            if not isinstance(j, Joint):
                raise InputError("joints", f"each must be a Joint, not {type(j).__name__}")
            if j.name in taken or j.name in seen:
                raise InputError(f"{j.name}.name", "a joint's name must differ from every "
                                 "body's, contact's and other joint's")
            seen.add(j.name)
            for side in j.bodies:
                if side not in names:
                    raise InputError(f"{j.name}.bodies", f"no body named {side!r}")
                why = off_body(self._body(side), j.point)
                if why:
                    raise InputError(f"{j.name}.point", f"not on {side}: {why}")
            if all(self._body(side).support == "fixed" for side in j.bodies):
                raise InputError(f"{j.name}.bodies", "a joint between two fixed bodies "
                                 "holds nothing: at least one must move")
        if len(self.contacts) > MAX_ENUMERATED:
            raise InputError("joints", f"joints are solved with at most {MAX_ENUMERATED} "
                             f"contacts (this collision has {len(self.contacts)})")
        # with symbols, at two seeded random points (an identity that holds there
        # holds everywhere but on a set of measure zero); exactly at numbers
        drift = sp.Matrix(self.G) * self.u_before
        S = self._joint_S
        for point in _sample_points(drift.free_symbols | S.free_symbols
                                    | self.u_before.free_symbols):
            gap = [sp.N(x.xreplace(point), 30) for x in drift]
            for k, j in enumerate(self.joints):
                here = gap[2 * k:2 * k + 2]
                if any(abs(x) > 1e-20 * (1 + max(abs(sp.N(u.xreplace(point), 30))
                                                 for u in self.u_before)) for x in here):
                    first, second = j.bodies
                    moved = [tidy(x) for x in drift[2 * k:2 * k + 2]]
                    raise InputError(f"{j.name}", f"its two bodies do not move together "
                                     f"at ({j.point[0]}, {j.point[1]}) before the impact: "
                                     f"{second}'s point moves at ({moved[0]}, {moved[1]}) "
                                     f"relative to {first}'s; give velocities and spins "
                                     "that keep the joint together")
            if abs(sp.N(S.xreplace(point).det(), 30)) < 1e-20:
                raise InputError("joints", "the joints are not independent (a closed loop "
                                 "or a body pinned twice over): their impulses are not "
                                 "fixed")

    @cached_property
    def G(self) -> sp.Matrix:
        """Two rows per joint: the velocity of its second body's point less its first's,
        along x then y, as a function of u (zero before and after the impact)."""
        x, y = sp.ImmutableMatrix([1, 0]), sp.ImmutableMatrix([0, 1])
        return jacobian(self.bodies, self.coordinates,
                        [(j.first, j.second, j.point, d) for j in self.joints
                         for d in (x, y)])

    @cached_property
    def _free_M_inverse(self) -> sp.Matrix:
        """M^-1 of the bodies as if no joint held them (diagonal)."""
        n = len(self.coordinates)
        return sp.SparseMatrix(n, n, dict(((j, j), x)
                                          for j, x in enumerate(self._inverse_inertia)))

    @cached_property
    def _joint_S(self) -> sp.Matrix:
        """``G M^-1 G^T``: how the joints' impulses open their joints."""
        G = sp.Matrix(self.G)
        return (G * sp.Matrix(self._free_M_inverse) * G.T).applyfunc(tidy)

    @cached_property
    def _joint_map(self) -> sp.Matrix:
        """``S^-1 G M^-1``: the joints' impulses are ``-S^-1 G M^-1 F`` for the contacts'
        generalized impulse F (so that the joints stay together)."""
        G = sp.Matrix(self.G)
        return (self._joint_S.inv() * G * sp.Matrix(self._free_M_inverse)).applyfunc(tidy)

    def _joint_impulses(self, impulses: dict[str, sp.Expr],
                        tangential: dict[str, sp.Expr]) -> dict[str, tuple[sp.Expr, sp.Expr]]:
        """Each joint's impulse (x, y) on its second body, from the contacts' impulses
        along their unit normals and tangents."""
        if not self.joints:
            return {}
        P_n = sp.Matrix([impulses[t.name] for t in self.contacts])
        P_t = sp.Matrix([tangential.get(t.name, 0) for t in self.contacts])
        force = self.J.T * P_n + (self.J_t.T * P_t if any(P_t) else sp.zeros(
            len(self.coordinates), 1))
        lam = (-self._joint_map * force).applyfunc(tidy)
        return {j.name: (lam[2 * k], lam[2 * k + 1]) for k, j in enumerate(self.joints)}

    @cached_property
    def symbols(self) -> frozenset[sp.Symbol]:
        """The symbols left in the collision (none: every rule runs; some: the
        simultaneous and one-pass sequential formulas, each with its conditions)."""
        return frozenset(self._J.free_symbols | self._free_M_inverse.free_symbols
                         | (self.G.free_symbols if self.joints else set())
                         | self.u_before.free_symbols
                         | set().union(*(sp.Tuple(t.restitution, t.friction or 0,
                                                  t.tangential_restitution or 0).free_symbols
                                         for t in self.contacts)))

    def _smooth_only(self, where: str) -> None:
        rough = [t.name for t in self.contacts if t.laws[1].grips]
        if rough:
            needed = (f": give [values] (or --set) for "
                      f"{', '.join(sorted(map(str, self.symbols)))}, or ask for one "
                      "sequential pass in an order (solved with symbols, case by case)"
                      if where == "with symbols" and self.symbols else "")
            raise InputError(f"{rough[0]}.tangential", f"friction at several contacts is "
                             f"solved with numbers, by the simultaneous or sequential rule; "
                             f"not {where}{needed}")

    def _numbers_only(self, rule: str) -> None:
        if self.symbols:
            raise InputError("values", f"the {rule} rule needs numbers: give [values] for "
                             f"{', '.join(sorted(map(str, self.symbols)))}")

    @classmethod
    def from_values(cls, bodies: Sequence[Body], contacts: Sequence[Contact],
                    values: dict, joints: Sequence[Joint] = ()) -> Collision:
        """The collision with numbers put in for its symbols.

        Examples
        --------
        >>> x = sp.Symbol("x")
        >>> c = Collision.from_values([Body.rigid(1, 0, (0, 0), (x, 0), name="a"),
        ...                            Body.fixed("wall")],
        ...                           [Contact(restitution=1, bodies=("a", "wall"))], {x: 2})
        >>> c.simultaneous().results()["a.vx"]
        -2
        """
        def number(v):
            return sp.sympify(v).xreplace(values)

        def vector(v):
            return None if v is None else sp.ImmutableMatrix(v).xreplace(values)

        bodies = tuple(b if b.support == "fixed" else replace(
            b, mass=number(b.mass), inertia=number(b.inertia), position=vector(b.position),
            velocity=vector(b.velocity), spin=number(b.spin), pivot=vector(b.pivot))
            for b in bodies)
        return cls(bodies, tuple(c.at(values) for c in contacts),
                   tuple(j.at(values) for j in joints))

    def _body(self, name: str) -> Body:
        return self._by_body_name[name]

    @cached_property
    def _by_body_name(self) -> dict[str, Body]:
        return {b.name: b for b in self.bodies}

    @cached_property
    def coordinates(self) -> tuple[Coordinate, ...]:
        """The generalized velocities (see :func:`rigidimpact.model.impulse.coordinates_of`)."""
        return coordinates_of(self.bodies)

    @cached_property
    def J(self) -> sp.Matrix:
        """One row per contact: its normal closing velocity as a function of u (sparse:
        a contact touches only its two bodies' coordinates)."""
        return self._rows(lambda t, s: t.unit_normal)

    @cached_property
    def J_t(self) -> sp.Matrix:
        """One row per contact: the tangential velocity (second minus first) along its
        tangent, as a function of u."""
        return self._rows(lambda t, s: t.tangent)

    @cached_property
    def row_scale(self) -> tuple[sp.Expr, ...]:
        """Each contact's rows in the solvers' J and J_t are its unit normal's and
        tangent's times this.

        A normal given as rational numbers is used as given, so its scale is its length
        (sqrt(61)/8 for (3/4, -5/8)); any other normal is made unit (scale 1). Every rule
        is unchanged by a positive scale of a contact's rows (the closing velocity and
        the impulse scale inversely, the laws and the friction cone are homogeneous), so
        the algebra stays in the rationals where the data are rational instead of in a
        field with one square root adjoined per contact; the impulses are put back on
        the unit normal where the Solution is made (:meth:`_named`).

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> Collision((Body.rigid(1, 1, (0, 0), (0, -1), name="a"), Body.fixed("floor")),
        ...           (Contact(normal=(3, -4), bodies=("a", "floor")),)).row_scale
        (5,)
        """
        return tuple(sp.sqrt(t.normal[0] ** 2 + t.normal[1] ** 2)
                     if all(isinstance(x, sp.Rational) for x in t.normal) else sp.Integer(1)
                     for t in self.contacts)

    @cached_property
    def _J(self) -> sp.Matrix:
        """J with each row times its :attr:`row_scale` (what the rules solve with)."""
        if all(s == 1 for s in self.row_scale):
            return self.J
        return self._rows(lambda t, s: t.unit_normal if s == 1 else t.normal)

    @cached_property
    def _J_t(self) -> sp.Matrix:
        """J_t with each row times its :attr:`row_scale`."""
        if all(s == 1 for s in self.row_scale):
            return self.J_t
        return self._rows(lambda t, s: t.tangent if s == 1 else perp(t.normal))

    def _rows(self, direction_of) -> sp.Matrix:
        return jacobian(self.bodies, self.coordinates,
                        [(t.first, t.second, t.point, direction_of(t, s))
                         for t, s in zip(self.contacts, self.row_scale, strict=True)])

    @property
    def frictional(self) -> bool:
        """Whether any contact's tangential law gives a tangential impulse."""
        return any(t.laws[1].grips for t in self.contacts)

    @cached_property
    def M_inverse(self) -> sp.Matrix:
        """M^-1 (diagonal for free and pivoted bodies); with joints, the projected
        ``M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1``: the velocity change an impulse gives
        the bodies while every joint holds."""
        if not self.joints:
            return self._free_M_inverse
        free = sp.Matrix(self._free_M_inverse)
        return (free - free * sp.Matrix(self.G).T * self._joint_map).applyfunc(tidy)

    @cached_property
    def W(self) -> sp.Matrix:
        """``J M^-1 J^T``: how the contacts' impulses change their closing velocities."""
        return self._product(self.J)

    @cached_property
    def _W(self) -> sp.Matrix:
        """W of the scaled rows (:attr:`row_scale`): what the rules solve with."""
        return self.W if self._J is self.J else self._product(self._J)

    def _product(self, J: sp.Matrix) -> sp.Matrix:
        if not (J.free_symbols or self.M_inverse.free_symbols):
            # numbers: in their own field (the rationals, or with sqrt(3) adjoined), where
            # the product of sparse rows is exact and fast at hundreds of contacts
            J, Minv = J.to_DM(extension=True), self.M_inverse.to_DM(extension=True)
            J, Minv = J.unify(Minv)
            return (J * Minv * J.transpose()).to_Matrix()
        return (J * self.M_inverse * J.T).applyfunc(_tidied)

    @cached_property
    def u_before(self) -> sp.Matrix:
        return sp.Matrix([c.before for c in self.coordinates])

    @cached_property
    def velocity_before(self) -> sp.Matrix:
        """Normal closing velocity of every contact before (negative: approaching)."""
        return (self.J * self.u_before).applyfunc(tidy)

    @cached_property
    def _velocity_before(self) -> sp.Matrix:
        """The closing velocities of the scaled rows (:attr:`row_scale`)."""
        return self._times(self.u_before)

    def _closing(self, k: int, u: Sequence[sp.Expr]) -> sp.Expr:
        """Contact k's normal closing velocity at the generalized velocities u (its row
        of J, two bodies' coordinates), tidied."""
        return tidy(sp.Add(*(value * u[j] for j, value in self._J_rows[k])))

    def _times(self, u: Sequence[sp.Expr]) -> sp.Matrix:
        """``J u``: every contact's normal closing velocity, one sparse row at a time."""
        return sp.Matrix([self._closing(k, u) for k in range(len(self.contacts))])

    @cached_property
    def _J_rows(self) -> list[list[tuple[int, sp.Expr]]]:
        """Each row of J as its nonzero (column, value) pairs."""
        found: list[list[tuple[int, sp.Expr]]] = [[] for _ in self.contacts]
        for i, j, value in self._J.row_list():
            found[i].append((j, value))
        return found

    @cached_property
    def _inverse_inertia(self) -> list[sp.Expr]:
        """The diagonal of M^-1, one entry per coordinate."""
        return [1 / c.inertia for c in self.coordinates]

    def _after(self, u: sp.Matrix) -> tuple[Body, ...]:
        """The bodies moving with `u`, tidied (a pivoted body's centre by its turn)."""
        after = moving(self.bodies, self.coordinates, [_tidied(x) for x in u])
        return tuple(b if b.support != "pivot" else b.with_motion(
            b.velocity.applyfunc(_tidied), b.spin) for b in after)

    def _outcome(self, rule: str, order: Sequence[str], u: sp.Matrix,
                 impulses: dict[str, sp.Expr], acted: Sequence[str], passes: int = 1,
                 **more: Any) -> Solution:
        """The one :class:`Solution` a rule gives: the bodies moving with `u` after,
        certified (see :mod:`rigidimpact.solve.certificate`): a physical limit of the
        model here goes into its warnings; a broken condition is never an answer."""
        joined: dict[str, Any] = {"joints": self.joints, "joint_impulses":
                                  self._joint_impulses(impulses, more.get("tangential") or {})
                                  } if self.joints else {}
        solution = Solution(before=self.bodies, after=self._after(u), impulses=impulses,
                            contacts=self.contacts, rule=rule, order=tuple(order),
                            acted=tuple(acted), passes=passes, **joined, **more)
        return certified(solution)

    @property
    def _dense(self) -> bool:
        """Whether M^-1 is dense (joints couple the bodies' coordinates; a model source
        with a full mass matrix): then an impulse moves every coordinate through it."""
        return bool(self.joints)

    def _kick(self, u: sp.Matrix, impulses: sp.Matrix) -> sp.Matrix:
        if self._dense:  # the joints spread each impulse over every joined body
            return (sp.Matrix(u) + self.M_inverse * (self._J.T * sp.Matrix(impulses))
                    ).applyfunc(tidy)
        change: dict[int, sp.Expr] = {}
        for i, row in enumerate(self._J_rows):
            if impulses[i] != 0:
                for j, value in row:
                    change[j] = change.get(j, 0) + value * impulses[i]
        inverse = self._inverse_inertia
        return sp.Matrix([tidy(u[j] + inverse[j] * change[j]) if j in change
                          else u[j] for j in range(len(u))])

    def simultaneous(self) -> Solution:
        """All contacts at once, no contact pulling (a complementarity problem).

        Newton's law: every acting contact leaves at ``-e`` times its closing velocity
        before, every released one at least that fast. Poisson's law: the compression
        impulses solve the same problem with target zero, and each is scaled by 1 + e.
        How the problem is solved depends on its size and numbers (see :meth:`_lcp`):
        Lemke's method in exact arithmetic (a 16-contact fan in 0.025 s here), trying
        the acting sets from the largest down, or past those sizes floating point with
        an exact check (a 1001-ball cradle in about 1 s); the outcome's `method` and
        notes say which when it is not the first.
        """
        self._numbers_only("simultaneous")
        if self.frictional:
            return self._frictional_simultaneous()
        v = self._velocity_before
        poisson = self._poisson()
        target = sp.zeros(len(v), 1) if poisson else \
            sp.Matrix([self._leaving(i, min(v[i], 0)) for i in range(len(v))])
        impulses, how, method = self._lcp(v, target)
        if poisson:  # each law makes its whole impulse from its compression impulse
            impulses = sp.Matrix([self.contacts[i].laws[0].from_compression(impulses[i])
                                  for i in range(len(v))])
        u = self._kick(self.u_before, impulses)
        return self._outcome("simultaneous", (), u, self._named(impulses),
                       tuple(t.name for t, p in zip(self.contacts, impulses, strict=True)
                             if p > 0), notes=how + (self._still_closing(u) if poisson else ()),
                             method=method)

    def _leaving(self, k: int, closing: sp.Expr) -> sp.Expr:
        """The normal velocity after that contact k's restitution law asks on a straight
        impulse path, from its closing velocity before (the law's own, so a new law is
        one class)."""
        return tidy(self.contacts[k].laws[0].leaving(closing))

    def _still_closing(self, u: sp.Matrix) -> tuple[str, ...]:
        """A warning for every contact that still approaches after the impact (the bodies
        would pass into each other): Poisson's law scales each compression impulse by
        its own 1 + e, which need not leave every contact opening."""
        after = self._times(u)
        scale = max(abs(x) for x in self._velocity_before)
        closing = [(t.name, after[i] / self.row_scale[i]) for i, t in enumerate(self.contacts)
                   if after[i] < -sp.Rational(1, 10**12) * scale]
        return tuple(f"{name} still approaches after the impact (normal velocity "
                     f"{float(speed):.6g}): the bodies would pass into each other; the "
                     f"simultaneous rule with Poisson's law cannot honour the physics here "
                     f"(the sequential rule can)" for name, speed in closing)

    def _frictional_simultaneous(self) -> Solution:
        """All contacts at once with Coulomb friction, at the velocity level.

        Each contact is released (no impulse, separating at least as fast as Newton's
        law asks), sticking (it leaves with Newton's normal velocity and no slip, its
        tangential impulse inside the cone |P_t| <= mu P_n) or sliding (on the cone's
        edge, opposite to the slip it leaves with). This is the model of time-stepping
        codes (Stewart and Trinkle, Anitescu and Potra), not Routh's integration over
        the impact: friction acts on the velocities after, so it agrees with Routh's
        method when the slip does not change during the impact. Every combination of
        states is solved exactly; with friction the problem can have several solutions,
        or none (Painleve's paradox), and the outcome says so.
        """
        if len(self.contacts) == 1:  # one contact: its own exact answer, under any law
            return self._one_acting(0, [sp.Integer(0)])
        restitution, tangential = zip(*(t.laws for t in self.contacts), strict=True)
        late = [t.name for t, r in zip(self.contacts, restitution, strict=True)
                if r.together != "velocity"]
        if late:
            raise InputError(f"{late[0]}.law", "with friction the simultaneous rule takes "
                             "Newton's law at every contact (the sequential rule takes "
                             "each law)")
        formless = [(t.name, law.name) for t, law in zip(self.contacts, tangential,
                                                          strict=True)
                    if not law.velocity_states]
        if formless:
            raise InputError(f"{formless[0][0]}.tangential", f"the {formless[0][1]} law "
                             "has no form for contacts acting together: use the "
                             "sequential rule (each contact's own impact)")
        n = len(self.contacts)
        v_n, v_t = self._velocity_before, (self._J_t * self.u_before).applyfunc(tidy)
        mu = [law.cone() for law in tangential]
        target = [self._leaving(i, min(v_n[i], 0)) for i in range(n)]
        rows = sp.Matrix.vstack(self._J, self._J_t)
        W = (rows * self.M_inverse * rows.T).applyfunc(_tidied)
        states = [("off",) + law.velocity_states for law in tangential]
        found: list[tuple[sp.Matrix, tuple[str, ...]]] = []
        count = math.prod(len(s) for s in states)
        if count > MAX_SYMBOLIC_CASES:
            raise InputError("contacts", _too_many_states(n, count))
        deadline = time.perf_counter() + MAX_SYMBOLIC_SECONDS
        not_unique = False
        for pattern in itertools.product(*states):
            if all(state == "off" for state in pattern):
                continue
            if time.perf_counter() > deadline:
                raise InputError("contacts", _too_many_states(n, count))
            fits = self._friction_pattern(pattern, W, v_n, v_t, target, mu)
            if fits is None:
                continue
            solved, unique = fits
            if all(solved != f for f, _ in found):
                found.append((solved, pattern))
                not_unique = not_unique or not unique
        if not found:
            raise InputError("impact.rule", "no impulses satisfy the simultaneous rule with "
                             "friction here (a Painleve-type inconsistency); try the "
                             "sequential rule")
        acting = {tuple(i for i in range(n) if f[i] > 0) for f, _ in found}
        if len(acting) == 1 and len(next(iter(acting))) == 1:
            (k,), = acting
            if tangential[k].solved_by_regimes:  # one contact acts: its own exact answer
                return self._one_acting(k, target)
        impulses, pattern = found[0]
        motions = [(self.u_before + self.M_inverse * rows.T * f).applyfunc(tidy)
                   for f, _ in found]
        u = motions[0]
        notes: tuple[str, ...] = ()
        if not_unique:
            notes = ("more contact conditions than freedoms: the motion after is unique but "
                     "the impulses are not; shown: the least-norm impulses of each state",)
        if len(found) > 1 and all(m == u for m in motions):
            # with the velocities after fixed, the conditions on the impulses are convex:
            # every mixture of the solutions found is one too; the mean is shown
            impulses = (sum((f for f, _ in found), sp.zeros(2 * n, 1)) / len(found)
                        ).applyfunc(tidy)
            pattern = tuple(pattern[i] if all(p[i] == pattern[i] for _, p in found)
                            else "mixed" for i in range(n))
            notes += (f"the motion after is unique but the impulses are not: {len(found)} "
                     "ways to share them between the contacts fit the rule, and every "
                     "mixture of them; shown: their mean",)
        elif len(found) > 1:
            notes += (f"the simultaneous rule with friction has {len(found)} solutions here, "
                     "with different motions after; shown: " + ", ".join(
                         _STATE[s] for s in pattern) + "; others: " + "; ".join(
                         ", ".join(_STATE[s] for s in p) for _, p in found[1:]),)
        normal = impulses[:n, 0]
        return self._outcome("simultaneous", (), u,
                       self._named(normal), tuple(t.name for t, p in
                                                  zip(self.contacts, normal, strict=True)
                                                  if p > 0),
                       tangential=self._named(impulses[n:, 0]),
                       courses=tuple(f"{t.name}: {_STATE[s]}" for t, s in
                                     zip(self.contacts, pattern, strict=True)),
                       notes=notes)

    def _one_acting(self, k: int, target: list[sp.Expr]) -> Solution:
        """Only contact k acts: its frictional impact alone by Routh's method (the answer
        for one contact under every rule), if that leaves every other contact opening
        at least as fast as its law asks; otherwise one line saying so."""
        normal, along, course, u = self._routh_step(k, self.u_before)
        after = self._times(u)
        blocked = [t.name for i, t in enumerate(self.contacts)
                   if i != k and after[i] < target[i]]
        name = self.contacts[k].name
        if blocked:
            raise InputError("impact.rule", f"only {name} acts at the velocity level, but "
                             f"its exact (Routh) impulse leaves {', '.join(blocked)} "
                             "closing: the simultaneous rule has no consistent answer here; "
                             "try the sequential rule")
        zeros = sp.zeros(len(self.contacts), 1)
        normals, tangentials = zeros.copy(), zeros.copy()
        normals[k], tangentials[k] = normal, along
        return self._outcome("simultaneous", (), u,
                       self._named(normals), (name,),
                       tangential=self._named(tangentials) if self.frictional else {},
                       courses=tuple(f"{t.name}: {course}" if i == k else
                                     f"{t.name}: {_STATE['off']}"
                                     for i, t in enumerate(self.contacts)))

    def _friction_pattern(self, pattern, W, v_n, v_t, target,
                          mu) -> tuple[sp.Matrix, bool] | None:
        """The impulses (normal then tangential) for one choice of contact states, if
        that choice is consistent, and whether they are the only ones."""
        n = len(pattern)
        P = sp.symbols(f"p0:{2 * n}")
        after = sp.Matrix(list(v_n) + list(v_t)) + W * sp.Matrix(P)
        equations = []
        for i, state in enumerate(pattern):
            if state == "off":
                equations += [P[i], P[n + i]]
                continue
            equations.append(after[i] - target[i])
            if state in ("on",):
                equations.append(P[n + i])
            elif state == "stick":
                equations.append(after[n + i])
            else:
                equations.append(P[n + i] + (1 if state == "slide+" else -1) * mu[i] * P[i])
        matrix, rhs = sp.linear_eq_to_matrix(equations, P)
        impulses, unique = _exact_solve(matrix, rhs), True
        if impulses is None:  # the states do not fix the impulses: if they are consistent
            impulses, unique = least_norm(matrix, rhs), False  # the motion is fixed (W's
            if impulses is None:  # null vectors are J^T's); the least-norm ones are shown
                return None
        after = (sp.Matrix(list(v_n) + list(v_t)) + W * impulses).applyfunc(tidy)
        for i, state in enumerate(pattern):
            p_n, p_t, slip = impulses[i], impulses[n + i], after[n + i]
            if state == "off":
                if after[i] < target[i]:
                    return None
                continue
            if p_n < 0:
                return None
            if state == "stick" and mu[i] is not None and abs(p_t) > mu[i] * p_n:
                return None
            if state == "slide+" and slip < 0 or state == "slide-" and slip > 0:
                return None
        return impulses, unique

    def _poisson(self) -> bool:
        """Whether the contacts act under Poisson's law (else Newton's); they must agree."""
        if len(self.contacts) == 1:  # a straight impulse path: every law reads as Newton's
            return False
        forms = [t.laws[0].together for t in self.contacts]
        if None in forms:
            name = self.contacts[forms.index(None)].name
            raise InputError(f"{name}.law", f"the {self.contacts[forms.index(None)].law} "
                             "law has no form for contacts acting together: use the "
                             "sequential rule (each contact's own impact)")
        if len(set(forms)) > 1:
            raise InputError("contacts", "give every contact the same law to act together")
        return forms[0] == "impulse"

    def _active_sets(self, v: sp.Matrix, target: sp.Matrix):
        """Each set of acting contacts whose block of W is invertible, largest first:
        ``(active, P, v + W P)`` with P solving ``(v + W P)_i = target_i`` where it acts
        and zero elsewhere (the conditions that pick a set are the caller's)."""
        n = len(v)
        deadline = time.perf_counter() + MAX_SYMBOLIC_SECONDS
        for size in range(n, 0, -1):
            for active in itertools.combinations(range(n), size):
                if time.perf_counter() > deadline:  # checked for singular blocks too
                    raise InputError("contacts", f"{n} contacts: {2 ** n} sets of acting "
                                     "contacts, more than can be tried in "
                                     f"{MAX_SYMBOLIC_SECONDS:.0f} s (give numbers for the "
                                     "symbols: the rule then needs no such search)")
                block = self._W.extract(list(active), list(active))
                det = tidy(block.det())
                if det == 0 or (block.has(sp.Float) and det.is_number and abs(det) <= 1e-35
                                * abs(sp.prod(block[i, i] for i in range(size)))):
                    continue  # singular (at 50 digits: to within their rounding)
                solved = block.LUsolve(sp.Matrix([target[i] - v[i] for i in active]))
                impulses = sp.zeros(n, 1)
                for k, i in enumerate(active):
                    impulses[i] = tidy(solved[k])
                yield active, impulses, v + self._W * impulses

    def _lcp(self, v: sp.Matrix,
             target: sp.Matrix) -> tuple[sp.Matrix, tuple[str, ...], str]:
        """The complementarity problem: exactly by Lemke's method (:mod:`rigidimpact.solve.lcp`)
        when its numbers are rational, W invertible (then exactly one answer fits, the one
        enumeration finds) and the contacts at most :data:`MAX_LEMKE`; at more contacts,
        or with irrational numbers past :data:`MAX_ENUMERATED`, in floating point with an
        exact check (:meth:`_lcp_at_scale`); otherwise by enumerating the acting sets.
        Returns the impulses, the notes a reader must see (an answer in floating point,
        with its residual) and how the problem was solved (at scale)."""
        rational = self._rational_W and all(isinstance(x, sp.Rational)
                                            for x in list(v) + list(target))
        if len(v) > MAX_LEMKE or (not rational and len(v) > MAX_ENUMERATED):
            return self._lcp_at_scale(v, target, rational)
        if rational:
            W = self._W.to_DM()
            if W.rank() == W.shape[0]:
                q = [Fraction(int(x.p), int(x.q)) for x in v - target]
                M = [[Fraction(int(x.p), int(x.q)) for x in self._W.row(i)]
                     for i in range(len(v))]
                try:
                    z = lemke(M, q)
                except NoSolution:  # cannot happen for a positive definite W; be safe
                    return self._complementarity(v, target), (), ""
                return sp.Matrix([sp.Rational(x.numerator, x.denominator) for x in z]), (), \
                    ""
            if len(v) > MAX_ENUMERATED:  # singular W: many impulses, one motion after
                return self._lcp_at_scale(v, target, rational)
        return self._complementarity(v, target), (), ""

    @cached_property
    def _rational_rows(self) -> bool:
        """Whether J's rows and M^-1 are rational (then so is W)."""
        return not self._dense and \
            all(isinstance(x, sp.Rational) for row in self._J_rows for _, x in row) and \
            all(isinstance(x, sp.Rational) for x in self._inverse_inertia)

    @cached_property
    def _rational_W(self) -> bool:
        """Whether W is rational (it can be where J is not: sqrt(3)^2)."""
        return self._rational_rows or all(isinstance(x, sp.Rational)
                                          for _, _, x in self._W_entries)

    def _float_W(self) -> Any:
        """W in float64 as a SciPy sparse matrix, from J's sparse rows (W itself, dense
        when one body touches every contact, is never formed exactly at scale)."""
        import scipy.sparse as sps

        rows = self._J_rows
        J = sps.csr_matrix(([float(x) for row in rows for _, x in row],
                            ([i for i, row in enumerate(rows) for _ in row],
                             [j for row in rows for j, _ in row])),
                           shape=(len(rows), len(self.coordinates)))
        inverse = sps.diags([float(x) for x in self._inverse_inertia])
        return (J @ inverse @ J.T).tocsc()

    @cached_property
    def _W_entries(self) -> list[tuple[int, int, sp.Expr]]:
        return [(i, j, x) for (i, j), x in sorted(self._W.todok().items()) if x != 0]

    def _lcp_at_scale(self, v: sp.Matrix, target: sp.Matrix,
                      rational: bool) -> tuple[sp.Matrix, tuple[str, ...], str]:
        """Many contacts: the acting set by block principal pivoting in floating point
        (sparse W), then, with rational numbers, that set solved and checked exactly.
        The notes say which it is, with the floating-point answer's certified residual
        when the exact check could not be made; a singular W (more contacts than a
        body's freedoms) has many impulses with the same motion after, and the one
        reported is then said to be chosen close to the least-norm one."""
        import numpy as np
        from scipy.sparse.linalg import splu

        n = len(v)
        W = self._float_W()
        q = np.array([float(v[i] - target[i]) for i in range(n)])
        try:
            pivots = np.abs(splu(W, permc_spec="MMD_AT_PLUS_A").U.diagonal())
            singular = bool(pivots.min() < 1e-11 * pivots.max())
        except RuntimeError:  # exactly singular
            singular = True
        if singular:
            z, steps = proximal(W, q, 1e-2 * float(W.diagonal().max()))
            method = f"the proximal point method, {steps} rounds of block principal pivoting"
        else:
            z, steps, _ = pivoting(W, q)
            method = f"block principal pivoting, {steps} steps"
            acting = [i for i in range(n) if z[i] > 0]
            if rational and self._rational_rows:  # in SymPy's QQ (python-flint's fmpq
                def field(x: sp.Rational) -> Any:  # where it is installed), W unformed
                    return QQ(int(x.p), int(x.q))

                exact = confirm_by_rows(
                    [[(j, field(x)) for j, x in row] for row in self._J_rows],
                    [field(x) for x in self._inverse_inertia],
                    [field(x) for x in v - target], acting)
            elif rational:  # W rational, J not (sqrt(3) in a hexagonal cluster)
                rows: dict[int, dict[int, Fraction]] = {i: {} for i in range(n)}
                for i, j, x in self._W_entries:
                    rows[i][j] = Fraction(int(x.p), int(x.q))
                exact = confirm(rows, [Fraction(int(x.p), int(x.q)) for x in v - target],
                                acting)
            else:
                exact = None
            if exact is not None:
                return sp.Matrix([sp.sympify(QQ.to_sympy(x) if not isinstance(x, Fraction)
                                             else sp.Rational(x.numerator, x.denominator))
                                  for x in exact]), (), (
                        f"{n} contacts: the acting set found in floating point ({method}) "
                        "and confirmed in exact arithmetic")
        error = residual(W, q, z)
        how = ("W is singular (more contacts than the bodies' freedoms): the motion after "
               "is unique, the impulses are not (those reported stay close to the "
               "least-norm ones); " if singular else "")
        note = (f"{n} contacts solved in floating point ({method}): {how}complementarity "
                f"residual {error:.1e} of the largest closing speed"
                + ("" if error < 1e-9 else " (LARGE: do not trust these numbers)"))
        return sp.Matrix([sp.Float(float(x), 17) for x in z]), (note,), note

    def _complementarity(self, v: sp.Matrix, target: sp.Matrix) -> sp.Matrix:
        """P >= 0 with ``v + W P >= target`` and equality wherever P > 0, by trying the
        acting sets (largest first) for at most MAX_SYMBOLIC_SECONDS: past that, one line
        says how large the problem is instead of a run of minutes."""
        for active, impulses, after in self._active_sets(v, target):
            if all(impulses[i] >= 0 for i in active) and all(
                    after[i] - target[i] >= 0 for i in range(len(v)) if i not in active):
                return impulses
        return sp.zeros(len(v), 1)

    def _smooth_step(self, k: int, u: list[sp.Expr], closing: sp.Expr) -> sp.Expr:
        """Contact k alone, smooth, with Newton's e: its impulse, with u changed in place
        (only the two bodies' coordinates the contact moves)."""
        impulse = tidy((self._leaving(k, closing) - closing) / self._W[k, k])
        if self._dense:
            change = self.M_inverse * self._J[k, :].T * impulse
            for j in range(len(u)):
                u[j] = tidy(u[j] + change[j])
            return impulse
        for j, value in self._J_rows[k]:
            u[j] = tidy(u[j] + value * impulse * self._inverse_inertia[j])
        return impulse

    def sequential(self, order: Sequence[str]) -> Solution:
        """One contact at a time in `order`, passes repeated until none approaches.

        With e < 1 the passes can go on forever while the closing speeds shrink
        geometrically (a stack coming to rest): they stop once every closing speed left
        is below 1e-40 of the largest before, so such results are exact to that size.
        """
        self._numbers_only("sequential")
        index = self._order_index(order)
        u = list(self.u_before)
        floating: list[str] = []

        def step(k: int, closing: sp.Expr) -> tuple[sp.Expr, sp.Expr, str | None]:
            if self.contacts[k].laws[1].grips:  # its own impact (Routh's for Coulomb)
                if not floating and not all(x.is_Rational for x in u):
                    # the arithmetic is chosen before the next case analysis: a state
                    # out of the rationals (an energetic step's square root) would
                    # nest a root in every later step, so from here on every step
                    # starts from the state as FLOAT_DIGITS-digit Floats
                    floating.append(self.contacts[k].name)
                if floating:
                    u[:] = [_rounded(x) for x in u]
                impulse, along, course, after = self._routh_step(k, sp.Matrix(u))
                if floating:
                    impulse, along = _rounded(impulse), _rounded(along)
                    after = after.applyfunc(_rounded)
                u[:] = list(after)
                return impulse, along, course
            return self._smooth_step(k, u, closing), sp.Integer(0), None

        count, steps = sequential_passes([index[name] for name in order],
                                         lambda k: self._closing(k, u), step,
                                         max(abs(v) for v in self._velocity_before))
        total, tangential = sp.zeros(len(index), 1), sp.zeros(len(index), 1)
        for k, impulse, along, _ in steps:
            total[k] += impulse
            tangential[k] += along
        courses = tuple(f"{self.contacts[k].name}: {course}" for k, _, _, course in steps
                        if course is not None)
        notes = (f"from {floating[0]}'s step on, the velocities held square roots that "
                 "would nest at every further step: each step from there started from "
                 f"them rounded to {FLOAT_DIGITS} digits (the results are good to about "
                 "that many digits, not exact)",) if floating else ()
        return self._outcome("sequential", tuple(order), sp.Matrix(u),
                             self._named(total.applyfunc(tidy)),
                             tuple(t.name for t, p in zip(self.contacts, total, strict=True)
                                   if p > 0),
                             count, tangential=self._named(tangential.applyfunc(tidy))
                             if self.frictional else {}, courses=courses, notes=notes,
                             method=f"rounded to {FLOAT_DIGITS} digits between steps"
                             if floating else "")

    def _routh_step(self, k: int,
                    u: sp.Matrix) -> tuple[sp.Expr, sp.Expr, str, sp.Matrix]:
        """Contact k's impact alone under its own laws (Routh's method for Coulomb,
        Walton's for rough): (P_n, P_t, course, the generalized velocities after)."""
        restitution, tangential = self.contacts[k].laws
        rows = sp.Matrix.vstack(self._J[k, :], self._J_t[k, :])
        W = (rows * self.M_inverse * rows.T).applyfunc(_tidied)
        if W.det() == 0 and tangential.grips and not tangential.solved_by_regimes:
            raise InputError(f"{self.contacts[k].name}.tangential",
                             f"{tangential.name}: the touching points have one degree of "
                             "freedom here (their 2x2 W is singular), so they cannot both "
                             "stop slipping and leave by the restitution law; tangential = "
                             "\"coulomb\" follows them (Routh's method), or make it smooth")
        normal, along, course = tangential.alone(W, (rows * u).applyfunc(tidy), restitution)
        normal, along = tidy(normal), tidy(along)
        u_after = (u + self.M_inverse * (self._J[k, :].T * normal
                                         + self._J_t[k, :].T * along)).applyfunc(tidy)
        return normal, along, course, u_after

    def compliant(self, stiffness: Sequence[float] | float = 1e6, hertz: bool = False,
                  tolerance: float = 1e-10, record: bool = False) -> Solution:
        """Every contact a push-only spring-dashpot, integrated until all have let go.

        The contact's compression grows at its closing speed, ``d' = -(J u)``, and it
        pushes with ``k d + c d'`` (``k d^(3/2)`` with `hertz`, elastic only), never
        pulling; ``u' = M^-1 J^T f``. The bodies do not move appreciably during the
        contact, so the geometry is that of the instant of impact (the limit the rigid
        rules describe). A linear contact's damping follows from its e (see
        :mod:`rigidimpact.laws.compliance`, on the contact's effective mass ``1/W_ii``), which
        gives back exactly e for that contact alone. Equal stiffnesses give a result
        independent of their size; the ratios between contacts decide it, and as one
        contact grows far stiffer than the next, the result tends to the sequential
        rule in that order. With `record`, the outcome's ``history`` holds the
        integrator's times and the generalized velocities u there (rows: coordinates).
        The integration's energy error grows with the contacts (about k times the
        tolerance: 1e-7 for a 1000-ball Hertz chain at the default), and the outcome's
        energy tolerance says so. A 1000-ball Hertz chain runs in about 6 s here.

        Examples
        --------
        >>> out = chain(2).compliant()
        >>> round(float(out.results()["ball1.vx"]), 6)
        1.0
        """
        if self._dense:
            raise InputError("impact.rule", "the compliant rule takes built-in bodies "
                             "without joints so far (its springs integrate a diagonal M): "
                             "use the simultaneous or the sequential rule")
        import math

        import numpy as np
        import scipy.sparse as sps
        from scipy.integrate import solve_ivp
        from scipy.sparse.csgraph import reverse_cuthill_mckee

        self._numbers_only("compliant")
        self._smooth_only("under the compliant rule")
        for t in self.contacts:  # the springs' damping is chosen to give Newton's e
            if type(t.laws[0]).leaving is not NewtonRestitution.leaving:
                raise InputError(f"{t.name}.law", f"the {t.laws[0].name} law has no "
                                 "spring-dashpot form: use the simultaneous or sequential "
                                 "rule")
        k = len(self.contacts)
        stiff = np.broadcast_to(np.asarray(stiffness, dtype=float), (k,)).copy()
        if np.any(~np.isfinite(stiff)) or np.any(stiff <= 0):
            raise InputError("stiffness", "every contact stiffness must be a positive number")
        # only the coordinates some contact moves are integrated (a chain's balls do not
        # spin or move across it); J is sparse, each contact touching two bodies
        entries = self.J.row_list()  # the springs push along the unit normals
        moved = sorted({j for _, j, _ in entries})
        column = {j: c for c, j in enumerate(moved)}
        n = len(moved)
        J = sps.csr_matrix(([float(x) for _, _, x in entries],
                            ([i for i, _, _ in entries], [column[j] for _, j, _ in entries])),
                           shape=(k, n))
        JT = J.T.tocsr()
        m_inv = np.array([float(self._inverse_inertia[j]) for j in moved])
        w_diag = np.asarray(J.multiply(J) @ m_inv).ravel()  # diag(J M^-1 J^T)
        e = np.array([float(t.restitution) for t in self.contacts])
        if hertz and np.any(e < 1):
            raise InputError("restitution", "Hertzian contacts here are elastic (e = 1)")
        ratio = np.array([damping_ratio_for(float(x)) for x in e])
        damping = 0.0 if hertz else 2 * ratio * np.sqrt(stiff / w_diag)

        def force(depth, rate):
            pressed = depth > 0
            if hertz:
                push = stiff * np.where(pressed, depth, 0.0) ** 1.5
            else:
                push = stiff * depth + damping * rate
            return np.where(pressed, np.maximum(push, 0.0), 0.0)

        def rhs(_, y):
            u, depth = y[:n], y[n:n + k]
            rate = -(J @ u)
            f = force(depth, rate)
            return np.concatenate([m_inv * (JT @ f), rate, f])

        u_all = np.array(self.u_before.evalf(), dtype=float).ravel()
        y = np.concatenate([u_all[moved], np.zeros(k), np.zeros(k)])
        speed = float(max(abs(v) for v in self._velocity_before))
        mass = 1 / w_diag  # each contact's effective mass
        if hertz:  # a Hertz contact lasts about 3 (m^2 / (k^2 v))^(1/5)
            period = 3 * float(((mass / stiff) ** 2 / speed).max() ** 0.2)
        else:
            period = math.pi * float(np.sqrt(mass / stiff).max())
        # LSODA (compiled, switching between Adams and BDF as the problem asks) with the
        # Jacobian's sparsity given as a band: u couples to the depths and impulses only
        # through the sparse J, and the state, ordered by reverse Cuthill-McKee, has a
        # narrow band (a chain's a few wide), so a stiff stretch costs a band
        # factorisation, not LSODA's dense n^2 one
        none = sps.csr_matrix((n, k))  # u', depth', impulse' against u, depth, impulse
        pattern = sps.bmat([[JT @ J, JT, none], [J, None, None], [J, sps.identity(k), None]],
                           format="csr")
        pattern = (pattern + pattern.T + sps.identity(n + 2 * k)).tocsr()
        order = reverse_cuthill_mckee(pattern, symmetric_mode=True)
        place = np.empty_like(order)
        place[order] = np.arange(len(order))
        rows, cols = pattern.nonzero()
        band = int(np.abs(place[rows] - place[cols]).max())

        def ordered(t, y):
            return rhs(t, y[place])[order]

        times, states, elapsed, window = [], [], 0.0, period
        atol = tolerance * max(speed, 1.0) * period
        for rounds in range(MAX_WINDOWS):  # until every contact has let go, none closing
            run = solve_ivp(ordered, (0.0, window), y[order], method="LSODA",
                            rtol=tolerance, atol=atol, lband=band, uband=band,
                            t_eval=None if record else [window])  # else only the end
            run.y = run.y[place]
            y = run.y[:, -1]
            if record:
                times.append(run.t + elapsed)
                full = np.repeat(u_all[:, None], len(run.t), axis=1)
                full[moved] = run.y[:n]
                states.append(full)
            elapsed += window
            u, depth = y[:n], y[n:n + k]
            closing = -(J @ u)
            free = np.all(depth <= NOISE * atol)
            if free and np.all(closing <= NOISE * tolerance * speed):
                break
            if free:  # free flight until the next contact closes: exact
                soon = closing > NOISE * tolerance * speed
                wait = float(np.min(-depth[soon] / closing[soon]))
                y = y.copy()
                y[n:n + k] = np.minimum(depth + closing * wait, 0.0)
                elapsed += wait
                window = period
            elif rounds >= 10:  # a long chain: the windows grow, so they stay few
                window *= 1.5
        else:
            raise InputError("impact.rule", "the compliant contacts did not let go")
        u_all[moved] = y[:n]
        y = np.concatenate([u_all, y[n:]])
        n = len(u_all)
        u_after = sp.Matrix([sp.Float(x, 17) for x in y[:n]])
        impulses = sp.Matrix([sp.Float(x, 17) for x in y[n + k:]])
        history = (np.concatenate(times), np.concatenate(states, axis=1)) if record else None
        return self._outcome("compliant", (), u_after,
                       {t.name: impulses[i] for i, t in enumerate(self.contacts)},
                       tuple(t.name for t, p in zip(self.contacts, impulses, strict=True)
                             if p > 0), history=history,
                       energy_tolerance=max(COMPLIANT_ENERGY_TOLERANCE, 10 * k * tolerance))

    def _order_index(self, order: Sequence[str]) -> dict[str, int]:
        index = {t.name: k for k, t in enumerate(self.contacts)}
        unknown = [name for name in order if name not in index]
        if unknown or sorted(order) != sorted(index):
            raise InputError("impact.order", f"must list every contact once: "
                             f"{', '.join(index)}")
        return index

    def simultaneous_cases(self) -> tuple[Solution, ...]:
        """The simultaneous rule with symbols: one outcome per set of acting contacts,
        each with the conditions under which it is the one (its impulses >= 0, every
        released contact separating at least as fast as its law asks, every contact
        closing or at rest before). Where W is positive definite exactly one case holds
        at any numbers. Under Newton's law each contact's sign before decides its target
        (-e v- if it closes, 0 if it opens), so the cases are also split by those signs.

        Examples
        --------
        >>> m = sp.Symbol("m", positive=True)
        >>> balls = [Body.rigid(1, 1, (0, 0), (1, 0), name="a"),
        ...          Body.rigid(m, 1, (2, 0), (0, 0), name="b"),
        ...          Body.rigid(1, 1, (4, 0), (0, 0), name="c")]
        >>> touches = [Contact(restitution=1, name="ab", bodies=("a", "b"), point=(1, 0)),
        ...            Contact(restitution=1, name="bc", bodies=("b", "c"), point=(3, 0))]
        >>> both = Collision(tuple(balls), tuple(touches)).simultaneous_cases()[0]
        >>> both.results()["c.vx"], both.conditions
        (2/(m + 2), (True,))
        """
        regimes = [t.name for t in self.contacts if t.laws[1].solved_by_regimes]
        if regimes:  # Coulomb's and Walton's courses: no closed form acting together
            self._smooth_only("with symbols")
        stick = [i for i, t in enumerate(self.contacts) if t.laws[1].grips]
        v = self._velocity_before
        poisson = self._poisson()
        n = len(v)
        if stick and poisson:
            raise InputError(f"{self.contacts[stick[0]].name}.law", "a sticking contact "
                             "acting together with others takes Newton's law")
        # Newton's target -e min(v, 0) depends on each contact's sign before: one
        # pattern of signs at a time (a contact at rest, or under Poisson's law: one)
        options = []
        for i in range(n):
            if poisson or tidy(v[i]).is_zero:
                options.append([(sp.true, sp.Integer(0), v[i].is_negative is True)])
                continue
            options.append([(sp.Le(v[i], 0), self._leaving(i, v[i]), True),
                            (sp.Ge(v[i], 0), sp.Integer(0), False)])
        count = math.prod(len(o) for o in options) * 2**n  # sign patterns x acting sets
        if count > MAX_SYMBOLIC_CASES:
            raise InputError("contacts", _too_many_cases(n, count))
        deadline = time.perf_counter() + MAX_SYMBOLIC_SECONDS
        cases = []
        for pattern in itertools.product(*options):
            if not poisson and not any(closing for _, _, closing in pattern):
                continue  # nothing approaches: no impact
            signs = _conditions([c for c, _, _ in pattern])
            if signs == (sp.false,):
                continue
            target = sp.Matrix([t for _, t, _ in pattern])
            found = (self._active_sets(v, target) if not stick
                     else self._sticking_sets(v, target, stick))
            for active, compression, after, *extra in found:
                if time.perf_counter() > deadline:
                    raise InputError("contacts", _too_many_cases(n, count))
                held = _conditions(list(signs) + [sp.Ge(compression[i], 0) for i in active]
                                   + [sp.Ge(tidy(after[i] - target[i]), 0)
                                      for i in range(n) if i not in active])
                if held == (sp.false,):
                    continue
                impulses = sp.Matrix([self.contacts[i].laws[0].from_compression(
                    compression[i]) if poisson else compression[i]
                    for i in range(n)]).applyfunc(tidy)
                if extra:  # sticking contacts: their tangential impulses move u too
                    tangential, free = extra
                    u = (self.u_before + self.M_inverse * (self._J.T * impulses
                                                           + self._J_t.T * tangential)
                         ).applyfunc(tidy)
                    more: dict[str, Any] = {"tangential": self._named(tangential),
                            "courses": tuple(f"{t.name}: " + (_STATE["stick"] if i in active
                                                              else _STATE["off"])
                                             for i, t in enumerate(self.contacts))}
                    if free:
                        more["notes"] = (f"the motion after is unique but the impulses are "
                                         f"not: {', '.join(map(str, free))} may take any "
                                         "value that meets the conditions",)
                else:
                    u, more = self._kick(self.u_before, impulses), {}
                more["conditions"] = held
                cases.append(self._outcome("simultaneous", (), u, self._named(impulses),
                                           tuple(self.contacts[i].name for i in active),
                                           **more))
        return tuple(cases)

    def _sticking_sets(self, v: sp.Matrix, target: sp.Matrix, stick: Sequence[int]):
        """As :meth:`_active_sets`, with the contacts in `stick` leaving without slip
        where they act (their tangential impulse an unknown of its own, no cone):
        ``(active, P_n, v_n + (W P)_n, P_t)`` for each set whose block is invertible."""
        n = len(v)
        rows = sp.Matrix.vstack(self._J, self._J_t)
        W = (rows * self.M_inverse * rows.T).applyfunc(_tidied)
        slip = (self._J_t * self.u_before).applyfunc(tidy)
        deadline = time.perf_counter() + MAX_SYMBOLIC_SECONDS
        for size in range(n, 0, -1):
            for active in itertools.combinations(range(n), size):
                if time.perf_counter() > deadline:
                    raise InputError("contacts", _too_many_cases(n, 2**n))
                unknowns = list(active) + [n + i for i in active if i in stick]
                block = W.extract(unknowns, unknowns)
                rhs = sp.Matrix([target[i] - v[i] for i in active]
                                + [-slip[i] for i in active if i in stick])
                if tidy(block.det()) != 0:
                    solved, free = block.LUsolve(rhs), ()
                else:  # more conditions than freedoms: consistent, or no such case
                    try:
                        solved, params = block.gauss_jordan_solve(rhs)
                    except ValueError:
                        continue
                    # the impulses are not unique (the motion after is: a null vector
                    # of W's block is one of J^T's); each free part keeps a name
                    free = tuple(sp.Symbol(f"tau_{k + 1}", real=True)
                                 for k in range(len(params)))
                    solved = solved.xreplace(dict(zip(params, free, strict=True)))
                P = sp.zeros(2 * n, 1)
                for k, j in enumerate(unknowns):
                    P[j] = tidy(solved[k])
                yield active, P[:n, 0], v + (W * P)[:n, 0], P[n:, 0], free

    def sequential_pass(self, order: Sequence[str]) -> Solution:
        """The sequential rule with symbols: one pass in `order`, every contact acting
        once, with the conditions that make it so (each contact closing at its turn) and
        that end the rule there (no contact closing after the pass).

        Examples
        --------
        >>> e = sp.Symbol("e", nonnegative=True)
        >>> out = chain(3, e).sequential_pass(("c0", "c1"))
        >>> [out.results()[f"ball{k}.vx"] for k in range(3)]
        [-(e - 1)/2, (1 - e)*(e + 1)/4, (e + 1)**2/4]

        With e < 1 the first pair still closes after the pass, so one pass ends the rule
        only at e = 1:

        >>> out.conditions
        (e**2 - 2*e <= -1,)
        """
        self._smooth_only("with symbols")
        index = self._order_index(order)
        u = list(self.u_before)
        total = sp.zeros(len(index), 1)
        conditions = []
        for name in order:
            k = index[name]
            closing = self._closing(k, u)
            conditions.append(sp.Lt(closing, 0))
            total[k] = self._smooth_step(k, u, closing)
        conditions += [sp.Ge(x, 0) for x in self._times(u)]
        return self._outcome("sequential", tuple(order), sp.Matrix(u),
                       self._named(total.applyfunc(tidy)), tuple(order),
                       conditions=_conditions(conditions))

    def sequential_cases(self, order: Sequence[str]) -> tuple[Solution, ...]:
        """The sequential rule with symbols, friction allowed: one pass in `order`, each
        contact's step its own impact under its own laws, as in :meth:`sequential_pass`.
        A Coulomb or rough step can take several courses (Routh's and Walton's regimes,
        each with its conditions), so the pass is a tree of cases: one outcome per path
        through it, with every condition along the path (and the pass's own: each
        contact closing at its turn, none closing after). A path whose conditions cannot
        hold is dropped.

        Examples
        --------
        A particle of mass 1 sliding onto a floor at (1, -1) with Coulomb's mu and
        Poisson's e = 1/2: the normal impulse is 1 in compression and 3/2 in all, so it
        slides throughout while mu 3/2 <= 1, stops sliding in compression once mu >= 1,
        and in restitution between.

        >>> mu = sp.Symbol("mu", positive=True)
        >>> floor = Contact((0, -1), sp.Rational(1, 2), "coulomb", "poisson", "f",
        ...                 bodies=("p", "floor"), friction=mu)
        >>> ball = Body.rigid(1, 0, (0, 0), (1, -1), name="p")
        >>> cases = Collision((ball, Body.fixed("floor")), (floor,)).sequential_cases(("f",))
        >>> for c in cases:
        ...     print(c.courses, c.results()["p.vx"], c.conditions)
        ('f: slip',) -(3*mu - 2)/2 (mu <= 2/3,)
        ('f: slip-stick, in compression',) 0 (mu > 1,)
        ('f: slip-stick, in restitution',) 0 (mu <= 1, mu > 2/3)
        """
        if not self.frictional:
            return (self.sequential_pass(order),)
        index = self._order_index(order)
        n = len(index)
        # each path so far: (u, normal impulses, tangential impulses, conditions, courses)
        branches: list[tuple[sp.Matrix, sp.Matrix, sp.Matrix, list, list[str]]] = [
            (sp.Matrix(self.u_before), sp.zeros(n, 1), sp.zeros(n, 1), [], [])]
        for name in order:
            k = index[name]
            restitution, tangential = self.contacts[k].laws
            rows = sp.Matrix.vstack(self._J[k, :], self._J_t[k, :])
            W = (rows * self.M_inverse * rows.T).applyfunc(_tidied)
            grown = []
            for u, total, along, conditions, courses in branches:
                v = (rows * u).applyfunc(tidy)
                here = [*conditions, sp.Lt(v[0], 0)]
                if tangential.solved_by_regimes:
                    steps = [(r.impulse, r.conditions, r.name)
                             for r in tangential.regimes(W, v, restitution)]
                else:
                    normal, t, course = tangential.alone(W, v, restitution)
                    steps = [((normal, t), (), course)]
                for (normal, t), more, course in steps:
                    kept = _conditions([*here, *more])
                    if kept == (sp.false,):
                        continue
                    push = sp.Matrix([tidy(normal), tidy(t)])
                    after = (u + self.M_inverse * rows.T * push).applyfunc(tidy)
                    grown.append((after, total + _at(n, k, push[0]), along + _at(n, k, push[1]),
                                  [c for c in kept if c is not sp.true],
                                  [*courses, f"{name}: {course}"]))
            branches = grown
        cases = []
        for u, total, along, conditions, courses in branches:
            kept = _conditions([*conditions, *(sp.Ge(x, 0) for x in self._times(u))])
            if kept == (sp.false,):
                continue
            cases.append(self._outcome("sequential", tuple(order), u,
                                       self._named(total.applyfunc(tidy)), tuple(order),
                                       tangential=self._named(along.applyfunc(tidy)),
                                       courses=tuple(courses), conditions=kept))
        if not cases:
            symbols = ", ".join(sorted(map(str, self.symbols)))
            raise InputError("contacts", f"one pass in the order {', '.join(order)} does not "
                             "end the sequential rule for any value of the symbols (a "
                             "contact closes again after it): the passes that follow need "
                             f"numbers; give [values] (or --set) for {symbols}")
        return tuple(cases)

    def every_order(self) -> tuple[Solution, ...]:
        """The sequential rule in every order of the contacts."""
        names = [t.name for t in self.contacts]
        count = math.factorial(len(names))  # counted before any order is made
        if count > MAX_ORDERS:
            raise InputError("impact.order", f"{len(names)} contacts have {count} orders "
                             f"(at most {MAX_ORDERS} are run): give one, or ask for a "
                             "seeded sample (orders = N, seed = S)")
        orders = list(itertools.permutations(names))
        if self.symbols:
            return tuple(self.sequential_pass(order) for order in orders)
        return tuple(self.sequential(order) for order in orders)

    def sampled_orders(self, count: int, seed: int) -> tuple[Solution, ...]:
        """The sequential rule in `count` orders drawn at random (``random.Random(seed)``,
        each a uniform shuffle; repeats possible when the orders are few): a sample of
        the outcomes' spread, not every order."""
        self._numbers_only("sequential")
        if not 1 <= count <= MAX_SAMPLED_ORDERS:
            raise InputError("impact.orders", f"must lie in [1, {MAX_SAMPLED_ORDERS}], got "
                             f"{count}")
        draw, names = random.Random(seed), [t.name for t in self.contacts]
        orders = []
        for _ in range(count):
            order = names[:]
            draw.shuffle(order)
            orders.append(tuple(order))
        # a cost budget, not only a count: the first order's time says what all cost
        start = time.perf_counter()
        found = [self.sequential(orders[0])]
        estimate = (time.perf_counter() - start) * count
        if estimate > MAX_SAMPLE_SECONDS:
            raise InputError("impact.orders", f"{count} orders would take about "
                             f"{estimate:.0f} s (one took {estimate / count:.2g} s), past "
                             f"the budget of {MAX_SAMPLE_SECONDS:g} s: ask for fewer")
        return tuple(found + [self.sequential(order) for order in orders[1:]])

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
        if len(self.contacts) == 1 and not self.joints:  # every rule: its own answer,
            solved = self.alone()  # reported under the rule that was asked
            if solved.rule != rule.name:
                solved = replace(solved, rule=rule.name, order=(
                    (self.contacts[0].name,) if rule.name == "sequential" else ()))
            return (solved,)
        return tuple(replace(o, pivot_reactions=reactions)
                     if (reactions := self._pivot_reactions(o)) else o
                     for o in rule.outcomes(self))

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
        solution = Impact(first, second, c).solve()

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

    def _pivot_reactions(self, outcome: Solution) -> dict[str, tuple[sp.Expr, sp.Expr]]:
        """What each pivot gives its body: the body's change of linear momentum less the
        contact impulses it received (each along its contact's unit normal and tangent;
        the second body of a contact receives +P, the first -P)."""
        found = {}
        for before, after in zip(outcome.before, outcome.after, strict=True):
            if before.support != "pivot":
                continue
            received = sp.zeros(2, 1)
            for t in self.contacts:
                if before.name not in (t.first, t.second):
                    continue
                push = outcome.impulses[t.name] * t.unit_normal + \
                    outcome.tangential.get(t.name, sp.Integer(0)) * t.tangent
                received += push if before.name == t.second else -push
            for j in self.joints:
                if before.name in j.bodies:
                    push = sp.Matrix(outcome.joint_impulses[j.name])
                    received += push if before.name == j.second else -push
            reaction = before.mass * (after.velocity - before.velocity) - received
            found[before.name] = (tidy(reaction[0]), tidy(reaction[1]))
        return found

    def unknowns(self) -> tuple[sp.Symbol, ...]:
        """What the printed equations are solved for: each generalized velocity after
        (``V_BODYfx``, ``V_BODYfy``, ``omega_BODYfz``), then each contact's normal and
        (with friction) tangential impulse (``Pn_CONTACT``, ``Pt_CONTACT``)."""
        speeds = [sp.Symbol(f"omega_{c.body}fz" if c.kind == "omega"
                            else f"V_{c.body}f{c.kind[1]}", real=True)
                  for c in self.coordinates]
        pushes = [sp.Symbol(f"Pn_{t.name}", real=True) for t in self.contacts]
        if self.frictional:
            pushes += [sp.Symbol(f"Pt_{t.name}", real=True) for t in self.contacts]
        pushes += [sp.Symbol(f"J{axis}_{j.name}", real=True) for j in self.joints
                   for axis in "xy"]
        return tuple(speeds + pushes)

    def equations(self, outcome: Solution) -> tuple[Equation, ...]:
        """The labelled equations `outcome` solves, over :meth:`unknowns`: the momentum
        balance of every generalized velocity (``M (u+ - u-) = J^T P``, the same for
        every rule), then what the rule imposed at each contact. Substituting the
        outcome's results makes every residual zero (tested), so what is printed is
        what was solved.

        Examples
        --------
        >>> c = chain(2)
        >>> [str(eq.as_sympy()) for eq in c.equations(c.simultaneous())][-1]
        'Eq(-V_ball0fx + V_ball1fx, 1)'
        """
        n, size = len(self.contacts), len(self.coordinates)
        symbols = self.unknowns()
        u_after, P_n = sp.Matrix(symbols[:size]), sp.Matrix(symbols[size:size + n])
        pinned = 2 * len(self.joints)
        rest = symbols[size + n:len(symbols) - pinned]
        P_t = sp.Matrix(rest) if self.frictional else sp.zeros(n, 1)
        J, J_t = self.J, self.J_t
        push = J.T * P_n + J_t.T * P_t
        if self.joints:
            push += sp.Matrix(self.G).T * sp.Matrix(symbols[len(symbols) - pinned:])
        v_before = J * self.u_before
        found = []
        for i, c in enumerate(self.coordinates):
            body = self._body(c.body)
            what = {"vx": f"x momentum of {c.body}", "vy": f"y momentum of {c.body}"}.get(
                c.kind) or f"angular momentum of {c.body} about its " + (
                "pivot" if body.support == "pivot" else "centre")
            found.append(Equation(f"{what}: its change is the contacts' impulse" + (
                " and the joints'" if self.joints else ""), "",
                c.inertia * (u_after[i] - c.before), tidy(push[i]), law="momentum"))
        held = sp.Matrix(self.G) * u_after if self.joints else sp.zeros(0, 1)
        for k, j in enumerate(self.joints):
            for axis, row in (("x", held[2 * k]), ("y", held[2 * k + 1])):
                found.append(Equation(f"{j.name} holds: {j.second} and {j.first} move "
                                      f"together at it, along {axis}", "", tidy(row), 0,
                                      law="joint"))
        u = self._u_of(outcome)
        routh = outcome.rule == "simultaneous" and len(outcome.acted) == 1 and \
            self.frictional and self._by_name(outcome.acted[0]).laws[1].solved_by_regimes
        for k, t in enumerate(self.contacts):
            restitution, tangential = t.laws
            closing = (J[k, :] * u_after)[0]
            slip = (J_t[k, :] * u_after)[0]
            normal, along = outcome.impulses[t.name], outcome.tangential.get(t.name, 0)
            if outcome.rule != "simultaneous" or routh:
                how = {"sequential": f"the sum of {t.name}'s impulses in turn (each its own "
                                     "impact)",
                       "compliant": f"{t.name}'s spring impulse, integrated",
                       "simultaneous": f"{t.name} alone by its own {tangential.name} law "
                                       "(Routh's or Walton's regimes)"}
                found.append(Equation(how[outcome.rule], "", P_n[k], normal,
                                      law="rule"))
                if self.frictional:
                    found.append(Equation(how[outcome.rule] + ", tangential", "", P_t[k],
                                          along, law="rule"))
                continue
            if t.name not in outcome.acted:
                found.append(Equation(f"{t.name} released: no impulse", "", P_n[k], 0,
                                      law="released"))
            elif restitution.together == "impulse" and n > 1:
                W_k = J[k, :] * self.M_inverse * J.T
                compression = (v_before[k] + sum(
                    (W_k[0, j] * self.contacts[j].laws[0].compression(P_n[j])
                     for j in range(n)), sp.Integer(0)))
                found.append(Equation(f"{t.name} at rest at the end of compression "
                                      "(Poisson's law: each impulse is 1 + e times its "
                                      "compression impulse)", "", tidy(compression), 0,
                                      law="restitution"))
            else:
                before = tidy(v_before[k])
                closed = before.is_negative
                found.append(Equation(f"restitution at {t.name} (Newton's law" + (
                    ")" if closed else "; at rest before, it leaves at rest)"), "", closing,
                    self._leaving(k, before) if closed else 0, law="restitution"))
            if not self.frictional:
                continue
            after_slip = tidy((J_t[k, :] * u)[0])
            if not tangential.grips or t.name not in outcome.acted:
                found.append(Equation(f"{t.name}: no tangential impulse", "", P_t[k], 0,
                                      law="tangential"))
            elif after_slip == 0:
                found.append(Equation(f"{t.name} sticks: no slip after", "", slip, 0,
                                      law="tangential"))
            else:
                sign = -1 if after_slip > 0 else 1
                found.append(Equation(f"{t.name} slides: Coulomb's friction against the "
                                      "slip after", "", P_t[k], sign * tangential.cone()
                                      * P_n[k], law="tangential"))
        return tuple(found)

    def _u_of(self, outcome: Solution) -> sp.Matrix:
        """The generalized velocities of `outcome`'s bodies after."""
        after = {b.name: b for b in outcome.after}
        values = []
        for c in self.coordinates:
            body = after[c.body]
            values.append(body.spin if c.kind == "omega" else
                          body.velocity[0 if c.kind == "vx" else 1])
        return sp.Matrix(values)

    def solved_values(self, outcome: Solution) -> dict[sp.Symbol, sp.Expr]:
        """:meth:`unknowns` -> their values in `outcome` (to check the equations)."""
        n, size = len(self.contacts), len(self.coordinates)
        symbols = self.unknowns()
        values = dict(zip(symbols[:size], self._u_of(outcome), strict=True))
        values.update({symbols[size + k]: outcome.impulses[t.name]
                       for k, t in enumerate(self.contacts)})
        if self.frictional:
            values.update({symbols[size + n + k]: outcome.tangential.get(t.name, 0)
                           for k, t in enumerate(self.contacts)})
        for k, j in enumerate(self.joints):
            start = len(symbols) - 2 * len(self.joints) + 2 * k
            x, y = outcome.joint_impulses[j.name]
            values.update({symbols[start]: x, symbols[start + 1]: y})
        return values

    def _by_name(self, name: str) -> Contact:
        return next(t for t in self.contacts if t.name == name)

    def _named(self, impulses: sp.Matrix) -> dict[str, sp.Expr]:
        """Each contact's impulse along its unit normal (or tangent), by name, from the
        impulses of its scaled rows (see :attr:`row_scale`)."""
        return {t.name: impulses[k] if s == 1 else tidy(impulses[k] * s)
                for k, (t, s) in enumerate(zip(self.contacts, self.row_scale, strict=True))}


def _too_many_cases(n: int, count: int) -> str:
    return (f"{n} contacts with symbols make {count} cases (signs before x contacts "
            f"acting), more than can be solved in {MAX_SYMBOLIC_SECONDS:.0f} s: give "
            "numbers for the symbols (--set or [values]) and it is solved exactly at them")


def _exact_solve(matrix: sp.Matrix, rhs: sp.Matrix) -> sp.Matrix | None:
    """The unique solution of a square linear system of numbers, or None when it is
    singular. The numbers are taken into their own field (the rationals with sqrt(2)
    adjoined, say), where elimination is exact and fast; SymPy's general expressions
    would be factored at every step.

    Examples
    --------
    >>> _exact_solve(sp.Matrix([[1, sp.sqrt(2)], [0, 2]]), sp.Matrix([1, 2])).T
    Matrix([[1 - sqrt(2), 1]])
    """
    augmented = sp.Matrix.hstack(matrix, rhs).to_DM(extension=True)
    reduced, pivots = augmented.rref()
    size = matrix.shape[1]
    if tuple(pivots) != tuple(range(size)):
        return None
    return reduced.to_Matrix()[:, size]


def _too_many_states(n: int, count: int) -> str:
    return (f"{n} frictional contacts have {count} combinations of states (released, "
            f"sticking, sliding either way), more than can be solved exactly in "
            f"{MAX_SYMBOLIC_SECONDS:.0f} s: try the sequential rule with an order")


FLIPPED = {sp.GreaterThan: sp.LessThan, sp.LessThan: sp.GreaterThan,
           sp.StrictGreaterThan: sp.StrictLessThan, sp.StrictLessThan: sp.StrictGreaterThan}


def _sign_of(relation: sp.Basic) -> sp.Basic:
    """``expr OP 0`` with every factor of known sign taken out (a positive mass, 1 + e),
    so what is left is the condition itself.

    Examples
    --------
    >>> m, v = sp.Symbol("m", positive=True), sp.Symbol("v", real=True)
    >>> _sign_of(sp.Ge(-3 * m * v / (m + 1), 0))
    v <= 0
    """
    if relation in (sp.true, sp.false):
        return relation
    if isinstance(relation, (sp.And, sp.Or)):  # a regime's compound condition
        return type(relation)(*(_sign_of(r) for r in relation.args))
    if isinstance(relation, sp.Not):
        return sp.Not(_sign_of(relation.args[0]))
    if not isinstance(relation, sp.core.relational.Relational):
        return relation
    op = type(relation)
    expr = sp.factor(relation.lhs - relation.rhs)
    numerator, denominator = sp.fraction(expr)
    kept = []
    for factor in sp.Mul.make_args(numerator) + sp.Mul.make_args(denominator):
        if factor.is_positive:
            continue
        if factor.is_negative:
            op = FLIPPED[op]
            continue
        kept.append(factor)
    return op(sp.Mul(*kept), 0)


def sequential_passes(order: Sequence[int], closing: Callable[[int], sp.Expr],
                      step: Callable[[int, sp.Expr], tuple[sp.Expr, sp.Expr, str | None]],
                      scale: sp.Expr, settled: sp.Expr = SETTLED
                      ) -> tuple[int, list[tuple[int, sp.Expr, sp.Expr, str | None]]]:
    """The sequential rule's passes, for any model: contact by contact in `order`, each
    contact still closing (``closing(k) < 0``, beyond `settled` times `scale`) takes its
    own impact (``step(k, closing)``: its normal and tangential impulse and its course,
    the model's velocities moved by the step), repeated until a pass in which none acts.
    Returns the passes in which some contact acted and every step taken.

    Examples
    --------
    Two unit masses at rest and a third arriving at 1, e = 1, head on:

    >>> u = [1, 0, 0]
    >>> def hit(k, closing):  # equal masses: they swap velocities
    ...     u[k], u[k + 1] = u[k + 1], u[k]
    ...     return -closing, 0, None
    >>> sequential_passes([0, 1], lambda k: u[k + 1] - u[k], hit, 1)
    (1, [(0, 1, 0, None), (1, 1, 0, None)])
    """
    steps: list[tuple[int, sp.Expr, sp.Expr, str | None]] = []
    count, acted = 0, True
    deadline = time.perf_counter() + MAX_SEQUENTIAL_SECONDS * (1 + len(order) / 100)
    while acted:  # a pass in which no contact acted ends the rule
        if count == MAX_PASSES or time.perf_counter() > deadline:
            raise InputError("impact.rule", f"the sequential rule did not settle in "
                             f"{count} passes ({len(steps)} impacts, "
                             f"{MAX_SEQUENTIAL_SECONDS * (1 + len(order) / 100):g} s at "
                             "most): the contacts keep "
                             "closing again after each other's impacts (with e = 1 they "
                             "can ring for ever); try the simultaneous rule")
        count, acted = count + 1, False
        for k in order:
            now = closing(k)
            if now >= 0 or -now <= settled * scale:
                continue
            steps.append((k, *step(k, now)))
            acted = True
    return count - 1, steps


def _rounded(x: sp.Expr) -> sp.Expr:
    """A number as a Float of FLOAT_DIGITS significant digits (a Float stays as it is):
    SymPy's polynomial arithmetic keeps a Float's precision, and unlike a rational of
    that many digits it puts no large integer under the next square root."""
    x = sp.sympify(x)
    if x.is_Float:
        return x
    return sp.N(x, FLOAT_DIGITS)


def _tidied(x: Any) -> sp.Expr:
    """`tidy`, with a number left as it is (most of them, at scale)."""
    x = sp.sympify(x)
    return x if x.is_Number else tidy(x)


def _at(n: int, k: int, value: sp.Expr) -> sp.Matrix:
    """An n-vector holding `value` at k."""
    vector = sp.zeros(n, 1)
    vector[k] = value
    return vector


def _conditions(relations: Sequence[sp.Basic]) -> tuple[sp.Basic, ...]:
    """Relations with the ones that always hold dropped: ``(True,)`` when none is left,
    ``(False,)`` when they cannot all hold, or hold only on a boundary (an equality,
    where the neighbouring case gives the same numbers)."""
    kept = []
    for relation in relations:
        relation = _sign_of(relation)
        if relation == sp.false:
            return (sp.false,)
        if relation != sp.true and relation not in kept:
            kept.append(relation)
    if not kept:
        return (sp.true,)
    joint = sp.simplify(sp.And(*kept))
    if joint == sp.false or isinstance(joint, sp.Eq) or (
            isinstance(joint, sp.And) and any(isinstance(a, sp.Eq) for a in joint.args)):
        return (sp.false,)
    return tuple(joint.args) if isinstance(joint, sp.And) else (joint,)


def _sample_points(symbols: set[sp.Symbol]) -> list[dict[sp.Symbol, sp.Expr]]:
    """Points at which to test an identity in `symbols`: none needed (one empty point)
    without symbols, else two seeded random rational points that respect each symbol's
    sign assumptions."""
    if not symbols:
        return [{}]
    rng = random.Random(32)
    points = []
    for _ in range(2):
        point = {}
        for s in sorted(symbols, key=str):
            x = sp.Rational(rng.randint(101, 997), 311)
            point[s] = -x if s.is_negative else x
        points.append(point)
    return points


# the builders' budget: bodies are made one SymPy object at a time, a few ms each (a
# 10,000-ball chain took 35 s to build and 19 s to solve here); past it, one line first
MAX_BUILT_CONTACTS = 3000


def whole_number(name: str, value: Any, least: int, most: int | None = None,
                 why: str = "") -> int:
    """`value` as an int in [least, most], or InputError naming `name` (a bool, a float
    or a string is refused, not rounded or parsed).

    Examples
    --------
    >>> whole_number("n", 3, 2)
    3
    >>> whole_number("n", 2.5, 2)
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: n: must be a whole number, not float 2.5
    """
    if isinstance(value, bool) or not hasattr(value, "__index__"):
        raise InputError(name, f"must be a whole number, not {type(value).__name__} "
                         f"{value!r}")
    value = int(value.__index__())
    if value < least:
        raise InputError(name, f"must be at least {least}, got {value}")
    if most is not None and value > most:
        raise InputError(name, f"{value} is past the budget of {most}{why}")
    return value


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
    at `speed`, touches the middle row's first disc.

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


# ---- rules: how contacts that close together act, each one small class ---------------

class Rule:
    """How several contacts that close at the same instant act together.

    A rule is one small class: :meth:`outcomes` says what it makes of a collision (one
    outcome, or one per case or order), built from the collision's own solvers, so every
    rule returns the same :class:`~rigidimpact.solve.solution.Solution`. :data:`RULE_TYPES`
    lists the built-in ones for the scene reader; a new rule needs no entry there to be
    used from Python.
    """

    name: ClassVar[str] = ""

    def outcomes(self, collision: Collision) -> tuple[Solution, ...]:
        raise NotImplementedError

    def laws(self, frictional: bool = False) -> str:
        """What the rule imposes, in words."""
        return rule_laws(self.name, frictional)


@dataclass(frozen=True)
class Simultaneous(Rule):
    """All contacts at once, none pulling (a complementarity problem); with symbols, one
    outcome per case, each with its conditions.

    Examples
    --------
    >>> [o.label for o in chain(3).solve(Simultaneous())]
    ['simultaneous']
    """

    name: ClassVar[str] = "simultaneous"

    def outcomes(self, collision: Collision) -> tuple[Solution, ...]:
        if collision.symbols:
            return collision.simultaneous_cases()
        return (collision.simultaneous(),)


@dataclass(frozen=True)
class Sequential(Rule):
    """One contact at a time in `order`; every order when `order` is None, or a seeded
    sample of `sample` orders.

    Examples
    --------
    >>> [o.label for o in chain(3).solve(Sequential(("c0", "c1")))]
    ['sequential c0, c1']
    """

    order: tuple[str, ...] | None = None
    sample: int | None = None  # with no order: this many orders drawn with `seed`
    seed: int = 0
    name: ClassVar[str] = "sequential"

    def __post_init__(self) -> None:
        if self.order is not None:
            if isinstance(self.order, str) or not all(
                    isinstance(x, str) for x in self.order):
                raise InputError("order", "must be a sequence of contact names, e.g. "
                                 f"(\"c0\", \"c1\"), not {self.order!r}")
            object.__setattr__(self, "order", tuple(self.order))
        if self.sample is not None:
            whole_number("sample", self.sample, 1, MAX_SAMPLED_ORDERS,
                          " sampled orders (each a whole sequential run)")
        whole_number("seed", self.seed, 0)

    def outcomes(self, collision: Collision) -> tuple[Solution, ...]:
        if self.order is None and self.sample is not None:
            return collision.sampled_orders(self.sample, self.seed)
        if self.order is None:
            return collision.every_order()
        if collision.symbols:
            return collision.sequential_cases(self.order)
        return (collision.sequential(self.order),)


@dataclass(frozen=True)
class Compliant(Rule):
    """Every contact a push-only spring (linear with damping from e, or Hertz's), with
    one stiffness per contact in their order (N/m)."""

    stiffness: tuple[float, ...] | float = 1e6
    hertz: bool = False
    name: ClassVar[str] = "compliant"

    def __post_init__(self) -> None:
        values = self.stiffness if isinstance(self.stiffness, (tuple, list)) \
            else (self.stiffness,)
        for value in values:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                    not math.isfinite(value) or value <= 0:
                raise InputError("stiffness", "every contact stiffness must be a positive "
                                 f"finite number, not {value!r}")
        if not isinstance(self.hertz, bool):
            raise InputError("hertz", f"must be True or False, not {self.hertz!r}")

    def outcomes(self, collision: Collision) -> tuple[Solution, ...]:
        return (collision.compliant(self.stiffness, self.hertz),)


RULE_TYPES: tuple[type[Rule], ...] = (Simultaneous, Sequential, Compliant)
