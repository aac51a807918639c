"""The contact: line of impact, restitution law and tangential behaviour.

The normal is the line of impact at O, pointing from the first body into the second.
Restitution is Newton's kinematic coefficient ``e`` (the paper's eq. 3): the normal
relative velocity of the contact points reverses and is scaled by ``e``. Tangentially
the contact is either smooth (no tangential impulse, the paper's section 3) or sticking
(the contact points leave with the same tangential velocity, the clay ball of figure 2).

Examples
--------
>>> from rigidimpact.symbolic.notation import symbol
>>> c = Contact(restitution=symbol("e"))
>>> c.normal.T, c.tangential
(Matrix([[1, 0]]), 'smooth')
>>> Contact(normal=(0, 2)).frame
Matrix([
[ 0, 1],
[-1, 0]])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.cone import tangents
from rigidimpact.laws.law import (
    RESTITUTION_LAWS,
    TANGENTIAL_LAWS,
    ContactLaw,
    NewtonRestitution,
)
from rigidimpact.model.bodies import _expr, as_vector
from rigidimpact.model.roles import Role
from rigidimpact.model.space import as_vector3
from rigidimpact.symbolic.geometry import frame_of
from rigidimpact.symbolic.rewrite import tidy

__all__ = ["Contact", "RESTITUTION_LAWS", "TANGENTIAL"]


def _components(value: Any) -> int | None:
    """How many components a vector given as a sequence or matrix has (None if neither)."""
    if isinstance(value, sp.MatrixBase) or (isinstance(value, (list, tuple))):
        return len(value)
    return None

TANGENTIAL = tuple(TANGENTIAL_LAWS)


@dataclass(frozen=True)
class Contact:
    """Where and how two bodies meet.

    Parameters
    ----------
    normal : 2-vector
        Direction of the line of impact (any nonzero length), from body 1 into body 2.
    restitution : expr
        The restitution law's coefficient e, in [0, 1].
    tangential : {"smooth", "stick", "coulomb", "rough"}
        Smooth: the impulse is purely normal. Stick: a tangential impulse makes the
        contact points leave with equal tangential velocities. Coulomb: friction with
        coefficient `friction`, solved exactly by Routh's method (slip, stick, slip
        reversal). Rough: the tangential velocity of the touching points reverses,
        scaled by `tangential_restitution`, unless that needs more than Coulomb's
        friction allows (Walton's law).
    law : {"newton", "poisson", "energetic"}
        The restitution law: kinematic (Newton), kinetic (Poisson) or energetic
        (Stronge). On a straight impulse path (smooth contacts) the three agree.
    friction : expr, optional
        Coulomb's coefficient mu >= 0, with "coulomb" (required) and "rough".
    tangential_restitution : expr, optional
        beta in [-1, 1], with "rough" (required).
    name : str
        Names the contact in result keys (``contact.normal_impulse``).
    bodies : (str, str), optional
        The names of the two bodies, the normal pointing from the first into the second;
        needed where several contacts share one set of bodies (:mod:`rigidimpact.solve.collision`).
    point : 2-vector
        Where the bodies touch, from the world origin (default the origin O).

    Examples
    --------
    >>> Contact(restitution=1, tangential="stick")
    Contact(normal=(1, 0), restitution=1, tangential='stick', law='newton')
    """

    normal: Any = (1, 0)
    restitution: Any = 0
    tangential: str = "smooth"
    law: str = "newton"
    name: str = "contact"
    friction: Any = None
    tangential_restitution: Any = None
    bodies: tuple[str, str] | None = None
    point: Any = (0, 0)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.isidentifier():
            raise InputError("contact.name", f"must be an identifier, got {self.name!r}")
        if self.bodies is not None:
            if (not isinstance(self.bodies, (tuple, list)) or len(self.bodies) != 2
                    or not all(isinstance(b, str) for b in self.bodies)):
                raise InputError(f"{self.name}.bodies", "two body names")
            if self.bodies[0] == self.bodies[1]:
                raise InputError(f"{self.name}.bodies", "a contact needs two bodies")
            object.__setattr__(self, "bodies", tuple(self.bodies))
        spatial = _components(self.normal) == 3  # a 3-D contact: normal and point in space
        read = as_vector3 if spatial else as_vector
        point = (0, 0, 0) if spatial and _components(self.point) == 2 and \
            all(sp.sympify(x) == 0 for x in self.point) else self.point
        object.__setattr__(self, "point", read(point, f"{self.name}.point"))
        normal = read(self.normal, "contact.normal")
        if all(c.is_zero for c in normal):
            raise InputError("contact.normal", "must not be the zero vector")
        object.__setattr__(self, "normal", normal)
        e = _expr(self.restitution, "contact.restitution")
        role = Role("contact.restitution", "the restitution coefficient", e, 0, 1)
        if e.is_negative or (e - 1).is_positive or role.allows(e) is False:
            raise InputError("contact.restitution", role.describe(e))
        object.__setattr__(self, "restitution", e)
        if not isinstance(self.tangential, str) or self.tangential not in TANGENTIAL_LAWS:
            raise InputError("contact.tangential", f"must be one of {', '.join(TANGENTIAL)}, "
                             f"got {self.tangential!r}")
        if not isinstance(self.law, str) or self.law not in RESTITUTION_LAWS:
            raise InputError("contact.law", f"must be one of {', '.join(RESTITUTION_LAWS)}, "
                             f"got {self.law!r}")
        tangential = TANGENTIAL_LAWS[self.tangential]  # each law says what it takes
        if tangential.newtons_only and RESTITUTION_LAWS[self.law](e).newtons_e() is None:
            raise InputError("contact.law", f"{tangential.newtons_only}; for the "
                             f"{self.law} law use tangential = \"coulomb\" with a "
                             "friction coefficient")
        for key, what, low, high in (
                ("friction", "Coulomb's friction coefficient", 0, None),
                ("tangential_restitution", "the tangential restitution coefficient", -1, 1)):
            self._coefficient(key, what, low, high,
                              needed=tangential.coefficients.get(key, False),
                              allowed=key in tangential.coefficients)

    def _coefficient(self, key: str, what: str, low: Any, high: Any, needed: bool,
                     allowed: bool) -> None:
        value = getattr(self, key)
        where = f"{self.name}.{key}"
        if value is None:
            if needed:
                raise InputError(where, f"required with tangential = {self.tangential!r}")
            return
        if not allowed:
            raise InputError(where, f"not used with tangential = {self.tangential!r}")
        value = _expr(value, where)
        role = Role(where, what, value, low, high)
        if ((value - low).is_negative or (high is not None and (value - high).is_positive)
                or role.allows(value) is False):
            raise InputError(where, role.describe(value))
        object.__setattr__(self, key, value)

    @property
    def by_regimes(self) -> bool:
        """Whether the tangential law picks its course from the numbers (Routh's method,
        Walton's law) rather than being imposed as linear conditions."""
        return self.laws[1].solved_by_regimes

    @property
    def spatial(self) -> bool:
        """Whether the contact is in three dimensions (its normal has three components)."""
        return len(self.normal) == 3

    def __repr__(self) -> str:
        n = self.normal
        extra = "" if self.name == "contact" else f", name={self.name!r}"
        if self.friction is not None:
            extra += f", friction={self.friction}"
        if self.tangential_restitution is not None:
            extra += f", tangential_restitution={self.tangential_restitution}"
        if self.bodies is not None:
            p = self.point
            extra += f", bodies={self.bodies!r}, point=({', '.join(map(str, p))})"
        return (f"Contact(normal=({', '.join(map(str, n))}), restitution={self.restitution}, "
                f"tangential={self.tangential!r}, law={self.law!r}{extra})")

    def at(self, values: Mapping[sp.Symbol, Any]) -> Contact:
        """The same contact with numbers (or expressions) put in for its symbols.

        Examples
        --------
        >>> e = sp.Symbol("e", nonnegative=True)
        >>> Contact(restitution=e).at({e: sp.Rational(1, 2)})
        Contact(normal=(1, 0), restitution=1/2, tangential='smooth', law='newton')
        """
        def put(x: Any) -> Any:
            return x if x is None else sp.sympify(x).xreplace(dict(values))

        return replace(self, normal=put(self.normal), restitution=put(self.restitution),
                       friction=put(self.friction), point=put(self.point),
                       tangential_restitution=put(self.tangential_restitution))

    @cached_property
    def laws(self) -> tuple[NewtonRestitution, ContactLaw]:
        """The restitution law and the tangential law, as objects (made once, from the
        one registry of laws).

        Examples
        --------
        >>> Contact(restitution=1).laws
        (NewtonRestitution(1), Smooth())
        """
        return (RESTITUTION_LAWS[self.law](self.restitution),
                TANGENTIAL_LAWS[self.tangential].from_contact(self))

    @cached_property
    def frame(self) -> sp.ImmutableMatrix:
        """Rotation taking scene coordinates to contact coordinates (x along the normal).

        Its rows are the unit normal and the unit tangent (the normal turned by +90
        degrees); for the default normal it is the identity.

        Examples
        --------
        >>> Contact().frame
        Matrix([
        [1, 0],
        [0, 1]])
        """
        n = self.normal
        if self.spatial:  # rows n, t1, t2 (laws.cone.tangents says which tangents)
            return sp.ImmutableMatrix.vstack(*(t.T for t in tangents(n)))
        length = sp.sqrt(tidy(n[0] ** 2 + n[1] ** 2))  # tidy sees cos^2 + sin^2 = 1
        return frame_of(sp.ImmutableMatrix([tidy(n[0] / length), tidy(n[1] / length)]))

    @property
    def first(self) -> str:
        """The body on the -normal side (the first of `bodies`)."""
        return self._pair[0]

    @property
    def second(self) -> str:
        """The body the normal points into (the second of `bodies`)."""
        return self._pair[1]

    @property
    def _pair(self) -> tuple[str, str]:
        if self.bodies is None:
            raise InputError(f"{self.name}.bodies", "required: name the two bodies")
        return self.bodies

    @property
    def unit_normal(self) -> sp.ImmutableMatrix:
        """The normal scaled to unit length (scene frame)."""
        return self.frame.row(0).T

    @property
    def tangent(self) -> sp.ImmutableMatrix:
        """The unit tangent: the normal turned by +90 degrees (scene frame)."""
        return self.frame.row(1).T
