"""Every scene shipped in derivations/ gives the results it gave before the core was
redesigned (issue: one core for one contact and many).

The files under tests/golden/scenes were written by ``derive --json`` and ``evaluate
--json`` of the release before the redesign, so they pin behaviour, not correctness
(correctness is checked against the paper, hand derivations and laws elsewhere). A
result may change form, never value: symbolic results must differ by exactly zero,
numbers by nothing beyond float64 rounding, and every key must still be printed."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import sympy as sp

from rigidimpact.cli import main

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = ROOT / "tests" / "golden" / "scenes"
SCENES = sorted(p.stem for p in (ROOT / "derivations").glob("*.toml"))


def _same(old: str, new: str) -> bool:
    """Two sympy strings name the same expression (exactly: their difference is zero)."""
    if old == new:
        return True
    a, b = sp.sympify(old), sp.sympify(new)
    if isinstance(a, sp.Piecewise) or isinstance(b, sp.Piecewise):
        return sp.piecewise_fold(a - b).simplify() == 0
    return sp.simplify(a - b) == 0


def _run(argv: list[str], capsys) -> dict:
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_every_shipped_scene_is_pinned():
    assert SCENES and all((GOLDEN / f"{n}.derive.json").exists() for n in SCENES)


@pytest.mark.parametrize("name", SCENES)
def test_derive_gives_the_pinned_results(name, capsys):
    old = json.loads((GOLDEN / f"{name}.derive.json").read_text())
    new = _run(["derive", str(ROOT / "derivations" / f"{name}.toml"), "--json"], capsys)
    assert set(old["results"]) <= set(new["results"])
    for key, value in old["results"].items():
        assert _same(value["sympy"], new["results"][key]["sympy"]), key
    assert [r["name"] for r in old.get("regimes", [])] == \
        [r["name"] for r in new.get("regimes", [])]


@pytest.mark.parametrize("name", SCENES)
def test_evaluate_gives_the_pinned_numbers(name, capsys):
    old = json.loads((GOLDEN / f"{name}.evaluate.json").read_text())
    new = _run(["evaluate", str(ROOT / "derivations" / f"{name}.toml"), "--json"], capsys)
    assert set(old) <= set(new)
    for key, value in old.items():
        if isinstance(value, float):
            assert new[key] == pytest.approx(value, rel=1e-13, abs=1e-15), key
        else:
            assert new[key] == value, key
