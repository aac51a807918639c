"""The driven rule: one contact strikes and every other contact touching with zero normal
velocity rests, staying closed while it pushes (a ball on the table striking a cushion,
a block on a floor struck from the side). The impact is followed in the striking
contact's normal impulse, each resting contact sticking or slipping under Coulomb's law
as the impulse grows, by :func:`rigidimpact.laws.together.driven_impact`, in floating
point; contacts moving apart take no part. Where the striking contact's own impact
(its laws' one face, in closed form) leaves no resting contact closing, the resting ones carry
nothing (a resting contact pushes only to stay closed, and friction without a push is
none): that exact answer is the rule's, and nothing is integrated (two balls lying on a
table meeting along a level line of centres).

It is one implementation in the plane and in space: each contact's rows in its own frame
(:meth:`~rigidimpact.solve.problem.ImpulseRows.frame_rows`) go to the integrator, a
planar contact's second tangent row zero (the bodies cannot move across the plane, so
nothing slips there and no friction acts there), a 3-D contact's its own.

Examples
--------
A disc (m = 1, r = 1, I = 1/2) rests on a smooth floor and strikes a smooth wall at 2,
e = 1/2: the floor takes nothing, the disc leaves the wall at 1.

>>> import sympy as sp
>>> from rigidimpact.laws.contact import Contact
>>> from rigidimpact.model.bodies import Body
>>> from rigidimpact.solve.collision import Collision
>>> disc = Body.rigid(1, sp.Rational(1, 2), (0, 0), (2, 0), name="disc")
>>> wall = Contact((1, 0), sp.Rational(1, 2), name="wall", bodies=("disc", "ground"),
...                point=(1, 0))
>>> floor = Contact((0, 1), 0, name="floor", bodies=("ground", "disc"), point=(0, -1))
>>> (out,) = Collision((disc, Body.fixed("ground")), (wall, floor)).solve(Driven())
>>> round(float(out.results()["disc.vx"]), 12), out.rule
(-1.0, 'driven')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.together import driven_impact
from rigidimpact.lazy import deferred
from rigidimpact.solve.problem import ImpulseRows
from rigidimpact.solve.rules.base import Rule, RuleSettings, alone_outcome, own_step
from rigidimpact.solve.solution import Solution

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["Driven", "driven"]


@dataclass(frozen=True)
class Driven(Rule):
    """One contact strikes, the others rest (see the module's text); `tolerance` is the
    integration's relative tolerance (default 1e-10)."""

    tolerance: float | None = None
    name: ClassVar[str] = "driven"
    spoken: ClassVar[str] = "one strikes, the others rest"  # as 3-D evaluate long said
    said: ClassVar[str] = (
        "one contact strikes under its restitution law and every contact touching at rest "
        "stays closed while it pushes, followed in the striking contact's normal impulse "
        "(floating point)")
    said_with_friction: ClassVar[str] = (
        "one contact strikes under its restitution law; each resting contact sticks while "
        "its cone holds it and otherwise slips with |P_t| = mu P_n against its slip, as "
        "the striking contact's normal impulse grows")
    stated_tolerance: ClassVar[float | None] = 1e-7  # integrated to 1e-10, stated 1000x
    impulse_words: ClassVar[str] = ("{name}'s impulse, integrated in the striking contact's "
                                    "normal impulse")

    @classmethod
    def from_settings(cls, settings: RuleSettings) -> Driven:
        return cls(settings.tolerance)

    def outcomes(self, problem: ImpulseRows) -> tuple[Solution, ...]:
        return (driven(problem, self.tolerance),)


def driven(problem: ImpulseRows, tolerance: float | None = None) -> Solution:
    """The driven rule on a planar impulse problem (see the module's text)."""
    problem.numbers_only("driven")
    for c in problem.contacts:
        if c.laws[1].grips and c.laws[1].coulomb() is None:
            raise InputError(f"{c.name}.tangential", "the driven rule follows Coulomb's "
                             f"friction (or none), not {c.tangential!r}")
    if problem.joints:
        raise InputError("joints", "the driven rule does not take joints yet: use the "
                         "simultaneous or sequential rule")
    # the solvers' rows (each contact's scaled alike, which no law minds); the impulses
    # are put back on the unit normal by _named
    J = np.array(problem.scaled_J.evalf(30), dtype=float)
    u = np.array(problem.u_before.evalf(30), dtype=float).ravel()
    size = max(float(np.abs(u).max()), 1e-300)
    speeds = J @ u
    approaching = [i for i, v in enumerate(speeds) if v < -1e-12 * size]
    resting = [i for i, v in enumerate(speeds) if abs(v) <= 1e-12 * size]
    if len(approaching) != 1:
        raise InputError("impact.rule", "the driven rule takes one striking contact and "
                         f"others resting; here {len(approaching)} approach: use the "
                         "simultaneous or sequential rule")
    alone = _alone(problem, approaching[0], resting)
    if alone is not None:
        return alone
    acting = approaching + resting
    striking = problem.contacts[approaching[0]]
    rows = [problem.frame_rows(i) for i in acting]
    friction = [float(problem.contacts[i].friction or 0) for i in acting]
    Minv = np.array(problem.M_inverse.evalf(30), dtype=float)
    out = driven_impact(Minv, rows, u, striking.laws[0], friction,
                        tolerance)
    n = len(problem.contacts)
    normal, along, across = sp.zeros(n, 1), sp.zeros(n, 1), sp.zeros(n, 1)
    for k, i in enumerate(acting):
        normal[i], along[i], across[i] = (sp.Float(x, 17) for x in out.impulses[k])
    courses = tuple(f"{problem.contacts[i].name}: {course}"
                    for i, course in zip(acting, out.courses, strict=True))
    rest = [problem.contacts[i].name for i in resting]
    more: dict[str, Any] = {"tangent_impulses": {
        c.name: (along[i], across[i]) for i, c in enumerate(problem.contacts)}} \
        if problem.tangents == 2 else {}
    left = [c.name for i, c in enumerate(problem.contacts) if i not in acting]
    notes = (f"{striking.name} strikes" + (
        f" and {', '.join(rest)} rest{'s' if len(rest) == 1 else ''} (closed while "
        "pushing)" if rest else "") + f": the impulses are integrated in {striking.name}'s "
        f"normal impulse to a relative tolerance of {out.tolerance:g} ({out.steps} steps)",
        *((f"moving apart, not acting: {', '.join(left)}",) if left else ()))
    return problem.outcome(
        "driven", (), sp.Matrix([sp.Float(x, 17) for x in out.u_after]),
        problem.named(normal), tuple(problem.contacts[i].name for i in acting
                                      if normal[i] > 0),
        tangential=problem.named(along), courses=courses, notes=notes,
        method=f"integrated to {out.tolerance:g}", **more)



def _alone(problem: ImpulseRows, k: int, resting: list[int]) -> Solution | None:
    """The striking contact k's own impact, where it is a closed form (exact, or in the
    numbers' own floating point) and leaves every resting contact not closing (so they
    carry nothing); else None."""
    if not all(sp.sympify(x).is_number for x in (*problem.u_before, *problem.M_inverse)):
        return None
    try:
        P, course, after, tolerance, _ = own_step(problem, k, problem.u_before)
    except InputError:
        return None
    opening = [problem.closing(i, list(after)) for i in resting]
    if tolerance is not None or any(x < 0 for x in opening):
        return None
    name = problem.contacts[k].name
    rest = ", ".join(problem.contacts[i].name for i in resting)
    notes = (f"{name} strikes" + (f"; its own impact leaves {rest} not closing, so "
                                  f"{'they carry' if len(resting) > 1 else 'it carries'} "
                                  "nothing" if rest else ""),)
    return alone_outcome(problem, k, "driven", P, course, after, courses=(
        f"{name}: {course}", *(f"{problem.contacts[i].name}: "
                               + ("lets go" if x > 0 else "stays closed, carrying nothing")
                               for i, x in zip(resting, opening, strict=True))),
        notes=notes)
