"""The laws of an impulsive contact, as labelled equations with the paper's numbers.

Each function takes bodies in the contact frame (x along the normal) before and after
the impact and returns an :class:`Equation` ``lhs = rhs`` that keeps what it says and
which equation of Mungan (Eur. J. Phys. 28, 2007) it is, so a derivation can be shown
step by step.

Examples
--------
>>> from rigidimpact.bodies import Body, cross
>>> ball = Body.particle(2, velocity=(3, 0))
>>> after = ball.with_motion((1, 0), 0)
>>> tangential_momentum(ball, after)
Equation(label='tangential momentum of ball is unchanged', paper='(13)', lhs=0, rhs=0)
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from rigidimpact.bodies import Body, cross

__all__ = [
    "Equation",
    "normal_momentum",
    "tangential_momentum",
    "pair_tangential_momentum",
    "angular_momentum",
    "angular_momentum_about_pivot",
    "restitution",
    "no_slip",
]


@dataclass(frozen=True)
class Equation:
    """``lhs = rhs``, with what it states and the paper's equation number(s).

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> eq = Equation("demo", "(1)", 2 * x, 4)
    >>> eq.residual, eq.as_sympy()
    (2*x - 4, Eq(2*x, 4))
    """

    label: str
    paper: str
    lhs: sp.Expr
    rhs: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "lhs", sp.sympify(self.lhs, strict=True))
        object.__setattr__(self, "rhs", sp.sympify(self.rhs, strict=True))

    @property
    def residual(self) -> sp.Expr:
        """``lhs - rhs``, zero when the equation holds."""
        return self.lhs - self.rhs

    def as_sympy(self) -> sp.Equality:
        """The equation as an unevaluated SymPy ``Eq``."""
        return sp.Eq(self.lhs, self.rhs, evaluate=False)

    def subs(self, *args, **kwargs) -> Equation:
        """The same law with a substitution made on both sides.

        Examples
        --------
        >>> x = sp.Symbol("x")
        >>> Equation("demo", "", x, 1).subs(x, 2).lhs
        2
        """
        return Equation(self.label, self.paper, self.lhs.subs(*args, **kwargs),
                        self.rhs.subs(*args, **kwargs))

    def xreplace(self, rule: dict) -> Equation:
        """The same law with `rule` replacing subexpressions exactly on both sides.

        Examples
        --------
        >>> x = sp.Symbol("x")
        >>> Equation("demo", "", x, 1).xreplace({x: 2}).lhs
        2
        """
        return Equation(self.label, self.paper, self.lhs.xreplace(rule),
                        self.rhs.xreplace(rule))


def normal_momentum(first: Body, first_after: Body, second: Body,
                    second_after: Body) -> Equation:
    """Linear momentum of the pair along the normal is conserved: eqs. (1) and (12).

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 0), "a"), Body.particle(3, (0, 0), "b")
    >>> normal_momentum(a, a.with_motion((0, 0), 0), b, b.with_motion((1, 0), 0)).residual
    -1
    """
    return Equation(
        "linear momentum along the normal",
        "(1), (12)",
        first.momentum[0] + second.momentum[0],
        first_after.momentum[0] + second_after.momentum[0],
    )


def tangential_momentum(before: Body, after: Body) -> Equation:
    """A smooth contact gives no tangential impulse: each body keeps V_y, eq. (13)."""
    return Equation(f"tangential momentum of {before.name} is unchanged", "(13)",
                    before.velocity[1], after.velocity[1])


def pair_tangential_momentum(first: Body, first_after: Body, second: Body,
                             second_after: Body) -> Equation:
    """With sticking the tangential impulses cancel in pairs: the pair keeps its P_y.

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 1), "a"), Body.particle(1, (0, 0), "b")
    >>> pair_tangential_momentum(a, a, b, b).residual
    0
    """
    return Equation(
        "tangential momentum of the pair",
        "(13), summed",
        first.momentum[1] + second.momentum[1],
        first_after.momentum[1] + second_after.momentum[1],
    )


def angular_momentum(before: Body, after: Body) -> Equation:
    """The impulse acts at O, so each body's angular momentum about O is kept: (2), (14).

    Spin part ``I omega`` plus orbital part ``m R x V``, before and after.

    Examples
    --------
    >>> b = Body.rigid(1, 1, (0, 1), velocity=(1, 0))
    >>> angular_momentum(b, b.with_motion((0, 0), sp.Symbol("w"))).as_sympy()
    Eq(-1, w)
    """
    return Equation(f"angular momentum of {before.name} about O", "(2), (14)",
                    before.angular_momentum, after.angular_momentum)


def angular_momentum_about_pivot(before: tuple[Body, Body], after: tuple[Body, Body],
                                 hinged: Body) -> Equation:
    """With one body on a fixed hinge, the pair's angular momentum about the hinge is kept.

    The hinge's reaction impulse acts at the hinge, so it has no moment about it; the
    contact impulses are internal to the pair. Each body counts ``I omega`` plus
    ``m (R - q) x V`` about the hinge q. (The pair's linear momentum is *not* kept: the
    reaction changes it.)

    Examples
    --------
    >>> ball = Body.particle(1, (1, 0), "ball")
    >>> rod = Body.rod(3, 2, sp.pi / 2, 0, pivot=(0, -1), name="rod")
    >>> w, u = sp.symbols("w u")
    >>> angular_momentum_about_pivot((ball, rod), (ball.with_motion((u, 0), 0),
    ...                              rod.with_motion((-w, 0), w)), rod).as_sympy()
    Eq(-1, -u + 4*w)
    """
    q = hinged.pivot

    def about_pivot(body: Body) -> sp.Expr:
        if body.support == "fixed":
            return sp.Integer(0)
        return body.inertia * body.spin + body.mass * cross(body.position - q, body.velocity)

    return Equation(f"angular momentum of the pair about {hinged.name}'s pivot", "-",
                    sum((about_pivot(b) for b in before), sp.Integer(0)),
                    sum((about_pivot(b) for b in after), sp.Integer(0)))


def restitution(first: Body, first_after: Body, second: Body, second_after: Body,
                e: sp.Expr) -> Equation:
    """Newton's kinematic restitution at O along the normal: eqs. (3) and (4).

    ``v_2fx - v_1fx = -e (v_2ix - v_1ix)`` with the contact velocities of eq. (11).

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 0), "a"), Body.particle(1, (0, 0), "b")
    >>> restitution(a, a, b, b, 1).as_sympy()
    Eq(-2, 2)
    """
    return Equation(
        "restitution along the normal",
        "(3), (4)",
        second_after.contact_velocity[0] - first_after.contact_velocity[0],
        -e * (second.contact_velocity[0] - first.contact_velocity[0]),
    )


def no_slip(first_after: Body, second_after: Body) -> Equation:
    """Sticking: the contact points leave O with the same tangential velocity.

    Examples
    --------
    >>> a, b = Body.particle(1, (2, 1), "a"), Body.particle(1, (0, 3), "b")
    >>> no_slip(a, b).residual
    2
    """
    return Equation(
        "sticking: no tangential slip at O afterwards",
        "(8)-(9), fig. 2",
        second_after.contact_velocity[1] - first_after.contact_velocity[1],
        sp.Integer(0),
    )
