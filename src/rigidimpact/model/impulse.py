"""The generalized-impulse core: velocities u, mass matrix M, Jacobian J, W = J M^-1 J^T.

Every impact is solved here, from the paper's two free bodies to a pivoted rod striking
a wall. Each movable body contributes generalized velocities u: a free body its centre's
velocity and its spin (no spin for a point mass), a body on a pivot its spin alone (the
pivot's two bilateral rows are reduced away, its mass matrix entry is the inertia about
the pivot), a fixed body nothing. The contact's Jacobian J maps u to the relative
velocity of the touching points, second minus first, in the contact frame (normal,
tangent):

    v = J u,   u+ = u- + M^-1 J^T P,   v+ = v- + W P,   W = J M^-1 J^T,

with P the impulse the first body gives the second. The contact laws (see
:mod:`rigidimpact.laws.law`) are conditions on v+ and P; a smooth or sticking contact gives
linear ones. A pivot's reaction impulse is what the body's momentum change needs beyond
the contact impulse. The energy lost is the work of the impulse, ``-P . (v- + v+)/2``.

Examples
--------
>>> from rigidimpact.model.bodies import Body
>>> core = TouchingPair((Body.particle(1, (2, 0), "a"), Body.particle(3, name="b")))
>>> core.W
Matrix([
[4/3,   0],
[  0, 4/3]])
>>> core.velocity_before.T
Matrix([[-2, 0]])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import sympy as sp

from rigidimpact.model.bodies import Body
from rigidimpact.symbolic.geometry import cross, spin_cross

__all__ = ["TouchingPair", "Coordinate", "coordinates_of", "jacobian", "moving",
           "kinetic_energy"]


@dataclass(frozen=True)
class Coordinate:
    """One generalized velocity: which body, what it is (``vx``, ``vy``, ``omega``), its
    mass-matrix entry and its value before.

    Examples
    --------
    >>> Coordinate("ball", "vx", 2, 5)
    Coordinate(body='ball', kind='vx', inertia=2, before=5)
    """

    body: str
    kind: str
    inertia: sp.Expr
    before: sp.Expr


def coordinates_of(bodies: Sequence[Body]) -> tuple[Coordinate, ...]:
    """The generalized velocities of some bodies: a free body's centre velocity and spin
    (no spin for a point mass), a pivoted body's spin (its inertia about the pivot), a
    fixed body none.

    Examples
    --------
    >>> [c.kind for c in coordinates_of([Body.particle(1), Body.fixed()])]
    ['vx', 'vy']
    """
    found: list[Coordinate] = []
    for body in bodies:
        if body.support == "pivot":
            found.append(Coordinate(body.name, "omega", body.inertia_about_pivot, body.spin))
        elif body.support == "free":
            found += [Coordinate(body.name, "vx", body.mass, body.velocity[0]),
                      Coordinate(body.name, "vy", body.mass, body.velocity[1])]
            if not body.inertia.is_zero:
                found.append(Coordinate(body.name, "omega", body.inertia, body.spin))
    return tuple(found)


def jacobian(bodies: Sequence[Body], coordinates: Sequence[Coordinate],
             rows: Sequence[tuple[str, str, sp.MatrixBase, sp.MatrixBase]]) -> sp.SparseMatrix:
    """The Jacobian rows of contacts: for each ``(first, second, point, direction)``, the
    velocity of the touching points at `point` (second minus first) along `direction`, as
    a function of the generalized velocities u. Sparse: a row touches only its two
    bodies' coordinates. A unit spin moves the point, seen from the body's axis (its
    pivot, or its centre), by ``z x (point - axis)``, whose part along d is
    ``(point - axis) x d``.

    Examples
    --------
    >>> a, b = Body.particle(1, (1, 0), "a"), Body.rigid(2, 1, (0, 1), name="b")
    >>> coordinates = coordinates_of((a, b))
    >>> jacobian((a, b), coordinates, [("a", "b", sp.Matrix([0, 0]), sp.Matrix([1, 0]))])
    Matrix([[-1, 0, 1, 0, 1]])
    """
    by_name = {b.name: b for b in bodies}
    columns: dict[str, list[tuple[int, Coordinate]]] = {}
    for j, coordinate in enumerate(coordinates):
        columns.setdefault(coordinate.body, []).append((j, coordinate))
    entries: dict[tuple[int, int], sp.Expr] = {}
    for i, (first, second, point, direction) in enumerate(rows):
        for name, sign in ((first, -1), (second, 1)):
            for j, coordinate in columns.get(name, ()):
                if coordinate.kind == "vx":
                    value = direction[0]
                elif coordinate.kind == "vy":
                    value = direction[1]
                else:
                    body = by_name[name]
                    axis = body.pivot if body.support == "pivot" else body.position
                    value = cross(point - axis, direction)
                entries[i, j] = entries.get((i, j), 0) + sign * value
    return sp.SparseMatrix(len(rows), len(coordinates),
                           {k: v for k, v in entries.items() if v != 0})


def moving(bodies: Sequence[Body], coordinates: Sequence[Coordinate],
           u: Sequence[sp.Expr]) -> tuple[Body, ...]:
    """The bodies moving with generalized velocities `u` (a pivoted body's centre by its
    turn about the pivot; a fixed body as it is).

    Examples
    --------
    >>> ball = Body.particle(1, name="b")
    >>> moving([ball], coordinates_of([ball]), [3, 0])[0].velocity.T
    Matrix([[3, 0]])
    """
    values = {(c.body, c.kind): x for c, x in zip(coordinates, u, strict=True)}
    after = []
    for body in bodies:
        if body.support == "fixed":
            after.append(body)
            continue
        spin = values.get((body.name, "omega"), body.spin)
        if body.support == "pivot":
            after.append(body.with_motion(spin_cross(spin, body.position - body.pivot), spin))
        else:
            after.append(body.with_motion((values[(body.name, "vx")],
                                           values[(body.name, "vy")]), spin))
    return tuple(after)


@dataclass(frozen=True)
class TouchingPair:
    """Two bodies touching at O in the contact frame (x along the normal).

    Parameters
    ----------
    bodies : pair of Body
        In the contact frame; the first is on the -x side of O.

    Examples
    --------
    >>> from rigidimpact.model.bodies import Body
    >>> rod = Body.rod(3, 2, sp.pi / 2, -1, pivot=(0, -2), name="rod")
    >>> core = TouchingPair((Body.particle(1, (1, 0), "ball"), rod))
    >>> [(c.body, c.kind, c.inertia) for c in core.coordinates]
    [('ball', 'vx', 1), ('ball', 'vy', 1), ('rod', 'omega', 4)]
    >>> core.W[0, 0]  # 1/m + (lever arm)^2 / I_pivot
    2
    """

    bodies: tuple[Body, Body]

    @cached_property
    def coordinates(self) -> tuple[Coordinate, ...]:
        """The generalized velocities, body by body."""
        return coordinates_of(self.bodies)

    @cached_property
    def J(self) -> sp.ImmutableMatrix:
        """Rows: the normal and tangential relative velocity of the touching points at O
        (second minus first); columns: the coordinates (:func:`jacobian`, as for any
        number of contacts)."""
        first, second = (b.name for b in self.bodies)
        origin = sp.ImmutableMatrix([0, 0])
        rows = jacobian(self.bodies, self.coordinates,
                        [(first, second, origin, sp.ImmutableMatrix([1, 0])),
                         (first, second, origin, sp.ImmutableMatrix([0, 1]))])
        return sp.ImmutableMatrix(rows) if self.coordinates else sp.ImmutableMatrix(2, 0, [])

    @cached_property
    def M_inverse(self) -> sp.ImmutableMatrix:
        """The inverse mass matrix (diagonal in these coordinates)."""
        return sp.ImmutableMatrix(sp.diag(*[1 / c.inertia for c in self.coordinates]))

    @cached_property
    def W(self) -> sp.ImmutableMatrix:
        """``J M^-1 J^T``: how an impulse at O changes the relative contact velocity."""
        if not self.coordinates:
            return sp.ImmutableMatrix.zeros(2, 2)
        return sp.ImmutableMatrix((self.J * self.M_inverse * self.J.T).applyfunc(sp.cancel))

    @cached_property
    def velocity_before(self) -> sp.ImmutableMatrix:
        """The relative velocity of the touching points before, ``J u-``."""
        u = sp.Matrix([c.before for c in self.coordinates])
        return sp.ImmutableMatrix(self.J * u) if self.coordinates else sp.ImmutableMatrix([0, 0])

    def velocity_after(self, impulse: Sequence[sp.Expr]) -> sp.ImmutableMatrix:
        """``v- + W P``.

        Examples
        --------
        >>> from rigidimpact.model.bodies import Body
        >>> core = TouchingPair((Body.particle(1, (2, 0), "a"), Body.particle(1, name="b")))
        >>> core.velocity_after((2, 0)).T
        Matrix([[2, 0]])
        """
        return sp.ImmutableMatrix(self.velocity_before + self.W * sp.Matrix(impulse))

    def bodies_after(self, impulse: Sequence[sp.Expr]) -> tuple[Body, Body]:
        """Both bodies after receiving the impulse P at O (the first gets -P).

        ``u+ = u- + M^-1 J^T P``, read back body by body: a pivoted body's centre moves by
        its turn about the pivot.
        """
        change = self.M_inverse * self.J.T * sp.Matrix(impulse)
        u = [c.before + change[k] for k, c in enumerate(self.coordinates)]
        after = moving(self.bodies, self.coordinates, u)
        return after[0], after[1]

    @staticmethod
    def work(impulse: Sequence[sp.Expr], before: sp.MatrixBase,
             after: sp.MatrixBase) -> sp.Expr:
        """The kinetic energy an impulse gives the pair: ``P . (v- + v+) / 2``.

        Examples
        --------
        >>> TouchingPair.work((2, 0), sp.Matrix([-2, 0]), sp.Matrix([2, 0]))
        0
        """
        return sp.Matrix(impulse).dot(sp.Matrix(before) + sp.Matrix(after)) / 2


def kinetic_energy(M: Any, u: Any) -> sp.Expr:
    """``u^T M u / 2``: the kinetic energy at generalized speeds u of a system whose
    mass matrix is M (the one formula a system's energies before, after and lost are
    taken from).

    Examples
    --------
    >>> kinetic_energy(sp.diag(2, 3), sp.Matrix([1, 2]))
    7
    """
    u = sp.Matrix(u)
    return (u.T * sp.Matrix(M) * u)[0] / 2

