"""The fused kernel: the same numbers as the per-result kernels, chunked, swept."""

from __future__ import annotations

import json

import numpy as np
import pytest

from rigidimpact.analyses.bench import CRADLE_SCENE
from rigidimpact.cli import main
from rigidimpact.errors import InputError
from rigidimpact.paper.problems import derive
from rigidimpact.symbolic.numeric import fused, has_numba, kernels

BACKENDS = ["numpy"] + (["numba"] if has_numba() else [])


def _random_sets(count: int, seed: int = 1) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    return {"M": 10 ** rng.uniform(-6, 6, count), "m": 10 ** rng.uniform(-6, 6, count),
            "L": 10 ** rng.uniform(-3, 3, count), "theta": rng.uniform(0, np.pi, count),
            "e": rng.uniform(0, 1, count), "v_ix": rng.uniform(-2, 2, count)}


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("problem", ["barbell", "sticking", "discs", "two-body"])
def test_fused_agrees_with_each_results_own_kernel(problem, backend):
    # the same stable forms, with shared subexpressions: within a few ulps of the scale
    results = derive(problem).results
    kernel = fused(results, backend, chunk=1000)
    rng = np.random.default_rng(7)
    sets = {n: rng.uniform(0.5, 2.0, 5000) for n in kernel.arguments}
    if "e" in sets:
        sets["e"] = rng.uniform(0, 1, 5000)
    got = kernel(**sets)
    for key, single in kernels(results).items():
        want = np.broadcast_to(single(**{n: sets[n] for n in single.arguments}), (5000,))
        assert np.allclose(got[key], want, rtol=1e-13, atol=1e-15), key


@pytest.mark.parametrize("backend", BACKENDS)
def test_chunks_scalars_and_broadcasting_do_not_change_the_numbers(backend):
    results = derive("barbell").results
    sets = _random_sets(10_000)
    whole = fused(results, backend, chunk=1 << 20)(**sets)
    small = fused(results, backend, chunk=333)(**sets)
    for key in whole:
        assert np.array_equal(whole[key], small[key]), key
    # a single number for an input is the same as an array of it
    point = fused(results, backend)(**(sets | {"L": 2.0, "m": 1.0}))
    spread = fused(results, backend)(**(sets | {"L": np.full(10_000, 2.0),
                                                "m": np.full(10_000, 1.0)}))
    for key in point:
        assert np.array_equal(point[key], spread[key]), key
    grid = fused(results, backend)(theta=np.linspace(0, 3, 7)[:, None],
                                   M=sets["M"][:5][None, :], m=1.0, L=1.0, e=0.5, v_ix=1.0)
    assert grid["V_x"].shape == (7, 5)
    with pytest.raises(InputError, match="do not broadcast"):
        fused(results, backend)(**(sets | {"theta": np.zeros(3)}))


@pytest.mark.parametrize("backend", BACKENDS)
def test_into_given_arrays_gives_the_same_numbers_and_refuses_wrong_ones(backend):
    results = derive("barbell").results
    kernel = fused(results, backend, chunk=999)
    sets = _random_sets(5_000, seed=3)
    buffers = {k: np.full(5_000, np.nan) for k in kernel.keys}
    kernel.into(buffers, **sets)
    fresh = kernel(**sets)
    for key in kernel.keys:
        assert np.array_equal(buffers[key], fresh[key]), key
    # reused: a second call overwrites every element
    kernel.into(buffers, **(sets | {"e": 0.0}))
    again = kernel(**(sets | {"e": 0.0}))
    for key in kernel.keys:
        assert np.array_equal(buffers[key], again[key]), key
    bad = [np.empty(4_999), np.empty(5_000, dtype=np.float32), np.empty((5_000, 2))[:, 0],
           np.empty(5_000).view(), None]
    bad[3].flags.writeable = False
    for wrong in bad:
        with pytest.raises(InputError, match="outputs.v_fx"):
            kernel.into(buffers | {"v_fx": wrong}, **sets)


@pytest.mark.skipif(not has_numba(), reason="numba is not installed")
def test_numba_divides_by_zero_as_numpy_does():
    # massless bodies make the denominator of eq. (5) zero: nan or inf as in NumPy,
    # never an exception from inside the compiled loop
    results = derive("barbell").results
    sets = {"M": np.array([0.0, 0.0, 1.0]), "m": np.array([0.0, 1.0, 1.0]),
            "L": np.array([1.0, 0.0, 1.0]), "theta": np.ones(3), "e": 0.5, "v_ix": 1.0}
    with np.errstate(all="ignore"):
        want = fused(results)(**sets)
    got = fused(results, "numba")(**sets)
    for key in want:
        assert np.array_equal(got[key], want[key], equal_nan=True), key
    assert not np.isfinite(got["V_x"][0]) and not np.isfinite(got["omega_z"][1])


