"""Friction by Routh's method: references, limits and laws, each by another route."""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from rigidimpact.errors import InputError
from rigidimpact.laws import routh
from rigidimpact.laws.contact import Contact
from rigidimpact.laws.law import RESTITUTION_LAWS
from rigidimpact.model.bodies import Body
from rigidimpact.model.impulse import TouchingPair
from rigidimpact.paper.problems import derive
from rigidimpact.solve.impact import Impact
from rigidimpact.symbolic.notation import symbol

SEED = 1305
ROOT = Path(__file__).resolve().parents[1]


def rod_on_floor(tangential: float = 0.6) -> tuple[Body, Body]:
    """Issue example: a slender rod (mass 1, half-length 1) at 45 degrees whose lower end
    meets the floor with velocity (tangential, normal) = (0.6, -1), no spin. Contact
    frame: x from the floor up into the rod, y the tangent."""
    c = sp.sqrt(2) / 2
    rod = Body.rigid(1, sp.Rational(1, 3), (c, c), velocity=(-1, sp.nsimplify(tangential)),
                     name="rod")
    return Body.fixed("floor"), rod


def integrate(W, v, mu, e, law, width=1e-7):
    """An independent route: the impulse equations with Coulomb's law smoothed,
    dP_t/dP_n = -mu tanh(v_t / width), integrated numerically with the law's end as an
    event; no events of slip are sought, sticking emerges from the smoothing."""
    W = np.array(W.evalf(), dtype=float)
    v0 = np.array([float(x) for x in v])

    def rhs(p, y):  # y = (P_t, work of the normal impulse)
        vel = v0 + W @ np.array([p, y[0]])
        slope = -mu * math.tanh(vel[1] / width)
        if abs(W[1, 0] / W[1, 1]) <= mu and abs(vel[1]) < 50 * width:
            slope = -W[1, 0] / W[1, 1] - vel[1] / width / W[1, 1] * 1e-3  # hold the stick
        return [slope, vel[0]]

    def v_n(p, y):
        return v0[0] + W[0, 0] * p + W[0, 1] * y[0]

    def compressed(p, y):
        return v_n(p, y)
    compressed.terminal, compressed.direction = True, 1
    first = solve_ivp(rhs, (0, 100), [0.0, 0.0], events=compressed, method="LSODA",
                      rtol=1e-10, atol=1e-13, max_step=1e-3)
    p_c, (pt_c, work_c) = first.t[-1], first.y[:, -1]

    def ended(p, y):
        if law == "newton":
            return v_n(p, y) + e * v0[0]
        if law == "poisson":
            return p - (1 + e) * p_c
        return (y[1] - work_c) + e**2 * work_c
    ended.terminal, ended.direction = True, 1
    second = solve_ivp(rhs, (p_c, 100), [pt_c, work_c], events=ended, method="LSODA",
                       rtol=1e-10, atol=1e-13, max_step=1e-3)
    if law == "newton" and v_n(p_c, [pt_c]) + e * v0[0] >= 0:  # e = 0: ends at compression
        return p_c, pt_c
    return second.t[-1], second.y[0, -1]


def energy_ratio(bodies, impulse):
    core = TouchingPair(bodies)
    after = core.bodies_after(sp.Matrix(impulse))
    before = sum(b.kinetic_energy for b in bodies)
    return float(sum(b.kinetic_energy for b in after) / before)


@pytest.mark.parametrize("law, ratio", [("newton", 1.033371), ("poisson", 0.868652),
                                        ("energetic", 0.912313)])
def test_rod_on_a_rough_floor_matches_the_published_ratios(law, ratio):
    bodies = rod_on_floor()
    core = TouchingPair(bodies)
    (regime,) = routh.regimes(core.W, core.velocity_before, sp.Rational(2, 5),
                              RESTITUTION_LAWS[law](1))
    assert regime.name.startswith("slip-reversal")
    assert energy_ratio(bodies, regime.impulse) == pytest.approx(ratio, abs=5e-7)
    # the same by smoothed integration, a route with no events of its own
    p_n, p_t = integrate(core.W, core.velocity_before, 0.4, 1.0, law)
    assert energy_ratio(bodies, (p_n, p_t)) == pytest.approx(ratio, abs=2e-4)


