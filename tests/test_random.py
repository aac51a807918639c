"""Random inputs (issue: restitution as a random quantity): the exact distribution of
an output by a change of variables against independent routes, and the seeded Monte
Carlo within its standard error. The barbell of Mungan (Eur. J. Phys. 28, 2007) falls
flat at unit speed onto a floor, its rod at a uniform random angle to the floor."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad
from scipy.optimize import brentq

from rigidimpact.errors import InputError
from rigidimpact.scenes.scene import parse_scene
from rigidimpact.symbolic.distributions import distribution, monte_carlo, pushforward

ROOT = Path(__file__).resolve().parents[1]

BARBELL_DROP = '''
[[bodies]]
name = "barbell"
shape = "barbell"
mass = "m"
half_length = "L"
angle = "theta"
struck = "A"
velocity = ["0", "-1"]

[[bodies]]
name = "floor"
shape = "fixed"

[contact]
bodies = ["barbell", "floor"]
normal = ["0", "-1"]
restitution = "e"
'''


@pytest.fixture(scope="module")
def barbell():
    scene = parse_scene(BARBELL_DROP)
    g = scene.derivation().results["barbell.vy"]
    theta, e = scene.symbols["theta"], scene.symbols["e"]
    angle = distribution({"uniform": ["0", "pi/2"]}, "theta")
    return g, theta, e, angle, pushforward(g, theta, angle, {e: sp.Rational(1, 2)})


def test_the_centre_rebounds_between_minus_half_of_one_less_e_and_e(barbell):
    # flat (theta = 0) both ends would strike: the limit of one end striking is
    # (e - 1)/2; upright (pi/2) the barbell rebounds as a ball, at e
    g, theta, e, _, out = barbell
    assert sp.simplify(g - ((1 + e) / (1 + sp.cos(theta) ** 2) - 1)) == 0  # by hand
    assert [sp.simplify(s - t) for s, t in zip(out.support, ((e - 1) / 2, e),
                                                strict=True)] == [0, 0]


def test_the_mean_and_the_chance_of_falling_on(barbell):
    # by hand: the integral of 1/(1 + cos^2) over a quarter turn is pi/(2 sqrt 2), so
    # the mean is (1 + e)/sqrt(2) - 1; the centre keeps falling where cos^2 > e, a
    # fraction 2 acos(sqrt e)/pi of the angles
    _, theta, e, angle, out = barbell
    assert sp.simplify(out.mean - ((1 + e) / sp.sqrt(2) - 1)) == 0
    below = out.probability_below(0, angle.density(theta), theta)
    assert sp.simplify(below - 2 * sp.acos(sp.sqrt(e)) / sp.pi) == 0


@pytest.mark.parametrize("e_value", [0.1, 0.5, 0.9])
def test_the_density_against_the_angles_measure(barbell, e_value):
    # an independent route: the distribution function at y is the measure of the angles
    # whose rebound is below y, found by a root of g(theta) = y (no inverse from SymPy),
    # against the density integrated numerically; and the density's total is 1
    g, theta, e, _, out = barbell
    rebound = sp.lambdify(theta, g.subs(e, e_value))
    density = sp.lambdify(out.variable, out.density.subs(e, e_value))
    low, high = (e_value - 1) / 2, e_value
    total = quad(density, low, high, limit=200)[0]
    assert total == pytest.approx(1, abs=1e-6)
    for y in np.linspace(low, high, 7)[1:-1]:
        edge = brentq(lambda t, y=y: rebound(t) - y, 0, math.pi / 2, xtol=1e-14)
        measured = edge / (math.pi / 2)
        assert quad(density, low, y, limit=200)[0] == pytest.approx(measured, abs=1e-6)


def test_a_seeded_monte_carlo_within_its_standard_error(barbell):
    g, theta, e, angle, out = barbell
    e_value = 0.3
    drawn = monte_carlo(g, {theta: angle}, {e: e_value}, 400_000, seed=35,
                        chunk=100_000)
    exact_mean = float(out.mean.subs(e, e_value))
    assert abs(drawn["mean"] - exact_mean) < 4 * drawn["standard_error"]
    chance = 2 * math.acos(math.sqrt(e_value)) / math.pi
    assert abs(drawn["below_zero"] - chance) < 4 * math.sqrt(chance * (1 - chance) / 4e5)
    # the same seed and chunks give the same draws; another seed others
    again = monte_carlo(g, {theta: angle}, {e: e_value}, 400_000, seed=35, chunk=100_000)
    assert again == drawn
    other = monte_carlo(g, {theta: angle}, {e: e_value}, 400_000, seed=36, chunk=100_000)
    assert other["mean"] != drawn["mean"]


def test_an_output_not_monotone_in_pieces_found_in_closed_form_is_left_to_monte_carlo():
    x = sp.Symbol("x")
    assert pushforward(x, x, distribution({"normal": ["0", "1"]}, "x")) is None
    square = pushforward(x ** 2, x, distribution({"uniform": ["-1", "1"]}, "x"))
    assert square.support == (0, 1) and len(square.pieces) == 2  # two monotone pieces
    y = square.variable
    assert sp.simplify(square.density.subs(y, sp.Rational(1, 4)) - 1) == 0  # 2 * 1/2 / (2 * 1/2)


@pytest.mark.parametrize(("table", "message"), [
    ({"uniform": ["1", "0"]}, "second end must be above"),
    ({"normal": ["0", "-1"]}, "spread must be positive"),
    ({"uniform": ["0"]}, "two numbers"),
    ({"triangular": ["0", "1"]}, "one of uniform"),
    ({"discrete": ["0", "1"], "weights": ["1"]}, "one weight for each"),
    ({"uniform": ["0", "__import__('os')"]}, "random.theta.uniform"),
    ("0..1", "a table such as"),
])
def test_a_bad_random_entry_is_one_line(table, message):
    with pytest.raises(InputError, match=message):
        distribution(table, "theta")


def test_derive_prints_the_shipped_scenes_distribution(capsys):
    # derivations/random-barbell.toml: derive --json gives the density, support and
    # mean as SymPy strings, equal to the hand forms, and the Monte Carlo beside them
    import json
    from pathlib import Path

    from rigidimpact.cli import main

    scene = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    assert main(["derive", str(scene), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)["distributions"]["barbell.vy"]
    e, y = sp.Symbol("e", nonnegative=True), sp.Symbol("y", real=True)
    names = {"e": e, "y": y}
    hand = (1 + e) / (sp.pi * (1 + y) * sp.sqrt((e - y) * (1 + 2 * y - e)))
    assert sp.simplify(sp.sympify(out["density"], locals=names) - hand) == 0
    assert [sp.simplify(sp.sympify(s, locals=names) - t) for s, t in
            zip(out["support"], ((e - 1) / 2, e), strict=True)] == [0, 0]
    assert sp.simplify(sp.sympify(out["mean"], locals=names) - ((1 + e) / sp.sqrt(2) - 1)) == 0
    mc = out["monte_carlo"]
    exact = (1.5 / math.sqrt(2)) - 1  # e = 1/2 under [values]
    assert mc["samples"] == 1_000_000 and mc["seed"] == 2011
    assert abs(mc["mean"] - exact) < 4 * mc["standard_error"]
    assert main(["derive", str(scene)]) == 0
    text = capsys.readouterr().out
    assert "Distributions (random: theta uniform" in text and "P(barbell.vy < 0)" in text


@pytest.mark.parametrize(("entry", "message"), [
    ('e = { uniform = ["0", "2"] }', "random.e"),  # restitution above 1: its role
    ('zeta = { uniform = ["0", "1"] }', "not a symbol of the scene"),
    ('theta = { uniform = ["0", "1"] }\nsamples = 0', "random.samples"),
    ('theta = { uniform = ["0", "1"] }\noutputs = ["barbell.vz"]', "no result"),
])
def test_a_bad_random_table_in_a_scene_is_one_line(tmp_path, capsys, entry, message):
    from rigidimpact.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(BARBELL_DROP + "\n[values]\ne = 0.5\n\n[random]\n" + entry + "\n")
    assert main(["derive", str(path)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err


# the three bodies dropped flat at unit speed on a smooth floor, each at a uniform
# random angle theta in [0, pi/2] (derivations/random-*.toml): k = m d^2 / I, with d
# the struck point's distance from the centre and I the inertia about the axis the blow
# turns it on. The barbell (two masses m at +-L, I = 2 m L^2 for the mass 2m) has
# k = 1, the uniform rod (I = m L^2/3) k = 3, the coin (a thin disc landing on its rim,
# I = m r^2/4 about a diameter) k = 4.
DROPPED = [("random-barbell", "barbell.vy", 1), ("random-rod", "rod.vy", 3),
           ("random-coin", "coin.vy", 4)]


@pytest.fixture(scope="module", params=DROPPED, ids=[d[0] for d in DROPPED])
def dropped(request):
    from rigidimpact.scenes.scene import load_scene

    name, key, k = request.param
    scene = load_scene(ROOT / "derivations" / f"{name}.toml")
    g = scene.derivation().results[key]
    theta, e = scene.symbols["theta"], scene.symbols["e"]
    angle = scene.random.inputs[theta]
    out = pushforward(g, theta, angle, {e: sp.Rational(1, 2)})
    return SimpleNamespace(g=g, theta=theta, e=e, angle=angle, out=out, k=k, name=name,
                           key=key)


def test_each_dropped_body_by_hand(dropped):
    # by hand: the blow J at the struck point, d cos(theta) across from the centre,
    # obeys 1/m_eff = (1 + k cos^2)/m, so the centre leaves at (1 + e)/(1 + k cos^2) - 1:
    # from (e - k)/(1 + k) (flat) to e (upright). Over a quarter turn the mean of
    # 1/(1 + k cos^2) is 1/sqrt(1 + k), so the mean is (1 + e)/sqrt(1 + k) - 1; the
    # centre keeps falling where cos^2 > e/k, a fraction 2 acos(sqrt(e/k))/pi; and the
    # change of variables u = cos^2 gives the density
    # (1 + e)/(pi (1 + y) sqrt((e - y)((k + 1) y + k - e))).
    g, theta, e, angle, out, k = (dropped.g, dropped.theta, dropped.e, dropped.angle,
                                  dropped.out, dropped.k)
    assert sp.simplify(g - ((1 + e) / (1 + k * sp.cos(theta) ** 2) - 1)) == 0
    assert [sp.simplify(s - t) for s, t in zip(out.support, ((e - k) / (1 + k), e),
                                                strict=True)] == [0, 0]
    assert sp.simplify(out.mean - ((1 + e) / sp.sqrt(1 + k) - 1)) == 0
    below = out.probability_below(0, angle.density(theta), theta)
    assert sp.simplify(below - 2 * sp.acos(sp.sqrt(e / k)) / sp.pi) == 0
    y = out.variable
    hand = (1 + e) / (sp.pi * (1 + y) * sp.sqrt((e - y) * ((k + 1) * y + k - e)))
    for e_value in (sp.Rational(1, 10), sp.Rational(1, 2), sp.Rational(9, 10)):
        for share in (sp.Rational(1, 7), sp.Rational(1, 2), sp.Rational(6, 7)):
            low, high = (e_value - k) / (1 + k), e_value
            at = {e: e_value, y: low + share * (high - low)}
            assert float(out.density.subs(at)) == pytest.approx(float(hand.subs(at)),
                                                                 rel=1e-12)


@pytest.mark.parametrize("e_value", [0.1, 0.5, 0.9])
def test_each_density_against_the_angles_measure(dropped, e_value):
    # the independent route of test_the_density_against_the_angles_measure, for the
    # rod and the coin too
    g, theta, e, out, k = dropped.g, dropped.theta, dropped.e, dropped.out, dropped.k
    rebound = sp.lambdify(theta, g.subs(e, e_value))
    density = sp.lambdify(out.variable, out.density.subs(e, e_value))
    low, high = (e_value - k) / (1 + k), e_value
    assert quad(density, low, high, limit=200)[0] == pytest.approx(1, abs=1e-6)
    for y in np.linspace(low, high, 6)[1:-1]:
        edge = brentq(lambda t, y=y: rebound(t) - y, 0, math.pi / 2, xtol=1e-14)
        assert quad(density, low, y, limit=200)[0] == pytest.approx(edge / (math.pi / 2),
                                                                     abs=1e-6)


def test_each_shipped_drop_prints_its_distribution_beside_its_monte_carlo(dropped, capsys):
    import json

    from rigidimpact.cli import main

    k = dropped.k
    scene = ROOT / "derivations" / f"{dropped.name}.toml"
    assert main(["derive", str(scene), "--json"]) == 0
    row = json.loads(capsys.readouterr().out)["distributions"][dropped.key]
    mc = row["monte_carlo"]
    exact = 1.5 / math.sqrt(1 + k) - 1  # e = 1/2 under [values]
    assert abs(mc["mean"] - exact) < 4 * mc["standard_error"]
    chance = 2 * math.acos(math.sqrt(0.5 / k)) / math.pi
    assert abs(mc["below_zero"] - chance) < 4 * math.sqrt(chance * (1 - chance) / 1e6)


@pytest.mark.parametrize("workers", [1, 2])
def test_the_dask_path_equals_one_process_for_the_same_seed(barbell, workers):
    # one task a chunk, each from its own stream of the seed, summed in order: the same
    # numbers to the last bit whatever the number of workers (threads here, to start fast)
    pytest.importorskip("dask.distributed")
    from rigidimpact.analyses.distributions import monte_carlo_on_dask

    g, theta, e, angle, _ = barbell
    alone = monte_carlo(g, {theta: angle}, {e: 0.5}, 300_000, seed=7, chunk=50_000)
    spread = monte_carlo_on_dask(g, {theta: angle}, {e: 0.5}, 300_000, seed=7,
                                 chunk=50_000, workers=workers, processes=False)
    assert spread == alone


def _always_start_workers(monkeypatch):
    """Local workers started for any work, however small (a test's is small)."""
    from rigidimpact.outputs import workers

    monkeypatch.setattr(workers, "REPAYS", {kind: 0 for kind in workers.REPAYS})


def test_derive_with_a_missing_scheduler_or_no_random_table_is_one_line(capsys):
    # the command on two local workers gives the one-process numbers: checked with the
    # processes it leaves behind (test_a_run_on_local_workers_leaves_no_process_behind),
    # the one run of it in this file
    from pathlib import Path

    from rigidimpact.cli import main

    pytest.importorskip("dask.distributed")
    scene = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    assert main(["derive", str(scene), "--scheduler", "tcp://127.0.0.1:1"]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no Dask scheduler at tcp://127.0.0.1:1" in err[0]
    assert "connection was refused" in err[0]  # at once, not after the client's 10 s
    assert main(["derive", str(scene), "--scheduler", "tcp://127.0.0.1:99999"]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "a port lies between 1 and 65535" in err[0]
    assert main(["derive", "barbell", "--workers", "2"]) != 0
    assert "only a scene with a [random] table" in capsys.readouterr().err


def test_a_scheduler_address_where_something_else_answers_is_one_line(capsys):
    # a server that is not Dask's (here one that answers as a web server would): Dask's
    # client reads its first bytes as a length of exabytes; said in one line, not as an
    # input too large
    import socket
    import threading
    from pathlib import Path

    from rigidimpact.cli import main

    pytest.importorskip("dask.distributed")
    server = socket.create_server(("127.0.0.1", 0))
    port = server.getsockname()[1]
    held = []

    def answer() -> None:
        while True:
            try:
                conn, _ = server.accept()
            except OSError:  # closed at the test's end
                return
            held.append(conn)
            conn.sendall(b"HTTP/1.1 400 Bad Request\r\n\r\n")

    threading.Thread(target=answer, daemon=True).start()
    scene = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    try:
        assert main(["derive", str(scene), "--scheduler", f"tcp://127.0.0.1:{port}"]) != 0
    finally:
        server.close()
        for conn in held:
            conn.close()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "does not speak Dask's protocol" in err[0], err


def test_the_distribution_is_exported_as_latex(capsys):
    from pathlib import Path

    from rigidimpact.cli import main
    from rigidimpact.outputs.latex import to_latex

    scene = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    assert main(["derive", str(scene), "--format", "latex"]) == 0
    text = capsys.readouterr().out
    e, y = sp.Symbol("e", nonnegative=True), sp.Symbol("y", real=True)
    assert "% distribution of barbell.vy (y), random: theta" in text
    density = (e + 1) / (sp.pi * sp.sqrt((e - y) * (-e + 2 * y + 1)) * (y + 1))
    assert f"f(y) = {to_latex(density)}" in text  # the hand form, as derive finds it
    assert "\\mathrm{E}[y] = " in text and "P(y < 0) = " in text


# a rod (mass 1, inertia 1/3, ends at x = -1 and 1) lands flat at unit speed spinning at
# 1/2, both ends at once, Newton's e at each under the simultaneous rule, e uniform on
# [0, 1]: by hand the ends leave at 3e/2 and e/2 (both impulses push: 7(1 + e)/12 and
# 5(1 + e)/12), so the centre leaves at e and the spin is -e/2, whose means are 1/2 and
# -1/4, and neither is ever below zero / above it
RANDOM_ROD_FLAT = '''
[values]
e = 0.5

[random]
e = { uniform = ["0", "1"] }
outputs = ["rod.vy", "rod.omega"]
samples = 192
seed = 11

[[bodies]]
name = "rod"
shape = "rigid"
mass = "1"
inertia = "1/3"
position = ["0", "0"]
velocity = ["0", "-1"]
spin = "1/2"

[[bodies]]
name = "floor"
shape = "fixed"

[[contacts]]
name = "left"
bodies = ["rod", "floor"]
point = ["-1", "0"]
normal = ["0", "-1"]
restitution = "e"

[[contacts]]
name = "right"
bodies = ["rod", "floor"]
point = ["1", "0"]
normal = ["0", "-1"]
restitution = "e"

[impact]
rule = "simultaneous"
'''


def test_several_contacts_a_solve_a_draw_by_hand(tmp_path, capsys):
    import json

    from rigidimpact.cli import main

    path = tmp_path / "rod.toml"
    path.write_text(RANDOM_ROD_FLAT)
    assert main(["derive", str(path), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)["distributions"]
    vy, spin = found["rod.vy"]["monte_carlo"], found["rod.omega"]["monte_carlo"]
    assert vy["samples"] == 192 and vy["seed"] == 11 and vy["warned"] == 0
    # the spin is -vy/2 draw by draw, so their means and errors are tied exactly
    assert spin["mean"] == pytest.approx(-vy["mean"] / 2, rel=1e-12)
    assert spin["standard_error"] == pytest.approx(vy["standard_error"] / 2, rel=1e-9)
    assert abs(vy["mean"] - 0.5) < 4 * vy["standard_error"]
    # a uniform on [0, 1] has standard deviation 1/sqrt(12)
    assert vy["standard_error"] * math.sqrt(192) == pytest.approx(1 / math.sqrt(12), rel=0.2)
    assert vy["below_zero"] == 0 and spin["below_zero"] == 1
    assert "no closed form" in found["rod.vy"]["solved"]
    assert main(["derive", str(path)]) == 0
    text = capsys.readouterr().out
    assert "Distributions (random: e uniform on [0, 1]; Monte Carlo at [values], 192 " \
        "samples, seed 11):" in text and "no closed form: a solve a draw" in text


def test_several_contacts_on_dask_equal_one_process(tmp_path, monkeypatch):
    pytest.importorskip("dask.distributed")
    from rigidimpact.analyses.distributions import point_monte_carlo
    from rigidimpact.scenes.scene import load_scene

    path = tmp_path / "rod.toml"
    path.write_text(RANDOM_ROD_FLAT)
    scene = load_scene(path)
    keys = ["rod.vy", "rod.omega"]
    alone = point_monte_carlo(scene, keys, 96, seed=3, chunk=16)
    _always_start_workers(monkeypatch)
    spread = point_monte_carlo(scene, keys, 96, seed=3, chunk=16, workers=2,
                               processes=False)
    assert spread == alone


def test_several_contacts_past_the_budget_is_one_line(tmp_path, capsys):
    from rigidimpact.cli import main

    path = tmp_path / "rod.toml"
    path.write_text(RANDOM_ROD_FLAT.replace("samples = 192", "samples = 2000000"))
    assert main(["derive", str(path)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "random.samples" in err[0] and "budget" in err[0], err


def test_local_workers_keep_the_adaptive_memory_threshold(monkeypatch):
    # Dask's own default starts workers with MALLOC_TRIM_THRESHOLD_ set, which made a
    # chunk of draws about 1.4 times as slow there as in one process; the local
    # cluster started here leaves it unset (a user's own setting still passes through)
    pytest.importorskip("dask.distributed")
    import os

    from rigidimpact.outputs.workers import dask_client

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with dask_client(1) as client:
        found = client.run(os.environ.get, "MALLOC_TRIM_THRESHOLD_")
    assert list(found.values()) == [None]


def test_whether_a_closed_form_is_sought_depends_on_the_outputs_form_alone():
    # no clock decides it: a ratio of polynomials of degree at most 2 in x, cos x, sin x
    # or tan x is sought (the three shipped bodies are, in cos theta), anything else is
    # left to the Monte Carlo, with the reason
    from rigidimpact.analyses.distributions import closed_form_refusal

    x, e = sp.Symbol("x", real=True), sp.Symbol("e", nonnegative=True)
    for g in ((e - sp.cos(x) ** 2) / (1 + sp.cos(x) ** 2), 3 * x ** 2 - e,
              e / (1 + sp.tan(x) ** 2), (1 + e) * sp.sin(x) / (2 + sp.sin(x) ** 2)):
        assert closed_form_refusal(g, x) is None, g
    for g in (sp.sqrt(1 + x ** 2), sp.sin(x) * sp.cos(x) + e, x ** 3,
              sp.Piecewise((x, x > e), (0, True))):
        assert "not a ratio of polynomials of degree at most 2" in \
            closed_form_refusal(g, x), g


def test_a_density_needs_no_number_for_e(tmp_path, capsys):
    # the exact density needs e only to judge the signs of its pieces: with no number
    # for e they are judged at three seeded points of [0, 1] and the formulas kept where
    # they agree; the mean is (1 + e)/sqrt(2) - 1 and P(vy < 0) = 2 acos(sqrt(e))/pi, as
    # derived by hand in the scene's comment; the Monte Carlo, which needs e, is said
    # to be left out
    import json

    from rigidimpact.cli import main

    text = (ROOT / "derivations" / "random-barbell.toml").read_text()
    path = tmp_path / "barbell.toml"
    path.write_text(text.replace("\ne = 0.5\n", "\n"))
    assert main(["derive", str(path), "--json"]) == 0
    row = json.loads(capsys.readouterr().out)["distributions"]["barbell.vy"]
    e = sp.Symbol("e")
    assert sp.simplify(sp.sympify(row["mean"]) - ((1 + e) / sp.sqrt(2) - 1)) == 0
    assert sp.sympify(row["below_zero"]) == 2 * sp.acos(sp.sqrt(e)) / sp.pi
    assert row["symbolic_in"] == ["e"] and "monte_carlo" not in row
    assert main(["derive", str(path)]) == 0
    assert "no Monte Carlo: the draws need a number for e" in capsys.readouterr().out


def _in_session(sid: int) -> list[str]:
    """Every process (zombies too) of session `sid`, as 'pid state name'."""
    from pathlib import Path

    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:  # ended while listed
            continue
        name_end = text.rindex(")")
        fields = text[name_end + 2:].split()
        if int(fields[3]) == sid:  # state, ppid, pgrp, session
            found.append(f"{stat.parent.name} {fields[0]} {text[:name_end + 1]}")
    return found


def test_local_workers_are_forked_on_linux_unless_the_users_dask_config_says(
        monkeypatch, tmp_path):
    # forked workers start with what the command has loaded; a method the user names
    # in Dask's own configuration (a variable or a file) is left to Dask
    dask = pytest.importorskip("dask")
    from rigidimpact.outputs.workers import _fork_here

    monkeypatch.delenv("DASK_DISTRIBUTED__WORKER__MULTIPROCESSING_METHOD", raising=False)
    monkeypatch.setattr(dask.config, "paths", [str(tmp_path)])
    monkeypatch.setattr("sys.platform", "linux")
    assert _fork_here(dask)
    monkeypatch.setattr("sys.platform", "darwin")
    assert not _fork_here(dask)
    monkeypatch.setattr("sys.platform", "linux")
    (tmp_path / "dask.yaml").write_text("distributed:\n  worker:\n"
                                        "    multiprocessing-method: forkserver\n")
    assert not _fork_here(dask)
    (tmp_path / "dask.yaml").unlink()
    monkeypatch.setenv("DASK_DISTRIBUTED__WORKER__MULTIPROCESSING_METHOD", "spawn")
    assert not _fork_here(dask)


def test_local_workers_look_at_themselves_seldom_unless_the_user_says(monkeypatch,
                                                                     tmp_path):
    # the event loops' own delay, the memory and the dashboard's records are taken every
    # 1 to 2 s, not every 20 to 500 ms: in the workers and in this process's scheduler;
    # an interval the user sets in Dask's own configuration is kept
    dask = pytest.importorskip("dask")
    pytest.importorskip("dask.distributed")
    from rigidimpact.outputs.workers import QUIET, dask_client

    def intervals(dask_worker=None, dask_scheduler=None) -> dict[str, float]:
        server = dask_worker or dask_scheduler
        return {k: server.periodic_callbacks[k].callback_time for k in ("tick", "monitor")}

    for key in QUIET:
        monkeypatch.delenv("DASK_" + key.upper().replace(".", "__").replace("-", "_"),
                           raising=False)
    monkeypatch.setattr(dask.config, "paths", [str(tmp_path)])  # no file of the user's
    assert dask.config.get("distributed.admin.tick.interval") == "20ms"  # Dask's default
    with dask_client(1) as client:
        assert list(client.run(intervals).values()) == [{"tick": 1000, "monitor": 2000}]
        assert client.run_on_scheduler(intervals) == {"tick": 1000, "monitor": 2000}
        assert list(client.run(lambda: __import__("dask").config.get(
            "distributed.worker.memory.monitor-interval")).values()) == ["1s"]
    assert dask.config.get("distributed.admin.tick.interval") == "20ms"  # as it was
    monkeypatch.setenv("DASK_DISTRIBUTED__ADMIN__TICK__INTERVAL", "50ms")
    dask.config.refresh()  # as a process started with the variable reads it
    try:
        with dask_client(1) as client:
            assert list(client.run(intervals).values()) == [{"tick": 50, "monitor": 2000}]
    finally:
        monkeypatch.delenv("DASK_DISTRIBUTED__ADMIN__TICK__INTERVAL")
        dask.config.refresh()


def test_local_workers_do_not_profile_themselves_unless_the_user_asks(monkeypatch,
                                                                     tmp_path):
    # Dask's statistical profiler feeds a dashboard that is not started here; its stack
    # sampling every 10 ms took CPU beside the solves. A user who enables it (a
    # variable, or a file on Dask's path) keeps it
    dask = pytest.importorskip("dask")
    pytest.importorskip("dask.distributed")
    from rigidimpact.outputs.workers import PROFILE, dask_client

    def profiled() -> bool:
        import dask as inside

        return bool(inside.config.get(PROFILE))

    monkeypatch.delenv("DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED", raising=False)
    monkeypatch.setattr(dask.config, "paths", [str(tmp_path)])  # no file of the user's
    assert dask.config.get(PROFILE)  # Dask's default, which the workers here change
    with dask_client(1) as client:
        assert list(client.run(profiled).values()) == [False]
    assert dask.config.get(PROFILE)  # this process's own configuration is as it was
    monkeypatch.setenv("DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED", "True")
    with dask_client(1) as client:
        assert list(client.run(profiled).values()) == [True]


@pytest.mark.skipif(not __import__("pathlib").Path("/proc/self/stat").exists(),
                    reason="reads the process table from /proc")
def test_a_run_on_local_workers_leaves_no_process_behind(capsys, tmp_path):
    # the command is started in its own session: once it has exited, nothing it started
    # (the workers, their nannies, multiprocessing's resource tracker) is left in it,
    # not even a finished process waiting to be reaped; and its answers are the
    # one-process answers, to the last bit, for both its outputs (one with a closed
    # form, derived here while the workers draw; one without)
    pytest.importorskip("dask.distributed")
    import json
    import subprocess
    import sys
    from pathlib import Path

    from rigidimpact.cli import main

    shipped = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    text = shipped.read_text()
    assert 'outputs = ["barbell.vy"]' in text and "samples = 1000000\n" in text
    scene = tmp_path / "two-outputs.toml"
    scene.write_text(text.replace('outputs = ["barbell.vy"]',
                                  'outputs = ["barbell.vy", "barbell.omega"]')
                     .replace("samples = 1000000\n", "samples = 300000\n"))
    started = ("from rigidimpact.outputs import workers; "  # for a test's few draws too
               "workers.REPAYS.update(draws=0); "
               "from rigidimpact.cli import main; "
               f"raise SystemExit(main(['derive', {str(scene)!r}, '--workers', '2', "
               "'--json']))")
    command = subprocess.Popen([sys.executable, "-c", started], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, start_new_session=True, text=True)
    out, err = command.communicate(timeout=300)
    left = _in_session(command.pid)  # at once: an orphan is reaped within moments
    assert command.returncode == 0, err
    assert left == [], left
    on_dask = json.loads(out)["distributions"]
    assert main(["derive", str(scene), "--json"]) == 0
    alone = json.loads(capsys.readouterr().out)["distributions"]
    assert list(on_dask) == list(alone) == ["barbell.vy", "barbell.omega"]
    assert "density" in alone["barbell.vy"] and "no_closed_form" in alone["barbell.omega"]
    for key, found in alone.items():
        assert on_dask[key]["monte_carlo"]["samples"] == 300000
        # one chunk of 10^6 draws or fewer is one task: one worker drew it, none here
        assert on_dask[key]["monte_carlo"].pop("workers") == 1
        assert found["monte_carlo"].pop("workers") == 0
        timed = {"monte_carlo_seconds", "exact_seconds"}
        assert {k: v for k, v in on_dask[key].items() if k not in timed} == \
            {k: v for k, v in found.items() if k not in timed}, key


@pytest.mark.slow
def test_local_workers_close_in_silence_and_say_how_many_drew(tmp_path):
    # Dask's own progress bar had the scheduler feed it from a coroutine that slept
    # 100 ms between sends; the cluster closed within them cancelled it, and the
    # scheduler logged a CancelledError traceback after the answer. Flaky by nature:
    # run several times, with the bar (text) and without it (--json)
    pytest.importorskip("dask.distributed")
    import json
    import subprocess
    import sys
    from pathlib import Path

    shipped = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    scene = tmp_path / "four-chunks.toml"  # four tasks of 10^6 draws for two workers
    scene.write_text(shipped.read_text().replace("samples = 1000000\n",
                                                 "samples = 4000000\n"))
    for run, extra in enumerate([[], [], [], [], ["--json"], ["--json"]]):
        started = ("from rigidimpact.outputs import workers; "  # for 4 x 10^6 draws too
                   "workers.REPAYS.update(draws=0); "
                   "from rigidimpact.cli import main; "
                   f"raise SystemExit(main(['derive', {str(scene)!r}, '--workers', '2'"
                   f"{''.join(f', {x!r}' for x in extra)}]))")
        done = subprocess.run([sys.executable, "-c", started], capture_output=True,
                              text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        noise = [line for line in done.stderr.splitlines()
                 if "Traceback" in line or "ERROR" in line or "Error" in line
                 or line.startswith("  File ")]
        assert noise == [], (run, done.stderr)
        # only the bar of the Dask tasks, on the standard error, and not on the answer's
        assert all(line.endswith("Dask tasks") for line in done.stderr.splitlines())
        assert "Dask tasks" not in done.stdout and "\r" not in done.stdout
        if extra:
            carlo = json.loads(done.stdout)["distributions"]["barbell.vy"]["monte_carlo"]
            assert carlo["workers"] == 2 and carlo["samples"] == 4_000_000
        else:
            assert "s on 2 Dask workers" in done.stdout


def test_local_workers_step_aside_where_the_work_cannot_repay_them(capsys):
    # the rule counts work, never seconds: the shipped scene's 10^6 draws are far fewer
    # than the 10^8 that repay starting local workers, so --workers 2 runs in this
    # process, says so in its text and its JSON, and gives the same numbers (sweeps:
    # tests/test_fused.py)
    import json
    from pathlib import Path

    from rigidimpact.cli import main
    from rigidimpact.outputs.workers import REPAYS

    scene = Path(__file__).resolve().parents[1] / "derivations" / "random-barbell.toml"
    assert main(["derive", str(scene), "--json", "--workers", "2"]) == 0
    stepped = json.loads(capsys.readouterr().out)["distributions"]["barbell.vy"]
    assert main(["derive", str(scene), "--json"]) == 0
    alone = json.loads(capsys.readouterr().out)["distributions"]["barbell.vy"]
    assert stepped["monte_carlo"] == alone["monte_carlo"] and "workers" not in alone
    assert stepped["monte_carlo"]["workers"] == 0  # no Dask worker drew: this process did
    assert stepped["workers"].startswith("--workers 2: 1,000,000 draws are fewer than "
                                         f"the {REPAYS['draws']:,}")
    assert main(["derive", str(scene), "--workers", "2"]) == 0
    assert "  (--workers 2: 1,000,000 draws are fewer than" in capsys.readouterr().out


@pytest.mark.parametrize("law", ["uniform", "normal", "lognormal", "discrete", "constant"])
def test_a_draw_plan_draws_what_the_fused_kernel_gives_on_numpys_own_draws(law):
    # the plan that workers draw with (NumPy alone) against the kernel built from the
    # expression in this process, on draws made by NumPy's own calls: bit for bit
    import numpy as np

    from rigidimpact.symbolic.distributions import distribution, draw_plan
    from rigidimpact.symbolic.numeric import fused

    x, y, e = sp.symbols("x y e")
    tables = {"uniform": {"uniform": ["0", "pi/2"]}, "normal": {"normal": ["1", "1/3"]},
              "lognormal": {"lognormal": ["0", "1/2"]},
              "discrete": {"discrete": ["1/4", "1/2", "1"], "weights": [1, 2, 1]},
              "constant": {"uniform": ["0", "1"]}}
    inputs = {x: distribution(tables[law], "x"), y: distribution({"uniform": ["-1", "1"]}, "y")}
    g = sp.Integer(3) / 7 if law == "constant" else (e - sp.cos(x) ** 2 * y) / (1 + sp.cos(x) ** 2)
    size = 20_001  # not a whole number of the kernel's chunks
    got = draw_plan(g, inputs, {e: 0.5}).values(np.random.default_rng(11), size)
    rng = np.random.default_rng(11)  # x then y: the inputs in the order of their names
    drawn_x = {"uniform": lambda: rng.uniform(0.0, float(sp.pi / 2), size),
               "normal": lambda: rng.normal(1.0, 1 / 3, size),
               "lognormal": lambda: rng.lognormal(0.0, 0.5, size),
               "discrete": lambda: rng.choice(np.array([0.25, 0.5, 1.0]), size=size,
                                              p=np.array([1.0, 2.0, 1.0]) / 4.0),
               "constant": lambda: rng.uniform(0.0, 1.0, size)}[law]()
    drawn_y = rng.uniform(-1.0, 1.0, size)
    if law == "constant":
        expected = np.full(size, 3 / 7)
    else:
        expected = fused({"y": g.subs(e, sp.Float(0.5))})(x=drawn_x, y=drawn_y)["y"]
    assert got.shape == (size,) and np.array_equal(got, expected)


@pytest.mark.parametrize("case", ["one input", "two inputs", "constant"])
def test_a_chunks_sums_are_its_values_summed_block_by_block(case):
    # a chunk's values are made and summed a block at a time: its three sums must equal,
    # to the bit, NumPy's sums of the blocks' sums of the values the plan draws whole
    # from the chunk's stream (one input's draws made a block at a time are the same
    # numbers; several inputs are drawn whole, in turn)
    import numpy as np

    from rigidimpact.symbolic.distributions import distribution, draw_plan
    from rigidimpact.symbolic.drawn import stream

    x, y, e = sp.symbols("x y e")
    g = {"one input": (e - sp.cos(x) ** 2) / (1 + sp.cos(x) ** 2),
         "two inputs": (e - sp.cos(x) ** 2) / (1 + y * sp.cos(x) ** 2),
         "constant": sp.Rational(1, 10)}[case]
    inputs = {x: distribution({"uniform": ["0", "pi/2"]}, "x"),
              y: distribution({"normal": ["1", "1/10"]}, "y")}
    plan = draw_plan(g, {s: inputs[s] for s in g.free_symbols if s in inputs}, {e: 0.5})
    size = 100_003
    values = np.array(plan.values(np.random.default_rng(stream(5, 2)), size))
    blocks = [values[a:a + plan.chunk] for a in range(0, size, plan.chunk)]
    assert len(blocks) == 13
    expected = (float(np.sum([b.sum() for b in blocks])),
                float(np.sum([(b * b).sum() for b in blocks])),
                float(np.count_nonzero(values < 0)))
    assert plan.sums(5, 2, size) == expected
    assert (expected[2] > 0) is (case != "constant") and expected[1] > 0


def test_guided_runs_cover_the_work_in_order_and_shrink_to_the_least():
    # each run is a 2 * workers-th part of what is left (rounded up, at least `least`),
    # so they cover range(count) in order and only shrink, the last one possibly short
    import random

    from rigidimpact.outputs.workers import guided

    rng = random.Random(45)
    for _ in range(500):
        count, workers, least = rng.randrange(0, 5000), rng.randrange(1, 9), rng.randrange(1, 20)
        runs = guided(count, workers, least)
        assert [a for a, _ in runs] == [0] + [b for _, b in runs[:-1]]
        assert runs[-1][1] == count if count else runs == []
        sizes = [b - a for a, b in runs]
        assert sizes == sorted(sizes, reverse=True)
        assert all(s >= least for s in sizes[:-1])
        for (a, b) in runs[:-1]:
            assert b - a == max(least, -(-(count - a) // (2 * workers)))


@pytest.mark.parametrize("kind, numbers, weights", [
    ("uniform", (0.0, 1.5707963267948966), ()),
    ("normal", (1.0, 0.1), ()),
    ("lognormal", (0.0, 0.5), ()),
    ("discrete", (0.2, 0.5, 0.9), ()),
    ("discrete", (0.2, 0.5, 0.9), (1.0, 2.0, 5.0))])
def test_a_samplers_draws_made_a_block_at_a_time_are_its_draws_made_at_once(
        kind, numbers, weights):
    # what a chunk's sums rely on to draw one input a block at a time (NumPy's
    # generators draw each value in turn from the stream, keeping nothing between
    # calls): a NumPy that changed this would change the Monte Carlo's draws
    import numpy as np

    from rigidimpact.symbolic.drawn import Sampler, stream

    sampler = Sampler("x", kind, numbers, weights)
    size, block = 100_003, 8192
    whole = sampler.sample(np.random.default_rng(stream(11, 4)), size)
    rng = np.random.default_rng(stream(11, 4))
    blocks = np.concatenate([sampler.sample(rng, min(block, size - a))
                             for a in range(0, size, block)])
    assert np.array_equal(whole, blocks)
    assert len(np.unique(whole)) > 2


def test_derive_plot_draws_each_output_over_its_exact_density(tmp_path, capsys):
    """derive SCENE --plot: the coin's rebound, drawn 10^6 times at the scene's seed,
    lies on its exact density (the histogram's bins integrate to one and match the
    density averaged over each bin where it is smooth); the PNG is written."""
    import numpy as np

    from rigidimpact.analyses.distributions import distribution_curves, scene_distributions
    from rigidimpact.cli import main
    from rigidimpact.scenes.scene import load_scene

    root = Path(__file__).parents[1]
    scene = load_scene(root / "derivations" / "random-coin.toml")
    results = dict(scene.derivation().results)
    found = scene_distributions(scene, results)
    ((key, edges, sampled, points, exact),) = distribution_curves(scene, results, found)
    assert key == "coin.vy" and abs(np.sum(sampled * np.diff(edges)) - 1) < 1e-12
    centre = (edges[:-1] + edges[1:]) / 2
    inside = slice(10, -10)  # away from the density's infinite ends
    by_bin = np.interp(centre, points, exact)[inside]
    assert np.allclose(sampled[inside], by_bin, rtol=0.05)
    target = tmp_path / "coin.png"
    assert main(["derive", str(root / "derivations" / "random-coin.toml"), "--plot",
                 str(target)]) == 0
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_scenes_distributions_and_their_picture_in_one_call_each(tmp_path):
    """ri.distributions: the shipped barbell's rebound against the hand forms (mean
    (1 + e)/sqrt(2) - 1, chance of falling on 2 acos(sqrt e)/pi, support (e - 1)/2 to
    e) and its Monte Carlo within four standard errors of the hand mean at e = 1/2;
    ri.draw_distributions writes the PNG from those answers; a scene without [random]
    is refused in one line."""
    import rigidimpact as ri

    scene = ri.load_scene(ROOT / "derivations" / "random-barbell.toml")
    found = ri.distributions(scene)["barbell.vy"]
    e = ri.symbol("e")
    assert sp.simplify(found["mean"] - ((1 + e) / sp.sqrt(2) - 1)) == 0
    assert sp.simplify(found["below_zero"] - 2 * sp.acos(sp.sqrt(e)) / sp.pi) == 0
    assert [sp.simplify(s - t) for s, t in zip(found["support"], ((e - 1) / 2, e),
                                                strict=True)] == [0, 0]
    mc = found["monte_carlo"]
    assert mc["seed"] == 2011 and mc["samples"] == 1_000_000 and mc["workers"] == 0
    assert abs(mc["mean"] - (1.5 / math.sqrt(2) - 1)) < 4 * mc["standard_error"]
    # by path, the same numbers
    again = ri.distributions(str(ROOT / "derivations" / "random-barbell.toml"))
    assert again["barbell.vy"]["monte_carlo"] == mc
    target = tmp_path / "barbell.png"
    ri.draw_distributions(scene, target, {"barbell.vy": found})
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(InputError, match="no \\[random\\] table"):
        ri.distributions(ROOT / "derivations" / "rod-rough-floor.toml")


def test_a_random_input_that_is_not_uniform_says_why_it_has_no_closed_form():
    # the change of variables is made for a uniform input: a normal angle gets the
    # Monte Carlo alone, and the reason names the input's law
    from rigidimpact.analyses.distributions import distributions_text, scene_distributions

    scene = parse_scene(BARBELL_DROP + '''
[values]
e = 0.5
m = 1
L = 0.5
[random]
theta = { normal = ["pi/4", "0.2"] }
outputs = ["barbell.vy"]
samples = 1000
''')
    found = scene_distributions(scene, dict(scene.derivation().results))
    entry = found["barbell.vy"]
    assert "density" not in entry and "monte_carlo" in entry
    assert entry["no_closed_form"] == ("theta is normal, and the closed form is derived "
                                       "for a uniform input only")
    assert "      no closed form sought: theta is normal, and the closed form is derived " \
        "for a uniform input only" in distributions_text(scene.random, scene.values, found)


def test_an_output_of_two_random_inputs_says_why_it_has_no_closed_form_and_no_curve(
        tmp_path, capsys):
    # found by a new user: ball.vy (driven by e and mu) had a Monte Carlo with no word of
    # why no density, and --plot left it out in silence; rod.omega (e alone, sliding
    # throughout: P_n = m_eff (1 + e) v) keeps its closed form and its curve
    import json

    from rigidimpact.cli import main

    scene = Path(__file__).parent / "data" / "random-two-inputs.toml"
    assert main(["derive", str(scene), "--json"]) == 0
    found = json.loads(capsys.readouterr().out)["distributions"]
    assert found["ball.vy"]["no_closed_form"] == (
        "the output is driven by 2 random inputs (e, mu): a closed form is derived for one")
    assert "density" in found["rod.omega"] and "no_closed_form" not in found["rod.omega"]
    assert main(["derive", str(scene), "--plot", str(tmp_path / "d.png")]) == 0
    err = capsys.readouterr().err
    assert "left out: ball.vy" in err and "rod.omega" not in err.split("left out:")[1]
    assert (tmp_path / "d.png").stat().st_size > 10_000
