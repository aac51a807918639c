"""The one impulse problem: bodies, contacts and joints as generalized speeds u, the
inverse mass M^-1 (diagonal for free shapes, projected where joints or a mechanics
system couple the speeds), the contact rows J (normal) and J_t (tangent), and
W = J M^-1 J^T.

It knows how the bodies move under impulses (:meth:`ImpactProblem.kick`), how fast
each contact closes, what each body is after, and how the printed equations read;
it does not know how contacts act together: that is a rule's
(:mod:`rigidimpact.solve.rules`), and every rule works on this one type, whatever
the source of M and J (the built-in shapes, joints, a sympy.physics.mechanics
system).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any, Self

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import Equation
from rigidimpact.model.bodies import Body
from rigidimpact.model.impulse import Coordinate, coordinates_of, jacobian, moving
from rigidimpact.model.joints import Joint, off_body
from rigidimpact.solve.conditions import sample_points, tidied
from rigidimpact.solve.registry import Conduct, conduct
from rigidimpact.solve.solution import Solution, read_back
from rigidimpact.symbolic.geometry import perp
from rigidimpact.symbolic.notation import COMPONENTS, labelled
from rigidimpact.symbolic.rewrite import tidy

MAX_ENUMERATED = 12


MAX_FACETS = 256  # the most edges of a pyramid standing for Coulomb's cone


def check_facets(facets: Any) -> None:
    """None, or an even whole number of a pyramid's edges from 4 to MAX_FACETS."""
    if facets is not None and (isinstance(facets, bool) or not isinstance(facets, int)
                               or not 4 <= facets <= MAX_FACETS or facets % 2):
        raise InputError("impact.facets", f"an even whole number from 4 to {MAX_FACETS}, "
                         f"not {facets!r}")