def random_bodies(generator: random.Random) -> tuple[Body, Body]:
    def number(lo, hi):
        return sp.Rational(generator.randint(int(lo * 100), int(hi * 100)), 100)

    striker = Body.rigid(number(0.5, 3), number(0.1, 2), (number(-2, -0.1), number(-2, 2)),
                         (number(0.2, 3), number(-2, 2)), number(-2, 2), name="a")
    other = Body.fixed("wall") if generator.random() < 0.5 else Body.rigid(
        number(0.5, 3), number(0.1, 2), (number(0.1, 2), number(-2, 2)),
        (number(-1, 0), number(-2, 2)), number(-2, 2), name="b")
    closing = TouchingPair((striker, other)).velocity_before[0]
    if closing == 0:
        return random_bodies(generator)
    if closing > 0:  # moving apart: run the draw backward
        striker, other = (b if b.support == "fixed" else b.with_motion(-b.velocity, -b.spin)
                          for b in (striker, other))
    return striker, other


@pytest.mark.parametrize("case", range(12))
def test_routh_agrees_with_smoothed_integration(case):
    generator = random.Random(SEED + case)
    bodies = random_bodies(generator)
    core = TouchingPair(bodies)
    mu = generator.choice([0.1, 0.3, 0.8])
    e = generator.choice([0.0, 0.5, 0.9])
    for law in routh.LAWS:
        (regime,) = routh.regimes(core.W, core.velocity_before, sp.nsimplify(mu),
                                  RESTITUTION_LAWS[law](sp.nsimplify(e)))
        p_n, p_t = integrate(core.W, core.velocity_before, mu, e, law)
        scale = max(1.0, abs(float(regime.impulse[0])))
        assert float(regime.impulse[0]) == pytest.approx(p_n, abs=1e-3 * scale), regime.name
        assert float(regime.impulse[1]) == pytest.approx(p_t, abs=1e-3 * scale), regime.name


@pytest.mark.parametrize("case", range(10))
def test_no_friction_is_the_smooth_result(case):
    bodies = random_bodies(random.Random(SEED * 7 + case))
    e = sp.Rational(1, 2)
    smooth = Impact(*bodies, Contact(restitution=e)).solve().results()
    for law in routh.LAWS:
        rough = Impact(*bodies, Contact(restitution=e, tangential="coulomb", friction=0,
                                        law=law)).solve()
        assert {k: v for k, v in rough.results().items()} == smooth


def test_enough_friction_is_the_sticking_result():
    # Newton's law with Coulomb friction: once slip stops and friction can hold it, the
    # points leave with v_t = 0 and v_n = -e v_n-, which is the sticking law exactly.
    # It applies where slip stops before the impact ends: with strong coupling the
    # tangential impulse that stops the slip can end the impact first (regime "slip")
    stuck = 0
    for case in range(12):
        bodies = random_bodies(random.Random(SEED * 11 + case))
        e = sp.Rational(3, 10)
        stick = Impact(*bodies, Contact(restitution=e, tangential="stick")).solve()
        core = TouchingPair(bodies)
        mu = 2 * abs(core.W[1, 0] / core.W[1, 1]) + 50  # holds, and stops slip early
        rough = Impact(*bodies, Contact(restitution=e, tangential="coulomb",
                                        friction=mu)).solve()
        if rough.regime == "slip":
            assert rough.contact_velocities_after[0] != rough.contact_velocities_after[1]
            continue
        assert rough.regime == "slip-stick"
        stuck += 1
        for key, value in stick.results().items():
            if key != "impulse_t":
                assert sp.simplify(rough.results()[key] - value) == 0, key
    assert stuck >= 8


def test_slip_throughout_makes_the_three_laws_agree():
    bodies = rod_on_floor(tangential=-0.6)  # leaning the other way: it slides throughout
    results = [Impact(*bodies, Contact(restitution=sp.Rational(4, 5), tangential="coulomb",
                                       friction=sp.Rational(2, 5), law=law)).solve()
               for law in routh.LAWS]
    assert {r.regime for r in results} == {"slip"}
    assert results[0].results() == results[1].results() == results[2].results()


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.integers(0, 10**6), st.floats(0, 3), st.floats(0, 1),
       st.sampled_from(["poisson", "energetic"]))
def test_poisson_and_energetic_never_create_energy(seed, mu, e, law):
    bodies = random_bodies(random.Random(seed))
    core = TouchingPair(bodies)
    (regime,) = routh.regimes(core.W, core.velocity_before, sp.nsimplify(round(mu, 3)),
                              RESTITUTION_LAWS[law](sp.nsimplify(round(e, 3))))
    assert energy_ratio(bodies, regime.impulse) <= 1 + 1e-12


