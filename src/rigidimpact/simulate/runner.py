"""Carry out a plan: the impulse, then free flight to the event the scene asks for.

Examples
--------
>>> from rigidimpact.scenes.scene import load_scene
>>> outcome = run(load_scene("derivations/barbell.toml"))
>>> [event["kind"] for event in outcome.events]
['impact', 'end']
>>> round(outcome.final["barbell.vx"], 12)
0.285714285714
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model.shapes import is_segment
from rigidimpact.scenes.scene import Scene
from rigidimpact.scenes.space import SpaceScene
from rigidimpact.simulate.compliant import prepare, run_compliant
from rigidimpact.simulate.flight import Flyer, first_contact, reach_interval
from rigidimpact.simulate.linkage import run_linkage
from rigidimpact.simulate.numbers import as_float, scene_values
from rigidimpact.simulate.outcome import FlightTrack, Outcome, finite, flyer
from rigidimpact.simulate.planner import make_plan
from rigidimpact.simulate.several import run_several
from rigidimpact.simulate.space import bounces_in_plane, run_in_plane, run_space
from rigidimpact.simulate.tangential import run_tangential
from rigidimpact.solve.collision import rule_laws
from rigidimpact.solve.derivation import model_name, physics_warnings

__all__ = ["Outcome", "run", "flyer", "explain", "FlightTrack", "impact_view", "rigid_limit"]


def _no_search(scene: Scene) -> str | None:
    """Why the next contact of a two-body scene cannot be searched for, or None: the
    search follows a point (the ball) against the other body's outline."""
    if sum(b.shape == "particle" for b in scene.bodies) != 1:
        shapes = " and ".join(f"a {b.shape}" for b in scene.bodies)
        return (f"a search for the next contact needs one particle (the ball) and one "
                f"barbell, rod, disc, ring or sphere, not {shapes}: make the striker a "
                "particle, or follow only the impact (until = \"separation\")")
    return None


def explain(scene: Scene) -> str:
    """The plan in words; for a compliant model also the integrator and contact it picks.

    Examples
    --------
    >>> from rigidimpact.scenes.scene import load_scene
    >>> print(explain(load_scene("derivations/restrike.toml")).splitlines()[2])
    2. free-flight: no force between impacts: straight lines and steady spin in closed form, with an exact search for the next contact
    """  # noqa: E501
    plan = make_plan(scene.simulate)
    lines = [plan.explain()]
    if scene.joints:  # a linkage flies with its joints held: not straight lines
        held = "under gravity" if "gravity" in plan.effects else "with no force"
        lines = [line.replace(
            "free-flight: no force between impacts: straight lines and steady spin in "
            "closed form, with an exact search for the next contact",
            f"linkage flight: the bodies move {held} with every joint and pivot held "
            "(the linkage's equations of motion, integrated with DOP853 at rtol 1e-10), "
            "watched for the next contact") for line in plan.explain().splitlines()]
    if len(scene.contacts) > 1:
        frictional = any(t.laws[1].grips for t in scene.contacts)
        lines.append(f"impact rule: {scene.rule}: {rule_laws(scene.rule, frictional)}")
        if "gravity" not in plan.effects and any(b.support == "fixed" for b in scene.bodies):
            lines.append("note: without gravity nothing brings the bodies back to the "
                         "fixed body; ask for effects = [\"gravity\"] to see them land again")
        return "\n".join(lines)
    if plan.until != "separation" and not bounces_in_plane(scene) and \
            all(step.model != "compliant" for step in plan.steps):
        unsearched = _no_search(scene)
        if unsearched:
            lines.append(f"refused: {unsearched}")
    if any(step.model == "compliant" for step in plan.steps):
        model = prepare(scene, plan, scene_values(scene))
        chosen = model.integrator
        lines.append(f"integrator: {chosen['method']}, rtol {chosen['rtol']:.1e} "
                     f"(tolerance {plan.settings['tolerance']:.1e}); {chosen['why']}")
        contact = model.contact
        lines.append(f"contact: {contact['model']}"
                     + (f", damping ratio {contact['damping_ratio']:.6g} returns e = "
                        f"{contact['reached_e']:.6g}" if "damping_ratio" in contact else ""))
        if "note" in contact:
            lines.append(f"note: {contact['note']}")
    return "\n".join(lines)


