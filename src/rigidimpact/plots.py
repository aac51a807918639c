"""Figures of the paper's results. Each function returns its Figure and never shows it.

Examples
--------
>>> fig = omega_vs_theta(e_values=(0, 1), mass_ratios=(1,))
>>> fig.axes[0].get_xlabel()
'initial angle $\\\\theta$ (degrees)'
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib

matplotlib.use("Agg")  # files only: no screen is assumed

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from rigidimpact.notation import symbol  # noqa: E402
from rigidimpact.problems import derive  # noqa: E402

__all__ = ["omega_vs_theta", "energy_loss_vs_theta", "FIGSIZE", "DPI"]

FIGSIZE = (8.0, 4.0)
DPI = 100

m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))


def _curve(key: str):
    expr = derive("barbell").results[key]
    return sp.lambdify((m, M, L, theta, e, v_ix), expr, "numpy")


def _against_theta(key: str, e_values: Sequence[float], mass_ratios: Sequence[float],
                   ylabel: str, title: str) -> tuple[Figure, plt.Axes]:
    """One line of a barbell result against the initial angle per (e, M/m); m = L = v_ix = 1."""
    curve = _curve(key)
    degrees = np.linspace(0.0, 180.0, 361)
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    for ratio in mass_ratios:
        for ev in e_values:
            ax.plot(degrees, curve(1.0, ratio, 1.0, np.radians(degrees), ev, 1.0),
                    label=f"e = {ev:g}, M/m = {ratio:g}")
    ax.set_xlabel(r"initial angle $\theta$ (degrees)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.set_xticks(range(0, 181, 30))
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3)
    return fig, ax


def omega_vs_theta(e_values: Sequence[float] = (0.0, 0.5, 1.0),
                   mass_ratios: Sequence[float] = (0.5, 2.0)) -> Figure:
    """Barbell spin after the impact, omega_z L / v_ix, against the initial angle.

    One line per restitution e and barbell-to-ball mass ratio M/m (eq. 5).
    """
    fig, _ = _against_theta("omega_z", e_values, mass_ratios,
                            r"$\omega_z L / v_{ix}$ (dimensionless)",
                            "Barbell spin after the impact (Mungan eq. 5)")
    fig.tight_layout()
    return fig


def energy_loss_vs_theta(e_values: Sequence[float] = (0.0, 0.5, 0.9),
                         mass_ratios: Sequence[float] = (0.5, 2.0)) -> Figure:
    """Fraction of kinetic energy lost (eq. 7) against the initial angle; least at 90."""
    fig, ax = _against_theta("energy_loss_fraction", e_values, mass_ratios,
                             r"$\Delta K_{\mathrm{lost}} / K_i$ (fraction)",
                             "Kinetic energy lost (Mungan eq. 7): least at 90 degrees")
    ax.axvline(90.0, color="grey", lw=0.8, ls=":")
    ax.set_ylim(bottom=0.0)
    fig.tight_layout()
    return fig
