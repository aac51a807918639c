"""Billiards: cut shots between equal balls by the 3-D contact solver, against hand
derivations and beside pooltool's FrictionalInelastic model; a ball striking a cushion
with the table's contact acting at the same time, against hand derivations, an
independent integration of Mathavan's equations and pooltool's Mathavan model (pooltool
runs where it is installed: ``make pooltool``)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rigidimpact.analyses.billiards import (
    CUSHION_HEIGHT,
    MASS,
    RADIUS,
    alciatore_friction,
    cushion,
    cut_shot,
)

SHOTS = [(cut, top, side) for cut in (5, 15, 30, 45, 60, 75)
         for top, side in ((0, 0), (1, 0), (-1, 0), (0, 0.5), (1, -0.5))]


def test_a_stun_shot_throws_by_the_hand_formula():
    # no spin: the slip at contact is v sin(cut) across the line of the centres; the
    # normal impulse per mass is (1 + e)/2 v cos(cut); the balls' W across is 7/m
    for cut in (5, 15, 30, 45, 60, 75):
        mu, e, v = 0.06, 0.95, 1.0
        out = cut_shot(cut, v, 0.0, 0.0, mu=mu, e=e)
        c, s = math.cos(math.radians(cut)), math.sin(math.radians(cut))
        normal = (1 + e) / 2 * v * c
        across = min(mu * normal, v * s / 7)  # slides throughout, or stops and sticks
        assert out["throw_degrees"] == pytest.approx(math.degrees(math.atan2(across, normal)),
                                                     rel=1e-12)
        assert out["course"] == ("slides throughout" if mu * normal <= v * s / 7
                                 else "slides, then sticks")


def test_alciatores_fit():
    assert alciatore_friction(0.0) == pytest.approx(0.117951)
    assert alciatore_friction(10.0) < 0.011


def _pooltool(cut: float, speed: float, top: float, side: float, mu: float, e: float):
    """pooltool's own ball-ball resolution (the installed version's function) on the
    same shot: ball 1 the cue ball, ball 2 the object ball."""
    model = pytest.importorskip(
        "pooltool.physics.resolve.ball_ball.frictional_inelastic")
    n = np.array([math.cos(math.radians(cut)), -math.sin(math.radians(cut)), 0.0])
    rolling = speed / RADIUS
    cue = np.array([-2 * RADIUS * n, [speed, 0.0, 0.0], [0.0, top * rolling,
                                                         side * rolling]])
    ball = np.zeros((3, 3))
    after_cue, after_ball = model._resolve_ball_ball(cue.copy(), ball.copy(), RADIUS, mu, e)
    return after_cue, after_ball


@pytest.mark.parametrize("cut,top,side", SHOTS)
def test_where_pooltools_assumptions_hold_both_agree_to_rounding(cut, top, side):
    # pooltool's model takes equal solid balls and a tangential change of
    # mu |relative normal velocity after|; at e = 1 that is mu times the normal impulse
    # per mass, Coulomb's law exactly, so the two must agree
    # except one thing pooltool 0.6.0 drops: a ball with top or draw spin slips
    # vertically at the contact, so friction has a vertical part; pooltool keeps its turn
    # on the spins but sets both balls' vertical velocity to zero (its "FIXME3D": the
    # table is left to absorb it), where the two balls alone keep their vertical
    # momentum: ours give the balls opposite vertical velocities, summing to zero
    mu = alciatore_friction(1.0)
    cue, ball = _pooltool(cut, 1.0, top, side, mu, 1.0)
    ours = cut_shot(cut, 1.0, top, side, mu=mu, e=1.0)
    for name, state in (("cue", cue), ("object", ball)):
        for i, axis in enumerate("xy"):
            assert ours[f"{name}.v{axis}"] == pytest.approx(state[1][i], abs=1e-12)
        for i, axis in enumerate("xyz"):
            assert ours[f"{name}.omega_{axis}"] == pytest.approx(state[2][i], abs=1e-9)
        assert state[1][2] == 0.0
    assert ours["cue.vz"] + ours["object.vz"] == pytest.approx(0.0, abs=1e-15)
    assert (abs(ours["object.vz"]) > 1e-3) == (top != 0)  # vertical slip: top or draw


def test_below_e_1_pooltool_takes_less_friction_than_coulombs_law():
    # at e < 1 pooltool's tangential change is mu e |v_n| where Coulomb's law gives
    # mu (1 + e)/2 |v_n| (the normal impulse per mass): on a sliding shot its throw is
    # smaller by the factor 2e / (1 + e); ours keeps |P_t| = mu P_n, read from the
    # object ball's momentum alone
    mu, e, cut = 0.06, 0.8, 45
    cue, ball = _pooltool(cut, 1.0, 0.0, 0.0, mu, e)
    ours = cut_shot(cut, 1.0, 0.0, 0.0, mu=mu, e=e)
    n = np.array([math.cos(math.radians(cut)), -math.sin(math.radians(cut)), 0.0])
    t = np.array([-n[1], n[0], 0.0])
    mine = np.array([ours["object.vx"], ours["object.vy"], ours["object.vz"]])
    assert abs(mine @ t) == pytest.approx(mu * (mine @ n), rel=1e-12)  # Coulomb
    theirs = ball[1]
    assert abs(theirs @ t) / abs(mine @ t) == pytest.approx(2 * e / (1 + e), rel=1e-9)
    assert theirs @ n == pytest.approx(mine @ n, rel=1e-12)  # the normal parts agree
    del cue


# -- a ball on the table striking a cushion (Mathavan, Jackson and Parkin 2010) --------

SPEEDS = ("vx", "vy", "omega_x", "omega_y", "omega_z")
CUSHION_SHOTS = [(30, 0, 0), (0, 0, 0), (45, 0.5, 0.3), (60, -0.5, -0.5), (20, 1, 0),
                 (0, 1, 0), (70, 1, 1)]


def _after(out: dict) -> np.ndarray:
    return np.array([out[f"ball.{k}"] for k in SPEEDS])


def _start(angle: float, top: float, side: float) -> list[float]:
    a, w = math.radians(angle), 1 / RADIUS
    return [math.sin(a), math.cos(a), -top * w * math.cos(a), top * w * math.sin(a),
            side * w]


def _mathavan_smoothed(angle: float, top: float, side: float, eps: float,
                       e: float = 0.85, mu_w: float = 0.2, mu_s: float = 0.2) -> np.ndarray:
    """Mathavan et al.'s equations of the ball in the cushion's normal impulse, written
    out here apart from the package (the table's normal impulse rate sin(theta) +
    mu_w sin(phi) cos(theta) in closed form, Coulomb's direction v/|v| smoothed to
    v/sqrt(|v|^2 + eps^2)), integrated by LSODA: as eps -> 0 this tends to Coulomb's
    law, slip and stick alike."""
    R, M = RADIUS, MASS
    st = (CUSHION_HEIGHT - R) / R
    ct = math.sqrt(1 - st * st)
    k = 5 / (2 * M * R)

    def rates(_p: float, y: np.ndarray) -> list[float]:
        vx, vy, ox, oy, oz, _ = y
        xI, yI = vx + oy * R * st - oz * R * ct, -vy * st + ox * R  # slip at the cushion
        xC, yC = vx - oy * R, vy + ox * R  # slip at the table
        nI, nC = math.hypot(xI, yI, eps), math.hypot(xC, yC, eps)
        cI, sI, cC, sC = xI / nI, yI / nI, xC / nC, yC / nC
        lam = st + mu_w * sI * ct  # the table's normal impulse rate (no lift)
        return [-(mu_w * cI + mu_s * cC * lam) / M,
                -(ct - mu_w * st * sI + mu_s * sC * lam) / M,
                -k * (mu_w * sI + mu_s * sC * lam),
                -k * (mu_w * cI * st - mu_s * cC * lam),
                k * mu_w * cI * ct,
                -vy * ct]  # the work of the cushion's normal impulse

    def compressed(_p: float, y: np.ndarray) -> float:
        return y[1]
    compressed.terminal, compressed.direction = True, -1  # type: ignore[attr-defined]
    first = solve_ivp(rates, (0, 10), [*_start(angle, top, side), 0.0], method="LSODA",
                      rtol=1e-11, atol=1e-13, events=compressed)
    work_c = first.y[5, -1]

    def restored(_p: float, y: np.ndarray) -> float:
        return (y[5] - work_c) + e * e * work_c
    restored.terminal, restored.direction = True, 1  # type: ignore[attr-defined]
    second = solve_ivp(rates, (first.t[-1], 10), first.y[:, -1], method="LSODA",
                       rtol=1e-11, atol=1e-13, events=restored)
    return second.y[:5, -1]


@pytest.mark.parametrize("angle,top,side", CUSHION_SHOTS[:5])
def test_the_cushion_is_the_limit_of_mathavans_equations_with_smoothed_friction(
        angle, top, side):
    # the smoothed equations' gap to the answer shrinks with eps, ten times per decade,
    # and is within 2e-4 (of speeds near 1 m/s and spins near 10 rad/s) at eps = 1e-6
    ours = _after(cushion(1.0, angle, top, side))
    gaps = [np.abs(_mathavan_smoothed(angle, top, side, eps) - ours).max()
            for eps in (1e-4, 1e-6)]
    assert gaps[1] < 2e-4
    assert gaps[1] < gaps[0] / 30


def test_a_frictionless_cushion_and_table_give_back_e_times_the_normal_speed():
    # no friction: the cushion's impulse runs through the centre (no spin changes) and
    # the table's cancels its vertical part, so only v_y changes; the cushion's normal
    # velocity is -v_y cos(theta), and without friction the energetic law is Newton's,
    # so v_y -> -e v_y
    for angle in (0, 30, 60):
        out = cushion(1.0, angle, 0.5, 0.2, e=0.85, mu_cushion=0.0, mu_table=0.0)
        before = _start(angle, 0.5, 0.2)
        assert out["ball.vx"] == pytest.approx(before[0], abs=1e-12)
        assert out["ball.vy"] == pytest.approx(-0.85 * before[1], rel=1e-9)
        assert out["ball.vz"] == pytest.approx(0.0, abs=1e-12)
        for k in (2, 3, 4):
            assert out[f"ball.{SPEEDS[k]}"] == pytest.approx(before[k], rel=1e-12)


def test_a_cushion_at_the_equator_leaves_the_table_idle():
    # h = R: the cushion's normal is horizontal, so nothing presses the ball into the
    # table and the table's friction does nothing, however rough; a smooth cushion then
    # gives v_y -> -e v_y with every other speed unchanged
    out = cushion(1.0, 40, 1.0, -0.3, mu_cushion=0.0, mu_table=0.9, height=RADIUS)
    before = _start(40, 1.0, -0.3)
    assert out["table.normal_impulse"] == pytest.approx(0.0, abs=1e-12)
    assert out["ball.vy"] == pytest.approx(-0.85 * before[1], rel=1e-9)
    assert out["ball.omega_y"] == pytest.approx(before[3], rel=1e-12)


@pytest.mark.parametrize("angle,top,side", CUSHION_SHOTS)
def test_the_cushion_obeys_its_laws(angle, top, side):
    out = cushion(1.0, angle, top, side)
    solution = out["solution"]
    assert max(solution.checks.values()) < 1e-12
    assert out["table.normal_impulse"] > 0 and out["cushion.normal_impulse"] > 0
    for name, mu in (("cushion", 0.2), ("table", 0.2)):
        assert out[f"{name}.tangential_impulse"] <= mu * out[f"{name}.normal_impulse"] \
            * (1 + 1e-12)
    assert out["ball.vz"] == pytest.approx(0.0, abs=1e-12)  # the table holds the ball
    assert 0 < solution.energies[1]  # energy is lost


def test_a_head_on_shot_rebounds_straight_back():
    # mirror symmetry across the plane of the path: nothing may move sideways or turn
    # about the vertical or the path's own axis
    for top in (0.0, 1.0, -0.7):
        out = cushion(1.0, 0, top, 0)
        for k in ("vx", "omega_y", "omega_z"):
            assert out[f"ball.{k}"] == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("angle,top,side", CUSHION_SHOTS)
def test_pooltools_mathavan_model_tends_to_the_same_answer(angle, top, side):
    # pooltool integrates the same equations with fixed steps (Euler's method, a
    # slip direction from atan2 that chatters where a contact sticks): its gap to the
    # answer falls about tenfold when its steps are ten times finer
    model = pytest.importorskip("pooltool.physics.resolve.ball_cushion.mathavan_2010.model")
    ours = _after(cushion(1.0, angle, top, side))
    gaps = [np.abs(np.array(model.solve(MASS, RADIUS, CUSHION_HEIGHT, 0.85, 0.2, 0.2,
                                        *_start(angle, top, side), steps, 1e-12)) - ours)
            .max() for steps in (1000, 100000)]
    assert gaps[1] < 2e-4
    assert gaps[1] < gaps[0] / 20


def test_a_ball_lifted_off_the_table_by_the_cushion_is_followed():
    # a stun shot at 30 degrees into a cushion of friction 0.67 or more: the cushion's
    # friction lifts the ball (the table lets go at once), and when the cushion's
    # contact sticks the ball comes down onto the table again within the impact; its gap
    # is still zero, so the table touches again and rests. Once refused ("please
    # report"). The answer is checked by the laws it must obey: the certificate, the
    # ball leaving the table level (its vertical speed zero to the integration's
    # tolerance), the table never pulling, and the rebound continuous in the friction
    # across the friction where the table begins to let go
    from rigidimpact.analyses.billiards import cushion

    below = cushion(2.0, 30, topspin=0, mu_cushion=0.66)
    for mu in (0.67, 1.0):
        shot = cushion(2.0, 30, topspin=0, mu_cushion=mu)
        assert shot["courses"][1].startswith("table: lets go, then slides")
        solution = shot["solution"]
        assert abs(shot["ball.vz"]) < 1e-9
        assert solution.impulses["table"] >= 0
        assert max(abs(float(v)) for v in solution.checks.values()) < 1e-9
        assert solution.assessed()[1] == []
    near = cushion(2.0, 30, topspin=0, mu_cushion=0.67)
    assert abs(near["rebound_degrees"] - below["rebound_degrees"]) < 1e-2
    assert abs(near["rebound_speed"] - below["rebound_speed"]) < 1e-3
