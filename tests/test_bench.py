"""The bench's machinery (not its timings): rows, fronts, the automatic choice, outputs."""

from __future__ import annotations

import json
import math

import mpmath
import pytest

from rigidimpact.analyses import bench, restrike
from rigidimpact.cli import main
from rigidimpact.outputs.workers import REPAYS


def test_pareto_keeps_only_unbeaten_rows():
    rows = [bench._row("a", "slow and rough", 1e-3, 2.0), bench._row("a", "fast", 1e-3, 1.0),
            bench._row("b", "fine", 1e-9, 3.0), bench._row("b", "exact", 0.0, 5.0),
            bench._row("b", "dominated", 1e-6, 4.0)]
    assert [r["setting"] for r in bench.pareto(rows)] == ["fast", "fine", "exact"]


def test_auto_choice_compares_with_the_cheapest_setting_that_meets_the_tolerance():
    rows = [bench._row("integration", "x", 1e-5, 1.0, tolerance=1e-4),
            bench._row("integration", "y", 1e-7, 2.0, tolerance=1e-8),
            bench._row("integration", "z", 1e-9, 3.0, tolerance=1e-8),
            bench._row("integration", "auto", 5e-7, 2.5, tolerance=1e-6, auto=True)]
    choice = bench.auto_choice(rows)
    assert choice["meets_tolerance"] and choice["cheapest"] == "y"
    assert math.isclose(choice["cost_ratio"], 1.25)


def test_fixed_step_marching_converges_to_the_exact_restrike_turn():
    angle = math.radians(10.0)
    exact = float(restrike.restrike_turn(mpmath.radians(10), 0, 1))
    errors = [abs(bench._fixed_step_turn(angle, h) - exact) for h in (1e-2, 1e-3)]
    assert errors[1] < errors[0] / 10  # linear interpolation: second order in h


def test_restrike_event_row_is_accurate():
    [row] = bench._restrike_event(repeats=1)
    assert row["error"] < 1e-13 and row["problem"] == "restrike"


def test_throughput_kernel_and_numpy_agree():
    result = bench.throughput(count=2000, repeats=1)
    assert result["max_difference"] < 1e-14
    assert result["kernel_per_s"] > 0 and result["numpy_per_s"] > 0


def test_exact_families_have_the_accuracy_of_their_arithmetic():
    report = bench.run_bench(quick=True, families=("symbolic", "float64", "mpmath"))
    by_setting = {(r["method"], r["setting"]): r["error"] for r in report["rows"]}
    assert by_setting[("mpmath", "dps=30")] < 1e-28
    assert by_setting[("mpmath", "dps=50")] < 1e-48
    assert by_setting[("float64", "stable-form kernel, one point")] < 1e-15
    assert by_setting[("symbolic", "exact, then 17 digits")] < 1e-16


def test_pymunk_row_when_installed():
    pytest.importorskip("pymunk")
    [row] = bench._pymunk(bench._exact(), repeats=1, steps=(1e-4,))
    assert row["method"] == "pymunk" and row["error"] < 1e-6


def test_unknown_family_is_refused():
    with pytest.raises(ValueError, match="unknown"):
        bench.run_bench(families=("magic",))


def test_bench_cli_writes_its_three_files(tmp_path, capsys):
    # two families make every part of the report (the rows, the kernels' throughput,
    # the automatic pick against the integrations); the whole quick bench is the slow
    # tier's (below)
    out = tmp_path / "bench"
    assert main(["bench", "--quick", "--family", "float64", "--family", "integration",
                 "--out", str(out), "--json"]) == 0
    _three_files(out, json.loads(capsys.readouterr().out))


@pytest.mark.slow
def test_the_whole_quick_bench_writes_its_three_files(tmp_path, capsys):
    out = tmp_path / "bench"
    assert main(["bench", "--quick", "--out", str(out), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    _three_files(out, data)
    assert {"ladder", "verify_vs_plain", "start_vs_sympy", "contacts"} <= set(data)
    start = data["start_vs_sympy"]
    assert start["derive_ratio"] == start["derive_barbell_s"] / start["import_sympy_s"]
    assert start["derive_ratio_same_collector"] == (start["derive_barbell_s"]
                                                    / start["import_sympy_same_collector_s"])


def _three_files(out, data):
    assert {"rows", "throughput"} <= set(data)
    assert all({"method", "setting", "error", "seconds"} <= set(r) for r in data["rows"])
    assert {"kernel_per_s", "numpy_per_s"} <= set(data["throughput"])
    assert data["auto_choice"]["meets_tolerance"]
    assert json.loads((out / "bench.json").read_text())["rows"]
    assert "| problem | method |" in (out / "bench.md").read_text()
    # the report ends with what the bench itself took
    assert data["seconds"] > 0 and \
        f"took {data['seconds']:.0f} s." in (out / "bench.md").read_text()
    assert (out / "accuracy-vs-time.png").read_bytes()[:4] == b"\x89PNG"


def test_sweep_row_is_accurate_and_reports_time_per_angle():
    [row] = bench._restrike_sweep(repeats=1, count=2000)
    assert row["error"] < 1e-13 and row["problem"] == "restrike"
    assert math.isclose(row["seconds"] * 2000, row["total_seconds"])


def test_fixed_step_marching_stops_at_the_crossing_across_blocks():
    angle = math.radians(10.0)
    small_blocks = bench._fixed_step_turn(angle, 1e-3, block=64)
    assert small_blocks == bench._fixed_step_turn(angle, 1e-3)
    with pytest.raises(ArithmeticError):
        bench._fixed_step_turn(math.radians(30.0), 1e-2)  # above theta_c: no re-strike


def test_the_dask_bench_asks_for_work_that_starts_local_workers():
    # below what repays starting local workers, --workers 2 would run in one process:
    # the bench would time one process twice and call it Dask
    with pytest.raises(ValueError, match=f"local workers start for {REPAYS['solves']} "):
        bench.dask_against_one(1, REPAYS["solves"] - 1)
    with pytest.raises(ValueError, match=f"local workers start for {REPAYS['draws']} "):
        bench.dask_draws_against_one(1, 10**6)


@pytest.mark.slow
def test_the_dask_bench_times_three_ways_with_the_same_numbers():
    # one process, two Dask workers, and two plain processes each sweeping half: the
    # bench itself raises if the two-worker sweep's numbers differ from one process's
    pytest.importorskip("dask.distributed")
    found = bench.dask_against_one(1)
    assert found["solves"] == 1000
    assert min(found["one_process_s"], found["two_workers_s"],
               found["two_processes_apart_s"]) > 0
    assert found["dask_gain"] == found["one_process_s"] / found["two_workers_s"]
    assert found["two_core_limit"] == found["one_process_s"] / found["two_processes_apart_s"]


@pytest.mark.slow
def test_the_dask_draws_bench_times_three_ways_with_the_same_numbers():
    # one process, two Dask workers, and two plain processes each drawing half the
    # chunks: the bench raises if the two-worker Monte Carlo differs from one process's
    # by a bit, or the halves' sums added in order give another mean
    pytest.importorskip("dask.distributed")
    found = bench.dask_draws_against_one(1, 2 * 10**8)
    assert found["samples"] == 2e8
    assert min(found["one_process_s"], found["two_workers_s"],
               found["two_processes_apart_s"]) > 0
    assert found["dask_gain"] == found["one_process_s"] / found["two_workers_s"]
    assert found["two_core_limit"] == found["one_process_s"] / found["two_processes_apart_s"]
