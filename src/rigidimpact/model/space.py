"""Rigid bodies in three dimensions: a sphere, a rigid body with an inertia tensor and an
orientation, and a fixed body, at the instant of impact.

A :class:`Body3` holds its mass, its central inertia tensor in the world frame
(``R I_body R^T`` for a body turned by R), the position of its centre, its velocity and
its angular velocity ``spin = (wx, wy, wz)`` (world frame, right-handed). Its
generalized speeds are ``u = (vx, vy, vz, wx, wy, wz)`` and its mass matrix
``diag(m, m, m, I)``; the velocity of a point x of the body is ``v + spin x (x - c)``,
so the row that gives that point's velocity along a unit d is ``[d, (x - c) x d]``
(:meth:`Body3.row`).

Examples
--------
>>> ball = Body3.sphere(1, 1, position=(0, 0, 1), velocity=(1, 0, -2), spin=(0, 3, 0),
...                     name="ball")
>>> ball.inertia
Matrix([
[2/5,   0,   0],
[  0, 2/5,   0],
[  0,   0, 2/5]])
>>> ball.point_velocity((0, 0, 0)).T   # its lowest point: v + w x (0, 0, -1)
Matrix([[-2, 0, -2]])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.model.bodies import _expr, as_vector
from rigidimpact.symbolic.given import given_values

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["Body3", "as_vector3", "rotation", "SPEEDS"]

SPEEDS = ("vx", "vy", "vz", "omega_x", "omega_y", "omega_z")  # result keys BODY.<speed>


def as_vector3(value: Any, where: str) -> sp.ImmutableMatrix:
    """A 3-vector (column) of finite expressions.

    Examples
    --------
    >>> as_vector3((1, 2, 3), "v").T
    Matrix([[1, 2, 3]])
    """
    return as_vector(value, where, 3)


def rotation(axis: Sequence[Any], angle: Any) -> sp.ImmutableMatrix:
    """The rotation by `angle` (radians, right-handed) about `axis` (any nonzero length),
    by Rodrigues' formula.

    Examples
    --------
    >>> rotation((0, 0, 1), sp.pi / 2) * sp.Matrix([1, 0, 0])
    Matrix([
    [0],
    [1],
    [0]])
    """
    k = sp.Matrix(as_vector3(axis, "orientation.axis"))
    size = sp.sqrt(k.dot(k))
    if size.is_zero:
        raise InputError("orientation.axis", "must not be the zero vector")
    k = k / size
    angle = _expr(angle, "orientation.angle")
    K = sp.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    R = sp.eye(3) + sp.sin(angle) * K + (1 - sp.cos(angle)) * K * K
    # simplifying sines of a number (cos(pi/7)) takes seconds and gains nothing
    return sp.ImmutableMatrix(R if angle.is_number else R.applyfunc(sp.simplify))


def _exact_or_50_digits(x: sp.Expr) -> sp.Expr:
    """A number kept exact when rational, else to 50 digits (sines of numbers simplify
    slowly and gain nothing)."""
    return x if x.is_Rational or not x.has(sp.sin, sp.cos) else sp.N(x, 50)


def _orthonormal(R: sp.Matrix) -> bool:
    """Whether R is a proper rotation (exactly, or to 1e-25 when it holds sines)."""
    gap = R.T * R - sp.eye(3)
    if all(x.is_number for x in R):
        return max(abs(sp.N(x, 40)) for x in gap) < 1e-25 and sp.N(R.det(), 40) > 0
    return sp.simplify(gap) == sp.zeros(3) and sp.simplify(R.det() - 1) == 0


ASYMMETRY = 1e-12  # an inertia tensor's I_ij - I_ji taken as rounding, of its largest entry


@dataclass(frozen=True)
class Body3:
    """A rigid body in space at the instant of impact (see the module's text).

    Build one with :meth:`sphere`, :meth:`rigid` or :meth:`fixed`.
    """

    name: str
    mass: sp.Expr
    inertia: sp.ImmutableMatrix  # central, world frame
    position: sp.ImmutableMatrix
    velocity: sp.ImmutableMatrix
    spin: sp.ImmutableMatrix
    support: str = "free"  # or "fixed"
    radius: sp.Expr | None = None  # a sphere's
    inertia_inverse: sp.ImmutableMatrix | None = field(default=None, repr=False)
    turned: bool = field(default=False, repr=False)  # built with an orientation

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise InputError("bodies.name", f"must be an identifier, got {self.name!r}")
        if self.support == "fixed":
            return
        if self.mass.is_number and not self.mass > 0:
            raise InputError(f"{self.name}.mass", f"must be positive, got {self.mass}")
        inertia = self.inertia
        if inertia.shape != (3, 3):
            raise InputError(f"{self.name}.inertia", "must be a symmetric 3 x 3 tensor")
        gaps = [inertia[i, j] - inertia[j, i] for i in range(3) for j in range(i)]
        if all(x.is_number for x in inertia):
            # a tensor read from measured or computed floats: differences within
            # ASYMMETRY of its largest entry are rounding, and the mean of each pair is
            # taken; larger ones are refused
            largest = max(abs(float(x)) for x in inertia) or 1.0
            worst = max(abs(float(g)) for g in gaps)
            if worst > ASYMMETRY * largest:
                raise InputError(f"{self.name}.inertia", f"must be a symmetric 3 x 3 "
                                 f"tensor (I_ij and I_ji differ by up to {worst:.3g}; "
                                 f"differences within {ASYMMETRY:g} of the largest entry "
                                 "are taken as rounding)")
            if worst:
                inertia = sp.ImmutableMatrix(3, 3, lambda i, j: (inertia[i, j]
                                                                 + inertia[j, i]) / 2)
                object.__setattr__(self, "inertia", inertia)
        elif any(sp.simplify(g) != 0 for g in gaps):
            raise InputError(f"{self.name}.inertia", "must be a symmetric 3 x 3 tensor")
        if all(x.is_number for x in inertia):
            if any(x.has(sp.nan, sp.zoo, sp.oo, -sp.oo) for x in inertia):
                where = (f"{self.name}.orientation.axis", "is the zero vector at these "
                         "values: a turn needs an axis") if self.turned else \
                    (f"{self.name}.inertia", "is undefined at these values")
                raise InputError(*where)
            values = sorted(float(x) for x in np.linalg.eigvalsh(
                np.array(sp.Matrix(inertia).evalf(30), dtype=float)))
            if values[0] <= 0:
                raise InputError(f"{self.name}.inertia", "must be positive definite "
                                 f"(principal moments {', '.join(f'{x:.4g}' for x in values)})")
            a, b, c = values
            if c > a + b + 1e-12 * c:
                raise InputError(f"{self.name}.inertia", "its principal moments break the "
                                 f"triangle inequality ({a:.4g} + {b:.4g} < {c:.4g}): no "
                                 "rigid body has them")

    @classmethod
    def sphere(cls, mass: Any, radius: Any, position: Any = (0, 0, 0),
               velocity: Any = (0, 0, 0), spin: Any = (0, 0, 0), name: str = "sphere",
               inertia: Any = None) -> Body3:
        """A sphere; its central moment is ``2/5 m r^2`` (uniform) unless `inertia` gives
        it (``2/3 m r^2`` for a thin shell)."""
        m, r = _expr(mass, f"{name}.mass"), _expr(radius, f"{name}.radius")
        if r.is_number and not r > 0:
            raise InputError(f"{name}.radius", f"must be positive, got {r}")
        if inertia is not None and not isinstance(inertia, (int, float, sp.Expr)):
            raise InputError(f"{name}.inertia", "a sphere's inertia is its one central "
                             "moment (a number); a body with three moments is a rigid one")
        moment = sp.Rational(2, 5) * m * r**2 if inertia is None else \
            _expr(inertia, f"{name}.inertia")
        return cls(name, m, sp.ImmutableMatrix(sp.eye(3) * moment),
                   as_vector3(position, f"{name}.position"),
                   as_vector3(velocity, f"{name}.velocity"),
                   as_vector3(spin, f"{name}.spin"), radius=r)

    @classmethod
    def rigid(cls, mass: Any, inertia: Any, position: Any = (0, 0, 0),
              velocity: Any = (0, 0, 0), spin: Any = (0, 0, 0), orientation: Any = None,
              name: str = "body") -> Body3:
        """A rigid body whose central inertia tensor in its own axes is `inertia` (a
        3 x 3 matrix, or three principal moments), turned by `orientation` (a 3 x 3
        rotation, or ``(axis, angle)``) into the world frame."""
        if isinstance(inertia, sp.MatrixBase):
            tensor = sp.Matrix(inertia)
        else:
            items = list(inertia)
            if len(items) == 3 and not isinstance(items[0], (list, tuple)):
                tensor = sp.diag(*[_expr(x, f"{name}.inertia") for x in items])
            else:
                tensor = sp.Matrix(items)
        tensor = tensor.applyfunc(lambda x: _expr(x, f"{name}.inertia"))
        if tensor.shape != (3, 3):
            raise InputError(f"{name}.inertia", "three principal moments or a 3 x 3 tensor")
        if orientation is not None:
            R = sp.Matrix(orientation) if isinstance(orientation, sp.MatrixBase) else \
                rotation(*orientation)
            if R.shape != (3, 3) or not _orthonormal(R):
                raise InputError(f"{name}.orientation", "must be a rotation")
            inverse = None
            if tensor.is_diagonal() and all(x.is_number for x in tensor):
                inverse = R * sp.diag(*[1 / tensor[i, i] for i in range(3)]) * R.T
            tidy = _exact_or_50_digits if all(x.is_number for x in (*R, *tensor)) else sp.simplify
            tensor = (R * tensor * R.T).applyfunc(tidy)
            body = cls(name, _expr(mass, f"{name}.mass"), sp.ImmutableMatrix(tensor),
                       as_vector3(position, f"{name}.position"),
                       as_vector3(velocity, f"{name}.velocity"),
                       as_vector3(spin, f"{name}.spin"), turned=True)
            if inverse is not None:
                object.__setattr__(body, "inertia_inverse",
                                   sp.ImmutableMatrix(inverse.applyfunc(tidy)))
            return body
        return cls(name, _expr(mass, f"{name}.mass"), sp.ImmutableMatrix(tensor),
                   as_vector3(position, f"{name}.position"),
                   as_vector3(velocity, f"{name}.velocity"),
                   as_vector3(spin, f"{name}.spin"))

    @classmethod
    def fixed(cls, name: str = "ground") -> Body3:
        """A body that does not move (a floor, a wall, a cushion's support)."""
        zero = sp.ImmutableMatrix([0, 0, 0])
        return cls(name, sp.Integer(0), sp.ImmutableMatrix(sp.zeros(3)), zero, zero, zero,
                   support="fixed")

    @property
    def speeds(self) -> sp.ImmutableMatrix:
        """``u = (vx, vy, vz, wx, wy, wz)``."""
        return sp.ImmutableMatrix([*self.velocity, *self.spin])

    def point_velocity(self, point: Any) -> sp.Matrix:
        """The velocity of the body's point at `point` (world frame)."""
        arm = sp.Matrix(as_vector3(point, "point")) - sp.Matrix(self.position)
        return sp.Matrix(self.velocity) + sp.Matrix(self.spin).cross(arm)

    def row(self, point: Any, direction: sp.Matrix) -> sp.Matrix:
        """The 1 x 6 row taking u to the velocity of `point` along `direction`."""
        arm = sp.Matrix(as_vector3(point, "point")) - sp.Matrix(self.position)
        return sp.Matrix([[*direction, *arm.cross(direction)]])

    def mass_inverse(self) -> sp.Matrix:
        """``diag(1/m, 1/m, 1/m, I^-1)`` (6 x 6); a turned body's ``I^-1`` is
        ``R diag(1/I1, 1/I2, 1/I3) R^T``, formed when it was built."""
        inverse = self.inertia_inverse if self.inertia_inverse is not None else \
            sp.Matrix(self.inertia).inv()
        return sp.diag(*([1 / self.mass] * 3), sp.Matrix(inverse))

    def moved(self, u: Sequence[Any]) -> Body3:
        """The body with speeds u."""
        u = list(u)
        return replace(self, velocity=sp.ImmutableMatrix(u[:3]),
                       spin=sp.ImmutableMatrix(u[3:]))

    @property
    def kinetic_energy(self) -> sp.Expr:
        if self.support == "fixed":
            return sp.Integer(0)
        v, w = sp.Matrix(self.velocity), sp.Matrix(self.spin)
        return (self.mass * v.dot(v) + (w.T * sp.Matrix(self.inertia) * w)[0]) / 2

    def at(self, values: Mapping[sp.Basic, Any]) -> Body3:
        """The body with numbers put in for its symbols: Python or SymPy numbers (or
        expressions), each checked (:func:`~rigidimpact.symbolic.given.given_values`).

        Examples
        --------
        >>> m = sp.Symbol("m", positive=True)
        >>> Body3.sphere(m, 1, name="ball").at({m: 2}).mass
        2
        """
        values = given_values(values)
        if self.support == "fixed":
            return self

        def put(x: Any) -> Any:
            return x.xreplace(values) if isinstance(x, (sp.Basic, sp.MatrixBase)) else x
        return replace(self, mass=put(self.mass), inertia=put(self.inertia),
                       position=put(self.position), velocity=put(self.velocity),
                       spin=put(self.spin), radius=put(self.radius),
                       inertia_inverse=put(self.inertia_inverse))
