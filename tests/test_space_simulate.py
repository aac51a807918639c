"""``simulate`` of a 3-D scene past its impact: a sphere among fixed planes, from the
command line, with its figure and animation (issue: three dimensions after the impact).

Expected values are derived by hand here: Garwin's bounce map of a perfectly rough,
elastic solid sphere, and the one quantity a ball on a floor keeps through flight,
bounces and sliding."""

from __future__ import annotations

from fractions import Fraction as F
from pathlib import Path

import pytest
from PIL import Image

from helpers import evaluated, refused, scene_file
from rigidimpact.cli import main

ROOT = Path(__file__).resolve().parents[1]
SUPERBALL = str(ROOT / "derivations" / "superball-under-table.toml")
SPINNING = str(ROOT / "derivations" / "spinning-ball-bounces.toml")


def _garwin(v: F, s: F, floor: bool) -> tuple[F, F]:
    """One bounce of a perfectly rough, elastic solid sphere (k = I/(m R^2) = 2/5), by
    hand: the touching point's slip S reverses, the impulse F = -2 S m k/(1 + k) along
    x. On the floor (normal +z) the slip is v - R w_y and R w_y changes by -F/(m k); on
    the table's underside (normal -z) the slip is v + R w_y and R w_y changes by
    +F/(m k). `v` is v_x, `s` is R w_y."""
    k = F(2, 5)
    slip = v - s if floor else v + s
    push = -2 * slip * k / (1 + k)  # F / m
    return v + push, s + (-push / k if floor else push / k)


def test_garwins_superball_comes_back_toward_the_thrower(capsys):
    out = evaluated(capsys, ["simulate", SUPERBALL])
    v, s = F(2), F(0)
    for floor in (True, False, True):
        v, s = _garwin(v, s, floor)
    assert (v, s) == (F(-666, 343), F(-260, 343))  # the map's fixed numbers, by hand
    final = out["final"]
    assert final["ball.vx"] == pytest.approx(float(v), rel=1e-15)
    assert final["ball.omega_y"] == pytest.approx(float(s * 40), rel=1e-15)  # R = 1/40
    assert final["ball.vz"] == 3.0 and final["ball.vy"] == final["ball.omega_x"] == 0.0
    # the centre rises 29/40 at 3 between floor and table: a bounce every 7/30 s; it
    # goes forward 6/7 * 7/30 = 1/5, then back -62/49 * 7/30: ends at x = -2/21, behind
    # the thrower's release point
    impacts = [(e["t"], e["plane"]) for e in out["events"] if e["kind"] == "impact"]
    assert impacts == [(0.0, "floor"), (pytest.approx(7 / 30), "table"),
                       (pytest.approx(7 / 15), "floor")]
    assert final["ball.x"] == pytest.approx(-2 / 21, rel=1e-15)
    assert out["exact"] is True and out["impacts"] == 3


def test_a_spinning_ball_bounces_slides_and_rolls_as_its_kept_quantity_says(capsys):
    # through flight, each bounce on the floor and the sliding after, the ball keeps
    # L = I w + m R n x v_h (the floor's impulse and friction act at the touching point;
    # in flight nothing turns the ball or moves it sideways); rolling (v_h = w x R n)
    # with that L gives v_h = (5/7)(v_h0 + (2/5) R w0 x n) = (5/7)((1, 1/2) + (-4/5, 0))
    out = evaluated(capsys, ["simulate", SPINNING])
    final = out["final"]
    assert (final["ball.vx"], final["ball.vy"]) == (pytest.approx(1 / 7, rel=1e-14),
                                                    pytest.approx(5 / 14, rel=1e-14))
    # it rolls: the touching point is at rest, it lies on the floor, no spin about z
    assert final["ball.vx"] - 0.1 * final["ball.omega_y"] == pytest.approx(0, abs=1e-14)
    assert final["ball.vy"] + 0.1 * final["ball.omega_x"] == pytest.approx(0, abs=1e-14)
    assert final["ball.vz"] == 0.0 and final["ball.z"] == pytest.approx(0.1)
    assert final["ball.omega_z"] == 0.0
    kinds = [e["kind"] for e in out["events"]]
    assert kinds[-2:] == ["rolls", "end"] and kinds.count("impact") == out["impacts"]
    # each bounce's rise halves (e = 1/2): the gaps between bounces halve too
    times = [e["t"] for e in out["events"] if e["kind"] == "impact"]
    assert times[2] - times[1] == pytest.approx((times[1] - times[0]) / 2, rel=1e-12)
    courses = [e["course"] for e in out["events"] if e["kind"] == "impact"]
    assert courses[:3] == ["slides throughout", "slides, then sticks", "sticks"]
    # the bounces from the third (each sticks, rolling) are summed: the rises from the
    # first landing at 2 are 1, 1/2, ..., whose flights 2 v / g add up to 4 / 9.81 in all
    assert kinds[-3:-1] == ["settles", "rolls"]
    assert "infinitely many bounces summed" in out["events"][-3]["course"]
    assert out["events"][-3]["t"] == pytest.approx(4 / 9.81, rel=1e-14)