def _restrike(ball: Flyer, other: Flyer, horizon: float) -> tuple[list[dict], float]:
    """The next contact (if any) and the time the run ends."""
    hit = first_contact(ball, other, horizon)
    if hit is not None:
        event = {"kind": "restrike", "t": hit.t, "part": hit.part,
                 "point": [float(c) for c in hit.point]}
        if is_segment(other.shape):
            event["s"] = hit.s
        return [event], hit.t
    if other.ends is not None:
        reach = max(math.hypot(*q) for q in other.ends)
    else:
        reach = other.radius
    window = reach_interval(ball.at(0)[0] - other.at(0)[0],
                            ball.velocity_at(0) - other.velocity_at(0), reach)
    leaves = window[1] if window is not None and math.isfinite(window[1]) else 0.0
    if math.isfinite(horizon):
        return [], horizon
    return [{"kind": "out-of-reach", "t": leaves}], leaves


def run(scene: Scene | SpaceScene) -> Outcome:
    """Simulate a scene as its plan says.

    Raises
    ------
    InputError
        A bad ``[simulate]`` table, a missing value, or a question the runners cannot
        answer (a re-strike search needs one particle).
    """
    if isinstance(scene, SpaceScene):  # a 3-D scene: its impact, or a sphere's bounces
        return run_space(scene)
    if "impacts" in scene.simulate:
        raise InputError("simulate.impacts", "a count of impacts is read by a 3-D scene's "
                         "bouncing sphere; a planar scene runs until a time")
    if bounces_in_plane(scene):  # a round body among fixed ones: its bounces
        return finite(run_in_plane(scene))
    effects = scene.simulate.get("effects")
    if isinstance(effects, list) and {"rolling-resistance", "pivot-friction"} & set(effects):
        raise InputError("simulate.effects", "rolling-resistance and pivot-friction wear a "
                         "sphere lying on a plane: a 3-D scene's")
    if scene.joints:  # a linkage: the impact, then its flight with the joints held
        return run_linkage(scene)
    if len(scene.contacts) > 1:
        return run_several(scene)
    start = time.perf_counter()
    plan = make_plan(scene.simulate)
    values = scene_values(scene)
    if "tangential-compliance" in plan.effects:
        return finite(run_tangential(scene, plan, values, start))
    supported = [b.name for b in scene.bodies if b.support != "free"]
    if supported and (plan.until != "separation" or len(plan.steps) > 1):
        raise InputError("simulate", f"{supported[0]} is pivoted or fixed: only the impact "
                         "itself (until = separation, no effects) is simulated for such "
                         "scenes so far")
    if any(step.model == "compliant" for step in plan.steps):
        return finite(run_compliant(scene, plan, values, start))
    solution = scene.impact().solve()
    # solved seen from the contact point (Scene.pair); followed in the scene's own frame
    origin = sp.ImmutableMatrix(scene.contact.point)
    after = (solution.first_after.shifted(origin), solution.second_after.shifted(origin))
    g = plan.settings["g"] if "gravity" in plan.effects else 0.0
    flyers = [replace(flyer(b, values), gravity=g) for b in after]
    events: list[dict[str, Any]] = [{"kind": "impact", "t": 0.0}]
    t_end, why = 0.0, "the bodies separate at the impact (until = separation)"
    if plan.until != "separation":
        horizon = math.inf if plan.until == "restrike" else float(plan.until)
        unsearched = _no_search(scene)
        if unsearched:
            raise InputError("simulate.until", unsearched)
        ball = next(f for f in flyers if f.shape == "particle")
        other = flyers[1 - flyers.index(ball)]
        more, t_end = _restrike(ball, other, horizon)
        events += more
        why = {"restrike": "the next contact", "out-of-reach": "no next contact: the "
               "ball leaves the other body's reach for good"}.get(
            more[0]["kind"] if more else "", f"reached until = {t_end:g} s")
    events.append({"kind": "end", "t": t_end, "why": why})
    details = {}
    energy = {"energy_loss_fraction": as_float(solution.energy_loss_fraction, values),
              "impulse": as_float(solution.normal_impulse, values)}
    warnings = physics_warnings(energy, None, model_name(scene.contact))
    if warnings:
        details["warnings"] = list(warnings)
    final: dict[str, float] = {}
    for body in flyers:
        place, turn = body.at(t_end)
        velocity = body.velocity_at(t_end)
        final |= {f"{body.name}.vx": float(velocity[0]),
                  f"{body.name}.vy": float(velocity[1]),
                  f"{body.name}.omega": float(body.spin),
                  f"{body.name}.x": float(place[0]), f"{body.name}.y": float(place[1]),
                  f"{body.name}.turn": turn}
    final["t"] = t_end
    return finite(Outcome(plan, final, events, time.perf_counter() - start,
                           details=details, trajectory=FlightTrack(tuple(flyers), t_end)))