@pytest.mark.parametrize("backend", BACKENDS)
def test_sweep_writes_the_grid_without_building_it(backend, tmp_path):
    # 40 x 30 sets; every value must equal the fused kernel on the materialised grid
    theta, big = np.linspace(0, np.pi / 2, 40), np.linspace(0.1, 10, 30)
    folder = tmp_path / "out"
    argv = ["sweep", "barbell", "--grid", "theta=0:pi/2:40", "--grid", "M=0.1:10:30",
            "--set", "m=1", "--set", "e=1/2", "--set", "v_ix=1", "--set", "L=2",
            "--backend", backend, "--out", str(folder), "--json"]
    assert main(argv) == 0
    T, B = np.meshgrid(theta, big, indexing="ij")
    want = fused(derive("barbell").results)(theta=T, M=B, m=1.0, e=0.5, v_ix=1.0, L=2.0)
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["shape"] == [40, 30] and summary["sets"] == 1200
    for key, values in want.items():
        got = np.load(folder / f"{key}.npy").reshape(40, 30)
        assert np.allclose(got, values, rtol=1e-15, atol=0), key
        assert summary["results"][key]["max"] == pytest.approx(float(values.max()))


def test_sweep_keys_writes_only_the_keys_asked_for(tmp_path, capsys):
    # the energy lost is still evaluated (its statistics and warnings are in the
    # summary) but only V_x is written: a 10^8-set sweep once wrote a second 800 MB file
    folder = tmp_path / "out"
    argv = ["sweep", "barbell", "--grid", "theta=0:pi/2:40", "--set", "M=2", "--set", "m=1",
            "--set", "e=1/2", "--set", "v_ix=1", "--set", "L=2", "--keys", "V_x",
            "--out", str(folder), "--json"]
    assert main(argv) == 0
    capsys.readouterr()
    written = sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))
    assert written == ["V_x.npy", "summary.json", "table.csv"]
    header = (folder / "table.csv").read_text().splitlines()[0]
    assert header == "theta,V_x"  # the table too holds only the keys asked for
    summary = json.loads((folder / "summary.json").read_text())
    assert "energy_loss_fraction" in summary["results"]
    # eq. (7) at theta = 0, m/M = 1/2, e = 1/2: 2M(1 - e^2)/(2M + m) = 3/5 (the least
    # loss is at 90 degrees: (1 - e^2) 2M/(2M + 2m) = 1/2)
    assert summary["results"]["energy_loss_fraction"]["max"] == pytest.approx(0.6)
    assert summary["results"]["energy_loss_fraction"]["min"] == pytest.approx(0.5)


def test_sweep_refuses_bad_grids_in_one_line(tmp_path, capsys):
    base = ["sweep", "barbell", "--set", "m=1", "--set", "v_ix=1", "--set", "L=1",
            "--set", "theta=0", "--out", str(tmp_path / "x")]
    for grid, words in ((["--grid", "e=0:2:10", "--set", "M=1"], "must lie in [0, 1]"),
                        (["--grid", "e=0:1"], "NAME=START:STOP:COUNT"),
                        (["--grid", "M=1:2:ten", "--set", "e=0"], "whole number"),
                        (["--grid", "q=1:2:3", "--set", "e=0", "--set", "M=1"], "not a symbol"),
                        (["--set", "e=0"], "needs values for: M")):
        assert main(base + grid) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and words in err, (grid, err)
        assert not (tmp_path / "x").exists()


def test_numba_missing_is_one_line(monkeypatch):
    import builtins

    real = builtins.__import__

    def no_numba(name, *args, **kwargs):
        if name == "numba":
            raise ImportError("no numba")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_numba)
    with pytest.raises(InputError, match="numba is not installed"):
        fused(derive("discs").results, "numba")


