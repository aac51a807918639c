"""rigidimpact's impact maps of sympy.physics.mechanics systems beside Pinocchio's
``impulseDynamics`` (the robotics library's impact of a kinematic tree, package `pin`):
the same systems written both ways, their speeds after compared, and what one impact
costs in each.

- a planar chain of point masses hanging from O, its tip striking a wall (Newton's
  e = 1/2, the normal row only): rigidimpact from KanesMethod's mass matrix and the
  tip's partial velocities, Pinocchio from a tree of revolute joints (relative angles);
- the floating compass-gait biped of derivations/compass_gait.py at heel strike (e = 0
  and stick: both rows of the heel).

Run: ``python derivations/beside_pinocchio.py [--links N] [--json]`` (needs `make peers`);
with ``--kernel 100000``, the compiled maps (``SystemImpact.kernel``) over 10^5 states
at once against Pinocchio called once a state, and the same map exported as C
(:func:`rigidimpact.outputs.mapcode.impact_map_code`), compiled with gcc -O2 and called
in a loop over the states (a shared library loaded with ctypes; the column is left
out, and said, where gcc is missing).
The tests in tests/test_pinocchio.py hold the two to 1e-10 at seeded random states.
"""

from __future__ import annotations

import argparse
import ctypes
import json
import random
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import sympy as sp
import sympy.physics.mechanics as me

import rigidimpact as ri
from rigidimpact.outputs.mapcode import impact_map_code

try:
    import pinocchio as pin
except ImportError:  # the peer is optional: main() says how to get it
    pin = None

HERE = Path(__file__).resolve().parent


def point_mass(mass: float, where):
    return pin.Inertia(mass, np.array(where, float), np.zeros((3, 3)))


def chain_in_sympy(links: int):
    """The chain of tests/test_mechanics_numbers.py at numbers: point masses m = 1 on
    massless links of length l = 1 hanging from O, absolute angles q_i, the tip striking
    a wall of normal -x with Newton's e = 1/2."""
    q = me.dynamicsymbols(f"c1:{links + 1}")
    u = me.dynamicsymbols(f"w1:{links + 1}")
    frame = me.ReferenceFrame("F")
    top = me.Point("T")
    top.set_vel(frame, 0)
    tip, particles = top, []
    for i in range(links):
        link = frame.orientnew(f"L{i}", "Axis", [q[i], frame.z])
        link.set_ang_vel(frame, u[i] * frame.z)
        point = tip.locatenew(f"Q{i}", -link.y)
        point.v2pt_theory(tip, frame, link)
        particles.append(me.Particle(f"b{i}", point, 1))
        tip = point
    kane = me.KanesMethod(frame, q, u, [q[i].diff() - u[i] for i in range(links)])
    kane.kanes_equations(particles, [(p.point, -10 * p.mass * frame.y) for p in particles])
    system = ri.mechanics.impact(kane, [ri.mechanics.contact(
        tip, -frame.x, restitution=sp.Rational(1, 2), name="tip")], frame=frame)
    return system, q, u


def chain_in_pinocchio(links: int):
    """The same chain as a Pinocchio tree: revolute joints about z, each the next link's
    angle relative to its parent (q_i - q_{i-1}), a point mass at (0, -1) of each link's
    frame, and a frame at the last mass (the tip)."""
    model = pin.Model()
    parent = 0
    for i in range(links):
        place = pin.SE3.Identity() if i == 0 else pin.SE3(np.eye(3), np.array([0, -1.0, 0]))
        parent = model.addJoint(parent, pin.JointModelRZ(), place, f"j{i}")
        model.appendBodyToJoint(parent, point_mass(1.0, (0, -1, 0)), pin.SE3.Identity())
    tip = model.addFrame(pin.Frame("tip", parent, 0, pin.SE3(np.eye(3), np.array(
        [0, -1.0, 0])), pin.FrameType.OP_FRAME))
    return model, tip


def relative(values):
    """Absolute angles (or rates) to Pinocchio's relative ones."""
    return np.array([values[0]] + [values[i] - values[i - 1] for i in range(1, len(values))])


