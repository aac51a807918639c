"""Where an impact followed along its path ends, for each restitution law: one
implementation, which the law objects give (:meth:`NewtonRestitution.end_event
<rigidimpact.laws.law.NewtonRestitution.end_event>`) and the path integrators use in the
plane and in space (the circular cone, :mod:`rigidimpact.laws.cone`; contacts driven
together, :mod:`rigidimpact.laws.together`).

Each end is a function of ``(p, v_n, p_c, work_c, work)``: the normal impulse so far,
the normal velocity, the impulse and the normal impulse's work at the end of compression
(None before it), and the normal work so far. It crosses zero upward where the impact
ends.

Examples
--------
>>> end = poisson(0.5)
>>> end(1.0, -0.1, None, None, -0.3), end(1.5, 0.4, 1.0, -0.5, -0.4)
(-1.0, 0.0)
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["End", "kinematic", "poisson", "energetic"]

End = Callable[[float, float, float | None, float | None, float], float]


def kinematic(target: float) -> End:
    """A kinematic law (Newton's, or a user's): the normal velocity reaches `target`,
    what the law asks of the closing velocity.

    Examples
    --------
    >>> kinematic(1.0)(0.5, 0.25, 0.3, -0.1, 0.0)
    -0.75
    """
    def end(p: float, v_n: float, p_c: float | None, work_c: float | None,
            work: float) -> float:
        return v_n - target
    return end


def poisson(e: float) -> End:
    """Poisson's kinetic law: the normal impulse reaches ``(1 + e)`` times its
    compression impulse."""
    def end(p: float, v_n: float, p_c: float | None, work_c: float | None,
            work: float) -> float:
        return -1.0 if p_c is None else p - (1 + e) * p_c
    return end


def energetic(e: float) -> End:
    """Stronge's energetic law: the normal work in restitution reaches ``-e^2`` times
    the work in compression.

    Examples
    --------
    >>> energetic(0.5)(2.0, 1.0, 1.0, -1.0, -0.75)
    0.0
    """
    def end(p: float, v_n: float, p_c: float | None, work_c: float | None,
            work: float) -> float:
        return -1.0 if work_c is None else (work - work_c) + e * e * work_c
    return end