def test_a_sweep_on_dask_writes_the_one_process_numbers(tmp_path, monkeypatch):
    # blocks of sets as Dask tasks (made small here so that 1,200 sets make five), each
    # in the kernel's own chunks: every number equals the one-process sweep's, bit for bit
    pytest.importorskip("dask.distributed")
    import rigidimpact.outputs.sweep as sweep_module
    from rigidimpact.outputs.sweep import run_sweep

    monkeypatch.setattr(sweep_module, "BLOCK", 256)
    results = derive("barbell").results
    grid = {"theta": np.linspace(0, np.pi / 2, 40), "M": np.linspace(0.1, 10, 30)}
    fixed = {"m": 1.0, "e": 0.5, "v_ix": 1.0, "L": 2.0}
    monkeypatch.setattr(sweep_module, "fused", lambda r, b: fused(r, b, chunk=64))
    alone = run_sweep(results, grid, fixed, tmp_path / "alone")
    # local workers started for a test's few sets too
    monkeypatch.setattr("rigidimpact.outputs.workers.REPAYS",
                        {"draws": 0, "sets": 0, "solves": 0})
    spread = run_sweep(results, grid, fixed, tmp_path / "dask", workers=2, processes=False)
    assert alone["results"] == spread["results"] and "workers" not in spread
    for key in results:
        a = np.load(tmp_path / "alone" / f"{key}.npy")
        b = np.load(tmp_path / "dask" / f"{key}.npy")
        assert np.array_equal(a, b, equal_nan=True), key


def test_a_sweep_of_compliant_runs_set_by_set_and_on_dask(tmp_path, monkeypatch, capsys):
    # a scene with no closed form (the compliant rule) is solved set by set; on Dask
    # (threads here, to start fast) the numbers are the same, and each equals what
    # evaluate gives at that set
    pytest.importorskip("dask.distributed")
    import rigidimpact.outputs.sweep as sweep_module
    from rigidimpact.outputs.sweep import run_point_sweep

    monkeypatch.setattr(sweep_module, "POINTS", 3)
    scene = tmp_path / "cradle.toml"
    scene.write_text(CRADLE_SCENE)
    grid = {"e": np.linspace(0.5, 1.0, 7)}
    alone = run_point_sweep(str(scene), grid, {}, tmp_path / "alone")
    monkeypatch.setattr("rigidimpact.outputs.workers.REPAYS",
                        {"draws": 0, "sets": 0, "solves": 0})
    spread = run_point_sweep(str(scene), grid, {}, tmp_path / "dask", workers=2,
                             processes=False)
    assert alone["results"] == spread["results"] and alone["sets"] == 7
    last = np.load(tmp_path / "dask" / "last.vx.npy")
    assert np.array_equal(np.load(tmp_path / "alone" / "last.vx.npy"), last)
    for k in (0, 6):
        assert main(["evaluate", str(scene), "--set", f"e={float(grid['e'][k])!r}", "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["last.vx"] == last[k]
    assert main(["sweep", str(scene), "--grid", "e=0.5:1:3", "--keys", "last.vx",
                 "--out", str(tmp_path / "keys")]) != 0
    assert "solved set by set" in capsys.readouterr().err


def test_a_sweep_steps_aside_from_local_workers_its_sets_cannot_repay(tmp_path, capsys):
    # the rule counts work: 10 sets of a closed form and 3 solves are far fewer than
    # what repays starting local workers (outputs/workers.py, REPAYS), so --workers 2
    # runs in this process, says so on the standard error and in the summary, and
    # writes the numbers the one-process sweep writes
    settings = ["--set", "m=1", "--set", "M=2", "--set", "L=1", "--set", "e=0.5",
                "--set", "v_ix=1"]
    assert main(["sweep", "barbell", "--grid", "theta=0:1.5:10", *settings,
                 "--workers", "2", "--out", str(tmp_path / "stepped"), "--json"]) == 0
    captured = capsys.readouterr()
    assert json.loads(captured.out)["workers"].startswith("--workers 2: 10 sets are fewer")
    assert "rigidimpact: note: --workers 2: 10 sets" in captured.err
    assert main(["sweep", "barbell", "--grid", "theta=0:1.5:10", *settings,
                 "--out", str(tmp_path / "alone"), "--json"]) == 0
    assert "workers" not in json.loads(capsys.readouterr().out)
    for key in ("v_fx", "V_x", "omega_z"):
        assert np.array_equal(np.load(tmp_path / "stepped" / f"{key}.npy"),
                              np.load(tmp_path / "alone" / f"{key}.npy"), equal_nan=True)
    scene = tmp_path / "cradle.toml"
    scene.write_text(CRADLE_SCENE)
    assert main(["sweep", str(scene), "--grid", "e=0.5:1:3", "--workers", "2",
                 "--out", str(tmp_path / "solves"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["workers"].startswith(
        "--workers 2: 3 solves are fewer")
