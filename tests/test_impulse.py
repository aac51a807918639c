"""The generalized-impulse core: W = J M^-1 J^T, laws as printed and as solved."""

from __future__ import annotations

import random

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import NewtonRestitution, Stick
from rigidimpact.model.bodies import Body
from rigidimpact.model.impulse import TouchingPair
from rigidimpact.solve.impact import Impact
from rigidimpact.symbolic.notation import symbol

SEED = 20261122


def random_pair(generator: random.Random) -> tuple[Body, Body]:
    """Two bodies at O in random supports: free, pivoted or fixed (not both fixed)."""
    def rational(lo, hi):
        return sp.Rational(generator.randint(lo * 100, hi * 100), 100)

    def body(name, side, support):
        if support == "fixed":
            return Body.fixed(name)
        centre = (side * rational(0, 2), rational(-2, 2))
        spin = rational(-2, 2)
        if support == "pivot":
            pivot = (rational(-3, 3), rational(-3, 3))
            while pivot == centre:
                pivot = (rational(-3, 3), rational(-3, 3))
            turn = (-spin * (centre[1] - pivot[1]), spin * (centre[0] - pivot[0]))
            return Body.rigid(rational(1, 5), rational(1, 3), centre, turn, spin, name,
                              pivot=pivot)
        return Body.rigid(rational(1, 5), rational(1, 3), centre,
                          (rational(-3, 3), rational(-3, 3)), spin, name)

    supports = generator.choice([("free", "free"), ("free", "pivot"), ("pivot", "fixed"),
                                 ("pivot", "pivot"), ("free", "fixed")])
    return body("a", -1, supports[0]), body("b", 1, supports[1])


@pytest.mark.parametrize("case", range(25))
def test_W_is_symmetric_positive_and_predicts_the_velocity_change(case):
    generator = random.Random(SEED + case)
    first, second = random_pair(generator)
    core = TouchingPair((first, second))
    W = core.W
    assert W == W.T
    assert all(value >= 0 for value in W.eigenvals())  # a kinetic-energy form
    impulse = sp.Matrix([sp.Rational(generator.randint(-9, 9), 4) for _ in range(2)])
    after = core.bodies_after(impulse)
    # the touching points' velocities, from the bodies themselves, against v- + W P
    relative = after[1].contact_velocity - after[0].contact_velocity
    if first.support == "fixed":
        relative = after[1].contact_velocity
    elif second.support == "fixed":
        relative = -after[0].contact_velocity
    assert relative == core.velocity_after(impulse)
    # the work of the impulse is the change of kinetic energy
    energy = sum(b.kinetic_energy for b in after) - sum(b.kinetic_energy for b in (first, second))
    assert sp.nsimplify(energy - core.work(impulse, core.velocity_before,
                                           core.velocity_after(impulse))) == 0


def test_the_barbell_W_is_the_papers_denominator():
    # Mungan eq. (5): the impulse is (1 + e) m v 2M / (2M + m(1 + sin^2 theta)), i.e.
    # (1 + e) v / W_nn with W_nn = 1/m + 1/(2M) + sin^2(theta)/(2M)
    m, M, L, theta = (symbol(n) for n in ("m", "M", "L", "theta"))
    core = TouchingPair((Body.particle(m, (1, 0)), Body.barbell(M, L, theta)))
    expected = 1 / m + 1 / (2 * M) + sp.sin(theta) ** 2 / (2 * M)
    assert sp.simplify(core.W[0, 0] - expected) == 0


@pytest.mark.parametrize("case", range(10))
def test_laws_impose_what_they_print(case):
    # the printed laws at the kicked bodies are the contact-space conditions every path
    # solves with (each law's one face, linear_conditions), written with W:
    # v+_n = -e v-_n and v+_t = 0
    generator = random.Random(SEED - case)
    first, second = random_pair(generator)
    core = TouchingPair((first, second))
    impulse = sp.Matrix(sp.symbols("P_n P_t", real=True))
    kicked = core.bodies_after(impulse)
    e = sp.Rational(generator.randint(0, 10), 10)
    v_before, v_after = core.velocity_before, core.velocity_after(impulse)
    law = NewtonRestitution(e)
    (newton,) = law.equations((first, second), kicked)
    assert sp.expand(newton.residual - (v_after[0] + e * v_before[0])) == 0
    (stick,) = Stick().equations((first, second), kicked)
    faced = Stick().linear_conditions(v_before, v_after, impulse, law.leaving(v_before[0]))
    assert sp.expand(stick.residual - v_after[1]) == 0
    assert [sp.expand(x) for x in faced] == [sp.expand(newton.residual),
                                             sp.expand(stick.residual)]


@pytest.mark.parametrize("case", range(12))
def test_printed_equations_hold_at_the_solution(case):
    generator = random.Random(SEED + 100 + case)
    first, second = random_pair(generator)
    contact = Contact(restitution=sp.Rational(generator.randint(0, 10), 10),
                      tangential=generator.choice(["smooth", "stick"]))
    if (first.contact_velocity - second.contact_velocity)[0] < 0:  # run the draw backward
        first, second = (b if b.support == "fixed" else b.with_motion(-b.velocity, -b.spin)
                         for b in (first, second))
    impact = Impact(first, second, contact)
    try:
        solution = impact.solve()
    except InputError as exc:  # sticking with one degree of freedom is indeterminate
        assert "one degree of freedom" in str(exc)
        assert sum(b.support == "free" for b in (first, second)) == 0
        return
    for eq in impact.equations():
        assert sp.simplify(eq.residual.subs(solution.values)) == 0, eq.label
    assert len(impact.equations()) == len(impact.unknowns)