class ImpulseRows:
    """The one impulse problem, holding no bodies: generalized speeds u and u before,
    the inverse mass M^-1, one row block per contact (its normal row in J, its tangent
    rows in J_t and, in space, a second), the contacts with their law objects; W =
    J M^-1 J^T. Every rule reads only this (:mod:`rigidimpact.solve.rules`), whatever
    the source: the planar shapes with their supports and joints
    (:class:`ImpactProblem`), a 3-D collision and a sympy.physics.mechanics system
    (:class:`RowsProblem`).

    A source supplies ``contacts``, ``u_before``, ``M_inverse``, ``J`` and ``J_t`` (and
    their rows scaled by ``row_scale``), ``coordinates``, ``symbols``, whether M^-1 is
    ``dense``, and :meth:`outcome`, its reading back: what a rule's speeds after and
    impulses are in the source's own terms, as a certified Solution.
    """

    contacts: tuple[Contact, ...]
    joints: tuple[Joint, ...] = ()  # bilateral rows the source keeps itself
    facets: int | None = None  # Coulomb's cone as a pyramid of this many edges
    tolerance: float | None = None  # a source's stated tolerance for an integrated cone

    # what a source supplies
    u_before: sp.Matrix
    M_inverse: sp.Matrix
    J: sp.Matrix
    J_t: sp.Matrix
    scaled_J: sp.Matrix
    scaled_J_t: sp.Matrix

    @property
    def row_scale(self) -> tuple[sp.Expr, ...]:
        """Each contact's rows in the scaled J and J_t are its unit ones times this."""
        raise NotImplementedError

    @property
    def coordinates(self) -> tuple[Coordinate, ...]:
        """The generalized speeds, with their names and values before."""
        raise NotImplementedError

    @property
    def symbols(self) -> frozenset[sp.Symbol]:
        """The symbols left in the problem (none: at numbers)."""
        raise NotImplementedError

    @property
    def dense(self) -> bool:
        """Whether M^-1 couples the speeds (then an impulse moves every speed through it)."""
        return True

    def outcome(self, rule: str, order: Sequence[str], u: sp.Matrix,
                impulses: dict[str, sp.Expr], acted: Sequence[str], passes: int = 1,
                **more: Any) -> Solution:
        """The source's own Solution of what a rule made of the rows (its reading back:
        the bodies after, its checks from its own kinematics)."""
        raise NotImplementedError(f"{type(self).__name__} reads a rule's answer back into "
                                  "its source's Solution")

    def own_answer(self, rule: Any) -> Solution | None:
        """A source's own closed form for its one contact, in its own notation (the
        paper's two bodies: the two-body core and its printed laws), which the door
        reports under `rule`; None where the rules' one-contact step is the answer."""
        return None

    def smooth_only(self, where: str) -> None:
        rough = [t.name for t in self.contacts if t.laws[1].grips]
        if rough:
            needed = (f": give [values] (or --set) for "
                      f"{', '.join(sorted(map(str, self.symbols)))}, or ask for one "
                      "sequential pass in an order (solved with symbols, case by case)"
                      if where == "with symbols" and self.symbols else "")
            raise InputError(f"{rough[0]}.tangential", f"friction at several contacts is "
                             f"solved with numbers, by the simultaneous or sequential rule; "
                             f"not {where}{needed}")

    def numbers_only(self, rule: str) -> None:
        if self.symbols:
            raise InputError("values", f"the {rule} rule needs numbers: give [values] for "
                             f"{', '.join(sorted(map(str, self.symbols)))}")

    @property
    def frictional(self) -> bool:
        """Whether any contact's tangential law gives a tangential impulse."""
        return any(t.laws[1].grips for t in self.contacts)

    @cached_property
    def W(self) -> sp.Matrix:
        """``J M^-1 J^T``: how the contacts' impulses change their closing velocities."""
        return self._product(self.J)

    @cached_property
    def scaled_W(self) -> sp.Matrix:
        """W of the scaled rows (:attr:`row_scale`): what the rules solve with."""
        return self.W if self.scaled_J is self.J else self._product(self.scaled_J)

    def _product(self, J: sp.Matrix) -> sp.Matrix:
        """``J M^-1 J^T``."""
        exact = _in_field(J, self.M_inverse)
        if exact:  # numbers: in their own field, where the product of sparse rows is
            J, Minv = exact  # exact and fast at hundreds of contacts
            return (J * Minv * J.transpose()).to_Matrix()
        return (J * self.M_inverse * J.T).applyfunc(tidied)

    @cached_property
    def velocity_before(self) -> sp.Matrix:
        """Normal closing velocity of every contact before (negative: approaching)."""
        return (self.J * self.u_before).applyfunc(tidy)

    @cached_property
    def scaled_velocity_before(self) -> sp.Matrix:
        """The closing velocities of the scaled rows (:attr:`row_scale`)."""
        return self.closings(self.u_before)

    def closing(self, k: int, u: Sequence[sp.Expr]) -> sp.Expr:
        """Contact k's normal closing velocity at the generalized velocities u (its row
        of J, two bodies' coordinates), tidied."""
        return tidy(sp.Add(*(value * u[j] for j, value in self.sparse_rows[k])))

    def closings(self, u: Sequence[sp.Expr]) -> sp.Matrix:
        """``J u``: every contact's normal closing velocity, one sparse row at a time."""
        return sp.Matrix([self.closing(k, u) for k in range(len(self.contacts))])

    @cached_property
    def sparse_rows(self) -> list[list[tuple[int, sp.Expr]]]:
        """Each row of J as its nonzero (column, value) pairs."""
        found: list[list[tuple[int, sp.Expr]]] = [[] for _ in self.contacts]
        for i, j, value in self.scaled_J.row_list():
            found[i].append((j, value))
        return found

    @cached_property
    def inverse_inertia(self) -> list[sp.Expr]:
        """The diagonal of M^-1, one entry per coordinate."""
        return [1 / c.inertia for c in self.coordinates]

    def kick(self, u: sp.Matrix, impulses: sp.Matrix) -> sp.Matrix:
        """u after `impulses` on the scaled rows: ``u + M^-1 J^T P``."""
        if self.dense:  # M^-1 spreads each impulse over every coupled speed
            push = self.scaled_J.T * sp.Matrix(impulses)
            return (sp.Matrix(u) + self._moved_by(push)).applyfunc(tidy)
        change: dict[int, sp.Expr] = {}
        for i, row in enumerate(self.sparse_rows):
            if impulses[i] != 0:
                for j, value in row:
                    change[j] = change.get(j, 0) + value * impulses[i]
        inverse = self.inverse_inertia
        return sp.Matrix([tidy(u[j] + inverse[j] * change[j]) if j in change
                          else u[j] for j in range(len(u))])

    def _moved_by(self, push: sp.Matrix) -> sp.Matrix:
        """``M^-1 push``: the speeds' change under a generalized impulse."""
        return self.M_inverse * push

    def leaving(self, k: int, closing: sp.Expr) -> sp.Expr:
        """The normal velocity after that contact k's restitution law asks on a straight
        impulse path, from its closing velocity before (the law's own, so a new law is
        one class)."""
        return tidy(self.contacts[k].laws[0].leaving(closing))

    def acts_by_impulse(self) -> bool:
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

    @cached_property
    def rational_rows(self) -> bool:
        """Whether J's rows and M^-1 are rational (then so is W)."""
        return not self.dense and \
            all(isinstance(x, sp.Rational) for row in self.sparse_rows for _, x in row) and \
            all(isinstance(x, sp.Rational) for x in self.inverse_inertia)

    @cached_property
    def rational_W(self) -> bool:
        """Whether W is rational (it can be where J is not: sqrt(3)^2)."""
        return self.rational_rows or all(isinstance(x, sp.Rational)
                                          for _, _, x in self.W_entries)

    def float_W(self) -> Any:
        """W in float64 as a SciPy sparse matrix, from J's sparse rows (W itself, dense
        when one body touches every contact, is never formed exactly at scale)."""
        import scipy.sparse as sps

        rows = self.sparse_rows
        J = sps.csr_matrix(([float(x) for row in rows for _, x in row],
                            ([i for i, row in enumerate(rows) for _ in row],
                             [j for row in rows for j, _ in row])),
                           shape=(len(rows), len(self.coordinates)))
        inverse = sps.diags([float(x) for x in self.inverse_inertia])
        return (J @ inverse @ J.T).tocsc()

    @cached_property
    def W_entries(self) -> list[tuple[int, int, sp.Expr]]:
        return [(i, j, x) for (i, j), x in sorted(self.scaled_W.todok().items()) if x != 0]

    def order_index(self, order: Sequence[str]) -> dict[str, int]:
        index = {t.name: k for k, t in enumerate(self.contacts)}
        unknown = [name for name in order if name not in index]
        if unknown or sorted(order) != sorted(index):
            raise InputError("impact.order", f"must list every contact once: "
                             f"{', '.join(index)}")
        return index

    @property
    def tangents(self) -> int:
        """Tangent rows a contact: one in the plane (two in space, :class:`RowsProblem`)."""
        return 1

    def contact_rows(self, k: int) -> sp.Matrix:
        """Contact k's rows in its own frame, exact: (normal, tangent) in the plane."""
        return sp.Matrix.vstack(self.scaled_J[k, :], self.scaled_J_t[k, :])

    def frame_rows(self, k: int) -> Any:
        """Contact k's rows in its own frame as float64, (normal, t1, t2): the rows the
        rules that follow an impulse path read, in the plane with t2 zero (nothing moves
        across the plane, so nothing slips or rubs there)."""
        import numpy as np

        n = np.array(self.scaled_J.row(k).evalf(30), dtype=float).ravel()
        t = np.array(self.scaled_J_t.row(k).evalf(30), dtype=float).ravel()
        return np.vstack([n, t, np.zeros_like(n)])

    def _by_name(self, name: str) -> Contact:
        return next(t for t in self.contacts if t.name == name)

    def named(self, impulses: sp.Matrix) -> dict[str, sp.Expr]:
        """Each contact's impulse along its unit normal (or tangent), by name, from the
        impulses of its scaled rows (see :attr:`row_scale`)."""
        return {t.name: impulses[k] if s == 1 else tidy(impulses[k] * s)
                for k, (t, s) in enumerate(zip(self.contacts, self.row_scale, strict=True))}