def impact_view(scene: Scene, outcome: Outcome) -> tuple[list, list, dict]:
    """What a picture of the impact needs, in numbers: the bodies (scene frame), each
    contact as (point, normal, first, second), and each body's (vx, vy, omega) after."""
    values = dict(scene.values)
    bodies = [b if b.support == "fixed" else b.at(values) for b in scene.bodies]
    contacts = [(t.point.xreplace(values), t.unit_normal.xreplace(values), t.first, t.second)
                for t in scene.contacts]
    after = {b.name: tuple(outcome.final[f"{b.name}.{k}"] for k in ("vx", "vy", "omega"))
             for b in bodies if b.support != "fixed"}
    return bodies, contacts, after


def rigid_limit(scene: Scene, contact_stiffnesses: list[float], rod_exponent: float = 1.5,
                rod_scale: float = 100.0) -> list[dict[str, float]]:
    """Compliant runs against the rigid closed form as the contact stiffens.

    The rod stiffens faster: ``k_rod = rod_scale * k_contact ** rod_exponent``. Each row
    gives both stiffnesses, the largest difference of any final velocity or spin from
    the rigid solution, and the run's cost. ``order`` is the slope of log(error) against
    log(k_contact) between neighbouring rows.
    """
    values = scene_values(scene)
    solution = scene.impact().solve()
    rigid = {}
    for body in (solution.first_after, solution.second_after):
        for key, x in ((f"{body.name}.vx", body.velocity[0]),
                       (f"{body.name}.vy", body.velocity[1]),
                       (f"{body.name}.omega", body.spin)):
            rigid[key] = as_float(x, values)
    rows: list[dict[str, float]] = []
    for k_c in contact_stiffnesses:
        table = {**scene.simulate, "effects": ["rod-compliance", "contact-compliance"],
                 "contact_stiffness": k_c, "rod_stiffness": rod_scale * k_c**rod_exponent,
                 "until": "separation"}
        outcome = run(replace(scene, simulate=table))
        error = max(abs(outcome.final[k] - v) for k, v in rigid.items())
        row = {"contact_stiffness": k_c, "rod_stiffness": table["rod_stiffness"],
               "error": error, "ode_steps": outcome.ode_steps, "wall_s": outcome.wall_s}
        if rows:
            row["order"] = -math.log(error / rows[-1]["error"]) / math.log(
                k_c / rows[-1]["contact_stiffness"])
        rows.append(row)
    return rows
