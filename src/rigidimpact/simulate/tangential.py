"""``effects = ["tangential-compliance"]``: a round body striking a fixed flat through a
tangentially compliant contact.

The rigid contact sticks or slides in an instant (Routh's method); a real contact is
also a spring across the normal, and a body whose contact stops sliding is sprung back
sideways, which changes its rebound at small angles of incidence (Kharaz, Gorham and
Salman 2001; notebook 11). The model is the lumped contact of the discrete-element codes
(:func:`rigidimpact.laws.compliance.tangential_bounce`): a normal spring with the
dashpot that returns e, a tangential spring ``stiffness_ratio`` times as stiff, and
Coulomb's cap. Linear springs make the answer independent of the stiffness itself: the
ratio is the one parameter.

It applies to a scene of one contact between a disc, ring or sphere and a fixed body,
with Coulomb friction; the final speeds are given beside the rigid contact's.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import tangential_bounce
from rigidimpact.scenes.scene import Scene
from rigidimpact.simulate.outcome import Outcome
from rigidimpact.simulate.planner import Plan

__all__ = ["run_tangential", "ROUND"]

ROUND = ("disc", "ring", "sphere")
STEPS = 4000  # per normal period; first order: see rigidimpact.analyses.experiment


def run_tangential(scene: Scene, plan: Plan, values: dict, start: float) -> Outcome:
    """The bounce through the tangentially compliant contact (see the module's text)."""
    if len(scene.contacts) != 1 or scene.joints:
        raise InputError("simulate.effects", "tangential-compliance takes one contact "
                         "(a round body on a fixed one) so far")
    if set(plan.effects) != {"tangential-compliance"} or plan.until != "separation":
        raise InputError("simulate.effects", "tangential-compliance runs alone, until = "
                         "\"separation\", so far")
    contact = scene.contacts[0]
    if contact.laws[1].coulomb() is None:
        raise InputError("simulate.effects", "tangential-compliance needs a Coulomb "
                         "contact (tangential = \"coulomb\", friction = mu)")
    if contact.laws[0].newtons_e() is None:
        raise InputError("simulate.effects", "tangential-compliance takes Newton's e (its "
                         "dashpot is chosen to return e)")
    free = [b for b in scene.bodies if b.support == "free"]
    fixed = [b for b in scene.bodies if b.support == "fixed"]
    if len(free) != 1 or len(fixed) != 1 or free[0].shape not in ROUND:
        raise InputError("simulate.effects", "tangential-compliance needs one disc, ring "
                         "or sphere and one fixed body")
    body = free[0]

    def number(x: Any) -> float:
        return float(sp.sympify(x).xreplace(values))

    radius = number(dict(body.dimensions)["radius"])
    inertia = number(body.inertia) / (number(body.mass) * radius**2)
    n = np.array([number(x) for x in contact.normal])
    n = n / np.hypot(*n)
    if body.name == contact.first:  # the normal from the flat into the body
        n = -n
    t = np.array([n[1], -n[0]])  # the touching point at -R n slips at v.t + omega R
    v = np.array([number(x) for x in body.velocity])
    spin = number(body.spin)
    vn = float(v @ n)
    if vn >= 0:
        raise InputError("bodies", f"{body.name} is not approaching the flat")
    ratio, e, mu = plan.settings["stiffness_ratio"], number(contact.restitution), \
        number(contact.friction)
    vt, vn_after, turn = tangential_bounce(float(v @ t), vn, spin * radius, mu, e, ratio,
                                           inertia, STEPS)
    after = float(vt) * t + float(vn_after) * n
    final = {f"{body.name}.vx": float(after[0]), f"{body.name}.vy": float(after[1]),
             f"{body.name}.omega": float(turn) / radius, "t": 0.0}
    rigid = scene.impact().solve().results()
    details = {"contact": {"model": "tangentially compliant: a normal spring with the "
                                    "dashpot that returns e, a tangential spring capped by "
                                    "Coulomb (linear, so only k_t/k_n matters)",
                           "stiffness_ratio": ratio, "steps_per_period": STEPS},
               "rigid": {k: float(sp.sympify(rigid[k]).xreplace(values))
                         for k in (f"{body.name}.vx", f"{body.name}.vy",
                                   f"{body.name}.omega")}}
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0}, {
        "kind": "end", "t": 0.0, "why": "the body separates from the flat (the contact's "
        "duration is not resolved in time: only k_t/k_n enters)"}]
    return Outcome(plan, final, events, time.perf_counter() - start, 0, details)
