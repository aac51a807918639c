"""The impact map of sympy.physics.mechanics systems, checked against the published
walkers (their own equations, transcribed, solved here independently with SciPy) and
against the laws; and the published examples' JSON keys."""

from __future__ import annotations

import json
import math
import random
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
import sympy.physics.mechanics as me
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve
from sympy.polys.matrices import DomainMatrix

import rigidimpact as ri
from rigidimpact.errors import InputError

DERIVATIONS = Path(__file__).resolve().parents[1] / "derivations"
sys.path.insert(0, str(DERIVATIONS))

import compass_gait  # noqa: E402
import double_pendulum_floor  # noqa: E402
import rimless_wheel  # noqa: E402
import simplest_walker  # noqa: E402


@pytest.fixture(scope="module")
def biped():
    kane, strike, solution = compass_gait.heel_strike()
    return kane, strike, solution, compass_gait.impact_map(solution, kane)


@pytest.fixture(scope="module")
def compass_found(biped):
    """The compass gait's period-one gait (derivations/compass_gait.py's own search)."""
    kane, _, solution, _ = biped
    return compass_gait.gait(solution, kane)


@pytest.fixture(scope="module")
def walker_found(biped):
    """The simplest walker's long-period gait (derivations/simplest_walker.py's search)."""
    kane, _, solution, _ = biped
    return compass_gait.gait(solution, kane, simplest_walker.VALUES,
                             guess=(0.2, -0.2, -0.2, -0.04))


@pytest.fixture(scope="module")
def wheel():
    """The rimless wheel's landing ratio and its steady roll."""
    _, ratio = rimless_wheel.landing()
    return ratio, rimless_wheel.roll(ratio)


# ---- the compass gait (Goswami, Thuilot and Espiau) ---------------------------------

def _goswami_Q(m, mH, a, b, alpha):
    """Their transition matrices (angular momentum about the new contact for the whole
    biped, and about the hip for the old stance leg), as published: Q+ w+ = Q- w- with
    w = [swing rate, stance rate]."""
    l, c = a + b, sp.cos(2 * alpha)
    minus = sp.Matrix([[-m * a * b, -m * a * b + (mH * l**2 + 2 * m * a * l) * c],
                       [0, -m * a * b]])
    plus = sp.Matrix([[m * b * (b - l * c), m * l * (l - b * c) + m * a**2 + mH * l**2],
                      [m * b**2, -m * b * l * c]])
    return plus, minus


def test_compass_heel_strike_map_is_goswamis(biped):
    *_, H = biped
    swap = sp.Matrix([[0, 1], [1, 0]])  # their [swing, stance] to our [stance, swing]
    rng = random.Random(24)
    for _ in range(6):
        values = {compass_gait.m: rng.uniform(0.5, 8), compass_gait.m_H: rng.uniform(0.5, 20),
                  compass_gait.a: rng.uniform(0.1, 1), compass_gait.b: rng.uniform(0.1, 1),
                  compass_gait.alpha: rng.uniform(0.05, 0.6)}
        plus, minus = _goswami_Q(*(values[s] for s in (
            compass_gait.m, compass_gait.m_H, compass_gait.a, compass_gait.b,
            compass_gait.alpha)))
        expected = swap * plus.LUsolve(minus) * swap
        got = H.xreplace(values)
        assert np.allclose(np.array(got, float), np.array(expected, float), rtol=1e-12)


def test_plastic_impact_is_the_projection(biped):
    # e = 0 with stick: u+ = (I - M^-1 J^T W^-1 J) u-, the projection onto the speeds
    # that leave the heel at rest, written out here from M and J alone. At heel strike
    # (theta_st = -alpha, theta_sw = alpha) everything is rational in s = sin(alpha),
    # c = cos(alpha), m, m_H, a, b; both sides are formed as rational functions of those
    # six symbols, s and c independent, and are equal as such: a symbolic identity
    kane, strike, solution, _ = biped
    _, _, st, sw = kane.q
    s, c = sp.symbols("s c")
    at = {st: -compass_gait.alpha, sw: compass_gait.alpha}

    def plain(x):
        x = sp.expand_trig(sp.sympify(x).xreplace(at))
        return x.xreplace({sp.sin(compass_gait.alpha): s, sp.cos(compass_gait.alpha): c})

    M, J = strike.M.applyfunc(plain), strike.J.applyfunc(plain)
    field = sp.QQ.frac_field(*sorted(M.free_symbols | J.free_symbols,
                                     key=sp.default_sort_key))
    dM, dJ = (DomainMatrix.from_Matrix(x).convert_to(field) for x in (M, J))
    Minv_JT = dM.lu_solve(dJ.transpose())
    projection = DomainMatrix.eye(4, field) - Minv_JT * (dJ * Minv_JT).lu_solve(dJ)
    H = solution.speeds_after.applyfunc(plain).jacobian(sp.Matrix(kane.u))
    assert DomainMatrix.from_Matrix(H).convert_to(field) == projection


