"""A new law, and a new rule, is one class and one registry line: written here, each
works from a planar scene file, a 3-D scene file and a sympy.physics.mechanics system,
by every path those take (one contact's own answer, the rules, the impact map's kernel).

The law: Newton's kinematic law with its coefficient read as the square root of
Newton's, v+ = -e^2 v-. Whatever it is solved with, it must give Newton's answer at
e^2: that is the expected value, from another law, not from the code under test.
"""

from __future__ import annotations

import math

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.laws import law as laws
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.scenes.space import parse_space_scene
from rigidimpact.solve import rules


class SquaredNewton(laws.NewtonRestitution):
    """Newton's law with e read as the square root of Newton's coefficient."""

    name = "squared"

    def leaving(self, closing: sp.Expr) -> sp.Expr:
        return -self.e ** 2 * closing


@pytest.fixture
def registered(monkeypatch):
    """The one registry line."""
    monkeypatch.setitem(laws.RESTITUTION_LAWS, "squared", SquaredNewton)


PLANE = """
[[bodies]]
name = "rod"
shape = "rigid"
mass = "1"
inertia = "1/3"
position = ["0", "0"]
velocity = ["0", "-1"]
spin = "1"
[[bodies]]
name = "floor"
shape = "fixed"
[[contacts]]
name = "left"
bodies = ["rod", "floor"]
point = ["-1", "0"]
normal = ["0", "-1"]
restitution = "{e}"
law = "{law}"
[[contacts]]
name = "right"
bodies = ["rod", "floor"]
point = ["1", "0"]
normal = ["0", "-1"]
restitution = "{e}"
law = "{law}"
[impact]
rule = "{rule}"
"""

ONE = """
[[bodies]]
name = "ball"
shape = "particle"
mass = "m"
velocity = ["v", "0"]
[[bodies]]
name = "wall"
shape = "fixed"
[contact]
bodies = ["ball", "wall"]
restitution = "{e}"
law = "{law}"
"""

SPACE = """
[[bodies]]
name = "floor"
shape = "fixed"
[[bodies]]
name = "ball"
shape = "sphere"
mass = "1"
radius = "1"
position = ["0", "0", "1"]
velocity = ["1", "1/2", "-2"]
spin = ["3", "-1", "2"]
[contact]
bodies = ["floor", "ball"]
point = ["0", "0", "0"]
normal = ["0", "0", "1"]
restitution = "{e}"
law = "{law}"
"""


def test_one_contact_in_the_plane_takes_the_new_law(registered):
    e = sp.Symbol("e", nonnegative=True)
    new = parse_scene(ONE.format(e="e", law="squared")).derivation().results
    old = parse_scene(ONE.format(e="e", law="newton")).derivation().results
    assert sp.simplify(new["ball.vx"] - old["ball.vx"].subs(e, e ** 2)) == 0


@pytest.mark.parametrize("rule", ["simultaneous", "sequential", "driven"])
def test_several_contacts_in_the_plane_and_in_space_take_the_new_law(registered, rule):
    new = parse_scene(PLANE.format(e="1/2", law="squared", rule=rule)).outcomes()
    old = parse_scene(PLANE.format(e="1/4", law="newton", rule=rule)).outcomes()
    assert [o.results() for o in new] == pytest.approx([o.results() for o in old])
    flat = PLANE.replace('["0", "0"]', '["0", "0", "0"]').replace(
        '["0", "-1"]', '["0", "-1", "0"]').replace('"1/3"', '["1/3", "1/3", "1/3"]').replace(
        'spin = "1"', 'spin = ["0", "0", "1"]').replace('["-1", "0"]', '["-1", "0", "0"]') \
        .replace('["1", "0"]', '["1", "0", "0"]')
    spatial = parse_space_scene(flat.format(e="1/2", law="squared", rule=rule))
    for ours, theirs in zip(spatial.collision().outcomes(), old, strict=True):
        r = ours.results()
        for key, value in theirs.results().items():
            other = r[key + "_z" if key.endswith(".omega") else key]
            assert float(other) == pytest.approx(float(value), rel=1e-9, abs=1e-12), key


def test_a_model_built_on_newtons_e_does_not_take_the_new_law_for_it():
    # the simulators' compliant bounce and the sticking contact's checks ask for
    # Newton's e: a law with another target must not pass for it
    assert SquaredNewton(sp.Rational(1, 2)).newtons_e() is None
    assert laws.NewtonRestitution(sp.Rational(1, 2)).newtons_e() == sp.Rational(1, 2)


def test_one_contact_in_space_takes_the_new_law(registered):
    new = parse_space_scene(SPACE.format(e="1/2", law="squared")).derivation().results
    old = parse_space_scene(SPACE.format(e="1/4", law="newton")).derivation().results
    assert new == old


