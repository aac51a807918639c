"""One door: every answer, whatever its source (the planar shapes, a 3-D collision, a
sympy.physics.mechanics system) and however many contacts, goes through one method of
the rule, ``Rule.answer``; a single contact is the rules' one-contact step there
(``Rule.one_contact``), or a source's own closed form of it (the paper's two bodies with
its printed laws, a mechanics system's fraction-free solve), never a path beside it.

The expected values are by hand: a particle meeting a fixed floor with Newton's e
leaves at -e times its closing speed; a ball sliding onto a rough floor takes the
normal impulse (1 + e) m v and friction mu times it.
"""

from __future__ import annotations

from dataclasses import replace

import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.laws.contact import Contact
from rigidimpact.model.joints import Joint
from rigidimpact.model.space import Body3
from rigidimpact.solve.collision import chain
from rigidimpact.solve.rules.base import Rule

HALF = sp.Rational(1, 2)


@pytest.fixture
def doors(monkeypatch):
    """Each call of Rule.answer: the type of problem and how many contacts it had."""
    seen: list[tuple[str, int]] = []
    through = Rule.answer

    def answer(self, problem):
        seen.append((type(problem).__name__, len(problem.contacts)))
        return through(self, problem)

    monkeypatch.setattr(Rule, "answer", answer)
    return seen


class Marked(ri.Simultaneous):
    """The simultaneous rule whose one-contact step marks what it returns."""

    def one_contact(self, problem):
        return replace(super().one_contact(problem), notes=("marked",))


def _pendulum(law_at_wall: dict):
    """A particle on a light rod of length 1 hinged at O, striking a wall along -x."""
    q, u = me.dynamicsymbols("q u")
    N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
    A.orient_axis(N, N.z, q)
    A.set_ang_vel(N, u * N.z)
    origin = me.Point("O")
    origin.set_vel(N, 0)
    P = origin.locatenew("P", A.x)
    P.v2pt_theory(origin, N, A)
    kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
    kane.kanes_equations([me.Particle("bob", P, 1)], [])
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(P, -N.x, name="wall",
                                                          **law_at_wall)], frame=N)
    return hit.at({q: sp.pi / 2}).at({u: -1})


def _sphere_on_floor(**laws):
    ball = Body3.sphere(1, 1, (0, 0, 1), (1, 0, -2), name="ball")
    floor = Contact(normal=(0, 0, 1), bodies=("floor", "ball"), point=(0, 0, 0),
                    name="floor", **laws)
    return ri.SpaceCollision((Body3.fixed("floor"), ball), (floor,))


def test_every_source_answers_through_the_one_door(doors):
    ball = ri.Body.particle(1, (0, -2), "ball")
    plane = ri.Collision((ball, ri.Body.fixed("floor")), (Contact(
        (0, -1), HALF, bodies=("ball", "floor"), name="floor"),))
    (one,) = plane.solve(ri.Simultaneous())
    assert one.results()["ball.vy"] == 1  # -e times -2
    (three,) = chain(3).solve(ri.Simultaneous())
    assert [three.results()[f"ball{k}.vx"] for k in range(3)] == \
        [-sp.Rational(1, 3), sp.Rational(2, 3), sp.Rational(2, 3)]
    assert _sphere_on_floor(restitution=HALF).solve().results()["ball.vz"] == 1
    assert _pendulum({"restitution": HALF}).solve().speeds_after[0] == HALF
    assert doors == [("Collision", 1), ("Collision", 2), ("SpaceRows", 1),
                     ("SystemRows", 1)]


def test_one_contact_is_the_rules_one_step_in_space_and_in_a_system():
    # a solid ball sliding at 1 onto a rough floor (e = 1/2, mu = 1/20): normal impulse
    # (1 + e) 2 = 3; stopping the slip would take 1 / (1 + R^2 m / I) = 2/7, more than
    # mu 3 = 3/20, so it slides throughout and friction is 3/20
    rough = dict(restitution=HALF, tangential="coulomb", friction=sp.Rational(1, 20))
    space = replace(_sphere_on_floor(**rough), rule=Marked())
    (found,) = space.outcomes()
    assert found.notes == ("marked",)
    assert found.results()["floor.normal_impulse"] == 3
    assert found.results()["floor.tangential_impulse"] == sp.Rational(3, 20)
    # a mechanics system whose law picks its course (Coulomb): a particle moving at
    # (1, -2) onto a floor, e = 1/2, mu = 1/20: normal impulse 3, friction 3/20 against
    # the slip (stopping it would take 1), so it leaves at (1 - 3/20, 1)
    x, y, ux, uy = me.dynamicsymbols("x y u_x u_y")
    N = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(N, 0)
    P = origin.locatenew("P", x * N.x + y * N.y)
    P.set_vel(N, ux * N.x + uy * N.y)
    kane = me.KanesMethod(N, [x, y], [ux, uy], [x.diff() - ux, y.diff() - uy])
    kane.kanes_equations([me.Particle("bob", P, 1)], [])
    system = ri.mechanics.impact(kane, [ri.mechanics.contact(P, N.y, name="floor", **rough)],
                                 frame=N).at({x: 0, y: 0}).at({ux: 1, uy: -2})
    marked = system.solve(Marked())
    assert marked.notes == ("marked",)
    assert list(marked.speeds_after) == [sp.Rational(17, 20), 1]


def test_a_planar_contact_on_a_joint_takes_the_rules_one_step():
    # two rods pinned end to end, a particle striking the second's free end: one
    # contact, but the joint's rows make it the rules' one-contact step
    third = sp.Rational(1, 3)
    bodies = (ri.Body.rigid(1, third, (0, 0), name="a"),
              ri.Body.rigid(1, third, (2, 0), name="b"),
              ri.Body.particle(1, (0, 1), "p").shifted((3, 0)))
    hit = ri.Collision(bodies, (Contact((0, 1), 1, bodies=("p", "b"), name="hit",
                                        point=(3, 0)),), joints=(Joint("pin", ("a", "b"),
                                                                          (1, 0)),))
    (out,) = hit.solve(Marked())
    assert out.notes == ("marked",)
    # momentum along y: the particle's 1 shared; e = 1 at one contact keeps the energy
    r = out.results()
    assert r["p.vy"] + r["a.vy"] + r["b.vy"] == 1
    assert out.energy_lost == 0
