"""The shipped draw shot (derivations/draw-shot.toml) against a derivation by hand.

The cue ball (mass m, radius R, k = I/(m R^2) = 2/5) meets an equal object ball straight
on along x at v = 3/2 with backspin w = -3000/57 about y (R w = -3/2; rolling along +x
is +w), the balls smooth with e = 19/20. By hand:

- the meeting: the cue ball keeps v' = (1 - e)/2 v and all its spin, the object ball
  leaves at (1 + e)/2 v, the impulse is m (1 + e)/2 v, and the energy lost is
  m v^2 (1 - e^2)/4 of the energy before, m v^2/2 + k m R^2 w^2/2;
- the cue ball's slide: its lowest point slips at s = v' - R w > 0, so the cloth pushes
  it back at mu g and the slip shrinks at mu g (1 + 1/k); it rolls after
  s / (mu g (1 + 1/k)). About the touching point friction has no moment (and the weight
  and the cloth's push act along one vertical line), so the angular momentum there,
  k m R^2 w + m R v, is kept: it rolls at (v' + k R w)/(1 + k), backwards since
  R |w| > v'/k. The centre turns back at v'/(mu g);
- rolling, each ball is slowed at mu_r g until it meets a rail R from its plane.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction as F
from pathlib import Path

import pytest

import rigidimpact as ri
from rigidimpact.cli import main

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "derivations" / "draw-shot.toml"
GOLDEN = ROOT / "tests" / "golden" / "scenes"

M, R, K = F(17, 100), F(57, 2000), F(2, 5)
V, W, E = F(3, 2), F(-3000, 57), F(19, 20)
MU, G, MU_R = F(1, 5), F(49, 5), F(1, 100)

V_CUE = (1 - E) / 2 * V  # 3/80
V_OBJECT = (1 + E) / 2 * V  # 117/80
ROLL_BACK = (V_CUE + K * R * W) / (1 + K)  # -45/112


def _by_hand() -> dict[str, F]:
    before = M * V ** 2 / 2 + K * M * R ** 2 * W ** 2 / 2
    lost = M * V ** 2 * (1 - E ** 2) / 4
    zero = {f"{b}.{q}": F(0) for b in ("cue", "object")
            for q in ("vy", "vz", "omega_x", "omega_z")}
    return {**zero, "cue.vx": V_CUE, "cue.omega_y": W, "object.vx": V_OBJECT,
            "object.omega_y": F(0), "impulse": M * V_OBJECT,
            "balls.normal_impulse": M * V_OBJECT, "energy_loss_fraction": lost / before,
            "cloth.normal_impulse": F(0), "cloth_object.normal_impulse": F(0)}


def test_the_numbers_by_hand_are_the_ones_the_scene_states():
    assert (V_CUE, V_OBJECT, ROLL_BACK) == (F(3, 80), F(117, 80), F(-45, 112))
    assert R * W == -V  # backspin as fast as rolling at its speed, the other way


def test_the_meeting_is_the_hand_derivation(capsys):
    assert main(["evaluate", str(SCENE), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key, value in _by_hand().items():
        assert out[key] == pytest.approx(float(value), rel=1e-15, abs=1e-15), key
    assert out["regime"] == ("balls: smooth; cloth: stays closed, carrying nothing; "
                             "cloth_object: stays closed, carrying nothing")


def test_the_pinned_results_are_the_hand_derivation():
    # the golden files were written by derive/evaluate --json and are held here to the
    # derivation by hand, exactly
    import sympy as sp

    derived = json.loads((GOLDEN / "draw-shot.derive.json").read_text())["results"]
    numbers = json.loads((GOLDEN / "draw-shot.evaluate.json").read_text())
    for key, value in _by_hand().items():
        assert sp.Rational(derived[key]["sympy"]) == sp.Rational(value.numerator,
                                                                 value.denominator), key
        assert numbers[key] == pytest.approx(float(value), rel=1e-15, abs=1e-15), key


def _events(text: str | None = None) -> list:
    scene = ri.load_any(SCENE) if text is None else _parsed(text)
    return ri.run(scene).trajectory.run.events


def _parsed(text: str):
    from rigidimpact.scenes.space import parse_space_scene

    return parse_space_scene(text)


def _first(events: list, ball: str, kind: str, plane: str | None = None):
    return next(e for e in events if e.ball == ball and e.kind == kind
                and (plane is None or e.plane == plane))


def _vec(x) -> list[float]:
    return [float(y) for y in x]


def test_the_cue_ball_comes_back_at_the_speed_its_kept_angular_momentum_gives():
    events = _events()
    meet = events[0]
    assert (meet.t, meet.kind, meet.ball, meet.other) == (0, "impact", "cue", "object")
    roll = _first(events, "cue", "rolls")
    slip = V_CUE - R * W
    t_roll = slip / (MU * G * (1 + 1 / K))
    assert float(roll.t) == pytest.approx(float(t_roll), rel=1e-14)
    assert _vec(roll.velocity) == pytest.approx([float(ROLL_BACK), 0, 0], rel=1e-14, abs=1e-15)
    assert _vec(roll.spin) == pytest.approx([0, float(ROLL_BACK / R), 0], rel=1e-14, abs=1e-14)
    # the angular momentum about the touching point, at the meeting and when it rolls
    about = [K * M * R ** 2 * float(e.spin[1]) + M * R * float(e.velocity[0])
             for e in (meet, roll)]
    assert about[1] == pytest.approx(about[0], rel=1e-14)
    # it slid under a constant push mu m g backwards: its centre where that puts it, and
    # its velocity falling at mu g through zero at v'/(mu g)
    x = V_CUE * t_roll - MU * G * t_roll ** 2 / 2
    assert float(roll.position[0]) == pytest.approx(float(x), rel=1e-14)
    rate = (float(roll.velocity[0]) - float(V_CUE)) / float(roll.t)
    assert rate == pytest.approx(-float(MU * G), rel=1e-14)
    turn = float(V_CUE / (MU * G))
    assert 0 < turn < float(roll.t)


def test_each_ball_rolls_to_its_rail_when_the_hand_derivation_says():
    events = _events()
    # the cue ball, rolling back from where it began to roll, slowed at mu_r g, meets the
    # head rail when its centre is R from x = -1/2
    roll = _first(events, "cue", "rolls")
    x0, u, a = float(roll.position[0]), -float(roll.velocity[0]), float(MU_R * G)
    gap = x0 - (-0.5 + float(R))
    tau = (u - math.sqrt(u * u - 2 * a * gap)) / a
    rail = _first(events, "cue", "impact", "head_rail")
    assert float(rail.t) == pytest.approx(float(roll.t) + tau, rel=1e-12)
    # the object ball slides at mu g, rolls from 2 u/(7 mu g) at 5/7 of its speed, and
    # meets the foot rail when its centre is R from x = 5/2
    t_o = 2 * V_OBJECT / (7 * MU * G)
    roll = _first(events, "object", "rolls")
    assert float(roll.t) == pytest.approx(float(t_o), rel=1e-14)
    x0 = 2 * R + V_OBJECT * t_o - MU * G * t_o ** 2 / 2
    u = F(5, 7) * V_OBJECT
    assert float(roll.position[0]) == pytest.approx(float(x0), rel=1e-14)
    assert float(roll.velocity[0]) == pytest.approx(float(u), rel=1e-14)
    gap = float(F(5, 2) - R - x0)
    tau = (float(u) - math.sqrt(float(u) ** 2 - 2 * float(MU_R * G) * gap)) / float(MU_R * G)
    rail = _first(events, "object", "impact", "foot_rail")
    assert float(rail.t) == pytest.approx(float(t_o) + tau, rel=1e-12)


@pytest.mark.parametrize("backspin, comes_back", [(F(1, 2), False), (F(2), True)])
def test_the_cue_ball_comes_back_only_with_backspin_beyond_5_2_of_the_speed_it_kept(
        backspin, comes_back):
    # R |w| against (5/2) v' = 3/32: half of that follows on, twice it draws back
    w = -backspin * F(5, 2) * V_CUE / R
    text = SCENE.read_text().replace('"-3000/57"', f'"{w}"').replace("until = 7", "until = 1")
    roll = _first(_events(text), "cue", "rolls")
    expected = (V_CUE + K * R * w) / (1 + K)
    assert (expected < 0) is comes_back
    assert float(roll.velocity[0]) == pytest.approx(float(expected), rel=1e-14)
