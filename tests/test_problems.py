"""The built-in problems against the paper's equations (typed in independently here)."""

from __future__ import annotations

import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.paper.problems import derive, sphere_a_velocity, sticking_routes
from rigidimpact.solve.impact import Impact
from rigidimpact.symbolic.notation import symbol

m, M, L, theta, e, v = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
f_paper = (e + 1) * m / (2 * M + m * (1 + sp.sin(theta) ** 2))  # Mungan eq. (5)


def _zero(expr) -> bool:
    return sp.simplify(expr) == 0


def test_barbell_matches_eq_5():
    r = derive("barbell").results
    assert _zero(r["V_x"] - f_paper * v)
    assert _zero(r["omega_z"] - f_paper * sp.sin(theta) / L * v)
    assert _zero(r["v_fx"] - (m - 2 * M * f_paper) / m * v)


def test_barbell_f_is_named_and_e_eliminated():
    d = derive("barbell")
    f = symbol("f")
    assert d.named["V_x"] == f * v
    assert all(not expr.has(e) for expr in d.named.values())


def test_energy_loss_is_eq_7_and_bounded():
    loss = derive("barbell").results["energy_loss_fraction"]
    assert _zero(loss - (1 - e**2) / (1 + m / (2 * M) * (1 + sp.sin(theta) ** 2)))
    # a law it must obey: 0 <= loss <= 1 for 0 <= e <= 1 (checked on a seeded grid)
    for ev in (0, sp.Rational(1, 3), 1):
        for th in (0, sp.pi / 7, sp.pi / 2, 2):
            value = loss.subs({e: ev, theta: th, m: 3, M: sp.Rational(1, 2)})
            assert 0 <= value <= 1


def test_sphere_a_moves_in_minus_y_below_90_degrees():
    vy = sphere_a_velocity()[1]
    for th in (sp.pi / 12, sp.pi / 4, sp.pi / 3):
        assert vy.subs({theta: th, m: 1, M: 1, L: 1, e: sp.Rational(1, 2), v: 1}) < 0
    for th in (2 * sp.pi / 3, 3 * sp.pi / 4):  # and +y beyond 90 degrees
        assert vy.subs({theta: th, m: 1, M: 1, L: 1, e: sp.Rational(1, 2), v: 1}) > 0


def test_sticking_routes_agree_with_eq_10():
    u_paper = m / (2 * M + m) * v
    w_paper = m * sp.sin(theta) / (2 * (M + m) * L) * v
    for route in sticking_routes().values():
        assert _zero(route["u_x"] - u_paper)
        assert _zero(route["omega_z"] - w_paper)


def test_discs_match_eq_16_and_swap_subscripts():
    r = derive("discs").results
    v1, v2 = symbol("V_1ix"), symbol("V_2ix")
    assert _zero(r["V_1fx"] - ((1 - e) * v1 + (1 + e) * v2) / 2)
    assert _zero(r["V_2fx"] - r["V_1fx"].subs({v1: v2, v2: v1}, simultaneous=True))


def test_two_body_impulse_is_the_textbook_formula():
    # independent: J = (1 + e) v_approach / (1/m1 + 1/m2 + R1y^2/I1 + R2y^2/I2)
    d = derive("two-body")
    s = {n: symbol(n) for n in ("m_1", "m_2", "I_1", "I_2", "R_1y", "R_2y", "V_1ix", "V_2ix",
                                "omega_1iz", "omega_2iz")}
    approach = (s["V_1ix"] + s["omega_1iz"] * s["R_1y"]) - (s["V_2ix"] + s["omega_2iz"] * s["R_2y"])
    textbook = (1 + e) * approach / (1 / s["m_1"] + 1 / s["m_2"] + s["R_1y"] ** 2 / s["I_1"]
                                     + s["R_2y"] ** 2 / s["I_2"])
    assert _zero(d.definitions["J"] - textbook)


def test_numeric_mode_agrees_with_the_exact_solution():
    # an all-number scene with a transcendental angle is solved in 50-digit floats
    angle = sp.Rational(37, 100)
    ball = Body.particle(2, (3, 0), "ball")
    bar = Body.barbell(sp.Rational(1, 2), sp.Rational(3, 4), angle)
    impact = Impact(ball, bar, Contact(restitution=sp.Rational(2, 5)))
    assert impact.numeric
    numeric = impact.solve().results()
    exact = derive("barbell").results
    at = {m: 2, M: sp.Rational(1, 2), L: sp.Rational(3, 4), theta: angle, e: sp.Rational(2, 5),
          v: 3}
    for key, ours in (("v_fx", "ball.vx"), ("V_x", "barbell.vx"), ("omega_z", "barbell.omega")):
        assert abs(sp.N(exact[key].subs(at), 50) - numeric[ours]) < 1e-45