def test_newton_creates_energy_and_evaluate_says_so(capsys):
    from rigidimpact.cli import main

    scene = ROOT / "derivations" / "rod-rough-floor.toml"  # Newton's law, mu = 0.4, e = 1
    assert main(["evaluate", str(scene), "--json"]) == 0
    captured = capsys.readouterr()
    assert '"regime": "slip-reversal"' in captured.out
    assert "kinetic energy is created" in captured.err
    assert "Kane-Levinson" in captured.err


def test_superball_reverses_its_contact_velocity():
    # Garwin (Am. J. Phys. 37, 1969): a solid sphere with beta = 1 and no spin keeps
    # 1 - 2(1 + beta)/7 = 3/7 of its centre's tangential velocity and spins up to
    # 10/7 v / r; its contact point's tangential velocity reverses
    v, r = symbol("v"), symbol("r")
    ball = Body.sphere(1, r, side=-1, velocity=(1, v), name="ball")
    sol = Impact(ball, Body.fixed("floor"),
                 Contact(restitution=1, tangential="rough", tangential_restitution=1)).solve()
    after = sol.first_after
    assert sp.simplify(after.velocity[1] - sp.Rational(3, 7) * v) == 0
    assert sp.simplify(after.contact_velocity[1] + ball.contact_velocity[1]) == 0


def test_the_clay_ball_is_the_sticking_limit():
    # the paper's clay ball (figure 2): e = 0 and enough friction to hold
    impact = Impact(Body.particle(symbol("m"), (symbol("v_ix"), 0), "ball"),
                    Body.barbell(symbol("M"), symbol("L"), sp.pi / 3),
                    Contact(restitution=0, tangential="coulomb", friction=10))
    solution = impact.solve()
    paper = derive("sticking").results
    values = {symbol(n): 1 for n in ("m", "M", "L", "v_ix")}
    assert solution.regime_at(values) == "stick"
    stuck = next(s for name, _, s in solution.regimes if name == "stick")
    assert sp.simplify(stuck.second_after.spin
                       - paper["omega_z"].subs(symbol("theta"), sp.pi / 3)) == 0


def test_symbolic_rod_gives_regimes_with_conditions():
    mu = symbol("mu")
    bodies = rod_on_floor()
    solution = Impact(*bodies, Contact(restitution=1, tangential="coulomb",
                                       friction=mu)).solve()
    names = [name for name, _, _ in solution.regimes]
    assert names == ["slip-stick", "slip-reversal"]  # slip throughout cannot happen here
    assert solution.regime_at({mu: sp.Rational(2, 5)}) == "slip-reversal"
    assert solution.regime_at({mu: 1}) == "slip-stick"  # mu >= 3/5 = |W_tn| / W_tt


