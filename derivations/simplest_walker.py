"""The simplest walking model of Garcia, Chatterjee, Ruina and Coleman (J. Biomech. Eng.
120, 1998): a compass gait whose mass is a hip M and two point feet m, in the limit m/M
-> 0, on a slope gamma (g = l = 1).

The biped is the compass gait of ``compass_gait.py`` with its leg masses at the feet
(a = 0, b = l), built with sympy.physics.mechanics; rigidimpact derives its heel-strike
map (e = 0, stick) and its limit m/M -> 0 in closed form (``heel_strike``: the stance and
swing rates after from the stance rate before, theta being the stance leg's angle from
the slope's normal at heel strike). ``fixed_point``: [theta, thetadot] just after heel
strike on the long-period gait at gamma = 0.009, found on the hybrid simulation of the
same model with m/M = 1e-10 (the limit is reached to about that size: at 1e-7 the point
lay 1.5e-8 from Garcia et al.'s, at 1e-10 within 1e-10); ``eigenvalues``:
of the Poincare map over (theta, thetadot, swing rate).

Run: ``python derivations/simplest_walker.py [--json]``.
"""

from __future__ import annotations

import argparse
import json
import time

import sympy as sp
from compass_gait import a, alpha, b, g, gait, gamma, heel_strike, m, m_H

GAMMA = sp.Rational(9, 1000)
VALUES = {m: sp.Rational(1, 10**10), m_H: 1, a: 0, b: 1, g: 1, gamma: GAMMA}


def limit_map(solution, kane) -> sp.Matrix:
    """The heel-strike map at theta_st = -alpha (before), theta_sw = alpha, in the limit
    m/M -> 0: rows (new stance rate, new swing rate), columns (old stance, old swing)."""
    _, _, st, sw = kane.q
    ux, uy, w_st, w_sw = kane.u
    after = solution.speeds_after.xreplace({st: -alpha, sw: alpha, ux: 0, uy: 0,
                                            a: 0, b: 1})
    rows = [after[3], after[2]]
    H = sp.Matrix([[sp.diff(r, w) for w in (w_st, w_sw)] for r in rows])
    return H.applyfunc(lambda x: sp.simplify(sp.limit(sp.cancel(x), m, 0)))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    kane, _, solution = heel_strike()
    H = limit_map(solution, kane)
    found = gait(solution, kane, VALUES, guess=(0.2, -0.2, -0.2, -0.04))
    out = {"heel_strike": str(H),
           "fixed_point": [float(found.state[0]), float(found.state[2])],
           "swing_rate": float(found.state[3]),
           "eigenvalues": [[float(z.real), float(z.imag)] for z in found.eigenvalues],
           "stable": found.stable,
           "seconds": round(time.perf_counter() - start, 2)}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print("Heel strike in the limit m/M -> 0 (new stance, new swing rate from old):")
        sp.pprint(H)
        print("Long-period gait just after heel strike [theta, thetadot]:", out["fixed_point"])
        print("Eigenvalues of the Poincare map:", out["eigenvalues"])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