def test_a_mechanics_system_takes_the_new_law(registered):
    # a particle on a light rod hinged at O strikes a wall at x = 1
    q, u = me.dynamicsymbols("q u")
    N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
    A.orient_axis(N, N.z, q)
    A.set_ang_vel(N, u * N.z)
    origin = me.Point("O")
    origin.set_vel(N, 0)
    P = origin.locatenew("P", A.x)
    P.v2pt_theory(origin, N, A)
    bob = me.Particle("bob", P, 1)
    kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
    kane.kanes_equations([bob], [])

    def system(law, e):
        return ri.mechanics.impact(kane, [ri.mechanics.contact(
            P, -N.x, restitution=e, law=law, name="wall")], frame=N)

    new, old = system("squared", sp.Rational(1, 2)), system("newton", sp.Rational(1, 4))
    assert new.at({q: sp.pi / 2}).at({u: -1}).solve().speeds_after == \
        old.at({q: sp.pi / 2}).at({u: -1}).solve().speeds_after
    # and the impact map's kernel, which asks the law for its target (no (1 + e) of its
    # own): Newton's at 1/4 leaves at a quarter of the speed, state by state
    states = [[math.pi / 2], [1.2], [2.0]]
    rates = [[-1.0], [-2.0], [-0.5]]
    ours = new.kernel()(states, rates).speeds_after
    theirs = old.kernel()(states, rates).speeds_after
    assert ours == pytest.approx(theirs, rel=1e-12)
    assert ours[:, 0] == pytest.approx([0.25, 0.5, 0.125], rel=1e-12)


class InFileOrder(ri.Rule):
    """One contact at a time in the order the scene gives them."""

    name = "in-file-order"

    def outcomes(self, problem):
        return ri.Sequential(tuple(c.name for c in problem.contacts)).outcomes(problem)


def test_a_new_rule_is_one_class_and_one_registry_line(monkeypatch):
    monkeypatch.setitem(rules.RULE_CLASSES, "in-file-order", InFileOrder)
    # the plane: the scene names it, and it gives the sequential rule in that order
    new = parse_scene(PLANE.format(e="1/2", law="newton", rule="in-file-order")).outcomes()
    old = parse_scene(PLANE.format(e="1/2", law="newton", rule="sequential").replace(
        'rule = "sequential"', 'rule = "sequential"\norder = ["left", "right"]')).outcomes()
    assert [o.results() for o in new] == [o.results() for o in old]
    # space: the same file in three dimensions
    flat = PLANE.replace('["0", "0"]', '["0", "0", "0"]').replace(
        '["0", "-1"]', '["0", "-1", "0"]').replace('"1/3"', '["1/3", "1/3", "1/3"]').replace(
        'spin = "1"', 'spin = ["0", "0", "1"]').replace('["-1", "0"]', '["-1", "0", "0"]') \
        .replace('["1", "0"]', '["1", "0", "0"]')
    (ours,) = parse_space_scene(flat.format(e="1/2", law="newton",
                                            rule="in-file-order")).collision().outcomes()
    for key, value in old[0].results().items():
        other = ours.results()[key + "_z" if key.endswith(".omega") else key]
        assert float(other) == pytest.approx(float(value), rel=1e-9, abs=1e-12), key
    # a mechanics system: the rod on the floor as a KanesMethod, the same rule object
    x, y, th = me.dynamicsymbols("x y theta")
    ux, uy, w = me.dynamicsymbols("u_x u_y w")
    N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
    A.orient_axis(N, N.z, th)
    A.set_ang_vel(N, w * N.z)
    origin = me.Point("O")
    origin.set_vel(N, 0)
    C = origin.locatenew("C", x * N.x + y * N.y)
    C.set_vel(N, ux * N.x + uy * N.y)
    ends = [C.locatenew(name, sign * A.x) for name, sign in (("L", -1), ("R", 1))]
    for end in ends:
        end.v2pt_theory(C, N, A)
    rod = me.RigidBody("rod", C, A, 1, (me.inertia(A, 0, 0, sp.Rational(1, 3)), C))
    kane = me.KanesMethod(N, [x, y, th], [ux, uy, w],
                          [x.diff() - ux, y.diff() - uy, th.diff() - w])
    kane.kanes_equations([rod], [])
    half = sp.Rational(1, 2)
    hit = ri.mechanics.impact(kane, [
        ri.mechanics.contact(ends[0], N.y, name="left", restitution=half),
        ri.mechanics.contact(ends[1], N.y, name="right", restitution=half)], frame=N)
    strike = hit.at({x: 0, y: 0, th: 0}).at({ux: 0, uy: -1, w: 1})
    mine = strike.solve(rules.rule_named("in-file-order"))
    r = old[0].results()
    assert list(mine.speeds_after) == [r["rod.vx"], r["rod.vy"], r["rod.omega"]]