def test_the_figure_and_the_animation_are_written(tmp_path, capsys):
    png, gif = tmp_path / "superball.png", tmp_path / "superball.gif"
    assert main(["simulate", SUPERBALL, "--plot", str(png), "--animate", str(gif)]) == 0
    capsys.readouterr()
    with Image.open(png) as picture:
        # two views one over the other at one scale: the ball rises 0.75 m and travels
        # 0.3 m, so the picture is taller than wide
        assert picture.size[1] > picture.size[0] > 200
    with Image.open(gif) as film:
        assert film.n_frames == 60


SPHERE = """
[[bodies]]
name = "room"
shape = "fixed"
[[bodies]]
name = "ball"
shape = "sphere"
mass = "1"
radius = "1"
position = ["0", "0", "1"]
velocity = ["1", "0", "-1"]
[contact]
name = "floor"
bodies = ["room", "ball"]
point = ["0", "0", "0"]
normal = ["0", "0", "1"]
restitution = "1/2"
tangential = "coulomb"
friction = "1/5"
"""


@pytest.mark.parametrize("extra, needle", [
    ('[simulate]\nimpacts = 0', "simulate.impacts"),
    ('[simulate]\nimpacts = "three"', "simulate.impacts"),
    ('[simulate]\nimpacts = true', "simulate.impacts"),
    ('[simulate]\nuntil = -1', "simulate.until"),
    ('[simulate]\nuntil = 1\neffects = ["tangential-compliance"]',
     "simulate.stiffness_ratio"),
    ('[simulate]\nuntil = 1\neffects = ["tangential-compliance"]\nstiffness_ratio = 1\n'
     '[[planes]]\nname = "wall"\nbodies = ["room", "ball"]\npoint = ["3/2", "0", "0"]\n'
     'normal = ["-1", "0", "0"]\nrestitution = "1"', "wall.tangential"),
    ('[simulate]\nuntil = 1\neffects = ["wind"]', "simulate.effects"),
    ('[[planes]]\nbodies = ["room", "ball"]\nnormal = ["1", "0", "0"]\nrestitution = "1"'
     '\n[simulate]\nuntil = 1', "planes[0].name"),
    ('[[planes]]\nname = "floor"\nbodies = ["room", "ball"]\nnormal = ["1", "0", "0"]\n'
     'restitution = "1"\n[simulate]\nuntil = 1', "planes[0].name"),
    ('[[planes]]\nname = "wall"\nbodies = ["room", "room"]\nnormal = ["1", "0", "0"]\n'
     'restitution = "1"\n[simulate]\nuntil = 1', "planes[0].bodies"),
    ('[[planes]]\nname = "wall"\nbodies = ["room", "cat"]\nnormal = ["1", "0", "0"]\n'
     'restitution = "1"\n[simulate]\nuntil = 1', "planes[0].bodies"),
    ('[[planes]]\nname = "wall"\nbodies = ["room", "ball"]\nnormal = ["1", "0", "0"]\n'
     'restitution = "2"\n[simulate]\nuntil = 1', "planes[0]"),
    ("[[planes]]\nname = 'wall'\nbodies = ['room', 'ball']\nnormal = ['1', '0', '0']\n"
     "restitution = '1'\nfoo = 1\n[simulate]\nuntil = 1", "planes[0].foo"),
    ("[planes]\nname = 'wall'", "planes"),
])
def test_bad_input_to_every_new_field_is_refused_in_one_line(tmp_path, capsys, extra,
                                                            needle):
    refused(capsys, ["simulate", scene_file(tmp_path, SPHERE + extra)], needle)


def test_pictures_of_a_run_that_ends_at_the_impact_are_refused(tmp_path, capsys):
    path = scene_file(tmp_path, SPHERE)
    refused(capsys, ["simulate", path, "--plot", str(tmp_path / "a.png")], "--plot")
    refused(capsys, ["simulate", path, "--animate", str(tmp_path / "a.gif")], "--animate")
    longer = scene_file(tmp_path, SPHERE + "[simulate]\nuntil = 1", "later.toml")
    refused(capsys, ["simulate", longer, "--animate", str(tmp_path / "a.mp4")], "--animate")
    assert not any(tmp_path.glob("a.*"))