def _goswami_gait(m=5.0, mH=10.0, a=0.5, b=0.5, g=9.8, slope=3 * math.pi / 180):
    """The period-one gait from their equations of motion (M, N and gravity, as
    published, in angles from the true vertical) and their transition, by SciPy."""
    l = a + b

    def rhs(_t, x):
        ns, s, dns, ds = x
        c, sn = math.cos(s - ns), math.sin(s - ns)
        M = np.array([[m * b * b, -m * l * b * c], [-m * l * b * c, (mH + m) * l * l + m * a * a]])
        N = np.array([[0, m * l * b * sn * ds], [-m * l * b * sn * dns, 0]])
        G = np.array([m * b * g * math.sin(ns), -(mH * l + m * a + m * l) * g * math.sin(s)])
        return [dns, ds, *np.linalg.solve(M, -N @ [dns, ds] - G)]

    def strike(_t, x):  # the swing foot on the slope
        return x[0] + x[1] + 2 * slope

    strike.terminal = True

    def step(x):
        t0 = 0.0
        while True:
            run = solve_ivp(rhs, (t0, t0 + 5), x, events=strike, rtol=1e-11, atol=1e-12,
                            method="DOP853")
            t, x = run.t_events[0][0], run.y_events[0][0]
            if x[0] > x[1] + 0.05:  # the swing leg ahead: heel strike, not a scuff
                break
            t0 = t + 1e-9
            x = solve_ivp(rhs, (t, t0), x, rtol=1e-11, atol=1e-12).y[:, -1]
        alpha = (x[0] - x[1]) / 2
        plus, minus = _goswami_Q(m, mH, a, b, alpha)
        w = np.array(plus.LUsolve(minus * sp.Matrix(x[2:])), float).ravel()
        return np.array([x[1], x[0], *w])

    def residual(z):  # z = [stance angle, swing rate, stance rate] after heel strike
        after = step(np.array([-2 * slope - z[0], z[0], z[1], z[2]]))
        return after[[1, 2, 3]] - z

    z = fsolve(residual, [0.3, -0.3, -1.3], xtol=1e-13)
    return np.array([z[0], -2 * slope - z[0], z[2], z[1]])  # [st, sw, st rate, sw rate]


def test_compass_gait_fixed_point_matches_goswamis_equations(compass_found):
    found = compass_found
    slope = float(compass_gait.VALUES[compass_gait.gamma])
    ours = found.state - np.array([slope, slope, 0, 0])
    theirs = _goswami_gait()
    assert np.allclose(ours, theirs, atol=1e-8), (ours, theirs)
    assert found.stable
    # the stable gait's eigenvalues: a complex pair inside the unit circle and one real
    assert sorted(abs(found.eigenvalues.imag))[-1] > 0.1
    assert np.all(abs(found.eigenvalues) < 1)


# ---- the simplest walker (Garcia, Chatterjee, Ruina and Coleman) ---------------------

def test_simplest_walker_heel_strike_is_garcias(biped):
    kane, _, solution, _ = biped
    H = simplest_walker.limit_map(solution, kane)
    c = sp.cos(2 * compass_gait.alpha)
    # theirs: thetadot+ = cos 2theta thetadot-, phidot+ = cos 2theta (1 - cos 2theta)
    # thetadot-, with phi = stance - swing angle: the swing rate after is cos^2 2theta
    # thetadot-, and neither depends on the swing rate before
    expected = sp.Matrix([[c, 0], [c * c, 0]])
    assert (H - expected).applyfunc(sp.simplify) == sp.zeros(2, 2)


def _garcia_gait(gamma=0.009):
    """The long-period gait from their scaled equations (transcribed), by SciPy."""
    def rhs(_t, x):
        th, ph, dth, dph = x
        ddth = math.sin(th - gamma)
        ddph = ddth + dth**2 * math.sin(ph) - math.cos(th - gamma) * math.sin(ph)
        return [dth, dph, ddth, ddph]

    def strike(_t, x):
        return x[1] - 2 * x[0]

    strike.terminal = True

    def step(z):
        th, dth = z
        c = math.cos(2 * th)
        x = [th, 2 * th, dth, c * (1 - c) * dth / c]  # just after heel strike
        t0 = 0.0
        while True:
            run = solve_ivp(rhs, (t0, t0 + 10), x, events=strike, rtol=1e-12, atol=1e-13,
                            method="DOP853")
            t, x = run.t_events[0][0], run.y_events[0][0]
            if x[0] < -0.05:  # past mid-stance: heel strike (not the scuff at phi = 0)
                break
            t0 = t + 1e-9
            x = solve_ivp(rhs, (t, t0), x, rtol=1e-12, atol=1e-13).y[:, -1]
        return np.array([-x[0], math.cos(2 * x[0]) * x[2]])

    return fsolve(lambda z: step(z) - z, [0.2, -0.2], xtol=1e-13)


