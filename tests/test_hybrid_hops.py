"""A hybrid run finds every impact, however short the hop before it, or says it cannot.

Reproduces a double pendulum whose tip bounces on a floor (e = 1/2) under gravity: each
hop halves, and the steps of the flow came to stride over one, so the tip sank 0.39 m
into the floor with no word (the run said it had made its impacts). The flow's steps are
now shortened where the gap is found negative past rounding, and the run ends at the
pile-up; an impact map that gives no finite state is refused in one line.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri


def _bouncing_pendulum(e: float = 0.5):
    q1, q2, u1, u2 = me.dynamicsymbols("q1 q2 u1 u2")
    m1, m2, l1, l2, g = sp.symbols("m_1 m_2 l_1 l_2 g", positive=True)
    N, A, B = (me.ReferenceFrame(n) for n in "NAB")
    A.orient_axis(N, N.z, q1)
    B.orient_axis(N, N.z, q2)
    A.set_ang_vel(N, u1 * N.z)
    B.set_ang_vel(N, u2 * N.z)
    pivot = me.Point("O")
    pivot.set_vel(N, 0)
    P1 = pivot.locatenew("P1", -l1 * A.y)
    P1.v2pt_theory(pivot, N, A)
    P2 = P1.locatenew("P2", -l2 * B.y)
    P2.v2pt_theory(P1, N, B)
    kane = me.KanesMethod(N, [q1, q2], [u1, u2], [q1.diff() - u1, q2.diff() - u2])
    kane.kanes_equations([me.Particle("b1", P1, m1), me.Particle("b2", P2, m2)],
                         [(P1, -m1 * g * N.y), (P2, -m2 * g * N.y)])
    constants = {m1: 1.0, m2: 2.0, l1: 1.0, l2: 1.0, g: 9.81}
    hit = ri.mechanics.impact(kane, [ri.mechanics.contact(
        P2, N.y, restitution=sp.Rational(e).limit_denominator(100), name="floor")], frame=N)
    kernel = hit.kernel(constants)

    def gap(x):  # the floor 1.6 below the pivot
        return 1.6 - np.cos(x[0]) - np.cos(x[1])

    def jump(x):
        found = kernel(np.array([x[:2]]), np.array([x[2:]]))
        return np.concatenate([x[:2], found.speeds_after[0]])

    def rising(x):
        return np.sin(x[0]) * x[2] + np.sin(x[1]) * x[3] < 0

    return ri.mechanics.Hybrid(ri.mechanics.flow_of(kane, constants), gap, jump,
                               guard=rising), gap


def _lowest(walk, gap) -> float:
    return min(min(gap(s[:, k]) for k in range(s.shape[1])) for s in walk.states)


def test_the_reported_pendulum_never_sinks_into_the_floor_and_stops_at_the_pile_up():
    biped, gap = _bouncing_pendulum()
    walk = biped.simulate(np.array([1.2, 0.3, 0.0, 0.0]), impacts=200, until=6.0)
    assert _lowest(walk, gap) > -1e-9  # it sank 0.39 m before
    assert walk.stopped == "zeno"
    # the hops shrink by the restitution, so the rest of them sum to the last times
    # r / (1 - r): the accumulation lies past the last impact by about the last interval
    last = np.diff(walk.impact_times)[-1]
    assert walk.impact_times[-1] < walk.accumulation < walk.impact_times[-1] + 2 * last


@pytest.mark.parametrize("seed", range(4))
def test_a_seeded_family_of_bouncing_pendulums_stays_above_the_floor_or_says_why(seed):
    # each run stays above the floor (past rounding) to its end, or is refused in one
    # line: where the bounces pile up and the tip then stays on the floor sliding (seed
    # 3: the intervals shrink by 0.343 each), a flow between impacts cannot go on
    draw = np.random.default_rng(seed)
    e = float(draw.uniform(0.3, 0.8))
    biped, gap = _bouncing_pendulum(e)
    start = np.array([draw.uniform(0.9, 1.3), draw.uniform(-0.4, 0.4), 0.0, 0.0])
    assert gap(start) > 0
    try:
        walk = biped.simulate(start, impacts=60, until=4.0)
    except ri.InputError as refusal:
        assert "piling up" in str(refusal) and "\n" not in str(refusal), str(refusal)
        return
    assert _lowest(walk, gap) > -1e-9, (seed, e, start)
    assert walk.stopped in ("zeno", "impacts", "time")


def test_an_impact_map_that_gives_no_number_is_refused_in_one_line():
    ball = ri.mechanics.Hybrid(lambda t, x: np.array([x[1], -1.0]), lambda x: x[0],
                               lambda x: np.array([0.0, np.nan]))
    with pytest.raises(ri.InputError, match="no finite state at t = 1.41421"):
        ball.simulate(np.array([1.0, 0.0]), impacts=3)
