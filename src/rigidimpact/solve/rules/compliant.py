"""The compliant rule: every contact a push-only spring-dashpot (linear, its damping
set by e) or an elastic Hertz spring, integrated numerically until all let go; the
stiffnesses' ratios decide the outcome.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.compliance import damping_ratio_for
from rigidimpact.laws.law import NewtonRestitution
from rigidimpact.lazy import deferred
from rigidimpact.solve.problem import ImpulseRows
from rigidimpact.solve.rules.base import Rule, RuleSettings
from rigidimpact.solve.solution import Solution

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

# the compliant rule integrates at rtol 1e-10; an elastic Hertz chain of 3 to 8 balls kept
# its energy to 6e-10 to 9e-10: a gain is reported only beyond 1000 times the rtol
COMPLIANT_ENERGY_TOLERANCE = 1e-7


PERSISTENT_FROM = 200  # contacts: past it one integrator for every window (see below)
MAX_WINDOWS = 2000  # the compliant rule's integration windows before it gives up


# the compliant rule ends once no contact is pressed deeper than this many times the
# integrator's absolute tolerance and none closes faster than this many times its
# relative tolerance of the fastest closing speed before: less is the integration's
# own error (a long Hertz chain leaves such traces behind its wave, which would
# otherwise be followed for a thousand times as long)
NOISE = 1000


@dataclass(frozen=True)
class Compliant(Rule):
    """Every contact a push-only spring (linear with damping from e, or Hertz's), with
    one stiffness per contact in their order (N/m)."""

    stiffness: tuple[float, ...] | float = 1e6
    hertz: bool = False
    name: ClassVar[str] = "compliant"
    stated_tolerance: ClassVar[float | None] = 1e-6
    may_stay_closing: ClassVar[bool] = True
    said: ClassVar[str] = (
        "every contact a push-only spring-dashpot (linear, damping from e) or an elastic "
        "Hertz spring, integrated until all let go (floating point)")
    impulse_words: ClassVar[str] = "{name}'s spring impulse, integrated"
    summary: ClassVar[str] = ("every contact a push-only spring-dashpot, integrated (LSODA, "
                              "rtol 1e-10) until all let go")

    def __post_init__(self) -> None:
        values = self.stiffness if isinstance(self.stiffness, (tuple, list)) \
            else (self.stiffness,)
        for value in values:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                    not math.isfinite(value) or value <= 0:
                raise InputError("stiffness", "every contact stiffness must be a positive "
                                 f"finite number, not {value!r}")
        if not isinstance(self.hertz, bool):
            raise InputError("hertz", f"must be True or False, not {self.hertz!r}")

    @classmethod
    def from_settings(cls, settings: RuleSettings) -> Compliant:
        stiffness, hertz = settings.compliance
        return cls(stiffness, hertz)

    def outcomes(self, problem: ImpulseRows) -> tuple[Solution, ...]:
        return (compliant(problem, self.stiffness, self.hertz),)


def compliant(problem: ImpulseRows, stiffness: Sequence[float] | float = 1e6, hertz: bool = False,
              tolerance: float = 1e-10, record: bool = False) -> Solution:
    """Every contact a push-only spring-dashpot, integrated until all have let go.

    The contact's compression grows at its closing speed, ``d' = -(J u)``, and it
    pushes with ``k d + c d'`` (``k d^(3/2)`` with `hertz`, elastic only), never
    pulling; ``u' = M^-1 J^T f``. The bodies do not move appreciably during the
    contact, so the geometry is that of the instant of impact (the limit the rigid
    rules describe). A linear contact's damping follows from its e (see
    :mod:`rigidimpact.laws.compliance`, on the contact's effective mass ``1/W_ii``), which
    gives back exactly e for that contact alone. Equal stiffnesses give a result
    independent of their size; the ratios between contacts decide it, and as one
    contact grows far stiffer than the next, the result tends to the sequential
    rule in that order. With `record`, the outcome's ``history`` holds the
    integrator's times and the generalized velocities u there (rows: coordinates).
    The integration's energy error grows with the contacts (about k times the
    tolerance: 1e-7 for a 1000-ball Hertz chain at the default), and the outcome's
    energy tolerance says so.

    Examples
    --------
    >>> from rigidimpact.solve.collision import chain
    >>> out = chain(2).compliant()
    >>> round(float(out.results()["ball1.vx"]), 6)
    1.0
    """
    from scipy.integrate import ode, solve_ivp

    problem.numbers_only("compliant")
    problem.smooth_only("under the compliant rule")
    for t in problem.contacts:  # the springs' damping is chosen to give Newton's e
        if type(t.laws[0]).leaving is not NewtonRestitution.leaving:
            raise InputError(f"{t.name}.law", f"the {t.laws[0].name} law has no "
                             "spring-dashpot form: use the simultaneous or sequential "
                             "rule")
    k = len(problem.contacts)
    moved, J, JT, accelerate, compliance, force = _springs(problem, stiffness, hertz)
    n = len(moved)

    def rhs(_, y):
        u, depth = y[:n], y[n:n + k]
        rate = -(J @ u)
        f = force(depth, rate)
        return np.concatenate([accelerate(f), rate, f])

    u_all = np.array(problem.u_before.evalf(), dtype=float).ravel()
    y = np.concatenate([u_all[moved], np.zeros(k), np.zeros(k)])
    speed = float(max(abs(v) for v in problem.scaled_velocity_before))
    # `compliance`: each contact's effective mass 1 / W_ii over its stiffness k
    if hertz:  # a Hertz contact lasts about 3 (m^2 / (k^2 v))^(1/5)
        period = 3 * float((compliance ** 2 / speed).max() ** 0.2)
    else:
        period = math.pi * float(np.sqrt(compliance).max())
    # LSODA (compiled, switching between Adams and BDF as the problem asks) with the
    # Jacobian's sparsity given as a band: u couples to the depths and impulses only
    # through the sparse J, and the state, ordered by reverse Cuthill-McKee, has a
    # narrow band (a chain's a few wide), so a stiff stretch costs a band
    # factorisation, not LSODA's dense n^2 one
    order, place, band = _banded(J, JT, problem.dense)

    def ordered(t, y):
        return rhs(t, y[place])[order]

    times, states, elapsed, window = [], [], 0.0, period
    atol = tolerance * max(speed, 1.0) * period
    # past PERSISTENT_FROM contacts one LSODA integrator runs on through the windows on
    # one clock, and restarts on its own work arrays after a free flight: every fresh
    # start of LSODA (each call of solve_ivp, each set_initial_value) allocates work
    # arrays the size of the state's band that scipy 1.17 does not give back (see
    # scipy issue 10070), which grew a 954-contact cluster to 569 MiB
    persistent, clock, restart = None, 0.0, True
    if k >= PERSISTENT_FROM and not record:
        persistent = ode(ordered).set_integrator(
            "lsoda", rtol=tolerance, atol=atol, lband=band, uband=band, nsteps=10**7)
    for rounds in range(MAX_WINDOWS):  # until every contact has let go, none closing
        if persistent is not None:
            if restart:
                _restart(persistent, y[order], clock)
                restart = False
            clock += window
            end = persistent.integrate(clock)
            if not persistent.successful():
                raise InputError("impact.rule", "the compliant contacts' integration "
                                 "failed (LSODA); please report the scene")
            y = end[place]
        else:
            run = solve_ivp(ordered, (0.0, window), y[order], method="LSODA",
                            rtol=tolerance, atol=atol, lband=band, uband=band,
                            t_eval=None if record else [window])  # else only the end
            run.y = run.y[place]
            y = run.y[:, -1]
        if record:
            times.append(run.t + elapsed)
            full = np.repeat(u_all[:, None], len(run.t), axis=1)
            full[moved] = run.y[:n]
            states.append(full)
        elapsed += window
        u, depth = y[:n], y[n:n + k]
        closing = -(J @ u)
        free = np.all(depth <= NOISE * atol)
        if free and np.all(closing <= NOISE * tolerance * speed):
            break
        if free:  # free flight until the next contact closes: exact
            soon = closing > NOISE * tolerance * speed
            wait = float(np.min(-depth[soon] / closing[soon]))
            y = y.copy()
            y[n:n + k] = np.minimum(depth + closing * wait, 0.0)
            elapsed += wait
            restart = True
            window = period
        elif rounds >= 10:  # a long chain: the windows grow, so they stay few
            window *= 1.5
    else:
        raise InputError("impact.rule", "the compliant contacts did not let go")
    u_all[moved] = y[:n]
    y = np.concatenate([u_all, y[n:]])
    n = len(u_all)
    u_after = sp.Matrix([sp.Float(x, 17) for x in y[:n]])
    impulses = sp.Matrix([sp.Float(x, 17) for x in y[n + k:]])
    history = (np.concatenate(times), np.concatenate(states, axis=1)) if record else None
    return problem.outcome("compliant", (), u_after,
                   {t.name: impulses[i] for i, t in enumerate(problem.contacts)},
                   tuple(t.name for t, p in zip(problem.contacts, impulses, strict=True)
                         if p > 0), history=history,
                   energy_tolerance=max(COMPLIANT_ENERGY_TOLERANCE, 10 * k * tolerance))


def _restart(solver: Any, y: Any, t: float) -> None:
    """Start `solver` (scipy's ``ode`` with LSODA) afresh from y at t on the work arrays
    it already has (LSODA's istate = 1): ``set_initial_value`` would allocate new ones,
    and the old ones are not given back (scipy 1.17, pinned)."""
    integrator: Any = getattr(solver, "_integrator", None)
    if getattr(integrator, "call_args", None) is None or len(solver._y) != len(y):
        solver.set_initial_value(y, t)
        return
    solver._y = np.array(y, dtype=float)
    solver.t = t
    integrator.call_args[3] = 1  # istate 1: a new problem, the same arrays
    integrator.istate = 1


def _banded(J: Any, JT: Any, dense: bool) -> tuple[np.ndarray, np.ndarray, int]:
    """The state's order (reverse Cuthill-McKee), its inverse and the half-width of the
    band that ordering gives the Jacobian of (u, depths, impulses): u couples to the
    depths and impulses only through the sparse J."""
    import scipy.sparse as sps
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    k, n = J.shape
    none = sps.csr_matrix((n, k))  # u', depth', impulse' against u, depth, impulse
    coupled = sps.csr_matrix(np.ones((n, n))) if dense else JT @ J
    pattern = sps.bmat([[coupled, JT, none], [J, None, None], [J, sps.identity(k), None]],
                       format="csr")
    pattern = (pattern + pattern.T + sps.identity(n + 2 * k)).tocsr()
    order = reverse_cuthill_mckee(pattern, symmetric_mode=True)
    place = np.empty_like(order)
    place[order] = np.arange(len(order))
    rows, cols = pattern.nonzero()
    return order, place, int(np.abs(place[rows] - place[cols]).max())


def _springs(problem: ImpulseRows, stiffness: Sequence[float] | float, hertz: bool
             ) -> tuple[list[int], Any, Any, Any, np.ndarray, Any]:
    """The springs' model on the coordinates some contact moves: those coordinates, J
    and J^T there (sparse, along the unit normals), M^-1 J^T f as a function, each
    contact's effective mass over its stiffness, and its force as a function of its
    depth and rate."""
    import scipy.sparse as sps

    k = len(problem.contacts)
    stiff = np.broadcast_to(np.asarray(stiffness, dtype=float), (k,)).copy()
    if np.any(~np.isfinite(stiff)) or np.any(stiff <= 0):
        raise InputError("stiffness", "every contact stiffness must be a positive number")
    # only the coordinates some contact moves are integrated (a chain's balls do not
    # spin or move across it); J is sparse, each contact touching two bodies
    entries = problem.J.row_list()  # the springs push along the unit normals
    dense = problem.dense  # joints or a mechanics system: M^-1 couples the speeds
    moved = list(range(len(problem.coordinates))) if dense else \
        sorted({j for _, j, _ in entries})
    column = {j: c for c, j in enumerate(moved)}
    n = len(moved)
    J = sps.csr_matrix(([float(x) for _, _, x in entries],
                        ([i for i, _, _ in entries], [column[j] for _, j, _ in entries])),
                       shape=(k, n))
    JT = J.T.tocsr()
    if dense:
        m_full = np.array(problem.M_inverse.evalf(30), dtype=float)
        w_diag = np.einsum("ij,jk,ik->i", J.toarray(), m_full, J.toarray())
    else:
        m_inv = np.array([float(problem.inverse_inertia[j]) for j in moved])
        w_diag = np.asarray(J.multiply(J) @ m_inv).ravel()  # diag(J M^-1 J^T)

    def accelerate(f):
        """M^-1 J^T f: the speeds' rates under the contact forces."""
        return m_full @ (JT @ f) if dense else m_inv * (JT @ f)
    e = np.array([float(t.restitution) for t in problem.contacts])
    if hertz and np.any(e < 1):
        raise InputError("restitution", "Hertzian contacts here are elastic (e = 1)")
    ratio = np.array([damping_ratio_for(float(x)) for x in e])
    damping = 0.0 if hertz else 2 * ratio * np.sqrt(stiff / w_diag)

    def force(depth, rate):
        pressed = depth > 0
        if hertz:
            push = stiff * np.where(pressed, depth, 0.0) ** 1.5
        else:
            push = stiff * depth + damping * rate
        return np.where(pressed, np.maximum(push, 0.0), 0.0)

    mass = 1 / w_diag  # each contact's effective mass
    return moved, J, JT, accelerate, mass / stiff, force
