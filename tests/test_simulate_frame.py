"""``simulate`` reports positions in the scene's own frame, whatever point its contact
is at: in the final state (text and JSON) and in the paths the figures draw. The
one-contact runners solve seen from the contact point; what they print must not be."""

from __future__ import annotations

import math
import random
import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from helpers import evaluated, scene_file
from rigidimpact.errors import InputError
from rigidimpact.scenes.space import SpaceScene, load_any
from rigidimpact.simulate.runner import run
from rigidimpact.simulate.space import BounceTrack

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted((ROOT / "derivations").glob("*.toml"))


def _getting_started() -> str:
    """The rod of docs/getting-started.md, as the page gives it."""
    text = (ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")
    block = next(b for b in re.findall(r"```toml\n(.*?)```", text, re.S)
                 if 'name = "rod"' in b)
    return block


def test_the_getting_started_rod_stays_where_the_scene_puts_it(tmp_path, capsys):
    # the rod's centre is at (0, 1/2), the floor contact at (-sqrt(3)/2, 0): the rigid
    # impact is an instant, so at its end (t = 0) the rod is still at (0, 1/2); it was
    # printed at (sqrt(3)/2, 1/2), seen from the contact point
    out = evaluated(capsys, ["simulate", scene_file(tmp_path, _getting_started())])
    assert out["final"]["t"] == 0
    assert (out["final"]["rod.x"], out["final"]["rod.y"]) == (0, 0.5)


def _moved(text: str, dx: sp.Rational, dy: sp.Rational) -> str:
    """A scene with its origin moved: every point it gives shifted by (dx, dy)."""
    if "getting" in text:
        text = text.replace('position = ["0", "1/2"]', f'position = ["{dx}", "1/2 + {dy}"]')
        return text.replace('point = ["-sqrt(3)/2", "0"]',
                            f'point = ["-sqrt(3)/2 + {dx}", "{dy}"]')
    # the compliant barbell: the ball at the contact point, the barbell placed from it
    text = text.replace('velocity = ["v_ix", "0"]',
                        f'velocity = ["v_ix", "0"]\nposition = ["{dx}", "{dy}"]')
    return text.replace('normal = ["1", "0"]', f'normal = ["1", "0"]\npoint = ["{dx}", "{dy}"]')


@pytest.mark.parametrize("which", ["getting-started", "compliant"])
def test_moving_the_scene_moves_every_printed_position_and_nothing_else(tmp_path, capsys,
                                                                       which):
    # seed 4: the getting-started rod's rigid impact, and the ball and the barbell
    # through the compliant contact (followed in time), seen from origins moved by
    # random rational offsets: each position moves by the offset, each velocity and
    # spin is the same
    text = "# getting started\n" + _getting_started() if which == "getting-started" else \
        (ROOT / "derivations" / "compliant.toml").read_text(encoding="utf-8")
    here = evaluated(capsys, ["simulate", scene_file(tmp_path, text)])["final"]
    rng = random.Random(4)
    for _ in range(3):
        dx, dy = (sp.Rational(rng.randint(-50, 50), rng.randint(1, 7)) for _ in range(2))
        moved = _moved(text, dx, dy)
        assert moved.count(f"{dx}") >= 2
        there = evaluated(capsys, ["simulate", scene_file(tmp_path, moved)])["final"]
        for key, value in here.items():
            fixed = key.startswith("floor.")
            shift = float(dx) if key.endswith(".x") and not fixed else \
                float(dy) if key.endswith(".y") and not fixed else 0.0
            assert math.isclose(there[key], value + shift, rel_tol=1e-9, abs_tol=1e-9), key


def _expected(scene, values) -> dict[str, np.ndarray]:
    """Each movable body's centre in the scene's frame, as the scene states it."""
    return {b.name: np.array([float(sp.sympify(x).xreplace(values)) for x in b.position])
            for b in scene.bodies if b.support != "fixed"}


def _start(track) -> dict[str, np.ndarray]:
    """Each body's centre at the first sample of a run's paths; a body drawn by two
    ends of equal mass (a rod, a barbell) by their midpoint."""
    if isinstance(track, BounceTrack):
        return {b.name: track.states(b.name)[0][1] for b in track.balls}
    points = track.points()
    centres = {k: v[0] for k, v in points.items() if "." not in k}
    ends: dict[str, list[np.ndarray]] = {}
    for key, path in points.items():
        if "." in key:
            ends.setdefault(key.split(".")[0], []).append(path[0])
    centres |= {k: (v[0] + v[1]) / 2 for k, v in ends.items()
                if k not in centres and len(v) == 2}
    return centres


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_every_shipped_scene_starts_where_it_says(path):
    scene = load_any(path)
    try:
        outcome = run(scene)
    except InputError:  # a scene that is derived, not simulated
        pytest.skip("not a scene simulate runs")
    values = dict(scene.values)
    expected = _expected(scene, values)
    if outcome.final.get("t") == 0 and not isinstance(scene, SpaceScene):
        for name, centre in expected.items():  # the rigid impact: an instant
            if f"{name}.x" in outcome.final:
                got = np.array([outcome.final[f"{name}.x"], outcome.final[f"{name}.y"]])
                assert np.allclose(got, centre, rtol=1e-12, atol=1e-12), name
    if outcome.trajectory is None:
        return
    start = _start(outcome.trajectory)
    assert start
    for name, centre in start.items():
        if name in expected:
            assert np.allclose(centre, expected[name], rtol=1e-9, atol=1e-9), name
