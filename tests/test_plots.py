"""Section 1's figures speak of one mass ratio, m/M: the ball's mass over one sphere's."""

from __future__ import annotations

import re

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from rigidimpact.outputs import plots  # noqa: E402


def _f(ratio: float, theta: np.ndarray, e: float) -> np.ndarray:
    """Mungan's eq. (5), written here by hand: f = (e + 1) m / [2M + m (1 + sin^2 theta)],
    at m = 1 and M = m / ratio."""
    m, big = 1.0, 1.0 / ratio
    return (e + 1) * m / (2 * big + m * (1 + np.sin(theta) ** 2))


def _spin(ratio: float, theta: np.ndarray, e: float) -> np.ndarray:
    """Eq. (5): omega_z = f sin(theta) v_ix / L, with L = v_ix = 1."""
    return _f(ratio, theta, e) * np.sin(theta)


def _loss(ratio: float, theta: np.ndarray, e: float) -> np.ndarray:
    """Eq. (7): (1 - e^2) / (1 + m (1 + sin^2 theta) / 2M), at M = m / ratio."""
    return (1 - e**2) / (1 + ratio / 2 * (1 + np.sin(theta) ** 2))


def _stuck(ratio: float, theta: np.ndarray) -> np.ndarray:
    """Eq. (10): omega_z = m sin(theta) v_ix / (2 (M + m) L), at M = m / ratio."""
    return np.sin(theta) / (2 * (1.0 / ratio + 1.0))


LABEL = re.compile(r"e = (?P<e>[\d.]+), m/M = (?P<ratio>[\d.]+)$")


def _curves(fig) -> list:
    """The figure's labelled lines (matplotlib names an unlabelled one ``_child...``)."""
    return [line for line in fig.axes[0].get_lines() if not line.get_label().startswith("_")]


@pytest.mark.parametrize(("draw", "expected"), [
    (plots.omega_vs_theta, _spin), (plots.energy_loss_vs_theta, _loss)])
def test_each_curve_labelled_m_over_M_is_the_papers_at_M_equal_m_over_that_ratio(
        draw, expected):
    fig = draw(e_values=(0.0, 0.5), mass_ratios=(4.0, 0.25))
    lines = _curves(fig)
    labels = [line.get_label() for line in lines]
    assert fig.axes[0].get_legend() is not None
    assert labels == ["e = 0, m/M = 4", "e = 0.5, m/M = 4",
                      "e = 0, m/M = 0.25", "e = 0.5, m/M = 0.25"]
    for line in lines:
        found = LABEL.match(line.get_label())
        degrees, values = line.get_data()
        want = expected(float(found["ratio"]), np.radians(degrees), float(found["e"]))
        np.testing.assert_allclose(values, want, rtol=1e-12, atol=1e-15)


def test_the_default_curves_are_the_former_ones_read_as_m_over_M():
    # M/m = 0.5 and 2 before are m/M = 2 and 0.5 now, in the same order (colours)
    for draw in (plots.omega_vs_theta, plots.energy_loss_vs_theta):
        labels = [line.get_label() for line in _curves(draw())]
        assert all("M/m" not in label for label in labels)
        assert [label.split("m/M = ")[1] for label in labels[::3]] == ["2", "0.5"]
    # a light barbell (m/M = 2) head on at 90 degrees and e = 0 spins at f = 1/3, by hand:
    # f = 1 / (2 * 0.5 + 1 * (1 + 1))
    spin = plots.omega_vs_theta(e_values=(0.0,), mass_ratios=(2.0,)).axes[0].get_lines()[0]
    degrees, values = spin.get_data()
    assert values[list(degrees).index(90.0)] == pytest.approx(1 / 3, rel=1e-14)


def test_the_clay_ball_and_its_bounce_are_labelled_m_over_M_and_meet_at_90_degrees():
    lines = _curves(plots.sticking_vs_bouncing((3.0, 0.5)))
    labels = [line.get_label() for line in lines]
    assert labels == ["sticks, m/M = 3", "bounces with e = 0, m/M = 3",
                      "sticks, m/M = 0.5", "bounces with e = 0, m/M = 0.5"]
    for stick, bounce, ratio in ((lines[0], lines[1], 3.0), (lines[2], lines[3], 0.5)):
        degrees, values = stick.get_data()
        np.testing.assert_allclose(values, _stuck(ratio, np.radians(degrees)), rtol=1e-12,
                                   atol=1e-15)
        degrees, values = bounce.get_data()
        np.testing.assert_allclose(values, _spin(ratio, np.radians(degrees), 0.0),
                                   rtol=1e-12, atol=1e-15)
        at = list(degrees).index(90.0)
        assert stick.get_data()[1][at] == pytest.approx(values[at], rel=1e-14)
