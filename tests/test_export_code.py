"""The derivation as code: each language's export compiled (or interpreted) here and run
at seeded points, against the numbers of ``rigidimpact evaluate`` to 1e-12 relative.

A language whose compiler or interpreter is missing skips with the reason (CI installs
them: .ci/run). The default tier runs a representative (the barbell in every language,
a frictional scene's cases in C and JavaScript); the slow tier runs every shipped scene
with a closed form in C and JavaScript, and the built-in problems in every language.
"""

from __future__ import annotations

import glob
import shutil
from pathlib import Path

import pytest

from helpers import agreement, export_reference, refused, run_export, seeded_points
from rigidimpact.outputs.code import BUILD, LANGUAGES, program_of, to_code

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted(Path(p).name for p in glob.glob(str(ROOT / "derivations" / "*.toml")))
BUILTIN = ["barbell", "sticking", "discs", "two-body"]
# a scene whose evaluate solves at each point's numbers (friction, 3-D) costs about a
# second a point: fewer points there
SOLVED_AT_NUMBERS = {"rod-rough-floor.toml", "sphere-oblique-flat.toml",
                     "spinning-ball-bounces.toml", "spinning-ball-floor.toml",
                     "superball-under-table.toml"}


def _tool(lang: str) -> None:
    tool = BUILD[lang]["tool"]
    if shutil.which(tool) is None:
        pytest.skip(f"{tool} is not installed (Debian: apt-get install "
                    f"{BUILD[lang]['debian']}); CI installs it")


def _target(name: str) -> str:
    return name if name in BUILTIN else str(ROOT / "derivations" / name)


def check(name: str, lang: str, count: int, tmp_path: Path, seed: int = 69) -> float:
    """The largest relative error of `lang`'s export against evaluate over `count`
    seeded points (every output, the regime's name too where exported)."""
    _tool(lang)
    target = _target(name)
    program = program_of(target)
    points = seeded_points(program, count, seed, export_reference(target))
    assert len(points) == (count if program.names else 1), "too few points evaluate accepts"
    rows = run_export(lang, to_code(program, lang), [p for p, _, _ in points], tmp_path)
    assert len(rows) == len(points)
    worst = 0.0
    for key in program.outputs:
        scale = max(abs(numbers[key]) for _, numbers, _ in points)
        for (point, numbers, _), row in zip(points, rows, strict=True):
            error = agreement(row[key], numbers[key], scale)
            assert error <= 1e-12, (key, point, row[key], numbers[key])
            worst = max(worst, error)
    if program.regime is not None:
        for (point, _, regime), row in zip(points, rows, strict=True):
            assert row.get("regime") == regime, (point, row.get("regime"), regime)
    for (_, numbers, _), row in zip(points, rows, strict=True):
        assert set(row) - {"regime"} == set(numbers), "the keys differ from evaluate's"
    return worst


@pytest.mark.parametrize("lang", LANGUAGES)
def test_the_barbell_in_every_language_agrees_with_evaluate(lang, tmp_path):
    assert check("barbell", lang, 1000, tmp_path) <= 1e-12


@pytest.mark.parametrize("lang", ["c", "js"])
def test_a_frictional_course_and_its_regime_agree_with_evaluate(lang, tmp_path):
    # Routh's courses: a Piecewise whose conditions are code, the regime's name too
    assert check("rod-rough-floor.toml", lang, 40, tmp_path) <= 1e-12


@pytest.mark.parametrize("lang", ["c", "js"])
def test_several_contacts_are_their_numbers_at_the_scene_values(lang, tmp_path):
    assert check("two-ball-drop.toml", lang, 1, tmp_path) <= 1e-12
    assert "no closed form" in to_code(_target("two-ball-drop.toml"), lang)


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["c", "js"])
@pytest.mark.parametrize("name", BUILTIN + SCENES)
def test_every_shipped_scene_agrees_with_evaluate(name, lang, tmp_path):
    count = 100 if name in SOLVED_AT_NUMBERS else 1000
    assert check(name, lang, count, tmp_path) <= 1e-12


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["fortran", "rust", "octave"])
@pytest.mark.parametrize("name", BUILTIN + ["rod-rough-floor.toml", "discs.toml"])
def test_the_other_languages_agree_with_evaluate(name, lang, tmp_path):
    count = 100 if name in SOLVED_AT_NUMBERS else 1000
    assert check(name, lang, count, tmp_path) <= 1e-12


def test_the_rationals_stay_exact_and_the_roots_computed():
    c = to_code(_target("rod-rough-floor.toml"), "c")
    body = c[c.index("int rod_rough_floor("):]
    assert "3.0/5.0" in body  # Routh's threshold mu = 3/5, as a division of exact literals
    assert "M_SQRT2" in body and "1.4142" not in body
    rust = to_code(_target("rod-rough-floor.toml"), "rust")
    assert "sqrt()" in rust and "1.4142" not in rust


@pytest.mark.parametrize("lang", ["c", "js"])
def test_the_main_refuses_bad_values_in_one_line(lang, tmp_path):
    import subprocess

    _tool(lang)
    text = to_code("barbell", lang)
    run_export(lang, text, [{}], tmp_path)  # builds it; the defaults run
    exe = [x.format(src=tmp_path / f"program{'.c' if lang == 'c' else '.js'}",
                    exe=tmp_path / "program") for x in BUILD[lang]["run"]]
    for args, needle in ((["x=1"], "unknown symbol 'x'"), (["e=2"], "restitution"),
                         (["e=abc"], "must be a finite number"), (["e"], "name=value"),
                         (["v_ix=-1"], "")):
        done = subprocess.run(exe + args, capture_output=True, text=True)
        assert done.returncode == 2 and done.stdout.strip() == ""
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and needle in lines[0], done.stderr


def test_export_to_an_unknown_language_is_one_line(capsys, tmp_path):
    refused(capsys, ["export", "barbell", "--to", "cobol", "--out", str(tmp_path / "x")],
            "unknown language 'cobol'")
    assert not list(tmp_path.iterdir())


def test_export_writes_the_file_and_python_gives_the_same(tmp_path, capsys):
    import rigidimpact as ri
    from rigidimpact.cli import main

    out = tmp_path / "barbell.c"
    assert main(["export", "barbell", "--to", "c", "--out", str(out)]) == 0
    assert out.read_text() == ri.to_code("barbell", "c") == ri.to_code(ri.derive("barbell"), "c")
    assert capsys.readouterr().out.strip() == str(out)


def test_the_guide_shows_what_the_c_program_prints(tmp_path):
    # the C program of the guide's first example, built and run as the guide shows
    import re

    page = (ROOT / "docs" / "guide" / "export-code.md").read_text()
    shown = re.search(r"\./barbell e=0\.5 theta=0\.5\n```\n\n```text\n(.*?)```", page, re.S)
    assert shown is not None
    _tool("c")
    [row] = run_export("c", to_code("barbell", "c"), [{"e": 0.5, "theta": 0.5}], tmp_path)
    assert "".join(f"{k} = {v!r}\n" for k, v in row.items()) != ""  # parsed
    import subprocess

    done = subprocess.run([str(tmp_path / "program"), "e=0.5", "theta=0.5"],
                          capture_output=True, text=True)
    assert done.stdout == shown.group(1)
