"""Rigid-body primitives in planar motion, placed relative to the contact point O.

A :class:`Body` holds what an impulsive collision needs: mass, central moment of
inertia, the position ``R`` of its centre of mass relative to O, and the velocity of
its centre and its spin (counter-clockwise positive) at one instant. Positions are
those at the instant of impact: the impulse acts before anything has moved.

Examples
--------
>>> from rigidimpact.symbolic.notation import symbol
>>> m, M, L, theta = (symbol(n) for n in ("m", "M", "L", "theta"))
>>> ball = Body.particle(m, velocity=(symbol("v_ix"), 0), name="ball")
>>> bar = Body.barbell(M, L, theta)
>>> bar.mass, bar.inertia
(2*M, 2*L**2*M)
>>> bar.position.T
Matrix([[L*cos(theta), L*sin(theta)]])
>>> join(ball, bar).mass
2*M + m
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.symbolic.geometry import cross, spin_cross
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Body", "join", "cross", "spin_cross", "as_vector"]



def _expr(value: Any, where: str) -> sp.Expr:
    """A finite SymPy expression from a number or expression (never from a string)."""
    if isinstance(value, str):
        raise InputError(where, "expected a number or SymPy expression, not text")
    try:
        expr = sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError) as exc:
        raise InputError(where, f"not a number or expression: {value!r}") from exc
    if not isinstance(expr, sp.Expr):
        raise InputError(where, f"not a scalar expression: {value!r}")
    if expr.has(sp.nan) or expr.has(sp.zoo) or expr.has(sp.oo) or expr.has(-sp.oo):
        raise InputError(where, f"must be finite, got {expr}")
    # asking a large formula whether it is real can take minutes: ask numbers only
    if expr.has(sp.I) or (expr.is_number and expr.is_real is False):
        raise InputError(where, f"must be real, got {expr}")
    return expr


def as_vector(value: Any, where: str, size: int = 2) -> sp.ImmutableMatrix:
    """A vector (column) of `size` finite expressions: 2 in the plane, 3 in space.

    Examples
    --------
    >>> as_vector((1, 2), "v").T
    Matrix([[1, 2]])
    """
    words = {2: "two components [x, y]", 3: "three components [x, y, z]"}[size]
    if isinstance(value, sp.MatrixBase):
        items = list(value)
    elif isinstance(value, Sequence) and not isinstance(value, str):
        items = list(value)
    else:
        raise InputError(where, f"expected {words}, got {value!r}")
    if len(items) != size:
        raise InputError(where, f"expected {words}, got {len(items)}")
    return sp.ImmutableMatrix([_expr(c, f"{where}[{i}]") for i, c in enumerate(items)])


def _difference(v: sp.Expr, w: sp.Expr) -> sp.Expr:
    """``v - w`` tidied; over the cases of a ``Piecewise`` (a frictional impact's
    courses), case by case."""
    difference = sp.piecewise_fold(v - w) if v.has(sp.Piecewise) or w.has(sp.Piecewise) \
        else v - w
    if isinstance(difference, sp.Piecewise):
        if all(tidy(piece).is_zero for piece, _ in difference.args):
            return sp.Integer(0)
        return difference
    return tidy(difference)


def _negligible(difference: sp.Expr, *scale: sp.Expr) -> bool:
    """Zero, or (in 50-digit numeric mode) a rounding's worth of the values compared."""
    if difference == 0:
        return True
    if not difference.is_number or not all(x.is_number for x in scale):
        return False
    return bool(abs(difference) <= sp.Float(1e-40) * (1 + sum(abs(x) for x in scale)))


def _short(expr: Any, width: int = 60) -> str:
    """An expression for a message: whole when short, else cut with an ellipsis."""
    text = str(expr)
    return text if len(text) <= width else text[:width - 3] + "..."


def _must_be_positive(value: sp.Expr, where: str) -> sp.Expr:
    if value.is_positive is False:
        raise InputError(where, f"must be positive, got {value}")
    return value


def _must_be_nonnegative(value: sp.Expr, where: str) -> sp.Expr:
    if value.is_nonnegative is False:
        raise InputError(where, f"must not be negative, got {value}")
    return value


@dataclass(frozen=True)
class Part:
    """A point mass that a body is built of (the spheres of a barbell).

    Examples
    --------
    >>> Part("A", 1, sp.ImmutableMatrix([0, 0])).label
    'A'
    """

    label: str
    mass: sp.Expr
    position: sp.ImmutableMatrix


