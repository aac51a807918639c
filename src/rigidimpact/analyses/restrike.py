r"""After the impact: does the barbell strike the ball again, and where is the critical angle?

Section 2 of Mungan (Eur. J. Phys. 28, 2007) states without derivation that after a
perfectly inelastic impact (e = 0) the barbell comes round and hits the ball from behind
whenever the initial angle is below a critical theta_c with tan(theta_c) = 1/(pi - theta_c).
Here that condition is derived from the free flight that follows the solved impact, and
extended to any e and mass ratio.

The argument, in the frame that moves with the barbell's centre C. Measure time by the
angle the rod has turned, tau = omega t. The ball, a point, then moves on a straight line
``p(tau) = L (-cos(theta) + k tau sin(theta), -sin(theta))`` whose drift rate k comes out
of the impact as ``k = 1 - e/(f sin^2 theta)``. The rod (half-length L either side of C)
can only touch the ball while |p| <= L, which holds for tau between 0 and the exit turn
``T = 2 cot(theta)/k``; the ball then leaves at the direction -theta. The polar angle of
the ball about C changes at ``k L^2 sin^2(theta)/|p|^2 <= k`` while the rod turns at 1, so
the angle between them grows monotonically from -pi (the ball at sphere A): the first
part to come round is the B half of the rod, and it reaches the ball before it escapes
exactly when ``T >= 2 (pi - theta)``, the turn that brings B to the exit direction. For
e = 0, k = 1 and the condition is ``cot(theta) >= pi - theta``: tan(theta_c) = 1/(pi - theta_c),
free of m/M, with sphere B arriving just as the ball leaves at the critical angle.

Multiplying the condition by ``k^2 sin(theta)/2 >= 0`` gives a form that also covers k <= 0,
``W = k cos(theta) - (pi - theta) k^2 sin(theta) >= 0``. The numerator of W factors into
``m sin^2(theta) - e (m + 2M)`` (k = 0: the ball at rest relative to C, with closed-form roots)
and a transcendental factor whose roots are the generalised critical angles; its
denominator is positive on (0, pi). The windows of angles with a re-strike are where the
product of the factors has the right sign.

Examples
--------
>>> result = critical_angle()
>>> mpmath.nstr(result.theta_c_deg, 20)
'19.664290128280113773'
>>> [[round(float(x), 6) for x in w] for w in result.windows_deg]
[[0.0, 19.66429]]
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING

import mpmath
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred
from rigidimpact.paper import problems
from rigidimpact.paper.published import CRITICAL_ANGLE_EQUATION, F
from rigidimpact.symbolic.compare import Verdict, agree, symbolic_zero
from rigidimpact.symbolic.expr import parse_expression
from rigidimpact.symbolic.notation import symbol
from rigidimpact.symbolic.rewrite import polynomial_roots, tidy

if TYPE_CHECKING:
    import numpy as np
else:  # the sweeps and frames alone use it: verify and the critical angle need none
    np = deferred("numpy")

__all__ = ["Restrike", "derive", "Edge", "CriticalAngle", "critical_angle", "windows",
           "restrike_turn", "sweep", "Sweep", "restrike_map", "strobe_frames", "DIGITS"]

DIGITS = 40  # working precision of the window edges; 30 are promised, 10 are guard digits
ENDS = mpmath.mpf(10) ** -12  # edges closer than this to 0 or pi (radians) are not resolved
CERTIFY = mpmath.mpf(10) ** -(DIGITS + 2)  # an edge's sign change is shown this close
GRID, END_GRID = 2048, 200  # scan points across (0, pi), and toward each end
m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
tau = symbol("tau")


@dataclass(frozen=True)
class Restrike:
    """The re-strike condition, derived from the motion after the section 1 impact.

    Parameters
    ----------
    drift : Expr
        k: the ball's speed relative to C along x, over omega L sin(theta).
    relative_position : ImmutableMatrix
        p(tau), the ball relative to C, as the rod turns through tau.
    exit_turn : Expr
        T: the turn after which the ball is out of the rod's reach for good.
    meet_turn : Expr
        The turn that brings sphere B to the direction where the ball leaves.
    condition : Expr
        ``T - meet_turn``; a re-strike when it is >= 0 (with T > 0).
    window : Expr
        ``W``, the condition times ``k^2 sin(theta)/2``, valid for every sign of k.
    factors : tuple of (Expr, int)
        W's numerator as ``sign * prod(factors)``: ``factors[0]`` is the k = 0 factor,
        ``factors[1]`` the transcendental one.
    sign : int
    critical : Expr
        The condition at e = 0.
    seconds : float
    """

    drift: sp.Expr
    relative_position: sp.ImmutableMatrix
    exit_turn: sp.Expr
    meet_turn: sp.Expr
    condition: sp.Expr
    window: sp.Expr
    factors: tuple[sp.Expr, ...]
    sign: int
    critical: sp.Expr
    seconds: float


@functools.cache
def derive() -> Restrike:
    """Derive the re-strike condition from the free flight after the impact.

    Examples
    --------
    >>> derive().drift
    -(2*M*e + e*m - m*sin(theta)**2)/(m*(e + 1)*sin(theta)**2)
    >>> derive().critical
    2*(theta*sin(theta) - pi*sin(theta) + cos(theta))/sin(theta)
    """
    start = time.perf_counter()
    solved = problems.barbell().solution
    assert solved is not None  # a built-in problem keeps its solved impact
    ball, bar = solved.first_after, solved.second_after
    omega = bar.spin
    # free flight from the impact: straight lines and a steady turn; t = tau/omega
    t_of_tau = tau / omega
    ball_at = ball.position + ball.velocity * t_of_tau
    centre_at = bar.position + bar.velocity * t_of_tau
    p = sp.ImmutableMatrix([tidy(c) for c in ball_at - centre_at])
    drift = tidy(sp.diff(p[0], tau) / (L * sp.sin(theta)))
    reach = sp.Poly(sp.expand(p.dot(p) - L**2), tau)
    c2, c1, c0 = reach.all_coeffs()
    if tidy(c0) != 0:
        raise ArithmeticError("the ball should start on the rod's circle of reach")
    exit_turn = tidy(-c1 / c2)
    meet_turn = 2 * (sp.pi - theta)
    condition = exit_turn - meet_turn
    window = tidy(condition * drift**2 * sp.sin(theta) / 2)
    numerator, denominator = sp.fraction(sp.together(window))
    _require_positive(denominator)
    sign, factors = sp.factor_list(numerator)
    factors = sorted((f for f, _ in factors), key=lambda f: f.has(sp.cos))
    return Restrike(drift, p, exit_turn, meet_turn, condition, window, tuple(factors),
                    int(sp.sign(sign)), tidy(condition.subs(e, 0)),
                    time.perf_counter() - start)


def _require_positive(expr: sp.Expr) -> None:
    """Every factor is positive by assumption, or an odd power of sin(theta) on (0, pi)."""
    for factor, power in sp.factor_list(expr)[1]:
        if factor.is_positive or factor == sp.sin(theta) or power % 2 == 0:
            continue
        raise ArithmeticError(f"cannot show the denominator factor {factor} is positive")


def _split_critical(factor: sp.Expr) -> sp.Equality:
    """Write the transcendental factor as ``A(theta) = (pi - theta) B(theta)``."""
    s, c, x = sp.Dummy("s"), sp.Dummy("c"), sp.Dummy("x")
    plain = sp.Poly(factor.xreplace({sp.sin(theta): s, sp.cos(theta): c}).subs(theta, x), x)
    if plain.degree() != 1:
        raise ArithmeticError(f"expected a factor linear in the bare angle: {factor}")
    b, a = plain.all_coeffs()
    back = {s: sp.sin(theta), c: sp.cos(theta)}
    lhs = sp.factor((a + b * sp.pi).xreplace(back))
    rhs = sp.factor(b.xreplace(back))
    if lhs.could_extract_minus_sign() and rhs.could_extract_minus_sign():
        lhs, rhs = -lhs, -rhs
    return sp.Eq(lhs, (sp.pi - theta) * rhs, evaluate=False)


def _parameters(restitution: Fraction, mass_ratio: Fraction) -> dict[sp.Symbol, sp.Expr]:
    return {e: sp.Rational(restitution), m: sp.Rational(mass_ratio), M: sp.Integer(1)}


@dataclass(frozen=True)
class Edge:
    """One end of a window of initial angles with a re-strike.

    ``kind`` is ``"limit"`` (0 or 180 degrees), ``"at rest"`` (k = 0: the ball keeps still
    relative to C and sphere B meets it after half a turn) or ``"outrace"`` (the
    generalised critical angle: B arrives just as the ball leaves its reach).
    """

    rad: mpmath.mpf
    kind: str
    equation: sp.Equality | None

    @property
    def deg(self) -> mpmath.mpf:
        with mpmath.workdps(DIGITS + 10):
            return self.rad * 180 / mpmath.pi


@dataclass(frozen=True)
class CriticalAngle:
    """The re-strike analysis for one restitution and mass ratio.

    ``theta_c`` is the upper end of the lowest window when that end is an ``outrace``
    edge (the paper's critical angle at e = 0), else None.
    """

    restitution: Fraction
    mass_ratio: Fraction
    theta_c: mpmath.mpf | None
    equation: sp.Equality
    windows: tuple[tuple[Edge, Edge], ...]

    @property
    def theta_c_deg(self) -> mpmath.mpf | None:
        with mpmath.workdps(DIGITS + 10):
            return None if self.theta_c is None else self.theta_c * 180 / mpmath.pi

    @property
    def windows_deg(self) -> list[list[mpmath.mpf]]:
        return [[lo.deg, hi.deg] for lo, hi in self.windows]


def _checked(restitution, mass_ratio) -> tuple[Fraction, Fraction]:
    """e and m/M as exact fractions (``"0.3"`` is 3/10), each bounded as scene numbers."""

    exact = []
    for value, where in ((restitution, "--e"), (mass_ratio, "--mass-ratio")):
        if isinstance(value, Fraction):
            value = f"{value.numerator}/{value.denominator}"
        number = parse_expression(value, where)
        if not number.is_Rational:
            raise InputError(where, f"must be a rational number such as 0.3 or 1/3, got "
                             f"{value!r}")
        exact.append(Fraction(int(number.p), int(number.q)))
    e_value, r_value = exact
    if not 0 <= e_value <= 1:
        raise InputError("--e", f"the restitution coefficient must lie in [0, 1], got "
                         f"{restitution}")
    if not r_value > 0:
        raise InputError("--mass-ratio", f"m/M must be positive, got {mass_ratio}")
    return e_value, r_value


def _grid(lo: mpmath.mpf, hi: mpmath.mpf) -> list[mpmath.mpf]:
    """Uniform in the middle, geometric toward both ends (where roots can crowd)."""
    middle = [lo + (hi - lo) * j / GRID for j in range(1, GRID)]
    near = [mpmath.mpf(10) ** (-3 - 9 * j / END_GRID) for j in range(END_GRID + 1)]
    if (hi - lo) / GRID <= near[0]:  # the ends' points reach into the middle's
        return sorted(set([lo + x for x in near] + middle + [hi - x for x in near]))
    # else in order as made (near falls from 1e-3 to 1e-12, within the middle's first
    # and last step), so no sort of 2,600 multiprecision numbers is needed
    return [lo + x for x in reversed(near)] + middle + [hi - x for x in near]


def _scale(expr: sp.Expr) -> sp.Expr:
    """The expression with every sum's terms in absolute value: the size it is made of."""
    return expr.replace(lambda n: isinstance(n, sp.Add),
                        lambda n: sp.Add(*(sp.Abs(t) for t in n.args)))


def _bisect(f, a: mpmath.mpf, b: mpmath.mpf, width: mpmath.mpf) -> mpmath.mpf:
    """A root of `f` in [a, b] (where f changes sign) by halving down to `width`."""
    fa = f(a)
    while b - a > width:
        mid = (a + b) / 2
        fm = f(mid)
        if fm == 0:
            return mid
        if (fm > 0) == (fa > 0):
            a, fa = mid, fm
        else:
            b = mid
    return (a + b) / 2


def _certified(f, r: mpmath.mpf, a: mpmath.mpf, b: mpmath.mpf) -> mpmath.mpf:
    """`r` if f provably changes sign within ``CERTIFY`` (relative) of it, else the root
    found by bisection of [a, b]; either way the printed digits are right."""
    delta = abs(r) * CERTIFY
    noise = mpmath.mpf(10) ** (-(DIGITS + 5))
    if a < r - delta and r + delta < b:
        left, right = f(r - delta), f(r + delta)
        if left * right < 0 and min(abs(left), abs(right)) > noise:
            return r
    root = _bisect(f, a, b, delta)
    left, right = f(root - delta), f(root + delta)
    if not (left * right < 0 and min(abs(left), abs(right)) > noise):
        raise InputError("--mass-ratio", "the edge of a window cannot be certified to the "
                         "digits printed at this e and mass ratio (the condition is too flat "
                         "there)")
    return root


def _roots(expr: sp.Expr, lo: mpmath.mpf, hi: mpmath.mpf) -> list[mpmath.mpf]:
    """The roots of `expr` (a function of theta) in (lo, hi).

    The factor is divided by its scale (``_scale``), so its size does not depend on m/M
    (a factor of size 1e-80 would otherwise pass any absolute tolerance at once). It is
    scanned on a grid (dense toward the ends, where a root can sit within a hair of 0 or
    pi); a sign change is a simple root, refined by a bracketing solver and then
    certified: the sign must change within ``CERTIFY`` of the root (relative), or the
    root is found by bisection instead. Where |f| has a local minimum without a sign
    change, the derivative's root there is found and, if f changes sign at it, both roots
    of the pair are taken. Roots closer than ``ENDS`` to the ends are not resolved.
    """
    # a root at an end (pi always, for the outrace factor: there the ball is struck where
    # it stands) is divided out, to its order: so a multiple root there (order 5 where
    # e (1 + 2M/m) = 1 + e) leaves a factor that is not flat, and the digits that the
    # division cancels near the end are worked with
    orders = [_order_at(expr, end) for end in (lo, hi)]
    ends = (theta - _sp_value(lo)) ** orders[0] * (_sp_value(hi) - theta) ** orders[1]
    reduced = expr / (_scale(expr) * ends)
    with mpmath.workdps(mpmath.mp.dps + 12 * sum(orders)):
        return _scan(sp.lambdify(theta, reduced, modules="mpmath"),
                     sp.lambdify(theta, sp.diff(reduced, theta) /
                                 _scale(sp.diff(expr, theta) / ends), modules="mpmath"),
                     lo, hi, _quick(reduced, orders))


# the scan reads a grid point's sign in double precision where that sign is sure: the
# reduced factor is at most 1 in size (divided by its scale), so its rounding error is
# about 1e-16 over what dividing out the ends' roots amplifies; a point is read so only
# where that division is at least QUICK_ENDS and the value QUICK_SIZE or more (a
# margin of about 1e7), every other point (near a root, near an end) at full precision
QUICK_ENDS, QUICK_SIZE = 1e-3, 1e-6


def _quick(reduced: sp.Expr, orders: Sequence[int]) -> Callable[[float], float | None]:
    """The reduced factor's sign-sure value in double precision at a point, None where
    it is not sure (:data:`QUICK_SIZE`, :data:`QUICK_ENDS`)."""
    value = sp.lambdify(theta, reduced, modules="math")
    a, b = orders

    def sure(x: float) -> float | None:
        if x ** a * (math.pi - x) ** b < QUICK_ENDS:
            return None
        try:
            y = value(x)
        except (ArithmeticError, ValueError):
            return None
        return y if math.isfinite(y) and abs(y) >= QUICK_SIZE else None

    return sure


def _sp_value(x: mpmath.mpf) -> sp.Expr:
    """0 and pi exactly (the ends of the scan)."""
    return sp.Integer(0) if x == 0 else sp.pi


def _order_at(expr: sp.Expr, end: mpmath.mpf) -> int:
    """The order of the root of `expr` at an end of (0, pi), 0 where it has none.

    Examples
    --------
    >>> _order_at(sp.sin(theta) ** 3, mpmath.pi)
    3
    """
    at = _sp_value(end)
    derivative = expr
    for order in range(12):  # the first derivative not zero there (no series needed)
        if order:
            derivative = sp.diff(derivative, theta)
        value = derivative.subs(theta, at)
        if not _zero(value):
            return order
    raise InputError("--e", "the re-strike condition vanishes to 12th order at an end "
                     "of (0, 180) degrees: its windows there cannot be told apart")


def _zero(value: sp.Expr) -> bool:
    """Whether a number is zero: nonzero where 60 digits show it, else by SymPy's
    simplification (a sum of sines at 0 or pi that cancels)."""
    number = sp.N(value, 60)
    if number.is_number and number != 0 and abs(number) > sp.Float(10) ** -45:
        return False
    return sp.simplify(value) == 0


def _scan(f, df, lo: mpmath.mpf, hi: mpmath.mpf,
          quick: Callable[[float], float | None] | None = None) -> list[mpmath.mpf]:
    xs = _grid(lo, hi)

    def at(x: mpmath.mpf) -> mpmath.mpf:
        sure = quick(float(x)) if quick is not None else None
        return f(x) if sure is None else mpmath.mpf(sure)

    ys = [at(x) for x in xs]
    found: list[mpmath.mpf] = []

    def bracketed(a, b):
        try:
            guess = mpmath.findroot(f, (a, b), solver="anderson")
        except (ValueError, ZeroDivisionError):
            guess = (a + b) / 2
        return _certified(f, guess if a <= guess <= b else (a + b) / 2, a, b)

    for j in range(len(xs) - 1):
        if ys[j] == 0:
            found.append(xs[j])
        elif ys[j] * ys[j + 1] < 0:
            found.append(bracketed(xs[j], xs[j + 1]))
        elif 0 < j and abs(ys[j]) < abs(ys[j - 1]) and abs(ys[j]) < abs(ys[j + 1]):
            a, b = xs[j - 1], xs[j + 1]
            if df(a) * df(b) >= 0:
                continue
            try:
                turning = mpmath.findroot(df, (a, b), solver="anderson")
            except (ValueError, ZeroDivisionError):
                turning = _bisect(df, a, b, abs(a) * CERTIFY)
            if not a < turning < b:
                turning = _bisect(df, a, b, abs(a) * CERTIFY)
            if f(turning) == 0 or abs(f(turning)) < mpmath.mpf(10) ** (-DIGITS):
                found.append(turning)  # touching: an edge of zero width
            elif f(turning) * ys[j] < 0:
                found += [bracketed(a, turning), bracketed(turning, b)]
    merged: list[mpmath.mpf] = []
    tiny = mpmath.mpf(10) ** (-DIGITS + 5)
    for r in sorted(found):
        if lo + ENDS < r < hi - ENDS and (not merged or r - merged[-1] > tiny):
            merged.append(r)
    return merged


@functools.cache
def _analysis(restitution: Fraction, mass_ratio: Fraction) -> CriticalAngle:
    d = derive()
    at = _parameters(restitution, mass_ratio)
    factors = [f.subs(at) for f in d.factors]
    outrace = _critical_equation(at)
    with mpmath.workdps(DIGITS + 10):
        lo, hi = mpmath.mpf(0), mpmath.pi
        edges = [Edge(_mp_value(x), "at rest", sp.Eq(theta, x))
                 for x in _at_rest_edges(factors[0])]
        if factors[1].free_symbols:
            edges += [Edge(r, "outrace", outrace) for r in _roots(factors[1], lo, hi)
                      if all(abs(r - x.rad) > ENDS for x in edges)]
        edges.sort(key=lambda x: x.rad)
        cuts = [Edge(lo, "limit", None), *edges, Edge(hi, "limit", None)]
        product = sp.lambdify(theta, d.sign * sp.Mul(*factors), modules="mpmath")
        windows: list[list[Edge]] = []
        for a, b in zip(cuts, cuts[1:], strict=False):
            if b.rad - a.rad <= 0 or product((a.rad + b.rad) / 2) <= 0:
                continue
            if windows and windows[-1][1] is a:  # the edge between was a touching root
                windows[-1][1] = b
            else:
                windows.append([a, b])
        result = tuple((a, b) for a, b in windows)
    first = result[0][1] if result else None
    theta_c = first.rad if first is not None and first.kind == "outrace" else None
    return CriticalAngle(restitution, mass_ratio, theta_c, outrace, result)


def _at_rest_edges(factor: sp.Expr) -> list[sp.Expr]:
    """Closed-form angles in (0, pi) where the k = 0 factor vanishes (a polynomial in sin)."""
    if not factor.free_symbols:
        return []
    s = sp.Dummy("s", positive=True)
    plain = factor.xreplace({sp.sin(theta): s})
    if theta in plain.free_symbols:
        raise ArithmeticError(f"the k = 0 factor should depend on sin(theta) only: {factor}")
    angles = []
    for root in polynomial_roots(plain, s):
        if root.is_real and 0 < root <= 1:
            angles += [sp.asin(root), sp.pi - sp.asin(root)] if root < 1 else [sp.pi / 2]
    return sorted(set(angles), key=lambda x: float(x))


def _critical_equation(at: dict) -> sp.Equality:
    """The equation of the outrace edge; at e = 0 in the paper's form."""
    if at[e] == 0:
        return sp.Eq(sp.tan(theta), 1 / (sp.pi - theta))
    return _split_critical(derive().factors[1].subs(at))


def critical_angle(restitution=0, mass_ratio=1) -> CriticalAngle:
    """The windows of initial angle with a re-strike, and the critical angle.

    Parameters
    ----------
    restitution : number or str
        e in [0, 1] (read exactly: ``"0.3"`` is 3/10).
    mass_ratio : number or str
        m/M, the ball's mass over one sphere's.

    Examples
    --------
    >>> r = critical_angle("0.3", 1)
    >>> r.equation
    Eq(13*sin(theta)*cos(theta)/10, (pi - theta)*(10*sin(theta)**2 - 9)/10)
    >>> [[round(float(x), 4) for x in w] for w in r.windows_deg]
    [[71.5651, 83.4771], [108.4349, 180.0]]
    >>> [(lo.kind, hi.kind) for lo, hi in r.windows]
    [('at rest', 'outrace'), ('at rest', 'limit')]
    >>> r.windows[0][0].equation
    Eq(theta, asin(3*sqrt(10)/10))
    """
    return _analysis(*_checked(restitution, mass_ratio))


def windows(restitution=0, mass_ratio=1) -> list[list[mpmath.mpf]]:
    """The windows of initial angle (degrees) in which the barbell strikes the ball again.

    Examples
    --------
    >>> [[round(float(x), 3) for x in w] for w in windows("0.1", 4)]
    [[22.786, 36.973], [157.214, 180.0]]
    """
    return critical_angle(restitution, mass_ratio).windows_deg


# ---- the turn at which the re-strike happens, for numbers -----------------------------

@functools.cache
def _drift_function(modules: str = "numpy"):
    return sp.lambdify((theta, e, m, M), derive().drift, modules=modules)


@dataclass(frozen=True)
class Sweep:
    """The re-strike over many initial angles (arrays of the angles' shape).

    ``hit`` says whether there is one; ``turn`` is the angle the barbell has turned
    through when it happens (``t = turn/omega``), NaN without a hit; ``reach`` is the
    ball's distance from C then, over L (1 means sphere B, below 1 the rod's B half).
    """

    theta: np.ndarray
    hit: np.ndarray
    turn: np.ndarray
    reach: np.ndarray


def sweep(thetas: Sequence[float] | np.ndarray, restitution: float = 0.0,
          mass_ratio: float = 1.0, iterations: int = 64) -> Sweep:
    """The first re-strike for each initial angle (radians), all at once.

    The angle between the rod's B half and the ball grows monotonically (see the module
    notes) from -pi, so the meeting turn is the single root of that angle, bracketed
    between pi and 2(pi - theta); bisection halves the bracket `iterations` times.

    Examples
    --------
    >>> s = sweep(np.radians([10.0, 30.0]))
    >>> s.hit.tolist(), np.round(s.turn, 6).tolist()
    ([True, False], [3.378307, nan])
    """
    th = np.asarray(thetas, dtype=float)
    k = np.asarray(_drift_function()(th, restitution, mass_ratio, 1.0), dtype=float)
    sin, cos = np.sin(th), np.cos(th)

    def gap(turn: np.ndarray) -> np.ndarray:  # rod B direction minus ball direction
        ball = np.arctan2(-sin, -cos + k * turn * sin) + 2 * np.pi
        return th + turn - ball

    a = np.minimum(np.pi, 2 * (np.pi - th))
    b = np.maximum(np.pi, 2 * (np.pi - th))
    for _ in range(iterations):
        mid = 0.5 * (a + b)
        below = gap(mid) < 0
        a, b = np.where(below, mid, a), np.where(below, b, mid)
    turn = 0.5 * (a + b)
    with np.errstate(divide="ignore", invalid="ignore"):
        exit_turn = np.where(k == 0, np.inf, 2 * cos / (sin * k))
    hit = (k == 0) | ((k * cos > 0) & (turn <= exit_turn))
    reach = np.hypot(-cos + k * turn * sin, sin)
    return Sweep(th, hit, np.where(hit, turn, np.nan), np.where(hit, reach, np.nan))


def restrike_turn(theta_value, restitution=0, mass_ratio=1, dps: int = DIGITS):
    """The turn at the re-strike for one angle, to `dps` digits with mpmath; None if none.

    Examples
    --------
    >>> mpmath.nstr(restrike_turn(mpmath.radians(10)), 15)
    '3.37830679260745'
    """
    e_value, r_value = _checked(restitution, mass_ratio)
    with mpmath.workdps(dps + 10):
        th = mpmath.mpf(theta_value)
        k = _drift_function("mpmath")(th, _mp(e_value), _mp(r_value), 1)
        s, c = mpmath.sin(th), mpmath.cos(th)

        def gap(turn):
            return th + turn - (mpmath.atan2(-s, -c + k * turn * s) + 2 * mpmath.pi)

        if k == 0:
            return +mpmath.pi
        if k * c <= 0:
            return None
        a, b = sorted((mpmath.pi, 2 * (mpmath.pi - th)))
        b = min(b, 2 * c / (s * k))
        if gap(b) < 0:
            return None
        return +mpmath.findroot(gap, (a, b), solver="anderson")


def _mp_value(x: sp.Expr) -> mpmath.mpf:
    """An exact number as an mpf at the current working precision (not through float)."""
    return mpmath.mpf(str(sp.N(x, mpmath.mp.dps + 5)))


def _mp(x: Fraction) -> mpmath.mpf:
    return mpmath.mpf(x.numerator) / x.denominator


def restrike_map(ratios: Sequence[float] = (0.5, 1.0, 4.0), e_count: int = 101,
                 theta_count: int = 361) -> tuple[np.ndarray, np.ndarray, dict]:
    """Hit / no hit over a grid of (e, theta in degrees), per mass ratio, from :func:`sweep`.

    Examples
    --------
    >>> degrees, e_values, hits = restrike_map((1.0,), 3, 7)
    >>> hits[1.0].astype(int).tolist()[0]
    [1, 0, 0, 0, 0, 0, 0]
    """
    degrees = np.linspace(0.0, 180.0, theta_count)
    inner = np.radians(np.clip(degrees, 1e-6, 180 - 1e-6))  # the ends themselves are limits
    e_values = np.linspace(0.0, 1.0, e_count)
    hits = {ratio: np.array([sweep(inner, ev, ratio).hit for ev in e_values])
            for ratio in ratios}
    return degrees, e_values, hits


@functools.cache
def _after_impact():
    r = problems.barbell().results
    return sp.lambdify((theta, e, m, M, L, v_ix), [r["v_fx"], r["V_x"], r["omega_z"]],
                       modules="math")


def strobe_frames(theta_value: float, restitution: float = 0.0, mass_ratio: float = 1.0,
                  count: int = 12) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Ball, sphere A and sphere B (units of L, v_ix = 1) from the impact to the re-strike.

    Without a re-strike the frames run for one turn of the barbell.

    Examples
    --------
    >>> frames = strobe_frames(np.radians(10.0), count=3)
    >>> [np.round(x, 6).tolist() for x in frames[0]]
    [[0.0, 0.0], [0.0, 0.0], [1.969616, 0.347296]]
    """
    v_fx, v_x, omega = _after_impact()(theta_value, restitution, mass_ratio, 1.0, 1.0, 1.0)
    found = sweep([theta_value], restitution, mass_ratio)
    turn = float(found.turn[0]) if found.hit[0] else 2 * math.pi
    frames = []
    for t in np.linspace(0.0, turn / omega, count):
        centre = np.array([math.cos(theta_value) + v_x * t, math.sin(theta_value)])
        rod = np.array([math.cos(theta_value + omega * t), math.sin(theta_value + omega * t)])
        frames.append((np.array([v_fx * t, 0.0]), centre - rod, centre + rod))
    return frames


# ---- checks for `rigidimpact verify` --------------------------------------------------

def _check_drift() -> Verdict:
    return agree(derive().drift, 1 - e / (F * sp.sin(theta) ** 2))


def _check_monotone() -> Verdict:
    d = derive()
    p = d.relative_position
    ball_rate = tidy((p[0] * sp.diff(p[1], tau) - p[1] * sp.diff(p[0], tau)) / p.dot(p))
    bound = tidy(d.drift * L**2 * sp.sin(theta) ** 2 / p.dot(p))
    closest = tidy(p.dot(p) - L**2 * sp.sin(theta) ** 2 - p[0] ** 2)
    k_at_most_one = agree(1 - d.drift, e / (F * sp.sin(theta) ** 2))
    ok = symbolic_zero(ball_rate - bound) and closest == 0 and k_at_most_one.passed
    return Verdict(ok, "ball's angular rate = k L^2 sin^2/|p|^2 with |p| >= L sin(theta); "
                       f"1 - k = e/(f sin^2): {k_at_most_one.detail}")


def _check_critical() -> Verdict:
    critical = derive().critical
    if critical.free_symbols != {theta}:
        return Verdict(False, f"depends on {critical.free_symbols}")
    reference = CRITICAL_ANGLE_EQUATION.xreplace({sp.tan(theta): sp.sin(theta) / sp.cos(theta)})
    ratio = sp.factor(sp.cancel(sp.together(critical / reference)))
    # the ratio may vanish or blow up only where cos, sin or (pi - theta) do
    top, bottom = sp.fraction(ratio)
    zeros = [f for part in (top, bottom) for f, _ in sp.factor_list(part)[1]]
    allowed = {sp.cos(theta), sp.sin(theta), theta - sp.pi, sp.pi - theta}
    ok = all(f in allowed or f.is_number for f in zeros)
    return Verdict(ok, f"condition = ({ratio}) * (tan(theta) - 1/(pi - theta)); "
                       "free of m, M, L and v_ix")


def _check_sphere_b() -> Verdict:
    d = derive()
    at_critical = {e: 0}
    leaves = (d.relative_position.subs(tau, d.exit_turn) / L).subs(at_critical)
    b_turned = sp.ImmutableMatrix([sp.cos(theta + d.meet_turn), sp.sin(theta + d.meet_turn)])
    ok = all(symbolic_zero(x) for x in leaves.applyfunc(tidy) - b_turned)
    return Verdict(ok, "p(T)/L = (cos(theta + 2(pi - theta)), sin(...)): sphere B's place")


def _check_theta_c() -> Verdict:
    with mpmath.workdps(DIGITS + 10):
        ours = critical_angle().theta_c
        assert ours is not None  # at e = 0 the first window ends at the outrace edge
        direct = mpmath.findroot(lambda x: mpmath.tan(x) - 1 / (mpmath.pi - x), 0.34)
        residual = abs(mpmath.tan(ours) - 1 / (mpmath.pi - ours))
        ok = (abs(ours - direct) < mpmath.mpf(10) ** -35 and residual < mpmath.mpf(10) ** -35
              and abs(ours * 180 / mpmath.pi - mpmath.mpf("19.7")) < mpmath.mpf("0.05"))
        return Verdict(ok, f"theta_c = {mpmath.nstr(ours * 180 / mpmath.pi, 32)} deg; "
                           f"residual {mpmath.nstr(residual, 3)}")


# the re-strike's checks, run by `rigidimpact verify` with the paper's own
CHECKS: tuple[tuple[str, str, str, Callable[[], Verdict]], ...] = (
    ("restrike.drift", "(5), section 2",
     "after the impact the ball drifts from C at k = 1 - e/(f sin^2 theta) "
     "(in units of omega L sin theta), so k = 1 when e = 0",
     _check_drift),
    ("restrike.monotone", "section 2",
     "the angle from the ball to the rod's B half only grows: the ball's own "
     "angle about C turns at most k <= 1 as fast as the rod",
     _check_monotone),
    ("restrike.critical", "section 2",
     "at e = 0 the condition is tan(theta_c) = 1/(pi - theta_c) on (0, pi/2), "
     "whatever m/M",
     _check_critical),
    ("restrike.sphere_b", "section 2",
     "at theta_c sphere B reaches the ball as it leaves, after a turn of "
     "2(pi - theta_c)",
     _check_sphere_b),
    ("restrike.theta_c", "section 2",
     "theta_c solved to 30 digits is about 19.7 degrees and two independent "
     "root searches agree",
     _check_theta_c),
)
