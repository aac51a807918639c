"""A sphere among fixed planes: flight, the next contact, each impact, and the sliding
to rolling where a bounce leaves it lying on the floor; against hand derivations."""

from __future__ import annotations

import random
from pathlib import Path

import pytest
import sympy as sp

from helpers import scene_file
from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.space import Body3
from rigidimpact.simulate.bounces import bounces

R = sp.Rational
ROUGH = dict(restitution=1, tangential="rough", tangential_restitution=1)


def _floor(**laws):
    return Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                   name="floor", **laws)


def test_garwins_superball_comes_back_from_under_the_table():
    # no gravity (Garwin's fast throw): floor at z = 0, the table's underside at z = 3;
    # the ball (R = 1) leaves the floor at (3/7, 0, 1) with spin 10/7 about y, meets
    # the table at t = 1 at x = 3/7, and the floor at t = 2; after the third bounce it
    # moves at (-333/343, 0, 1) (hand derivation, tests/test_sphere_motion.py)
    ball = Body3.sphere(1, 1, (0, 0, 1), (1, 0, -1), name="ball")
    table = Contact(normal=(0, 0, -1), bodies=("table", "ball"), point=(0, 0, 3),
                    name="table", **ROUGH)
    run = bounces(ball, (_floor(**ROUGH), table), gravity=(0, 0, 0), impacts=3)
    assert [(e.t, e.plane) for e in run.events] == [(0, "floor"), (1, "table"), (2, "floor")]
    assert run.events[0].velocity.T.tolist() == [[R(3, 7), 0, 1]]
    assert run.events[0].spin[1] == R(10, 7)
    assert run.events[1].position.T.tolist() == [[R(3, 7), 0, 2]]
    assert run.velocity.T.tolist() == [[R(-333, 343), 0, 1]] and run.exact
    assert run.stopped == "impacts"


def test_a_ball_landing_without_bounce_slides_then_rolls_at_five_sevenths():
    # dropped from 1 above the floor (R = 1, g = 49/5) moving at 3 along x, e = 0, mu =
    # 1/10: it lands at sqrt(2/g), slides through the impact (mu (7/2) P_n < 3) and on
    # the floor until it rolls; its angular momentum about the touching point is kept
    # throughout (every impulse and friction force acts there), so it rolls at
    # (5/7) 3 = 15/7. Hand numbers: P_n = sqrt(2 g), after the impact v_x = 3 - P_n/10
    # and w_y = (5/2) P_n/10; it rolls after (v_x - w_y) / (mu g (1 + 5/2)) more
    g = R(49, 5)
    ball = Body3.sphere(1, 1, (0, 0, 2), (3, 0, 0), name="ball")
    run = bounces(ball, (_floor(restitution=0, tangential="coulomb", friction=R(1, 10)),),
                  gravity=(0, 0, -g), impacts=5)
    (landing, rolls) = run.events
    p_n = sp.sqrt(2 * g)
    assert abs(landing.t - sp.sqrt(2 / g)) < 1e-35
    assert abs(landing.velocity[0] - (3 - p_n / 10)) < 1e-35
    assert abs(landing.spin[1] - R(5, 2) * p_n / 10) < 1e-35
    slip = (3 - p_n / 10) - R(5, 2) * p_n / 10
    assert abs(rolls.t - (sp.sqrt(2 / g) + slip / (g / 10 * R(7, 2)))) < 1e-35
    assert abs(run.velocity[0] - R(15, 7)) < 1e-35 and run.stopped == "rolling"
    assert not run.exact  # sqrt(2/g) is irrational: floating point from the landing on


