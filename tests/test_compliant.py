"""Compliant models: the push-only contact's e, the spring rod, the rigid limit."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rigidimpact as ri
import rigidimpact.solve.rules.compliant as compliant_rule
from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import load_scene, parse_scene
from rigidimpact.simulate import run
from rigidimpact.simulate.compliant import (
    MAX_DAMPING_RATIO,
    damping_ratio_for,
    restitution_of,
)
from rigidimpact.simulate.runner import rigid_limit

DERIVATIONS = Path(__file__).resolve().parent.parent / "derivations"
RIGID_SCENES = ["barbell", "disc-rod", "discs", "restrike", "sticking"]


def _isolated_contact(z: float) -> float:
    """e of the push-only spring-dashpot, by integrating it (independent of the closed form)."""
    def lets_go(_t, y):
        return y[0] + 2 * z * y[1]

    lets_go.terminal, lets_go.direction = True, -1
    sol = solve_ivp(lambda _t, y: [y[1], -y[0] - 2 * z * y[1]], (0.0, 50.0 + 50 * z),
                    [0.0, 1.0], method="Radau", events=lets_go, rtol=1e-12, atol=1e-14)
    return -sol.y_events[0][0][1]


@pytest.mark.parametrize("z", [0.05, 0.3, 0.7071, 1.0, 1.5, 4.0, 20.0])
def test_push_only_restitution_matches_integration(z):
    assert math.isclose(restitution_of(z), _isolated_contact(z), rel_tol=1e-7)


def test_push_only_contact_is_not_the_textbook_formula():
    z = 0.3
    textbook = math.exp(-math.pi * z / math.sqrt(1 - z * z))
    assert abs(restitution_of(z) - textbook) > 0.05


@pytest.mark.parametrize("e", [0.999, 0.9, 0.5, 0.1, 1e-3])
def test_damping_ratio_inverts_restitution(e):
    assert math.isclose(restitution_of(damping_ratio_for(e)), e, rel_tol=1e-10)


def test_e_zero_is_capped_and_says_so():
    text = (DERIVATIONS / "compliant.toml").read_text().replace("e = 0.5", "e = 0")
    outcome = run(parse_scene(text, "e0"))
    contact = outcome.details["contact"]
    assert contact["damping_ratio"] == MAX_DAMPING_RATIO
    assert 0 < contact["reached_e"] < 1e-6 and "unbounded" in contact["note"]


@pytest.mark.parametrize("name", RIGID_SCENES)
def test_rigid_scenes_integrate_nothing(name):
    outcome = run(load_scene(DERIVATIONS / f"{name}.toml"))
    assert outcome.ode_steps == 0
    assert not outcome.plan.effects


def _two_particles(e: float, k: float) -> str:
    return f"""
