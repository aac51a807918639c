"""The command line, in process through main(argv)."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pytest

from rigidimpact.cli import main

DERIVATIONS = Path(__file__).resolve().parent.parent / "derivations"
KEYS = {
    "barbell": {"v_fx", "V_x", "omega_z", "f", "energy_loss_fraction"},
    "sticking": {"u_x", "omega_z", "h"},
    "discs": {"V_1fx", "V_2fx"},
    "two-body": {"V_1fx", "V_1fy", "omega_1fz", "V_2fx", "V_2fy", "omega_2fz"},
}
KEYS_ORDER = ["v_fx", "V_x", "omega_z", "f", "energy_loss_fraction"]
SYMBOLS = {
    "barbell": {"m", "M", "L", "theta", "e", "v_ix"},
    "sticking": {"m", "M", "L", "theta", "v_ix"},
    "discs": {"V_1ix", "V_2ix", "e"},
    "two-body": {"m_1", "m_2", "I_1", "I_2", "R_1x", "R_1y", "R_2x", "R_2y", "V_1ix",
                 "V_1iy", "omega_1iz", "V_2ix", "V_2iy", "omega_2iz", "e"},
}


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("name", sorted(KEYS))
def test_derive_json_follows_the_contract(capsys, name):
    import sympy as sp

    data = _json(capsys, ["derive", name, "--json"])
    assert data["problem"] == name
    assert all({"label", "paper", "sympy", "latex"} <= set(eq) for eq in data["equations"])
    assert KEYS[name] <= set(data["results"])
    for key in KEYS[name]:
        entry = data["results"][key]
        # the sympy string is over the problem's own symbol names (parsed by the test,
        # never by the tool)
        names = {s.name for s in sp.sympify(entry["sympy"]).free_symbols}
        assert names <= SYMBOLS[name], (key, names)
        assert entry["latex"]


def test_verify_json(capsys):
    data = _json(capsys, ["verify", "--json"])
    assert data["failed"] == 0 and data["passed"] == len(data["checks"])
    assert all({"id", "paper", "status"} <= set(c) for c in data["checks"])


def test_derive_a_scene_file(capsys):
    data = _json(capsys, ["derive", str(DERIVATIONS / "disc-rod.toml"), "--json"])
    assert {"disc.vx", "disc.vy", "disc.omega", "rod.vx", "rod.omega", "impulse",
            "energy_loss_fraction"} <= set(data["results"])


def test_derive_latex_format(capsys):
    assert main(["derive", "barbell", "--format", "latex"]) == 0
    assert r"\begin{equation}" in capsys.readouterr().out


def test_export_json_lists_the_files(tmp_path, capsys):
    files = _json(capsys, ["export", "discs", "--out", str(tmp_path), "--json"])
    assert all(Path(f).exists() for f in files)


@pytest.mark.parametrize(("argv", "needle"), [
    (["derive", "nonsense"], "unknown problem"),
    (["derive", "missing.toml"], "cannot read"),
    (["frobnicate"], "invalid choice"),
])
def test_bad_input_is_one_line_and_status_2(capsys, argv, needle):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1 and "Traceback" not in err


def test_bad_scene_is_one_line_and_status_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text((DERIVATIONS / "barbell.toml").read_text().replace(
        'mass = "m"', 'mass = "__import__(\'os\')"'))
    assert main(["derive", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("rigidimpact: error: bodies[0].mass:") and err.count("\n") == 1


def test_evaluate_json_matches_hand_computed_values(capsys):
    # theta = 30 deg, m = 1, M = 2, e = 1/2: f = 1.5/5.25 = 2/7, v_fx = -1/7 (by hand)
    data = _json(capsys, ["evaluate", "barbell", "--set", "m=1", "--set", "M=2", "--set",
                          "L=1", "--set", "theta=30 deg", "--set", "e=0.5", "--set",
                          "v_ix=1", "--json"])
    assert abs(data["f"] - 2 / 7) < 1e-15 and abs(data["v_fx"] + 1 / 7) < 1e-15


def test_evaluate_uses_a_scene_values(capsys):
    data = _json(capsys, ["evaluate", str(DERIVATIONS / "discs.toml"), "--json"])
    assert abs(data["disc1.vx"]) < 1e-15  # elastic, equal discs: the striker stops along x


@pytest.mark.parametrize(("argv", "needle"), [
    (["evaluate", "barbell", "--set", "m=1"], "needs values for"),
    (["evaluate", "barbell", "--set", "m=inf"], "must be finite"),
    (["evaluate", "barbell", "--set", "q=1"], "not a symbol"),
    (["evaluate", "barbell", "--set", "e=1.5"], "[0, 1]"),
    (["evaluate", "barbell", "--set", "m"], "NAME=VALUE"),
    (["evaluate", "discs", "--set", "V_1ix=0", "--set", "V_2ix=1", "--set", "e=1",
      "--set", "V_1iy=0", "--set", "V_2iy=0"], "not approaching"),
])
def test_evaluate_refuses_bad_values(capsys, argv, needle):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_critical_angle_json_prints_theta_c_to_30_digits(capsys):
    import mpmath

    assert main(["critical-angle", "--json"]) == 0
    text = capsys.readouterr().out
    data = json.loads(text)
    assert {"theta_c_deg", "theta_c_rad", "equation", "windows_deg"} <= set(data)
    assert data["equation"]["sympy"] == "Eq(tan(theta), 1/(pi - theta))"
    # every printed digit is right: compare the literal with the paper's equation solved here
    literal = text.split('"theta_c_deg": ')[1].split(",")[0]
    with mpmath.workdps(60):
        root = mpmath.findroot(lambda x: mpmath.tan(x) - 1 / (mpmath.pi - x), 0.3)
        assert len(literal.replace(".", "")) >= 30
        assert literal == mpmath.nstr(root * 180 / mpmath.pi, 30)
    assert data["windows_deg"][0][0] == 0 and len(data["windows_deg"]) == 1


def test_critical_angle_with_e_and_mass_ratio(capsys):
    data = _json(capsys, ["critical-angle", "--e", "0.3", "--mass-ratio", "1", "--json"])
    assert len(data["windows_deg"]) == 2
    assert data["edges"][0][0]["kind"] == "at rest"
    assert "asin" in data["edges"][0][0]["equation"]["sympy"]


@pytest.mark.parametrize("argv, field", [(["--e", "1.2"], "e"), (["--mass-ratio", "0"], "mass"),
                                         (["--e", "x"], "--e")])
def test_critical_angle_rejects_bad_parameters(capsys, argv, field):
    assert main(["critical-angle", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and field in err


def test_simulate_restrike_scene_reports_the_event(capsys):
    data = _json(capsys, ["simulate", str(DERIVATIONS / "restrike.toml"), "--json"])
    assert {"effects", "not_simulated", "final", "events", "cost"} <= set(data)
    kinds = [event["kind"] for event in data["events"]]
    assert kinds == ["impact", "restrike", "end"]
    assert data["events"][1]["part"] == "rod"
    assert data["cost"]["ode_steps"] == 0
    assert data["final"]["t"] == data["events"][1]["t"]


def test_simulate_explain_prints_the_plan(capsys):
    assert main(["simulate", str(DERIVATIONS / "restrike.toml"), "--explain"]) == 0
    out = capsys.readouterr().out
    assert "free-flight" in out and "left out: rod-compliance" in out


def test_simulate_bad_table_is_one_line(tmp_path, capsys):
    scene = (DERIVATIONS / "restrike.toml").read_text().replace('until = "restrike"',
                                                              'until = "never"')
    path = tmp_path / "bad.toml"
    path.write_text(scene)
    assert main(["simulate", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "simulate.until" in err


def test_simulate_plot_of_a_rigid_run_and_a_bad_plot_name(tmp_path, capsys):
    path = tmp_path / "restrike.png"
    assert main(["simulate", str(DERIVATIONS / "restrike.toml"), "--plot", str(path)]) == 0
    assert path.read_bytes()[:4] == b"\x89PNG"
    assert main(["simulate", str(DERIVATIONS / "restrike.toml"), "--plot",
                 str(tmp_path / "x.pdf")]) == 2
    assert "--plot" in capsys.readouterr().err
    assert not (tmp_path / "x.pdf").exists()


def test_simulate_animates_the_restrike_to_a_gif(tmp_path, capsys):
    from PIL import Image

    movie = tmp_path / "restrike.gif"
    scene = str(Path(__file__).resolve().parents[1] / "derivations" / "restrike.toml")
    assert main(["simulate", scene, "--animate", str(movie), "--json"]) == 0
    with Image.open(movie) as image:
        assert image.n_frames == 60  # a fixed frame count: the same run, the same film
    assert not [p for p in tmp_path.iterdir() if p.name != "restrike.gif"]  # no leftovers
    assert main(["simulate", scene, "--animate", str(tmp_path / "film.txt")]) == 2
    assert "--animate: expected a .gif or .mp4" in capsys.readouterr().err


def test_start_up_imports_only_what_is_needed():
    # `import rigidimpact` and `rigidimpact --help` pull in neither SymPy's heavy
    # neighbours nor the plotting and integration libraries (issue: fast start)
    import subprocess
    import sys

    script = ("import sys, rigidimpact\n"
              "from rigidimpact.cli import _build_parser\n"
              "_build_parser().format_help()\n"
              "print(sorted(m for m in ('scipy', 'matplotlib', 'sympy', 'numba', 'mpmath')"
              " if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def _loaded_by(command: list[str], modules: tuple[str, ...]) -> str:
    """Which of `modules` a fresh process has loaded once it ran `command` (derived
    afresh: the result cache off), as the sorted list's text."""
    import os
    import subprocess
    import sys

    script = ("import sys\n"
              "from rigidimpact.cli import main\n"
              f"assert main({command!r}) == 0\n"
              f"print(sorted(m for m in {modules!r} if m in sys.modules), file=sys.stderr)")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          check=True, cwd=Path(__file__).resolve().parents[1],
                          env={**os.environ, "RIGIDIMPACT_CACHE": "off"})
    return done.stderr.strip().splitlines()[-1]


