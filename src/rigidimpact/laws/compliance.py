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
from typing import TYPE_CHECKING, Any

from rigidimpact.lazy import deferred

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")


__all__ = ["tangential_bounce", "sphere_bounce", "restitution_of", "damping_ratio_for",
           "MAX_DAMPING_RATIO"]

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
        from scipy.optimize import brentq  # scipy on first use: the command line starts fast

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
    from scipy.optimize import brentq

    return brentq(lambda z: restitution_of(z) - e, 0.0, MAX_DAMPING_RATIO, xtol=1e-15,
                  rtol=8.9e-16)


def tangential_bounce(vt: Any, vn: Any, slip_spin: Any, mu: float, e: float, ratio: float,
                      inertia: float, steps: int = 4000) -> tuple[Any, Any, Any]:
    """A round body striking a fixed flat through a tangentially compliant contact:
    the tangential and normal velocity of its centre and ``omega R`` after, for arrays
    of impacts at once (``vn < 0`` approaching; ``slip_spin`` is ``omega R``, so the
    touching point slips at ``vt + slip_spin``).

    The contact is the lumped one of the discrete-element codes: a linear normal spring
    with the dashpot that returns `e`, and a linear tangential spring `ratio` times as
    stiff, stretched by the slip and capped by Coulomb's ``mu F_n`` (beyond the cap the
    points slide and the spring keeps the cap's stretch). Linear springs make the answer
    independent of the stiffness and of the radius; `inertia` is the body's central moment
    in units of ``m R^2`` (2/5 for a solid sphere, 1/2 for a disc). Integrated with
    `steps` per normal period (semi-implicit Euler, first order).

    Examples
    --------
    A solid sphere at 40 degrees with the coefficients of a published spring-dashpot
    simulation (mu = 0.092, e = 1, k_t / k_n = 1.48 / 1.72): e_t = 0.7807 there.

    >>> import math
    >>> vt, vn, w = tangential_bounce(math.sin(0.6981317), -math.cos(0.6981317), 0.0,
    ...                               0.092, 1.0, 1.48 / 1.72, 0.4)
    >>> round(float(vt / math.sin(0.6981317)), 4)
    0.7807
    """
    vt, vn, spin = (np.array(x, dtype=float) * np.ones(np.broadcast(vt, vn, slip_spin).shape)
                    for x in (vt, vn, slip_spin))
    speed = float(np.max(np.abs(np.stack([vt, vn, spin])))) or 1.0
    vt, vn, spin = vt / speed, vn / speed, spin / speed  # units where the speed is 1
    damping = 2 * damping_ratio_for(float(e))
    depth, stretch = np.zeros_like(vt), np.zeros_like(vt)
    touched, done = np.zeros(vt.shape, bool), np.zeros(vt.shape, bool)
    after = [vt.copy(), vn.copy(), spin.copy()]
    dt = 2 * np.pi / steps
    for _ in range(3 * steps):
        push = np.where(touched & (depth <= 0), 0.0, np.maximum(0.0, depth - damping * vn))
        stretch = stretch + (vt + spin) * dt
        trial, cap = -ratio * stretch, mu * push
        sliding = np.abs(trial) > cap
        along = np.where(sliding, np.sign(trial) * cap, trial)
        stretch = np.where(sliding, -along / ratio, stretch)
        vt, spin, vn = vt + along * dt, spin + along / inertia * dt, vn + push * dt
        depth = depth - vn * dt
        touched |= depth > 0
        ends = touched & (depth <= 0) & ~done
        after = [np.where(ends, x, y) for x, y in zip((vt, vn, spin), after, strict=True)]
        done |= ends
        if done.all():
            break
    return after[0] * speed, after[1] * speed, after[2] * speed


def sphere_bounce(v: Any, w: Any, n: Any, radius: float, inertia: float, mu: float, e: float,
                  ratio: float, steps: int = 4000) -> tuple[np.ndarray, np.ndarray]:
    """A sphere's velocity and spin after it bounces on a fixed flat of normal `n`
    (from the flat into the sphere) through the tangentially compliant contact of
    :func:`tangential_bounce`, whatever its spin.

    The bounce is planar: the sphere's tangential mobility is the same in every direction
    across the normal and the spring's stretch starts at zero, so the slip, the stretch
    and the tangential force stay on the line of the first slip, s. Across s nothing
    acts: the centre's velocity across s, the spin's part that moves the touching point
    across s, and the spin about the normal keep their values. Along s the bounce is
    :func:`tangential_bounce`'s, in the plane of n and s; a sphere that meets the flat
    without slipping keeps its tangential motion.

    Examples
    --------
    Straight down at 1 with e = 1/2 and no spin: nothing slips, and it rises at 1/2 to
    the first-order integration's accuracy (0.49974 with 4000 steps a period).

    >>> v, w = sphere_bounce((0, 0, -1), (0, 0, 0), (0, 0, 1), 0.1, 0.4, 0.2, 0.5, 1.0)
    >>> [round(float(x), 3) for x in v], [float(x) for x in w]
    ([0.0, 0.0, 0.5], [0.0, 0.0, 0.0])
    """
    v, w, n = (np.array(x, dtype=float) for x in (v, w, n))
    n = n / np.linalg.norm(n)
    vn = float(v @ n)
    if vn >= 0:
        raise ValueError("the sphere is not approaching the flat")
    v_t = v - vn * n
    spin_slip = radius * np.cross(w, -n)  # the touching point at -R n moves at w x (-R n)
    slip = v_t + spin_slip
    size = float(np.linalg.norm(slip))
    if size == 0.0:  # nothing to stretch the spring: the tangential motion is kept
        s = np.zeros(3)
        along_v = along_w = 0.0
    else:
        s = slip / size
        along_v, along_w = float(v_t @ s), float(spin_slip @ s)
    vt_after, vn_after, turn = tangential_bounce(along_v, vn, along_w, mu, e, ratio, inertia,
                                                 steps)
    v_after = v + (float(vn_after) - vn) * n + (float(vt_after) - along_v) * s
    # the tangential force F s at -R n turns the sphere about (-R n) x s; its slip along
    # s changes by R (w x (-n)) . s, which is turn - along_w
    return v_after, w + (float(turn) - along_w) / radius * np.cross(-n, s)
