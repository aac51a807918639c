"""The published results of Mungan, Eur. J. Phys. 28 (2007) 563-568, as data.

Each :class:`Reference` is typed in from the paper, in the paper's own arrangement
(the f of eq. 5 left as the paper defines it, eq. 7 with its ``m/2M``), and carries
the equation number it comes from. Nothing here is produced by the solver: these are
what the solver's output is checked against.

Examples
--------
>>> REFERENCES["barbell.V_x"].paper
'(5)'
>>> REFERENCES["sticking.h"].expr
L*m/(2*M + m)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import sympy as sp

from rigidimpact.symbolic.notation import symbol

__all__ = ["Reference", "REFERENCES", "F", "CRITICAL_ANGLE_EQUATION"]

m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))
v_fx, V_x, omega_z, u_x = (symbol(n) for n in ("v_fx", "V_x", "omega_z", "u_x"))
V_1ix, V_2ix = symbol("V_1ix"), symbol("V_2ix")


@dataclass(frozen=True)
class Reference:
    """One result of the paper.

    Parameters
    ----------
    id : str
        ``PROBLEM.KEY`` or a name for a relation.
    paper : str
        Equation number, ``"(5)"``, or the section for a claim made in the text.
    statement : str
        What it says, in our words.
    expr : sympy.Expr
        The value (or, for an equation, ``lhs - rhs``).
    """

    id: str
    paper: str
    statement: str
    expr: sp.Expr


# eq. (5): f = (e + 1) m / [2M + m (1 + sin^2 theta)]
F = (e + 1) * m / (2 * M + m * (1 + sp.sin(theta) ** 2))

_h = m * L / (2 * M + m)  # section 2, the offset of S from C along the bar

# section 2: tan(theta_c) = 1/(pi - theta_c), written as lhs - rhs in theta
CRITICAL_ANGLE_EQUATION = sp.tan(theta) - 1 / (sp.pi - theta)

_REFERENCES = (
    Reference("barbell.eq1", "(1)", "momentum: m v_ix = 2M V_x + m v_fx",
              m * v_ix - (2 * M * V_x + m * v_fx)),
    Reference("barbell.eq2", "(2)", "barbell's angular momentum about O stays zero",
              2 * M * L**2 * omega_z - 2 * M * V_x * L * sp.sin(theta)),
    Reference("barbell.eq4", "(4)", "restitution at O: V_x + omega L sin(theta) - v_fx = e v_ix",
              V_x + omega_z * L * sp.sin(theta) - v_fx - e * v_ix),
    Reference("barbell.f", "(5)", "the dimensionless ratio f", F),
    Reference("barbell.v_fx", "(5)", "ball after: (m - 2Mf)/m v_ix", (m - 2 * M * F) / m * v_ix),
    Reference("barbell.V_x", "(5)", "barbell centre after: f v_ix", F * v_ix),
    Reference("barbell.omega_z", "(5)", "barbell spin after: f sin(theta)/L v_ix",
              F * sp.sin(theta) / L * v_ix),
    Reference("barbell.energy_loss_fraction", "(7)",
              "fraction of kinetic energy lost: (1 - e^2)/(1 + m(1 + sin^2)/2M)",
              (1 - e**2) / (1 + m / (2 * M) * (1 + sp.sin(theta) ** 2))),
    Reference("barbell.theta0.e0", "(5), section 1",
              "head on and perfectly inelastic: v_fx = V_x = m v_ix/(2M + m)",
              m * v_ix / (2 * M + m)),
    Reference("barbell.theta0.e1.v_fx", "(5), section 1, ref. [6]",
              "head on and elastic: the 1-D textbook result for m striking 2M at rest",
              (m - 2 * M) / (m + 2 * M) * v_ix),
    Reference("barbell.theta0.e1.V_x", "(5), section 1, ref. [6]",
              "head on and elastic: the 1-D textbook result for m striking 2M at rest",
              2 * m / (m + 2 * M) * v_ix),
    Reference("barbell.theta90.e0.v_fx", "section 2",
              "at 90 degrees with e = 0 the ball leaves at twice V_x", 2 * F.subs(
                  {theta: sp.pi / 2, e: 0}) * v_ix),
    Reference("sticking.h", "section 2", "S lies h = mL/(2M + m) from C toward A", _h),
    Reference("sticking.eq8", "(8)", "momentum: m v_ix = (2M + m) u_x",
              m * v_ix - (2 * M + m) * u_x),
    Reference("sticking.eq9", "(9)", "omega (L + h) = u_x sin(theta)",
              omega_z * (L + _h) - u_x * sp.sin(theta)),
    Reference("sticking.u_x", "(10)", "centre of mass after: m v_ix/(2M + m)",
              m / (2 * M + m) * v_ix),
    Reference("sticking.omega_z", "(10)", "spin after: m sin(theta) v_ix / (2(M + m) L)",
              m * sp.sin(theta) / (2 * (M + m) * L) * v_ix),
    Reference("discs.V_1fx", "(16)", "((1 - e) V_1ix + (1 + e) V_2ix)/2",
              ((1 - e) * V_1ix + (1 + e) * V_2ix) / 2),
    Reference("discs.V_2fx", "(16), subscripts swapped", "((1 - e) V_2ix + (1 + e) V_1ix)/2",
              ((1 - e) * V_2ix + (1 + e) * V_1ix) / 2),
    Reference("critical.equation", "section 2", "tan(theta_c) = 1/(pi - theta_c)",
              CRITICAL_ANGLE_EQUATION),
)

REFERENCES: Mapping[str, Reference] = MappingProxyType({r.id: r for r in _REFERENCES})