def test_routh_command_prints_the_path_and_draws_the_diagram(tmp_path, capsys):
    from rigidimpact.cli import main

    scene = str(ROOT / "derivations" / "rod-rough-floor.toml")
    assert main(["routh", scene, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["regime"] == "slip-reversal"
    # the path: slip along the cone's edge until the sticking line, then back the other
    # way: the first leg has P_t/P_n = +mu, the second -mu
    (n0, t0), (n1, t1), (n2, t2) = data["path"]
    assert (n0, t0) == (0.0, 0.0)
    assert t1 / n1 == pytest.approx(0.4) and (t2 - t1) / (n2 - n1) == pytest.approx(-0.4)
    picture = tmp_path / "routh.png"
    assert main(["routh", scene, "--set", "mu=0.8", "--plot", str(picture)]) == 0
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["routh", str(ROOT / "derivations" / "hinged-rod.toml")]) == 2
    assert "Coulomb" in capsys.readouterr().err


@pytest.mark.parametrize("law", routh.LAWS)
def test_printed_laws_hold_for_friction(law):
    # what is printed is what is solved: with friction the momentum laws (and Newton's
    # relation, under Newton's law) hold at the solution; Poisson's and the energetic law
    # are not printed as Newton's relation, since the bent impulse path does not obey it
    bodies = rod_on_floor()
    impact = Impact(*bodies, Contact(restitution=1, tangential="coulomb",
                                     friction=sp.Rational(2, 5), law=law))
    solution = impact.solve()
    for eq in impact.equations():
        assert sp.simplify(eq.residual.subs(solution.values)) == 0, eq.label
    assert any(eq.law == "restitution" for eq in impact.equations()) == (law == "newton")


# ---- friction where the touching points have one degree of freedom ----------------------

def _pendulum_on_floor(law: str, mu):
    # a uniform rod (mass 1, length 2) hinged at its upper end (-1, sqrt 3) swings down
    # at spin -1 and its lower end meets a floor at O (normal (0, -1), rod to floor)
    rod = Body.rod(1, 2, -sp.pi / 3, -1, (-sp.sqrt(3) / 2, -sp.Rational(1, 2)), -1, "rod",
                   pivot=(-1, sp.sqrt(3)))
    contact = Contact((0, -1), sp.Rational(1, 2), "coulomb", law, friction=mu)
    return Impact(rod, Body.fixed("floor"), contact).solve()


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
def test_a_hinged_rod_slides_on_a_rough_floor_by_routh(law):
    # by hand: the end moves along (sqrt 3, 1) omega, so across the floor at v_n = omega
    # and along it at sqrt(3) omega; about the hinge (inertia 4/3) the rod turns by
    # I d(omega) = P_n - sqrt(3) P_t. Slip (positive) and approach stop together:
    # compression along P_t = -mu P_n ends at P_c = (4/3)/(1 + sqrt(3) mu); restitution
    # along P_t = +mu P_n turns the rod back at (1 - sqrt(3) mu)/(4/3) per unit P_n
    mu, e, r3 = sp.Rational(1, 10), sp.Rational(1, 2), sp.sqrt(3)
    P_c = sp.Rational(4, 3) / (1 + r3 * mu)
    back = (1 - r3 * mu) * sp.Rational(3, 4)
    solution = _pendulum_on_floor(law, mu)
    P_n, P_t = solution.contact_impulse
    omega = solution.after[0].spin
    P_r = P_n - P_c
    assert solution.regime == "slip-reversal"
    assert sp.simplify(P_t - (-mu * P_c + mu * P_r)) == 0
    assert sp.simplify(omega - back * P_r) == 0
    expected_r = {"newton": e / back,  # it leaves at -e times its approach: omega = e
                  "poisson": e * P_c,
                  "energetic": sp.sqrt(e**2 * P_c / back)}  # work P_r w/2 = e^2 P_c 1/2
    assert sp.simplify(P_r - expected_r[law]) == 0
    assert solution.energy_lost >= 0


def test_a_hinged_rod_locks_on_a_floor_too_rough_to_leave():
    # mu sqrt(3) > 1: the restitution impulse along the cone's other edge would drive the
    # end into the floor, so the rod stops dead at the end of compression
    solution = _pendulum_on_floor("poisson", 1)
    assert solution.regime == "slip-lock"
    assert solution.after[0].spin == 0
    assert sp.simplify(solution.contact_impulse[0] - sp.Rational(4, 3) / (1 + sp.sqrt(3))) == 0
    assert sp.simplify(solution.energy_loss_fraction - 1) == 0  # all of it


def test_one_freedom_friction_with_symbols_is_piecewise():
    mu = sp.Symbol("mu", positive=True)
    solution = _pendulum_on_floor("poisson", mu)
    assert [name for name, _, _ in solution.regimes] == ["slip-reversal", "slip-lock"]
    assert solution.regime_at({mu: sp.Rational(1, 10)}) == "slip-reversal"
    assert solution.regime_at({mu: 1}) == "slip-lock"


def test_stick_and_straight_across_motion_with_one_freedom_are_refused_in_one_line():
    rod = Body.rod(1, 2, -sp.pi / 3, -1, (-sp.sqrt(3) / 2, -sp.Rational(1, 2)), -1, "rod",
                   pivot=(-1, sp.sqrt(3)))
    with pytest.raises(InputError, match="one degree of freedom .* tangential = \"coulomb\""):
        Impact(rod, Body.fixed("floor"), Contact((0, -1), sp.Rational(1, 2), "stick")).solve()
    # a rod hanging straight down from its hinge moves across a wall only: friction does
    # no work and its impulse is not fixed
    hanging = Body.rod(1, 2, -sp.pi / 2, -1, (1, 0), 1, "rod", pivot=(0, 2))
    with pytest.raises(InputError, match="friction does no work"):
        Impact(hanging, Body.fixed("wall"), Contact((1, 0), sp.Rational(1, 2), "coulomb",
                                                    friction=sp.Rational(1, 2))).solve()
