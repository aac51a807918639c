"""Validation by role: a coefficient is checked for what it *is*, whatever it is called.

A scene may call its restitution coefficient ``e``, ``k`` or ``1 - d/2``; what bounds it
is its role in the contact (Newton's e lies in [0, 1]), not its name. A :class:`Role`
ties an expression to the range its role allows, and :func:`check_roles` is the one
place every door (a scene's ``[values]``, ``--set``, the Python API) checks numbers
against the roles and against the symbols' own assumptions.

Examples
--------
>>> k = sp.Symbol("k", nonnegative=True)
>>> role = Role("contact.restitution", "the restitution coefficient", k, 0, 1)
>>> check_roles([role], {k: sp.Integer(3)}, {k: "--set k"})
Traceback (most recent call last):
...
rigidimpact.errors.InputError: --set k: the restitution coefficient (contact.restitution = k) must lie in [0, 1], got 3
"""  # noqa: E501

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError

__all__ = ["Role", "check_roles", "check_assumptions", "roles_of"]


@dataclass(frozen=True)
class Role:
    """An expression whose physical role bounds its value.

    Parameters
    ----------
    field : str
        Where the expression was stated (``contact.restitution``, ``ball.mass``).
    meaning : str
        What it is, in words.
    expr : sympy.Expr
    low, high : number or None
        The closed range the role allows (None: unbounded on that side).
    open_low : bool
        True when `low` itself is excluded (a mass must be positive).

    Examples
    --------
    >>> Role("ball.mass", "a mass", sp.Integer(2), 0, None, open_low=True).allows(2)
    True
    """

    field: str
    meaning: str
    expr: Any
    low: Any = None
    high: Any = None
    open_low: bool = False
    zero: bool = False  # the role asks for zero (a point on a surface), to 40 digits

    def allows(self, value: sp.Expr) -> bool | None:
        """Whether a value fits the range (None while it is not a number)."""
        value = sp.sympify(value)
        if not value.is_number:
            return None
        if self.zero and value.is_Rational:
            return bool(value == 0)
        if self.zero:  # exact zeros of sums of radicals need not simplify to 0 by
            # themselves: decided at 60 digits, far beyond any stated number's digits
            return bool(abs(sp.N(value, 60)) < sp.Float("1e-40", 60))
        if value.is_real is False:
            return False
        try:
            return self._holds(value)
        except TypeError:  # SymPy cannot order it (sines that sum to zero, say): at 60
            digits = sp.N(value, 60)  # digits, a zero to 40 of them on the boundary
            return self._holds(sp.Integer(0) if abs(digits) < sp.Float("1e-40", 60)
                               else digits)

    def _holds(self, value: sp.Expr) -> bool:
        low_ok = (self.low is None or (value > self.low if self.open_low
                                       else value >= self.low))
        high_ok = self.high is None or value <= self.high
        return bool(low_ok and high_ok)

    @property
    def range(self) -> str:
        low = "(" if self.open_low else "["
        return (f"{low}{'-inf' if self.low is None else self.low}, "
                f"{'inf' if self.high is None else self.high}]")

    def describe(self, value: sp.Expr) -> str:
        """The refusal for `value`, naming the role and its range."""
        if self.zero:
            return f"{self.meaning}; here it is off by {_short(value)}"
        if self.high is None and self.low == 0:
            bound = "must be positive" if self.open_low else "must not be negative"
        else:
            bound = f"must lie in {self.range}"
        expr = sp.sympify(self.expr)
        name = (f"{self.meaning} ({self.field} = {expr})" if expr.free_symbols
                else f"{self.meaning} ({self.field})")
        return f"{name} {bound}, got {_short(value)}"


def _short(value: sp.Expr) -> str:
    """A number as a user would read it: exact when short, else 6 digits."""
    text = str(value)
    return text if len(text) <= 24 else str(sp.N(value, 6))


def check_assumptions(sym: sp.Symbol, value: sp.Expr, where: str) -> sp.Expr:
    """Refuse a number that contradicts the symbol's own assumptions.

    Examples
    --------
    >>> check_assumptions(sp.Symbol("m", positive=True), sp.Integer(-1), "values.m")
    Traceback (most recent call last):
    ...
    rigidimpact.errors.InputError: values.m: must be positive (m is positive), got -1
    """
    if not value.is_finite:
        raise InputError(where, f"must be finite, got {value}")
    for assumption, ok in (("positive", value > 0), ("nonnegative", value >= 0),
                           ("negative", value < 0), ("nonpositive", value <= 0),
                           ("nonzero", value != 0)):
        if getattr(sym, f"is_{assumption}") and not ok:
            raise InputError(where, f"must be {assumption} ({sym} is {assumption}), "
                             f"got {_short(value)}")
    return value


def check_roles(roles: Iterable[Role], values: Mapping[sp.Symbol, sp.Expr],
                sources: Mapping[sp.Symbol, str]) -> None:
    """Check every role whose expression `values` make a number.

    Parameters
    ----------
    roles : iterable of Role
    values : mapping of Symbol to exact number
    sources : mapping of Symbol to str
        Where each value came from (``values.e``, ``--set e``), for the message.

    Raises
    ------
    InputError
        Naming where the offending value came from, the role and the range.
    """
    for role in roles:
        expr = sp.sympify(role.expr)
        value = expr.xreplace(dict(values)) if expr.free_symbols else expr
        if value.free_symbols or role.allows(value) is not False:
            continue
        doors = sorted({sources[s] for s in expr.free_symbols if s in sources})
        raise InputError(", ".join(doors) or role.field, role.describe(value))


