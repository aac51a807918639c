"""Billiards: a cut shot between two equal balls, with spin, by the 3-D contact solver.

The cue ball (solid, mass m, radius R) rolls or slides toward an object ball at rest and
strikes it at a cut angle (the angle between the cue ball's path and the line of the
centres). The contact between the balls has the balls' W, isotropic and uncoupled along
the line of the centres: the slip direction cannot turn and the answer is the closed
form of :func:`rigidimpact.laws.cone.cone_impact`. The object ball's *throw* is the
angle between its path and the line of the centres, which friction turns it by.

The table's contact is not in this model (the balls are struck in the instant; the table
acts over the roll that follows).

Examples
--------
A stun shot (no spin) at a 30 degree cut, e = 1, mu = 0.06. By hand: the normal impulse
per mass is v cos 30, sticking would need v sin 30 / 7 = 0.071 v > mu v cos 30 = 0.052 v,
so the contact slides throughout and tan(throw) = mu, a throw of 3.434 degrees.

>>> out = cut_shot(30, 1.0, 0.0, 0.0, mu=0.06, e=1.0)
>>> round(out["throw_degrees"], 3), out["course"]
(3.434, 'slides throughout')
"""

from __future__ import annotations

import math
from typing import Any

import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.model.space import Body3
from rigidimpact.solve.space import SpaceCollision

__all__ = ["cut_shot", "cushion", "alciatore_friction", "RADIUS", "MASS", "CUSHION_HEIGHT"]

RADIUS = 0.028575  # m: a pool ball of 2.25 in
MASS = 0.170097  # kg: 6 oz
CUSHION_HEIGHT = 0.036576  # m: the nose of the cushion above the table (1.44 in)


def alciatore_friction(speed: float) -> float:
    """Alciatore's fit of the measured ball-ball friction against the relative surface
    speed (m/s) at contact: ``9.951e-3 + 0.108 exp(-1.088 v)``."""
    return 9.951e-3 + 0.108 * math.exp(-1.088 * speed)


def cut_shot(cut_degrees: float, speed: float, topspin: float, sidespin: float,
             mu: float | None = None, e: float = 0.95) -> dict[str, Any]:
    """The two balls after a cut shot.

    The object ball sits at the origin; the cue ball's centre is at distance 2R along
    the line of the centres, which makes `cut_degrees` with the cue ball's velocity
    (`speed` along +x). `topspin` is the cue ball's spin about the axis across its path
    in units of rolling (1: rolling, 0: stun, -1: as much draw); `sidespin` its spin about
    the vertical, in the same units (speed / R). `mu` defaults to Alciatore's fit at the
    contact's relative surface speed.
    """
    cut = math.radians(cut_degrees)
    R = sp.Float(RADIUS, 30)
    # the line of the centres, from the cue ball into the object ball
    n = (math.cos(cut), -math.sin(cut), 0.0)
    centre = tuple(-2 * float(R) * x for x in n)
    rolling = speed / RADIUS
    spin = (0.0, topspin * rolling, sidespin * rolling)  # rolling along +x: w_y = v / R
    cue = Body3.sphere(MASS, R, centre, (speed, 0, 0), spin, name="cue")
    ball = Body3.sphere(MASS, R, (0, 0, 0), (0, 0, 0), (0, 0, 0), name="object")
    point = tuple(-float(R) * x for x in n)
    if mu is None:
        probe = SpaceCollision((cue, ball), (Contact(
            normal=n, restitution=e, bodies=("cue", "object"), point=point),))
        v = probe.rows(probe.contacts[0]) * probe.u_before
        mu = alciatore_friction(float(sp.sqrt(v[1] ** 2 + v[2] ** 2)))
    contact = Contact(normal=n, restitution=sp.Float(e, 30), tangential="coulomb",
                      friction=sp.Float(mu, 30), bodies=("cue", "object"), point=point)
    solution = SpaceCollision((cue, ball), (contact,)).solve()
    r = {k: float(v) for k, v in solution.results().items()}
    along = r["object.vx"] * n[0] + r["object.vy"] * n[1]
    across = -r["object.vx"] * n[1] + r["object.vy"] * n[0]
    return {**r, "throw_degrees": math.degrees(math.atan2(abs(across), along)),
            "mu": mu, "course": solution.regime}


def cushion(speed: float, angle_degrees: float, topspin: float = 0.0, sidespin: float = 0.0,
            e: float = 0.85, mu_cushion: float = 0.2, mu_table: float = 0.2,
            height: float = CUSHION_HEIGHT, law: str = "energetic",
            tolerance: float | None = None) -> dict[str, Any]:
    """A ball on the table striking a straight cushion: the cushion's contact strikes and
    the table's rests, both rough, acting together (Mathavan, Jackson and Parkin 2010).

    The cushion runs along x at y = 0 and the ball comes from y < 0 at `speed`, its path
    making `angle_degrees` with the cushion's normal (0: head on). The cushion's nose is
    at `height` above the table, so it touches the ball above its equator, at the angle
    theta with ``sin theta = (height - R) / R``, and its normal (from the cushion into the
    ball) points back and down through the centre. `topspin` is the spin about the axis
    across the path in units of rolling (1: rolling, 0: stun), `sidespin` the spin about
    the vertical in units of speed / R. The cushion's restitution law is `law` (Mathavan
    use the energetic one). Returns the speeds after (``ball.vx`` ... ``ball.omega_z``),
    the rebound angle and speed, each contact's impulses and course.
    """
    a = math.radians(angle_degrees)
    R = RADIUS
    sin_t = (height - R) / R
    cos_t = math.sqrt(1 - sin_t ** 2)
    v = (speed * math.sin(a), speed * math.cos(a), 0.0)
    rolling = speed / R
    # rolling along the path (sin a, cos a, 0): omega = (v / R) z x path... = (-cos a, sin a) v/R
    spin = (-topspin * rolling * math.cos(a), topspin * rolling * math.sin(a),
            sidespin * rolling)
    ball = Body3.sphere(MASS, R, (0, 0, R), v, spin, name="ball")
    point = (0.0, R * cos_t, R + R * sin_t)
    rail = Contact(normal=(0.0, -cos_t, -sin_t), restitution=e, law=law,
                   tangential="coulomb", friction=mu_cushion, name="cushion",
                   bodies=("rail", "ball"), point=point)
    table = Contact(normal=(0, 0, 1), restitution=0, tangential="coulomb",
                    friction=mu_table, name="table", bodies=("table", "ball"),
                    point=(0, 0, 0))
    solution = SpaceCollision((Body3.fixed("rail"), Body3.fixed("table"), ball),
                              (rail, table), tolerance, rule="driven").solve()
    r = {k: float(x) for k, x in solution.results().items()}
    rebound = math.degrees(math.atan2(r["ball.vx"], -r["ball.vy"]))
    return {**r, "rebound_degrees": rebound,
            "rebound_speed": math.hypot(r["ball.vx"], r["ball.vy"]),
            "courses": solution.courses, "solution": solution}
