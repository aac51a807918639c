"""Section 2 of Mungan (2007): energy lost, sphere A's sideways kick, the clay ball.

Run: python derivations/section2_implications.py
"""

from __future__ import annotations

import sympy as sp

import rigidimpact as ri
from rigidimpact.problems import sphere_a_velocity, sticking_routes


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


if __name__ == "__main__":
    main()
