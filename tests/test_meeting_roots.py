"""When two spheres meet, and when a sphere reaches a plane: the first closing root of a
quartic (two centres' distance) or a quadratic (a plane's gap), found by exact real-root
isolation (never a numerical root finder that may fail to converge), against roots
derived by hand and against a stable closed form at 60 digits."""

from __future__ import annotations

import math
import random
from pathlib import Path

import mpmath
import sympy as sp

from helpers import evaluated, scene_file
from rigidimpact.simulate.bounces import DIGITS, _first_root, _meeting, first_closing_root

R = sp.Rational
F = lambda x: sp.Float(x, DIGITS)  # noqa: E731 - the run's 40-digit floats
T = sp.Symbol("t")


def _coeffs(expr):
    return sp.Poly(sp.expand(expr), T).all_coeffs()


def test_a_graze_is_passed_and_the_crossing_after_it_found():
    # (t - 1)^2 (t - 3)(t - 4): positive at 0, touches zero at 1 (a graze) and goes
    # below zero at 3
    assert first_closing_root(_coeffs((T - 1) ** 2 * (T - 3) * (T - 4))) == 3
    assert first_closing_root(_coeffs((T - 1) ** 2 * (T - 3) * (T - 4)), factor=False) == 3


def test_a_root_going_up_is_an_opening_not_a_meeting():
    # 2 - t^2 ... negative at 0 (rounding's overlap): the root at sqrt(2) opens the gap
    assert first_closing_root(_coeffs(T ** 2 - 2)) is None
    # touching at 0 and parting: t (t - 1) is negative just after 0, then opens at 1
    assert first_closing_root(_coeffs(T * (T - 1))) is None
    # touching at 0 and parting, closing again at 5: t (t + 1)(t - 5)(t - 6)
    assert first_closing_root(_coeffs(T * (T + 1) * (T - 5) * (T - 6))) == 5


def test_an_irrational_root_has_forty_digits():
    # 3 - t^2 - t^4/10^6: t^2 = -5 10^5 + sqrt(25 10^10 + 3 10^6)
    root = first_closing_root(_coeffs(3 - T ** 2 - T ** 4 / 10**6))
    exact = sp.sqrt(-R(10**6, 2) + sp.sqrt(R(10**12, 4) + 3 * 10**6))
    assert abs(root - exact).evalf(60) < sp.Float(10) ** (2 - DIGITS)


def test_a_meeting_with_rounding_noise_in_the_acceleration_is_found():
    # two centres 1 apart closing at 2, their relative acceleration 1e-41 (the rounding
    # of two equal rolling decelerations): they meet when the gap of 1 - 1/2 is closed,
    # at t = 1/4; the quartic's leading coefficient is 1e-83, and its two huge roots
    # made a numerical root finder give up
    d = sp.Matrix([F(1), 0, 0])
    u = sp.Matrix([F(-2), 0, 0])
    acc = sp.Matrix([F("7.17e-42"), F("-1.2e-41"), 0])
    when = _meeting(d, u, acc, R(1, 2), exact=False)
    assert abs(when - R(1, 4)) < sp.Float(10) ** (5 - DIGITS)
    # parting, the same paths meet never
    assert _meeting(d, -u, acc, R(1, 2), exact=False) is None


def test_a_meeting_at_a_cue_speed_of_1e30():
    d = sp.Matrix([F("0.24"), F("0.18"), 0])
    u = sp.Matrix([F("-0.8e30"), F("-0.6e30"), 0])
    when = _meeting(d, u, sp.zeros(3, 1), R(57, 1000), exact=False)
    assert abs(when - R(3, 10) / R(10**30) + R(57, 1000) / R(10**30)) < \
        sp.Float(10) ** (5 - DIGITS) * when


