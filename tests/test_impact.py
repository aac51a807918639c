"""Every solved impact obeys the laws it must: checked on random pairs of primitives."""

from __future__ import annotations

import random

import pytest
import sympy as sp

from conftest import SEED, random_body
from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.solve.impact import Impact

CASES = 40


def _approaching_pair(rng: random.Random):
    while True:
        first, second = random_body(rng, "one", -1), random_body(rng, "two", 1)
        closing = first.contact_velocity[0] - second.contact_velocity[0]
        if closing > 0:
            return first, second


def _is_zero(expr) -> bool:
    """Exact data: zero to 45 digits at 60-digit precision; symbolic: simplify to zero."""
    expr = sp.sympify(expr)
    if isinstance(expr, sp.MatrixBase):
        return all(_is_zero(x) for x in expr)
    if expr.free_symbols:
        return sp.simplify(expr) == 0
    return abs(sp.N(expr, 60)) < sp.Float("1e-40")


def _laws_hold(impact: Impact) -> None:
    sol = impact.solve()
    before = (impact.first, impact.second)
    after = (sol.first_after, sol.second_after)
    e = impact.contact.restitution
    # linear momentum of the pair, both components
    assert _is_zero(sum((b.momentum for b in before), sp.zeros(2, 1))
                    - sum((a.momentum for a in after), sp.zeros(2, 1)))
    # angular momentum of each body about O (the impulse acts at O)
    for b, a in zip(before, after, strict=True):
        assert _is_zero(b.angular_momentum - a.angular_momentum)
    # restitution along the normal
    n = impact.contact.frame.row(0).T
    rel_before = (before[1].contact_velocity - before[0].contact_velocity).dot(n)
    rel_after = (after[1].contact_velocity - after[0].contact_velocity).dot(n)
    assert _is_zero(rel_after + e * rel_before)
    # kinetic energy is not created
    assert sp.N(sol.kinetic_energy_before - sol.kinetic_energy_after, 30) >= -1e-25
    # the normal impulse pushes the bodies apart
    assert sp.N(sol.normal_impulse, 30) > 0
    if impact.contact.tangential == "smooth":
        assert _is_zero(sol.tangential_impulse)
        for b, a in zip(before, after, strict=True):  # eq. (13)
            assert _is_zero((b.momentum - a.momentum).dot(impact.contact.frame.row(1).T))
    else:
        t = impact.contact.frame.row(1).T
        slip = (after[1].contact_velocity - after[0].contact_velocity).dot(t)
        assert _is_zero(slip)


@pytest.mark.parametrize("case", range(CASES))
def test_random_primitive_pairs_obey_the_laws(case):
    rng = random.Random(SEED + case)
    first, second = _approaching_pair(rng)
    e = sp.Rational(rng.randint(0, 100), 100)
    tangential = rng.choice(["smooth", "stick"])
    _laws_hold(Impact(first, second, Contact(restitution=e, tangential=tangential)))


@pytest.mark.parametrize("case", range(10))
def test_tilted_normals_obey_the_laws(case):
    rng = random.Random(10 * SEED + case)
    angle = sp.Rational(rng.randint(-300, 300), 100)
    n = (sp.cos(angle), sp.sin(angle))
    # a disc on each side of the tilted normal, the first moving along it
    first = Body.disc(2, sp.Rational(1, 3), position=(-n[0] / 3, -n[1] / 3),
                      velocity=(2 * n[0] + sp.Rational(1, 2), 2 * n[1]), spin=1, name="one")
    second = Body.rod(3, 2, angle + sp.Rational(1, 2), sp.Rational(1, 3), name="two")
    _laws_hold(Impact(first, second, Contact(normal=n, restitution=sp.Rational(1, 2),
                                             tangential=rng.choice(["smooth", "stick"]))))


def test_elastic_smooth_impact_keeps_energy_exactly():
    rng = random.Random(SEED)
    first, second = _approaching_pair(rng)
    sol = Impact(first, second, Contact(restitution=1)).solve()
    assert _is_zero(sol.energy_loss_fraction)


def test_bodies_moving_apart_are_refused():
    a = Body.particle(1, (-1, 0), "a")
    b = Body.particle(1, (0, 0), "b")
    with pytest.raises(InputError, match="not approaching"):
        Impact(a, b, Contact())


def test_particle_spin_is_not_an_unknown():
    imp = Impact(Body.particle(1, (1, 0), "a"), Body.particle(1, name="b"), Contact())
    assert [str(u) for u in imp.unknowns] == ["V_1fx", "V_1fy", "V_2fx", "V_2fy"]