def test_the_events_do_not_depend_on_the_horizon():
    # a ball bouncing with e = 1/2 on a rough floor: its impacts up to t = 1 are the same
    # whether the run is asked to stop at 1 or at 2
    ball = Body3.sphere(1, R(1, 10), (0, 0, 1), (1, 0, 0), (0, 5, 0), name="ball")
    floor = _floor(restitution=R(1, 2), tangential="coulomb", friction=R(1, 5))
    short = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=1)
    long = bounces(ball, (floor,), gravity=(0, 0, -10), horizon=2)
    assert short.events and short.stopped == "horizon"
    assert [(e.t, tuple(e.velocity)) for e in short.events] == \
        [(e.t, tuple(e.velocity)) for e in long.events[:len(short.events)]]
    assert all(e.t >= 1 for e in long.events[len(short.events):])
    # each bounce leaves at half the landing speed (e = 1/2), the floor being smooth
    # along the normal: the rebound heights fall by 1/4
    ups = [e.velocity[2] for e in long.events if e.kind == "impact"]
    assert all(abs(b / a - R(1, 2)) < 1e-30 for a, b in zip(ups, ups[1:], strict=False))
    # they pile up (summed) where the flights 2 e^i v1 / g, after the first landing at
    # v1 = sqrt(2 g 0.9) = 3 sqrt(2) at t1 = 0.3 sqrt(2), add up to 2 e v1 / (g (1 - e)):
    # at 0.9 sqrt(2)
    kinds = [e.kind for e in long.events]
    assert kinds[-2:] == ["settles", "rolls"]
    assert abs(long.events[-2].t - R(9, 10) * sp.sqrt(2)) < 1e-30
    # rolling: (v + k R w x n)/(1 + k) = (1 + (2/5)(1/10) 5)/(7/5) = 6/7
    assert all(abs(x - y) < 1e-30 for x, y in zip(long.velocity, (R(6, 7), 0, 0), strict=True))


def test_bad_input_is_refused_in_one_line():
    ball = Body3.sphere(1, 1, (0, 0, 1), (1, 0, -1), name="ball")
    with pytest.raises(InputError, match="give a number of impacts or a time"):
        bounces(ball, (_floor(**ROUGH),))
    with pytest.raises(InputError, match="simulate.impacts"):
        bounces(ball, (_floor(**ROUGH),), impacts=0)
    with pytest.raises(InputError, match="must name the sphere"):
        bounces(ball, (Contact(normal=(0, 0, 1), bodies=("floor", "other"),
                               point=(0, 0, 0), restitution=1),), impacts=1)
    with pytest.raises(InputError, match="a positive time"):
        bounces(ball, (_floor(**ROUGH),), horizon=-1)


def test_a_ball_lying_on_the_floor_at_the_start_slides_and_rolls_and_stays_there():
    # set down on the floor moving at 1 without spin (R = 1/10, mu = 1/5, g = 981/100):
    # it slides until t = 1 / (mu g (1 + 5/2)) and rolls at 5/7; it never falls through
    g = R(981, 100)
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, 0), name="ball")
    run = bounces(ball, (_floor(restitution=R(1, 2), tangential="coulomb",
                                friction=R(1, 5)),), gravity=(0, 0, -g), horizon=2)
    (rolls,) = run.events
    assert rolls.kind == "rolls" and rolls.t == 1 / (R(1, 5) * g * R(7, 2))
    assert run.velocity.T.tolist() == [[R(5, 7), 0, 0]] and run.position[2] == R(1, 10)
    assert run.exact and run.stopped == "horizon"


def test_a_rolling_ball_strikes_a_cushion_with_the_floor_resting_by_hand():
    # rolling at 1 (R = 1/10, spin 10 about y) into a smooth cushion at x = 1, e = 1/2:
    # it strikes at t = 9/10, the floor resting (the cushion's impulse is level, so the
    # floor takes none and gives no friction): v_x = -1/2, the spin kept. Then the floor
    # brings it to roll; its angular momentum about the touching point is kept, so it
    # rolls at (5/7)(v + (2/5) R w x n) = (5/7)(-1/2 + 2/5) = -1/14. The cushion's own
    # impact leaves the floor open, so the driven rule takes it exactly: the run stays
    # exact
    g = R(981, 100)
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, 0), (0, 10, 0), name="ball")
    floor = _floor(restitution=R(1, 2), tangential="coulomb", friction=R(1, 5))
    cushion = Contact(normal=(-1, 0, 0), bodies=("rail", "ball"), point=(1, 0, 0),
                      name="cushion", restitution=R(1, 2))
    run = bounces(ball, (floor, cushion), gravity=(0, 0, -g), horizon=3)
    kinds = [(e.kind, e.plane) for e in run.events]
    assert kinds == [("rolls", "floor"), ("impact", "cushion"), ("rolls", "floor")]
    hit = run.events[1]
    assert hit.t == R(9, 10) and "floor: stays closed, carrying nothing" in hit.course
    assert hit.velocity.T.tolist() == [[-R(1, 2), 0, 0]]
    assert hit.spin.T.tolist() == [[0, 10, 0]]
    assert run.velocity.T.tolist() == [[-R(1, 14), 0, 0]]
    assert run.position[2] == R(1, 10) and run.exact and run.tolerance is None
    # the same run asked to stop earlier has the same first events (horizon-free)
    early = bounces(ball, (floor, cushion), gravity=(0, 0, -g), horizon=1)
    assert [(e.t, e.kind) for e in early.events] == [(e.t, e.kind) for e in run.events[:2]]


