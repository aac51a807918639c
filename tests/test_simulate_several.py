"""Flight after an impact at several contacts: each expected time derived by hand here."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from scipy.optimize import brentq

from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import load_scene, parse_scene
from rigidimpact.simulate import run

ROOT = Path(__file__).resolve().parents[1]
G = 9.81


def scene_with(name: str, simulate: str, swap: tuple[str, str] = ("", "")):
    text = (ROOT / "derivations" / name).read_text().replace(*swap)
    return parse_scene(text + "\n[simulate]\n" + simulate + "\n")


def test_two_ball_drop_lower_ball_comes_back_to_the_floor():
    # by hand: the floor sends the heavy ball up at 1; it meets the light one (down at 1):
    # 10 * 1 + 1 * (-1) = 9 shared, e = 1 gives the heavy one (10 - 1 - 2) / 11 = 7/11 up,
    # so it lands again after 2 (7/11) / g; the light ball (29/11 up) is never caught
    scene = scene_with("two-ball-drop.toml", 'until = "restrike"\neffects = ["gravity"]')
    outcome = run(scene)
    kinds = [(e["kind"], e.get("contacts")) for e in outcome.events]
    assert kinds == [("impact", None), ("restrike", ["ground"]), ("end", None)]
    assert outcome.final["t"] == pytest.approx(2 * (7 / 11) / G, rel=1e-12)
    assert outcome.final["lower.y"] == pytest.approx(1.0, abs=1e-12)  # back on the floor
    assert outcome.final["upper.vy"] == pytest.approx(29 / 11 - G * outcome.final["t"],
                                                      rel=1e-12)
    # both orders give the same flight (the same velocities after)
    assert [o["final"]["t"] for o in outcome.details["orders"]] == [outcome.final["t"]] * 2


def test_rod_landing_flat_meets_the_floor_again_with_its_right_end():
    # after (vy, omega) = (1, -1/2): the right end's height is t - g t^2 / 2 - sin(t / 2),
    # the left end's t - g t^2 / 2 + sin(t / 2): the right end lands first
    scene = scene_with("rod-lands-flat.toml", 'until = "restrike"\neffects = ["gravity"]')
    outcome = run(scene)
    right = brentq(lambda t: t - G * t * t / 2 - math.sin(t / 2), 1e-3, 1.0, xtol=1e-15)
    restrike = outcome.events[1]
    assert (restrike["kind"], restrike["contacts"]) == ("restrike", ["right"])
    assert restrike["t"] == pytest.approx(right, rel=1e-10)
    ends = outcome.trajectory.points()
    assert ends["rod@right"][-1][1] == pytest.approx(0.0, abs=1e-9)
    assert ends["rod@left"][-1][1] > 0.01


def test_without_gravity_the_rod_never_lands_again():
    # t - sin(t/2) > 0 and t + sin(t/2) > 0 for every t > 0
    scene = scene_with("rod-lands-flat.toml", 'until = "restrike"')
    outcome = run(scene)
    assert [e["kind"] for e in outcome.events] == ["impact", "end"]
    assert "no contact" in outcome.events[-1]["why"]


def test_cradle_flies_straight_until_the_time_asked():
    scene = load_scene(ROOT / "derivations" / "newtons-cradle.toml")  # until = 2
    outcome = run(scene)
    assert outcome.final["t"] == 2
    first, last = outcome.final["first.x"], outcome.final["last.x"]
    start = load_scene(ROOT / "derivations" / "newtons-cradle.toml").bodies
    x0 = {b.name: float(b.position[0]) for b in start}
    assert first == pytest.approx(x0["first"], abs=1e-15)  # one at a time: at rest
    assert last == pytest.approx(x0["last"] + 2.0, rel=1e-15)


def test_a_dead_ball_on_the_floor_stays_in_contact():
    # e = 0: the lower ball stops on the floor and gravity presses it in at once
    scene = scene_with("two-ball-drop.toml", 'until = 1\neffects = ["gravity"]',
                       ("e = 1", "e = 0"))
    outcome = run(scene)
    assert outcome.events[1]["kind"] == "stays-closed"
    assert outcome.final["t"] == 0.0


def test_a_sliding_rod_lands_again_on_both_ends_at_once():
    # rod-slides-flat.toml: after (5/8, 1/2) and no spin, both ends land after 2 (1/2) / g
    outcome = run(load_scene(ROOT / "derivations" / "rod-slides-flat.toml"))
    restrike = outcome.events[1]
    assert restrike["contacts"] == ["left", "right"]
    assert restrike["t"] == pytest.approx(1 / G, rel=1e-12)
    assert outcome.final["rod.x"] == pytest.approx(5 / 8 / G, rel=1e-12)


def test_two_shapeless_free_bodies_cannot_be_watched():
    text = """
[[bodies]]
name = "a"
shape = "rigid"
mass = "1"
inertia = "1"
position = ["-1", "0"]
velocity = ["1", "0"]
[[bodies]]
name = "b"
shape = "rigid"
mass = "1"
inertia = "1"
position = ["1", "0"]
[[bodies]]
name = "c"
shape = "rigid"
mass = "1"
inertia = "1"
position = ["3", "0"]
[[contacts]]
name = "ab"
bodies = ["a", "b"]
point = ["0", "0"]
normal = ["1", "0"]
restitution = "1"
[[contacts]]
name = "bc"
bodies = ["b", "c"]
point = ["2", "0"]
normal = ["1", "0"]
restitution = "1"
[simulate]
until = 1
"""
    with pytest.raises(InputError, match="contact ab"):
        run(parse_scene(text))


def test_simulate_cli_draws_and_animates_several_contacts(tmp_path, capsys):
    path = tmp_path / "drop.toml"
    path.write_text((ROOT / "derivations" / "rod-lands-flat.toml").read_text()
                    + '\n[simulate]\nuntil = "restrike"\neffects = ["gravity"]\n')
    png, gif = tmp_path / "rod.png", tmp_path / "rod.gif"
    assert main(["simulate", str(path), "--plot", str(png), "--animate", str(gif)]) == 0
    out = capsys.readouterr().out
    assert "restrike (contacts right)" in out and "contacts that acted: left, right" in out
    assert png.read_bytes()[:4] == b"\x89PNG" and gif.read_bytes()[:3] == b"GIF"