def test_simplest_walker_gait_matches_garcias_equations(walker_found):
    found = walker_found
    theirs = _garcia_gait()
    assert found.state[0] == pytest.approx(theirs[0], abs=1e-6)
    assert found.state[2] == pytest.approx(theirs[1], abs=1e-6)
    assert found.stable
    # Garcia, Chatterjee, Ruina and Coleman's long-period gait at gamma = 0.009, as
    # published to 14 digits: [theta, thetadot] just after heel strike
    assert abs(found.state[0] - 0.20031090049483) < 1e-9
    assert abs(found.state[2] - -0.19983247291764) < 1e-9


# ---- McGeer's rimless wheel ----------------------------------------------------------

def test_rimless_wheel_ratio_and_roll(wheel):
    ratio, found = wheel
    alpha, l, r = rimless_wheel.alpha, rimless_wheel.l, rimless_wheel.r
    # angular momentum about the landing foot: (l^2 cos 2 alpha + r^2) / (l^2 + r^2)
    assert sp.simplify(ratio - (l**2 * sp.cos(2 * alpha) + r**2) / (l**2 + r**2)) == 0
    # energy over one step (the hub falls 2 l sin alpha sin gamma) with the landing's
    # factor cos 2 alpha: omega*^2 = cos^2 2a 4 (g/l) sin a sin g / (1 - cos^2 2a)
    a, g = math.pi / 8, 0.08
    expected = math.sqrt(math.cos(2 * a) ** 2 * 4 * 9.8 * math.sin(a) * math.sin(g)
                         / math.sin(2 * a) ** 2)
    assert -found.state[1] == pytest.approx(expected, rel=1e-9)
    assert found.eigenvalues[0].real == pytest.approx(math.cos(2 * a) ** 2, rel=1e-6)


# ---- the double pendulum on the floor: the laws ---------------------------------------

@pytest.fixture(scope="module")
def pendulum():
    return double_pendulum_floor.pendulum()


def _random_strikes(pendulum, law, count, seed):
    kane, N, tip = pendulum
    q1, q2 = kane.q
    u1, u2 = kane.u
    rng = random.Random(seed)
    e, mu = sp.Rational(rng.randint(0, 10), 10), sp.Rational(rng.randint(0, 10), 10)
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(
        tip, N.y, restitution=e, tangential="coulomb", friction=mu, law=law, name="tip")],
        frame=N)
    done = 0
    while done < count:
        at = {q1: sp.Float(rng.uniform(-1.2, 1.2), 30), q2: sp.Float(rng.uniform(-1.5, 1.5), 30),
              **double_pendulum_floor.VALUES}
        speeds = {u1: sp.Rational(rng.randint(-30, 30), 10),
                  u2: sp.Rational(rng.randint(-30, 30), 10)}
        numbers = hit.at(at)
        try:
            solved = numbers.at(speeds).solve()
        except InputError:  # not approaching: no impact
            continue
        done += 1
        yield numbers.at(speeds), solved, e


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
def test_double_pendulum_obeys_the_laws(pendulum, law):
    for strike, solved, e in _random_strikes(pendulum, law, 12, seed=hash(law) % 1000):
        u0, u1 = strike.u_before, solved.speeds_after
        P = sp.Matrix(solved.contact_impulse)
        # generalized impulse-momentum: M (u+ - u-) = J^T P
        assert np.allclose(np.array(strike.M * (u1 - u0), float),
                           np.array(strike.J.T * P, float), atol=1e-20)
        before, after = strike.J * u0, strike.J * u1
        assert float(P[0]) >= 0  # the floor only pushes
        course = solved.regime
        if law == "newton" or course in ("slip", "stick"):  # a straight path: Newton's e
            assert float(after[0]) == pytest.approx(float(-e * before[0]), abs=1e-20)
        lost = float(solved.energy_lost)
        if law != "newton":
            assert lost >= -1e-20, (law, course, lost)
        assert (lost < -1e-20) == any("created kinetic energy" in w for w in solved.warnings)


def test_newton_law_gain_is_said(pendulum):
    kane, N, tip = pendulum
    solved = double_pendulum_floor.strike("newton", kane, N, tip)
    assert float(solved.energy_lost) < 0
    assert any("created kinetic energy" in w for w in solved.warnings)
    for law in ("poisson", "energetic"):
        other = double_pendulum_floor.strike(law, kane, N, tip)
        assert float(other.energy_lost) > 0 and not other.warnings


