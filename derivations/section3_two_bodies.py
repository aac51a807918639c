"""Section 3 of Mungan (2007): two rigid bodies, eqs. (11)-(16).

Run: python derivations/section3_two_bodies.py
"""

from __future__ import annotations

import sympy as sp

import rigidimpact as ri


def main() -> None:
    d = ri.derive("two-body")
    print("# General smooth impact: every result in terms of the normal impulse J")
    print(f"  J = {d.definitions['J']}")
    for key, value in d.named.items():
        print(f"  {key} = {value}")
    central = {ri.symbol("R_1y"): 0, ri.symbol("R_2y"): 0}
    print("\n# Central impact (eq. 15): spins unchanged")
    for key in ("omega_1fz", "omega_2fz"):
        print(f"  {key} = {sp.cancel(d.results[key].subs(central))}")
    discs = ri.derive("discs")
    print("\n# Equal smooth discs (eq. 16)")
    for key in ("V_1fx", "V_2fx"):
        print(f"  {key} = {discs.results[key]}")


if __name__ == "__main__":
    main()
