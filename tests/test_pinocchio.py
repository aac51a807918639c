"""The impact maps of sympy.physics.mechanics systems held against Pinocchio's
``impulseDynamics`` (derivations/beside_pinocchio.py builds both sides): the same physics
written two ways, rigidimpact from the system's mass matrix and partial velocities,
Pinocchio from its own joint tree (relative angles, bodies placed in their parents'
frames); the speeds after agree to rounding once the coordinates are mapped. Pinocchio
is a peer (`make peers`); without it these tests skip.
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

pytest.importorskip("pinocchio")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "derivations"))
import beside_pinocchio as peer  # noqa: E402

LINKS = 5


def test_a_chain_of_five_struck_at_its_tip_agrees_with_pinocchio():
    system, q, u = peer.chain_in_sympy(LINKS)
    model, tip = peer.chain_in_pinocchio(LINKS)
    rng = random.Random(45)
    for _ in range(6):
        angles, rates = peer.chain_state(rng, LINKS)
        point = {**dict(zip(q, map(sp.Float, angles), strict=True)),
                 **dict(zip(u, map(sp.Float, rates), strict=True))}
        ours = [float(x) for x in system.at(point).solve().speeds_after]
        assert not np.allclose(ours, rates)  # the impact changes every state drawn
        theirs = peer.absolute(peer.pinocchio_after(model, tip, peer.relative(angles),
                                                    peer.relative(rates), [0], 0.5))
        assert np.allclose(ours, theirs, rtol=1e-10, atol=1e-10), (ours, theirs)


def test_the_compass_gait_heel_strike_agrees_with_pinocchio():
    kane, solution, values, model, heel = peer.compass_gait()
    x, y, st, sw = kane.q
    ux, uy, w_st, w_sw = kane.u
    rng = random.Random(45)
    for _ in range(6):
        half = rng.uniform(0.1, 0.4)  # the legs' half angle at heel strike
        before = [0.0, 0.0, rng.uniform(-2, -0.5), rng.uniform(-2, 1)]
        at = {x: 0, y: 0, st: -half, sw: half, ux: before[0], uy: before[1],
              w_st: before[2], w_sw: before[3], **values}
        ours = [float(v.xreplace(at)) for v in solution.speeds_after]
        q = np.array([0.0, 0.0, -half, 2 * half])
        v = np.array([before[0], before[1], before[2], before[3] - before[2]])
        theirs = peer.pinocchio_after(model, heel, q, v, [0, 1], 0.0)
        theirs[3] += theirs[2]  # back to the swing leg's absolute rate
        assert np.allclose(ours, theirs, rtol=1e-10, atol=1e-10), (ours, theirs)


def test_the_script_prints_its_table():
    rows = peer.costs(3, repeat=2)
    assert [r["system"] for r in rows] == ["chain of 3, tip on a wall",
                                           "compass gait, heel strike"]
    assert all(r["largest difference"] < 1e-10 for r in rows)


def test_the_kernels_of_both_maps_agree_with_pinocchio_at_a_thousand_states():
    # rigidimpact's compiled map, all states in one call, against Pinocchio state by state
    system, _, _ = peer.chain_in_sympy(LINKS)
    model, tip = peer.chain_in_pinocchio(LINKS)
    q, u = peer.chain_states(46, 1000, LINKS)
    found = system.kernel()(q, u)
    assert not found.warnings and found.honoured.all()
    for k in range(1000):
        theirs = peer.absolute(peer.pinocchio_after(model, tip, peer.relative(q[k]),
                                                    peer.relative(u[k]), [0], 0.5))
        assert np.allclose(found.speeds_after[k], theirs, rtol=1e-10, atol=1e-10)
    _, strike, values = peer.gait_strike()
    model, heel = peer.gait_in_pinocchio()
    q, u = peer.gait_states(46, 1000)
    found = strike.kernel(values)(q, u)
    assert not found.warnings
    for k in range(1000):
        theirs = peer.pinocchio_after(model, heel, np.array([0, 0, q[k, 2], q[k, 3] - q[k, 2]]),
                                      np.array([*u[k, :3], u[k, 3] - u[k, 2]]), [0, 1], 0.0)
        theirs[3] += theirs[2]
        assert np.allclose(found.speeds_after[k], theirs, rtol=1e-10, atol=1e-10)


def test_the_kernel_table_runs():
    rows = peer.kernel_costs(2000, links=3, repeat=1)
    assert [r["system"] for r in rows] == ["chain of 3, tip on a wall",
                                           "compass gait, heel strike"]
    assert all(r["largest difference"] < 1e-10 for r in rows)