@pytest.mark.parametrize("tangential", ["smooth", "stick"])
def test_two_link_arm_striking_a_wall_obeys_the_laws(pendulum, tangential):
    # the double pendulum as a two-link arm whose hand strikes a wall on its right
    # (normal -x): random configurations and rates, symbolic e
    kane, N, tip = pendulum
    q1, q2 = kane.q
    u1, u2 = kane.u
    e = sp.Symbol("e", nonnegative=True)
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(
        tip, -N.x, restitution=e, tangential=tangential, name="hand")], frame=N)
    rng, done = random.Random(11), 0
    while done < 8:
        at = {q1: sp.Rational(rng.randint(-12, 12), 10), q2: sp.Rational(rng.randint(-15, 15), 10),
              **double_pendulum_floor.VALUES}
        speeds = {u1: sp.Rational(rng.randint(-30, 30), 10),
                  u2: sp.Rational(rng.randint(-30, 30), 10)}
        strike = hit.at(at).at(speeds)
        v = strike.J * strike.u_before
        if not float(v[0]) < 0:
            continue  # the hand moves away from the wall: no impact
        done += 1
        solved = strike.solve()
        P = sp.Matrix(solved.contact_impulse)
        gap = strike.M * (solved.speeds_after - strike.u_before) - strike.J.T * P
        assert all(abs(float(x.subs(e, sp.Rational(1, 3)))) < 1e-12 for x in gap)
        after = strike.J * solved.speeds_after
        for value in (0, sp.Rational(1, 2), 1):
            assert float((after[0] + value * v[0]).subs(e, value)) == pytest.approx(
                0, abs=1e-12)  # Newton's e along the normal
            if tangential == "stick":
                assert float(after[1].subs(e, value)) == pytest.approx(0, abs=1e-12)
            # smooth, or plastic (e = 0) with stick, the impact cannot create energy;
            # stick with e > 0 can where W couples the normal and tangent (an algebraic
            # law, not a physical guarantee), so only those two are asserted
            if tangential == "smooth" or value == 0:
                assert float(solved.energy_lost.subs(e, value)) >= -1e-12


def test_two_link_arm_against_a_wall_matches_the_builtin_hinged_rod():
    # one link of a two-link arm: a uniform rod hinged at O swinging into a wall at its
    # tip; the same as rigidimpact's own pivoted rod striking a fixed wall
    q, u = me.dynamicsymbols("q u")
    M_, L, e = sp.Integer(3), sp.Integer(2), sp.Rational(2, 5)
    N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
    A.orient_axis(N, N.z, q)
    A.set_ang_vel(N, u * N.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    centre, tip = O.locatenew("c", -L / 2 * A.y), O.locatenew("tip", -L * A.y)
    centre.v2pt_theory(O, N, A)
    tip.v2pt_theory(O, N, A)
    rod = me.RigidBody("rod", centre, A, M_, (me.inertia(A, 0, 0, M_ * L**2 / 12), centre))
    kane = me.KanesMethod(N, [q], [u], [q.diff() - u])
    kane.kanes_equations([rod], [])
    # the wall on the right at the tip (q = 0): its normal points back, -x
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(tip, -N.x, restitution=e)],
                              frame=N).at({q: 0, u: 5})
    ours = hit.solve().speeds_after[0]
    builtin = ri.Impact(
        ri.Body.rigid(M_, M_ * L**2 / 12, (0, L / 2), (5 * L / 2, 0), 5, "rod",
                      pivot=(0, L)),
        ri.Body.fixed("wall"), ri.Contact(restitution=e)).solve().results()["rod.omega"]
    assert ours == builtin == -e * 5


# ---- bad input -----------------------------------------------------------------------

def test_bad_mechanics_input_is_one_clear_error(pendulum):
    kane, N, tip = pendulum
    fixed = me.Point("nail")
    fixed.set_vel(N, 0)
    with pytest.raises(InputError, match="does not depend on the system's speeds"):
        ri.mechanics.impact(kane, [ri.mechanics.contact(fixed, N.y)], frame=N)
    with pytest.raises(InputError, match="its velocity in N is not defined"):
        ri.mechanics.impact(kane, [ri.mechanics.contact(me.Point("loose"), N.y)], frame=N)
    with pytest.raises(InputError, match="normal: must not be the zero vector"):
        _ = ri.mechanics.impact(kane, [ri.mechanics.contact(tip, 0 * N.y)], frame=N).J
    bare = me.KanesMethod(N, kane.q, kane.u, [x.diff() - y for x, y in
                                                  zip(kane.q, kane.u, strict=True)])
    with pytest.raises(InputError, match="equations of motion are not formed yet: call "
                                         "kanes_equations"):
        ri.mechanics.impact(bare, [ri.mechanics.contact(tip, N.y)], frame=N)
    with pytest.raises(InputError, match="needs numbers for L_1"):
        ri.mechanics.flow_of(kane, {double_pendulum_floor.m1: 1, double_pendulum_floor.m2: 1,
                                    double_pendulum_floor.L2: 1})
    ball = ri.mechanics.Hybrid(lambda t, x: np.array([x[1], 1.0]), lambda x: x[0],
                               lambda x: x, max_step_time=2.0)
    with pytest.raises(InputError, match="no impact within 2 s"):
        ball.step(np.array([1.0, 0.0]))


# ---- the published examples print their keys ----------------------------------------