@pytest.mark.parametrize("command", [["derive", "barbell"],
                                     ["evaluate", "derivations/newtons-cradle.toml"]])
def test_a_derivation_and_a_smooth_scene_load_no_numeric_library(command):
    # the paper's barbell and a smooth scene are exact algebra: the modules they load
    # name numpy for the numeric paths, but only a stand-in is made until it is used
    assert _loaded_by(command, ("numpy", "scipy", "matplotlib", "numba", "dask")) == "[]"


def test_a_built_in_derivation_reads_no_scene_and_no_package_metadata():
    # `derive barbell` reads no scene file, so it loads no scene reader; the version
    # is read from the package's metadata only for --version
    import subprocess
    import sys

    assert _loaded_by(["derive", "barbell"], ("importlib.metadata", "rigidimpact.scenes.space",
                                              "rigidimpact.scenes.scene")) == "[]"
    shown = subprocess.run([sys.executable, "-m", "rigidimpact", "--version"],
                           capture_output=True, text=True, check=True).stdout
    assert shown.startswith("rigidimpact ") and shown.split()[1][0].isdigit()


def test_the_command_as_a_process_prints_and_exits_as_main_does(capsys):
    # `python -m rigidimpact` (the console script's run()) tunes the collector for a
    # short process; its output and exit status are main()'s, and main() called from
    # Python leaves the collector's settings as they were
    import gc
    import subprocess
    import sys

    before = gc.get_threshold()
    assert main(["derive", "discs", "--json"]) == 0
    assert gc.get_threshold() == before and not gc.get_freeze_count()
    in_process = capsys.readouterr().out
    env = {**os.environ, "RIGIDIMPACT_CACHE": "off"}
    shown = subprocess.run([sys.executable, "-m", "rigidimpact", "derive", "discs", "--json"],
                           capture_output=True, text=True, env=env)
    assert shown.returncode == 0 and shown.stderr == ""
    drop = ("seconds",)  # the one figure that differs between two runs
    assert ({k: v for k, v in json.loads(shown.stdout).items() if k not in drop}
            == {k: v for k, v in json.loads(in_process).items() if k not in drop})
    bad = subprocess.run([sys.executable, "-m", "rigidimpact", "derive", "nonsense"],
                         capture_output=True, text=True, env=env)
    assert bad.returncode == 2 and bad.stdout == ""
    assert bad.stderr.count("\n") == 1 and "unknown problem 'nonsense'" in bad.stderr