@dataclass(frozen=True)
class ImpactProblem(ImpulseRows):
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
    # Coulomb's cone as the inscribed pyramid of this many edges (the simultaneous rule
    # with friction; None: the cone itself). A planar contact's one tangent has two
    # edges, + and -, so there the pyramid is the law itself.
    facets: int | None = None

    def __post_init__(self) -> None:
        check_facets(self.facets)
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
        if not self.symbols and all(sp.N(v, 30) >= 0 for v in self.scaled_velocity_before):
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
            if j.spatial:
                raise InputError(f"{j.name}.point", "a joint in the plane has a point "
                                 "[x, y] (a ball joint or a hinge in space belongs in a 3-D "
                                 "scene)")
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
        for point in sample_points(drift.free_symbols | S.free_symbols
                                    | self.u_before.free_symbols):
            gap = [sp.N(x.xreplace(point), 30) for x in drift]
            scale = 1e-20 * (1 + max(abs(sp.N(u.xreplace(point), 30)) for u in self.u_before))
            for k, j in enumerate(self.joints):
                here = gap[2 * k:2 * k + 2]
                if any(abs(x) > scale for x in here):
                    first, second = j.bodies
                    moved = [tidy(x) for x in drift[2 * k:2 * k + 2]]
                    raise InputError(f"{j.name}", f"its two bodies do not move together "
                                     f"at ({j.point[0]}, {j.point[1]}) before the impact: "
                                     f"{second}'s point moves at ({moved[0]}, {moved[1]}) "
                                     f"relative to {first}'s; give velocities and spins "
                                     "that keep the joint together")
            if not _full_rank(S.xreplace(point)):
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
                                          for j, x in enumerate(self.inverse_inertia)))

    @cached_property
    def _joint_S(self) -> sp.Matrix:
        """``G M^-1 G^T``: how the joints' impulses open their joints."""
        G = sp.Matrix(self.G)
        exact = _in_field(G, self._free_M_inverse)
        if exact:  # numbers: in their own field, sparse (a chain of hundreds of rods)
            G, Minv = exact
            return (G * Minv * G.transpose()).to_Matrix()
        return (G * sp.Matrix(self._free_M_inverse) * G.T).applyfunc(tidy)

    @cached_property
    def _joint_map(self) -> sp.Matrix:
        """``S^-1 G M^-1``: the joints' impulses are ``-S^-1 G M^-1 F`` for the contacts'
        generalized impulse F (so that the joints stay together)."""
        G = sp.Matrix(self.G)
        exact = _in_field(self._joint_S, G, self._free_M_inverse)
        if exact:
            S, G, Minv = exact
            return _joint_solve(S, G * Minv).to_Matrix()
        return (self._joint_S.inv() * G * sp.Matrix(self._free_M_inverse)).applyfunc(tidy)

    def _joint_response(self, force: sp.Matrix) -> tuple[Any, Any] | None:
        """For a generalized impulse `force` on the joined bodies, the speeds' change
        ``M^-1 force`` and the joints' ``S^-1 G M0^-1 force`` (M0: the bodies' own mass,
        S = G M0^-1 G^T), as DomainMatrices in the numbers' field: one elimination with
        S, no inverse of S and no dense M^-1 formed (a chain of hundreds of rods). None
        where symbols are left."""
        exact = _in_field(force, sp.Matrix(self.G), self._free_M_inverse)
        if not exact:
            return None
        force, G, free = exact
        moved = free * force
        held = _joint_solve(G * free * G.transpose(), G * moved)
        return moved - free * G.transpose() * held, held

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
        exact = self._joint_response(force)
        lam = (-exact[1].to_Matrix() if exact else -self._joint_map * force).applyfunc(tidy)
        return {j.name: (lam[2 * k], lam[2 * k + 1]) for k, j in enumerate(self.joints)}

    @cached_property
    def symbols(self) -> frozenset[sp.Symbol]:
        """The symbols left in the collision (none: every rule runs; some: the
        simultaneous and one-pass sequential formulas, each with its conditions)."""
        return frozenset(self.scaled_J.free_symbols | self._free_M_inverse.free_symbols
                         | (self.G.free_symbols if self.joints else set())
                         | self.u_before.free_symbols
                         | set().union(*(sp.Tuple(t.restitution, t.friction or 0,
                                                  t.tangential_restitution or 0).free_symbols
                                         for t in self.contacts)))

    @classmethod
    def from_values(cls, bodies: Sequence[Body], contacts: Sequence[Contact],
                    values: dict, joints: Sequence[Joint] = ()) -> Self:
        """The collision with numbers put in for its symbols.

        Examples
        --------
        >>> from rigidimpact.solve.collision import Collision
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
        >>> from rigidimpact.solve.collision import Collision
        >>> from rigidimpact.model.bodies import Body
        >>> Collision((Body.rigid(1, 1, (0, 0), (0, -1), name="a"), Body.fixed("floor")),
        ...           (Contact(normal=(3, -4), bodies=("a", "floor")),)).row_scale
        (5,)
        """
        return tuple(sp.sqrt(t.normal[0] ** 2 + t.normal[1] ** 2)
                     if all(isinstance(x, sp.Rational) for x in t.normal) else sp.Integer(1)
                     for t in self.contacts)

    @cached_property
    def scaled_J(self) -> sp.Matrix:
        """J with each row times its :attr:`row_scale` (what the rules solve with)."""
        if all(s == 1 for s in self.row_scale):
            return self.J
        return self._rows(lambda t, s: t.unit_normal if s == 1 else t.normal)

    @cached_property
    def scaled_J_t(self) -> sp.Matrix:
        """J_t with each row times its :attr:`row_scale`."""
        if all(s == 1 for s in self.row_scale):
            return self.J_t
        return self._rows(lambda t, s: t.tangent if s == 1 else perp(t.normal))

    def _rows(self, direction_of) -> sp.Matrix:
        return jacobian(self.bodies, self.coordinates,
                        [(t.first, t.second, t.point, direction_of(t, s))
                         for t, s in zip(self.contacts, self.row_scale, strict=True)])

    @cached_property
    def M_inverse(self) -> sp.Matrix:
        """M^-1 (diagonal for free and pivoted bodies); with joints, the projected
        ``M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1``: the velocity change an impulse gives
        the bodies while every joint holds."""
        if not self.joints:
            return self._free_M_inverse
        exact = _in_field(self._free_M_inverse, self.G, self._joint_map)
        if exact:
            free, G, joint_map = exact
            return (free - free * G.transpose() * joint_map).to_Matrix()
        free = sp.Matrix(self._free_M_inverse)
        return (free - free * sp.Matrix(self.G).T * self._joint_map).applyfunc(tidy)

    def _product(self, J: sp.Matrix) -> sp.Matrix:
        if self.joints:  # J M^-1 J^T without the dense M^-1 (a chain of hundreds of rods)
            exact = _in_field(J, sp.Matrix(self.G), self._free_M_inverse)
            if exact:
                J, G, free = exact
                joined = G * free * J.transpose()  # the joints' opening by each row
                return (J * free * J.transpose() - joined.transpose()
                        * _joint_solve(G * free * G.transpose(), joined)).to_Matrix()
        return super()._product(J)

    def _moved_by(self, push: sp.Matrix) -> sp.Matrix:
        exact = self._joint_response(push) if self.joints else None  # the joints spread
        return exact[0].to_Matrix() if exact else self.M_inverse * push  # each impulse

    @cached_property
    def u_before(self) -> sp.Matrix:
        return sp.Matrix([c.before for c in self.coordinates])

    def _after(self, u: sp.Matrix) -> tuple[Body, ...]:
        """The bodies moving with `u`, tidied (a pivoted body's centre by its turn)."""
        after = moving(self.bodies, self.coordinates, [tidied(x) for x in u])
        return tuple(b if b.support != "pivot" else b.with_motion(
            b.velocity.applyfunc(tidied), b.spin) for b in after)

    def outcome(self, rule: str, order: Sequence[str], u: sp.Matrix,
                 impulses: dict[str, sp.Expr], acted: Sequence[str], passes: int = 1,
                 **more: Any) -> Solution:
        """The one :class:`Solution` a rule gives: the bodies moving with `u` after,
        certified (see :mod:`rigidimpact.solve.certificate`): a physical limit of the
        model here goes into its warnings; a broken condition is never an answer."""
        joined: dict[str, Any] = {"joints": self.joints, "joint_impulses":
                                  self._joint_impulses(impulses, more.get("tangential") or {})
                                  } if self.joints else {}
        return read_back(self.contacts, impulses, before=self.bodies, after=self._after(u),
                         rule=rule, order=order, acted=acted, passes=passes, **joined,
                         **more)

    @property
    def dense(self) -> bool:
        """Whether M^-1 is dense (joints couple the bodies' coordinates; a model source
        with a full mass matrix): then an impulse moves every coordinate through it."""
        return bool(self.joints)

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
        (``v_x^+_BODY``, ``v_y^+_BODY``, ``omega_z^+_BODY``), then each contact's normal
        and (with friction) tangential impulse (``P_n^CONTACT``, ``P_t^CONTACT``), then
        each joint's (``Q_x^JOINT``, ``Q_y^JOINT``): the names of
        :func:`~rigidimpact.symbolic.notation.labelled`."""
        speeds = [labelled(*COMPONENTS[c.kind][:2], c.body, after=True, real=True)
                  for c in self.coordinates]
        pushes = [labelled("P", "n", t.name, real=True) for t in self.contacts]
        if self.frictional:
            pushes += [labelled("P", "t", t.name, real=True) for t in self.contacts]
        pushes += [labelled("Q", axis, j.name, real=True) for j in self.joints
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
        >>> from rigidimpact.solve.collision import chain
        >>> c = chain(2)
        >>> [str(eq.as_sympy()) for eq in c.equations(c.simultaneous())][-1]
        'Eq(-v_x^+_ball0 + v_x^+_ball1, 1)'
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
        promised = conduct(outcome.rule)
        routh = promised.whole_impact and len(outcome.acted) == 1 and \
            self.frictional and self._by_name(outcome.acted[0]).laws[1].solved_by_regimes
        for k, t in enumerate(self.contacts):
            restitution, tangential = t.laws
            closing = (J[k, :] * u_after)[0]
            slip = (J_t[k, :] * u_after)[0]
            normal, along = outcome.impulses[t.name], outcome.tangential.get(t.name, 0)
            if not promised.whole_impact or routh:
                how = (f"{t.name} alone by its own {tangential.name} law (Routh's or "
                       "Walton's regimes)") if routh else promised.impulse_words.format(
                    name=t.name) if promised is not Conduct else \
                    f"{t.name}'s impulse by the {outcome.rule} rule"
                found.append(Equation(how, "", P_n[k], normal, law="rule"))
                if self.frictional:
                    found.append(Equation(how + ", tangential", "", P_t[k], along,
                                          law="rule"))
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
                    self.leaving(k, before) if closed else 0, law="restitution"))
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


def _in_field(*matrices: Any) -> tuple[Any, ...] | None:
    """The matrices as DomainMatrices over one field of numbers (the rationals, or with
    sqrt(3) adjoined), where sparse products and inverses are exact and fast; None
    where one holds a symbol or a sine (left to SymPy's matrices and `tidy`).

    Examples
    --------
    >>> a, b = _in_field(sp.Matrix([[1, 2]]), sp.Matrix([[sp.sqrt(3)], [1]]))
    >>> (a * b).to_Matrix()
    Matrix([[sqrt(3) + 2]])
    """
    if any(m.free_symbols or m.atoms(sp.sin, sp.cos, sp.tan) for m in matrices):
        return None
    from sympy.polys.constructor import construct_domain
    from sympy.polys.matrices import DomainMatrix

    # one field for every entry at once: fields made apart and unified cost a search
    # for an isomorphism between them (PSLQ), minutes for a few roots
    shaped = [sp.Matrix(m) for m in matrices]
    nonzero = [m.todok() for m in shaped]  # sparse: only the entries there are
    field, entries = construct_domain([x for d in nonzero for x in d.values()],
                                      extension=True)
    out, at = [], 0
    for m, d in zip(shaped, nonzero, strict=True):
        rows: dict[int, dict[int, Any]] = {}
        for (i, j), x in zip(d, entries[at:at + len(d)], strict=True):
            rows.setdefault(i, {})[j] = x
        at += len(d)
        out.append(DomainMatrix(rows, m.shape, field))
    return tuple(out)


def _joint_solve(S: Any, rhs: Any) -> Any:
    """``S^-1 rhs`` for the joints' S = G M^-1 G^T (a DomainMatrix over a field of
    numbers): one elimination, no inverse formed, dense (over the rationals in FLINT's
    compiled matrices, 0.1 s for a chain of 200 rods where SymPy's sparse LU, which
    goes dense in pure Python, took 8 s), the answer sparse again."""
    S = S.to_field()
    return S.to_dense().lu_solve(rhs.convert_to(S.domain).to_dense()).to_sparse()


def _full_rank(S: sp.Matrix) -> bool:
    """Whether the square matrix S (numbers) has full rank: exactly over the rationals by
    sparse elimination (a chain of 200 hinged rods is banded: instant, where SymPy's
    determinant took minutes), else its determinant at 30 digits.

    Examples
    --------
    >>> _full_rank(sp.Matrix([[1, 2], [2, 4]])), _full_rank(sp.eye(3))
    (False, True)
    """
    if all(x.is_Rational for x in S):
        from sympy.polys.matrices import DomainMatrix

        return DomainMatrix.from_Matrix(S).convert_to(sp.QQ).rank() == S.rows
    return abs(sp.N(S.det(), 30)) >= 1e-20


@dataclass(frozen=True)
class RowsProblem(ImpulseRows):
    """The one impulse problem given as rows: any source's generalized speeds, its
    inverse mass and, per contact, its normal row (and its tangent rows). A source of
    models (a 3-D collision, a sympy.physics.mechanics system) is one assembly function
    into this and one :meth:`outcome` back to its own :class:`Solution`, so every rule
    runs its one implementation on it.

    Parameters
    ----------
    contacts : each contact's laws (its name, restitution and tangential law).
    speeds : the generalized speeds' names.
    velocities : u before, one entry a speed.
    inverse_mass : M^-1 (projected where joints hold).
    normal_rows : J, one row a contact.
    tangent_rows : J_t, one row a contact, or None where every contact is smooth.
    second_tangent_rows : in space, each contact's second tangent row (t2 = n x t1).
    facets : Coulomb's cone as a pyramid of this many edges (None: the cone).
    tolerance : the relative tolerance a cone followed numerically is held to (None:
        the face's own).
    """

    contacts: tuple[Contact, ...]
    speeds: tuple[str, ...] = ()
    velocities: sp.ImmutableMatrix | None = None
    inverse_mass: sp.ImmutableMatrix | None = None
    normal_rows: sp.ImmutableMatrix | None = None
    tangent_rows: sp.ImmutableMatrix | None = None
    second_tangent_rows: sp.ImmutableMatrix | None = None  # in space: t2 = n x t1
    facets: int | None = None
    tolerance: float | None = None

    @property
    def tangents(self) -> int:
        return 0 if self.tangent_rows is None else 1 if self.second_tangent_rows is None \
            else 2

    def contact_rows(self, k: int) -> sp.Matrix:
        if self.second_tangent_rows is None:
            return super().contact_rows(k)
        return sp.Matrix([self.J.row(k), self.J_t.row(k), self.second_tangent_rows.row(k)])

    def frame_rows(self, k: int) -> Any:
        if self.second_tangent_rows is None:
            return super().frame_rows(k)
        import numpy as np

        return np.array(self.contact_rows(k).evalf(30), dtype=float)

    @cached_property
    def symbols(self) -> frozenset[sp.Symbol]:
        return frozenset(sp.Matrix(self.velocities).free_symbols
                         | sp.Matrix(self.inverse_mass).free_symbols
                         | sp.Matrix(self.normal_rows).free_symbols)

    @cached_property
    def coordinates(self) -> tuple[Coordinate, ...]:
        return tuple(Coordinate("system", name, 1, x)
                     for name, x in zip(self.speeds, self.u_before, strict=True))

    @cached_property
    def u_before(self) -> sp.Matrix:
        return sp.Matrix(self.velocities)

    @cached_property
    def row_scale(self) -> tuple[sp.Expr, ...]:
        return (sp.Integer(1),) * len(self.contacts)

    @cached_property
    def J(self) -> sp.Matrix:
        return sp.SparseMatrix(self.normal_rows)

    @cached_property
    def J_t(self) -> sp.Matrix:
        if self.tangent_rows is None:
            return sp.SparseMatrix.zeros(len(self.contacts), len(self.speeds))
        return sp.SparseMatrix(self.tangent_rows)

    @cached_property
    def scaled_J(self) -> sp.Matrix:
        return self.J

    @cached_property
    def scaled_J_t(self) -> sp.Matrix:
        return self.J_t

    @cached_property
    def M_inverse(self) -> sp.Matrix:
        return sp.Matrix(self.inverse_mass)
