"""A sphere's motion between impacts in space, in closed form: its flight under gravity,
and its sliding on a flat with Coulomb friction until it rolls.

The first pieces of a 3-D scene's life after its impact; exact (SymPy) where the data
are rational, so a time of change or a rolling speed is a number a teacher can check.

Sliding. A sphere of mass m, radius R and moment of inertia k m R^2 (k = 2/5 solid,
2/3 a thin shell) lies on a flat of upward unit normal n, its centre moving at v and
turning at omega. Its touching point slips at ``s = v + omega x (-R n)``. While s is not
zero, friction mu m g acts against it: ``dv/dt = -mu g s^``, and its moment about the
centre ``(-R n) x (-mu m g s^)`` turns the sphere, ``d omega/dt = (mu g / (k R)) n x
s^``. Then ``ds/dt = -mu g (1 + 1/k) s^``: the slip keeps its direction and shrinks at a
constant rate, so the sphere rolls from ``t = |s| / (mu g (1 + 1/k))`` on, at
``v + k/(1 + k) (R omega x n - v)``, which for a solid sphere is
``(5/7) (v + (2/5) R omega x n)``. The spin about the normal is untouched (no pivoting
friction). A check independent of these steps: the angular momentum about the touching
point (a point of the flat under the centre) is unchanged by the friction, whose line
passes through it, and by gravity and the normal force, which cancel.

Flight. Under gravity g alone the centre moves on a parabola and, the sphere's inertia
being the same about every axis, its spin is constant; the time it reaches the height of
a flat is the root of a quadratic, exact where the data are rational.

Examples
--------
A solid sphere thrown along a table at 3 without spin (R = 1/10, mu = 1/5, g = 49/5)
rolls from t = 150/343 at 15/7:

>>> import sympy as sp
>>> roll = sliding(v=(3, 0, 0), spin=(0, 0, 0), radius=sp.Rational(1, 10),
...                k=sp.Rational(2, 5), mu=sp.Rational(1, 5), g=sp.Rational(49, 5))
>>> roll.t, roll.velocity[0]
(150/343, 15/7)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.symbolic.given import given_number

__all__ = ["Sliding", "sliding", "flight", "landing_time"]

UP = (0, 0, 1)


def _vector(name: str, value: Sequence[Any]) -> sp.Matrix:
    """Three real, finite numbers (or SymPy expressions); text is refused, never read."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise InputError(name, f"must be three numbers, got {value!r}")
    if len(value) != 3:
        raise InputError(name, f"must have three components, got {len(value)}")
    return sp.Matrix([_exact(x, given_number(x, f"{name}[{i}]"))
                      for i, x in enumerate(value)])


def _exact(given: Any, number: sp.Expr) -> sp.Expr:
    """A float given is read as the simple rational it stands for (0.1 as 1/10)."""
    return sp.nsimplify(number) if isinstance(given, float) else number


def _positive(name: str, value: Any) -> sp.Expr:
    x = _exact(value, given_number(value, name))
    if x.is_number and not x > 0:
        raise InputError(name, f"must be positive, got {value!r}")
    return x


@dataclass(frozen=True)
class Sliding:
    """A sphere sliding on a flat until it rolls (see the module's text): ``t`` the time
    it starts to roll (0 if it already does), ``velocity`` and ``spin`` then, ``slip``
    the slip's unit direction while it slides (zero if it does not), and what it
    started from, to give the state at any time by :meth:`at`."""

    t: sp.Expr
    velocity: sp.Matrix
    spin: sp.Matrix
    slip: sp.Matrix
    start: tuple[sp.Matrix, sp.Matrix]
    rates: tuple[sp.Matrix, sp.Matrix]  # dv/dt and d omega/dt while it slides

    def at(self, t: Any) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
        """(displacement of the centre since the start, velocity, spin) at time t >= 0."""
        t = sp.sympify(t)
        v0, w0 = self.start
        dv, dw = self.rates
        sliding_for = sp.Min(t, self.t) if not (t.is_number and self.t.is_number) else \
            min(t, self.t)
        moved = v0 * sliding_for + dv * sliding_for ** 2 / 2 + \
            (v0 + dv * self.t) * (t - sliding_for)
        return (moved.applyfunc(sp.simplify), (v0 + dv * sliding_for).applyfunc(sp.simplify),
                (w0 + dw * sliding_for).applyfunc(sp.simplify))


def sliding(v: Sequence[Any], spin: Sequence[Any], radius: Any, k: Any, mu: Any, g: Any,
            normal: Sequence[Any] = UP) -> Sliding:
    """The sphere's sliding on the flat of unit `normal` until it rolls (see the module's
    text); `v` must lie in the flat (the sphere stays on it)."""
    v0, w0, n = _vector("v", v), _vector("spin", spin), _vector("normal", normal)
    if sp.simplify(n.dot(n) - 1) != 0:
        raise InputError("normal", "must be a unit vector")
    if sp.simplify(v0.dot(n)) != 0:
        raise InputError("v", "must lie in the flat: a sphere moving off it flies")
    R, k = _positive("radius", radius), _positive("k", k)
    mu, g = _positive("mu", mu), _positive("g", g)
    slip = v0 + w0.cross(-R * n)
    size = sp.sqrt(sp.simplify(slip.dot(slip)))
    zero = sp.zeros(3, 1)
    if size == 0:
        return Sliding(sp.Integer(0), v0, w0, zero, (v0, w0), (zero, zero))
    s = (slip / size).applyfunc(sp.simplify)
    dv = -mu * g * s
    dw = (mu * g / (k * R)) * n.cross(s)
    t = sp.simplify(size / (mu * g * (1 + 1 / k)))
    return Sliding(t, (v0 + dv * t).applyfunc(sp.simplify),
                   (w0 + dw * t).applyfunc(sp.simplify), s, (v0, w0), (dv, dw))


def flight(position: Sequence[Any], velocity: Sequence[Any], spin: Sequence[Any],
           gravity: Sequence[Any], t: Any) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """(position, velocity, spin) of a sphere in flight after time t: a parabola, and
    the spin unchanged (the same inertia about every axis, no torque)."""
    p, v = _vector("position", position), _vector("velocity", velocity)
    w, a = _vector("spin", spin), _vector("gravity", gravity)
    t = given_number(t, "t")
    return p + v * t + a * t ** 2 / 2, v + a * t, w


def landing_time(height: Any, rise: Any, g: Any) -> sp.Expr:
    """When a centre at `height` above the level it lands at, rising at `rise` under
    gravity g (downward), reaches that level: the later root of the quadratic."""
    h, u = given_number(height, "height"), given_number(rise, "rise")
    g = _positive("g", g)
    if h.is_number and h < 0:
        raise InputError("height", f"must be at least 0, got {height!r}")
    return sp.simplify((u + sp.sqrt(u ** 2 + 2 * g * h)) / g)
