"""Pivots and fixed bodies: the catalogue, the laws on random supported scenes, refusals."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest
import sympy as sp

from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body, cross
from rigidimpact.paper import catalogue
from rigidimpact.scenes.scene import load_scene, parse_scene
from rigidimpact.solve.impact import Impact
from rigidimpact.verify import agree

ROOT = Path(__file__).resolve().parents[1]
SEED = 12


@pytest.mark.parametrize("check_id, _, check", catalogue.CHECKS)
def test_catalogue_matches_its_independent_answers(check_id, _, check):
    verdict = check()
    assert verdict.passed, verdict.detail


def test_a_catalogue_comparison_can_fail():
    omega = catalogue.hinged_rod().results()["rod.omega"]
    assert not agree(omega, sp.Rational(45, 13)).passed


def hinge_momentum(body: Body, pivot) -> sp.Expr:
    """Angular momentum about the hinge point, from the body's own data."""
    if body.support == "fixed":
        return sp.Integer(0)
    return body.inertia * body.spin + body.mass * cross(body.position - pivot, body.velocity)


def random_supported_impact(generator: random.Random) -> Impact:
    def rational(lo, hi):
        return sp.Rational(generator.randint(lo * 100, hi * 100), 100)

    mass, inertia = rational(1, 5), rational(1, 3)
    centre = (rational(-2, 2), rational(-2, 2))
    pivot = (rational(-3, 3), rational(-3, 3))
    while pivot == centre:
        pivot = (rational(-3, 3), rational(-3, 3))
    spin = rational(-2, 2)
    turning = (-spin * (centre[1] - pivot[1]), spin * (centre[0] - pivot[0]))
    hinged = Body.rigid(mass, inertia, centre, turning, spin, name="hinged", pivot=pivot)
    striker = (Body.particle(rational(1, 3), (rational(1, 4), rational(-2, 2)), "ball")
               if generator.random() < 0.5 else
               Body.rigid(rational(1, 3), rational(1, 2), (rational(-2, 0), rational(-1, 1)),
                          (rational(1, 4), rational(-2, 2)), rational(-1, 1), name="ball"))
    contact = Contact(restitution=rational(0, 1),
                      tangential=generator.choice(["smooth", "smooth", "stick"]))
    return Impact(striker, hinged, contact)


def test_random_pivoted_scenes_obey_the_laws():
    generator, tested = random.Random(SEED), 0
    while tested < 40:
        try:
            impact = random_supported_impact(generator)
        except InputError:  # not approaching: draw again
            continue
        solution = impact.solve()
        before = (impact.first, impact.second)
        after = (solution.first_after, solution.second_after)
        pivot = impact.second.pivot
        # angular momentum of the pair about the hinge is kept
        assert sum(hinge_momentum(b, pivot) for b in before) == \
            sum(hinge_momentum(b, pivot) for b in after)
        # Newton's restitution along the normal at O
        closing = before[1].contact_velocity[0] - before[0].contact_velocity[0]
        leaving = after[1].contact_velocity[0] - after[0].contact_velocity[0]
        assert leaving == -impact.contact.restitution * closing
        # the hinge point stays put, and energy is not created on a smooth contact
        assert after[1].point_velocity(pivot) == sp.zeros(2, 1)
        if impact.contact.tangential == "smooth":
            assert solution.energy_lost >= 0
        # the reaction: momentum change of the hinged body = contact impulse + reaction
        change = after[1].momentum - before[1].momentum
        assert change == solution.impulse + solution.pivot_impulse(impact.second)
        tested += 1


def test_a_ball_on_a_floor_bounces_with_e():
    e = sp.Symbol("e", nonnegative=True)
    ball = Body.disc(1, 1, position=(0, 1), velocity=(0, -3), name="ball")
    solution = Impact(ball, Body.fixed("floor"), Contact(normal=(0, -1), restitution=e)).solve()
    assert solution.results()["ball.vy"] == 3 * e
    assert "floor.vx" not in solution.results()


