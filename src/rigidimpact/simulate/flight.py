"""Free flight after the impact, in closed form, and an exact search for the next contact.

Between impacts no force acts, so every body's centre moves in a straight line and its
orientation turns at a constant rate: positions at any time are written down, never
integrated. What needs care is the *event* — the first time after the impact at which
the ball (a point, as in the paper) meets the other body again. A sampled search can
step over a short crossing, so :func:`first_contact` certifies every gap it skips.

For a point against a rotating segment (a barbell's rod, a uniform rod) the event
function is g(t) = n(t) x p(t): the cross product of the rod's direction with the ball's
position relative to the rod's centre. While the ball is within reach (|p| <= half
length) its rate is bounded by ``D = |omega| R + |u|`` and its second derivative by
``G = omega^2 R + 2 |omega| |u|``. An interval [a, b] is skipped only when
``|g(a)| + |g(b)| > D (b - a)`` (no zero can fit) or when ``|g'(a)| > G (b - a)`` shows g
monotone on it (then a root exists exactly when the signs differ, and Brent's method
finds it). Otherwise it is halved. Round bodies reduce to a quadratic.

Examples
--------
A rod along x turning at a quarter turn a second, and a ball resting above its centre:
the rod is upright, and meets the ball, after one second.

>>> rod = Flyer("rod", "rod", (0.0, 0.0), (0.0, 0.0), math.pi / 2, ends=((-1.0, 0.0), (1.0, 0.0)))
>>> hit = first_contact(Flyer("ball", "particle", (0.0, 0.5), (0.0, 0.0), 0.0), rod)
>>> hit.part, round(hit.t, 12), round(hit.s, 12)
('rod', 1.0, 0.5)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rigidimpact.model.shapes import is_round, is_segment

__all__ = ["Flyer", "Meeting", "first_contact", "reach_interval", "segment_gap"]

END_TOLERANCE = 1e-9  # relative distance from a rod end at which the end sphere is named
REACH_TOLERANCE = 1e-12  # a ball this close outside the rod's circle (relative) is at its end


@dataclass(frozen=True)
class Flyer:
    """One body in free flight, with numbers: where it is at the impact and how it moves.

    Parameters
    ----------
    name, shape : str
        As in the scene.
    position, velocity : pair of float
        Centre of mass at t = 0 (relative to O) and its constant velocity.
    spin : float
        Constant angular velocity, counter-clockwise positive.
    ends : pair of points, optional
        For a barbell or rod: the two ends relative to the centre at t = 0.
    labels : pair of str
        Names of the two ends (``A``, ``B`` for a barbell).
    radius : float
        For a disc, ring or sphere.

    Examples
    --------
    >>> Flyer("b", "particle", (0, 0), (1, 2), 0).at(2.0)
    (array([2., 4.]), 0.0)
    """

    name: str
    shape: str
    position: tuple[float, ...]  # two components
    velocity: tuple[float, ...]
    spin: float
    ends: tuple[tuple[float, ...], ...] | None = None  # two points
    labels: tuple[str, str] = ("end 1", "end 2")
    radius: float = 0.0
    gravity: float = 0.0  # downward (-y) acceleration; every body falls alike
    _p: np.ndarray = field(init=False, repr=False, compare=False)
    _v: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_p", np.asarray(self.position, dtype=float))
        object.__setattr__(self, "_v", np.asarray(self.velocity, dtype=float))

    def at(self, t: float) -> tuple[np.ndarray, float]:
        """Centre position and the angle turned through since the impact, at time `t`."""
        fall = np.array([0.0, -0.5 * self.gravity * t * t])
        return self._p + self._v * t + fall, float(self.spin) * t

    def velocity_at(self, t: float) -> np.ndarray:
        """Centre velocity at time `t`."""
        return self._v + np.array([0.0, -self.gravity * t])

    def ends_at(self, t: float) -> tuple[np.ndarray, ...]:
        """The two ends of a segment body at time `t` (lab frame).

        Examples
        --------
        >>> rod = Flyer("r", "rod", (0, 0), (0, 0), math.pi, ends=((-1, 0), (1, 0)))
        >>> [np.round(p, 12) + 0.0 for p in rod.ends_at(0.5)]
        [array([ 0., -1.]), array([0., 1.])]
        """
        assert self.ends is not None, "only a segment body has ends"
        return tuple(self.carried(q, t) for q in self.ends)

    def carried(self, offset, t: float) -> np.ndarray:
        """Where the body's material point at `offset` from its centre (at t = 0) is at
        time `t` (lab frame).

        Examples
        --------
        >>> Flyer("r", "rigid", (1, 0), (0, 0), math.pi).carried((1, 0), 0.5).round(12) + 0
        array([1., 1.])
        """
        centre, turn = self.at(t)
        c, s = math.cos(turn), math.sin(turn)
        return centre + np.array([c * offset[0] - s * offset[1], s * offset[0] + c * offset[1]])


@dataclass(frozen=True)
class Meeting:
    """The first meeting (a contact) after the impact.

    ``part`` is ``rod`` for a point inside the segment, an end's label (``B``) at an end,
    or ``surface`` for a round body; ``s`` is the signed distance along the segment from
    its centre toward the second end; ``point`` is where it happens (lab frame).
    """

    t: float
    part: str
    point: tuple[float, ...]  # two components
    s: float = 0.0


def reach_interval(p0: np.ndarray, u: np.ndarray, radius: float) -> tuple[float, float] | None:
    """The times t >= 0 at which |p0 + u t| <= radius (a straight line against a circle).

    Examples
    --------
    >>> reach_interval(np.array([-1.0, 0.0]), np.array([1.0, 0.0]), 1.0)
    (0.0, 2.0)
    >>> reach_interval(np.array([-1.0, 2.0]), np.array([1.0, 0.0]), 1.0) is None
    True
    """
    a = float(u @ u)
    b = float(p0 @ u)
    c = float(p0 @ p0) - radius**2
    c = 0.0 if abs(c) <= 1e-12 * radius**2 else c  # on the circle, to rounding
    if a == 0.0:
        return (0.0, math.inf) if c <= 0.0 else None
    disc = b * b - a * c
    if disc < 0.0:
        return None
    root = math.sqrt(disc)
    # the two roots in a form that avoids cancelling b against the square root
    q = -(b + math.copysign(root, b))
    t1, t2 = sorted((q / a, c / q)) if q != 0.0 else (0.0, 0.0)
    if t2 < 0.0:
        return None
    return max(t1, 0.0), t2


def _certified_first_root(g, dg, a: float, b: float, rate: float, curvature: float,
                          tol: float) -> float | None:
    """The first zero of g on [a, b], skipping only intervals proved to hold none."""
    stack = [(a, g(a), b, g(b))]
    while stack:
        lo, g_lo, hi, g_hi = stack.pop()
        if g_lo == 0.0:
            return lo
        width = hi - lo
        if abs(dg(lo)) > curvature * width:  # g monotone here: a root iff a sign change
            if g_lo * g_hi <= 0.0:
                from scipy.optimize import brentq  # scipy on first use

                return brentq(g, lo, hi, xtol=tol, rtol=4 * np.finfo(float).eps)
            continue
        if abs(g_lo) + abs(g_hi) > rate * width:  # g cannot reach zero in between
            continue
        if width <= tol:  # a grazing touch, resolved to the tolerance
            return lo if abs(g_lo) <= abs(g_hi) else hi
        mid = 0.5 * (lo + hi)
        g_mid = g(mid)
        stack.append((mid, g_mid, hi, g_hi))  # the later half is searched last
        stack.append((lo, g_lo, mid, g_mid))
    return None


def segment_gap(ball: Flyer, body: Flyer):
    """The event function g(t) = n(t) x p(t) and its derivative, for a point and a segment.

    Returns ``(g, dg, p0, u, n0, half)``: p is the ball relative to the segment's centre
    and n the unit vector toward the second end.
    """
    assert body.ends is not None, "only a segment body has ends"
    first, second = (np.asarray(q, dtype=float) for q in body.ends)
    if not np.allclose(first, -second, rtol=0.0, atol=1e-12 * np.linalg.norm(second)):
        raise ValueError("the segment must be centred on the body's centre of mass")
    half = float(np.linalg.norm(second))
    n0 = second / half
    if ball.gravity != body.gravity:
        raise ValueError("both bodies must fall alike")
    p0 = ball._p - body._p  # uniform gravity drops out of the relative motion
    u = ball._v - body._v
    w = float(body.spin)
    phi0 = math.atan2(n0[1], n0[0])

    def g(t: float) -> float:
        phi = phi0 + w * t
        return math.cos(phi) * (p0[1] + u[1] * t) - math.sin(phi) * (p0[0] + u[0] * t)

    def dg(t: float) -> float:
        phi = phi0 + w * t
        px, py = p0[0] + u[0] * t, p0[1] + u[1] * t
        return (-w * (math.sin(phi) * py + math.cos(phi) * px)
                + math.cos(phi) * u[1] - math.sin(phi) * u[0])

    return g, dg, p0, u, n0, half


def first_contact(ball: Flyer, body: Flyer, horizon: float = math.inf,
                  tol: float = 1e-14) -> Meeting | None:
    """The first time after t = 0 at which the point `ball` meets `body`, or None.

    `tol` is relative to the time the ball spends within reach of the body.

    Examples
    --------
    >>> disc = Flyer("d", "disc", (1.0, 0.0), (1.0, 0.0), 0.0, radius=1.0)
    >>> first_contact(Flyer("b", "particle", (0, 0), (0.5, 0), 0), disc) is None
    True
    """
    if is_round(body.shape):
        p0, u = ball._p - body._p, ball._v - body._v
        window = reach_interval(p0, u, body.radius)
        if window is None or window[0] == window[1] or window[0] > horizon:
            return None  # a straight path that leaves a circle never re-enters it
        t = window[0]
        return Meeting(t, "surface", tuple(float(c) for c in ball.at(t)[0]))
    if not is_segment(body.shape) or body.ends is None:
        raise ValueError(f"no contact search for a point against a {body.shape}")
    g, dg, p0, u, n0, half = segment_gap(ball, body)
    window = reach_interval(p0, u, half * (1 + REACH_TOLERANCE))
    if window is None:
        return None
    start, stop = window[0], min(window[1], horizon)
    if not stop > start:
        return None
    w = abs(float(body.spin))
    speed = float(np.linalg.norm(u))
    if not math.isfinite(stop):  # the ball sits still relative to the centre
        if w == 0.0:
            return Meeting(start, _part(float(n0 @ p0), half, body.labels),
                           tuple(ball.at(start)[0])) if g(start) == 0.0 else None
        stop = start + 2 * math.pi / w  # the rod sweeps every direction within one turn
    rate = w * half + speed
    curvature = w * w * half + 2 * w * speed
    if abs(g(start)) <= 1e-15 * half:  # touching now (the impact itself): step clear of it
        slope = dg(start)
        if slope == 0.0:
            return Meeting(start, _part(float(n0 @ p0), half, body.labels),
                           tuple(ball.at(start)[0]))
        start += abs(slope) / curvature  # |g| >= |g'| t - G t^2/2 > 0 until here
        if start >= stop:
            return None
    root = _certified_first_root(g, dg, start, stop, rate, curvature,
                                 tol * max(stop - start, 1.0) if math.isfinite(stop) else tol)
    if root is None:
        return None
    t = root
    where = ball.at(t)[0]
    phi = math.atan2(n0[1], n0[0]) + float(body.spin) * t
    n = np.array([math.cos(phi), math.sin(phi)])
    s = float(n @ (where - body.at(t)[0]))
    return Meeting(t, _part(s, half, body.labels), (float(where[0]), float(where[1])), s)


def _part(s: float, half: float, labels: tuple[str, str]) -> str:
    if abs(s) >= half * (1 - END_TOLERANCE):
        return labels[1] if s > 0 else labels[0]
    return "rod"
