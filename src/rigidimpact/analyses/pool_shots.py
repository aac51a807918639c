"""Stun, draw and follow shots on a pool table, followed from the cue ball's start to
the balls' rest by :func:`rigidimpact.simulate.bounces.spheres`, beside pooltool
0.6.0's event-based simulation of the same shots.

Each shot is the shipped scene ``derivations/stun-shot.toml`` on a table of 3 m by
1 m (cushions at x = 0 and 3, y = 0 and 1): the cue ball starts at (1/2, 1/2) sliding
along +x at 2 m/s and meets the object ball at a cut whose line of centres is along
(4/5, 3/5) when the cue ball is at x = 1/2 + 351/800. Only the cue ball's spin differs:

- stun: backspin that friction has worn to nothing when the balls meet (t = 1/4);
- draw: twice that backspin, so the cue ball arrives with backspin and comes back;
- follow: the spin of rolling, so it rolls all the way, slowed by rolling resistance,
  and meets the object ball a little later.

The models are chosen to be the same on both sides: the balls meet without friction and
with e = 1 (pooltool's FrictionlessElastic), the cloth slides with mu = 0.2 and resists
rolling with mu_r = 0.01 and pivoting with mu_sp = 0.0127 (pooltool's rolling and
spinning friction), g = 9.8. The cushions differ: here a cushion is a rigid plane met at
the ball's equator under Newton's e and Coulomb's friction with the cloth's contact
resting; pooltool's default meets it above the equator through a compliant model
(Stronge's). So the two runs agree up to each ball's first cushion, and differ after.

One more difference, of size 1e-6: pooltool sets two balls, or a ball and a cushion,
1e-6 m apart before it resolves their collision (its ``MIN_DIST``), so each collision
happens from positions moved by up to that much; its times and positions after a
collision differ from the exact ones by about 1e-5 relative.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rigidimpact.scenes.space import parse_space_scene
from rigidimpact.simulate.space import run_space

__all__ = ["SHOTS", "scene_text", "scene", "ours", "pooltools", "side_by_side", "markdown"]

# the cue ball's spin about y at the start, per shot (rad/s)
SHOTS = {"stun": "-2450/57", "draw": "-4900/57", "follow": "4000/57"}
SHIFT = 0.5  # the shipped scene's origin on the 3 m by 1 m table
G, MU, ROLLING, PIVOT = 9.8, 0.2, 0.01, 0.0127
RADIUS, MASS = 0.0285, 0.17


def scene_text(shot: str, until: float = 8.0) -> str:
    """The shot as a 3-D scene on the table of the module's text.

    Examples
    --------
    >>> 'spin = ["0", "-2450/57", "0"]' in scene_text("stun")
    True
    """
    spin = SHOTS[shot]
    rails = [("near_rail", ("0", "0"), ("0", "1")), ("far_rail", ("0", "1"), ("0", "-1")),
             ("left_rail", ("0", "0"), ("1", "0")), ("right_rail", ("3", "0"), ("-1", "0"))]
    planes = "".join(f"""
[[planes]]
name = "{name}"
bodies = ["table", "cue"]
point = ["{p[0]}", "{p[1]}", "0"]
normal = ["{n[0]}", "{n[1]}", "0"]
restitution = "4/5"
tangential = "coulomb"
friction = "1/5"
""" for name, p, n in rails)
    return f"""title = "A {shot} shot beside pooltool"

[[bodies]]
name = "table"
shape = "fixed"

[[bodies]]
name = "cue"
shape = "sphere"
mass = "17/100"
radius = "57/2000"
position = ["1/2", "1/2", "57/2000"]
velocity = ["2", "0", "0"]
spin = ["0", "{spin}", "0"]

[[bodies]]
name = "object"
shape = "sphere"
mass = "17/100"
radius = "57/2000"
position = ["19687/20000", "2671/5000", "57/2000"]

[contact]
name = "cloth"
bodies = ["table", "cue"]
point = ["1/2", "1/2", "0"]
normal = ["0", "0", "1"]
restitution = "0"
tangential = "coulomb"
friction = "1/5"
{planes}
[[pairs]]
name = "balls"
bodies = ["cue", "object"]
restitution = "1"

[simulate]
effects = ["gravity", "rolling-resistance", "pivot-friction"]
g = {G}
rolling_resistance = {ROLLING}
pivot_friction = {PIVOT}
until = {until}
"""


def scene(shot: str, until: float = 8.0) -> Any:
    """The shot as a read 3-D scene (a :class:`~rigidimpact.scenes.space.SpaceScene`),
    followed until `until` seconds.

    Examples
    --------
    >>> [b.name for b in scene("draw").bodies]
    ['table', 'cue', 'object']
    """
    return parse_space_scene(scene_text(shot, until), f"{shot}-shot")


def ours(shot: str) -> list[tuple[float, str, str, float, float]]:
    """This package's events of the shot: (t, ball, what, x, y), what one of
    ``balls``, ``rolls``, ``cushion``, ``stops``.

    Examples
    --------
    >>> first = ours("stun")[0]
    >>> first[:3], round(first[3], 6)
    ((0.25, 'cue', 'balls'), 0.93875)
    """
    outcome = run_space(scene(shot))
    run = outcome.trajectory.run
    out = []
    for e in run.events:
        if e.kind == "impact" and e.plane == "cloth" or e.kind == "stops spinning" or \
                e.kind == "rolls" and e.t == 0:
            continue  # a landing after a cushion threw it up (pooltool keeps it down);
            # pooltool's spin about the vertical ends with no event; rolling from the start
        what = ("balls" if e.plane == "balls" else "cushion") \
            if e.kind == "impact" else e.kind
        balls = (e.ball, e.other) if e.other else (e.ball,)
        for name in balls:
            x, y = (float(v) for v in (e.position[:2] if name == e.ball else
                                       _at(run, e.t, name)[:2]))
            out.append((float(e.t), name, what, x, y))
    return out


def _at(run: Any, t: Any, name: str) -> Any:
    """A sphere's centre in the snapshot taken at time t."""
    for when, states in run.snapshots:
        if when == t:
            return states[name][0]
    raise KeyError(name)