[values]
e = {e}
[[bodies]]
name = "a"
shape = "particle"
mass = "1"
velocity = ["2", "0"]
[[bodies]]
name = "b"
shape = "particle"
mass = "3"
velocity = ["-1", "0"]
[contact]
bodies = ["a", "b"]
restitution = "e"
[simulate]
effects = ["contact-compliance"]
contact_stiffness = {k}
tolerance = 1e-9
"""


@pytest.mark.parametrize("e", [1.0, 0.8, 0.3, 0.05])
def test_isolated_compliant_contact_returns_newtons_e(e):
    outcome = run(parse_scene(_two_particles(e, 1e4), "pair"))
    # textbook 1D collision of masses 1 and 3 at velocities 2 and -1
    v_a = (2 * 1 + 3 * -1 - 3 * e * (2 - -1)) / 4
    v_b = (2 * 1 + 3 * -1 + 1 * e * (2 - -1)) / 4
    assert math.isclose(outcome.final["a.vx"], v_a, abs_tol=1e-7)
    assert math.isclose(outcome.final["b.vx"], v_b, abs_tol=1e-7)


def test_energy_bookkeeping_creates_nothing():
    outcome = run(load_scene(DERIVATIONS / "compliant.toml"))
    energy = outcome.details["energy"]
    assert energy["contact_work"] <= 0
    assert energy["kinetic"] + energy["stored"] <= energy["initial"] + 1e-9
    assert abs(energy["balance_error"]) < 1e-6 * energy["initial"]


def test_compliant_run_conserves_momentum():
    outcome = run(load_scene(DERIVATIONS / "compliant.toml"))
    f = outcome.final  # m = 1, M = 2 each (barbell mass 4), v_ix = 1
    assert math.isclose(1 * f["ball.vx"] + 4 * f["barbell.vx"], 1.0, rel_tol=1e-9)
    assert abs(f["barbell.vy"]) < 1e-9


def _rigid_velocities(scene):
    solution = scene.impact().solve()
    values = scene.values
    ball, bar = solution.first_after, solution.second_after
    return {"ball.vx": float(ball.velocity[0].subs(values)),
            "barbell.vx": float(bar.velocity[0].subs(values)),
            "barbell.vy": float(bar.velocity[1].subs(values)),
            "barbell.omega": float(bar.spin.subs(values))}


def test_stiff_rod_and_contact_end_within_2e3_of_rigid():
    scene = load_scene(DERIVATIONS / "compliant.toml")  # rod 1e8, contact 1e5
    outcome = run(scene)
    for key, value in _rigid_velocities(scene).items():
        assert abs(outcome.final[key] - value) < 2e-3, key


@pytest.mark.parametrize("degrees", [20, 45, 70])
def test_sphere_a_moves_along_x_first_then_gains_minus_y(degrees):
    text = (DERIVATIONS / "spring-rod.toml").read_text().replace('"30 deg"', f'"{degrees} deg"')
    outcome = run(parse_scene(text, "spring"))
    v = outcome.trajectory.contact_velocity("barbell")
    assert v[0, 0] > 0 and abs(v[0, 1]) < 1e-12 * v[0, 0]  # the push: +x only
    # then the rod turns it toward -y: the first sideways motion is -y, and so is the mean
    # (the rigid sphere A of eq. (5) has v_y = -omega L cos(theta) < 0 for 0 < theta < 90)
    sideways = np.flatnonzero(np.abs(v[:, 1]) > 1e-6 * v[0, 0])
    assert v[sideways[0], 1] < 0
    t = outcome.trajectory.t
    assert np.trapezoid(v[:, 1], t) / (t[-1] - t[0]) < 0


def test_error_to_the_rigid_limit_falls_at_order_one_half():
    rows = rigid_limit(load_scene(DERIVATIONS / "barbell.toml"), [1e3, 1e4, 1e5])
    errors = [r["error"] for r in rows]
    assert errors[0] > errors[1] > errors[2]
    # the contact lasts ~ k^-1/2 and the barbell turns meanwhile: error ~ k^-1/2
    assert all(0.4 < r["order"] < 0.6 for r in rows[1:])


def test_stiffness_ratio_1e8_runs_with_a_stiff_integrator():
    scene = load_scene(DERIVATIONS / "compliant.toml")
    # followed to just past the contact (it lets go at 0.075 s): after it the undamped rod
    # rings at the fast period, and following that ringing for the whole settling time takes
    # most of the run's time budget on a slow machine
    table = {**scene.simulate, "contact_stiffness": 1e3, "rod_stiffness": 1e11, "until": 0.1}
    outcome = run(replace(scene, simulate=table))
    assert outcome.final["t"] == 0.1
    assert [e["kind"] for e in outcome.events][:2] == ["impact", "contact-ends"]
    assert outcome.details["integrator"]["method"] == "LSODA"
    assert outcome.details["integrator"]["stiffness_ratio"] > 1e7
    assert all(np.isfinite(v) for v in outcome.final.values())
    for key, value in _rigid_velocities(scene).items():
        assert abs(outcome.final[key] - value) < 2e-2, key


def test_an_integrator_that_breaks_the_energy_balance_is_refused(capsys):
    # scipy's Radau strays from this push-only contact (the contact lasts three times as
    # long as under LSODA or BDF): the energy balance exposes it and the run is refused
    # instead of printing its velocities; LSODA on the same scene balances to 1e-8
    scene = load_scene(DERIVATIONS / "compliant.toml")
    table = {**scene.simulate, "contact_stiffness": 1e3, "rod_stiffness": 1e5,
             "tolerance": 1e-7}
    good = run(replace(scene, simulate=table | {"integrator": "LSODA"}))
    energy = good.details["energy"]
    assert abs(energy["balance_error"]) < 1e-6 * energy["initial"]
    with pytest.raises(InputError, match="energy of this run does not balance"):
        run(replace(scene, simulate=table | {"integrator": "Radau"}))


def test_tolerance_is_reached():
    scene = load_scene(DERIVATIONS / "compliant.toml")
    loose = run(replace(scene, simulate={**scene.simulate, "tolerance": 1e-5}))
    tight = run(replace(scene, simulate={**scene.simulate, "tolerance": 1e-10}))
    for key in ("ball.vx", "barbell.vx", "barbell.omega"):
        assert abs(loose.final[key] - tight.final[key]) < 1e-5
    assert tight.ode_steps > loose.ode_steps


def test_explain_names_the_integrator_and_what_is_left_out(capsys):
    assert main(["simulate", str(DERIVATIONS / "compliant.toml"), "--explain"]) == 0
    out = capsys.readouterr().out
    assert "1. compliant" in out and "left out: gravity" in out
    assert "integrator: DOP853" in out and "damping ratio" in out


def test_plot_writes_a_png(tmp_path, capsys):
    path = tmp_path / "run.png"
    assert main(["simulate", str(DERIVATIONS / "spring-rod.toml"), "--plot", str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert list(tmp_path.iterdir()) == [path]


@pytest.mark.parametrize("change, field", [
    (('mass = "m"', 'mass = "__import__(\'os\').system(\'true\')"'), "bodies[0].mass"),
    (("[simulate]", "[simulate"), "TOML"),
    (('effects = ["rod-compliance", "contact-compliance"]', 'effects = ["warp-drive"]'),
     "simulate.effects"),
    (("rod_stiffness = 1e8", "rod_stiffness = 0"), "simulate.rod_stiffness"),
    (("contact_stiffness = 1e5", "contact_stiffness = -1e5"), "simulate.contact_stiffness"),
])
def test_hostile_or_broken_scenes_are_refused_in_one_line(tmp_path, capsys, change, field):
    text = (DERIVATIONS / "compliant.toml").read_text()
    assert change[0] in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(change[0], change[1], 1))
    assert main(["simulate", str(path), "--json"]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert field.lower() in captured.err.lower()


def test_gravity_only_when_asked_and_it_leaves_the_restrike_alone():
    text = (DERIVATIONS / "restrike.toml").read_text()
    plain = run(parse_scene(text, "plain"))
    falling = run(parse_scene(text.replace('until = "restrike"',
                                           'until = "restrike"\neffects = ["gravity"]'), "g"))
    assert "gravity" in plain.plan.not_simulated and falling.plan.effects == ("gravity",)
    t = plain.events[-1]["t"]
    assert falling.events[-1]["t"] == t  # every body falls alike
    assert math.isclose(falling.final["ball.y"], -0.5 * 9.81 * t * t, rel_tol=1e-12)
    assert math.isclose(falling.final["ball.vy"], -9.81 * t, rel_tol=1e-12)


def test_gravity_in_a_compliant_run_keeps_the_energy_balance():
    text = (DERIVATIONS / "compliant.toml").read_text().replace(
        'effects = ["rod-compliance", "contact-compliance"]',
        'effects = ["rod-compliance", "contact-compliance", "gravity"]')
    outcome = run(parse_scene(text, "g"))
    energy = outcome.details["energy"]
    assert abs(energy["balance_error"]) < 1e-6 * energy["initial"]
    assert outcome.final["barbell.vy"] < 0


def test_one_integrator_through_the_windows_gives_what_one_per_window_gives(monkeypatch):
    # past a size the compliant rule keeps one LSODA integrator for every window (its
    # memory then grows with the contacts, not with the windows): the same answer as a
    # fresh solve_ivp per window, to the integration's tolerance
    collision = ri.cluster(4, 4)
    monkeypatch.setattr(compliant_rule, "PERSISTENT_FROM", 10**9)
    (fresh,) = collision.solve(ri.Compliant())
    monkeypatch.setattr(compliant_rule, "PERSISTENT_FROM", 1)
    (kept,) = collision.solve(ri.Compliant())
    a, b = fresh.results(), kept.results()
    speeds = [k for k in a if k.endswith((".vx", ".vy", ".omega"))]
    assert len(speeds) > 30
    assert max(abs(float(a[k]) - float(b[k])) for k in speeds) < 1e-8