@dataclass(frozen=True)
class _AtOrigin:
    """The one contact of a two-body impact: at O."""

    name: str
    first: str
    second: str
    normal: Any
    point: Any = (0, 0)


def _geometry(bodies: tuple[Any, ...], touches: Iterable[Any]) -> list[Role]:
    """Where each contact must be on the bodies it touches, as roles (so a value that
    arrives later, by ``--set`` or ``[values]``, is checked as if written in the file):
    a round body is touched on its rim, along the line through its centre, from outside
    (the normal points out of the first body and into the second); a rod is touched
    between its ends; a point mass where it is."""
    found: list[Role] = []
    by_name = {b.name: b for b in bodies}
    for touch in touches:
        # plain pairs of expressions, not matrices: a scene of a thousand contacts
        # builds its roles in a fraction of a second
        px, py = touch.point
        nx, ny = touch.normal
        for side, name in ((1, touch.first), (-1, touch.second)):
            body = by_name.get(name)
            if body is None or getattr(body, "support", "free") == "fixed":
                continue
            where = f"{touch.name}.point"
            dims = dict(body.dimensions)
            cx, cy = body.position
            ox, oy = side * (px - cx), side * (py - cy)  # outward, along the normal
            if "radius" in dims:
                found += [
                    Role(where, f"{name} is round: the contact must lie on its rim, "
                         f"{dims['radius']} from its centre",
                         ox ** 2 + oy ** 2 - dims["radius"] ** 2, zero=True),
                    Role(f"{touch.name}.normal", f"{name} is round: the normal must pass "
                         "through its centre", ox * ny - oy * nx, zero=True),
                    Role(f"{touch.name}.normal", f"the normal must point out of the first "
                         f"body and into the second ({name}'s centre is on the wrong side)",
                         ox * nx + oy * ny, 0, None, open_low=True)]
            if body.shape == "rod" and "struck_at" in dims:
                found.append(Role(f"{name}.struck_at", "the contact must lie on the rod: "
                                  "half the length minus |struck_at|",
                                  dims["length"] / 2 - sp.Abs(dims["struck_at"]), 0))
            if body.shape == "rod" and isinstance(touch, _AtOrigin) is False:
                ax, ay = sp.cos(dims["angle"]), sp.sin(dims["angle"])
                dx, dy = px - cx, py - cy
                found += [
                    Role(where, f"{name} is a thin rod: the contact must lie on its axis",
                         dx * ay - dy * ax, zero=True),
                    Role(where, f"{name} is a thin rod: the contact must lie between its "
                         "ends (half the length minus the distance from its centre)",
                         dims["length"] / 2 - sp.Abs(dx * ax + dy * ay), 0)]
    return found


def roles_of(bodies: Iterable[Any], contacts: Iterable[Any],
             touches: Iterable[Any] | None = None) -> tuple[Role, ...]:
    """The roles of an impact's data: masses positive, inertias and sizes not negative,
    restitution in [0, 1] (and, as laws are added, the friction and tangential
    coefficients in theirs), and where each contact lies on its bodies.

    Examples
    --------
    >>> from rigidimpact.model.bodies import Body
    >>> from rigidimpact.laws.contact import Contact
    >>> k = sp.Symbol("k")
    >>> [r.field for r in roles_of([Body.particle(1)], [Contact(restitution=k)])]
    ['ball.mass', 'ball.inertia', 'contact.restitution']
    >>> r = sp.Symbol("r", positive=True)
    >>> pair = [Body.particle(1, name="a"), Body.disc(1, r, (r, 0), name="b")]
    >>> [role.meaning for role in roles_of(pair, [Contact()]) if role.zero][0]
    'b is round: the contact must lie on its rim, r from its centre'

    """
    roles: list[Role] = []
    for body in bodies:
        if getattr(body, "support", "free") == "fixed":
            continue
        roles.append(Role(f"{body.name}.mass", "a mass", body.mass, 0, None, open_low=True))
        roles.append(Role(f"{body.name}.inertia", "a moment of inertia", body.inertia, 0))
        for key, size in body.dimensions:
            if key in ("length", "radius", "half_length", "mass_each"):
                roles.append(Role(f"{body.name}.{key}", f"a {key.replace('_', ' ')}", size,
                                  0, None, open_low=True))
    contacts = tuple(contacts)
    if touches is None and len(contacts) == 1:  # one contact: at O, between the two
        bodies = tuple(bodies)
        names = [b.name for b in bodies]
        if len(names) == 2:
            touches = (_AtOrigin(contacts[0].name, names[0], names[1], contacts[0].normal),)
    roles += _geometry(tuple(bodies), touches or ())
    for contact in contacts:
        name = getattr(contact, "name", "contact")
        roles.append(Role(f"{name}.restitution", "the restitution coefficient",
                          contact.restitution, 0, 1))
        if getattr(contact, "friction", None) is not None:
            roles.append(Role(f"{name}.friction", "Coulomb's friction coefficient",
                              contact.friction, 0))
        if getattr(contact, "tangential_restitution", None) is not None:
            roles.append(Role(f"{name}.tangential_restitution",
                              "the tangential restitution coefficient",
                              contact.tangential_restitution, -1, 1))
    return tuple(roles)
