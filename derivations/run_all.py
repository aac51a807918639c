"""The main job (`make run`): derive and verify the paper's results; write LaTeX, the PDF
where pdflatex exists, a verification table and the figures into one folder.

Run: python derivations/run_all.py --out build
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")  # this script draws to files only

import numpy as np  # noqa: E402
import section1_barbell  # noqa: E402
import section2_implications  # noqa: E402
import section3_two_bodies  # noqa: E402
import sympy as sp  # noqa: E402

import rigidimpact as ri  # noqa: E402
from rigidimpact import cli  # noqa: E402
from rigidimpact.analyses import restrike  # noqa: E402
from rigidimpact.analyses.bench import FLOOR, pareto  # noqa: E402
from rigidimpact.outputs import latex, plots  # noqa: E402
from rigidimpact.simulate.runner import rigid_limit  # noqa: E402
from rigidimpact.symbolic.numeric import Kernel  # noqa: E402


def _figures():
    """Every figure the notebooks show, made by the same library functions."""
    theta_c = float(restrike.critical_angle().theta_c)
    ten = math.radians(10.0)
    return (
        ("omega-vs-theta.png", plots.omega_vs_theta),
        ("energy-loss-vs-theta.png", plots.energy_loss_vs_theta),
        ("critical-angle.png", lambda: plots.critical_angle_graphical(theta_c)),
        ("restrike-map.png", lambda: plots.restrike_map(*restrike.restrike_map())),
        ("restrike-strobe.png", lambda: plots.strobe(
            restrike.strobe_frames(ten, 0.0, 1.0, 14),
            "e = 0, m = M, theta = 10 deg: from the impact to the re-strike by the B half")),
        ("sticking-vs-bouncing.png", plots.sticking_vs_bouncing),
        ("impulse-vs-offset.png", _impulse_vs_offset),
        ("oblique-discs.png", _oblique_discs),
        ("spring-rod.png", _spring_rod),
        ("double-pendulum-wall.png", _double_pendulum),
        ("compass-gait-heel-strike.png", _heel_strike),
        ("rigid-limit.png", lambda: plots.convergence(
            rigid_limit(ri.load_scene(HERE / "barbell.toml"), [1e3, 1e4, 1e5]))),
        ("accuracy-vs-time.png", _accuracy_vs_time),
        ("hard-case-v_fx.png", _hard_case),
        ("kharaz-comparison.png", kharaz_figure),
        ("random-barbell.png", _random_barbell),
        ("random-bodies.png", _random_bodies),
    )


def _dropped(name: str, key: str) -> tuple:
    """A body of derivations/NAME.toml dropped at a uniform random angle: its rebound
    g(theta), the angle and e, the angle's distribution and the exact distribution."""
    from rigidimpact.scenes.scene import load_scene
    from rigidimpact.symbolic.distributions import pushforward

    scene = load_scene(HERE / f"{name}.toml")
    theta, e = scene.symbols["theta"], scene.symbols["e"]
    g = scene.derivation().results[key]
    angle = scene.random.inputs[theta]
    return g, theta, e, angle, pushforward(g, theta, angle, {e: sp.Rational(1, 2)})


def _rebound_curve(label: str, dropped: tuple, value: float) -> tuple:
    """10^7 seeded samples of a dropped body's rebound at e = value, binned over its
    support, and its exact density there."""
    from rigidimpact.symbolic.distributions import histogram

    g, theta, e, angle, exact = dropped
    low, high = (float(x.subs(e, value)) for x in exact.support)
    edges = np.linspace(low, high, 61)
    sampled = histogram(g, {theta: angle}, {e: value}, 10**7, 2011, edges)
    points = np.linspace(low, high, 801)[1:-1]
    density = sp.lambdify(exact.variable, exact.density.subs(e, value))(points)
    return (label, edges, sampled, points, density)


def _random_barbell():
    """The barbell dropped at a random angle: 10^7 seeded samples of the centre's
    rebound for three restitutions, over the exact density derive gives."""
    barbell = _dropped("random-barbell", "barbell.vy")
    curves = [_rebound_curve(f"e = {value}", barbell, value) for value in (0.2, 0.5, 0.9)]
    return plots.random_rebound(curves, "a barbell dropped flat at a uniform random angle "
                                "(10^7 samples each)")