@pytest.mark.parametrize(("script", "keys"), [
    (rimless_wheel, {"speed_ratio", "omega_star"}),
    (simplest_walker, {"fixed_point", "eigenvalues"}),
    (compass_gait, {"impact_map", "fixed_point"}),
    (double_pendulum_floor, {"newton", "poisson", "energetic"}),
])
def test_examples_print_their_json_keys(capsys, monkeypatch, request, script, keys):
    # the contract is what each script prints: its derivation and its gait, checked
    # against the published numbers above, are read from those tests' fixtures, not
    # derived a second time in this process
    if script in (compass_gait, simplest_walker):
        kane, strike, solution, H = request.getfixturevalue("biped")
        found = request.getfixturevalue("compass_found" if script is compass_gait
                                        else "walker_found")
        monkeypatch.setattr(script, "heel_strike", lambda: (kane, strike, solution))
        if script is compass_gait:
            monkeypatch.setattr(script, "impact_map", lambda *_: H)
        monkeypatch.setattr(script, "gait", lambda *_, **__: found)
    if script is rimless_wheel:
        ratio, found = request.getfixturevalue("wheel")
        monkeypatch.setattr(script, "landing", lambda: (None, ratio))
        monkeypatch.setattr(script, "roll", lambda _: found)
    assert script.main(["--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert keys <= set(out)
    if script is rimless_wheel:
        assert out["speed_ratio"] == "cos(2*alpha)"
    if script is compass_gait:
        assert len(out["fixed_point"]) == 4
        H = sp.sympify(out["impact_map"])  # the contract: a sympy matrix string
        assert sp.Matrix(H).shape == (2, 2)


# ---- several contacts of a mechanics system, by the rules -------------------------------

def _free_planar_body(speeds: str):
    """A body free in the plane: its frame A turned by theta about N.z, its centre C at
    (x, y) moving at the first two `speeds`, its spin the third."""
    x, y, th = me.dynamicsymbols("x y theta")
    ux, uy, w = me.dynamicsymbols(speeds)
    N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
    A.orient_axis(N, N.z, th)
    A.set_ang_vel(N, w * N.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    C = O.locatenew("C", x * N.x + y * N.y)
    C.set_vel(N, ux * N.x + uy * N.y)
    return N, A, C, (x, y, th), (ux, uy, w)


def _flat_rod(restitution, tangential="smooth", friction=None, law="newton"):
    """A free rod (mass 1, half-length 1, inertia 1/3) as a sympy.physics.mechanics
    system in x, y, theta, with both ends on a floor: the shipped scenes rod-lands-flat
    and rod-slides-flat, stated the other way."""
    N, A, C, (x, y, th), (ux, uy, w) = _free_planar_body("u_x u_y w")
    ends = [C.locatenew(name, sign * A.x) for name, sign in (("L", -1), ("R", 1))]
    for end in ends:
        end.v2pt_theory(C, N, A)
    rod = me.RigidBody("rod", C, A, 1, (me.inertia(A, 0, 0, sp.Rational(1, 3)), C))
    kane = me.KanesMethod(N, [x, y, th], [ux, uy, w],
                          [x.diff() - ux, y.diff() - uy, th.diff() - w])
    kane.kanes_equations([rod], [])
    laws = dict(restitution=restitution, tangential=tangential, friction=friction, law=law)
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(ends[0], N.y, name="left", **laws),
                                     ri.mechanics.contact(ends[1], N.y, name="right", **laws)],
                              frame=N)
    return hit, (x, y, th), (ux, uy, w)


def _at(hit, q, u, speeds):
    return hit.at({q[0]: 0, q[1]: 0, q[2]: 0}).at(dict(zip(u, speeds, strict=True)))


def _scene(name, **values):
    from rigidimpact.scenes.scene import load_scene

    scene = load_scene(Path(__file__).resolve().parents[1] / "derivations" / f"{name}.toml")
    data = dict(scene.values)
    data.update({ri.symbol(k): v for k, v in values.items()})
    return scene.collision(data)


@pytest.mark.parametrize("spin", [sp.Rational(1, 2), 2])
def test_several_mechanics_contacts_match_the_built_in_shapes(spin):
    # rod-lands-flat (e = 1): at spin 1/2 both ends approach; at spin 2 the right end
    # recedes before, but the left end's impulse alone (3/2, by hand: W = 1 + 3) would
    # turn the rod to spin -5/2 and drive the right end down at 2, so it acts too and
    # leaves at rest. The built-in-shapes path (Collision, Lemke's method and its own
    # sequential steps) is the other engine.
    hit, q, u = _flat_rod(1)
    strike = _at(hit, q, u, (0, -1, spin))
    rod = ri.Body.rigid(1, sp.Rational(1, 3), (0, 0), (0, -1), spin, "rod")
    collision = ri.Collision((rod, ri.Body.fixed("floor")), _scene("rod-lands-flat").contacts)
    for rule in (ri.Simultaneous(), ri.Sequential(("left", "right")),
                 ri.Sequential(("right", "left"))):
        ours = strike.solve(rule)
        (theirs,) = collision.solve(rule)
        r = theirs.results()
        assert list(ours.speeds_after) == [r["rod.vx"], r["rod.vy"], r["rod.omega"]], rule
        for name in ("left", "right"):
            assert ours.impulses[name] == r[f"{name}.normal_impulse"], (rule, name)
        assert ours.energy_lost == theirs.energy_lost
    if spin == 2:
        ours = strike.solve()
        assert ours.acted == ("left", "right")
        assert (strike.J * ours.speeds_after)[2] == 0  # the right end at rest


def test_coulomb_at_several_mechanics_contacts_in_sequence():
    # rod-slides-flat (mu = 1/4, e = 1/2): each end's own impact by Routh's method in turn
    mu, e = sp.Rational(1, 4), sp.Rational(1, 2)
    hit, q, u = _flat_rod(e, "coulomb", mu)
    strike = _at(hit, q, u, (1, -1, 0))
    collision = _scene("rod-slides-flat")
    for order in (("left", "right"), ("right", "left")):
        ours = strike.solve(ri.Sequential(order))
        (theirs,) = collision.solve(ri.Sequential(order))
        r = theirs.results()
        assert list(ours.speeds_after) == [r["rod.vx"], r["rod.vy"], r["rod.omega"]]
        assert [ours.tangential[n] for n in order] == \
            [r[f"{n}.tangential_impulse"] for n in order]
    # acting together (it used to be refused): the built-in rule itself, Coulomb
    # friction at the velocity level, as for the built-in rod
    ours = strike.solve()
    (theirs,) = collision.solve(ri.Simultaneous())
    r = theirs.results()
    assert list(ours.speeds_after) == [r["rod.vx"], r["rod.vy"], r["rod.omega"]]
    assert ours.impulses == {n: r[f"{n}.normal_impulse"] for n in ("left", "right")}


def test_several_mechanics_contacts_with_symbols_state_when_all_act():
    # symbols: the case in which both ends approach and act, with the conditions that
    # make it the rule's answer; at spin 1/2 it is Lemke's answer above (vy = 1,
    # omega = -1/2). By hand: both ends approach while |s| <= 1, and then both push
    # ((1 + e)(3 + s)/6 and (1 + e)(3 - s)/6), so the conditions are -1 <= s <= 1
    e, spin = sp.Symbol("e", nonnegative=True), sp.Symbol("s")
    hit, q, u = _flat_rod(e)
    solved = _at(hit, q, u, (0, -1, spin)).solve()
    assert solved.acted == ("left", "right")
    for name, by_hand in (("left", (1 + e) * (3 + spin) / 6),
                          ("right", (1 + e) * (3 - spin) / 6)):
        assert sp.expand(solved.impulses[name] - by_hand) == 0, name
    values = {e: 1, spin: sp.Rational(1, 2)}
    assert [x.subs(values) for x in solved.speeds_after] == [0, 1, -sp.Rational(1, 2)]
    for s_, holds in ((sp.Rational(1, 2), True), (1, True), (-1, True), (2, False),
                      (sp.Rational(-11, 10), False)):
        assert all(bool(c.subs({e: sp.Rational(1, 3), spin: s_}))
                   for c in solved.conditions) is holds, s_


def test_several_mechanics_contacts_with_symbols_have_the_built_in_rods_cases():
    # the simultaneous rule with symbols is one implementation: the rod as a
    # sympy.physics.mechanics system and as a built-in shape give the same cases (the
    # acting ends, the speeds after and the impulses), each under the same conditions,
    # checked at seeded rational points of e and the spin
    e, spin = sp.Symbol("e", nonnegative=True), sp.Symbol("s")
    hit, q, u = _flat_rod(e)
    ours = _at(hit, q, u, (0, -1, spin)).cases()
    rod = ri.Body.rigid(1, sp.Rational(1, 3), (0, 0), (0, -1), spin, "rod")
    ends = tuple(replace(c, restitution=e) for c in _scene("rod-lands-flat").contacts)
    theirs = ri.Collision((rod, ri.Body.fixed("floor")), ends).simultaneous_cases()
    assert len(ours) == len(theirs) >= 3
    # each case is certified where it is the answer (its conditions), by both
    # sources: the spin given as an expression of s is drawn with s (it was left a
    # symbol, and the case went unchecked), and a case that needs a spin past
    # (3 + e)/(1 - e) is checked where the certificate's second round of points reaches
    for case in (*ours, *theirs):
        assert case.checks and max(case.checks.values()) < 1e-40, case.conditions
    rng = random.Random(44)
    for _ in range(40):
        point = {e: sp.Rational(rng.randint(0, 8), 8), spin: sp.Rational(rng.randint(-24, 24), 8)}
        held = [[c for c in cases if all(bool(x.subs(point)) for x in c.conditions)]
                for cases in (ours, theirs)]
        assert len(held[0]) >= 1 and len(held[1]) >= 1, point
        a, b = held[0][0], held[1][0]
        r = b.results()
        assert set(a.acted) == set(b.acted), point
        assert [x.subs(point) for x in a.speeds_after] == \
            [r[k].subs(point) for k in ("rod.vx", "rod.vy", "rod.omega")], point
        for name in ("left", "right"):
            assert a.impulses[name].subs(point) == r[f"{name}.normal_impulse"].subs(point)


# ---- a nonholonomic system: dependent speeds folded in ---------------------------------

def test_a_knife_edge_sleigh_striking_a_wall_matches_the_multiplier_solution():
    # a Chaplygin sleigh: a planar body whose centre C cannot move sideways (a knife
    # edge: -sin(theta) u1 + cos(theta) u2 = 0, u2 the dependent speed). Its corner D
    # strikes a wall (normal -x) with Newton's e. The independent check is the other
    # formulation, with the knife edge's impulsive reaction as an unknown multiplier:
    # M_all (u+ - u-) = J_n^T P + J_c^T L, J_c u+ = 0, J_n u+ = -e J_n u-.
    N, A, C, (x, y, th), (u1, u2, u3) = _free_planar_body("u1 u2 u3")
    m, inertia, a, b = sp.symbols("m I a b", positive=True)
    e = sp.Symbol("e", nonnegative=True)
    D = C.locatenew("D", a * A.x + b * A.y)
    D.v2pt_theory(C, N, A)
    kane = me.KanesMethod(N, [x, y, th], [u1, u3],
                          [x.diff() - u1, y.diff() - u2, th.diff() - u3], u_dependent=[u2],
                          velocity_constraints=[-sp.sin(th) * u1 + sp.cos(th) * u2])
    kane.kanes_equations([me.RigidBody("sleigh", C, A, m, (me.inertia(A, 0, 0, inertia), C))],
                         [])
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(D, -N.x, restitution=e)], frame=N)
    solved = hit.solve()
    assert solved.speeds_before == (u1, u3, u2)
    values = {m: 2, inertia: sp.Rational(1, 3), a: 1, b: sp.Rational(1, 2), e: sp.Rational(1, 2),
              th: sp.atan(sp.Rational(3, 4))}  # sin 3/5, cos 4/5
    s, c = sp.Rational(3, 5), sp.Rational(4, 5)
    before = {u1: 2, u3: sp.Rational(1, 5), u2: sp.Rational(3, 2)}  # u2 = tan(theta) u1
    ours = [sp.nsimplify(sp.simplify(x.xreplace(values).xreplace(before)))
            for x in solved.speeds_after]
    M_all = sp.diag(2, 2, sp.Rational(1, 3))  # over (u1, u2, u3)
    J_n = sp.Matrix([[-1, 0, 1 * s + sp.Rational(1, 2) * c]])  # -(v_D . x)
    J_c = sp.Matrix([[-s, c, 0]])
    U = sp.Matrix(sp.symbols("U1 U2 U3"))
    P, L = sp.symbols("P L")
    u_minus = sp.Matrix([2, sp.Rational(3, 2), sp.Rational(1, 5)])
    equations = list(M_all * (U - u_minus) - J_n.T * P - J_c.T * L)
    equations += [(J_c * U)[0], (J_n * U)[0] + sp.Rational(1, 2) * (J_n * u_minus)[0]]
    found = sp.solve(equations, [*U, P, L], dict=True)[0]
    assert ours == [found[U[0]], found[U[2]], found[U[1]]]  # in Kane's order u1, u3, u2
    assert sp.nsimplify(solved.impulses["contact"].xreplace(values).xreplace(before)) \
        == found[P]


