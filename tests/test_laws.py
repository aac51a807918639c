"""Laws as objects: printed and imposed alike; a new law is one class."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from rigidimpact import laws
from rigidimpact.bodies import Body
from rigidimpact.contact import Contact
from rigidimpact.impact import Impact


def test_contact_names_its_law_objects():
    restitution, tangential = Contact(restitution=sp.Rational(1, 2), tangential="stick").laws
    assert isinstance(restitution, laws.NewtonRestitution)
    assert restitution.e == sp.Rational(1, 2)
    assert isinstance(tangential, laws.Stick)


@dataclass(frozen=True, repr=False)
class TangentialRestitution(laws.ContactLaw):
    """The tangential velocity of the touching points reverses, scaled by beta."""

    beta: sp.Expr = sp.Integer(1)
    name = "reverse"

    def equations(self, before, after):
        v_before = before[1].contact_velocity[1] - before[0].contact_velocity[1]
        v_after = after[1].contact_velocity[1] - after[0].contact_velocity[1]
        return (laws.Equation("tangential restitution", "-", v_after, -self.beta * v_before),)


def test_a_new_law_is_one_class(monkeypatch):
    monkeypatch.setitem(laws.TANGENTIAL_LAWS, "reverse", TangentialRestitution)
    ball = Body.sphere(1, 1, side=-1, velocity=(1, 1), name="ball")
    solution = Impact(ball, Body.fixed("floor"),
                      Contact(restitution=1, tangential="reverse")).solve()
    after = solution.first_after
    # Garwin's superball (beta = 1, no spin before): W_tt = 1/m + r^2/I = 7/(2m), so the
    # centre keeps 1 - 2 (1 + beta)/7 = 3/7 of its tangential velocity and the contact
    # point's tangential velocity reverses
    assert after.velocity[1] == sp.Rational(3, 7)
    assert after.contact_velocity[1] == -ball.contact_velocity[1]
    assert after.velocity[0] == -1