@dataclass(frozen=True)
class Body:
    """A rigid body at the instant of impact.

    Parameters
    ----------
    name : str
        Used in result keys (``ball.vx``) and messages.
    mass : sympy.Expr
        Total mass, positive.
    inertia : sympy.Expr
        Moment of inertia about the centre of mass (zero for a particle).
    position : 2-vector
        Centre of mass relative to the contact point O.
    velocity : 2-vector
        Velocity of the centre of mass.
    spin : sympy.Expr
        Angular velocity about z, counter-clockwise positive.
    shape : str
        The shape's name (:data:`rigidimpact.model.shapes.SHAPES` lists those a scene may
        use); ``"fixed"`` marks an immovable body.
    dimensions : tuple of (str, expr)
        The sizes the shape was built from, for display and simulation.
    parts : tuple of Part
        Point masses for bodies made of them (barbell, particle).
    pivot : 2-vector or None
        A frictionless hinge fixed in the world at this point (relative to O): the body
        can only turn about it, and its velocity must be that of such a turn.

    Examples
    --------
    >>> Body("lump", 2, 0, (0, 0))
    Body(name='lump', mass=2, inertia=0, position=(0, 0), velocity=(0, 0), spin=0, shape='rigid')
    """

    name: str
    mass: Any
    inertia: Any
    position: Any
    velocity: Any = (0, 0)
    spin: Any = 0
    shape: str = "rigid"
    dimensions: tuple[tuple[str, Any], ...] = ()
    parts: tuple[Part, ...] = field(default=(), repr=False)
    pivot: Any = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise InputError("name", f"must be an identifier, got {self.name!r}")
        if not isinstance(self.shape, str) or not self.shape.isidentifier():
            raise InputError(f"{self.name}.shape", f"must be a shape's name (see "
                             f"rigidimpact.model.shapes), got {self.shape!r}")
        fix = object.__setattr__
        fix(self, "mass", _must_be_positive(_expr(self.mass, f"{self.name}.mass"),
                                            f"{self.name}.mass"))
        fix(self, "inertia", _must_be_nonnegative(_expr(self.inertia, f"{self.name}.inertia"),
                                                  f"{self.name}.inertia"))
        fix(self, "position", as_vector(self.position, f"{self.name}.position"))
        fix(self, "velocity", as_vector(self.velocity, f"{self.name}.velocity"))
        fix(self, "spin", _expr(self.spin, f"{self.name}.spin"))
        fix(self, "dimensions", tuple((k, _expr(v, f"{self.name}.{k}"))
                                      for k, v in self.dimensions))
        if self.pivot is not None:
            self._check_pivot()

    def _check_pivot(self) -> None:
        if self.shape == "fixed":
            raise InputError(f"{self.name}.pivot", "a fixed body cannot also have a pivot")
        pivot = as_vector(self.pivot, f"{self.name}.pivot")
        object.__setattr__(self, "pivot", pivot)
        if self.inertia_about_pivot.is_zero:
            raise InputError(f"{self.name}.pivot", "a point mass pivoted at its own place "
                             "cannot move: put the pivot elsewhere or make the body fixed")
        offset = self.position - pivot
        if sp.sympify(self.spin).is_zero and not all(v.is_zero for v in self.velocity):
            # no spin given but a velocity: the turn about the pivot that gives it (a
            # pendulum bob has no spin of its own; its swing rate is this)
            spin = tidy((offset[0] * self.velocity[1] - offset[1] * self.velocity[0])
                        / (offset[0] ** 2 + offset[1] ** 2))
            object.__setattr__(self, "spin", spin)
        expected = spin_cross(self.spin, offset)
        for axis, (v, w) in enumerate(zip(self.velocity, expected, strict=True)):
            if v != w and not _negligible(_difference(v, w), v, w):  # shown consistent
                raise InputError(f"{self.name}.velocity", f"a pivoted body moves only by "
                                 f"turning about its pivot: with spin {_short(self.spin)} "
                                 f"its centre's velocity must be ({_short(expected[0])}, "
                                 f"{_short(expected[1])}), got {_short(v)} in component "
                                 f"{axis}; leave velocity out to have it from the spin")

    @property
    def support(self) -> str:
        """``"free"``, ``"pivot"`` (a hinge fixed in the world) or ``"fixed"``.

        Examples
        --------
        >>> Body.fixed("wall").support, Body.particle(1).support
        ('fixed', 'free')
        """
        if self.shape == "fixed":
            return "fixed"
        return "free" if self.pivot is None else "pivot"

    @property
    def inertia_about_pivot(self) -> sp.Expr:
        """Moment of inertia about the pivot (parallel-axis theorem).

        Examples
        --------
        >>> Body.rod(3, 2, 0, 1, pivot=(2, 0)).inertia_about_pivot
        4
        """
        offset = self.position - self.pivot
        return tidy(self.inertia + self.mass * (offset[0] ** 2 + offset[1] ** 2))

    def __repr__(self) -> str:
        def vec(v: sp.MatrixBase) -> str:
            return f"({v[0]}, {v[1]})"

        if self.shape == "fixed":
            return f"Body.fixed({self.name!r})"
        pivot = "" if self.pivot is None else f", pivot={vec(self.pivot)}"
        return (f"Body(name={self.name!r}, mass={self.mass}, inertia={self.inertia}, "
                f"position={vec(self.position)}, velocity={vec(self.velocity)}, "
                f"spin={self.spin}, shape={self.shape!r}{pivot})")

    # ---- constructors ---------------------------------------------------------------

    @classmethod
    def particle(cls, mass: Any, velocity: Any = (0, 0), name: str = "ball") -> Body:
        """A point mass at the contact point (the paper's ball).

        Examples
        --------
        >>> Body.particle(1, velocity=(3, 0)).inertia
        0
        """
        zero = sp.ImmutableMatrix([0, 0])
        return cls(name, mass, 0, zero, velocity, 0, "particle",
                   parts=(Part(name, _expr(mass, f"{name}.mass"), zero),))

    @classmethod
    def barbell(cls, mass_each: Any, half_length: Any, angle: Any, velocity: Any = (0, 0),
                spin: Any = 0, name: str = "barbell", struck: str = "A") -> Body:
        """Two point masses on a massless rod of length ``2*half_length``, one end at O.

        The rod makes `angle` with the x axis, so the centre C is at
        ``half_length*(cos(angle), sin(angle))``; the struck sphere is at O.

        Examples
        --------
        >>> Body.barbell(1, 2, 0).position.T
        Matrix([[2, 0]])
        >>> [p.label for p in Body.barbell(1, 2, 0).parts]
        ['A', 'B']
        """
        if struck not in ("A", "B"):
            raise InputError(f"{name}.struck", f"must be 'A' or 'B', got {struck!r}")
        each = _must_be_positive(_expr(mass_each, f"{name}.mass"), f"{name}.mass")
        half = _must_be_positive(_expr(half_length, f"{name}.half_length"),
                                 f"{name}.half_length")
        angle = _expr(angle, f"{name}.angle")
        direction = sp.ImmutableMatrix([sp.cos(angle), sp.sin(angle)])
        other = "B" if struck == "A" else "A"
        parts = (Part(struck, each, sp.ImmutableMatrix([0, 0])),
                 Part(other, each, sp.ImmutableMatrix(2 * half * direction)))
        return cls(name, 2 * each, 2 * each * half**2, half * direction, velocity, spin,
                   "barbell", (("mass_each", each), ("half_length", half), ("angle", angle)),
                   parts)

    @classmethod
    def rod(cls, mass: Any, length: Any, angle: Any, struck_at: Any, velocity: Any = (0, 0),
            spin: Any = 0, name: str = "rod", pivot: Any = None) -> Body:
        """A uniform thin rod; its centre is at ``struck_at*(cos(angle), sin(angle))``.

        An end hit has ``struck_at = length/2``.

        Examples
        --------
        >>> Body.rod(3, 2, 0, 1).inertia
        1
        """
        mass = _must_be_positive(_expr(mass, f"{name}.mass"), f"{name}.mass")
        length = _must_be_positive(_expr(length, f"{name}.length"), f"{name}.length")
        angle = _expr(angle, f"{name}.angle")
        struck_at = _expr(struck_at, f"{name}.struck_at")
        if (sp.Abs(struck_at) - length / 2).is_positive:
            raise InputError(f"{name}.struck_at", f"the contact must lie on the rod: "
                             f"|{struck_at}| exceeds half the length {length / 2}")
        position = struck_at * sp.ImmutableMatrix([sp.cos(angle), sp.sin(angle)])
        return cls(name, mass, mass * length**2 / 12, position, velocity, spin, "rod",
                   (("length", length), ("angle", angle), ("struck_at", struck_at)),
                   pivot=pivot)

    @classmethod
    def _round(cls, shape: str, factor: sp.Expr, mass: Any, radius: Any, position: Any,
               side: int, velocity: Any, spin: Any, name: str) -> Body:
        mass = _must_be_positive(_expr(mass, f"{name}.mass"), f"{name}.mass")
        radius = _must_be_positive(_expr(radius, f"{name}.radius"), f"{name}.radius")
        if position is None:
            position = (side * radius, 0)
        centre = as_vector(position, f"{name}.position")
        if tidy(centre[0] ** 2 + centre[1] ** 2 - radius**2).is_zero is False:
            raise InputError(f"{name}.position", f"the centre must lie at the radius "
                             f"{radius} from the contact point O, but it is at "
                             f"({centre[0]}, {centre[1]})")
        return cls(name, mass, factor * mass * radius**2, position, velocity, spin, shape,
                   (("radius", radius),))

    @classmethod
    def disc(cls, mass: Any, radius: Any, position: Any = None, side: int = 1,
             velocity: Any = (0, 0), spin: Any = 0, name: str = "disc") -> Body:
        """A uniform disc; by default its centre is on the normal, `radius` from O.

        `side` is +1 for the body on the +x side of O, -1 for the other.

        Examples
        --------
        >>> Body.disc(2, 1, side=-1).position.T, Body.disc(2, 1).inertia
        (Matrix([[-1, 0]]), 1)
        """
        return cls._round("disc", sp.Rational(1, 2), mass, radius, position, side, velocity,
                          spin, name)

    @classmethod
    def ring(cls, mass: Any, radius: Any, position: Any = None, side: int = 1,
             velocity: Any = (0, 0), spin: Any = 0, name: str = "ring") -> Body:
        """A thin ring (hoop): all its mass at the radius.

        Examples
        --------
        >>> Body.ring(2, 3).inertia
        18
        """
        return cls._round("ring", sp.Integer(1), mass, radius, position, side, velocity,
                          spin, name)

    @classmethod
    def sphere(cls, mass: Any, radius: Any, position: Any = None, side: int = 1,
               velocity: Any = (0, 0), spin: Any = 0, name: str = "sphere") -> Body:
        """A uniform solid sphere moving in the plane (central inertia 2/5 m r^2).

        Examples
        --------
        >>> Body.sphere(5, 1).inertia
        2
        """
        return cls._round("sphere", sp.Rational(2, 5), mass, radius, position, side,
                          velocity, spin, name)

    @classmethod
    def rigid(cls, mass: Any, inertia: Any, position: Any, velocity: Any = (0, 0),
              spin: Any = 0, name: str = "body", pivot: Any = None) -> Body:
        """Any rigid body given by mass, central inertia and centre position.

        Examples
        --------
        >>> Body.rigid(1, 2, (3, 4)).position.T
        Matrix([[3, 4]])
        """
        return cls(name, mass, inertia, position, velocity, spin, "rigid", pivot=pivot)

    @classmethod
    def fixed(cls, name: str = "wall") -> Body:
        """An immovable body (a wall, a floor, a nail) as a contact partner.

        Its mass stands in for an infinite one: nothing it is given is used.

        Examples
        --------
        >>> Body.fixed("floor").kinetic_energy
        0
        """
        return cls(name, 1, 0, (0, 0), (0, 0), 0, "fixed")

    # ---- kinematics and dynamics ----------------------------------------------------

    def with_motion(self, velocity: Any, spin: Any) -> Body:
        """The same body moving with another velocity and spin.

        Examples
        --------
        >>> Body.particle(1).with_motion((2, 0), 0).velocity.T
        Matrix([[2, 0]])
        """
        return replace(self, velocity=velocity, spin=spin)

    def shifted(self, offset: Any) -> Body:
        """The same body seen from another origin: every point it holds (its centre, its
        parts, its pivot) moved by `offset`. Velocities and spin do not change.

        Examples
        --------
        >>> Body.barbell(1, 2, 0).shifted((1, 0)).position.T
        Matrix([[3, 0]])
        """
        d = as_vector(offset, f"{self.name}.position")
        if self.shape == "fixed" or all(x == 0 for x in d):
            return self
        parts = tuple(replace(p, position=sp.ImmutableMatrix(p.position + d))
                      for p in self.parts)
        # every field was checked when the body was made, and a sum of checked points is
        # one: the copy is not checked again (a scene of a thousand bodies)
        moved = copy.copy(self)
        for key, value in (("position", self.position + d), ("parts", parts),
                           ("pivot", None if self.pivot is None else self.pivot + d)):
            object.__setattr__(moved, key, value)
        return moved

    def at(self, values: Mapping[sp.Symbol, Any]) -> Body:
        """The same body with numbers (or expressions) put in for its symbols.

        Examples
        --------
        >>> m, v = sp.symbols("m v", positive=True)
        >>> Body.particle(m, (v, 0)).at({m: 2, v: 3})
        Body(name='ball', mass=2, inertia=0, position=(0, 0), velocity=(3, 0), spin=0, shape='particle')
        """  # noqa: E501
        def put(x: Any) -> Any:
            return x if x is None else sp.sympify(x).xreplace(dict(values))

        parts = tuple(replace(p, mass=put(p.mass), position=put(p.position))
                      for p in self.parts)
        return replace(self, mass=put(self.mass), inertia=put(self.inertia),
                       position=put(self.position), velocity=put(self.velocity),
                       spin=put(self.spin), pivot=put(self.pivot), parts=parts,
                       dimensions=tuple((k, put(v)) for k, v in self.dimensions))

    def point_velocity(self, point: sp.MatrixBase) -> sp.ImmutableMatrix:
        """Velocity of the material point at `point` (relative to O): V + omega x (r - R).

        Examples
        --------
        >>> b = Body.rigid(1, 1, (1, 0), velocity=(0, 0), spin=1)
        >>> b.point_velocity(sp.Matrix([0, 0])).T
        Matrix([[0, -1]])
        """
        return sp.ImmutableMatrix(self.velocity + spin_cross(self.spin, point - self.position))

    @property
    def contact_velocity(self) -> sp.ImmutableMatrix:
        """Velocity of the body's point at O, the paper's eq. (11): v = V - omega x R.

        Examples
        --------
        >>> Body.rigid(1, 1, (0, 2), velocity=(1, 0), spin=3).contact_velocity.T
        Matrix([[7, 0]])
        """
        return sp.ImmutableMatrix(self.velocity - spin_cross(self.spin, self.position))

    @property
    def momentum(self) -> sp.ImmutableMatrix:
        """Linear momentum m V.

        Examples
        --------
        >>> Body.particle(2, (3, 0)).momentum.T
        Matrix([[6, 0]])
        """
        return sp.ImmutableMatrix(self.mass * self.velocity)

    @property
    def angular_momentum(self) -> sp.Expr:
        """Angular momentum about O: spin part I omega plus orbital part m R x V (eq. 14).

        Examples
        --------
        >>> Body.rigid(1, 2, (0, 1), velocity=(3, 0), spin=1).angular_momentum
        -1
        """
        return self.inertia * self.spin + self.mass * cross(self.position, self.velocity)

    @property
    def kinetic_energy(self) -> sp.Expr:
        """Translational plus rotational kinetic energy.

        Examples
        --------
        >>> Body.rigid(2, 4, (1, 0), velocity=(1, 1), spin=1).kinetic_energy
        4
        """
        if self.shape == "fixed":
            return sp.Integer(0)
        v = self.velocity
        return sp.Rational(1, 2) * (self.mass * (v[0] ** 2 + v[1] ** 2)
                                    + self.inertia * self.spin**2)


