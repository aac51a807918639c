"""A sphere between impacts in space (rigidimpact.simulate.sphere): sliding to rolling
and flight, held against hand derivations and against laws the motion must obey."""

from __future__ import annotations

import random

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.simulate.sphere import flight, landing_time, sliding

R = sp.Rational


UP = sp.ImmutableMatrix([0, 0, 1])


def _about_contact(m, k, radius, v, w, n=UP):
    """Angular momentum about the touching point, a point of the flat under the centre:
    I w + (R n) x m v (the centre is R n above it)."""
    return k * m * radius ** 2 * w + (radius * n).cross(m * v)


def test_a_sphere_thrown_without_spin_rolls_at_five_sevenths():
    # by hand: the slip v decays at (7/2) mu g, so t = 2 v / (7 mu g) and the speed then
    # is v - mu g t = 5 v / 7
    roll = sliding((3, 0, 0), (0, 0, 0), R(1, 10), R(2, 5), R(1, 5), R(49, 5))
    assert roll.t == R(2 * 3, 7) / (R(1, 5) * R(49, 5))
    assert list(roll.velocity) == [R(15, 7), 0, 0]
    assert list(roll.spin) == [0, R(15, 7) / R(1, 10), 0]  # rolls: v = R w_y


def test_a_draw_shot_comes_back():
    # backspin R w_y = -5 at v = 1: (5/7)(v + (2/5) R w x n) = (5/7)(1 - 2) = -5/7
    roll = sliding((1, 0, 0), (0, -50, 0), R(1, 10), R(2, 5), R(1, 5), R(49, 5))
    assert list(roll.velocity) == [R(-5, 7), 0, 0]
    moved, velocity, _ = roll.at(roll.t / 2)
    assert velocity[0] == (1 + R(-5, 7)) / 2  # slows at a constant rate while sliding


def test_a_rolling_sphere_keeps_rolling_and_a_spin_about_the_normal_is_kept():
    roll = sliding((2, 0, 0), (0, 20, 7), R(1, 10), R(2, 5), R(1, 5), R(49, 5))
    assert roll.t == 0 and list(roll.velocity) == [2, 0, 0]
    side = sliding((1, 2, 0), (3, -1, 5), R(1, 4), R(2, 3), R(1, 3), 10)
    assert side.spin[2] == 5  # no pivoting friction


@pytest.mark.parametrize("seed", range(8))
def test_angular_momentum_about_the_touching_point_is_kept_while_sliding(seed):
    # a law the motion obeys, derived independently of its steps: friction acts through
    # the touching point, and weight and the normal force cancel
    rng = random.Random(seed)
    v = sp.Matrix([R(rng.randint(-9, 9), 4), R(rng.randint(-9, 9), 4), 0])
    w = sp.Matrix([R(rng.randint(-20, 20), 2) for _ in range(3)])
    radius, k = R(rng.randint(1, 5), 10), rng.choice([R(2, 5), R(2, 3), R(1, 2)])
    mu, g, m = R(rng.randint(1, 6), 10), 10, R(rng.randint(1, 5), 2)
    roll = sliding(v, w, radius, k, mu, g)
    before = _about_contact(m, k, radius, v, w)
    for when in (roll.t / 3, roll.t, roll.t + 1):
        _, v_t, w_t = roll.at(when)
        assert (_about_contact(m, k, radius, v_t, w_t) - before).applyfunc(
            sp.simplify) == sp.zeros(3, 1)
    # and it rolls from roll.t on: the touching point is at rest
    _, v_r, w_r = roll.at(roll.t)
    assert (v_r + w_r.cross(sp.Matrix([0, 0, -radius]))).applyfunc(sp.simplify) == \
        sp.zeros(3, 1)


