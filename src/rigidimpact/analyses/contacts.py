"""Several contacts at scale: each rule timed against the number of contacts, with the
baselines run side by side (``rigidimpact bench --family contacts``; the measured table
is docs/bench-contacts.md).

The cases: a cradle (a chain of balls), a hexagonal cluster of discs struck by one ball,
a fan (one striker touching k discs at once, so W is dense), and the rough family (a
spinning chain and the fan with every contact Coulomb). The baselines: trying every set
of acting contacts or every combination of contact states, a plain dense solve_ivp of
the same Hertz chain, pymunk on the same cluster (where installed), and for the fan the
exact step by elimination over W in Fractions.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from dataclasses import replace
from typing import Any

import numpy as np
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.solve.collision import Collision, chain, cluster, fan
from rigidimpact.solve.lcp import confirm
from rigidimpact.solve.rules import simultaneous as simultaneous_rule

__all__ = ["contacts_family", "rough_chain", "rough_cluster", "rough_fan", "CLUSTER_SIDES",
           "rough_exact_against_floating"]


CLUSTER_SIDES = (2, 3, 4, 6, 8, 12, 16, 19)  # a side x side cluster: 6 ... 1028 contacts
ROUGH_CHAIN_FRICTION, ROUGH_FAN_FRICTION = sp.Rational(1, 4), sp.Rational(1, 3)
ROUGH_CLUSTER_FRICTION = sp.Rational(1, 4)
# rows x columns of the rough cluster: up to 1,000 discs (2,872 contacts)
ROUGH_CLUSTERS = ((2, 2), (4, 4), (8, 8), (12, 12), (16, 16), (25, 40))


def _dense_chain_seconds(n: int) -> float:
    """The plain way for a chain of n Hertz balls (stiffness 1, unit masses, striker at
    1): scipy's solve_ivp (LSODA) on the dense state, every ball's x velocity, every
    contact's depth, rhs by dense matrix products, over the time the wave takes to cross
    the chain (0.84 balls per unit time here, and a third more)."""
    from scipy.integrate import solve_ivp

    k = n - 1
    J = np.zeros((k, n))
    J[np.arange(k), np.arange(k)], J[np.arange(k), np.arange(k) + 1] = -1.0, 1.0

    def rhs(_, y):
        u, depth = y[:n], y[n:]
        f = np.where(depth > 0, np.maximum(depth, 0.0) ** 1.5, 0.0)
        return np.concatenate([J.T @ f, -(J @ u)])

    y0 = np.zeros(n + k)
    y0[0] = 1.0
    begin = time.perf_counter()
    solve_ivp(rhs, (0.0, 1.33 * n / 0.84), y0, method="LSODA", rtol=1e-10, atol=1e-10)
    return time.perf_counter() - begin


def _pymunk_cluster_seconds(side: int) -> float | None:
    """The same hexagonal cluster in pymunk (elastic circles, no friction), stepped for
    the time a wave takes to cross it; None when pymunk is not installed."""
    try:
        import pymunk
    except ImportError:
        return None
    begin = time.perf_counter()
    space = pymunk.Space()
    space.iterations = 50
    for i in range(side):
        for j in range(side):
            body = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0, 0.5))
            body.position = (j + 0.5 * (i % 2), i * math.sqrt(3) / 2)
            shape = pymunk.Circle(body, 0.5)
            shape.elasticity, shape.friction = 1.0, 0.0
            space.add(body, shape)
    striker = pymunk.Body(1.0, pymunk.moment_for_circle(1.0, 0, 0.5))
    middle = (side - 1) // 2
    striker.position = (0.5 * (middle % 2) - 1 - 1e-9, middle * math.sqrt(3) / 2)
    striker.velocity = (1.0, 0.0)
    shape = pymunk.Circle(striker, 0.5)
    shape.elasticity, shape.friction = 1.0, 0.0
    space.add(striker, shape)
    for _ in range(100 * side):
        space.step(0.01)
    return time.perf_counter() - begin


def pymunk_rough_cluster(rows: int, columns: int, iterations: int,
                         friction: Any = ROUGH_CLUSTER_FRICTION
                         ) -> tuple[float, list[tuple[float, float, float]]] | None:
    """The rough cluster of :func:`rough_cluster` in pymunk: one step of its impulse
    solver with `iterations` sweeps, no gravity. pymunk aims each contact at a normal
    velocity of -e times its closing one (Newton's law at the velocity level) and
    clamps friction to the cone, the conditions of the simultaneous rule with friction,
    sweep by sweep (projected Gauss-Seidel) rather than exactly. Discs are made 1e-9
    larger, so that touching pairs count as contacts (pymunk leaves overlaps below its
    slop alone). Returns (seconds, each body's (vx, vy, omega) after, striker first,
    in :func:`rigidimpact.solve.collision.cluster`'s order), or None without pymunk."""
    try:
        import pymunk
    except ImportError:
        return None
    radius, grip = 0.5 * (1 + 1e-9), math.sqrt(float(friction))
    begin = time.perf_counter()
    space = pymunk.Space()
    space.iterations = iterations
    middle = (rows - 1) // 2
    places = [(0.5 * (middle % 2) - 1, middle * math.sqrt(3) / 2)]
    places += [(j + 0.5 * (i % 2), i * math.sqrt(3) / 2)
               for i in range(rows) for j in range(columns)]
    bodies = []
    for k, place in enumerate(places):
        body = pymunk.Body(1.0, 0.125)  # mass 1, radius 1/2: inertia 1/8
        body.position = place
        body.velocity = (1.0, 0.0) if k == 0 else (0.0, 0.0)
        shape = pymunk.Circle(body, radius)
        shape.elasticity, shape.friction = 1.0, grip  # pymunk multiplies the two
        space.add(body, shape)
        bodies.append(body)
    space.step(1e-6)
    seconds = time.perf_counter() - begin
    return seconds, [(b.velocity.x, b.velocity.y, b.angular_velocity) for b in bodies]


def _given(seconds: float) -> Callable[[], float]:
    """A baseline already run: its seconds."""
    return lambda: seconds


def _beside_pymunk(shape: tuple[int, int], solution: Any,
                   baseline: Callable[[str, Callable[[], float | None]], float | None]
                   ) -> dict[str, Any]:
    """pymunk's one step on the same rough cluster with 10 and 1,000 sweeps: its
    seconds and the largest difference of its speeds (vx, vy, omega) from `solution`'s."""
    ours = [(float(b.velocity[0]), float(b.velocity[1]), float(b.spin))
            for b in solution.after]
    found: dict[str, Any] = {}
    for sweeps in (10, 1000):
        ran = pymunk_rough_cluster(*shape, sweeps)
        if ran is None:
            continue
        seconds, theirs = ran
        found[f"pymunk_{sweeps}_s"] = baseline(f"pymunk {sweeps}", _given(seconds))
        found[f"pymunk_{sweeps}_gap"] = max(abs(a - b) for p, q in zip(ours, theirs,
                                                                        strict=True)
                                            for a, b in zip(p, q, strict=True))
    return found


def _fraction_elimination_seconds(problem: Collision) -> float:
    """The exact step as it was before the saddle-point elimination: the acting block
    of W (every contact of a fan acts) eliminated over Python's Fractions, timed alone
    (forming W is not counted)."""
    from fractions import Fraction

    n = len(problem.contacts)
    v = problem.velocity_before
    target = [-c.restitution * min(v[i], 0) for i, c in enumerate(problem.contacts)]
    rows: dict[int, dict[int, Fraction]] = {i: {} for i in range(n)}
    for (i, j), x in problem.W.todok().items():
        rows[i][j] = Fraction(int(x.p), int(x.q))
    q = [Fraction(int(x.p), int(x.q)) for x in (v[i] - target[i] for i in range(n))]
    begin = time.perf_counter()
    confirm(rows, q, range(n))
    return time.perf_counter() - begin


def _measure(solve: Callable[[], Any], memory: bool) -> tuple[float, float | None]:
    """Seconds of one run, and with `memory` the peak of Python allocations (MiB) in a
    second run under tracemalloc (which slows it, so it is not the timed one)."""
    import tracemalloc

    begin = time.perf_counter()
    solve()
    seconds = time.perf_counter() - begin
    if not memory:
        return seconds, None
    tracemalloc.start()
    try:
        solve()
        peak = tracemalloc.get_traced_memory()[1] / 2**20
    finally:
        tracemalloc.stop()
    return seconds, peak




def rough_chain(n: int, friction: Any = ROUGH_CHAIN_FRICTION) -> Collision:
    """A cradle of n balls that also move across the line and spin, every contact rough
    (Coulomb, `friction`): each contact slips, so friction acts at every one."""
    built = chain(n)
    bodies = tuple(replace(b, velocity=(b.velocity[0], sp.Rational((-1) ** k, k + 2)),
                           spin=sp.Rational(k % 3 - 1, 2)) for k, b in enumerate(built.bodies))
    return Collision(bodies, tuple(replace(t, tangential="coulomb", friction=friction)
                                   for t in built.contacts))


def rough_fan(k: int, friction: Any = ROUGH_FAN_FRICTION) -> Collision:
    """The fan of k discs (:func:`rigidimpact.solve.collision.fan`), every contact rough."""
    built = fan(k)
    return Collision(built.bodies, tuple(replace(t, tangential="coulomb", friction=friction)
                                         for t in built.contacts))


def rough_cluster(rows: int, columns: int, friction: Any = ROUGH_CLUSTER_FRICTION
                  ) -> Collision:
    """The hexagonal cluster of `rows` x `columns` discs struck by one ball
    (:func:`rigidimpact.solve.collision.cluster`, elastic), every contact rough."""
    built = cluster(rows, columns)
    return Collision(built.bodies, tuple(replace(t, tangential="coulomb", friction=friction)
                                         for t in built.contacts))


def _states_seconds(make: Callable[[], Collision]) -> float:
    """The rough simultaneous rule by trying every combination of contact states (its
    method for a few contacts), timed; InputError past its budget of tried
    combinations (MAX_STATES_WORK)."""
    saved = simultaneous_rule.MAX_FRICTION_STATES, simultaneous_rule.STATES_DIRECT
    simultaneous_rule.MAX_FRICTION_STATES, simultaneous_rule.STATES_DIRECT = 10**300, False
    try:
        problem = make()
        begin = time.perf_counter()
        problem.simultaneous()
        return time.perf_counter() - begin
    finally:
        simultaneous_rule.MAX_FRICTION_STATES, simultaneous_rule.STATES_DIRECT = saved


def _rules(case: str, size: int, make: Callable[[], Collision],
           baseline: Callable[[str, Callable[[], float | None]], float | None],
           enumeration: Callable[[Collision], float]) -> list[tuple[str, Callable[[], Any],
                                                                    dict[str, Any]]]:
    """The rules timed on one problem, each with its baselines' seconds."""
    if case.startswith("rough"):  # the simultaneous rule with friction
        return [("simultaneous (rough)", lambda: make().simultaneous(), {
            "states_s": baseline(f"{case} states", lambda: _states_seconds(make))})]
    order = tuple(t.name for t in make().contacts)
    exact_step = {"fraction_elimination_s": baseline(  # W dense: the exact step by
        "fraction elimination", lambda: _fraction_elimination_seconds(make()))} \
        if case == "fan" else {  # elimination over W
            "enumeration_s": baseline(f"{case} enumeration", lambda: enumeration(make()))}
    rules: list[tuple[str, Callable[[], Any], dict[str, Any]]] = [
        ("simultaneous", lambda: make().simultaneous(), exact_step)]
    if case != "fan":  # the fan is here for its dense W, which only acting together sees
        rules.append(("sequential", lambda: make().sequential(order), {}))
    if case == "cradle":
        rules.append(("compliant (Hertz)", lambda: make().compliant(1.0, hertz=True), {
            "dense_solve_ivp_s": baseline("dense", lambda: _dense_chain_seconds(size + 1))}))
    elif case == "cluster":
        rules.append(("compliant", lambda: make().compliant(1.0), {
            "pymunk_s": baseline("pymunk", lambda: _pymunk_cluster_seconds(size))}))
    return rules


def contacts_family(quick: bool = False, limit: float = 60.0, memory: bool = True,
                    shapes: Iterable[str] = ("cradle", "cluster", "fan", "rough-chain",
                                             "rough-fan", "rough-cluster")) -> dict[str, Any]:
    """Each rule against the number of contacts, on a cradle (a chain of n + 1 balls),
    a hexagonal cluster of discs struck by one ball and a fan (one striker touching k
    discs at once: W dense; the simultaneous rule only), with side by side baselines:
    trying every set of acting contacts (the simultaneous rule's method before Lemke's,
    while it finishes within `limit` seconds), a plain dense solve_ivp of the same Hertz
    chain (the compliant rule's baseline, likewise), pymunk on the same cluster (if
    installed), and for the fan the exact step by elimination over W in Fractions. The
    rough family (a spinning chain, the fan and the cluster, every contact Coulomb)
    times the simultaneous rule with friction beside trying every combination of
    contact states, and for the cluster pymunk's impulse solver (10 and 1,000 sweeps),
    with the largest difference of its speeds from ours. One run each. Rows: case,
    rule, n, seconds, peak MiB, the baselines' seconds (None: not run, past the limit
    or not installed); and the exponent of a power law fitted to each curve. `shapes`
    picks the cases."""
    chains: tuple[int, ...] = (8, 32, 128) if quick else (2, 4, 8, 16, 32, 64, 128, 256,
                                                          512, 1024)
    sides: tuple[int, ...] = (2, 4, 8) if quick else CLUSTER_SIDES
    rows: list[dict[str, Any]] = []
    stopped: set[str] = set()

    def baseline(key: str, run: Callable[[], float | None]) -> float | None:
        if key in stopped:
            return None
        try:
            seconds = run()
        except InputError:  # past the enumeration's own time budget
            seconds = None
        if seconds is None or seconds > limit / 10:  # the next size would pass the limit
            stopped.add(key)
        return seconds

    def enumeration(problem: Collision) -> float:
        v = problem.velocity_before
        e = [c.restitution for c in problem.contacts]
        target = sp.Matrix([-e[i] * min(v[i], 0) for i in range(len(v))])
        begin = time.perf_counter()
        simultaneous_rule._complementarity(problem, v, target)
        return time.perf_counter() - begin

    fans: tuple[int, ...] = (16, 64) if quick else (16, 32, 64, 128, 256, 512, 1000)
    roughs: tuple[int, ...] = (4, 16, 64) if quick else (2, 4, 8, 16, 32, 64, 128, 256, 512,
                                                         1024)
    cases: list[tuple[str, Any, Any]] = [("cradle", n, lambda n=n: chain(n + 1))
                                         for n in chains]
    cases += [("rough-chain", n, lambda n=n: rough_chain(n + 1)) for n in roughs]
    cases += [("rough-fan", k, lambda k=k: rough_fan(k)) for k in roughs]
    cases += [("cluster", side, lambda side=side: cluster(side, side)) for side in sides]
    cases += [("rough-cluster", shape, lambda shape=shape: rough_cluster(*shape))
              for shape in (ROUGH_CLUSTERS[:3] if quick else ROUGH_CLUSTERS)]
    cases += [("fan", k, lambda k=k: fan(k)) for k in fans]
    cases = [c for c in cases if c[0] in set(shapes)]
    for case, size, make in cases:
        for rule, solve, baselines in _rules(case, size, make, baseline, enumeration):
            answer: list[Any] = []

            def kept(solve: Callable[[], Any] = solve, answer: list[Any] = answer) -> None:
                answer.append(solve())

            seconds, peak = _measure(kept, memory)
            if case == "rough-cluster":  # pymunk on the same cluster, and how far apart
                baselines.update(_beside_pymunk(size, answer[0], baseline))
            rows.append({"case": case, "rule": rule, "n": len(make().contacts),
                         "seconds": seconds, "peak_mib": peak, **baselines})
    exponents = {}
    for case, rule in {(r["case"], r["rule"]) for r in rows}:
        points = [(r["n"], r["seconds"]) for r in rows
                  if r["case"] == case and r["rule"] == rule and r["n"] >= 16]
        if len(points) >= 2:
            x, y = np.log([p[0] for p in points]), np.log([p[1] for p in points])
            exponents[f"{case} {rule}"] = float(np.polyfit(x, y, 1)[0])
    return {"rows": rows, "exponents": dict(sorted(exponents.items()))}


def rough_exact_against_floating(repeats: int = 3, exact: int = 400, floating: int = 1000,
                                 shapes: Iterable[str] = ("rough-chain", "rough-fan")
                                 ) -> dict[str, dict[str, float]]:
    """The rough chain and the rough fan solved exactly at `exact` contacts (found in
    floating point, confirmed in the rationals) against the same cases at `floating`
    contacts, solved in floating point alone (past the exact path's 400): the
    simultaneous rule's own seconds, building excluded, the four timed in turn; medians.
    RuntimeError if the smaller answers are not exact (every residual zero) or the
    larger ones are. `shapes` picks the cases.

    Examples
    --------
    >>> found = rough_exact_against_floating(1, exact=8, floating=401, shapes=["rough-chain"])
    >>> sorted(found["rough-chain"])
    ['exact_s', 'floating_s', 'ratio']
    """
    known: dict[str, Callable[[int], Collision]] = {
        "rough-chain": lambda n: rough_chain(n + 1), "rough-fan": rough_fan}
    cases = {case: known[case] for case in shapes}
    samples: dict[tuple[str, int], list[float]] = {}
    for _ in range(repeats):
        for case, make in cases.items():
            for size in (exact, floating):
                problem = make(size)
                begin = time.perf_counter()
                answer = problem.simultaneous()
                samples.setdefault((case, size), []).append(time.perf_counter() - begin)
                if (max(answer.checks.values()) == 0) != (size == exact):
                    raise RuntimeError(f"{case} of {size} contacts: the answer is "
                                       f"{'not ' if size == exact else ''}exact")
    found = {}
    for case in cases:
        exact_s, floating_s = (float(np.median(samples[case, size]))
                               for size in (exact, floating))
        found[case] = {"exact_s": exact_s, "floating_s": floating_s,
                       "ratio": exact_s / floating_s}
    return found