def _random_bodies():
    """The barbell, the uniform rod and the coin dropped at a random angle, e = 1/2:
    the more a body turns about its struck point, the lower its centre rebounds."""
    curves = [_rebound_curve(label, _dropped(name, key), 0.5) for label, name, key in (
        ("barbell", "random-barbell", "barbell.vy"), ("uniform rod", "random-rod", "rod.vy"),
        ("coin on its rim", "random-coin", "coin.vy"))]
    return plots.random_rebound(curves, "three bodies dropped at a uniform random angle, "
                                "e = 0.5 (10^7 samples each)")


def kharaz_figure():
    """The rigid Coulomb model, fitted in the gross-slip range, and the tangentially
    compliant contact, fitted at every angle, against both digitisations of Kharaz, Gorham
    and Salman (2001) and the spring-dashpot simulation (notebook 11)."""
    from rigidimpact.analyses import experiment

    data = experiment.load_kharaz()
    found = experiment.fit()
    model = experiment.sphere_on_flat()
    angles = np.linspace(0.5, 65.0, 260)
    curves = {q: (angles, model.predict(q, angles, found.mu, found.e))
              for q in ("e_t", "rebound_angle", "omega")}
    shown = {"measured (MFiX digitisation)": data["mfix"].points,
             "measured (Lethe digitisation)": data["lethe"].points,
             "spring-dashpot simulation": data["simulation"].points}
    compliant = experiment.fit_compliant()
    springy = experiment.CompliantSphereOnFlat(compliant.ratio)
    others = {f"tangentially compliant, mu = {compliant.mu:.3f}, e = {compliant.e:.3f}, "
              f"k_t/k_n = {compliant.ratio:.3f} (fitted at every angle)": {
                  q: (angles, springy.predict(q, angles, compliant.mu, compliant.e))
                  for q in ("e_t", "rebound_angle", "omega")}}
    return plots.experiment_comparison(
        curves, shown, f"rigid, mu = {found.mu:.4f}, e = {found.e:.4f} (fitted from "
        f"{found.from_deg:g} deg up)",
        "Alumina spheres on glass (Kharaz et al. 2001): the rigid Coulomb contact and a "
        "tangentially compliant one", others)


def _impulse_vs_offset():
    """A unit disc at speed 1 strikes a disc, a ring or a rod off centre (notebook 5)."""
    names = ("m_1", "m_2", "I_1", "I_2", "R_1x", "R_1y", "R_2x", "R_2y", "V_1ix", "V_1iy",
             "omega_1iz", "V_2ix", "V_2iy", "omega_2iz", "e")
    impulse = sp.lambdify([ri.symbol(n) for n in names],
                          ri.derive("two-body").definitions["J"], "numpy")
    offsets = np.linspace(-0.9, 0.9, 181)
    second = {"disc (I = m/2)": 0.5, "ring (I = m)": 1.0, "rod of length 2 (I = m/3)": 1 / 3}
    return plots.impulse_vs_offset(offsets, {
        label: impulse(1, 1, 0.5, inertia, -1, 0, 0.5, offsets, 1, 0, 0, 0, 0, 0, 0.5)
        for label, inertia in second.items()})


def _oblique_discs():
    """Equal discs, e = 1: disc 1 at (3/5, 4/5) hits disc 2 at rest (notebook 6)."""
    first = ri.Body.disc(1, 1, side=-1, velocity=(sp.Rational(3, 5), sp.Rational(4, 5)),
                         name="one")
    solution = ri.Impact(first, ri.Body.disc(1, 1, name="two"), ri.Contact(restitution=1)).solve()
    after = [np.array([float(c) for c in b.velocity])
             for b in (solution.first_after, solution.second_after)]
    return plots.oblique_discs([np.array([0.6, 0.8]), np.zeros(2)], after)


def _spring_rod():
    scene = ri.load_scene(HERE / "spring-rod.toml")
    track = ri.run(scene).trajectory
    return plots.trajectories(track.t, track.points(), scene.title,
                              ("sphere A", track.contact_velocity("barbell")), relative=True)