@pytest.mark.parametrize("law", ["newton", "poisson", "energetic"])
def test_a_hinged_link_on_a_rough_floor_matches_the_built_in_rod(law):
    # one degree of freedom at the contact (W singular): Routh's method with slip and
    # approach stopping together. The same rod as tests/test_routh.py's hinged rod
    # (mass 1, length 2, hinge at (-1, sqrt 3), its end at O, spin -1), stated as a
    # KanesMethod system; the built-in shapes' answer is the other engine.
    q, w = me.dynamicsymbols("q w")
    N, A = me.ReferenceFrame("N"), me.ReferenceFrame("A")
    A.orient_axis(N, N.z, q)
    A.set_ang_vel(N, w * N.z)
    hinge = me.Point("hinge")
    hinge.set_vel(N, 0)
    centre, end = hinge.locatenew("C", A.x), hinge.locatenew("E", 2 * A.x)
    centre.v2pt_theory(hinge, N, A)
    end.v2pt_theory(hinge, N, A)
    kane = me.KanesMethod(N, [q], [w], [q.diff() - w])
    kane.kanes_equations([me.RigidBody("rod", centre, A, 1, (me.inertia(A, 0, 0, sp.Rational(1, 3)),
                                                              centre))], [])
    mu, e = sp.Rational(1, 10), sp.Rational(1, 2)
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(
        end, N.y, restitution=e, tangential="coulomb", friction=mu, law=law)], frame=N)
    ours = hit.at({q: -sp.pi / 3}).at({w: -1}).solve()
    rod = ri.Body.rod(1, 2, -sp.pi / 3, -1, (-sp.sqrt(3) / 2, -sp.Rational(1, 2)), -1, "rod",
                      pivot=(-1, sp.sqrt(3)))
    theirs = ri.Impact(rod, ri.Body.fixed("floor"),
                       ri.Contact((0, -1), e, "coulomb", law, friction=mu)).solve()
    assert ours.regime == theirs.regime == "slip-reversal"
    assert sp.simplify(ours.speeds_after[0] - theirs.after[0].spin) == 0
    for a, b in zip(ours.contact_impulse, theirs.contact_impulse, strict=True):
        assert sp.simplify(a - b) == 0


