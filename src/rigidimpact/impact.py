"""An impact of two bodies: its unknowns, its equations, and their solution.

The equations are built from the laws in :mod:`rigidimpact.laws` in the contact frame
(x along the normal), solved as the linear system they are, and tidied by ``cancel``
and ``factor`` only: no blanket ``simplify``.

Examples
--------
>>> from rigidimpact.bodies import Body
>>> from rigidimpact.contact import Contact
>>> a = Body.particle(1, velocity=(2, 0), name="a")
>>> b = Body.particle(1, name="b")
>>> sol = Impact(a, b, Contact(restitution=1)).solve()
>>> sol.results()["a.vx"], sol.results()["b.vx"]
(0, 2)
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import sympy as sp

from rigidimpact import laws
from rigidimpact.bodies import Body
from rigidimpact.contact import Contact
from rigidimpact.errors import InputError
from rigidimpact.notation import make_symbol
from rigidimpact.rewrite import tidy
from rigidimpact.solution import Solution

__all__ = ["Impact"]

DEFAULT_UNKNOWNS = (("V_1fx", "V_1fy", "omega_1fz"), ("V_2fx", "V_2fy", "omega_2fz"))


def _rotated(body: Body, frame: sp.MatrixBase) -> Body:
    """The body described in the contact frame."""
    if frame == sp.eye(2):
        return body
    return replace(body, position=frame * body.position, velocity=frame * body.velocity)


@dataclass(frozen=True)
class Impact:
    """Two bodies meeting at O under a contact law.

    Parameters
    ----------
    first, second : Body
        The first is on the -x side of O (the side the normal points away from).
    contact : Contact
        Line of impact, restitution and tangential behaviour.
    unknown_names : pair of (vx, vy, omega) names, optional
        Names for the final velocity components in the contact frame; the default is
        the paper's section 3 notation ``V_1fx, V_1fy, omega_1fz, ...``.

    Examples
    --------
    >>> from rigidimpact.bodies import Body
    >>> imp = Impact(Body.particle(1, (1, 0), "p"), Body.disc(1, 1, name="d"), Contact())
    >>> [str(u) for u in imp.unknowns]
    ['V_1fx', 'V_1fy', 'V_2fx', 'V_2fy', 'omega_2fz']
    """

    first: Body
    second: Body
    contact: Contact
    unknown_names: tuple[tuple[str, str, str], tuple[str, str, str]] = DEFAULT_UNKNOWNS

    def __post_init__(self) -> None:
        if self.first.name == self.second.name:
            raise InputError("bodies", f"the two bodies share the name {self.first.name!r}")
        approach = self.approach_speed
        if approach.is_nonpositive:
            raise InputError("bodies", f"the bodies are not approaching at O (normal approach "
                             f"speed {approach}); there is no impact")

    @property
    def frame(self) -> sp.ImmutableMatrix:
        """Rotation from scene to contact coordinates."""
        return self.contact.frame

    @property
    def before(self) -> tuple[Body, Body]:
        """Both bodies before the impact, in the contact frame."""
        return _rotated(self.first, self.frame), _rotated(self.second, self.frame)

    @property
    def approach_speed(self) -> sp.Expr:
        """How fast the contact points close along the normal: ``v_1ix - v_2ix``.

        Examples
        --------
        >>> from rigidimpact.bodies import Body
        >>> Impact(Body.particle(1, (3, 0), "a"), Body.particle(1, (1, 0), "b"),
        ...        Contact()).approach_speed
        2
        """
        first, second = self.before
        return sp.cancel(first.contact_velocity[0] - second.contact_velocity[0])

    @property
    def after(self) -> tuple[Body, Body]:
        """Both bodies after the impact, with unknown symbols for their motion."""
        states = []
        for body, names in zip(self.before, self.unknown_names, strict=True):
            vx, vy, omega = (make_symbol(n, real=True) for n in names)
            spin = 0 if body.inertia.is_zero else omega
            states.append(body.with_motion((vx, vy), spin))
        return states[0], states[1]

    @property
    def unknowns(self) -> tuple[sp.Symbol, ...]:
        """The final velocity components and spins to solve for."""
        found: list[sp.Symbol] = []
        for body in self.after:
            found += [body.velocity[0], body.velocity[1]]
            if isinstance(body.spin, sp.Symbol):
                found.append(body.spin)
        return tuple(found)

    def equations(self) -> tuple[laws.Equation, ...]:
        """The laws that fix the unknowns, in the order the paper gives them.

        Examples
        --------
        >>> from rigidimpact.bodies import Body
        >>> imp = Impact(Body.particle(1, (1, 0), "p"), Body.rod(1, 2, 1, 1, name="r"),
        ...              Contact())
        >>> [eq.paper for eq in imp.equations()]
        ['(1), (12)', '(13)', '(13)', '(2), (14)', '(3), (4)']
        """
        (first, second), (first_after, second_after) = self.before, self.after
        equations = [laws.normal_momentum(first, first_after, second, second_after)]
        if self.contact.tangential == "smooth":
            equations += [laws.tangential_momentum(first, first_after),
                          laws.tangential_momentum(second, second_after)]
        else:
            equations.append(
                laws.pair_tangential_momentum(first, first_after, second, second_after))
        # a point mass at O has no angular momentum about O: its law reads 0 = 0
        equations += [laws.angular_momentum(b, a) for b, a in
                      ((first, first_after), (second, second_after)) if not b.inertia.is_zero]
        equations.append(laws.restitution(first, first_after, second, second_after,
                                          self.contact.restitution))
        if self.contact.tangential == "stick":
            equations.append(laws.no_slip(first_after, second_after))
        return tuple(equations)

    def solve(self) -> Solution:
        """Solve the linear equations for the final motion.

        Returns
        -------
        Solution

        Examples
        --------
        >>> from rigidimpact.bodies import Body
        >>> sol = Impact(Body.particle(1, (2, 0), "a"), Body.particle(3, name="b"),
        ...              Contact(restitution=0)).solve()
        >>> sol.results()["b.vx"]
        1/2
        """
        equations = self.equations()
        unknowns = self.unknowns
        matrix, rhs = sp.linear_eq_to_matrix([eq.residual for eq in equations], unknowns)
        try:
            solved = matrix.LUsolve(rhs)
        except (ValueError, ZeroDivisionError) as exc:
            raise InputError("bodies", "the impact equations are singular for these "
                             "bodies") from exc
        values = {u: tidy(x) for u, x in zip(unknowns, solved, strict=True)}
        if any(v.has(sp.nan, sp.zoo) for v in values.values()):
            raise InputError("bodies", "the impact equations are singular for these bodies")
        return Solution(self, equations, unknowns, values)
