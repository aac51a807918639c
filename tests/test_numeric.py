"""Float64 kernels: stable forms, and the naive forms they replace failing where they pass."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from rigidimpact.paper.problems import derive
from rigidimpact.symbolic.notation import symbol
from rigidimpact.symbolic.numeric import Kernel, evaluate, magnitude, stable_form

m, M, L, theta, e, v = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
KERNELS = {k: Kernel.from_expr(x) for k, x in derive("barbell").results.items()}


def _rel(value: float, exact: mpmath.mpf) -> float:
    with mpmath.workdps(50):
        return float(abs(mpmath.mpf(value) - exact) / abs(exact))


def test_naive_eq_5_loses_digits_where_the_stable_kernel_does_not():
    # m << M, e = 0, head on: v_fx = m v/(2M + m) is tiny and (m - 2Mf)/m cancels
    values = {"m": 1.0, "M": 1e12, "L": 1.0, "theta": 0.0, "e": 0.0, "v_ix": 1.0}
    f = values["m"] * (values["e"] + 1) / (2 * values["M"] + values["m"]
                                           * (1 + math.sin(values["theta"]) ** 2))
    naive = (values["m"] - 2 * values["M"] * f) / values["m"] * values["v_ix"]
    exact = KERNELS["v_fx"].reference(50, **values)
    assert _rel(naive, exact) > 1e-6  # the paper's arrangement, read literally
    assert _rel(float(KERNELS["v_fx"](**values)), exact) < 1e-15


def test_naive_energy_loss_fails_near_elastic():
    # K_i - K_f from the velocities cancels as e -> 1; the closed form does not
    values = {"m": 1.0, "M": 0.7, "L": 1.0, "theta": 0.4, "e": 1 - 1e-12, "v_ix": 1.0}
    k = {key: float(KERNELS[key](**values)) for key in ("v_fx", "V_x", "omega_z")}
    before = 0.5 * values["m"] * values["v_ix"] ** 2
    after = 0.5 * (values["m"] * k["v_fx"] ** 2 + 2 * values["M"] * k["V_x"] ** 2
                   + 2 * values["M"] * values["L"] ** 2 * k["omega_z"] ** 2)
    naive = (before - after) / before
    exact = KERNELS["energy_loss_fraction"].reference(50, **values)
    assert _rel(naive, exact) > 1e-5
    assert _rel(float(KERNELS["energy_loss_fraction"](**values)), exact) < 1e-15


def test_stable_form_rewrites():
    x = sp.Symbol("x", real=True)
    assert stable_form(1 - e**2) == (1 - e) * (1 + e)
    assert stable_form(m - m * sp.sin(x) ** 2) == m * sp.cos(x) ** 2
    assert stable_form(2 * M + m * sp.sin(x) ** 2 + m) == 2 * M + m * sp.sin(x) ** 2 + m


def test_magnitude_of_v_fx_is_the_issue_scale():
    s2 = sp.sin(theta) ** 2
    scale = v * (m * (1 + s2) + 2 * M * e) / (2 * M + m * (1 + s2))
    assert sp.simplify(magnitude(derive("barbell").results["v_fx"]) - scale) == 0


def test_kernels_are_vectorised():
    thetas = np.linspace(0, math.pi, 7)
    out = KERNELS["omega_z"](m=1.0, M=2.0, L=0.5, theta=thetas, e=0.5, v_ix=1.0)
    assert out.shape == (7,)
    assert np.allclose(out, [float(KERNELS["omega_z"](m=1.0, M=2.0, L=0.5, theta=t, e=0.5,
                                                      v_ix=1.0)) for t in thetas], rtol=0)


def test_evaluate_mpmath_keeps_exact_inputs():
    values = {"m": 1, "M": 2, "L": 1, "theta": sp.pi / 6, "e": sp.Rational(1, 2), "v_ix": 1}
    out = evaluate(derive("barbell").results, values, dps=40)
    with mpmath.workdps(40):
        assert abs(out["v_fx"] + mpmath.mpf(1) / 7) < mpmath.mpf(10) ** -38


positive = st.floats(1e-6, 1e6)
angle = st.floats(0.0, math.pi)
restitution = st.floats(0.0, 1.0)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(m=positive, M=positive, L=positive, theta=angle, e=restitution, v_ix=positive)
def test_barbell_kernels_obey_the_laws(m, M, L, theta, e, v_ix):
    k = {key: float(KERNELS[key](m=m, M=M, L=L, theta=theta, e=e, v_ix=v_ix))
         for key in KERNELS}
    tol = 1e-12
    # momentum (1): the balance holds to rounding of its largest term
    scale = m * v_ix + 2 * M * abs(k["V_x"]) + m * abs(k["v_fx"])
    assert abs(m * v_ix - 2 * M * k["V_x"] - m * k["v_fx"]) <= tol * scale
    # angular momentum of the barbell about O (2)
    lhs, rhs = L * k["omega_z"], k["V_x"] * math.sin(theta)
    assert abs(lhs - rhs) <= tol * max(abs(lhs), abs(rhs), 1e-300)
    # restitution (4)
    rel = k["V_x"] + k["omega_z"] * L * math.sin(theta) - k["v_fx"]
    assert abs(rel - e * v_ix) <= tol * (abs(k["V_x"]) + abs(k["omega_z"] * L) + abs(k["v_fx"])
                                         + e * v_ix)
    # energy is not created, and not more than all of it is lost
    assert -1e-15 <= k["energy_loss_fraction"] <= 1 + 1e-15


@settings(max_examples=100, deadline=None, derandomize=True)
@given(m=positive, M=positive, L=positive, theta=st.floats(0.0, math.pi / 2),
       e=restitution)
def test_barbell_is_symmetric_under_theta_to_pi_minus_theta(m, M, L, theta, e):
    # the results depend on sin(theta) only (eqs. 5, 7); pi - theta is formed at 50 digits,
    # since float64 cannot represent it exactly
    with mpmath.workdps(50):
        mirrored = mpmath.pi - mpmath.mpf(theta)
    for key in ("v_fx", "V_x", "omega_z", "energy_loss_fraction"):
        a = KERNELS[key].mp(50, m=m, M=M, L=L, theta=theta, e=e, v_ix=1.0)
        b = KERNELS[key].mp(50, m=m, M=M, L=L, theta=mirrored, e=e, v_ix=1.0)
        with mpmath.workdps(50):
            assert abs(a - b) <= mpmath.mpf(10) ** -40 * max(abs(a), abs(b), 1)
