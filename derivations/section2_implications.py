"""Section 2 of Mungan (2007): energy lost, sphere A's sideways kick, the clay ball, and
the re-strike after a perfectly inelastic hit (the critical angle), extended to e > 0.

Run: python derivations/section2_implications.py
"""

from __future__ import annotations

import mpmath
import sympy as sp

import rigidimpact as ri
from rigidimpact.analyses import restrike
from rigidimpact.paper.problems import sphere_a_velocity, sticking_routes


def main() -> None:
    d = ri.derive("barbell")
    theta = ri.symbol("theta")
    print("# Energy lost (eqs. 6-7)")
    print(f"  Delta K / K_i = {d.results['energy_loss_fraction']}")
    print(f"  at 90 degrees: {d.results['energy_loss_fraction'].subs(theta, sp.pi / 2)}")
    print("\n# Sphere A just after the impact")
    v_a = sphere_a_velocity()
    print(f"  v_A = ({v_a[0]}, {v_a[1]})")
    print("  the y component is negative for 0 < theta < 90 degrees")
    print("\n# The clay ball (eqs. 8-10), four routes")
    for route, values in sticking_routes().items():
        print(f"  {route:>13}: u_x = {values['u_x']}, omega_z = {values['omega_z']}")
    print(f"  h = {ri.derive('sticking').results['h']}")
    print("\n# The re-strike (derived from the free flight after the impact)")
    derived = restrike.derive()
    print(f"  drift of the ball from C: k = {derived.drift}")
    print(f"  turn at which the ball leaves the rod's reach: T = {derived.exit_turn}")
    print(f"  re-strike when T >= {derived.meet_turn}; at e = 0: {derived.critical} >= 0")
    result = restrike.critical_angle()
    print(f"  theta_c = {mpmath.nstr(result.theta_c_deg, 30)} deg "
          f"(tan theta_c = 1/(pi - theta_c); the paper: ~19.7 deg)")
    for e_value, ratio in (("0.1", "4"), ("0.3", "1"), ("0.6", "1")):
        spans = [f"[{float(lo):.4f}, {float(hi):.4f}]"
                 for lo, hi in restrike.windows(e_value, ratio)]
        print(f"  e = {e_value}, m/M = {ratio}: re-strike for theta in "
              f"{', '.join(spans) + ' deg' if spans else 'no angle'}")


if __name__ == "__main__":
    main()