def test_flight_is_a_parabola_with_the_spin_kept_and_lands_when_its_height_is_spent():
    p, v, w = flight((0, 0, 2), (1, 0, 3), (0, 5, 0), (0, 0, -10), R(1, 2))
    assert list(p) == [R(1, 2), 0, 2 + R(3, 2) - R(5, 4)] and list(w) == [0, 5, 0]
    t = landing_time(2, 3, 10)  # 2 + 3 t - 5 t^2 = 0: t = 1
    assert t == 1
    assert flight((0, 0, 2), (1, 0, 3), (0, 0, 0), (0, 0, -10), t)[0][2] == 0


def test_bad_input_is_refused_in_one_line():
    with pytest.raises(InputError, match="mu: must be positive"):
        sliding((1, 0, 0), (0, 0, 0), 1, R(2, 5), 0, 10)
    with pytest.raises(InputError, match="must lie in the flat"):
        sliding((1, 0, 1), (0, 0, 0), 1, R(2, 5), R(1, 5), 10)
    with pytest.raises(InputError, match="three components"):
        sliding((1, 0), (0, 0, 0), 1, R(2, 5), R(1, 5), 10)


def _superball_bounce(v, w, z_normal):
    """One bounce of Garwin's superball (uniform, R = 1, m = 1; perfectly rough and
    elastic: Walton's law with e = 1, beta = 1 and friction ample) on a flat of normal
    (0, 0, z_normal) below it (1) or above it (-1), by rigidimpact's 3-D core."""
    from rigidimpact import Body3, Contact, SpaceCollision

    ball = Body3.sphere(1, 1, (0, 0, z_normal), v, w, name="ball")
    out = SpaceCollision((Body3.fixed("flat"), ball), (Contact(
        normal=(0, 0, z_normal), restitution=1, tangential="rough", friction=100,
        tangential_restitution=1, bodies=("flat", "ball"), point=(0, 0, 0)),)).solve()
    r = out.results()
    assert all(value == 0 for value in out.checks.values())
    return ([r[f"ball.v{a}"] for a in "xyz"], [r[f"ball.omega_{a}"] for a in "xyz"])


def test_garwins_superball_bounces_with_three_sevenths_and_returns_under_a_table():
    # Garwin (Am. J. Phys. 37, 88, 1969): perfectly rough and elastic, a uniform sphere
    # thrown without spin at the floor leaves it at 3/7 of its horizontal speed, spinning
    # at 10/7 of it over R. By hand, in (v_x, R w_y): the floor's map is (1/7)[[3, 4],
    # [10, -3]] and the table's underside's (1/7)[[3, -4], [-10, -3]] (the touching
    # point above the centre); floor, table, floor take (1, 0) to (-333/343, -130/343):
    # the ball comes back toward the thrower at 0.97 of its speed
    v, w = _superball_bounce((1, 0, -1), (0, 0, 0), 1)
    assert (v, w) == ([R(3, 7), 0, 1], [0, R(10, 7), 0])
    v, w = _superball_bounce(v, w, -1)  # it rises to the underside of the table
    assert (v[0], w[1], v[2]) == (R(-31, 49), R(-60, 49), -1)
    v, w = _superball_bounce(v, w, 1)  # and falls to the floor again
    assert (v[0], w[1], v[2]) == (R(-333, 343), R(-130, 343), 1)
    # the two laws of a perfectly rough elastic bounce, checked on their own: the
    # touching point's tangential velocity reverses, and the angular momentum about it
    # is kept (the impulse passes through it)
    before_v, before_w = sp.Matrix([1, 0, -1]), sp.Matrix([0, 0, 0])
    after_v, after_w = (sp.Matrix(x) for x in _superball_bounce((1, 0, -1), (0, 0, 0), 1))
    arm = sp.Matrix([0, 0, -1])  # from the centre to the touching point
    slip_before = before_v + before_w.cross(arm)
    slip_after = after_v + after_w.cross(arm)
    assert (slip_after[0], slip_after[1]) == (-slip_before[0], -slip_before[1])
    assert R(2, 5) * after_w + (-arm).cross(after_v) == \
        R(2, 5) * before_w + (-arm).cross(before_v)
