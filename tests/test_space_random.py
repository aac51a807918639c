"""[random] in 3-D scenes: the exact distribution where an output is monotone in one
random input, the Monte Carlo otherwise, checked against hand derivations."""

from __future__ import annotations

import pytest
import sympy as sp

from rigidimpact.analyses.distributions import scene_distributions
from rigidimpact.errors import InputError
from rigidimpact.scenes.space import parse_space_scene

BALL = """
title = "A ball lands on a rough floor"
[symbols]
{declare}
[values]
{value}
[[bodies]]
name = "floor"
shape = "fixed"
[[bodies]]
name = "ball"
shape = "sphere"
mass = 1
radius = 1
position = [0, 0, 1]
velocity = {velocity}
spin = {spin}
[contact]
bodies = ["floor", "ball"]
point = [0, 0, 0]
normal = [0, 0, 1]
restitution = "1/2"
tangential = "coulomb"
friction = "1/5"
[random]
{random}
outputs = {outputs}
samples = 4000
"""


def _distributions(scene):
    return scene_distributions(scene, dict(scene.derivation().results))


def test_a_random_drop_speed_has_its_exact_density():
    # v_z+ = e s = s/2 for s uniform on [1, 3]: density 1 on (1/2, 3/2), mean 1
    scene = parse_space_scene(BALL.format(
        declare="s = { positive = true }", value="s = 2", velocity='[1, 0, "-s"]',
        spin="[0, 0, 0]", random="s = { uniform = [1, 3] }", outputs='["ball.vz"]'))
    found = _distributions(scene)["ball.vz"]
    assert found["density"] == 1 and found["support"] == (sp.Rational(1, 2), sp.Rational(3, 2))
    assert found["mean"] == 1
    carlo = found["monte_carlo"]
    assert abs(carlo["mean"] - 1) < 4 * carlo["standard_error"]


def test_derive_prints_a_3d_scenes_distributions(tmp_path, capsys):
    from rigidimpact.cli import main

    path = tmp_path / "spin.toml"
    path.write_text(BALL.format(
        declare="w = { real = true }", value="w = 0", velocity="[1, 0, -2]",
        spin='[0, "w", 0]', random="w = { uniform = [-3, 3] }", outputs='["ball.vx"]'))
    assert main(["derive", str(path)]) == 0
    out = capsys.readouterr().out
    assert "Distributions (random: w uniform on [-3, 3]" in out and "Monte Carlo" in out


def test_a_random_spin_averages_as_by_hand():
    # spin w about y, uniform on [-3, 3]: the contact slips at 1 - w; P_n = 3, and the
    # ball (W_tt = 7/2, mu = 1/5) rolls off at 5/7 + 2w/7 where |1 - w| <= 21/10 and
    # slides to 2/5 where w < -11/10, so E[v_x] = (0.76 + (5/7) 4.1 + (9 - 1.21)/7)/6
    scene = parse_space_scene(BALL.format(
        declare="w = { real = true }", value="w = 0", velocity="[1, 0, -2]",
        spin='[0, "w", 0]', random="w = { uniform = [-3, 3] }", outputs='["ball.vx"]'))
    carlo = _distributions(scene)["ball.vx"]["monte_carlo"]
    expected = (0.76 + 5 / 7 * 4.1 + (9 - 1.21) / 7) / 6
    assert abs(carlo["mean"] - expected) < 4 * carlo["standard_error"]


def test_a_support_that_reaches_no_impact_is_refused():
    text = BALL.format(
        declare="s = { real = true }", value="s = 2", velocity='[1, 0, "-s"]',
        spin="[0, 0, 0]", random="s = { uniform = [-1, 3] }", outputs='["ball.vz"]')
    with pytest.raises(InputError, match="random.s: at the end -1 of its support.*not "
                                         "approaching"):
        parse_space_scene(text)
    with pytest.raises(InputError, match="random.q: not a symbol"):
        parse_space_scene(text.replace("s = { uniform = [-1, 3] }", "q = { uniform = [1, 3] }"))
