"""Several rough contacts in three dimensions acting in one impact: one contact strikes,
the others rest, followed in the striking contact's normal impulse.

This is the setting of a billiard ball striking a cushion while it sits on the table
(Mathavan, Jackson and Parkin 2010): the cushion's contact approaches and drives the
impact; the table's contact touches with zero normal velocity and stays closed for as
long as it pushes, its normal impulse being whatever keeps it closed. Both may slip,
stick, and slip again, each under Coulomb's circular cone.

The clock is the striking contact's normal impulse p (Stronge, Impact Mechanics, ch. 5,
for one contact). With ``J_k`` the rows (n, t1, t2) of contact k (the velocity of the
second body's touching point less the first's, in its frame) and ``M^-1`` the mobility,

    du/dp = M^-1 sum_k J_k^T f_k,

where ``f_k`` is contact k's impulse rate in its frame:

- the striking contact: normal rate 1;
- a resting contact: normal rate ``lambda_k``, fixed by ``d(v_n,k)/dp = 0``, and it must
  stay non-negative (a resting contact that would pull lets go, and is free from there);
- a slipping contact: tangential rate ``-mu_k (normal rate) s_k``, with ``s_k`` its unit
  slip direction;
- a sticking contact: tangential rate ``r_k``, fixed by ``d(v_t,k)/dp = 0``, kept while
  ``|r_k| <= mu_k (normal rate)``.

The unknown rates solve one small linear system at each step (least-norm where the
conditions depend on one another). The impact ends by the striking contact's
restitution law, as for one contact: Newton's (``v_n = -e v_n(0)``), Poisson's
(``p = (1 + e) p_c``) or the energetic law (the work of its normal impulse in restitution
is ``e^2`` times that in compression).

The path is integrated with scipy's DOP853 to a stated relative tolerance, phase by
phase: a phase ends where the striking contact's compression ends, where a slip stops
(seen as its component along a reference direction, renewed every 60 degrees of turn),
where a stick needs more than its cone, or where a resting contact would pull.

Examples
--------
A sphere (m = 1, R = 1, I = 2/5) resting on a floor (normal +z, the floor's contact
first) strikes a smooth vertical wall (normal -x) at 2, with no friction anywhere: the
floor takes nothing and the ball leaves the wall at e times its speed.

>>> import numpy as np
>>> Minv = np.diag([1, 1, 1, 2.5, 2.5, 2.5])
>>> wall = np.array([[-1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 1], [0, 0, -1, 0, 1, 0.]])
>>> floor = np.array([[0, 0, 1, 0, 0, 0], [1, 0, 0, 0, -1, 0], [0, 1, 0, 1, 0, 0.]])
>>> from rigidimpact.laws.law import EnergeticRestitution
>>> out = driven_impact(Minv, [wall, floor], np.array([2, 0, 0, 0, 0, 0.]),
...                     EnergeticRestitution(0.5), [0.0, 0.0])
>>> np.round(out.u_after[:3], 9).tolist(), np.round(out.impulses[1], 12).tolist()
([-1.0, 0.0, 0.0], [0.0, 0.0, 0.0])
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rigidimpact.errors import InputError
from rigidimpact.lazy import deferred

if TYPE_CHECKING:
    import numpy as np
else:
    np = deferred("numpy")

__all__ = ["DrivenImpact", "driven_impact", "TOLERANCE"]

TOLERANCE = 1e-10
MAX_PHASES = 200


@dataclass(frozen=True)
class DrivenImpact:
    """What the contacts give: ``impulses[k]`` = contact k's (P_n, P_t1, P_t2) on its
    second body in its frame; ``u_after`` the speeds after; ``courses[k]`` what contact k
    did ("slides throughout", "slides, then sticks from p = ...", "lets go at p = ...");
    ``phases`` each phase's start (p) and the contacts' modes; ``steps`` the integrator's
    accepted steps."""

    impulses: np.ndarray
    u_after: np.ndarray
    courses: tuple[str, ...]
    phases: tuple[tuple[float, tuple[str, ...]], ...]
    tolerance: float
    steps: int


def driven_impact(M_inverse: np.ndarray, rows: Sequence[np.ndarray], u: np.ndarray,
                  law: Any, mu: Sequence[float],
                  tolerance: float | None = None) -> DrivenImpact:
    """Follow the impact in which contact 0 strikes and every other contact rests (see
    the module's text).

    Parameters
    ----------
    M_inverse : (n, n) array
    rows : one (3, n) array per contact, its rows n, t1, t2
    u : (n,) array, the speeds before
    law : the striking contact's restitution law (an object: its end is its own)
    mu : each contact's friction coefficient
    tolerance : the integration's relative tolerance
    """
    tolerance = TOLERANCE if tolerance is None else tolerance
    k = len(rows)
    if len(mu) != k:
        raise InputError("contacts", "one friction coefficient per contact")
    J = [np.asarray(r, float) for r in rows]
    A = [M_inverse @ r.T for r in J]  # each contact's impulse (frame) to du
    u0 = np.asarray(u, float)
    v0 = [r @ u0 for r in J]
    # the end of the impact: the striking contact's law's own (laws.ends)
    end = law.end_event(float(v0[0][0]))
    if not v0[0][0] < 0:
        raise InputError("bodies", "the striking contact is not approaching")
    scale = max(float(np.abs(u0).max()), 1e-300)
    floor = 1e3 * tolerance * scale  # a slip below this is zero (the integration's error)
    for i in range(1, k):
        if abs(v0[i][0]) > floor:
            raise InputError("contacts", f"contact {i} is not resting (normal velocity "
                             f"{v0[i][0]:.6g}): with one striking contact, the others "
                             "must touch with zero normal velocity")
    n = len(u0)
    # state: u (n), each contact's impulse (3 k), the striking contact's normal work
    # a contact without friction slips as it likes: it has no stick, and no direction
    mode = ["smooth" if mu[i] == 0 else "slip" if np.linalg.norm(v0[i][1:]) > floor
            else "test" for i in range(k)]
    references: list[np.ndarray] = [np.zeros(2)] * k
    resumed: dict[int, np.ndarray] = {}

    path = _Path(J, A, list(mu), n, k, floor, resumed)

    def rates(y: np.ndarray, modes: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
        return _rates(path, y, modes)

    def rhs_for(modes: Sequence[str]) -> Any:
        def rhs(_p: float, y: np.ndarray) -> np.ndarray:
            du, f = rates(y, modes)
            return np.concatenate([du, f.ravel(), [J[0][0] @ y[:n]]])
        return rhs


    y = np.concatenate([u0, np.zeros(3 * k + 1)])
    p = 0.0
    p_c: float | None = None
    work_c: float | None = None
    courses: list[list[str]] = [[] for _ in range(k)]
    phases: list[tuple[float, tuple[str, ...]]] = []
    steps = 0
    back = float(law.leaving(-1.0))  # the law's rebound at unit speed
    horizon = 100.0 * (1 + back) * (-v0[0][0]) / max(float((J[0] @ A[0])[0, 0]), 1e-300) + 1.0

    def note(i: int, what: str) -> None:
        if not courses[i] or courses[i][-1].split(" from")[0] != what:
            courses[i].append(what if p == 0 else f"{what} from p = {p:.6g}")

    reclosed: tuple[int, float] | None = None  # the contact that touched again, where
    for _ in range(MAX_PHASES):
        _settle(path, y, mode, p)
        for _ in range(k):  # a resting contact that would pull from here lets go now
            _, f = rates(y, mode)
            pulling = [i for i in range(1, k) if mode[i] != "free" and f[i, 0] < -1e-9]
            if not pulling:
                break
            if reclosed == (pulling[0], p):
                raise InputError("contacts", f"contact {pulling[0]} closes again within "
                                 "the impact but could rest only by pulling: the rigid "
                                 "model has no answer here (a limit of the model, as in "
                                 "Painleve's paradox)")
            mode[pulling[0]] = "free"
        for i in range(k):
            if mode[i] == "slip":
                t = (J[i] @ y[:n])[1:]
                size = np.linalg.norm(t)
                references[i] = t / size if size > floor else resumed.get(i, np.zeros(2))
            note(i, {"slip": "slides", "stick": "sticks", "free": "lets go",
                     "smooth": "smooth"}[mode[i]])
        phases.append((p, tuple(mode)))
        modes = tuple(mode)
        rhs = rhs_for(modes)
        events, kinds, finish = _phase_events(path, modes, references, end, p_c, work_c)
        from scipy.integrate import solve_ivp  # scipy on first use

        run = solve_ivp(rhs, (p, p + horizon), y, method="DOP853", rtol=tolerance,
                        atol=tolerance * scale * 1e-3, events=events)
        steps += len(run.t)
        p, y = float(run.t[-1]), run.y[:, -1].copy()
        fired = [kinds[j] for j, t in enumerate(run.t_events) if len(t)]
        if not fired:
            raise InputError("impact", "the contacts' impulse did not end within its "
                             "horizon; please report the scene")
        kind, i = fired[0]
        if ("finish", 0) in fired:
            break
        if kind == "compression":
            p_c, work_c = p, float(y[-1])
            if finish(p, y, p_c, work_c) >= 0:
                break
            continue
        if kind == "stops" or (kind == "turns" and
                               np.linalg.norm((J[i] @ y[:n])[1:]) <= 10 * floor):
            mode[i] = "test"
            resumed.pop(i, None)
        elif kind == "turns":
            resumed.pop(i, None)
        elif kind == "slips":
            mode[i] = "slip"
            resumed[i] = _direction_of(path, i, y, p, mode)
        elif kind == "lets-go":
            mode[i] = "free"
        elif kind == "closes":  # its gap is still zero (an impact takes no time): it
            # touches again and rests, sliding if its points slip there
            slip = np.linalg.norm((J[i] @ y[:n])[1:])
            mode[i] = "test" if slip <= 10 * floor else "slip"
            resumed.pop(i, None)
            reclosed = (i, p)
    else:
        raise InputError("impact", f"the contacts changed between slip and stick more "
                         f"than {MAX_PHASES} times; please report the scene")
    impulses = y[n:n + 3 * k].reshape(k, 3)
    impulses[0, 0] = p
    u_after = u0 + sum((A[i] @ impulses[i] for i in range(k)), np.zeros(n))
    return DrivenImpact(impulses, u_after, tuple(
        ", then ".join(c) for c in courses), tuple(phases), tolerance, steps)


@dataclass
class _Path:
    """What the driven impact's rates read: each contact's rows J and its impulse's
    effect on the speeds A, the friction coefficients, the sizes, the slip below which
    a contact is at rest, and each slip's direction where it starts from rest."""

    J: list[np.ndarray]
    A: list[np.ndarray]
    mu: list[float]
    n: int
    k: int
    floor: float
    resumed: dict[int, np.ndarray]


def _rates(path: _Path, y: np.ndarray, modes: Sequence[str]) -> tuple[np.ndarray, np.ndarray]:
    """(du/dp, each contact's impulse rate (k x 3)) for these modes."""
    J, A, mu, n, k, floor, resumed = (path.J, path.A, path.mu, path.n, path.k, path.floor,
                                      path.resumed)
    uu = y[:n]
    known = np.zeros(n)
    columns: list[tuple[int, str, np.ndarray]] = []  # unknown rates and their du
    conditions: list[np.ndarray] = []
    slips = []
    for i in range(k):
        v = J[i] @ uu
        t = v[1:]
        # the slip's own direction; where it starts from rest (below the
        # integration's error), the direction the equations give it
        size = np.linalg.norm(t)
        s: np.ndarray = resumed[i] if i in resumed and size <= 10 * floor else \
            t / size if size > 0 else np.zeros(2)
        slips.append(s)
        if modes[i] == "free":
            continue
        slipping = modes[i] in ("slip", "smooth")
        if i == 0:
            known += A[0] @ (np.array([1.0, *(-mu[0] * s)]) if slipping
                             else np.array([1.0, 0, 0]))
        else:
            columns.append((i, "n", A[i] @ (np.array([1.0, *(-mu[i] * s)])
                                           if slipping else np.array([1.0, 0, 0]))))
            conditions.append(J[i][0])
        if not slipping:
            columns += [(i, "t1", A[i][:, 1]), (i, "t2", A[i][:, 2])]
            conditions += [J[i][1], J[i][2]]
    x = np.zeros(len(columns))
    if columns:
        B = np.column_stack([c for _, _, c in columns])
        C = np.vstack(conditions)
        x = np.linalg.lstsq(C @ B, -(C @ known), rcond=None)[0]
        du = known + B @ x
    else:
        du = known
    f = np.zeros((k, 3))
    f[0, 0] = 0.0 if modes[0] == "free" else 1.0
    for (i, part, _), value in zip(columns, x, strict=True):
        f[i, {"n": 0, "t1": 1, "t2": 2}[part]] = value
    for i in range(k):
        if modes[i] == "slip":
            f[i, 1:] = -mu[i] * f[i, 0] * slips[i]
    return du, f


def _direction_of(path: _Path, i: int, y: np.ndarray, p: float, mode: Sequence[str]
               ) -> np.ndarray:
    """The slip direction s of contact i starting from rest: the slip's rate under
    friction -mu s points along +s. Scanned around the circle, then refined where
    the rate's part across s changes sign."""
    J, A, resumed = path.J, path.A, path.resumed
    modes = [("stick" if m == "test" else m) for m in mode]
    modes[i] = "slip"

    def rate(angle: float) -> tuple[np.ndarray, np.ndarray]:
        s = np.array([math.cos(angle), math.sin(angle)])
        resumed[i] = s
        du, _ = _rates(path, y, modes)
        return s, (J[i] @ du)[1:]

    def along(angle: float) -> float:
        s, a = rate(angle)
        return float(a @ s - abs(a[0] * s[1] - a[1] * s[0]))

    def across(angle: float) -> float:
        s, a = rate(angle)
        return float(a[0] * s[1] - a[1] * s[0])

    angles = np.linspace(0, 2 * np.pi, 720, endpoint=False)
    values = np.array([along(a) for a in angles])
    tiny = 1e-9 * float(np.linalg.norm(J[i] @ A[i]))
    # the consistent directions: where the rate turns to lie along s and grows (the
    # peaks of `along` above the integration's noise)
    found = []
    for j in np.flatnonzero((values > tiny) & (values >= np.roll(values, 1))
                            & (values >= np.roll(values, -1))):
        lo, hi = angles[j] - np.pi / 360, angles[j] + np.pi / 360
        a_lo, a_hi = across(lo), across(hi)
        if a_lo * a_hi < 0:
            from scipy.optimize import brentq  # scipy on first use

            found.append(brentq(across, lo, hi, xtol=1e-15))
        elif min(abs(a_lo), abs(a_hi)) <= tiny:
            found.append(float(angles[j]))
    if not found:
        # wedged: no way of slipping grows while the cone cannot hold it (the closed
        # contacts hold the bodies while the striking one pushes)
        raise InputError("contacts", f"at p = {p:.6g} contact {i} can neither stick "
                         "nor start to slip in any direction: the rigid model does "
                         "not determine the impulses here (a limit of the model, as "
                         "in Painleve's paradox)")
    # neighbouring samples of one peak are one direction: distinct directions lie
    # more than the scan's two steps apart
    distinct = [a for j, a in enumerate(found) if all(
        abs(math.remainder(a - b, 2 * np.pi)) > np.pi / 180 for b in found[:j])]
    if len(distinct) > 1:
        raise InputError("contacts", f"at p = {p:.6g} contact {i} could start to "
                         f"slip in {len(distinct)} directions: the rigid model does "
                         "not determine which (a limit of the model, as in Painleve's "
                         "paradox)")
    best = distinct[0]
    return np.array([math.cos(best), math.sin(best)])


def _phase_events(path: _Path, modes: tuple[str, ...], references: Sequence[np.ndarray],
                  end: Any, p_c: float | None, work_c: float | None
                  ) -> tuple[list[Any], list[tuple[str, int]], Any]:
    """The events that end a phase of the driven impact (in these modes), with what each
    is (its kind and contact), and the striking contact's end as a function."""
    J, mu, n, k, floor = path.J, path.mu, path.n, path.k, path.floor
    mode = modes
    events: list[Any] = []
    kinds: list[tuple[str, int]] = []

    def finish(pp: float, yy: np.ndarray, p_c: float | None = p_c,
               work_c: float | None = work_c) -> float:
        return end(pp, float(J[0][0] @ yy[:n]), p_c, work_c, float(yy[-1]))
    events.append(finish)
    kinds.append(("finish", 0))
    if p_c is None:
        def compression(_p: float, yy: np.ndarray) -> float:
            return float(J[0][0] @ yy[:n])
        events.append(compression)
        kinds.append(("compression", 0))
    for i in range(k):
        if mode[i] == "slip":
            ref = references[i]

            def stops(_p: float, yy: np.ndarray, i: int = i, ref: np.ndarray = ref
                      ) -> float:
                return float((J[i] @ yy[:n])[1:] @ ref)

            def turns(_p: float, yy: np.ndarray, i: int = i, ref: np.ndarray = ref
                      ) -> float:
                t = (J[i] @ yy[:n])[1:]
                return float(t @ ref - 0.5 * np.linalg.norm(t))
            events += [stops, turns]
            kinds += [("stops", i), ("turns", i)]
        if mode[i] == "stick":
            def holds(_p: float, yy: np.ndarray, i: int = i,
                      modes: tuple[str, ...] = modes) -> float:
                _, f = _rates(path, yy, modes)
                return float(mu[i] * f[i, 0] - np.linalg.norm(f[i, 1:]))
            events.append(holds)
            kinds.append(("slips", i))
        if i and mode[i] != "free":
            def pushes(_p: float, yy: np.ndarray, i: int = i,
                       modes: tuple[str, ...] = modes) -> float:
                _, f = _rates(path, yy, modes)  # an impulse rate of 1e-9 of the
                return float(f[i, 0]) + 1e-9  # striking one's: zero, not a pull
            events.append(pushes)
            kinds.append(("lets-go", i))
        if i and mode[i] == "free":
            def closes(_p: float, yy: np.ndarray, i: int = i) -> float:
                return float(J[i][0] @ yy[:n]) + 1e-3 * floor  # the step's error
            events.append(closes)
            kinds.append(("closes", i))
    for ev, (kind, _) in zip(events, kinds, strict=True):
        ev.terminal = True  # type: ignore[attr-defined]
        ev.direction = 1.0 if kind in ("finish", "compression") else -1.0  # type: ignore[attr-defined]
    return events, kinds, finish


def _settle(path: _Path, y: np.ndarray, mode: list[str], p: float) -> None:
    """Each contact whose slip is (about) zero: stick if its cone holds it, else slip
    again in the direction the equations give (`mode` is changed in place)."""
    k, mu = path.k, path.mu
    for _ in range(4 * k):
        changed = False
        for i in range(k):
            if mode[i] != "test":
                continue
            trial = [m if j != i else "stick" for j, m in enumerate(mode)]
            trial = [("stick" if m == "test" else m) for m in trial]
            _, f = _rates(path, y, trial)
            if np.linalg.norm(f[i, 1:]) <= mu[i] * max(f[i, 0], 0.0) * (1 + 1e-9):
                mode[i] = "stick"
            else:
                mode[i] = "slip"
                path.resumed[i] = _direction_of(path, i, y, p, mode)
            changed = True
        if not changed:
            return
