"""Joints in space: ball joints and hinges, eliminated by the projected inverse mass as in
the plane. Checked against hand derivations (a rod hanging from a ball joint struck at
its tip; the same rod on a hinge, free to swing or held) and against the planar double
pendulum of derivations/double-pendulum-wall.toml written again in space."""

from __future__ import annotations

import pytest
import sympy as sp

from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.model.joints import Joint
from rigidimpact.model.space import Body3
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.scenes.space import parse_space_scene
from rigidimpact.solve.problem import ImpactProblem
from rigidimpact.solve.rules import Simultaneous
from rigidimpact.solve.space import SpaceCollision
from test_joints import PENDULUM

R = sp.Rational
HALF = R(1, 2)


def _hanging_rod(joint: Joint) -> SpaceCollision:
    """A rod (mass 1, length 2, its central moments 1/3 across and 1/100 along) hanging
    from O, struck at its tip (0, 0, -2) along x by a ball of mass 1 at speed 1, smooth,
    e = 1/2."""
    rod = Body3.rigid(1, (R(1, 3), R(1, 3), R(1, 100)), (0, 0, -1), name="rod")
    ball = Body3.sphere(1, HALF, (-HALF, 0, -2), (1, 0, 0), name="ball")
    hit = Contact(normal=(1, 0, 0), restitution=HALF, bodies=("ball", "rod"),
                  point=(0, 0, -2))
    return SpaceCollision((Body3.fixed("ground"), rod, ball), (hit,), joints=(joint,))


@pytest.mark.parametrize("axis", [None, (0, 1, 0), (0, 3, 0)])
def test_a_rod_on_a_ball_joint_or_a_hinge_swings_as_by_hand(axis):
    # by hand: about O the rod's moment is 1/3 + 1 = 4/3, so its tip along x weighs
    # 4/3 / 2^2 = 1/3 and W = 1 + 3 = 4; P = (1 + e) 1 / 4 = 3/8; the ball leaves at
    # 5/8, the rod turns at -(2 P)/(4/3) = -9/16 about y, its centre moving at 9/16,
    # and O gives it 9/16 - 3/8 = 3/16 along x. A hinge about y lets it swing the same.
    solution = _hanging_rod(Joint("top", ("ground", "rod"), (0, 0, 0), axis)).solve()
    r = solution.results()
    assert (r["ball.vx"], r["rod.omega_y"], r["rod.vx"]) == (R(5, 8), -R(9, 16), R(9, 16))
    assert (r["contact.normal_impulse"], r["top.impulse_x"]) == (R(3, 8), R(3, 16))
    assert r["top.impulse_y"] == r["top.impulse_z"] == 0
    assert max(solution.checks.values()) == 0 and solution.checks["top.holds"] == 0


def test_a_hinge_across_the_swing_holds_the_rod():
    # a hinge about x: the tip cannot move along x, so the ball meets a fixed rod:
    # P = (1 + e) 1 = 3/2 and the ball leaves at -1/2; O gives -3/2 along x and the
    # moment that balances the two impulses' moments about the centre, 2 x 3/2 = 3 about y
    solution = _hanging_rod(Joint("top", ("ground", "rod"), (0, 0, 0), (1, 0, 0))).solve()
    r = solution.results()
    assert (r["ball.vx"], r["rod.vx"], r["rod.omega_y"]) == (-HALF, 0, 0)
    assert (r["top.impulse_x"], r["top.moment_1"], r["top.moment_2"]) == (-R(3, 2), 3, 0)
    assert max(solution.checks.values()) == 0


def _pendulum_in_space(axis):
    """derivations/double-pendulum-wall.toml at m = l = 1, sin(theta_1) = 3/5,
    sin(theta_2) = 4/5, omega = (1, 2), e = 1/2, with the rods as rigid bodies in space
    (moments 1/12 across, 1/1000 along) joined by ball joints or hinges about z."""
    def rod(name, direction, centre, velocity, spin):
        a, b = direction
        turn = sp.Matrix([[a, -b, 0], [b, a, 0], [0, 0, 1]])  # body x along the rod
        return Body3.rigid(1, (R(1, 1000), R(1, 12), R(1, 12)), centre, velocity,
                           (0, 0, spin), orientation=turn, name=name)
    upper = rod("upper", (R(3, 5), -R(4, 5)), (R(3, 10), -R(2, 5), 0), (R(2, 5), R(3, 10), 0), 1)
    lower = rod("lower", (R(4, 5), -R(3, 5)), (1, -R(11, 10), 0), (R(7, 5), R(7, 5), 0), 2)
    joints = (Joint("top", ("ground", "upper"), (0, 0, 0), axis),
              Joint("knee", ("upper", "lower"), (R(3, 5), -R(4, 5), 0), axis))
    tip = Contact(normal=(1, 0, 0), restitution=HALF, bodies=("lower", "wall"),
                  point=(R(7, 5), -R(7, 5), 0), name="tip")
    return SpaceCollision((Body3.fixed("ground"), Body3.fixed("wall"), upper, lower),
                          (tip,), joints=joints)


