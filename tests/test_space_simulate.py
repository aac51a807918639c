"""simulate of a 3-D scene: the rigid impact, and a spinning sphere's bounce on a flat
through a tangentially compliant contact, against the same contact integrated here in
vector form, against the planar scene, and under a turn about the normal."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from helpers import refused, scene_file
from rigidimpact.cli import main
from rigidimpact.laws.compliance import damping_ratio_for

SCENE = """
title = "a spinning sphere on a flat"
[values]
m = 2.618e-4
r = 0.0025
e = 0.9308
mu = 0.0977
[[bodies]]
name = "flat"
shape = "fixed"
[[bodies]]
name = "ball"
shape = "sphere"
mass = "m"
radius = "r"
position = ["0", "0", "r"]
velocity = [VELOCITY]
spin = [SPIN]
[contact]
bodies = ["flat", "ball"]
point = ["0", "0", "0"]
normal = ["0", "0", "1"]
restitution = "e"
tangential = "coulomb"
friction = "mu"
[simulate]
effects = ["tangential-compliance"]
stiffness_ratio = 0.791
"""
R, MU, E, RATIO = 0.0025, 0.0977, 0.9308, 0.791


def _scene(velocity, spin) -> str:
    return SCENE.replace("VELOCITY", ", ".join(f'"{x!r}"' for x in velocity)).replace(
        "SPIN", ", ".join(f'"{x!r}"' for x in spin))


def _simulate(tmp_path, capsys, velocity, spin, extra=()) -> dict:
    path = scene_file(tmp_path, _scene(velocity, spin))
    assert main(["simulate", path, "--json", *extra]) == 0
    return json.loads(capsys.readouterr().out)


def _vector_bounce(velocity, spin, steps=4000):
    """The lumped contact written out here in vector form, apart from the package: unit
    mass and normal stiffness, a normal spring-dashpot returning e, a tangential spring
    (a vector in the flat's plane) RATIO times as stiff and capped by mu times the push,
    the same semi-implicit steps per normal period as the package's planar model."""
    v, w = np.array(velocity, float), np.array(spin, float)
    speed = float(np.abs(np.concatenate([v, w * R])).max())
    vt, vn = v[:2] / speed, v[2] / speed
    rolled = R * np.cross(w, [0.0, 0.0, -1.0])[:2] / speed  # the spin's part of the slip
    damping = 2 * damping_ratio_for(E)
    depth, stretch, touched = 0.0, np.zeros(2), False
    dt = 2 * math.pi / steps
    inertia = 0.4
    for _ in range(3 * steps):
        push = 0.0 if touched and depth <= 0 else max(0.0, depth - damping * vn)
        stretch = stretch + (vt + rolled) * dt
        trial, cap = -RATIO * stretch, MU * push
        size = float(np.linalg.norm(trial))
        force = trial * cap / size if size > cap else trial
        if size > cap:
            stretch = -force / RATIO
        vt, rolled, vn = vt + force * dt, rolled + force / inertia * dt, vn + push * dt
        depth -= vn * dt
        touched |= depth > 0
        if touched and depth <= 0:
            break
    # back to speeds: the rolled part of the slip is R (w x (-z)) = R (-w_y, w_x)
    w_after = np.array([rolled[1], -rolled[0]]) * speed / R
    return np.array([*(vt * speed), vn * speed]), np.array([*w_after, w[2]])


@pytest.mark.parametrize("velocity,spin", [
    ((1.2, 0.5, -3.6), (100.0, -300.0, 50.0)),
    ((0.3, -1.1, -2.0), (-400.0, 20.0, -10.0)),
    ((1.0, 0.0, -1.0), (0.0, 0.0, 0.0)),
])
def test_the_compliant_bounce_is_the_vector_contact_integrated_apart(
        tmp_path, capsys, velocity, spin):
    got = _simulate(tmp_path, capsys, velocity, spin)["final"]
    v, w = _vector_bounce(velocity, spin)
    for k, x in zip(("vx", "vy", "vz", "omega_x", "omega_y", "omega_z"), (*v, *w),
                    strict=True):
        assert got[f"ball.{k}"] == pytest.approx(x, rel=1e-9, abs=1e-9 * 400), k


def test_a_bounce_in_a_vertical_plane_is_the_planar_scenes(tmp_path, capsys):
    # the slip along x, the spin about y: the 2-D scene's tangential compliance (its own
    # code path, in the plane) gives the same speeds; the planar spin omega is -omega_y
    got = _simulate(tmp_path, capsys, (1.3, 0.0, -3.66), (0.0, 200.0, 0.0))["final"]
    planar = SCENE.split("[[bodies]]")[0] + """
[[bodies]]
name = "flat"
shape = "fixed"
[[bodies]]
name = "ball"
shape = "sphere"
mass = "m"
radius = "r"
position = ["0", "r"]
velocity = ["1.3", "-3.66"]
spin = "-200"
[contact]
bodies = ["flat", "ball"]
normal = ["0", "1"]
restitution = "e"
tangential = "coulomb"
friction = "mu"
[simulate]
effects = ["tangential-compliance"]
stiffness_ratio = 0.791
"""
    path = scene_file(tmp_path, planar, "planar.toml")
    assert main(["simulate", path, "--json"]) == 0
    flat = json.loads(capsys.readouterr().out)["final"]
    assert got["ball.vx"] == pytest.approx(flat["ball.vx"], rel=1e-12)
    assert got["ball.vz"] == pytest.approx(flat["ball.vy"], rel=1e-12)
    assert got["ball.omega_y"] == pytest.approx(-flat["ball.omega"], rel=1e-12)
    assert got["ball.vy"] == 0 and got["ball.omega_x"] == 0


def test_a_turn_about_the_normal_turns_the_answer(tmp_path, capsys):
    v, w = (1.2, 0.5, -3.6), (100.0, -300.0, 50.0)
    a = _simulate(tmp_path, capsys, v, w)["final"]
    b = _simulate(tmp_path, capsys, (-v[1], v[0], v[2]), (-w[1], w[0], w[2]))["final"]
    assert b["ball.vx"] == pytest.approx(-a["ball.vy"], rel=1e-12)
    assert b["ball.vy"] == pytest.approx(a["ball.vx"], rel=1e-12)
    assert b["ball.omega_x"] == pytest.approx(-a["ball.omega_y"], rel=1e-12)
    assert b["ball.omega_z"] == pytest.approx(a["ball.omega_z"], rel=1e-12)


def test_without_effects_simulate_gives_the_rigid_impact(tmp_path, capsys):
    text = _scene((1.2, 0.5, -3.6), (100.0, -300.0, 50.0)).replace(
        'effects = ["tangential-compliance"]\nstiffness_ratio = 0.791', 'until = "separation"')
    path = scene_file(tmp_path, text)
    assert main(["simulate", path, "--json"]) == 0
    final = json.loads(capsys.readouterr().out)["final"]
    assert main(["evaluate", path, "--json"]) == 0
    rigid = json.loads(capsys.readouterr().out)
    for k in ("vx", "vy", "vz", "omega_x", "omega_y", "omega_z"):
        assert final[f"ball.{k}"] == pytest.approx(rigid[f"ball.{k}"], rel=1e-15)


def test_what_a_3d_simulate_does_not_do_is_refused_in_one_line(tmp_path, capsys):
    base = _scene((1.2, 0.5, -3.6), (100.0, -300.0, 50.0))
    path = scene_file(tmp_path, base.replace('"tangential-compliance"', '"gravity"'))
    refused(capsys, ["simulate", path], "flight after the impact is not built")
    path = scene_file(tmp_path, base, "plot.toml")
    refused(capsys, ["simulate", path, "--plot", str(tmp_path / "x.png")], "numbers only")
    path = scene_file(tmp_path, base.replace('tangential = "coulomb"', 'tangential = '
                                             '"smooth"').replace('friction = "mu"', "")
                      .replace("mu = 0.0977\n", ""),
                      "smooth.toml")
    refused(capsys, ["simulate", path], "Coulomb contact")
