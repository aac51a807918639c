"""A push-only linear spring-dashpot contact and the restitution it gives.

The contact pushes with ``k d + c d'`` while that is positive and lets go when it falls to
zero, before the compression d itself is back to zero; so its restitution is not the
textbook ``exp(-z pi / sqrt(1 - z^2))`` of a dashpot that may pull, and the damping ratio
z that gives a wanted e is found here from the closed form of the isolated contact. The
simulator's compliant models and the compliant rule for several contacts share it.

Examples
--------
>>> round(restitution_of(damping_ratio_for(0.5)), 12)
0.5
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

__all__ = ["restitution_of", "damping_ratio_for", "MAX_DAMPING_RATIO"]

MAX_DAMPING_RATIO = 1e3  # e = 2.5e-7 here; e -> 0 needs an unbounded dashpot


def _gap(z: float, t: np.ndarray | float):
    """Penetration and its rate for the isolated contact (omega_0 = 1, d(0) = 0, d'(0) = 1)."""
    if z < 1.0:
        wd = math.sqrt(1.0 - z * z)
        decay = np.exp(-z * t)
        return decay * np.sin(wd * t) / wd, decay * (np.cos(wd * t) - z / wd * np.sin(wd * t))
    if z == 1.0:
        return t * np.exp(-t), (1.0 - t) * np.exp(-t)
    root = math.sqrt(z * z - 1.0)
    r1, r2 = -z + root, -z - root  # r1 is the slow root
    return ((np.exp(r1 * t) - np.exp(r2 * t)) / (r1 - r2),
            (r1 * np.exp(r1 * t) - r2 * np.exp(r2 * t)) / (r1 - r2))


def restitution_of(z: float) -> float:
    """e of a push-only linear spring-dashpot with damping ratio `z`, in closed form.

    The contact ends at the first t > 0 where ``d + 2 z d' = 0`` (the force vanishes);
    e is the rate of separation then over the rate of approach.

    Examples
    --------
    >>> round(restitution_of(0.1), 10)
    0.7440793977
    """
    if z < 0:
        raise ValueError("the damping ratio must be non-negative")
    if z == 0.0:
        return 1.0

    def force(t: float) -> float:
        d, rate = _gap(z, t)
        return float(d + 2 * z * rate)

    if z < 1.0:  # the closed form of the force's first zero
        wd = math.sqrt(1.0 - z * z)
        end = (math.pi - math.atan2(2 * z * wd, 1.0 - 2 * z * z)) / wd
    else:  # the force starts at 2z > 0 and falls through zero within a few slow times
        hi = 1.0
        while force(hi) > 0:
            hi *= 2.0
        end = brentq(force, 0.0 if force(0.0) <= 0 else 1e-300, hi, xtol=1e-15 * hi,
                     rtol=8.9e-16)
    return float(-_gap(z, end)[1])


def damping_ratio_for(e: float) -> float:
    """The damping ratio whose push-only contact returns `e` (capped for e -> 0).

    Examples
    --------
    >>> damping_ratio_for(1.0)
    0.0
    >>> damping_ratio_for(0.0) == MAX_DAMPING_RATIO
    True
    """
    if not 0.0 <= e <= 1.0:
        raise ValueError("e must lie in [0, 1]")
    if e == 1.0:
        return 0.0
    if e <= restitution_of(MAX_DAMPING_RATIO):
        return MAX_DAMPING_RATIO
    return brentq(lambda z: restitution_of(z) - e, 0.0, MAX_DAMPING_RATIO, xtol=1e-15,
                  rtol=8.9e-16)
