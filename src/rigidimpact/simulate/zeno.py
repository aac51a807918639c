"""The geometric tail of a sphere's bounces on a plane that gravity presses it into: with
0 < e < 1 infinitely many bounces pile up at a finite time, summed here in closed form.

A sphere's impact on a fixed plane is decoupled: the contact normal passes through the
centre, so every restitution law gives the normal speed ``-e`` times its landing speed,
and the tangential laws act on the slip ``s = u - R w x n`` (u the centre's velocity
across the normal n, w the spin, k = I/(m R^2)) alone. Each law is one of Walton's,
``s -> -beta s`` where the friction it needs, ``|du| = (1 + beta) k |s| / (1 + k)``, is
at most ``mu (1 + e) l`` (l the landing speed), and Coulomb's sliding,
``du = -mu (1 + e) l s/|s|``, where it is not: ``coulomb`` is beta = 0, ``stick`` beta
= 0 with no bound, ``smooth`` beta = -1 (nothing changes). The spin changes by
``-n x du / (k R)`` in either case, so ``I w + m R n x u``, the angular momentum about
the contact point, is kept across the normal: a slip that dies out leaves the sphere
rolling at ``(u + k R w x n) / (1 + k)``.

Between bounces the sphere flies for ``2 l / g`` with u and w kept, and the landing
speeds are ``l, e l, e^2 l, ...``. Two regimes repeat for ever once they hold, each
affine in the tangential state with the normal speed scaled by e, and are summed:

- **Walton's** with ``|beta| <= e`` (or no bound): the friction needed shrinks as
  ``|beta|^i`` and the bound as ``e^i``, so if it holds at the next landing it holds at
  every one; the slip goes as ``(-beta)^i s``;
- **sliding** at every landing: the slip shrinks by ``c l_i`` (c = mu (1 + e)(1 + k)/k)
  along its own line, which it does for ever when ``|s| >= c l max(1/(1 - e),
  1/(1 + beta))``.

Anything else (a bounce that sticks after sliding, a slip that reverses past the bound)
is followed bounce by bounce; a slip that reverses for ever without shrinking
(``|beta| = 1`` with no bound) has no limit and is refused in one line.

Examples
--------
A ball dropped at 5 on a smooth floor with e = 99/100 and g = 10 lies down 99 s after
its first bounce, ``2 e v0 / (g (1 - e))``:

>>> import sympy as sp
>>> from rigidimpact.laws.contact import Contact
>>> floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
...                 name="floor", restitution=sp.Rational(99, 100))
>>> n = sp.Matrix([0, 0, 1])
>>> tail = geometric_tail(floor, n, 10, sp.Matrix([1, 0, sp.Rational(99, 20)]),
...                       sp.zeros(3, 1), sp.Rational(1, 10), sp.Rational(2, 5))
>>> tail.t, tail.displacement.T, tail.velocity.T, tail.regime
(99, Matrix([[99, 0, 0]]), Matrix([[1, 0, 0]]), 'smooth')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact

__all__ = ["Tail", "geometric_tail", "bounce_map"]


@dataclass(frozen=True)
class Tail:
    """The sum of the bounces still to come: the time `t` until they pile up, the
    centre's `displacement` across the normal over it, the velocity and spin the sphere
    lies down with, and the regime summed."""

    t: sp.Expr
    displacement: sp.Matrix
    velocity: sp.Matrix
    spin: sp.Matrix
    regime: str  # rolling, smooth, walton (the slip scaled by -beta) or slides
    said: str  # the regime in words
    bounces: int | None = None  # how many were summed (None: all of them)


def _law(contact: Contact) -> tuple[sp.Expr, sp.Expr | None] | None:
    """(beta, mu) of the contact's tangential law as Walton's law capped by Coulomb's
    cone (mu None: no cap); None for a law this module does not know."""
    form = contact.laws[1].walton()
    if form is None:
        return None
    beta, mu = form
    return sp.sympify(beta), None if mu is None else sp.sympify(mu)


def _across(x: sp.Matrix, n: sp.Matrix) -> sp.Matrix:
    return x - n.dot(x) * n


def _size(x: sp.Matrix) -> sp.Expr:
    return sp.sqrt(x.dot(x))


def bounce_map(contact: Contact, n: sp.Matrix, v: sp.Matrix, w: sp.Matrix, R: sp.Expr,
               k: sp.Expr) -> tuple[sp.Matrix, sp.Matrix, str] | None:
    """The sphere's velocity and spin after landing on the fixed plane of `contact`
    (unit normal `n` toward the sphere) with velocity `v` and spin `w`, by the closed
    form of the module's text, and its regime (``rolling``, ``smooth``, ``walton``,
    ``slides``, as :attr:`Tail.regime`); None for a law it does not know."""
    law = _law(contact)
    if law is None or contact.restitution is None:
        return None
    beta, mu = law
    e = sp.sympify(contact.restitution)
    landing = -n.dot(v)
    u = _across(v, n)
    slip = u - R * w.cross(n)
    du = -(1 + beta) * k / (1 + k) * slip
    regime = "rolling" if slip == sp.zeros(3, 1) else "smooth" if beta == -1 else "walton"
    if mu is not None and regime == "walton" and _size(du) > mu * (1 + e) * landing:
        du = -mu * (1 + e) * landing * slip / _size(slip)
        regime = "slides"
    return u + du + e * landing * n, w - n.cross(du) / (k * R), regime


def geometric_tail(contact: Contact, n: sp.Matrix, g: Any, v: sp.Matrix, w: sp.Matrix,
                   R: sp.Expr, k: sp.Expr, bounces: int | None = None) -> Tail | None:
    """The bounces to come of a sphere leaving the plane of `contact` (unit normal `n`
    toward the sphere, gravity `g` pressing it in) with velocity `v` (rising) and spin
    `w`, summed where one of the module's two regimes holds for every one of them;
    None where neither does (follow the next bounce). With `bounces`, only that many
    are summed: the tail's time and displacement up to the last of them, and the
    velocity (rising again) and spin the sphere leaves it with.

    Raises
    ------
    InputError
        A slip that reverses at every bounce without shrinking: no limit exists.
    """
    law = _law(contact)
    if law is None or contact.restitution is None:
        return None
    beta, mu = law
    e = sp.sympify(contact.restitution)
    if not 0 < e < 1:
        return None
    rise = n.dot(v)  # the next landing speed
    u = _across(v, n)
    slip = u - R * w.cross(n)
    power = sp.Integer(0) if bounces is None else e ** bounces  # e^m, 0 for them all
    part = (1 - power) / (1 - e)  # 1 + e + ... + e^(m-1)
    time = 2 * rise / g * part
    leaves = rise * power * n  # its normal velocity after the last bounce summed
    if slip == sp.zeros(3, 1) or beta == -1:  # rolling (kept by any law) or smooth
        rolling = slip == sp.zeros(3, 1)
        return Tail(time, u * time, u + leaves, w, "rolling" if rolling else "smooth",
                    "it rolls at every bounce" if rolling else "a smooth plane", bounces)
    c = None if mu is None else mu * (1 + e) * (1 + k) / k
    if c is None or (abs(beta) <= e and (1 + beta) * _size(slip) <= c * rise):
        if abs(beta) == 1 and bounces is None:
            raise InputError(f"{contact.name}.tangential_restitution", "the slip reverses "
                             "at every bounce without shrinking (tangential restitution "
                             f"{beta}): the bounces pile up at {float(time):.6g} s from "
                             "here, where the motion has no limit")
        flip = sp.Integer(0) if bounces is None else (-beta) ** bounces
        flips = sp.Integer(0) if bounces is None else (-beta * e) ** bounces
        rolled = u - k / (1 + k) * slip  # the rolling velocity the slip dies out to
        last = u - k / (1 + k) * slip * (1 - flip)
        shift = 2 * rise / g * (rolled * part + k / (1 + k) * slip * (1 - flips) / (1 + beta * e))
        return Tail(time, shift, last + leaves, w - n.cross(last - u) / (k * R), "walton",
                    f"every bounce returns {-beta} of the slip", bounces)
    if _size(slip) < c * rise * max(1 / (1 - e), 1 / (1 + beta)):
        return None  # it sticks (or reverses) at some bounce to come
    along = slip / _size(slip)
    assert mu is not None
    last = u - mu * (1 + e) * rise * part * along
    # the sum over the flights of each flight's time 2 e^i rise / g times its velocity
    squares = part - (1 - power ** 2) / (1 - e ** 2)
    shift = 2 * rise / g * (u * part - mu * (1 + e) * rise * squares / (1 - e) * along)
    return Tail(time, shift, last + leaves, w - n.cross(last - u) / (k * R),
                "slides", "it slides at every bounce", bounces)