def pooltools(shot: str) -> list[tuple[float, str, str, float, float]]:
    """pooltool's events of the same shot, in the same form (pooltool must be
    installed: ``make pooltool``)."""
    import attrs
    import numpy as np
    import pooltool as pt
    import pooltool.constants as const
    from pooltool.objects.ball.datatypes import BallState
    from pooltool.physics.resolve.ball_ball.frictionless_elastic import FrictionlessElastic

    def ball(name: str, xy: tuple[float, float], v: tuple, w: tuple, state: int) -> Any:
        made = pt.Ball.create(name, xy=xy, m=MASS, R=RADIUS, u_s=MU, u_r=ROLLING,
                              u_sp_proportionality=PIVOT / RADIUS, g=G)
        made.state = BallState(np.array([[*xy, RADIUS], v, w], dtype=float), state)
        return made

    spin = float(Fraction(SHOTS[shot]))
    cue = ball("cue", (SHIFT, SHIFT), (2.0, 0.0, 0.0), (0.0, spin, 0.0),
               const.rolling if shot == "follow" else const.sliding)
    target = ball("object", (9687 / 20000 + SHIFT, 171 / 5000 + SHIFT), (0.0, 0.0, 0.0),
                  (0.0, 0.0, 0.0), const.stationary)
    table = pt.Table.from_table_specs(pt.objects.BilliardTableSpecs(l=1.0, w=3.0))
    system = pt.System(cue=pt.Cue(cue_ball_id="cue"), table=table,
                       balls={"cue": cue, "object": target})
    resolver = attrs.evolve(pt.physics.resolve.resolver.Resolver.default(),
                            ball_ball=FrictionlessElastic())
    pt.simulate(system, engine=pt.physics.PhysicsEngine(resolver=resolver), inplace=True)
    names = {"ball_ball": "balls", "sliding_rolling": "rolls",
             "ball_linear_cushion": "cushion", "rolling_stationary": "stops",
             "rolling_spinning": "stops"}
    out = []
    for e in system.events:
        what = names.get(str(e.event_type))
        if what is None:
            continue
        for agent in e.agents:
            if agent.id in ("cue", "object"):
                final: Any = agent.final  # a ball, for these two
                x, y = final.state.rvw[0][:2]
                out.append((float(e.time), agent.id, what, float(x) - SHIFT,
                            float(y) - SHIFT))
    return out


def side_by_side(shot: str, mine: list | None = None, theirs: list | None = None
                 ) -> list[tuple[str, str, tuple, tuple]]:
    """Each ball's events up to and including its first cushion, both runs': (ball,
    what, ours (t, x, y), pooltool's (t, x, y)). Positions are in the shipped scene's
    frame (pooltool's less (1/2, 1/2))."""
    mine = ours(shot) if mine is None else mine
    theirs = pooltools(shot) if theirs is None else theirs
    rows = []
    for name in ("cue", "object"):
        a = _until_cushion([e for e in mine if e[1] == name])
        b = _until_cushion([e for e in theirs if e[1] == name])
        rows += [(name, x[2], (x[0], x[3] - SHIFT, x[4] - SHIFT), (y[0], y[3], y[4]))
                 for x, y in zip(a, b, strict=False)]
        if [x[2] for x in a] != [y[2] for y in b]:
            rows.append((name, "differs", tuple(x[2] for x in a), tuple(y[2] for y in b)))
    return rows


def _until_cushion(events: list) -> list:
    out = []
    for e in events:
        out.append(e)
        if e[2] == "cushion":
            break
    return out


def markdown(rows_by_shot: dict[str, list]) -> str:
    """The side-by-side rows as a Markdown table.

    Examples
    --------
    >>> print(markdown({"stun": [("cue", "balls", (0.25, 0.5, 0.0), (0.25, 0.5, 0.0))]}))
    | shot | ball | event | t here (s) | t pooltool (s) | x, y here (m) | x, y pooltool (m) |
    |---|---|---|---|---|---|---|
    | stun | cue | balls | 0.250000 | 0.250000 | 0.500000, 0.000000 | 0.500000, 0.000000 |
    """
    lines = ["| shot | ball | event | t here (s) | t pooltool (s) | x, y here (m) | "
             "x, y pooltool (m) |", "|---|---|---|---|---|---|---|"]
    for shot, rows in rows_by_shot.items():
        for name, what, a, b in rows:
            lines.append(f"| {shot} | {name} | {what} | {a[0]:.6f} | {b[0]:.6f} | "
                         f"{a[1]:.6f}, {a[2]:.6f} | {b[1]:.6f}, {b[2]:.6f} |")
    return "\n".join(lines)
