"""The shapes a scene may name, each a small class in this one place.

A shape says which scene fields it takes (and which it needs), whether it can spin, how
its fields make a :class:`~rigidimpact.model.bodies.Body`, and what the event search and the
compliant models need to know of its outline (``round``: it touches along the normal at
its radius; ``segment``: a straight bar with two ends). A new shape is one subclass here,
listed in :data:`SHAPES`, and its test.

Examples
--------
>>> sorted(SHAPES)
['barbell', 'disc', 'fixed', 'particle', 'rigid', 'ring', 'rod', 'sphere']
>>> SHAPES["disc"].required, SHAPES["disc"].round
(('mass', 'radius'), True)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any, ClassVar

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model.bodies import Body
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Shape", "Fields", "SHAPES", "is_round", "is_segment"]


@dataclass(frozen=True)
class Fields:
    """What a shape reads its body from: the scene table and how to read its values.

    Parameters
    ----------
    table : mapping
        The ``[[bodies]]`` entry as read from TOML.
    expr, vector : callables
        Read one field as an expression, or as a 2-vector, naming the field on error.
    name, velocity, spin :
        The body's name and motion (already read).
    outward : 2-vector
        The unit vector from O toward where a round body's centre goes when the table
        gives no position (along the normal, to the body's own side).

    O is the point of the first contact that names the body: the scene reader gives
    every position from there and moves the body back to the scene's origin after.
    """

    table: Mapping[str, Any]
    expr: Callable[[str], sp.Expr]
    vector: Callable[[str], tuple]
    name: str
    velocity: tuple
    spin: sp.Expr
    outward: sp.MatrixBase
    contact: str = "contact"  # the name of the first contact that names the body


class Shape:
    """A kind of body: its scene fields, how they make a body, its outline's features."""

    name: ClassVar[str]
    fields: ClassVar[tuple[str, ...]]  # beyond name, shape, velocity, spin and pivot
    required: ClassVar[tuple[str, ...]]
    spins: ClassVar[bool] = True  # takes a `spin` field
    moves: ClassVar[bool] = True  # takes `velocity` and `pivot`
    round: ClassVar[bool] = False
    segment: ClassVar[bool] = False

    @classmethod
    def build(cls, given: Fields) -> Body:
        raise NotImplementedError


class Particle(Shape):
    """A point mass at O; it has no spin an impact could change or use."""

    name, fields, required, spins = "particle", ("mass", "position"), ("mass",), False

    @classmethod
    def build(cls, given: Fields) -> Body:
        body = Body.particle(given.expr("mass"), given.velocity, given.name)
        if "position" not in given.table:  # at O, its contact point
            return body
        return replace(body, position=given.vector("position"))


class Barbell(Shape):
    """Two equal point masses on a massless rod, one of them (``struck``) at O."""

    name, segment = "barbell", True
    fields = ("mass", "half_length", "angle", "struck")
    required = ("mass", "half_length", "angle")

    @classmethod
    def build(cls, given: Fields) -> Body:
        return Body.barbell(given.expr("mass"), given.expr("half_length"),
                            given.expr("angle"), given.velocity, given.spin, given.name,
                            given.table.get("struck", "A"))


class Rod(Shape):
    """A uniform thin rod struck at ``struck_at`` from its centre, or with its centre at
    ``position`` (from O: a rod of a linkage that no contact places)."""

    name, segment = "rod", True
    fields = ("mass", "length", "angle", "struck_at", "position")
    required = ("mass", "length", "angle")

    @classmethod
    def build(cls, given: Fields) -> Body:
        placed = [k for k in ("struck_at", "position") if k in given.table]
        if len(placed) != 1:
            raise InputError(f"{given.name}.struck_at", "give a rod exactly one of "
                             "struck_at (its centre from the contact point, along the rod) "
                             "and position (its centre from O)")
        if placed == ["struck_at"]:
            return Body.rod(given.expr("mass"), given.expr("length"), given.expr("angle"),
                            given.expr("struck_at"), given.velocity, given.spin, given.name)
        body = Body.rod(given.expr("mass"), given.expr("length"), given.expr("angle"), 0,
                        given.velocity, given.spin, given.name)
        return replace(body, position=sp.ImmutableMatrix(given.vector("position")))


class Rigid(Shape):
    """Any body given by its mass, central inertia and centre."""

    name = "rigid"
    fields = required = ("mass", "inertia", "position")

    @classmethod
    def build(cls, given: Fields) -> Body:
        return Body.rigid(given.expr("mass"), given.expr("inertia"), given.vector("position"),
                          given.velocity, given.spin, given.name)


class _Round(Shape):
    """A body that touches along the normal at its radius."""

    fields, required, round = ("mass", "radius", "position"), ("mass", "radius"), True
    factor: ClassVar[sp.Expr]  # central inertia over m r^2

    @classmethod
    def build(cls, given: Fields) -> Body:
        radius = given.expr("radius")
        if "position" in given.table:
            position = given.vector("position")
            off = tidy(position[0] ** 2 + position[1] ** 2 - radius**2)
            if off.is_zero is False:
                raise InputError("position", f"the centre must lie at the radius {radius} "
                                 f"from the point of contact {given.contact}, but it is at "
                                 f"({position[0]}, {position[1]}) from that point")
        else:
            position = tuple(radius * given.outward)
        maker = getattr(Body, cls.name)
        return maker(given.expr("mass"), radius, position, 1, given.velocity, given.spin,
                     given.name)


class Disc(_Round):
    """A uniform disc (central inertia m r^2 / 2)."""

    name, factor = "disc", sp.Rational(1, 2)


class Ring(_Round):
    """A thin ring (central inertia m r^2)."""

    name, factor = "ring", sp.Integer(1)


class Sphere(_Round):
    """A uniform solid sphere moving in the plane (central inertia 2 m r^2 / 5)."""

    name, factor = "sphere", sp.Rational(2, 5)


class Fixed(Shape):
    """An immovable partner: a wall, a floor, a nail."""

    name, fields, required, spins, moves = "fixed", (), (), False, False

    @classmethod
    def build(cls, given: Fields) -> Body:
        return Body.fixed(given.name)


SHAPES: dict[str, type[Shape]] = {
    s.name: s for s in (Particle, Barbell, Rod, Disc, Ring, Sphere, Rigid, Fixed)}


def is_round(shape: str) -> bool:
    """Whether a body of this shape touches along the normal at its radius.

    Examples
    --------
    >>> is_round("ring"), is_round("rod")
    (True, False)
    """
    return shape in SHAPES and SHAPES[shape].round


def is_segment(shape: str) -> bool:
    """Whether a body of this shape is a straight bar with two ends.

    Examples
    --------
    >>> is_segment("barbell"), is_segment("disc")
    (True, False)
    """
    return shape in SHAPES and SHAPES[shape].segment