def test_a_ball_lying_on_a_slope_is_refused_in_one_line():
    slope = Contact(normal=(0, R(3, 5), R(4, 5)), bodies=("floor", "ball"), point=(0, 0, 0),
                    name="slope", restitution=0, tangential="coulomb", friction=R(1, 2))
    ball = Body3.sphere(1, 1, (0, R(3, 5), R(4, 5)), (0, 0, 0), name="ball")
    with pytest.raises(InputError, match="slope"):
        bounces(ball, (slope,), gravity=(0, 0, -10), horizon=1)


def test_a_sliding_ball_strikes_a_cushion_at_an_irrational_time():
    # set down moving at 1 without spin, the cushion 1/20 beyond its surface: it strikes
    # while still sliding, at the earlier root of t - (mu g / 2) t^2 = 1/20 (irrational),
    # so the run goes on in floating point; the centre never passes the cushion's reach
    g = R(981, 100)
    ball = Body3.sphere(1, R(1, 10), (0, 0, R(1, 10)), (1, 0, 0), name="ball")
    floor = _floor(restitution=R(1, 2), tangential="coulomb", friction=R(1, 5))
    cushion = Contact(normal=(-1, 0, 0), bodies=("rail", "ball"), point=(R(3, 20), 0, 0),
                      name="cushion", restitution=R(1, 2))
    run = bounces(ball, (floor, cushion), gravity=(0, 0, -g), horizon=1)
    hit = next(e for e in run.events if e.kind == "impact")
    mu_g = R(1, 5) * g
    when = (1 - sp.sqrt(1 - 2 * mu_g / 20)) / mu_g
    assert hit.plane == "cushion" and abs(hit.t - when) < 1e-30 and not run.exact
    assert abs(hit.position[0] - R(1, 20)) < 1e-30 and hit.velocity[0] < 0
    assert all(e.position[0] <= R(1, 20) + 1e-30 for e in run.events)
    assert run.position[0] < R(1, 20)


def test_a_ball_that_starts_through_a_rail_is_refused_naming_both(tmp_path, capsys):
    # the stun shot with its far rail moved from y = 1/2 to y = -0.01: the cue ball's
    # centre (y = 0) is on the rail's far side, the object ball's (y = 0.0342) 0.0442
    # beyond it; the run used to ignore the rail and roll the object ball on to y = 2.26
    text = Path("derivations/stun-shot.toml").read_text(encoding="utf-8")
    moved = text.replace('point = ["0", "1/2", "0"]', 'point = ["0", "-0.01", "0"]', 1)
    assert moved != text
    assert main(["simulate", scene_file(tmp_path, moved)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "far_rail" in err and "cue starts through" in err


def test_random_starts_near_a_plane_are_refused_exactly_when_through():
    # seed 2: a sphere of radius r whose centre is s from a plane, on the side the
    # plane's normal points to for the sphere (normal along a rational unit vector; the
    # contact names the sphere first or second); it starts through the plane exactly
    # when s < r, touching (lying, or leaving) when s = r
    rng = random.Random(2)
    for _ in range(40):
        p, q = R(rng.randint(-9, 9), rng.randint(1, 9)), R(rng.randint(-9, 9), rng.randint(1, 9))
        k = 1 + p * p + q * q
        n = sp.Matrix([2 * p / k, 2 * q / k, (p * p + q * q - 1) / k])
        r = R(rng.randint(1, 20), 10)
        s = r * rng.choice((R(-3, 2), 0, R(1, 2), R(99, 100), 1, R(101, 100), 2))
        at = sp.Matrix([rng.randint(-5, 5) for _ in range(3)])
        first = rng.random() < 0.5
        ball = Body3.sphere(1, r, tuple(at + s * n), name="ball")
        plane = Contact(normal=tuple(-n if first else n),
                        bodies=("ball", "wall") if first else ("wall", "ball"),
                        point=tuple(at), name="wall", restitution=R(1, 2))
        if s < r:
            with pytest.raises(InputError, match="ball starts through the plane wall"):
                bounces(ball, (plane,), gravity=(0, 0, 0), horizon=1)
        else:
            assert bounces(ball, (plane,), gravity=(0, 0, 0), horizon=1).stopped in \
                ("horizon", "flying", "rolling", "rest")
