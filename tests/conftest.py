"""Shared helpers for the tests: random rigid bodies with a recorded seed."""

from __future__ import annotations

import os
import random

import pytest
import sympy as sp

from rigidimpact.model.bodies import Body

SEED = 1729

# every test derives what it checks: the cache of derive's answers is off (its own test
# turns it on, in a folder of its own)
os.environ["RIGIDIMPACT_CACHE"] = "off"


def random_body(rng: random.Random, name: str, side: int) -> Body:
    """A random primitive with exact rational data, on the given side of O."""

    def q(lo: float, hi: float) -> sp.Rational:
        return sp.Rational(rng.randint(int(lo * 100), int(hi * 100)), 100)

    shape = rng.choice(["particle", "barbell", "rod", "disc", "ring", "sphere", "rigid"])
    velocity = (q(-2, 2), q(-2, 2))
    spin = 0 if shape == "particle" else q(-3, 3)
    angle = q(0, 6) if side > 0 else q(0, 6) + sp.pi
    if shape == "particle":
        return Body.particle(q(0.1, 5), velocity, name)
    if shape == "barbell":
        return Body.barbell(q(0.1, 5), q(0.1, 2), angle, velocity, spin, name)
    if shape == "rod":
        length = q(0.2, 3)
        return Body.rod(q(0.1, 5), length, angle, length * q(-0.5, 0.5), velocity, spin, name)
    if shape == "rigid":
        return Body.rigid(q(0.1, 5), q(0.01, 2), (side * q(0.05, 2), q(-1, 1)), velocity,
                          spin, name)
    maker = {"disc": Body.disc, "ring": Body.ring, "sphere": Body.sphere}[shape]
    return maker(q(0.1, 5), q(0.05, 1), None, side, velocity, spin, name)


@pytest.fixture
def rng() -> random.Random:
    return random.Random(SEED)
