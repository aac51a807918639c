"""The same 3-D physics turned in space gives the turned answer: a seeded random family
of 3-D collisions (a box of three moments, turned; one to three contacts on a floor and
a wall; Newton's law with smooth, Coulomb and sticking contacts; the default rule and
the driven and sequential rules) is turned by a rational rotation about an axis out of
every coordinate plane and moved. Each body's velocity and spin after must be the
turned ones, each contact's normal impulse and the size of its tangential impulse the
same, and the energy lost the same: exactly where the answer is exact, to the
integration's tolerance where it is followed numerically. A collision refused one way
is refused the other way too.
"""

from __future__ import annotations

import functools
import random

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.space import Body3
from rigidimpact.solve.rules import rule_named
from rigidimpact.solve.space import SpaceCollision

R = sp.Rational
SEED = 68
COUNT = 16


def _rotation(a: int, b: int, c: int, d: int) -> sp.Matrix:
    """The rotation of the quaternion (a, b, c, d): rational for whole numbers."""
    n = a * a + b * b + c * c + d * d
    return sp.Matrix([
        [a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
        [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
        [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d]]) / n


TURN = _rotation(1, 2, 2, 4)  # about an axis out of every coordinate plane
SHIFT = sp.Matrix([R(7, 2), R(-5, 3), R(2, 7)])


def _case(rng: random.Random) -> dict:
    """A box above a floor (z = 0) and beside a wall (x = 1), touching one, two or three
    times: a corner on the floor, another on the floor, a third on the wall."""
    def small(lo=-3, hi=3):
        return R(rng.randint(lo, hi), rng.randint(1, 4))

    mass = R(rng.randint(1, 4), 2)
    a, b, c = (R(rng.randint(1, 4), 2) for _ in range(3))  # a box's sides
    moments = tuple(mass * (x * x + y * y) / 12 for x, y in ((b, c), (a, c), (a, b)))
    own = _rotation(*[rng.randint(0, 3) for _ in range(3)], 1)
    centre = sp.Matrix([R(1, 2), 0, R(1, 2)])
    velocity = sp.Matrix([small(0, 3), small(), small(-4, -1)])
    spin = sp.Matrix([small(), small(), small()])
    places = [(sp.Matrix([R(1, 3), R(1, 4), 0]), sp.Matrix([0, 0, 1]), "floor"),
              (sp.Matrix([R(1, 2), R(-1, 3), 0]), sp.Matrix([0, 0, 1]), "floor"),
              (sp.Matrix([1, R(1, 5), R(1, 3)]), sp.Matrix([-1, 0, 0]), "wall")]
    chosen = rng.sample(places, rng.randint(1, 3))
    contacts = []
    for k, (point, normal, fixed) in enumerate(chosen):
        tangential = rng.choice(["smooth", "coulomb", "stick"])
        laws = dict(restitution=R(rng.randint(0, 4), 4), tangential=tangential)
        if tangential == "coulomb":
            laws["friction"] = R(rng.randint(1, 6), 10)
        contacts.append((f"c{k}", fixed, point, normal, laws))
    return dict(mass=mass, moments=moments, own=own, centre=centre,
                velocity=velocity, spin=spin, contacts=contacts,
                rule=rng.choice([None, "driven", "sequential"]))


def _collision(case: dict, turn: sp.Matrix, shift: sp.Matrix) -> SpaceCollision:
    box = Body3.rigid(case["mass"], case["moments"], turn * case["centre"] + shift,
                      turn * case["velocity"], turn * case["spin"], turn * case["own"],
                      name="box")
    fixed = sorted({c[1] for c in case["contacts"]})
    contacts = tuple(Contact(normal=tuple(turn * normal), bodies=(wall, "box"),
                             point=tuple(turn * point + shift), name=name, **laws)
                     for name, wall, point, normal, laws in case["contacts"])
    rule = case["rule"]
    if rule == "sequential":
        rule = rule_named("sequential")
        rule = type(rule)(tuple(c.name for c in contacts))
    return SpaceCollision((*(Body3.fixed(w) for w in fixed), box), contacts,
                          rule=rule if rule is not None else "simultaneous")


def _answer(collision: SpaceCollision) -> dict | str:
    try:
        solution = collision.solve()
    except InputError as error:
        return f"refused: {str(error).split(':')[0]}"
    return {"solution": solution, "results": solution.results()}


CASES = [_case(random.Random(SEED * 1000 + k)) for k in range(COUNT)]
QUICK = 10  # the first cases in the quick tier, the rest in the slow one (CI runs both)


@functools.cache
def _plain(index: int) -> dict | str:
    return _answer(_collision(CASES[index], sp.eye(3), sp.zeros(3, 1)))


def _same(a, b, exact: bool) -> bool:
    if exact:
        return sp.simplify(sp.sympify(a) - sp.sympify(b)) == 0
    return abs(float(a) - float(b)) <= 1e-7 * (1 + abs(float(a)))


@pytest.mark.parametrize("index", [k if k < QUICK else pytest.param(k, marks=pytest.mark.slow)
                                   for k in range(COUNT)])
def test_turned_in_space(index):
    case = CASES[index]
    plain = _plain(index)
    turned = _answer(_collision(case, TURN, SHIFT))
    if isinstance(plain, str) or isinstance(turned, str):
        assert plain == turned  # refused both ways, for the same reason
        return
    r, t = plain["results"], turned["results"]
    exact = not any(sp.sympify(x).has(sp.Float) for x in (*r.values(), *t.values()))
    for part in ("v", "omega_"):
        keys = [f"box.{part}{axis}" for axis in "xyz"]
        expected = TURN * sp.Matrix([r[k] for k in keys])
        for k, want in zip(keys, expected, strict=True):
            assert _same(t[k], want, exact), (k, t[k], want)
    for name, *_ in case["contacts"]:
        for part in ("normal_impulse", "tangential_impulse"):
            key = f"{name}.{part}"
            assert _same(t[key], r[key], exact), (key, t[key], r[key])
    assert _same(turned["solution"].energies[1], plain["solution"].energies[1], exact)


def test_the_family_is_varied():
    # several contacts and one, every tangential law and every rule, some answers exact
    # and some followed numerically, and some refused, are all in the family
    counts = {len(c["contacts"]) for c in CASES}
    laws = {laws["tangential"] for c in CASES for *_, laws in c["contacts"]}
    rules = {c["rule"] for c in CASES}
    assert counts == {1, 2, 3} and laws == {"smooth", "coulomb", "stick"}
    assert rules == {None, "driven", "sequential"}
    answers = [_plain(k) for k in range(QUICK)]
    assert any(isinstance(a, dict) for a in answers)
    assert any(isinstance(a, str) for a in answers)  # and refusals, compared too