def absolute(values):
    return np.cumsum(values)


def pinocchio_after(model, frame, q, v, rows, restitution):
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    J = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return pin.impulseDynamics(model, data, q, v, J[rows, :], restitution, 0.0).copy()


def _compass_gait_module():
    sys.path.insert(0, str(HERE))
    try:
        import compass_gait as cg
    finally:
        sys.path.remove(str(HERE))
    return cg


def gait_strike():
    """(kane, the heel strike as a SystemImpact, symbol values) of :func:`compass_gait`,
    not solved: what :meth:`SystemImpact.kernel` compiles."""
    cg = _compass_gait_module()
    kane, frame, swing, _, _ = cg.legs(floating=True)
    strike = ri.mechanics.impact(kane, [ri.mechanics.contact(
        swing, frame.y, restitution=0, tangential="stick", name="heel")], frame=frame)
    values = {cg.m: 5, cg.m_H: 10, cg.a: sp.Rational(1, 2), cg.b: sp.Rational(1, 2)}
    return kane, strike, values


def chain_states(seed: int, count: int, links: int) -> tuple[np.ndarray, np.ndarray]:
    """`count` seeded states of the chain as arrays (angles, rates), each with the tip
    moving into the wall at more than 0.05 (the rates turned round where the tip moved
    away; a state that grazes the wall drawn again)."""
    rng = np.random.default_rng(seed)
    angles = rng.uniform(-1.2, 1.2, (2 * count, links))
    rates = rng.uniform(-2, 2, (2 * count, links))
    into = (np.cos(angles) * rates).sum(axis=1)
    rates[into < 0] *= -1
    kept = np.flatnonzero(np.abs(into) > 0.05)[:count]
    return angles[kept], rates[kept]


def gait_states(seed: int, count: int) -> tuple[np.ndarray, np.ndarray]:
    """`count` seeded heel-strike states of the compass gait (q: x, y, stance, swing;
    u likewise), as the tests draw them one at a time."""
    rng = np.random.default_rng(seed)
    half = rng.uniform(0.1, 0.4, count)
    q = np.stack([np.zeros(count), np.zeros(count), -half, half], axis=1)
    u = np.stack([np.zeros(count), np.zeros(count), rng.uniform(-2, -0.5, count),
                  rng.uniform(-2, 1, count)], axis=1)
    return q, u


def compass_gait():
    """(kane, rigidimpact's heel-strike solution, symbol values, Pinocchio's model and its
    heel frame) for the compass-gait biped: x and y of the stance foot, the stance leg's
    angle (from the slope's normal, the leg along its frame's +y), the swing leg's angle
    relative to it at the hip (the swing leg along its frame's -y); masses m = 5 at
    a = 1/2 on the stance leg, m_H = 10 at the hip, m at b = 1/2 below the hip."""
    cg = _compass_gait_module()
    kane, _, solution = cg.heel_strike()
    values = {cg.m: 5, cg.m_H: 10, cg.a: sp.Rational(1, 2), cg.b: sp.Rational(1, 2)}
    return (kane, solution, values, *gait_in_pinocchio())


def gait_in_pinocchio():
    """The compass gait of :func:`compass_gait` as a Pinocchio tree, and its heel frame."""
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelPX(), pin.SE3.Identity(), "x")
    j = model.addJoint(j, pin.JointModelPY(), pin.SE3.Identity(), "y")
    j = model.addJoint(j, pin.JointModelRZ(), pin.SE3.Identity(), "stance")
    model.appendBodyToJoint(j, point_mass(5.0, (0, 0.5, 0)) + point_mass(10.0, (0, 1.0, 0)),
                            pin.SE3.Identity())
    j = model.addJoint(j, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([0, 1.0, 0])),
                       "swing")
    model.appendBodyToJoint(j, point_mass(5.0, (0, -0.5, 0)), pin.SE3.Identity())
    heel = model.addFrame(pin.Frame("heel", j, 0, pin.SE3(np.eye(3), np.array(
        [0, -1.0, 0])), pin.FrameType.OP_FRAME))
    return model, heel


