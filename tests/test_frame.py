"""One scene reader, one frame rule for one contact and for several.

Every position, pivot and point is given from the scene's origin O; a contact's point is
O unless it says otherwise; a shape that places itself is placed from the point of its
first contact. The checks: moving the whole scene (every point given) changes no result,
a one-contact scene and the same contact written as ``[[contacts]]`` agree, a particle
may take a position, and round bodies without positions are placed on their contacts'
normals in a several-contact scene exactly as the shipped cradle places them by hand."""

from __future__ import annotations

from pathlib import Path

import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.scenes.scene import load_scene, parse_scene
from rigidimpact.solve.collision import Collision, Simultaneous

ROOT = Path(__file__).resolve().parents[1]

ROD_STRUCK = """
[[bodies]]
name = "ball"
shape = "particle"
mass = "m"
velocity = ["v", "0"]
{ball_position}
[[bodies]]
name = "rod"
shape = "rod"
mass = "M"
length = "l"
angle = "theta"
struck_at = "l/4"
{pivot}
[contact]
bodies = ["ball", "rod"]
restitution = "e"
{point}
"""


def _results(text: str) -> dict:
    return parse_scene(text).derivation().results


def test_moving_the_origin_changes_no_result():
    # the same rod and ball seen from an origin 2 left of and 1 below the contact point
    here = _results(ROD_STRUCK.format(ball_position="", pivot="", point=""))
    there = _results(ROD_STRUCK.format(ball_position='position = ["2", "1"]', pivot="",
                                       point='point = ["2", "1"]'))
    assert here == there
    hinged = ROD_STRUCK.format(ball_position="{ball}", pivot='pivot = ["{x}", "{y}"]',
                               point="{point}")
    at_o = _results(hinged.format(ball="", x="-l/2*cos(theta)", y="-l/2*sin(theta)",
                                  point=""))
    moved = _results(hinged.format(ball='position = ["2", "1"]',
                                   x="2 - l/2*cos(theta)", y="1 - l/2*sin(theta)",
                                   point='point = ["2", "1"]'))
    assert at_o == moved and "rod.pivot_impulse_x" in at_o
    # by hand: the hinge is l/2 behind the struck point along the rod, 3l/4 from the
    # centre, so the rod's inertia about it is M (l^2/12 + 9 l^2/16) = 31 M l^2/48; the
    # normal (x) has the lever arm (l/2) sin(theta) about the hinge, so the rod's
    # effective mass at the struck point is 31 M / (12 sin^2(theta))
    m, M, v, e, theta = (sp.Symbol(n) for n in ("m", "M", "v", "e", "theta"))
    effective = 31 * M / (12 * sp.sin(theta) ** 2)
    expected = v * (m - e * effective) / (m + effective)
    got = at_o["ball.vx"].subs({s: sp.Symbol(s.name) for s in at_o["ball.vx"].free_symbols})
    assert sp.simplify(got - expected) == 0


def test_one_contact_reads_the_same_as_contact_or_contacts():
    text = ROD_STRUCK.format(ball_position="", pivot="", point="")
    listed = text.replace("[contact]", "[[contacts]]")
    assert _results(text) == _results(listed)


def test_round_bodies_take_their_place_from_their_first_contact():
    # the shipped cradle gives every ball's position; the same cradle with none given
    # places each ball on its first contact's normal, radius 1/2 from that point
    shipped = load_scene(ROOT / "derivations" / "newtons-cradle.toml")
    text = (ROOT / "derivations" / "newtons-cradle.toml").read_text()
    stripped = "\n".join(line for line in text.splitlines()
                         if not line.startswith("position"))
    placed = parse_scene(stripped)
    assert [b.position for b in placed.bodies] == [b.position for b in shipped.bodies]
    assert [tuple(b.position) for b in placed.bodies] == [
        (-sp.Rational(1, 2), 0), (sp.Rational(1, 2), 0), (sp.Rational(3, 2), 0)]
    assert placed.derivation().results == shipped.derivation().results


def test_a_particle_may_take_its_position_with_several_contacts():
    text = """
[[bodies]]
name = "ball"
shape = "particle"
mass = "1"
position = ["3", "0"]
velocity = ["0", "-1"]
[[bodies]]
name = "pad"
shape = "rigid"
mass = "1"
inertia = "1"
position = ["3", "-1"]
[[bodies]]
name = "floor"
shape = "fixed"
[[contacts]]
name = "top"
bodies = ["ball", "pad"]
point = ["3", "0"]
normal = ["0", "-1"]
restitution = "0"
[[contacts]]
name = "bottom"
bodies = ["pad", "floor"]
point = ["3", "-2"]
normal = ["0", "-1"]
restitution = "0"
"""
    results = parse_scene(text).derivation().results
    # a plastic stack on a floor: everything stops, the ball's momentum goes to the floor
    assert (results["ball.vy"], results["pad.vy"]) == (0, 0)
    assert results["bottom.normal_impulse"] == 1


def test_one_contact_of_a_larger_collision_moves_only_its_bodies():
    # a third body that no contact touches keeps its motion; the struck pair is the
    # two-body core's answer whatever the origin
    a = Body.rigid(1, 1, (5, 1), (2, 0), name="a")
    b = Body.rigid(3, 1, (7, 1), (0, 0), name="b")
    c = Body.rigid(1, 1, (0, 9), (0, 4), name="c")
    contact = Contact(restitution=sp.Rational(1, 2), bodies=("a", "b"), point=(6, 1))
    (solution,) = Collision((a, b, c), (contact,)).solve(Simultaneous())
    r = solution.results()
    # a head-on impact along x (centres on the line of impact), masses 1 and 3, e = 1/2:
    # momentum 2 = v_a + 3 v_b and restitution v_b - v_a = 1 give v_a = -1/4, v_b = 3/4
    assert (r["a.vx"], r["b.vx"]) == (-sp.Rational(1, 4), sp.Rational(3, 4))
    assert (r["c.vx"], r["c.vy"]) == (0, 4)
    assert [b.position for b in solution.after] == [a.position, b.position, c.position]