def join(first: Body, second: Body, name: str | None = None) -> Body:
    """The composite of two bodies stuck together, by the parallel-axis theorem.

    The composite's centre S is the mass-weighted mean of the two centres, its central
    inertia is each body's central inertia plus its mass times its squared distance
    from S, and its motion is the rigid motion with the same linear momentum and the
    same angular momentum: the state of the pair just after a perfectly plastic,
    sticking impact.

    Examples
    --------
    >>> a = Body.particle(1, velocity=(2, 0), name="a")
    >>> b = Body.rigid(1, 0, (0, 0), name="b")
    >>> j = join(a, b)
    >>> j.mass, j.velocity.T
    (2, Matrix([[1, 0]]))
    """
    mass = first.mass + second.mass
    centre = sp.ImmutableMatrix(
        (first.mass * first.position + second.mass * second.position) / mass)

    def about_centre(body: Body) -> sp.Expr:
        offset = body.position - centre
        return body.inertia + body.mass * (offset[0] ** 2 + offset[1] ** 2)

    inertia = tidy(about_centre(first) + about_centre(second))
    velocity = sp.ImmutableMatrix((first.momentum + second.momentum) / mass)
    # angular momentum about S, which the composite must carry as I_S * omega
    spin_momentum = sum(
        (b.inertia * b.spin + b.mass * cross(b.position - centre, b.velocity - velocity)
         for b in (first, second)),
        sp.Integer(0),
    )
    spin = tidy(spin_momentum / inertia) if not inertia.is_zero else 0
    parts = first.parts + second.parts
    return Body(name or f"{first.name}_{second.name}", mass, inertia,
                centre.applyfunc(tidy), velocity.applyfunc(tidy), spin, "rigid",
                parts=parts)
