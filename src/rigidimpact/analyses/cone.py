"""What accuracy costs when a 3-D rough contact is followed numerically.

Three cases, each integrated in the normal impulse at a ladder of relative tolerances:

- ``sphere``: a spinning ball on a floor, whose exact answer is the closed form
  (:func:`rigidimpact.laws.cone.cone_impact` without a tolerance);
- ``planar rod``: a slender body landing on one end with its motion in a vertical
  plane, whose slip stops and reverses; its exact answer is Routh's planar one;
- ``turning box``: a box on one corner whose slip direction turns; no closed form, so
  the reference is the same integration at a tolerance of 1e-13.

Run ``python -m rigidimpact.analyses.cone`` for the table (docs/three-d.md shows one).
"""

from __future__ import annotations

import time
from typing import Any

import sympy as sp

from rigidimpact.laws.contact import Contact
from rigidimpact.model.bodies import Body
from rigidimpact.model.space import Body3
from rigidimpact.solve.collision import Collision
from rigidimpact.solve.rules import Simultaneous
from rigidimpact.solve.space import SpaceCollision

__all__ = ["accuracy_ladder", "TOLERANCES"]

TOLERANCES = (1e-3, 1e-5, 1e-7, 1e-9, 1e-11)
HALF = sp.Rational(1, 2)
TURNED = sp.Matrix([[2, -1, 2], [2, 2, -1], [-1, 2, 2]]) / 3
ROD_AXIS = sp.Matrix([[sp.Rational(4, 5), 0, -sp.Rational(3, 5)], [0, 1, 0],
                      [sp.Rational(3, 5), 0, sp.Rational(4, 5)]])


def _floor(mu: Any, law: str = "newton") -> Contact:
    return Contact(normal=(0, 0, 1), restitution=HALF, tangential="coulomb", friction=mu,
                   law=law, bodies=("floor", "body"), point=(0, 0, 0))


def _cases() -> dict[str, tuple[tuple, dict[str, float]]]:
    """Each case's bodies and contact, and its exact (or reference) speeds after."""
    sphere = (Body3.fixed("floor"), Body3.sphere(1, 1, (0, 0, 1), (HALF, 0, -2),
                                                 (0, 1, sp.Rational(1, 3)), name="body"))
    sphere_case = (sphere, (_floor(sp.Rational(1, 5)),))
    exact = SpaceCollision(sphere_case[0], sphere_case[1]).solve().results()
    rod = Body3.rigid(1, (sp.Rational(1, 100), sp.Rational(1, 3), sp.Rational(1, 3)),
                      (sp.Rational(4, 5), 0, sp.Rational(3, 5)), (sp.Rational(1, 10), 0, -1),
                      (0, 0, 0), ROD_AXIS, name="body")
    rod_case = ((Body3.fixed("floor"), rod), (_floor(sp.Rational(3, 10)),))
    flat = Body.rigid(1, sp.Rational(1, 3), (sp.Rational(4, 5), sp.Rational(3, 5)),
                      (sp.Rational(1, 10), -1), 0, name="rod")
    (planar,) = Collision((Body.fixed("floor"), flat), (Contact(
        normal=(0, 1), restitution=HALF, tangential="coulomb", friction=sp.Rational(3, 10),
        bodies=("floor", "rod"), point=(0, 0)),)).solve(Simultaneous())
    p = planar.results()
    routh = {"body.vx": p["rod.vx"], "body.vz": p["rod.vy"], "body.omega_y": -p["rod.omega"]}
    box = Body3.rigid(2, (HALF, sp.Rational(1, 3), sp.Rational(2, 3)),
                      (HALF, sp.Rational(1, 3), sp.Rational(3, 4)), (1, HALF, -2),
                      (1, -2, HALF), TURNED, name="body")
    box_case = ((Body3.fixed("floor"), box), (_floor(sp.Rational(3, 10), "poisson"),))
    reference = SpaceCollision(box_case[0], box_case[1], 1e-13).solve().results()
    return {"sphere (exact: closed form)": (sphere_case, exact),
            "planar rod, slip reverses (exact: Routh)": (rod_case, routh),
            "turning box (reference: 1e-13)": (box_case, reference)}


def accuracy_ladder(tolerances: tuple[float, ...] = TOLERANCES,
                    repeats: int = 5) -> list[dict[str, Any]]:
    """One row per case and tolerance: the largest error of the speeds after against the
    exact (or reference) answer, the integration's steps and the median time of
    `repeats` solves."""
    rows = []
    for name, (case, exact) in _cases().items():
        for tolerance in tolerances:
            times, out = [], None
            for _ in range(repeats):
                start = time.perf_counter()
                out = SpaceCollision(case[0], case[1], tolerance).solve()
                times.append(time.perf_counter() - start)
            assert out is not None
            r = out.results()
            error = max(abs(float(r[k]) - float(v)) for k, v in exact.items())
            steps = next((int(n.split("(")[1].split(" steps")[0]) for n in out.notes
                          if " steps;" in n), 0)
            turned = next((float(n.split("turned by ")[1].split(" degrees")[0])
                           for n in out.notes if "turned by" in n), 0.0)
            rows.append({"case": name, "tolerance": tolerance, "error": error,
                         "steps": steps, "turned": turned,
                         "seconds": sorted(times)[len(times) // 2]})
    return rows


def _table(rows: list[dict[str, Any]]) -> str:
    lines = ["| case | tolerance | largest error of the speeds | steps | slip turned (deg) "
             "| time (ms) |", "|---|---|---|---|---|---|"]
    lines += [f"| {r['case']} | {r['tolerance']:.0e} | {r['error']:.1e} | {r['steps']} | "
              f"{r['turned']:.1f} | {1000 * r['seconds']:.1f} |" for r in rows]
    return "\n".join(lines)


if __name__ == "__main__":
    print(_table(accuracy_ladder()))
