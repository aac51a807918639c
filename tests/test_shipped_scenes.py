"""Every scene shipped in derivations/ gives the results it gave before the core was
redesigned (issue: one core for one contact and many).

The files under tests/golden/scenes were written by ``derive --json`` and ``evaluate
--json`` of the release before the redesign, so they pin behaviour, not correctness
(correctness is checked against the paper, hand derivations and laws elsewhere). A
result may change form, never value: symbolic results must differ by exactly zero,
numbers by nothing beyond float64 rounding (an integrated number: beyond the
integrator's stated tolerance), and every key must still be printed."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import sympy as sp

from rigidimpact.cli import main

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = ROOT / "tests" / "golden" / "scenes"
SCENES = sorted(p.stem for p in (ROOT / "derivations").glob("*.toml"))


# the accuracy an integrated answer states for itself: its certificate's tolerance,
# 1000 times the integrator's relative step tolerance of 1e-10 (laws.cone.TOLERANCE,
# laws.together.TOLERANCE, the scenes' [impact] tolerance), relative to the answer's
# unit scale. A number the integrator made is pinned to that, not to its last bits,
# which differ between machines of one kind (vector units, BLAS kernels) and grow
# along the integration (the cushion's spin differs by 1.2e-9 between two machines)
INTEGRATED = 1e-7


# the scenes' symbols that sympy would read as its own functions (beta, gamma)
NAMES = {name: sp.Symbol(name) for name in ("beta", "gamma")}


def _parse(text: str) -> sp.Expr:
    return sp.sympify(text, locals=NAMES)


def _same(old: str, new: str) -> bool:
    """Two sympy strings name the same expression: exactly (their difference is zero),
    or, for a number the integrator made (a Float), to the integrator's tolerance."""
    if old == new:
        return True
    a, b = _parse(old), _parse(new)
    if a.is_number and b.is_number and (a.has(sp.Float) or b.has(sp.Float)):
        return bool(abs(a - b) <= INTEGRATED * max(abs(a), abs(b), 1))
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


def _integrated(name: str) -> bool:
    """Whether a shipped scene's results come from an integration (floats in its exact
    results)."""
    old = json.loads((GOLDEN / f"{name}.derive.json").read_text())
    return any(_parse(v["sympy"]).has(sp.Float) for v in old["results"].values())


@pytest.mark.parametrize("name", SCENES)
def test_evaluate_gives_the_pinned_numbers(name, capsys):
    old = json.loads((GOLDEN / f"{name}.evaluate.json").read_text())
    new = _run(["evaluate", str(ROOT / "derivations" / f"{name}.toml"), "--json"], capsys)
    assert set(old) <= set(new)
    integrated = _integrated(name)
    for key, value in old.items():
        if isinstance(value, float):
            rel, near = (INTEGRATED, INTEGRATED) if integrated else (1e-13, 1e-15)
            assert new[key] == pytest.approx(value, rel=rel, abs=near), key
        elif isinstance(value, dict):  # the certificate: new checks may be added
            # a residual is zero, or rounding of the arithmetic that computed it (50
            # digits, more where the data span orders of magnitude): pinned to its size
            got = {k: new[key].get(k) for k in value}
            assert got == pytest.approx(value, abs=INTEGRATED if integrated else 1e-40), key
        elif integrated and key == "notes":  # the adaptive integrator's step count
            assert [_steps(n) for n in new[key]] == [_steps(n) for n in value], key
        else:
            assert new[key] == value, key


def _steps(note: str) -> str:
    """A note with its count of integration steps left out (rounding moves it by one)."""
    return re.sub(r"\(\d+ steps\)", "(N steps)", note)
