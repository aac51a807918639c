"""``simulate`` for a 3-D scene: the impact as an instant, or a sphere's bounce on a fixed
flat through a tangentially compliant contact (``effects = ["tangential-compliance"]``).

The compliant bounce of a sphere on a flat is planar, whatever its spin: the sphere's
tangential mobility is isotropic (``1/m + R^2/I`` in every direction across the
normal), the spring's stretch starts at zero and grows along the slip, and every force
on the slip is along the stretch or along the slip; so the slip, the stretch and the
tangential force stay on the line of the first slip, ``s``. Across s nothing acts: the
centre's velocity across s and the spin's part that moves the touching point across s
keep their values, and so does the spin about the normal (the lumped contact has no
twisting spring). Along s the bounce is the planar one of
:func:`rigidimpact.laws.compliance.tangential_bounce`, in the plane of n and s. A
sphere that meets the flat without slipping has nothing to turn and keeps its
tangential motion.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import tangential_bounce
from rigidimpact.model.space import SPEEDS
from rigidimpact.scenes.space import SpaceScene
from rigidimpact.simulate.outcome import Outcome
from rigidimpact.simulate.planner import make_plan
from rigidimpact.simulate.tangential import STEPS

__all__ = ["run_space"]


def run_space(scene: SpaceScene, values: dict | None = None) -> Outcome:
    """Simulate a 3-D scene as its ``[simulate]`` table asks (see the module's text):
    until separation, the rigid impact alone or with tangential compliance."""
    start = time.perf_counter()
    plan = make_plan(scene.simulate)
    values = dict(scene.values) if values is None else values
    effects = set(plan.effects)
    if plan.until != "separation" or not effects <= {"tangential-compliance"}:
        raise InputError("simulate", "a 3-D scene is simulated until = \"separation\", "
                         "as a rigid impact or with effects = [\"tangential-compliance\"], "
                         "so far (its flight after the impact is not built)")
    missing = sorted(str(s) for s in scene.used if s not in values)
    if missing:
        raise InputError("values", f"give a value for {', '.join(missing)}")
    solution = scene.collision(values).solve()
    rigid = {k: float(sp.N(v, 17)) for k, v in solution.results().items()
             if any(k.endswith(f".{s}") for s in SPEEDS)}
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0}]
    if not effects:
        events.append({"kind": "end", "t": 0.0, "why": "the contact separates (a rigid "
                       "impact is an instant)"})
        return Outcome(plan, {**rigid, "t": 0.0}, events, time.perf_counter() - start, 0,
                       {"warnings": list(solution.warnings)})
    final = _compliant_sphere(scene, values, plan.settings["stiffness_ratio"])
    events.append({"kind": "end", "t": 0.0, "why": "the sphere separates from the flat "
                   "(the contact's duration is not resolved in time: only k_t/k_n enters)"})
    details = {"contact": {"model": "tangentially compliant: a normal spring with the "
                                    "dashpot that returns e, a tangential spring capped by "
                                    "Coulomb (linear, so only k_t/k_n matters), in the "
                                    "plane of the normal and the first slip",
                           "stiffness_ratio": plan.settings["stiffness_ratio"],
                           "steps_per_period": STEPS},
               "rigid": rigid}
    return Outcome(plan, {**final, "t": 0.0}, events, time.perf_counter() - start, 0,
                   details)


def _compliant_sphere(scene: SpaceScene, values: dict, ratio: float) -> dict[str, float]:
    """The sphere's speeds after its tangentially compliant bounce on the flat."""
    if len(scene.contacts) != 1:
        raise InputError("simulate.effects", "tangential-compliance takes one contact (a "
                         "sphere on a fixed flat) so far")
    (contact,) = scene.contacts
    if contact.tangential != "coulomb" or contact.law != "newton":
        raise InputError("simulate.effects", "tangential-compliance needs Newton's e and "
                         "a Coulomb contact (tangential = \"coulomb\", friction = mu)")
    free = [b for b in scene.bodies if b.support != "fixed"]
    if len(free) != 1 or free[0].radius is None:
        raise InputError("simulate.effects", "tangential-compliance needs one sphere and "
                         "one fixed body")
    ball = free[0].at(values)

    def number(x: Any) -> float:
        return float(sp.N(sp.sympify(x).xreplace(values), 17))

    R, m = number(ball.radius), number(ball.mass)
    inertia = number(ball.inertia[0]) / (m * R * R)  # in units of m R^2
    n = np.array([number(x) for x in contact.normal])
    n /= np.linalg.norm(n)
    if ball.name == contact.first:  # the normal from the flat into the sphere
        n = -n
    v = np.array([number(x) for x in ball.velocity])
    w = np.array([number(x) for x in ball.spin])
    vn = float(v @ n)
    if vn >= 0:
        raise InputError("bodies", f"{ball.name} is not approaching the flat")
    v_t = v - vn * n
    spin_slip = R * np.cross(w, -n)  # the touching point at -R n moves at w x (-R n)
    slip = v_t + spin_slip
    size = float(np.linalg.norm(slip))
    e, mu = number(contact.restitution), number(contact.friction)
    if size == 0.0:  # nothing to stretch the spring: the tangential motion is kept
        s = np.zeros(3)
        along_v = along_w = 0.0
    else:
        s = slip / size
        along_v, along_w = float(v_t @ s), float(spin_slip @ s)
    vt_after, vn_after, turn = tangential_bounce(along_v, vn, along_w, mu, e, ratio,
                                                 inertia, STEPS)
    v_after = v + (float(vn_after) - vn) * n + (float(vt_after) - along_v) * s
    # the spin's change: the tangential force F s at -R n turns the sphere about
    # (-R n) x s; its slip along s changes by R (w x (-n)) . s, which is turn - along_w
    axis = np.cross(-n, s)
    w_after = w + (float(turn) - along_w) / R * axis
    return {f"{ball.name}.{k}": float(x) for k, x in
            zip(SPEEDS, (*v_after, *w_after), strict=True)}
