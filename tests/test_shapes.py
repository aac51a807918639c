"""Shapes: each builds from its scene fields; a new shape is one class."""

from __future__ import annotations

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model import shapes
from rigidimpact.model.bodies import Body
from rigidimpact.scenes.scene import parse_scene

STRIKER = '''
[[bodies]]
name = "ball"
shape = "particle"
mass = "1"
velocity = ["1", "0"]
'''
CONTACT = '''
[contact]
bodies = ["ball", "target"]
restitution = "1"
'''
TABLES = {
    "particle": 'mass = "2"',
    "barbell": 'mass = "1"\nhalf_length = "1"\nangle = "0"',
    "rod": 'mass = "3"\nlength = "2"\nangle = "pi/2"\nstruck_at = "1/2"',
    "disc": 'mass = "2"\nradius = "1"',
    "ring": 'mass = "2"\nradius = "1"',
    "sphere": 'mass = "5"\nradius = "1"',
    "rigid": 'mass = "1"\ninertia = "2"\nposition = ["1", "1"]',
    "fixed": '',
}
# central inertia of each, from the textbook formula for its sizes above
INERTIA = {"particle": 0, "barbell": 2, "rod": 1, "disc": 1, "ring": 2, "sphere": 2,
           "rigid": 2}


@pytest.mark.parametrize("name", sorted(shapes.SHAPES))
def test_every_shape_builds_from_its_scene_fields(name):
    text = STRIKER + f'[[bodies]]\nname = "target"\nshape = "{name}"\n{TABLES[name]}\n' + CONTACT
    body = parse_scene(text).bodies[1]
    assert body.shape == name
    if name != "fixed":
        assert body.inertia == INERTIA[name]
    kind = shapes.SHAPES[name]
    for key in kind.required:  # each required field is refused when missing
        lines = [line for line in TABLES[name].splitlines() if not line.startswith(key)]
        broken = STRIKER + f'[[bodies]]\nname = "target"\nshape = "{name}"\n' + \
            "\n".join(lines) + "\n" + CONTACT
        with pytest.raises(InputError, match=f"bodies\\[1\\].{key}: required"):
            parse_scene(broken)


def test_outline_features():
    assert [n for n in shapes.SHAPES if shapes.is_round(n)] == ["disc", "ring", "sphere"]
    assert [n for n in shapes.SHAPES if shapes.is_segment(n)] == ["barbell", "rod"]
    assert not shapes.is_round("no-such-shape")


class Plate(shapes.Shape):
    """A square plate of side a, struck at a corner: I = m a^2 / 6, centre a/sqrt(2)
    along the normal."""

    name, fields, required = "plate", ("mass", "side"), ("mass", "side")

    @classmethod
    def build(cls, given):
        side = given.expr("side")
        return Body.rigid(given.expr("mass"), given.expr("mass") * side**2 / 6,
                          tuple(side / sp.sqrt(2) * given.outward), given.velocity,
                          given.spin, given.name)


def test_a_new_shape_is_one_class(monkeypatch):
    monkeypatch.setitem(shapes.SHAPES, "plate", Plate)
    text = STRIKER + '[[bodies]]\nname = "target"\nshape = "plate"\nmass = "6"\nside = "1"\n' \
        + CONTACT
    results = parse_scene(text).derivation().results
    # by hand: the blow passes through the centre (on the normal), so the plate does
    # not turn and the pair is a 1 : 6 line collision with e = 1: the plate takes 2/7
    assert results["target.vx"] == sp.Rational(2, 7)
    assert results["target.omega"] == 0
