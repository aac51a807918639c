"""Rough contacts with tilted normals of irrational length (sqrt(61)/8, sqrt(65)/8, ...):
scenes that once hung or crashed, each answer checked against an independent oracle
(tests/oracle.py: Routh's method and the velocity-level conditions, in mpmath at 50
digits), and a seeded random search over their family (tests/rough_search.py)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import rough_search
from rigidimpact.cli import main
from rigidimpact.errors import InputError

SCENES = Path(__file__).parent / "rough_scenes"


@pytest.mark.parametrize("name", sorted(p.name for p in SCENES.glob("*.toml")))
def test_each_scene_is_answered_and_confirmed_by_the_oracle(name, capsys):
    text = (SCENES / name).read_text()
    assert main(["evaluate", str(SCENES / name), "--json"]) == 0
    capsys.readouterr()
    assert rough_search.disagreement(text) == []


def test_scene_a_leaves_one_contact_by_routh_and_releases_the_other():
    # c0 slides, then sticks (Routh); c1 is released and opens
    text = (SCENES / "a-two-rough-simultaneous.toml").read_text()
    import rigidimpact as ri

    [solution] = ri.parse_scene(text).outcomes()
    assert solution.acted == ("c0",)
    assert solution.courses == ("c0: slip-stick", "c1: released")


def test_scene_b_evaluates_numbers_whose_integers_exceed_float64(tmp_path):
    # the energetic law's exact answer holds integers past 2**1024 under a square root:
    # evaluated from its exact form, not by a float64 kernel (once an internal error)
    text = (SCENES / "b-three-energetic-sequential.toml").read_text()
    status, err, _, numbers = rough_search.run_one(text, tmp_path)
    assert status == 0, err
    assert numbers["c1.tangential_impulse"] == 0.0 and numbers["c2.normal_impulse"] == 0.0


def test_a_ringing_sequential_run_says_where_it_left_exact_arithmetic():
    import rigidimpact as ri

    text = (SCENES / "e-ringing-energetic-sequential.toml").read_text()
    [solution] = ri.parse_scene(text).outcomes()
    assert solution.notes and "rounded to 60 digits" in solution.notes[0]
    assert solution.passes > 100


def test_the_rows_of_a_rational_normal_stay_rational():
    # every rule is unchanged by scaling a contact's rows; rational rows keep W rational
    import rigidimpact as ri

    text = (SCENES / "c-three-rough-simultaneous.toml").read_text()
    collision = ri.parse_scene(text).collision({})
    assert all(x.is_Rational for x in collision.scaled_W)
    assert [str(s) for s in collision.row_scale] == ["sqrt(58)/8", "sqrt(65)/8", "sqrt(61)/8"]


def test_random_rough_family_small(tmp_path):
    rows = rough_search.search(8, 2024, tmp_path)
    assert [r for r in rows if r["problem"]] == []
    assert all(r["status"] in (0, 2) for r in rows)


@pytest.mark.slow
def test_random_rough_family_300(tmp_path):
    rows = rough_search.search(300, 31, tmp_path)
    assert [(r["index"], r["problem"]) for r in rows if r["problem"]] == []


def test_builders_refuse_wrong_types_and_sizes_before_building():
    import rigidimpact as ri

    for call, needle in ((lambda: ri.chain("3"), "n: must be a whole number"),
                         (lambda: ri.chain(2.5), "n: must be a whole number"),
                         (lambda: ri.chain(True), "n: must be a whole number"),
                         (lambda: ri.chain(1), "n: must be at least 2"),
                         (lambda: ri.fan(0), "k: must be at least 1"),
                         (lambda: ri.cluster(0, 3), "rows: must be at least 1"),
                         (lambda: ri.cluster(100, 100), "past the budget"),
                         (lambda: ri.chain(3).solve("simultaneous"), "rule: must be a rule"),
                         (lambda: ri.Sequential("c0"), "order: must be a sequence"),
                         (lambda: ri.Sequential(sample=0), "sample: must be at least 1"),
                         (lambda: ri.Compliant(float("nan")), "stiffness"),
                         (lambda: ri.Compliant(1e6, hertz="yes"), "hertz")):
        with pytest.raises(InputError, match=needle):
            call()
    with pytest.raises(InputError, match="past the budget"):
        ri.chain(10**7)


def test_the_scene_files_are_what_the_issue_stated():
    a = tomllib.loads((SCENES / "a-two-rough-simultaneous.toml").read_text())
    assert [c["normal"] for c in a["contacts"]] == [["3/4", "-5/8"], ["3/4", "-3/4"]]


def test_passes_that_never_settle_are_refused_in_one_line():
    # a model whose contacts close again after every impact (as two elastic contacts
    # that hand the motion back and forth can): refused, with the count of passes
    from rigidimpact.solve.collision import sequential_passes

    with pytest.raises(InputError, match="did not settle in 1000 passes"):
        sequential_passes([0, 1], lambda k: -1, lambda k, closing: (1, 0, None), 1)


FOUR_DISCS = """
title = "four discs: Newton's rule acting together creates energy"
[[bodies]]
name = "d0"
shape = "rigid"
mass = "4/3"
inertia = "2/3"
position = ["0", "0"]
velocity = ["-1", "-3/2"]
[[bodies]]
name = "d1"
shape = "rigid"
mass = "7/2"
inertia = "7/16"
position = ["0", "3/2"]
[[bodies]]
name = "d2"
shape = "rigid"
mass = "7/2"
inertia = "7/4"
position = ["-42/29", "-40/29"]
[[bodies]]
name = "d3"
shape = "rigid"
mass = "3"
inertia = "27/32"
position = ["6/5", "37/20"]
velocity = ["1/2", "-1/2"]
[[contacts]]
name = "k0"
bodies = ["d0", "d1"]
point = ["0", "1"]
normal = ["0", "1"]
restitution = "1"
[[contacts]]
name = "k1"
bodies = ["d0", "d2"]
point = ["-21/29", "-20/29"]
normal = ["-21/29", "-20/29"]
restitution = "1"
[[contacts]]
name = "k2"
bodies = ["d1", "d3"]
point = ["12/25", "41/25"]
normal = ["24/25", "7/25"]
restitution = "0"
[impact]
rule = "simultaneous"
"""


def test_energy_created_is_a_warning_in_python_too(tmp_path, capsys):
    import sympy as sp

    import rigidimpact as ri

    [solution] = ri.parse_scene(FOUR_DISCS).outcomes()
    # the kinetic energies before and after, summed here from the bodies
    def kinetic(bodies):
        return sum((b.mass * (b.velocity[0] ** 2 + b.velocity[1] ** 2) + b.inertia
                    * b.spin ** 2) / 2 for b in bodies if b.support != "fixed")

    gained = kinetic(solution.after) - kinetic(solution.before)
    assert gained > 0 and sp.sympify(gained).is_Rational
    assert solution.checks["energy"] == gained
    assert any("kinetic energy is created" in w for w in solution.warnings)
    # every condition the rule imposed holds exactly
    assert all(v == 0 for k, v in solution.checks.items() if k != "energy")
    path = tmp_path / "discs.toml"
    path.write_text(FOUR_DISCS)
    assert main(["evaluate", str(path), "--json"]) == 0
    import json

    data = json.loads(capsys.readouterr().out)
    assert data["checks"]["energy"] == pytest.approx(float(gained))


def test_a_check_that_fails_is_never_an_answer():
    # a Solution whose impulses do not balance the momentum it reports is refused
    from dataclasses import replace

    import rigidimpact as ri
    from rigidimpact.solve.collision import certified

    solution = ri.chain(3).simultaneous()
    wrong = replace(solution, impulses={**solution.impulses, "c0": solution.impulses["c0"]
                                        + 1})
    assert wrong.checks["ball0.momentum_x"] == 1
    with pytest.raises(InputError, match="fails its own check"):
        certified(wrong)


def test_derive_prints_and_gives_each_outcome_checks(tmp_path, capsys):
    import json

    path = tmp_path / "discs.toml"
    path.write_text(FOUR_DISCS)
    assert main(["derive", str(path), "--json"]) == 0
    [outcome] = json.loads(capsys.readouterr().out)["outcomes"]
    assert outcome["checks"]["k0.restitution"] == "0"
    assert outcome["checks"]["energy"] != "0"
    assert any("kinetic energy is created" in w for w in outcome["warnings"])
    assert main(["derive", str(path)]) == 0
    assert "largest residual 0.247 (energy)" in capsys.readouterr().out
