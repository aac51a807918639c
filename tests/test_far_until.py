"""A far `until` costs closed-form time once nothing acts, in every simulation mode, and
the event found does not depend on how far the horizon is."""

from __future__ import annotations

from pathlib import Path

import mpmath as mp
import pytest

from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.simulate import run

ROOT = Path(__file__).parents[1]
G = 9.81

ROD_LANDS = """
title = "a rod lands flat and spins"
[[bodies]]
name = "bar"
shape = "rigid"
mass = "1"
inertia = "1/3"
position = ["0", "0"]
velocity = ["0", "-1"]
spin = "1/2"
[[bodies]]
name = "floor"
shape = "fixed"
[[contacts]]
name = "p0"
bodies = ["bar", "floor"]
point = ["-1", "0"]
normal = ["0", "-1"]
restitution = "1"
[[contacts]]
name = "p1"
bodies = ["bar", "floor"]
point = ["1", "0"]
normal = ["0", "-1"]
restitution = "1"
[impact]
rule = "simultaneous"
[simulate]
effects = ["gravity"]
"""


def _scene(text: str, until: str):
    return parse_scene(text + f"until = {until}\n")


@pytest.mark.parametrize("until", ["2", "1e6", "1e8", "1e12", "1e300"])
def test_the_next_landing_does_not_depend_on_the_horizon(until):
    # by hand: both ends act (e = 1) and the rod leaves at vy = 1 with its spin -1/2
    # (the simultaneous impulses cancel the spin's part at each end); its right end
    # is at height t - g t^2 / 2 - sin(t / 2) and lands at that function's first root
    expected = mp.findroot(lambda t: t - G * t**2 / 2 - mp.sin(t / 2), 0.1)
    outcome = run(_scene(ROD_LANDS, until))
    restrike = outcome.events[1]
    assert restrike["kind"] == "restrike" and restrike["contacts"] == ["p1"]
    assert restrike["t"] == pytest.approx(float(expected), rel=1e-12)
    assert type(restrike["t"]) is float  # never numpy's repr in the output


@pytest.mark.parametrize("until", ["1", "1e300"])
def test_no_effects_a_far_horizon_is_closed_form(until):
    text = (ROOT / "derivations" / "newtons-cradle.toml").read_text().split("[simulate]")[0]
    outcome = run(parse_scene(text + f"[simulate]\nuntil = {until}\n"))
    assert outcome.final["t"] == float(until)
    # the last ball leaves at 1 (e = 1, equal balls): it is at 1 * t past where it was
    assert outcome.final["last.vx"] == pytest.approx(1.0)


def _barbell_compliant(until: str, effects: str) -> str:
    text = (ROOT / "derivations" / "compliant.toml").read_text()
    text = text.replace('until = "separation"', f"until = {until}")
    return text.replace('effects = ["rod-compliance", "contact-compliance"]',
                        f"effects = {effects}")


def test_contact_compliance_with_gravity_a_far_horizon_is_closed_form_or_refused():
    effects = '["contact-compliance", "gravity"]'
    far = run(parse_scene(_barbell_compliant("1e6", effects)))
    # a fall of 1e6 s: -g t, in closed form, not a million seconds of steps
    assert far.final["ball.vy"] == pytest.approx(-G * 1e6, rel=1e-9)
    with pytest.raises(InputError, match="float64's range"):
        run(parse_scene(_barbell_compliant("1e300", effects)))


@pytest.mark.parametrize("effects", ['["contact-compliance"]'])
def test_contact_compliance_a_far_horizon_costs_nothing_after_separation(effects):
    near = run(parse_scene(_barbell_compliant("1", effects)))
    far = run(parse_scene(_barbell_compliant("1e300", effects)))
    assert far.final["t"] == 1e300 and "closed form" in far.events[-1]["why"]
    # after separation no force acts: the same velocities as at t = 1, by momentum
    for key in ("ball.vx", "barbell.vx", "barbell.omega"):
        assert far.final[key] == pytest.approx(near.final[key], rel=1e-12)
    # and the positions move on at those velocities (relative motion, gravity aside)
    gap_rate = far.final["barbell.vx"] - far.final["ball.vx"]
    assert far.final["barbell.x"] - far.final["ball.x"] == pytest.approx(gap_rate * 1e300,
                                                                          rel=1e-9)


def test_rod_compliance_a_far_horizon_is_refused_before_the_run():
    # a ringing rod never stops acting: no closed form; refused at once, in one line
    with pytest.raises(InputError, match="integration steps"):
        run(parse_scene(_barbell_compliant("1e300", '["rod-compliance"]')))