@pytest.mark.parametrize("axis", [None, (0, 0, 1)])
def test_the_double_pendulum_in_space_is_the_planar_one(axis):
    planar = parse_scene(PENDULUM, "pendulum")
    theta_1, theta_2 = (planar.symbols[n] for n in ("theta_1", "theta_2"))
    values = {**planar.values, theta_1: sp.atan(R(3, 4)), theta_2: sp.atan(R(4, 3)),
              planar.symbols["e"]: HALF}
    (solved,) = planar.collision(values).solve(Simultaneous())
    flat = solved.results()
    space = _pendulum_in_space(axis).solve()
    r = space.results()
    assert max(space.checks.values()) == 0
    assert r["upper.omega_z"] == sp.nsimplify(flat["upper.omega"])
    assert r["lower.omega_z"] == sp.nsimplify(flat["lower.omega"])
    assert (r["lower.vx"], r["lower.vy"]) == (flat["lower.vx"], flat["lower.vy"])
    assert r["tip.normal_impulse"] == flat["tip.normal_impulse"]
    assert (r["knee.impulse_x"], r["knee.impulse_y"]) == (flat["knee.impulse_x"],
                                                          flat["knee.impulse_y"])
    assert r["knee.impulse_z"] == 0 and r["upper.omega_x"] == r["upper.omega_y"] == 0


SCENE = """
title = "A door on a hinge, struck by a ball"
[[bodies]]
name = "frame"
shape = "fixed"
[[bodies]]
name = "door"
shape = "rigid"
mass = 1
inertia = ["1/3", "1/3", "1/100"]
position = [0, 0, -1]
[[bodies]]
name = "ball"
shape = "sphere"
mass = 1
radius = "1/2"
position = ["-1/2", 0, -2]
velocity = [1, 0, 0]
[[joints]]
name = "hinge"
bodies = ["frame", "door"]
point = [0, 0, 0]
axis = [0, 1, 0]
[contact]
bodies = ["ball", "door"]
point = [0, 0, -2]
normal = [1, 0, 0]
restitution = "1/2"
"""


def test_a_scene_file_takes_joints(tmp_path, capsys):
    scene = parse_space_scene(SCENE)
    r = scene.derivation().solution.results()
    assert (r["ball.vx"], r["hinge.impulse_x"]) == (R(5, 8), R(3, 16))
    printed = {eq.label for eq in scene.derivation().equations}
    assert any("hinge holds" in label for label in printed)
    path = tmp_path / "door.toml"
    path.write_text(SCENE)
    assert main(["evaluate", str(path)]) == 0
    assert "hinge.moment_1" in capsys.readouterr().out


@pytest.mark.parametrize("change, message", [
    (("velocity = [1, 0, 0]", "velocity = [1, 0, 0]"), None),
    (('axis = [0, 1, 0]', 'axis = [0, 0, 0]'), "axis: must not be the zero vector"),
    (('axis = [0, 1, 0]', 'axle = [0, 1, 0]'), "axle: not a field of a joint"),
    (('point = [0, 0, 0]', 'point = [0, 0]'), "point: expected a list of three"),
    (('bodies = ["frame", "door"]', 'bodies = ["frame", "dor"]'), "no body named 'dor'"),
    (("position = [0, 0, -1]", "position = [0, 0, -1]\nvelocity = [1, 0, 0]"),
     "do not move together"),
])
def test_a_bad_joint_is_refused_in_one_line(change, message):
    text = SCENE.replace(*change)
    if message is None:
        parse_space_scene(text)
        return
    with pytest.raises(InputError, match=message):
        parse_space_scene(text).derivation()


def test_a_planar_scene_refuses_a_joint_in_space():
    text = PENDULUM.replace('point = ["l_1*sin(theta_1)", "-l_1*cos(theta_1)"]',
                            'point = ["l_1*sin(theta_1)", "-l_1*cos(theta_1)", "0"]')
    with pytest.raises(InputError, match="point: expected a list of two components"):
        parse_scene(text)
    ball = Body.particle(1, (0, 0), "a")
    with pytest.raises(InputError, match="a joint in the plane has a point"):
        ImpactProblem((ball, Body.particle(1, (1, 0), "b")), (), (Joint(
            "pin", ("a", "b"), (0, 0, 0)),))