def test_both_ends_sticking_as_a_mechanics_system_match_the_built_in_shapes():
    # four conditions (Newton's e and no slip at each end) on three freedoms: consistent,
    # so the motion is fixed (by hand: vx = 0, vy = e, omega = -e w) and the impulses are
    # not unique, which a note says; the built-in shapes' rule is the other engine
    e, v, w = sp.Rational(1, 10), sp.Rational(7, 10), -sp.Rational(2, 5)
    hit, q, u = _flat_rod(e, "stick")
    ours = _at(hit, q, u, (v, -1, w)).solve()
    assert list(ours.speeds_after) == [0, e, -e * w]
    assert any("the impulses are not" in note for note in ours.notes)
    rod = ri.Body.rigid(1, sp.Rational(1, 3), (0, 0), (v, -1), w, "rod")
    contacts = tuple(ri.Contact((0, -1), e, "stick", name=name, bodies=("rod", "floor"),
                                point=(x, 0)) for name, x in (("left", -1), ("right", 1)))
    (theirs,) = ri.Collision((rod, ri.Body.fixed("floor")), contacts).solve(ri.Simultaneous())
    r = theirs.results()
    assert list(ours.speeds_after) == [r["rod.vx"], r["rod.vy"], r["rod.omega"]]
    assert [ours.impulses[n] for n in ("left", "right")] == \
        [r["left.normal_impulse"], r["right.normal_impulse"]]


