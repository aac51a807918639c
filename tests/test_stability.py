"""The hard-case suite: float64 within a few ulps of 50-digit references."""

from __future__ import annotations

import json

import pytest

from rigidimpact.analyses.stability import BOUND, run_suite
from rigidimpact.cli import main

# quantities whose exact value has no cancellation: bounded relative to their own value
WELL_CONDITIONED = {("barbell", "V_x"), ("barbell", "omega_z"), ("barbell", "f"),
                    ("barbell", "energy_loss_fraction"), ("sticking", "u_x"),
                    ("sticking", "omega_z"), ("sticking", "h"), ("disc-rod.toml", "rod.vx"),
                    ("disc-rod.toml", "rod.omega"), ("disc-rod.toml", "impulse"),
                    ("disc-rod.toml", "energy_loss_fraction"), ("two-body", "omega_2fz"),
                    ("sticking.toml", "impulse"), ("sticking.toml", "barbell.omega")}


@pytest.fixture(scope="module")
def report():
    return run_suite()


def test_every_quantity_is_within_the_bound_of_its_magnitude(report):
    failing = [(r["problem"], r["quantity"], r["scaled_error"]) for r in report["rows"]
               if r["scaled_error"] > BOUND]
    assert failing == []
    assert report["worst"]["rel_error"] <= BOUND


def test_stability_json(report, capsys):
    # the command line's report is the suite's (here in this file, where the process has
    # already run the suite once: the command reads the same report)
    assert main(["stability", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {"cases", "worst", "rows"} <= set(data)
    assert {"quantity", "rel_error"} <= set(data["worst"])
    assert data["worst"]["rel_error"] <= 1e-13
    assert data["cases"] == report["cases"] and len(data["rows"]) == len(report["rows"])


def test_quantities_without_cancellation_are_relatively_accurate(report):
    rows = {(r["problem"], r["quantity"]): r for r in report["rows"]}
    assert WELL_CONDITIONED <= set(rows)
    for key in WELL_CONDITIONED:
        assert rows[key]["rel_error"] <= BOUND, key


def test_v_fx_at_e_zero_is_relatively_accurate():
    import itertools

    import mpmath

    from rigidimpact.analyses.stability import ANGLES, LENGTHS, RATIOS
    from rigidimpact.paper.problems import derive
    from rigidimpact.symbolic.numeric import Kernel

    kernel = Kernel.from_expr(derive("barbell").results["v_fx"])
    for M, L, theta in itertools.product(RATIOS, LENGTHS, ANGLES):
        values = {"m": 1.0, "M": M, "L": L, "theta": theta, "e": 0.0, "v_ix": 1.0}
        exact = kernel.reference(50, **values)
        with mpmath.workdps(50):
            assert abs(mpmath.mpf(float(kernel(**values))) - exact) / abs(exact) <= BOUND


def test_the_suite_covers_the_extremes(report):
    assert report["cases"] > 5000
    barbell = next(r for r in report["rows"] if r["problem"] == "barbell")
    assert barbell["cases"] >= 1000


def test_every_backend_is_checked_and_passes(report):
    from rigidimpact.analyses.stability import available_backends

    assert report["backends"] == list(available_backends())
    for row in report["rows"]:
        assert set(row["by_backend"]) == set(report["backends"])
        for backend, errors in row["by_backend"].items():
            assert errors["scaled_error"] <= BOUND, (row["problem"], row["quantity"], backend)


def test_the_notebooks_snapshot_matches_a_fresh_run(report):
    # notebook 9 shows notebooks/data/stability.json instead of running the whole suite a
    # second time; it must still describe the suite as it is
    import json
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "notebooks" / "data" / "stability.json"
    stored = json.loads(path.read_text())
    assert stored["cases"] == report["cases"] and stored["bound"] == report["bound"]
    assert [(r["problem"], r["quantity"], r["cases"]) for r in stored["rows"]] == [
        (r["problem"], r["quantity"], r["cases"]) for r in report["rows"]]
    assert all(r["passed"] for r in stored["rows"])
    assert stored["worst"]["rel_error"] <= BOUND