_SHIPPED = Path(__file__).resolve().parents[1] / "derivations"


def test_a_sweep_of_chosen_keys_names_only_the_files_it_wrote(tmp_path, capsys):
    # the energy lost is evaluated for its warnings but not written: its line says so
    out = tmp_path / "sweep"
    assert main(["sweep", "barbell", "--grid", "theta=0:1:5", "--set", "L=1", "--set",
                 "M=2", "--set", "e=1/2", "--set", "m=1", "--set", "v_ix=1", "--keys",
                 "V_x", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    written = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert written == ["V_x.npy", "summary.json", "table.csv"]
    assert (out / "table.csv").read_text().splitlines()[0] == "theta,V_x"
    named = [line.split(".npy")[0].strip() + ".npy" for line in printed.splitlines()
             if ".npy:" in line]
    assert named == ["V_x.npy"]
    assert "energy_loss_fraction (checked for the warnings, not written)" in printed


_BARBELL_SET = ["--set", "m=1", "--set", "M=2", "--set", "e=1/2", "--set", "v_ix=1",
                "--set", "L=1"]


def _paper_barbell(theta, m=1.0, M=2.0, e=0.5, v=1.0, L=1.0):
    """The paper's eq. (5) and (7), typed here: f, then the motion after and the loss."""
    import math

    s2 = math.sin(theta) ** 2
    f = (1 + e) * m / (2 * M + m * (1 + s2))
    V = f * v
    return {"v_fx": v - 2 * M * V / m, "V_x": V, "omega_z": V * math.sin(theta) / L,
            "f": f, "energy_loss_fraction": (1 - e * e) / (1 + m / (2 * M) * (1 + s2))}


def test_a_sweep_writes_a_table_and_draws_each_result(tmp_path, capsys):
    import csv
    import math

    import numpy as np

    out, png = tmp_path / "sweep", tmp_path / "curves.png"
    assert main(["sweep", "barbell", "--grid", "theta=0:pi/2:9", *_BARBELL_SET,
                 "--out", str(out), "--plot", str(png)]) == 0
    assert "table.csv: one row a set" in capsys.readouterr().out
    with open(out / "table.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert list(rows[0]) == ["theta", *KEYS_ORDER]
    assert [float(r["theta"]) for r in rows] == list(np.linspace(0, math.pi / 2, 9))
    for row in rows:  # each value against the paper, and the same number as the .npy
        expected = _paper_barbell(float(row["theta"]))
        for key, value in expected.items():
            assert float(row[key]) == pytest.approx(value, rel=1e-12, abs=1e-15)
    for key in KEYS_ORDER:
        assert [float(r[key]) for r in rows] == np.load(out / f"{key}.npy").tolist()
    assert json.loads((out / "summary.json").read_text())["table"] == "table.csv"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_sweep_solved_set_by_set_writes_its_table_and_figure(tmp_path, capsys):
    import csv

    out, png = tmp_path / "sweep", tmp_path / "rod.png"
    assert main(["sweep", str(DERIVATIONS / "rod-slides-flat.toml"), "--grid",
                 "mu=0:1/4:3", "--out", str(out), "--plot", str(png)]) == 0
    with open(out / "table.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert [float(r["mu"]) for r in rows] == [0.0, 0.125, 0.25]
    for row in rows:  # both ends slide: Coulomb's friction is mu times the normal impulse
        for end in ("left", "right"):
            normal = float(row[f"{end}.normal_impulse"])
            assert normal > 0
            assert abs(float(row[f"{end}.tangential_impulse"])) == pytest.approx(
                float(row["mu"]) * normal, abs=1e-12)
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_sweep_curves_draw_every_output_against_the_symbol():
    import numpy as np

    from rigidimpact.outputs.plots import SWEEP_POINTS, sweep_curves

    x = np.linspace(0.0, 2.0, 3 * SWEEP_POINTS)
    fig = sweep_curves("theta", x, {"a": np.sin(x), "b": x ** 2, "c": np.cos(x)})
    assert [ax.get_ylabel() for ax in fig.axes] == ["a", "b", "c"]
    for ax, f in zip(fig.axes, (np.sin, np.square, np.cos), strict=True):
        [line] = ax.get_lines()
        xs, ys = line.get_xdata(), line.get_ydata()
        assert len(xs) <= SWEEP_POINTS + 1 and xs[0] == 0.0 and xs[-1] == 2.0
        assert np.array_equal(ys, f(xs))


@pytest.mark.parametrize("extra, said", [
    (["--plot", "{tmp}/nowhere/c.png"], "--plot: no such folder"),
    (["--plot", "{tmp}/c.pdf"], "--plot: expected a .png"),
    (["--plot", "{tmp}/c.png", "--grid", "e=0:1:3"], "exactly one --grid (got 2)"),
    (["--plot", "{tmp}/out/c.png"], "put the figure beside it"),
])
def test_a_sweep_refuses_a_bad_plot_before_writing_anything(tmp_path, capsys, extra, said):
    argv = ["sweep", "barbell", "--grid", "theta=0:1:3", *_BARBELL_SET,
            "--out", str(tmp_path / "out"), *(a.replace("{tmp}", str(tmp_path)) for a in extra)]
    if "e=0:1:3" in extra:  # e is swept, not set
        i = argv.index("e=1/2")
        del argv[i - 1:i + 1]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and said in err[0] and "Traceback" not in err[0]
    assert list(tmp_path.iterdir()) == []  # no folder, no figure, nothing half-written


def test_a_linkage_explains_its_flight_and_counts_its_steps(capsys):
    # the double pendulum swings under gravity with its joints held: not straight lines,
    # and its integration's steps are counted
    scene = str(_SHIPPED / "double-pendulum-wall.toml")
    assert main(["simulate", scene, "--explain"]) == 0
    explained = capsys.readouterr().out
    assert "straight lines" not in explained
    assert "every joint and pivot held" in explained
    assert main(["simulate", scene, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["cost"]["ode_steps"] > 0


def test_an_animation_says_where_it_was_written(tmp_path, capsys):
    movie = tmp_path / "restrike.gif"
    assert main(["simulate", str(_SHIPPED / "restrike.toml"), "--animate", str(movie)]) == 0
    assert movie.exists()
    assert f"animation written to {movie}" in capsys.readouterr().err


def test_derive_keeps_its_answer_and_reads_it_back(tmp_path, monkeypatch, capsys):
    # the second run prints what the first printed, its timing line saying it was read
    # from the cache; an edited scene is derived again; a spoiled entry is passed over
    monkeypatch.setenv("RIGIDIMPACT_CACHE", str(tmp_path / "cache"))
    assert main(["derive", "barbell"]) == 0
    first = capsys.readouterr().out
    assert main(["derive", "barbell"]) == 0
    again = capsys.readouterr().out
    assert "read from the cache" in again and "read from the cache" not in first
    timing = re.compile(r"^\(.* s.*\)$", re.MULTILINE)
    assert timing.sub("", again) == timing.sub("", first)
    (entry,) = (tmp_path / "cache").glob("*.json")
    entry.write_text("{not json")
    assert main(["derive", "barbell"]) == 0
    assert "read from the cache" not in capsys.readouterr().out
    scene = tmp_path / "drop.toml"
    text = (DERIVATIONS / "two-ball-drop.toml").read_text()
    scene.write_text(text)
    assert main(["derive", str(scene)]) == 0
    capsys.readouterr()
    scene.write_text(text.replace("title = ", "title = 'Edited' #"))
    assert main(["derive", str(scene)]) == 0
    edited = capsys.readouterr().out
    assert "Edited" in edited and "read from the cache" not in edited
    # a failing run is not kept, and a folder that cannot be made is passed over
    assert main(["derive", str(tmp_path / "missing.toml")]) == 2
    monkeypatch.setenv("RIGIDIMPACT_CACHE", str(entry / "inside-a-file"))
    assert main(["derive", "barbell"]) == 0


def test_evaluate_exact_prints_the_papers_numbers_exactly(capsys):
    """--exact: the barbell at m = 1, M = 2, theta = 30 deg, e = 1/2, v_ix = 1 has, by the
    paper's eq. (5), f = m (1 + e) / (2M + m sin^2 theta + m) = 2/7 and V_x = f v_ix,
    and by eq. (7) the energy lost 2M (1 - e^2) / (2M + m sin^2 theta + m) = 4/7."""
    import json

    from rigidimpact.cli import main

    argv = ["evaluate", "barbell", "--exact", *(x for s in ("m=1", "M=2", "L=1",
                                                             "theta=30 deg", "e=0.5",
                                                             "v_ix=1") for x in ("--set", s))]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "f = 2/7  (0.2857142857142857)" in out
    assert "energy_loss_fraction = 4/7" in out
    assert main([*argv, "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["exact"]["V_x"] == "2/7" and got["V_x"] == 2 / 7
