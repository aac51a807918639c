"""The impact map of a sympy.physics.mechanics system exported as C
(:func:`rigidimpact.outputs.mapcode.impact_map_code`), compiled with gcc -O2 and called
over 1,000 seeded states, against the NumPy kernel (``SystemImpact.kernel``): the same
speeds after to 1e-12 relative, NaN at the same states (a contact that would pull)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "derivations"))
import beside_pinocchio as peer  # noqa: E402

pytestmark = pytest.mark.skipif(shutil.which("gcc") is None,
                                reason="gcc is not installed (Debian: apt-get install gcc)")


def _same(found, wanted):
    assert np.array_equal(np.isnan(found), np.isnan(wanted))
    fine = ~np.isnan(wanted)
    error = np.abs(found[fine] - wanted[fine]) / np.maximum(np.abs(wanted[fine]), 1.0)
    assert error.max() <= 1e-12, error.max()


def test_the_chain_of_five_in_c_is_the_kernel():
    system, _, _ = peer.chain_in_sympy(5)
    q, u = peer.chain_states(12, 1000, 5)
    u = np.vstack([u, -u[:10]])  # moving away from the wall: no impact, NaN in both
    q = np.vstack([q, q[:10]])
    wanted = system.kernel()(q, u).speeds_after
    assert np.isnan(wanted).any()
    _same(peer.compiled_map(system)(q, u), wanted)


def test_the_compass_gait_heel_strike_in_c_is_the_kernel():
    _, strike, values = peer.gait_strike()
    q, u = peer.gait_states(12, 1000)
    _same(peer.compiled_map(strike, values)(q, u), strike.kernel(values)(q, u).speeds_after)
