"""Section 1 of Mungan (2007): the ball and the barbell, solved from the laws.

Run: python derivations/section1_barbell.py
"""

from __future__ import annotations

import rigidimpact as ri


def main() -> None:
    d = ri.derive("barbell")
    print(f"# {d.title}\n")
    for eq in d.equations:
        print(f"{eq.paper:>10}  {eq.lhs} = {eq.rhs}    [{eq.label}]")
    print("\nResults (eq. 5), with f recognised:")
    print(f"  f = {d.definitions['f']}")
    for key, value in d.named.items():
        print(f"  {key} = {value}")
    theta, e = ri.symbol("theta"), ri.symbol("e")
    print("\nHead on (theta = 0):")
    for ev in (0, 1):
        v_fx = d.results["v_fx"].subs({theta: 0, e: ev})
        V_x = d.results["V_x"].subs({theta: 0, e: ev})
        print(f"  e = {ev}: v_fx = {v_fx}, V_x = {V_x}, omega_z = "
              f"{d.results['omega_z'].subs(theta, 0)}")


if __name__ == "__main__":
    main()