@pytest.mark.parametrize("name, key, expected", [
    ("hinged-rod", "rod.omega", 45 / 14),
    ("hinged-rod", "ball.vx", -1 / 7),
    ("rocking-block", "block.omega", (1 - 1.5 * 0.36) * -2.0),
    ("ballistic-pendulum", "bob.vx", 0.01 * 400 / 2.01),
])
def test_catalogue_scenes_evaluate(capsys, name, key, expected):
    assert main(["evaluate", str(ROOT / "derivations" / f"{name}.toml"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data[key] == pytest.approx(expected, rel=1e-13)


def test_derive_prints_the_hinge_law(capsys):
    assert main(["derive", str(ROOT / "derivations" / "hinged-rod.toml")]) == 0
    out = capsys.readouterr().out
    assert "angular momentum of the pair about rod's pivot" in out
    assert "linear momentum" not in out  # the hinge's reaction changes it


SCENE = """
[[bodies]]
name = "ball"
shape = "particle"
mass = "1"
velocity = ["1", "0"]

[[bodies]]
name = "rod"
shape = "rod"
mass = "1"
length = "2"
angle = "pi/2"
struck_at = "1"
{extra}
"""


@pytest.mark.parametrize("extra, needle", [
    ('pivot = ["0", "2"]\nvelocity = ["1", "1"]', "moves only by turning"),
    ('pivot = ["0", "2"]\n[[bodies]]\nname = "w"\nshape = "fixed"', "exactly two"),
    ('[contact]\nbodies = ["ball", "rod"]\nrestitution = "1"', ""),
])
def test_supported_scenes_are_checked(extra, needle):
    text = SCENE.format(extra=extra)
    if needle:
        with pytest.raises(InputError, match=needle):
            parse_scene(text + '\n[contact]\nbodies = ["ball", "rod"]\nrestitution = "1"\n')
    else:
        parse_scene(text)


def test_refusals_for_supports():
    with pytest.raises(InputError, match="two fixed bodies"):
        Impact(Body.fixed("a"), Body.fixed("wall"), Contact())
    with pytest.raises(InputError, match="not approaching"):  # O moves along the wall
        Impact(Body.rigid(1, 1, (-1, 0), pivot=(-2, 0), spin=-1, velocity=(0, -1),
                          name="a"),
               Body.fixed("wall"), Contact())
    with pytest.raises(InputError, match="cannot move"):
        Body.rigid(1, 0, (0, 0), pivot=(0, 0))
    with pytest.raises(InputError, match="fixed body cannot also have a pivot"):
        Body("w", 1, 0, (0, 0), shape="fixed", pivot=(0, 1))


def test_simulate_refuses_flight_of_supported_bodies(tmp_path, capsys):
    text = (ROOT / "derivations" / "hinged-rod.toml").read_text()
    path = tmp_path / "s.toml"
    path.write_text(text + '\n[simulate]\nuntil = 1.0\n')
    assert main(["simulate", str(path)]) == 2
    assert "pivoted or fixed" in capsys.readouterr().err
    assert main(["simulate", str(ROOT / "derivations" / "hinged-rod.toml"), "--json"]) == 0
    final = json.loads(capsys.readouterr().out)["final"]
    assert final["rod.omega"] == pytest.approx(45 / 14)


def test_scene_with_a_wall_loads():
    scene = load_scene(ROOT / "derivations" / "bar-wall.toml")
    assert scene.bodies[1].support == "fixed"
    results = scene.derivation().results
    assert "wall.vx" not in results and "bar.omega" in results


def test_a_numeric_pivoted_scene_keeps_its_hinge_law():
    text = """
[[bodies]]
name = "ball"
shape = "particle"
mass = "2"
velocity = ["5", "0"]
[[bodies]]
name = "rod"
shape = "rod"
mass = "8"
length = "1.2"
angle = "1.3"
struck_at = "0.6"
spin = "0.5"
pivot = ["1.2*cos(1.3)", "1.2*sin(1.3)"]
[contact]
bodies = ["ball", "rod"]
restitution = "0.8"
"""
    scene = parse_scene(text)  # 50-digit numeric mode: the velocity follows from the spin
    solution = scene.derivation().solution
    pivot = scene.bodies[1].pivot
    before = sum(sp.N(hinge_momentum(b, pivot), 40) for b in scene.bodies)
    after = sum(sp.N(hinge_momentum(b, pivot), 40) for b in solution.after)
    assert abs(before - after) < 1e-35


ELL, MASS, W0 = sp.symbols("ell M omega_0", positive=True)


def _hanging_rod(name, top):
    """A uniform rod with one end at O and the other on a pivot at (0, top)."""
    spin = W0 if top > 0 else 0
    return Body.rod(MASS, ELL, sp.pi / 2, top / 2, velocity=(spin * top / 2, 0), spin=spin,
                    pivot=(0, top), name=name)


def test_pivoted_rod_strikes_a_wall():
    # by hand: one degree of freedom, so the end's normal velocity reverses scaled by e;
    # P = (1 + e) M w0 l / 3 (effective mass I_q / l^2 = M/3), and the pivot supplies the
    # rest of the centre's momentum change: -(1 + e) M w0 l / 6 along x
    e = sp.Symbol("e", nonnegative=True)
    rod = _hanging_rod("rod", ELL)
    solution = Impact(rod, Body.fixed("wall"), Contact(restitution=e)).solve()
    results = solution.results()
    assert sp.simplify(results["rod.omega"] + e * W0) == 0
    assert sp.simplify(results["impulse"] - (1 + e) * MASS * W0 * ELL / 3) == 0
    assert sp.simplify(results["rod.pivot_impulse_x"] + (1 + e) * MASS * W0 * ELL / 6) == 0
    assert results["rod.pivot_impulse_y"] == 0
    assert sp.simplify(solution.energy_loss_fraction - (1 - e**2)) == 0


def test_two_pivoted_rods_exchange_like_equal_masses():
    # by hand: both ends have the effective mass M/3 along the normal, so the end speeds
    # follow the equal-mass line collision: (1 - e)/2 and (1 + e)/2 of the striker's
    e = sp.Symbol("e", nonnegative=True)
    impact = Impact(_hanging_rod("a", ELL), _hanging_rod("b", -ELL), Contact(restitution=e))
    solution = impact.solve()
    results = solution.results()
    assert sp.simplify(results["a.omega"] - (1 - e) * W0 / 2) == 0
    assert sp.simplify(results["b.omega"] + (1 + e) * W0 / 2) == 0
    assert [eq.label for eq in impact.equations()][:2] == [
        "angular impulse on a about its pivot", "angular impulse on b about its pivot"]
    # what is printed is what is solved: every printed law holds at the solution
    for eq in impact.equations():
        assert sp.simplify(eq.residual.subs(solution.values)) == 0