def chain_state(rng: random.Random, links: int) -> tuple[list[float], list[float]]:
    """Seeded angles and rates of the chain, the tip moving into the wall (+x)."""
    while True:  # a state that grazes the wall (|speed into it| <= 0.05) drawn again
        angles = [rng.uniform(-1.2, 1.2) for _ in range(links)]
        rates = [rng.uniform(-2, 2) for _ in range(links)]
        into = sum(np.cos(a) * w for a, w in zip(angles, rates, strict=True))
        if abs(into) > 0.05:
            return angles, (rates if into > 0 else [-w for w in rates])


def _per_call(run, repeat: int) -> float:
    begin = time.perf_counter()
    for _ in range(repeat):
        run()
    return (time.perf_counter() - begin) / repeat


def costs(links: int = 5, repeat: int = 20) -> list[dict]:
    """Seconds per impact of each path (the mean of `repeat` calls in this process)."""
    rows = []
    system, q, u = chain_in_sympy(links)
    model, tip = chain_in_pinocchio(links)
    angles, rates = chain_state(random.Random(45), links)
    point = {**dict(zip(q, map(sp.Float, angles), strict=True)),
             **dict(zip(u, map(sp.Float, rates), strict=True))}
    ours = [float(x) for x in system.at(point).solve().speeds_after]
    theirs = absolute(pinocchio_after(model, tip, relative(angles), relative(rates), [0], 0.5))
    rows.append({"system": f"chain of {links}, tip on a wall",
                 "rigidimpact at numbers": _per_call(lambda: system.at(point).solve(),
                                                     max(1, repeat // 10)),
                 "pinocchio": _per_call(lambda: pinocchio_after(
                     model, tip, relative(angles), relative(rates), [0], 0.5), repeat * 50),
                 "largest difference": float(np.max(np.abs(np.array(ours) - theirs)))})
    kane, solution, values, model, heel = compass_gait()
    x, y, st, sw = kane.q
    ux, uy, w_st, w_sw = kane.u
    closed = sp.lambdify([st, sw, ux, uy, w_st, w_sw],
                         list(solution.speeds_after.xreplace({x: 0, y: 0, **values})),
                         "numpy", cse=True)
    half, before = 0.25, [0.0, 0.0, -1.1, -0.4]
    ours = closed(-half, half, *before)
    q_pin = np.array([0.0, 0.0, -half, 2 * half])
    v_pin = np.array([*before[:3], before[3] - before[2]])
    theirs = pinocchio_after(model, heel, q_pin, v_pin, [0, 1], 0.0)
    theirs[3] += theirs[2]
    rows.append({"system": "compass gait, heel strike",
                 "rigidimpact at numbers": None,
                 "rigidimpact closed form, evaluated": _per_call(
                     lambda: closed(-half, half, *before), repeat * 50),
                 "pinocchio": _per_call(lambda: pinocchio_after(
                     model, heel, q_pin, v_pin, [0, 1], 0.0), repeat * 50),
                 "largest difference": float(np.max(np.abs(np.array(ours, float) - theirs)))})
    return rows


def compiled_map(system, values=None):
    """The impact map as C, compiled with gcc -O2 into a shared library and loaded with
    ctypes: a function of q (N, len q) and u (N, len u) giving the speeds after (NaN
    where the map is not the impact), the loop over the states in C; None without gcc."""
    if shutil.which("gcc") is None:
        return None
    folder = Path(tempfile.mkdtemp(prefix="impact-map-"))
    source, library = folder / "impact_map.c", folder / "impact_map.so"
    source.write_text(impact_map_code(system, values))
    subprocess.run(["gcc", "-O2", "-shared", "-fPIC", "-o", str(library), str(source), "-lm"],
                   check=True)
    many = ctypes.CDLL(str(library)).impact_map_many
    shutil.rmtree(folder)  # loaded: the library stays mapped after its file is gone
    array = ctypes.POINTER(ctypes.c_double)
    many.restype, many.argtypes = ctypes.c_long, [ctypes.c_long, array, array, array]

    def run(q, u):
        q, u = np.ascontiguousarray(q, float), np.ascontiguousarray(u, float)
        after = np.empty_like(u)
        many(len(q), q.ctypes.data_as(array), u.ctypes.data_as(array),
             after.ctypes.data_as(array))
        return after
    return run


def kernel_costs(count: int = 10**5, links: int = 5, repeat: int = 3) -> list[dict]:
    """Seconds per state of rigidimpact's kernel of each impact map over `count` states
    at once (:meth:`SystemImpact.kernel`; compiling it excluded, the best of `repeat`
    calls) against Pinocchio called once a state from Python (over 2,000 states), and
    the largest difference between the two over the first 1,000 states."""
    rows = []
    system, _, _ = chain_in_sympy(links)
    model, tip = chain_in_pinocchio(links)
    kernel = system.kernel()
    q, u = chain_states(45, count, links)

    def theirs_chain(k):
        return absolute(pinocchio_after(model, tip, relative(q[k]), relative(u[k]), [0], 0.5))

    rows.append(_kernel_row(f"chain of {links}, tip on a wall", kernel, q, u, theirs_chain,
                            repeat, compiled_map(system)))
    kane, strike, values = gait_strike()
    kernel = strike.kernel(values)
    model, heel = gait_in_pinocchio()
    q, u = gait_states(45, count)

    def theirs_gait(k):
        q_pin = np.array([0.0, 0.0, q[k, 2], q[k, 3] - q[k, 2]])
        v_pin = np.array([*u[k, :3], u[k, 3] - u[k, 2]])
        after = pinocchio_after(model, heel, q_pin, v_pin, [0, 1], 0.0)
        after[3] += after[2]
        return after

    rows.append(_kernel_row("compass gait, heel strike", kernel, q, u, theirs_gait, repeat,
                            compiled_map(strike, values)))
    return rows


def _kernel_row(name, kernel, q, u, theirs, repeat, in_c=None) -> dict:
    best = min(_per_call(lambda: kernel(q, u), 1) for _ in range(repeat))
    found = kernel(q, u)
    if found.warnings:
        raise RuntimeError(f"{name}: " + "; ".join(found.warnings))
    checked = min(1000, len(q))
    gap = max(float(np.max(np.abs(found.speeds_after[k] - theirs(k)))) for k in range(checked))
    calls = min(2000, len(q))
    per_call = _per_call(lambda: [theirs(k) for k in range(calls)], 1) / calls
    row = {"system": name, "states": len(q), "kernel per state": best / len(q),
           "pinocchio per state": per_call, "largest difference": gap}
    if in_c is not None:  # the same map in C, compiled: the loop over the states in C
        row["C per state"] = min(_per_call(lambda: in_c(q, u), 1) for _ in range(repeat)) \
            / len(q)
        after = in_c(q, u)
        row["C against the kernel"] = float(np.max(np.abs(after - found.speeds_after)))
        row["C against pinocchio"] = max(float(np.max(np.abs(after[k] - theirs(k))))
                                         for k in range(checked))
    return row


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, default=5)
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--kernel", type=int, metavar="STATES", default=0,
                        help="time the compiled maps over this many states at once "
                             "against Pinocchio called once a state, instead")
    args = parser.parse_args(argv)
    if pin is None:
        print("beside_pinocchio: Pinocchio is not installed (make peers installs it)",
              file=sys.stderr)
        return 2
    rows = kernel_costs(args.kernel, args.links) if args.kernel > 0 else costs(args.links)
    if args.kernel > 0 and shutil.which("gcc") is None:
        print("beside_pinocchio: no gcc here: the map in C is left out", file=sys.stderr)
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    for row in rows:
        print(row["system"])
        for key, value in row.items():
            if key != "system" and value is not None:
                unit = "" if "differ" in key or "against" in key or key == "states" else \
                    " s" if "per state" in key else " s per impact"
                print(f"  {key}: {value:.3g}{unit}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