def test_a_count_of_impacts_in_a_planar_scene_is_refused(tmp_path, capsys):
    planar = """
[[bodies]]
name = "ball"
shape = "disc"
mass = "1"
radius = "1"
velocity = ["1", "0"]
[[bodies]]
name = "wall"
shape = "fixed"
[contact]
bodies = ["ball", "wall"]
point = ["1", "0"]
restitution = "1"
[simulate]
impacts = 2
"""
    refused(capsys, ["simulate", scene_file(tmp_path, planar)], "simulate.impacts")


def test_a_free_body_that_is_not_a_sphere_past_the_impact_is_refused(tmp_path, capsys):
    two = SPHERE.replace('[contact]', '''[[bodies]]
name = "other"
shape = "rigid"
mass = "1"
inertia = ["1", "1", "1"]
position = ["5", "0", "1"]
[contact]''') + "[simulate]\nuntil = 1"
    refused(capsys, ["simulate", scene_file(tmp_path, two)], "bodies")


def test_bounces_through_the_compliant_contact_keep_the_rolling_speed(tmp_path, capsys):
    # the compliant contact's forces act at the touching point too, so the angular
    # momentum about it is kept through every bounce as in the rigid run: the ball ends
    # rolling at the same (1/7, 5/14), though each bounce differs
    text = Path(SPINNING).read_text().replace(
        'effects = ["gravity"]     # g = 9.81 along -z',
        'effects = ["gravity", "tangential-compliance"]\nstiffness_ratio = 0.79')
    assert "tangential-compliance" in text
    out = evaluated(capsys, ["simulate", scene_file(tmp_path, text)])
    final = out["final"]
    assert (final["ball.vx"], final["ball.vy"]) == (pytest.approx(1 / 7, rel=1e-9),
                                                    pytest.approx(5 / 14, rel=1e-9))
    courses = [e["course"] for e in out["events"] if e["kind"] == "impact"]
    assert all("compliant contact" in c for c in courses)
    assert any("compliant contact" in n for n in out["notes"]) and out["exact"] is False
    rigid = evaluated(capsys, ["simulate", SPINNING])
    first = [e["t"] for e in out["events"] if e["kind"] == "impact"][1]
    assert first != pytest.approx([e["t"] for e in rigid["events"]
                                   if e["kind"] == "impact"][1], rel=1e-6)


def test_a_cue_ball_faster_than_light_is_refused_before_any_impact(tmp_path, capsys,
                                                                   monkeypatch):
    # at 1e30 m/s the stun shot's balls would cross the table a thousand times in 1e-27 s;
    # under gravity (m/s^2) the run is in SI units, where no rigid body moves that fast:
    # refused in one line naming the field, before any impact is solved
    import rigidimpact.simulate.bounces as bounces

    def never(*args, **kwargs):
        raise AssertionError("an impact was solved")
    monkeypatch.setattr(bounces, "_impact", never)
    text = (ROOT / "derivations" / "stun-shot.toml").read_text().replace(
        'velocity = ["3/2", "0", "0"]', 'velocity = ["1e30", "0", "0"]')
    assert "1e30" in text
    err = refused(capsys, ["simulate", scene_file(tmp_path, text)])
    assert "cue.velocity" in err and "speed of light" in err
    # a spin whose surface moves that fast, too
    text = (ROOT / "derivations" / "stun-shot.toml").read_text().replace(
        'velocity = ["3/2", "0", "0"]', 'velocity = ["3/2", "0", "0"]\nspin = ["0", "0", "1e11"]')
    err = refused(capsys, ["simulate", scene_file(tmp_path, text)])
    assert "cue.spin" in err and "speed of light" in err


def test_draw_and_animate_from_python_in_either_dimension(tmp_path):
    # ri.draw: a 3-D run that ends at the impact is drawn as its velocities before and
    # after; ri.animate refuses it in one line (nothing moves); a planar run that moves
    # is drawn and animated, its GIF more than one frame
    import PIL.Image

    import rigidimpact as ri

    scene = ri.load_any(str(ROOT / "derivations" / "cushion-rebound.toml"))
    outcome = ri.run(scene)
    ri.draw(scene, outcome, tmp_path / "cushion.png")
    with PIL.Image.open(tmp_path / "cushion.png") as picture:
        assert picture.format == "PNG" and picture.width > 300
    with pytest.raises(ri.InputError, match="nothing moves"):
        ri.animate(scene, outcome, tmp_path / "cushion.gif")
    assert not (tmp_path / "cushion.gif").exists()
    scene = ri.load_any(str(ROOT / "derivations" / "newtons-cradle.toml"))
    outcome = ri.run(scene)
    ri.draw(scene, outcome, tmp_path / "cradle.png")
    ri.animate(scene, outcome, tmp_path / "cradle.gif")
    with PIL.Image.open(tmp_path / "cradle.gif") as animation:
        assert animation.n_frames > 10
