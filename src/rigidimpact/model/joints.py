"""Joints: two bodies pinned together at a point by a frictionless hinge.

A joint keeps the two bodies' material points at its `point` moving together, so during
an impact it passes an impulse between them (two components, any sign) and after it
they still move together there. A body's ``pivot`` is the same hinge to the world.

The impulse problem carries each joint as two bilateral rows, ``G u = 0`` (the velocity
of the second body's point less the first's, along x and along y); their impulses are
eliminated by the projected inverse mass
``M^-1 - M^-1 G^T (G M^-1 G^T)^-1 G M^-1``, so every rule that works with ``M^-1`` and
the contact rows works unchanged with joints (see
:class:`~rigidimpact.solve.collision.Collision`).

Examples
--------
>>> Joint("knee", ("upper", "lower"), (0, -1))
Joint(name='knee', bodies=('upper', 'lower'), point=Matrix([
[ 0],
[-1]]), axis=None)
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model.bodies import Body, as_vector
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Joint", "off_body"]


@dataclass(frozen=True)
class Joint:
    """A frictionless hinge pinning `bodies` (first, second) together at `point` (from
    the scene's origin O). Its impulse is the one it gives the second body (the first
    receives its opposite).

    In space (a `point` of three components) it is a ball joint: the two material
    points move together (three bilateral rows); with an `axis` it is a hinge about
    that axis, which also keeps the two bodies from turning relative to each other
    about the two directions across it (two more rows, whose impulses are moments). A
    joint to a fixed body pivots the other in space."""

    name: str
    bodies: tuple[str, str]
    point: Any
    axis: Any = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise InputError("joints.name", f"must be an identifier, got {self.name!r}")
        if not (isinstance(self.bodies, (tuple, list)) and len(self.bodies) == 2 and
                all(isinstance(b, str) for b in self.bodies)):
            raise InputError(f"{self.name}.bodies", "must name two bodies, such as "
                             f"[\"upper\", \"lower\"], not {self.bodies!r}")
        if self.bodies[0] == self.bodies[1]:
            raise InputError(f"{self.name}.bodies", "a joint pins two different bodies")
        object.__setattr__(self, "bodies", tuple(self.bodies))
        spatial = isinstance(self.point, (list, tuple, sp.MatrixBase)) and \
            len(list(self.point)) == 3
        object.__setattr__(self, "point", as_vector(self.point, f"{self.name}.point",
                                                    3 if spatial else 2))
        if self.axis is not None:
            if not spatial:
                raise InputError(f"{self.name}.axis", "an axis is for a hinge in space (a "
                                 "point with three components); in the plane every joint "
                                 "turns about z")
            axis = as_vector(self.axis, f"{self.name}.axis", 3)
            if all(x.is_zero for x in axis):
                raise InputError(f"{self.name}.axis", "must not be the zero vector")
            object.__setattr__(self, "axis", axis)

    @property
    def spatial(self) -> bool:
        """Whether the joint is in space (a ball joint or a hinge about an axis)."""
        return len(self.point) == 3

    @property
    def first(self) -> str:
        return self.bodies[0]

    @property
    def second(self) -> str:
        return self.bodies[1]

    def at(self, values: dict) -> Joint:
        """The joint with numbers put in for its symbols."""
        axis = None if self.axis is None else sp.ImmutableMatrix(self.axis).xreplace(values)
        return replace(self, point=sp.ImmutableMatrix(self.point).xreplace(values),
                       axis=axis)


def off_body(body: Body, point: sp.MatrixBase) -> str | None:
    """Why `point` is not on `body`, in words, or None where it is (or where the body's
    shape says nothing of its extent: a fixed body, a rigid body given by its inertia).
    Undecided with symbols: None.

    Examples
    --------
    >>> rod = Body.rod(1, 2, 0, 0, name="rod")
    >>> off_body(rod, sp.Matrix([1, 0])) is None, off_body(rod, sp.Matrix([3, 0]))
    (True, 'it is 3 from the centre of a rod of half length 1')
    """
    dims = dict(body.dimensions)
    if body.support == "fixed" or not (body.inertia.is_zero or body.shape == "rod" or
                                       "radius" in dims):
        return None  # nothing says where the body's extent ends
    offset = sp.Matrix(point) - sp.Matrix(body.position)

    def false(x: sp.Expr) -> bool:  # decidedly false, not merely undecided
        return sp.sympify(x) is sp.false

    if body.inertia.is_zero:
        gap = [tidy(c) for c in offset]
        if any(c.is_zero is False for c in gap):
            return (f"a point mass is at ({body.position[0]}, {body.position[1]}), not at "
                    f"({point[0]}, {point[1]})")
        return None
    if body.shape == "rod":
        along = sp.Matrix([sp.cos(dims["angle"]), sp.sin(dims["angle"])])
        across = tidy(offset[0] * along[1] - offset[1] * along[0])
        distance = tidy(offset.dot(along))
        half = dims["length"] / 2
        if across.is_zero is False:
            return f"it is {across} off the line of the rod"
        if false(sp.Le(sp.Abs(distance), half)):
            return f"it is {sp.Abs(distance)} from the centre of a rod of half length {half}"
        return None
    if "radius" in dims:
        reach, limit = offset.dot(offset), dims["radius"] ** 2
        if reach.is_Rational and limit.is_Rational:  # at numbers (a thousand balls)
            beyond = bool(reach > limit)
        else:
            reach = tidy(reach)
            beyond = false(sp.Le(reach, limit))
        if beyond:
            return f"it is {sp.sqrt(reach)} from the centre, past the radius {dims['radius']}"
    return None
