"""One rough contact in three dimensions: Coulomb's circular cone, followed in the normal
impulse.

Everything happens in contact space. The contact's frame is its unit normal n and two
unit tangents t1, t2 (n, t1, t2 right-handed; :func:`tangents` says which). ``v`` is the
velocity of the second body's touching point less the first's, in that frame
(``v[0] < 0``: approaching), and the impulse ``P`` on the second body (the first gets
``-P``) changes it by ``dv = W P``, with ``W = J M^-1 J^T`` the contact's 3 x 3 block.

Stronge's formulation (Impact Mechanics, ch. 5) takes the normal impulse p as the
clock. While the touching points slip with unit direction ``s = v_t / |v_t|``, the
tangential impulse grows as ``dP_t = -mu s dp``, so

    dv/dp = W (1, -mu s)

and s may turn: it stays put only when the tangential block of W is isotropic
(``W_tt = w I``) and uncoupled from the normal (``W_tn = 0``), as for a sphere on a plane
or two spheres. Where the slip stops, the contact sticks if the tangential impulse rate
that holds it, ``r = -W_tt^-1 W_tn``, lies inside the cone (``|r| <= mu``); otherwise it
slips again at once, in the direction ``s`` that the equations give (``W_tn - mu W_tt s``
parallel to s, pointing along it). The normal velocity passes through zero at the end
of compression, p = p_c, and the impact ends by the restitution law:

- Newton's: when ``v_n = -e v_n(0)``;
- Poisson's: at ``p = (1 + e) p_c``;
- the energetic law: when the normal impulse's work in restitution is ``e^2`` times its
  work in compression (``int v_n dp``).

Where the block is isotropic and uncoupled the three laws agree (the normal motion does
not feel friction) and the answer is in closed form, with symbols as a ``Piecewise``:
the contact slides throughout when ``|v_t(0)| >= mu w p_f`` and sticks otherwise, with
``p_f = (1 + e) p_c``. Elsewhere the path is integrated numerically with a stated
tolerance; the result says where the slip direction turned and by how much.

Examples
--------
A solid sphere (m = 1, radius 1, I = 2/5) landing on a floor, its touching point
slipping at (2, 7/2) and approaching at 2, Newton's e = 1/2, mu = 1/5: the floor's W is
diag(1, 7/2, 7/2), p_f = 3, and mu w p_f = 21/10 < |v_t| = sqrt(65)/2, so it slides
throughout:

>>> W = sp.diag(1, sp.Rational(7, 2), sp.Rational(7, 2))
>>> from rigidimpact.laws.law import NewtonRestitution
>>> out = cone_impact(W, (-2, 2, sp.Rational(7, 2)), NewtonRestitution(sp.Rational(1, 2)),
...                   sp.Rational(1, 5))
>>> out.course, out.impulse.T
('slides throughout', Matrix([[3, -12*sqrt(65)/325, -21*sqrt(65)/325]]))
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.symbolic.notation import Given

if TYPE_CHECKING:  # numpy is imported where a path is integrated
    import numpy as np

__all__ = ["ConeImpact", "cone_impact", "tangents", "isotropic", "one_line",
           "TOLERANCE"]

TOLERANCE = 1e-10  # the integration's relative tolerance unless one is given
MAX_PHASES = 50  # slip, stick and slip again: more changes than this are refused


@dataclass(frozen=True)
class ConeImpact:
    """What one rough 3-D contact gives.

    impulse : (P_n, P_t1, P_t2) on the second body, in the contact frame.
    velocity_after : the touching points' relative velocity after, contact frame.
    course : "slides throughout", "sticks", "slides, then sticks at p = ..." and the like.
    exact : whether the answer is a closed form (else integrated, to `tolerance`).
    turned : the angle (radians) through which the slip direction turned while slipping.
    phases : (kind, p at its start) for each phase ("slip" or "stick").
    """

    impulse: sp.Matrix
    velocity_after: sp.Matrix
    course: str
    exact: bool
    turned: float = 0.0
    phases: tuple[tuple[str, float], ...] = ()
    tolerance: float | None = None
    steps: int = 0


def tangents(normal: Sequence[Any]) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """The contact frame (n, t1, t2) of a normal: n its unit vector; t1 the unit vector
    along the part of the x axis across n (the y axis's, when n lies along x); t2 = n x t1.

    Examples
    --------
    >>> [list(t) for t in tangents((0, 0, 1))]
    [[0, 0, 1], [1, 0, 0], [0, 1, 0]]
    >>> [list(t) for t in tangents((2, 0, 0))]
    [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    """
    n = sp.Matrix(normal)
    n = n / sp.sqrt(n.dot(n))
    n = n.applyfunc(sp.radsimp)
    for axis in (sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0])):
        across = axis - axis.dot(n) * n
        size = sp.sqrt(sp.simplify(across.dot(across)))
        if not size.is_zero:
            t1 = (across / size).applyfunc(sp.radsimp)
            return n, t1, n.cross(t1).applyfunc(sp.radsimp)
    raise InputError("contact.normal", "must not be the zero vector")


def isotropic(W: sp.Matrix) -> bool:
    """Whether the tangential block of W is a multiple of the identity and uncoupled from
    the normal: then the slip direction cannot turn."""
    gaps = (W[0, 1], W[0, 2], W[1, 2], W[1, 1] - W[2, 2])
    if all(x.is_number for x in W) and any(x.has(sp.Float) for x in W):
        # floating point (a cut angle's cosine): zero to the arithmetic's rounding
        size = max(abs(float(x)) for x in W)
        return all(abs(float(x)) <= 1e-12 * size for x in gaps)
    return all(sp.simplify(x) == 0 for x in gaps)


def cone_impact(W: sp.Matrix, v: Sequence[Any], law: Any, mu: Any,
                tolerance: float | None = None) -> ConeImpact:
    """The impulse of one rough contact (Coulomb's circular cone, coefficient `mu`) under
    the restitution `law`, an object (its :meth:`leaving` and :meth:`end_event`, so a
    user's law is followed as it asks); see the module's text.

    In closed form where the tangential block of W is isotropic and uncoupled (and no
    `tolerance` is asked); otherwise integrated in the normal impulse with relative
    `tolerance` (default :data:`TOLERANCE`), in floating point.
    """
    W = sp.Matrix(W)
    v0 = sp.Matrix(list(v))
    if W.shape != (3, 3) or v0.shape != (3, 1):
        raise ValueError("a 3-D contact has a 3 x 3 W and a 3-vector v")
    if v0[0].is_number and not v0[0] < 0:
        raise InputError("bodies", "the touching points are not approaching")
    if tolerance is None and isotropic(W):
        # the normal is uncoupled: its velocity is linear in the normal impulse whatever
        # the slip does, so every law ends where the velocity reaches the law's target
        target = law.leaving(v0[0])
        return _closed_form(W, v0, target, sp.sympify(mu))
    back = sp.sympify(law.leaving(sp.Integer(-1)))  # the law's rebound at unit speed
    numbers = [*W, *v0, back, mu]
    if not all(sp.sympify(x).is_number for x in numbers):
        raise InputError("values", "the slip direction of this contact may turn during the "
                         "impact (its tangential block of W is not isotropic, or it is "
                         "coupled to the normal): it is followed numerically, so give numbers")
    import numpy as np  # only where the path is integrated: the command line starts light

    return _integrated(np.array(W.evalf(30), dtype=float),
                       np.array(v0.evalf(30), dtype=float).ravel(), float(back), law,
                       float(mu), TOLERANCE if tolerance is None else float(tolerance))


def one_line(W: sp.Matrix, v: sp.Matrix) -> sp.Matrix | None:
    """The unit direction in the tangent plane to which the slip keeps throughout the
    impact, where there is one at numbers: the slip before (or, with none, the way the
    normal impulse drives it) along which the normal impulse's coupling lies and which
    the tangential block W_tt keeps. None where the slip may turn (or with symbols)."""
    if not all(sp.sympify(x).is_number for x in (*W, *v)):
        return None
    slip, coupling, block = sp.Matrix(v[1:, 0]), sp.Matrix(W[1:, 0]), sp.Matrix(W[1:, 1:])
    size = max(abs(sp.N(x, 30)) for x in W)
    uncoupled = all(abs(sp.N(x, 30)) <= 1e-12 * size for x in coupling)
    if uncoupled and (isotropic(W) or all(x == 0 for x in slip)):
        return None  # the normal uncoupled, a sphere's (or nothing slips): the closed form
    direction = slip if any(x != 0 for x in slip) else coupling

    def along(a: sp.Matrix, b: sp.Matrix) -> bool:
        """a and b on one line: exactly, or in floats to rounding's size."""
        cross = a[0] * b[1] - a[1] * b[0]
        if not (a.has(sp.Float) or b.has(sp.Float)):
            return sp.simplify(cross) == 0
        return bool(abs(sp.N(cross, 30)) <= 1e-12 * sp.N(a.norm() * b.norm(), 30))

    if not ((uncoupled or along(direction, coupling)) and along(direction, block * direction)):
        return None
    return (direction / sp.sqrt(direction.dot(direction))).applyfunc(sp.radsimp)


def _closed_form(W: sp.Matrix, v0: sp.Matrix, target: sp.Expr, mu: sp.Expr) -> ConeImpact:
    w_n, w_t = W[0, 0], W[1, 1]
    p_final = (target - v0[0]) / w_n  # the three laws agree: the normal is uncoupled
    slip = sp.Matrix(v0[1:])
    speed = sp.sqrt(sp.expand(slip.dot(slip)))
    course: str
    if speed.is_zero:
        tangential, course = sp.zeros(2, 1), "sticks"
    else:
        slides = sp.simplify(sp.Le(mu * w_t * p_final, speed))
        slide, stick = -mu * p_final * slip / speed, -slip / w_t
        if slides == sp.true:
            tangential, course = slide, "slides throughout"
        elif slides == sp.false:
            tangential, course = stick, "slides, then sticks"
        else:
            tangential = sp.Matrix([sp.Piecewise((a, slides), (b, True))
                                    for a, b in zip(slide, stick, strict=True)])
            course = Given("slides throughout where {}; otherwise slides, then sticks", slides)
    impulse = sp.Matrix([p_final, *tangential]).applyfunc(sp.radsimp)
    after = (v0 + W * impulse).applyfunc(lambda x: sp.piecewise_fold(sp.radsimp(x)))
    return ConeImpact(impulse, after, course, exact=True)


def _integrated(W: np.ndarray, v0: np.ndarray, back: float, law: Any, mu: float,
                tolerance: float) -> ConeImpact:
    """Follow the path in p with scipy's solve_ivp (DOP853), phase by phase."""
    import numpy as np
    from scipy.integrate import solve_ivp

    w_nn, w_tn, W_tt = W[0, 0], W[1:, 0], W[1:, 1:]
    scale = float(np.abs(v0).max())
    p_c_guess = -v0[0] / w_nn
    floor = tolerance * scale  # a slip speed below this is zero (the integration's error)

    def slipping(_p: float, y: np.ndarray) -> np.ndarray:
        v = y[:3]
        s = v[1:] / np.linalg.norm(v[1:])
        rate = W @ np.concatenate([[1.0], -mu * s])
        return np.concatenate([rate, -mu * s, [v[0]]])

    def sticking_rate() -> np.ndarray | None:
        r = -np.linalg.solve(W_tt, w_tn)
        return r if np.linalg.norm(r) <= mu * (1 + 1e-12) else None

    def resumed_direction() -> np.ndarray:
        """The unit s with W_tn - mu W_tt s along +s (slip starting from rest)."""
        angles = np.linspace(0, 2 * np.pi, 721)
        best, value = 0.0, -np.inf
        for a in angles:
            s = np.array([math.cos(a), math.sin(a)])
            d = w_tn - mu * W_tt @ s
            along = d @ s - abs(d[0] * s[1] - d[1] * s[0])
            if along > value:
                best, value = a, along
        from scipy.optimize import brentq

        def across(a: float) -> float:
            s = np.array([math.cos(a), math.sin(a)])
            d = w_tn - mu * W_tt @ s
            return float(d[0] * s[1] - d[1] * s[0])
        lo, hi = best - 0.01, best + 0.01
        if across(lo) * across(hi) < 0:
            best = brentq(across, lo, hi, xtol=1e-15)
        return np.array([math.cos(best), math.sin(best)])

    def stuck(r: np.ndarray):
        def rates(_p: float, y: np.ndarray) -> np.ndarray:
            rate = W @ np.concatenate([[1.0], r])
            rate[1:] = 0.0
            return np.concatenate([rate, r, [y[0]]])
        return rates

    # the end of the impact: the law's own (laws.ends, one implementation a law)
    end = law.end_event(float(v0[0]))

    def ends(p: float, y: np.ndarray, p_c: float | None, work_c: float | None) -> float:
        return end(p, float(y[0]), p_c, work_c, float(y[5]))

    y = np.concatenate([v0, [0.0, 0.0, 0.0]])  # v (3), P_t (2), the normal work
    p, p_c, work_c = 0.0, None, None
    phases: list[tuple[str, float]] = []
    turned, steps = 0.0, 0
    kind = "slip" if np.linalg.norm(v0[1:]) > floor else "stick-test"
    horizon = 10 * (1 + back) * max(p_c_guess, 1e-300) + 10
    # the slip's stop is seen as its component along a reference direction reaching
    # zero; the reference is renewed whenever the slip has turned 60 degrees from it, so
    # that component stays at least half the slip speed until the slip really stops
    reference = np.zeros(2)
    for _ in range(MAX_PHASES * 20):
        if kind == "stick-test":
            r = sticking_rate()
            if r is not None:
                kind, rhs = "stick", stuck(r)
                phases.append(("stick", p))
            else:
                s = resumed_direction()
                y = y.copy()
                y[1:3] = floor * 10 * s  # slip starts along s
                kind = "slip"
                phases.append(("slip", p))
        elif not phases:
            phases.append((kind, p))
        if kind == "slip":
            rhs = slipping
            reference = y[1:3] / np.linalg.norm(y[1:3])

        def compression(_p: float, yy: np.ndarray) -> float:
            return yy[0]

        def finish(pp: float, yy: np.ndarray, p_c: float | None = p_c,
                   work_c: float | None = work_c) -> float:
            return ends(pp, yy, p_c, work_c)

        def stops(_p: float, yy: np.ndarray, ref: np.ndarray = reference) -> float:
            return float(yy[1:3] @ ref)

        def turns(_p: float, yy: np.ndarray, ref: np.ndarray = reference) -> float:
            return float(yy[1:3] @ ref - 0.5 * np.linalg.norm(yy[1:3]))

        events: list[Any] = [finish, compression] if p_c is None else [finish]
        if kind == "slip":
            events += [stops, turns]
        for ev in events:
            ev.terminal = True  # type: ignore[attr-defined]
        finish.direction = 1.0  # type: ignore[attr-defined]
        compression.direction = 1.0  # type: ignore[attr-defined]
        stops.direction = -1.0  # type: ignore[attr-defined]
        turns.direction = -1.0  # type: ignore[attr-defined]
        run = solve_ivp(rhs, (p, p + horizon), y, method="DOP853", rtol=tolerance,
                        atol=tolerance * scale * 1e-3, events=events, dense_output=True)
        steps += len(run.t)
        if kind == "slip":  # the turn while slipping (not the flip as the slip stops)
            dense = run.sol(np.linspace(run.t[0], run.t[-1], 400))[1:3]
            norms = np.linalg.norm(dense, axis=0)
            kept = norms > 100 * floor
            if kept.sum() > 1:
                s_path = dense[:, kept] / norms[kept]
                angles = np.unwrap(np.arctan2(s_path[1], s_path[0]))
                turned += float(abs(angles[-1] - angles[0]))
        p, y = float(run.t[-1]), run.y[:, -1]
        fired = {ev.__name__ for ev, t in zip(events, run.t_events, strict=True) if len(t)}
        if "finish" in fired:  # the restitution law ends the impact
            break
        if "compression" in fired:
            p_c, work_c = p, y[5]
            if ends(p, y, p_c, work_c) >= 0:
                break
            continue  # the same phase goes on past the end of compression
        if "stops" in fired or ("turns" in fired and np.linalg.norm(y[1:3]) <= 10 * floor):
            kind = "stick-test"
            continue
        if "turns" in fired:
            continue  # a new reference direction, the same slip
        raise InputError("impact", "the rough contact's impulse did not end within its "
                         "horizon; please report the scene")
    else:
        raise InputError("impact", f"the contact changed between slip and stick more than "
                         f"{MAX_PHASES} times; please report the scene")
    impulse = sp.Matrix([sp.Float(p, 17), sp.Float(y[3], 17), sp.Float(y[4], 17)])
    after = sp.Matrix([sp.Float(x, 17) for x in v0 + W @ np.array([p, y[3], y[4]])])
    kinds = [k for k, _ in phases]
    if kinds == ["slip"]:
        course = "slides throughout"
    elif kinds == ["stick"]:
        course = "sticks"
    else:
        course = ", then ".join(
            f"{'slides' if k == 'slip' else 'sticks'}{' again' if k == 'slip' and i else ''}"
            f" from p = {q:.6g}" for i, (k, q) in enumerate(phases))
    return ConeImpact(impulse, after, course, exact=False, turned=turned,
                      phases=tuple(phases), tolerance=tolerance, steps=steps)