def _double_pendulum():
    """The double pendulum after its tip strikes the wall, until it strikes again."""
    scene = ri.load_scene(HERE / "double-pendulum-wall.toml")
    track = ri.run(scene).trajectory
    return plots.trajectories(track.t, track.points(), scene.title + ", until it strikes "
                              "again")


def _heel_strike():
    """The compass-gait biped at heel strike, its velocities before and after."""
    from rigidimpact.simulate import impact_view

    scene = ri.load_scene(HERE / "compass-gait-heel-strike.toml")
    return plots.impact_picture(*impact_view(scene, ri.run(scene)), scene.title)


def _accuracy_vs_time():
    """From the committed bench run that notebook 8 reads (no timing here)."""
    report = json.loads((HERE.parent / "notebooks" / "data" / "bench.json").read_text())
    rows = report["rows"]
    fronts = [pareto([r for r in rows if r["problem"] == p]) for p in ("collision", "restrike")]
    return plots.accuracy_vs_time(rows, fronts, FLOOR)


def _hard_case():
    kernel = Kernel.from_expr(ri.derive("barbell").results["v_fx"])
    ratios = np.logspace(0, 12, 13)
    theta = math.radians(30.0)
    naive, stable = [], []
    for big in ratios:
        point = {"M": big, "e": 0.0, "m": 1.0, "theta": theta, "v_ix": 1.0}
        exact = kernel.reference(50, **point)
        f = 1.0 / (2 * big + 1 + math.sin(theta) ** 2)  # eq. (5) read literally, m = 1
        naive.append(float(abs((1 - 2 * big * f - exact) / exact)))
        stable.append(float(abs((kernel(**point) - exact) / exact)))
    return plots.naive_vs_stable(ratios, np.array(naive), np.array(stable), "mass ratio M/m",
                                 "v_fx for a heavy barbell, e = 0, theta = 30 deg")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="build", type=Path)
    out = parser.parse_args(argv).out
    out.mkdir(parents=True, exist_ok=True)

    for section in (section1_barbell, section2_implications, section3_two_bodies):
        section.main()
        print()

    checks = ri.run_checks()
    failed = [c for c in checks if c.status != "pass"]
    rows = ["| check | paper | status | seconds |", "|---|---|---|---|"]
    rows += [f"| {c.id} | {c.paper} | {c.status} | {c.seconds:.2f} |" for c in checks]
    (out / "verification.md").write_text("\n".join(rows) + "\n", encoding="utf-8")
    (out / "verification.json").write_text(json.dumps(
        [{"id": c.id, "paper": c.paper, "status": c.status, "detail": c.detail}
         for c in checks], indent=2) + "\n", encoding="utf-8")
    print(f"verification: {len(checks) - len(failed)} passed, {len(failed)} failed "
          f"-> {out / 'verification.md'}")

    derivations = [ri.derive(name) for name in ri.PROBLEMS]
    derivations += [ri.load_any(p).derivation() for p in sorted(HERE.glob("*.toml"))]
    pdf = shutil.which("pdflatex") is not None
    written = latex.write_export(out / "latex", derivations, checks, pdf=pdf)
    print(f"LaTeX: {len(written)} files -> {out / 'latex'}"
          f"{'' if pdf else ' (no pdflatex here: no PDF)'}")

    figures = out / "figures"
    figures.mkdir(exist_ok=True)
    for name, make in _figures():
        make().savefig(figures / name)
        print(f"figure -> {figures / name}")
    # the re-strike as motion: the barbell comes round and strikes the ball again
    scene = ri.load_scene(HERE / "restrike.toml")
    track = ri.run(scene).trajectory
    plots.write_gif(np.asarray(track.t), track.points(), scene.title,
                    figures / "restrike.gif", fps=20)
    print(f"animation -> {figures / 'restrike.gif'}")
    # a 3-D run past its impact: Garwin's superball under a table, drawn and animated by
    # the command line's own simulate
    superball = [str(figures / "superball.png"), str(figures / "superball.gif")]
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        status = cli.main(["simulate", str(HERE / "superball-under-table.toml"),
                           "--plot", superball[0], "--animate", superball[1]])
    if status != 0:
        print("simulate of superball-under-table.toml failed")
        return 1
    print(f"figure -> {superball[0]}\nanimation -> {superball[1]}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
