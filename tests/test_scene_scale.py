"""Scenes of many contacts: read and checked in time linear in their size, names checked
before any algebra, and a size budget said in one line before anything is built."""

from __future__ import annotations

import pytest
import sympy as sp

from helpers import refused, scene_file
from rigidimpact.cli import main
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.solve.collision import chain


def cradle(n: int, misspelt: bool = False) -> str:
    """n touching spheres (radius 1/2, mass 1) in a row, the first at speed 1."""
    lines = ['title = "cradle"']
    for k in range(n):
        lines += ["[[bodies]]", f'name = "b{k}"', 'shape = "sphere"', 'mass = "1"',
                  'radius = "1/2"', f'position = ["{k}", "0"]',
                  f'velocity = ["{1 if k == 0 else 0}", "0"]']
    for k in range(n - 1):
        second = "bX" if misspelt and k == n - 2 else f"b{k + 1}"
        lines += ["[[contacts]]", f'name = "c{k}"', f'bodies = ["b{k}", "{second}"]',
                  f'point = ["{2 * k + 1}/2", "0"]', 'normal = ["1", "0"]',
                  'restitution = "1"']
    return "\n".join(lines + ["[impact]", 'rule = "simultaneous"']) + "\n"


def test_a_cradle_scene_gives_what_the_chain_builder_gives():
    # the same physics stated twice: a scene file and ri.chain (inertia aside: the
    # balls do not turn); every ball's velocity after must agree exactly
    n = 301
    [scene] = parse_scene(cradle(n)).outcomes()
    [built] = chain(n).solve(__import__("rigidimpact").Simultaneous())
    got = scene.results()
    want = built.results()
    assert all(got[f"b{k}.vx"] == want[f"ball{k}.vx"] for k in range(n))
    # by hand: every contact acts, the first leaves at 1 and the others at 0, so balls
    # 1 .. n-1 share one speed a and ball 0 has a - 1; momentum: n a - 1 = 1, a = 2/n
    assert got["b0.vx"] == sp.Rational(2, n) - 1
    assert all(got[f"b{k}.vx"] == sp.Rational(2, n) for k in range(1, n))


@pytest.mark.parametrize("n", [10_001, 100_001])
def test_scenes_past_the_budget_are_refused_at_once(tmp_path, capsys, n):
    path = scene_file(tmp_path, cradle(n))
    refused(capsys, ["evaluate", path], "past the budget")


def test_a_misspelt_body_in_the_last_contact_is_named_before_any_algebra(tmp_path, capsys):
    path = scene_file(tmp_path, cradle(2500, misspelt=True))
    refused(capsys, ["evaluate", path], "contacts[2498].bodies: no body named 'bX'")


def test_a_thousand_ball_cradle_scene_evaluates(tmp_path, capsys):
    path = scene_file(tmp_path, cradle(1001))
    assert main(["evaluate", path, "--json"]) == 0
    out = capsys.readouterr().out
    assert '"b1000.vx": 0.001998001998001998' in out  # 2/n, as derived above