def _rod_both_ways(rng):
    """A seeded flat rod landing on both ends: as a KanesMethod system and as the
    built-in shapes, with one law at both ends and a rule (the same data each way)."""
    R = sp.Rational
    e = R(rng.randint(0, 4), 4)
    tangential = rng.choice(["smooth", "coulomb", "coulomb", "stick"])
    mu = R(rng.randint(1, 8), 8) if tangential == "coulomb" else None
    law = rng.choice(["newton", "newton", "poisson", "energetic"]) \
        if tangential != "stick" else "newton"
    v = (R(rng.randint(-8, 8), 4), R(rng.randint(-8, -1), 4), R(rng.randint(-8, 8), 4))
    rule = rng.choice([ri.Simultaneous(), ri.Sequential(("left", "right")), ri.Driven()])
    hit, q, u = _flat_rod(e, tangential, mu, law)
    rod = ri.Body.rigid(1, R(1, 3), (0, 0), v[:2], v[2], "rod")
    contacts = tuple(ri.Contact((0, -1), e, tangential, law, name=name,
                                bodies=("rod", "floor"), point=(x, 0), friction=mu)
                     for name, x in (("left", -1), ("right", 1)))
    return _at(hit, q, u, v), ri.Collision((rod, ri.Body.fixed("floor")), contacts), rule


def _answer(solve, *args):
    try:
        return solve(*args)
    except ri.InputError as refusal:
        return f"refused: {refusal.field}"


@pytest.mark.parametrize("count", [24, pytest.param(120, marks=pytest.mark.slow)])
def test_a_seeded_rod_gets_one_answer_as_a_system_and_as_built_in_shapes(count):
    # every rule, law and tangential law: the two sources give the same speeds, or both
    # refuse. Found by this search and mended: an energetic law with one contact acting
    # was refused by the bridge only; the driven rule's integrated answer was refused by
    # the bridge's exact tolerance; a sequential run cut at the certificate's own line
    # (e = 0, ringing) was refused by the built-in shapes' certificate
    rng = random.Random(44)
    compared = 0
    for _ in range(count):
        system, shapes, rule = _rod_both_ways(rng)
        ours = _answer(system.solve, rule)
        theirs = _answer(lambda s, r: s.solve(r)[0], shapes, rule)
        assert isinstance(ours, str) == isinstance(theirs, str), (rule.name, ours, theirs)
        if isinstance(ours, str):
            continue
        r = theirs.results()
        for mine, other in zip(ours.speeds_after, (r["rod.vx"], r["rod.vy"], r["rod.omega"]),
                               strict=True):
            assert abs(float(mine - other)) < 1e-9, (rule.name, ours.speeds_after, r)
        compared += 1
    assert compared >= count // 2
