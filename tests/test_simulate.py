"""The simulation planner and runner (free flight after the impact)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.paper.published import F
from rigidimpact.scenes.scene import load_scene, parse_scene
from rigidimpact.simulate import EFFECTS, make_plan, run
from rigidimpact.simulate.flight import Flyer, first_contact, reach_interval
from rigidimpact.symbolic.notation import symbol

DERIVATIONS = Path(__file__).resolve().parent.parent / "derivations"


def test_plan_picks_only_what_the_scene_asks():
    assert [s.model for s in make_plan({}).steps] == ["impulse"]
    assert [s.model for s in make_plan({"until": "restrike"}).steps] == ["impulse",
                                                                          "free-flight"]
    plan = make_plan({"until": 2.0, "effects": ["gravity"]})
    assert plan.effects == ("gravity",)
    assert set(plan.not_simulated) | set(plan.effects) == set(EFFECTS)


@pytest.mark.parametrize("table, field", [({"until": -1}, "simulate.until"),
                                          ({"until": True}, "simulate.until"),
                                          ({"effects": ["magic"]}, "simulate.effects"),
                                          ({"effects": "gravity"}, "simulate.effects"),
                                          ({"rod_stiffness": -5}, "simulate.rod_stiffness"),
                                          ({"speed": 1}, "simulate.speed")])
def test_plan_rejects_bad_tables(table, field):
    with pytest.raises(InputError, match=field):
        make_plan(table)


def test_separation_gives_the_papers_velocities():
    outcome = run(load_scene(DERIVATIONS / "barbell.toml"))
    # eq. (5) at m = 1, M = 2, theta = 30 deg, e = 0.5, v_ix = 1, L = 0.5
    f = float(F.subs({symbol("m"): 1, symbol("M"): 2, symbol("e"): 0.5,
                      symbol("theta"): sp.pi / 6}))
    assert math.isclose(outcome.final["barbell.vx"], f, rel_tol=1e-14)
    assert math.isclose(outcome.final["barbell.omega"], f * 0.5 / 0.5, rel_tol=1e-14)
    assert math.isclose(outcome.final["ball.vx"], (1 - 4 * f), rel_tol=1e-14)
    assert [e["kind"] for e in outcome.events] == ["impact", "end"]


def test_restrike_time_and_place_follow_from_free_flight():
    outcome = run(load_scene(DERIVATIONS / "restrike.toml"))
    event = outcome.events[-2]
    assert event["kind"] == "restrike"
    t, fin = event["t"], outcome.final
    # at the event the ball lies on the rod's line, between the spheres
    phi = math.radians(10) + fin["barbell.turn"]
    rel = (fin["ball.x"] - fin["barbell.x"], fin["ball.y"] - fin["barbell.y"])
    assert abs(math.cos(phi) * rel[1] - math.sin(phi) * rel[0]) < 1e-12
    assert math.hypot(*rel) < 0.5
    assert math.isclose(fin["ball.x"], fin["ball.vx"] * t, rel_tol=1e-14)


def test_no_restrike_above_the_critical_angle():
    text = (DERIVATIONS / "restrike.toml").read_text().replace('"10 deg"', '"25 deg"')
    outcome = run(parse_scene(text, "restrike25"))
    assert [e["kind"] for e in outcome.events] == ["impact", "out-of-reach", "end"]


def test_simulate_needs_values(tmp_path):
    text = (DERIVATIONS / "restrike.toml").read_text().replace('theta = "10 deg"\n', "")
    with pytest.raises(InputError, match="theta"):
        run(parse_scene(text, "novalue"))


def test_reach_interval_is_a_line_against_a_circle():
    import numpy as np

    assert reach_interval(np.array([-2.0, 0.0]), np.array([1.0, 0.0]), 1.0) == (1.0, 3.0)
    assert reach_interval(np.array([2.0, 0.0]), np.array([1.0, 0.0]), 1.0) is None


def test_a_short_crossing_between_samples_is_not_missed():
    # the rod turns fast and the ball only clips the tip region briefly: the contact
    # lasts far less than any sensible sampling step, and must still be found
    rod = Flyer("rod", "rod", (0.0, 0.0), (0.0, 0.0), 50.0, ends=((-1.0, 0.0), (1.0, 0.0)))
    ball = Flyer("ball", "particle", (-2.0, 0.999), (1.0, 0.0), 0.0)
    hit = first_contact(ball, rod)
    assert hit is not None and hit.t > 1.9
    x, y = hit.point
    assert abs(math.hypot(x, y) - abs(hit.s)) < 1e-9 and abs(hit.s) <= 1.0