def test_a_plane_reached_at_a_speed_of_1e30_is_found_without_cancellation():
    # gap 0.3257 closing at 4.68e29, slowed at 1.53: the root near 6.96e-31, which the
    # textbook quadratic formula loses to cancellation in 40 digits
    a, b, c = F("0.76398"), F("-4.68e29"), F("0.3257")
    when = _first_root(a, b, c, sp.Integer(0))
    with mpmath.workdps(80):
        a_, b_, c_ = (mpmath.mpf(str(x)) for x in (a, b, c))
        # the small root in the form without cancellation: 2c / (-b + sqrt(b^2 - 4ac))
        oracle = sp.Float(str(2 * c_ / (-b_ + mpmath.sqrt(b_ ** 2 - 4 * a_ * c_))), 60)
    assert when is not None and abs(when - oracle) < \
        sp.Float(10) ** (3 - DIGITS) * when


def _unit(rng):
    """A rational unit vector: the inverse stereographic projection of a rational point."""
    p, q = R(rng.randint(-9, 9), rng.randint(1, 9)), R(rng.randint(-9, 9), rng.randint(1, 9))
    s = 1 + p * p + q * q
    return sp.Matrix([2 * p / s, 2 * q / s, (p * p + q * q - 1) / s])


def test_random_head_on_meetings_match_the_closed_form():
    # seed 6: two centres on one line n, the second x0 > reach ahead, closing at u and
    # accelerating at acc along n, the scales spread from 1e-40 to 1e30; they meet when
    # x0 + u t + acc t^2/2 first comes down to reach, a quadratic solved in the stable
    # form at 60 digits; the quartic is never formed by hand
    rng = random.Random(6)
    for _ in range(60):
        n = _unit(rng)
        reach = R(rng.randint(1, 100), 1000)
        x0 = reach * (1 + sp.Float(10) ** rng.uniform(-6, 3))
        u = -sp.Float(10) ** rng.uniform(-3, 30)
        acc = sp.Float(10) ** rng.uniform(-42, 2) * rng.choice((-1, 1))
        d, v, a = (F(x) * n for x in (x0, u, acc))
        when = _meeting(d, v, a, reach, exact=False)
        with mpmath.workdps(60):
            A, B, C = (mpmath.mpf(str(x)) for x in (sp.Float(acc, 60) / 2, sp.Float(u, 60),
                                                    sp.Float(x0, 60) - reach))
            disc = B * B - 4 * A * C
            if disc < 0:  # decelerating before it reaches: no meeting
                assert when is None
                continue
            q = -(B - mpmath.sqrt(disc)) / 2  # B < 0
            oracle = sp.Float(str(C / q), 60)
        assert when is not None
        assert abs(when - oracle) < sp.Float(10) ** (8 - DIGITS) * when


THIRD = '''
[[bodies]]
name = "third"
shape = "sphere"
mass = "17/100"
radius = "57/2000"
position = ["57/1250 + 6/25", "171/5000 + 9/50", "57/2000"]

[[contacts]]
name = "cloth_third"
bodies = ["table", "third"]
point = ["57/1250 + 6/25", "171/5000 + 9/50", "0"]
normal = ["0", "0", "1"]
restitution = "0"
tangential = "coulomb"
friction = "mu"

[[pairs]]
name = "object_third"
bodies = ["object", "third"]
restitution = "e_balls"

'''


def test_the_stun_shot_with_a_third_ball_in_the_object_balls_path(tmp_path, capsys):
    # the third ball lies 3/10 on from the object ball along the line of centres of the
    # stun, (4/5, 3/5), along which the object ball leaves (a smooth meeting pushes it
    # along the normal alone, and it slides and rolls on that line): it meets the third
    # head-on, and the third leaves along the same line
    text = Path("derivations/stun-shot.toml").read_text(encoding="utf-8")
    text = text.replace("[[planes]]", THIRD + "[[planes]]", 1).replace("until = 8",
                                                                       "until = 0.4")
    out = evaluated(capsys, ["simulate", scene_file(tmp_path, text)])
    meetings = [e for e in out["events"] if e.get("plane") == "object_third"]
    assert len(meetings) == 1 and 0 < meetings[0]["t"] < 0.4
    final = out["final"]
    assert final["third.vx"] > 0 and math.isclose(final["third.vy"] / final["third.vx"],
                                                  3 / 4, rel_tol=1e-12)
    assert math.isclose((final["third.y"] - 171 / 5000 - 9 / 50)
                        / (final["third.x"] - 57 / 1250 - 6 / 25), 3 / 4, rel_tol=1e-9)
