"""Figures of the paper's results. Each function returns its Figure and never shows it.

Examples
--------
>>> fig = omega_vs_theta(e_values=(0, 1), mass_ratios=(1,))
>>> fig.axes[0].get_xlabel()
'initial angle $\\\\theta$ (degrees)'
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

# the backend is the caller's: matplotlib picks Agg itself where there is no screen, a
# notebook keeps its inline one, and the command line asks for Agg before it draws
import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from rigidimpact.outputs.style import DPI, FIGSIZE
from rigidimpact.outputs.views import _animated_views, space_views
from rigidimpact.paper.problems import derive
from rigidimpact.symbolic.notation import symbol

__all__ = ["omega_vs_theta", "energy_loss_vs_theta", "critical_angle_graphical",
           "restrike_map", "strobe", "trajectories", "accuracy_vs_time", "oblique_discs",
    "convergence", "naive_vs_stable", "routh_diagram", "animation", "experiment_comparison",
           "impact_picture", "draw_bodies", "space_views", "sweep_curves", "FIGSIZE", "DPI"]


m, M, L, theta, e, v_ix = (symbol(n) for n in ("m", "M", "L", "theta", "e", "v_ix"))


def _curve(key: str):
    expr = derive("barbell").results[key]
    return sp.lambdify((m, M, L, theta, e, v_ix), expr, "numpy")


def _against_theta(key: str, e_values: Sequence[float], mass_ratios: Sequence[float],
                   ylabel: str, title: str) -> tuple[Figure, plt.Axes]:
    """One line of a barbell result against the initial angle per (e, m/M): the ball's
    mass m over one sphere's M, with m = L = v_ix = 1 (so M = 1 / ratio)."""
    curve = _curve(key)
    degrees = np.linspace(0.0, 180.0, 361)
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    for ratio in mass_ratios:
        for ev in e_values:
            ax.plot(degrees, curve(1.0, 1.0 / ratio, 1.0, np.radians(degrees), ev, 1.0),
                    label=f"e = {ev:g}, m/M = {ratio:g}")
    ax.set_xlabel(r"initial angle $\theta$ (degrees)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.set_xticks(range(0, 181, 30))
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3)
    return fig, ax


def omega_vs_theta(e_values: Sequence[float] = (0.0, 0.5, 1.0),
                   mass_ratios: Sequence[float] = (2.0, 0.5)) -> Figure:
    """Barbell spin after the impact, omega_z L / v_ix, against the initial angle.

    One line per restitution e and mass ratio m/M, the ball's mass over one sphere's
    (eq. 5; the paper's text speaks of M/m, its inverse).
    """
    fig, _ = _against_theta("omega_z", e_values, mass_ratios,
                            r"$\omega_z L / v_{ix}$ (dimensionless)",
                            "Barbell spin after the impact (Mungan eq. 5)")
    fig.tight_layout()
    return fig


def energy_loss_vs_theta(e_values: Sequence[float] = (0.0, 0.5, 0.9),
                         mass_ratios: Sequence[float] = (2.0, 0.5)) -> Figure:
    """Fraction of kinetic energy lost (eq. 7) against the initial angle; least at 90.

    One line per restitution e and mass ratio m/M, the ball's mass over one sphere's.
    """
    fig, ax = _against_theta("energy_loss_fraction", e_values, mass_ratios,
                             r"$\Delta K_{\mathrm{lost}} / K_i$ (fraction)",
                             "Kinetic energy lost (Mungan eq. 7): least at 90 degrees")
    ax.axvline(90.0, color="grey", lw=0.8, ls=":")
    ax.set_ylim(bottom=0.0)
    fig.tight_layout()
    return fig


# ---- section 2: the re-strike --------------------------------------------------------

def critical_angle_graphical(theta_c: float) -> Figure:
    """The paper's "graphical solution": tan(theta) and 1/(pi - theta) cross at theta_c.

    Examples
    --------
    >>> fig = critical_angle_graphical(0.3432)
    >>> len(fig.axes[0].lines)  # two curves, the crossing, the vertical marker
    4
    """
    x = np.linspace(0.0, np.radians(45.0), 400)
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    ax.plot(np.degrees(x), np.tan(x), label=r"$\tan\theta$")
    ax.plot(np.degrees(x), 1.0 / (np.pi - x), label=r"$1/(\pi - \theta)$")
    ax.plot([np.degrees(theta_c)], [np.tan(theta_c)], "ko",
            label=rf"$\theta_c = {np.degrees(theta_c):.4f}^\circ$")
    ax.axvline(np.degrees(theta_c), color="grey", lw=0.8, ls=":")
    ax.set_xlabel(r"initial angle $\theta$ (degrees)")
    ax.set_ylabel("value")
    ax.set_title(r"Critical angle of section 2: $\tan\theta_c = 1/(\pi - \theta_c)$ "
                 "(perfectly inelastic, any m/M)")
    ax.legend(loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def restrike_map(degrees: np.ndarray, e_values: np.ndarray,
                 hits: dict[float, np.ndarray]) -> Figure:
    """Where the barbell strikes the ball again, over (theta, e), one panel per m/M.

    `hits[ratio]` is a boolean array of shape ``(len(e_values), len(degrees))``.

    Examples
    --------
    >>> d, ev = np.linspace(0, 180, 5), np.linspace(0, 1, 3)
    >>> len(restrike_map(d, ev, {1.0: np.zeros((3, 5), bool)}).axes)
    1
    """
    fig, axes = plt.subplots(1, len(hits), figsize=FIGSIZE, dpi=DPI, sharey=True,
                             squeeze=False)
    for ax, (ratio, hit) in zip(axes[0], hits.items(), strict=True):
        ax.pcolormesh(degrees, e_values, hit.astype(float), cmap="Blues", vmin=0.0,
                      vmax=1.4, shading="nearest", rasterized=True)
        ax.set_title(f"m/M = {ratio:g}", fontsize="medium")
        ax.set_xlabel(r"$\theta$ (degrees)")
        ax.set_xticks(range(0, 181, 45))
    axes[0][0].set_ylabel("restitution e")
    fig.suptitle("Shaded: the barbell strikes the ball again after the impact")
    fig.tight_layout()
    return fig


def strobe(frames: Sequence[tuple[np.ndarray, np.ndarray, np.ndarray]], title: str) -> Figure:
    """Snapshots of the ball and barbell from the impact onward: above, in the lab frame;
    below, the same snapshots seen from the barbell's centre, where its turn and the
    ball closing on the B half show. Colour runs from the impact (dark) to the last
    snapshot (light).

    Each frame is ``(ball, sphere_a, sphere_b)`` positions.

    Examples
    --------
    >>> f = [(np.zeros(2), np.zeros(2), np.ones(2))] * 3
    >>> [ax.get_aspect() for ax in strobe(f, "demo").axes[:2]]
    [1.0, 1.0]
    """
    fig, (lab, centre) = plt.subplots(2, 1, figsize=(FIGSIZE[0], 1.5 * FIGSIZE[1]), dpi=DPI,
                                      gridspec_kw={"height_ratios": (1, 2.2)})
    shades = plt.cm.viridis(np.linspace(0.0, 0.9, len(frames)))
    for ax, moving in ((lab, False), (centre, True)):
        for (ball, a, b), colour in zip(frames, shades, strict=True):
            origin = (a + b) / 2 if moving else np.zeros(2)
            ball, a, b = ball - origin, a - origin, b - origin
            ax.plot([a[0], b[0]], [a[1], b[1]], "-", color=colour, lw=1.0)
            ax.plot([a[0]], [a[1]], "o", color=colour, ms=5, mfc="white")
            ax.plot([b[0]], [b[1]], "o", color=colour, ms=5)
            ax.plot([ball[0]], [ball[1]], "s", color=colour, ms=4)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    lab.set_xlabel("x / L (lab frame)")
    lab.set_ylabel("y / L")
    centre.set_xlabel("x / L, from the barbell's centre")
    centre.set_ylabel("y / L")
    lab.set_title(title, fontsize="medium")
    grey = "0.3"
    handles = [plt.Line2D([], [], ls="none", marker="s", color=grey, ms=4, label="ball"),
               plt.Line2D([], [], ls="none", marker="o", color=grey, mfc="white", ms=5,
                          label="sphere A (struck)"),
               plt.Line2D([], [], ls="none", marker="o", color=grey, ms=5, label="sphere B"),
               plt.Line2D([], [], color=shades[0], lw=2, label="at the impact"),
               plt.Line2D([], [], color=shades[-1], lw=2, label="last snapshot")]
    centre.legend(handles=handles, fontsize="small", loc="best")
    fig.tight_layout()
    return fig


def trajectories(times: np.ndarray, points: dict[str, np.ndarray], title: str,
                 velocity: tuple[str, np.ndarray] | None = None,
                 outlines: tuple[Sequence, Sequence[tuple]] | None = None,
                 relative: bool = False) -> Figure:
    """Paths of the tracked points in the plane; optionally one point's velocity in time.
    Each path starts at a dot (one legend entry says so). With `relative`, each point's
    displacement from where it was at the start, in mm, so that motions small against
    the bodies' size (a spring rod's) are seen, each from the same origin.

    Examples
    --------
    >>> t = np.linspace(0, 1, 5)
    >>> fig = trajectories(t, {"ball": np.c_[t, 0 * t]}, "demo", ("ball", np.c_[1 + 0 * t, 0 * t]))
    >>> len(fig.axes)
    2
    """
    panels = 2 if velocity is not None else 1
    fig, axes = plt.subplots(1, panels, figsize=FIGSIZE, dpi=DPI, squeeze=False)
    ax = axes[0][0]
    styles = ("-", "--", ":", "-.")
    for k, (name, xy) in enumerate(points.items()):
        if relative:
            xy = 1e3 * (xy - xy[:1])
        # the first body (the striker) is drawn on top, dashed ones beneath: tracks that
        # start at the same point stay visible
        still = not np.ptp(xy, axis=0).any()  # a point at rest: a marker, said so
        ax.plot(xy[:, 0], xy[:, 1], styles[k % len(styles)], lw=2.2 if k == 0 else 1.4,
                zorder=3 if k == 0 else 2, label=f"{name} (at rest)" if still else name,
                marker="o" if still else None, mfc="none", ms=9)
        ax.plot(xy[:1, 0], xy[:1, 1], "k.", ms=4, zorder=4,
                label="start (t = 0)" if k == len(points) - 1 else None)
    if outlines is not None:  # the bodies as they were at the impact, faint
        bodies, contacts = outlines
        drawn = len(ax.lines)
        draw_bodies(ax, bodies, contacts)
        for artist in [*ax.patches, *ax.lines[drawn:]]:
            artist.set_alpha(0.35)
    ax.set_aspect("equal", adjustable="datalim")
    if relative:
        ax.set_xlabel("displacement in x from the start (mm)")
        ax.set_ylabel("displacement in y (mm)")
    else:
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    if velocity is not None:
        name, v = velocity
        bx = axes[0][1]
        bx.plot(times, v[:, 0], label=f"{name}: $v_x$")
        bx.plot(times, v[:, 1], label=f"{name}: $v_y$")
        bx.set_xlabel("time t (s)")
        bx.set_ylabel("velocity (m/s)")
        bx.legend(fontsize="small")
        bx.grid(alpha=0.3)
    fig.suptitle(title, fontsize="medium")
    fig.tight_layout()
    return fig


def accuracy_vs_time(rows: Sequence[dict], fronts: Sequence[Sequence[dict]],
                     floor: float) -> Figure:
    """Log-log error against wall time, one series per method, each Pareto front joined.

    Examples
    --------
    >>> rows = [{"method": "a", "setting": "x", "error": 1e-3, "seconds": 1e-2},
    ...         {"method": "b", "setting": "y", "error": 0.0, "seconds": 1e-1}]
    >>> len(accuracy_vs_time(rows, [rows], 1e-18).axes[0].lines)
    4
    """
    fig, ax = plt.subplots(figsize=(FIGSIZE[0], 1.25 * FIGSIZE[1]), dpi=DPI)
    markers = "osD^v<>ph*"
    methods = list(dict.fromkeys(r["method"] for r in rows))
    for k, method in enumerate(methods):
        mine = [r for r in rows if r["method"] == method]
        ax.loglog([r["seconds"] for r in mine], [max(r["error"], floor) for r in mine],
                  markers[k % len(markers)], ms=5, alpha=0.8, label=method, ls="none")
    for k, front in enumerate(fronts):
        ax.loglog([r["seconds"] for r in front], [max(r["error"], floor) for r in front],
                  "k--" if k == 0 else "k:", lw=1.0,
                  label="Pareto front" + (f" ({front[0].get('problem')})" if front and
                                           front[0].get("problem") else ""))
    ax.axhline(floor, color="grey", lw=0.6, ls=":")
    ax.set_xlabel("wall time per answer (s, median)")
    ax.set_ylabel(f"relative error (below {floor:g}: drawn at {floor:g})")
    ax.set_title("What accuracy costs: the ball-barbell collision, every method")
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def oblique_discs(before: Sequence[np.ndarray], after: Sequence[np.ndarray],
                  radius: float = 1.0) -> Figure:
    """Two equal discs at the instant of impact, with their velocities before and after.

    Examples
    --------
    >>> v = [np.array([1.0, 0.5]), np.zeros(2)]
    >>> len(oblique_discs(v, v).axes)
    1
    """
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    centres = (np.array([-radius, 0.0]), np.array([radius, 0.0]))
    for k, centre in enumerate(centres):
        ax.add_patch(plt.Circle((centre[0], centre[1]), radius, fill=False, color=f"C{k}",
                                lw=1.5))
        for velocity, style, label in ((before[k], ":", "before"), (after[k], "-", "after")):
            if np.linalg.norm(velocity) > 0:
                ax.annotate("", tuple(centre + velocity), tuple(centre),
                            arrowprops={"arrowstyle": "->", "ls": style, "color": f"C{k}"})
                ax.plot([], [], style, color=f"C{k}", label=f"disc {k + 1} {label}")
    ax.plot([0, 0], [-radius, radius], color="grey", lw=0.8, ls="--", label="tangent at O")
    ax.set_aspect("equal")
    ax.set_xlim(-2.6 * radius, 2.6 * radius)
    ax.set_ylim(-1.4 * radius, 1.4 * radius)
    ax.set_xlabel("x (units of the radius)")
    ax.set_ylabel("y (units of the radius)")
    ax.set_title("Equal smooth discs, elastic oblique impact: they leave at right angles")
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return fig


def convergence(rows: Sequence[dict]) -> Figure:
    """Error to the rigid limit against contact stiffness (log-log), with the order.

    Examples
    --------
    >>> rows = [{"contact_stiffness": 1e3, "error": 1e-3}, {"contact_stiffness": 1e4,
    ...          "error": 3e-4, "order": 0.5}]
    >>> convergence(rows).axes[0].get_xscale()
    'log'
    """
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    k = np.array([r["contact_stiffness"] for r in rows])
    err = np.array([r["error"] for r in rows])
    ax.loglog(k, err, "o-", label="compliant run against eq. (5)")
    ax.loglog(k, err[0] * (k / k[0]) ** -0.5, "k:", label=r"slope $-1/2$")
    ax.set_xlabel("contact stiffness (N/m); the rod is stiffer still")
    ax.set_ylabel("largest error in the final velocities (m/s, rad/s)")
    ax.set_title("The rigid limit emerges: error against stiffness")
    ax.legend()
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def naive_vs_stable(ratios: np.ndarray, naive: np.ndarray, stable: np.ndarray,
                    xlabel: str, title: str) -> Figure:
    """Relative errors of a naive float64 formula and of the kernel, against a parameter.

    Examples
    --------
    >>> x = np.logspace(0, 3, 4)
    >>> naive_vs_stable(x, x * 1e-16, 0 * x, "M/m", "demo").axes[0].get_yscale()
    'log'
    """
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    floor = 1e-18
    ax.loglog(ratios, np.maximum(naive, floor), "o-", label="naive float64 formula")
    ax.loglog(ratios, np.maximum(stable, floor), "s-", label="rigidimpact kernel")
    ax.axhline(2.2e-16, color="grey", lw=0.8, ls=":", label="float64 epsilon")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"relative error (below {floor:g}: drawn at {floor:g})")
    ax.set_title(title)
    ax.legend()
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def sticking_vs_bouncing(mass_ratios: Sequence[float] = (2.0, 0.5)) -> Figure:
    """The barbell's spin when the clay ball sticks (eq. 10) and when it bounces with e = 0.

    They agree at 90 degrees, as section 2 of the paper notes; one pair of lines per mass
    ratio m/M, the ball's mass over one sphere's, with m = L = v_ix = 1.

    Examples
    --------
    >>> len(sticking_vs_bouncing((1.0,)).axes[0].lines)
    3
    """
    stick = sp.lambdify((m, M, L, theta, v_ix), derive("sticking").results["omega_z"], "numpy")
    bounce = _curve("omega_z")
    degrees = np.linspace(0.0, 180.0, 361)
    x = np.radians(degrees)
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    for k, ratio in enumerate(mass_ratios):
        ax.plot(degrees, stick(1.0, 1.0 / ratio, 1.0, x, 1.0), color=f"C{k}",
                label=f"sticks, m/M = {ratio:g}")
        ax.plot(degrees, bounce(1.0, 1.0 / ratio, 1.0, x, 0.0, 1.0), color=f"C{k}", ls="--",
                label=f"bounces with e = 0, m/M = {ratio:g}")
    ax.axvline(90.0, color="grey", lw=0.8, ls=":")
    ax.set_xlabel(r"initial angle $\theta$ (degrees)")
    ax.set_ylabel(r"$\omega_z L / v_{ix}$ (dimensionless)")
    ax.set_title("Clay ball (eq. 10) against a perfectly inelastic bounce: equal at 90 degrees")
    ax.set_xticks(range(0, 181, 30))
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def impulse_vs_offset(offsets: np.ndarray, impulses: dict[str, np.ndarray]) -> Figure:
    """The normal impulse J (eq. 11-14) against the struck body's offset from the normal.

    Examples
    --------
    >>> x = np.linspace(-1, 1, 5)
    >>> len(impulse_vs_offset(x, {"a": x ** 2}).axes[0].lines)
    1
    """
    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    for label, values in impulses.items():
        ax.plot(offsets, values, label=label)
    ax.set_xlabel(r"offset $R_{2y}$ of body 2's centre from the line of impact (m)")
    ax.set_ylabel(r"normal impulse $J$ (N s)")
    ax.set_title("General smooth impact: an off-centre hit gives a smaller impulse")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


SWEEP_POINTS = 20_000  # points drawn a curve at most: a longer sweep is drawn strided


def sweep_curves(name: str, x: np.ndarray, outputs: Mapping[str, np.ndarray],
                 title: str = "") -> Figure:
    """Each output of a sweep against the swept symbol `name`, one panel an output.

    A sweep longer than :data:`SWEEP_POINTS` is drawn at evenly strided sets (its ends
    kept); values that are not finite leave gaps.

    Examples
    --------
    >>> x = np.linspace(0, 1, 5)
    >>> fig = sweep_curves("theta", x, {"a": x, "b": x ** 2})
    >>> [ax.get_ylabel() for ax in fig.axes], fig.axes[-1].get_xlabel()
    (['a', 'b'], 'theta')
    """
    count = len(outputs)
    columns = 1 if count <= 4 else 2
    rows = -(-count // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(FIGSIZE[0], max(2.0, 1.8 * rows) + 0.8),
                             dpi=DPI, sharex=True, squeeze=False)
    step = max(1, -(-len(x) // SWEEP_POINTS))
    picked = np.unique(np.r_[np.arange(0, len(x), step), len(x) - 1])
    for ax, (key, values) in zip(axes.flat, outputs.items(), strict=False):
        ax.plot(np.asarray(x)[picked], np.asarray(values)[picked], lw=1.2)
        ax.set_ylabel(key, fontsize="small")
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[count:]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel(name)
    if count > columns:  # the last row's empty panel leaves its neighbour above unlabelled
        for ax in axes[-2][count % columns or columns:]:
            ax.set_xlabel(name)
            ax.xaxis.set_tick_params(labelbottom=True)
    fig.suptitle(title or f"every result against {name}", fontsize="medium")
    fig.tight_layout()
    return fig


def routh_diagram(diagram, title: str = "Routh's diagram") -> Figure:
    """The impulse plane of one frictional impact (Routh's construction).

    Normal impulse across, tangential impulse up: the friction cone ``|P_t| = mu P_n``
    (shaded: while the points slip the path runs parallel to one of its edges), the
    compression line (where the normal velocity is zero: compression ends where the
    path crosses it), the sticking line (where the tangential velocity is zero: slip
    stops there), and the path the impulse takes, with arrows along it and each event
    marked and named (slip stops, compression ends, the impact ends).

    Examples
    --------
    >>> from rigidimpact.model.bodies import Body
    >>> from rigidimpact.laws.contact import Contact
    >>> from rigidimpact.solve.impact import Impact
    >>> from rigidimpact.laws.routh import diagram
    >>> d = diagram(Impact(Body.particle(1, (1, 1), "ball"), Body.fixed("floor"),
    ...             Contact(restitution=1, tangential="coulomb", friction=0.25)), {})
    >>> figure = routh_diagram(d)
    >>> len(figure.axes[0].lines)
    5
    >>> [t.get_text() for t in figure.axes[0].texts if t.get_text()]  # and an arrow
    ['start', 'compression ends', 'the impact ends']
    """
    W = np.array(diagram.W.evalf(), dtype=float)
    v = np.array([float(x) for x in diagram.v_before])
    mu = float(diagram.mu)
    path = np.array([[float(a), float(b)] for a, b in diagram.regime.path])
    right = 1.25 * max(path[:, 0].max(), 1e-12)
    p_n = np.linspace(0.0, right, 200)
    fig, ax = plt.subplots(figsize=(7.0, 5.6), dpi=DPI, layout="constrained")
    ax.fill_between(p_n, -mu * p_n, mu * p_n, color="grey", alpha=0.12, lw=0)
    ax.plot(p_n, mu * p_n, color="grey", lw=0.8, label=rf"friction cone $|P_t| = \mu P_n$, "
            rf"$\mu = {mu:g}$")
    ax.plot(p_n, -mu * p_n, color="grey", lw=0.8)
    # v_n = 0 and v_t = 0 are straight lines in the impulse plane: v = v- + W P
    for row, style, label in ((0, "--", "compression ends ($v_n = 0$)"),
                              (1, ":", "sticking line ($v_t = 0$)")):
        colour = "C1" if row == 0 else "C2"
        if abs(W[row, 1]) > 1e-12 * abs(W).max():
            ax.plot(p_n, -(v[row] + W[row, 0] * p_n) / W[row, 1], style, color=colour,
                    label=label)
        else:  # the line stands upright at the normal impulse that zeroes the velocity
            ax.axvline(-v[row] / W[row, 0], ls=style, color=colour, label=label)
    ax.plot(path[:, 0], path[:, 1], "-", color="C0", lw=2,
            label=f"impulse path: {diagram.regime.name}")
    for a, b in zip(path[:-1], path[1:], strict=True):  # which way the impulse grows
        ax.annotate("", xy=a + 0.55 * (b - a), xytext=a + 0.45 * (b - a),
                    arrowprops={"arrowstyle": "-|>", "color": "C0", "lw": 2,
                                "mutation_scale": 16})
    span = max(mu * right, abs(path[:, 1]).max(), 1e-12)
    for point, text, colour, offset in _routh_events(path, v, W, diagram.regime.name):
        ax.scatter([point[0]], [point[1]], s=45, color=colour, zorder=5)
        ax.annotate(text, point, xytext=offset, textcoords="offset points",
                    fontsize="small", color=colour, ha="left" if offset[0] >= 0 else "right",
                    va="center", bbox={"boxstyle": "round,pad=0.2", "fc": "white",
                                       "ec": "none", "alpha": 0.8})
    ax.set_ylim(-1.4 * span, 1.4 * span)
    ax.set_xlim(0.0, right)
    ax.set_xlabel(r"normal impulse $P_n$ (N s)")
    ax.set_ylabel(r"tangential impulse $P_t$ (N s)")
    ax.set_title(f"{title}\n{diagram.law} restitution, e = {float(diagram.e):g}, "
                 f"$\\mu$ = {mu:g}", fontsize="medium")
    fig.legend(loc="outside lower center", ncol=2, fontsize="small")
    ax.grid(alpha=0.3)
    return fig


def _routh_events(path: np.ndarray, v: np.ndarray, W: np.ndarray, regime: str
                  ) -> list[tuple[tuple[float, float], str, str, tuple[float, float]]]:
    """The events of an impulse path, each as (point, name, colour, label offset in
    points): its start, where slip stops (each bend), where compression ends (the
    normal velocity zero along the path) and where the impact ends."""
    bend = ("slip stops, then reverses" if "reversal" in regime else
            "slip stops; the points stick" if "stick" in regime else
            "slip and approach stop" if "lock" in regime else "slip stops")

    def at(point: np.ndarray) -> tuple[float, float]:
        return float(point[0]), float(point[1])

    events = [(at(path[0]), "start", "C0", (8.0, -12.0))]
    events += [(at(p), bend, "C2", (8.0, 12.0)) for p in path[1:-1]]
    normal = v[0] + path @ W[0]  # the normal velocity at each event of the path
    for k in range(len(path) - 1):
        a, b = normal[k], normal[k + 1]
        if a < 0 <= b and b != a:
            where = path[k] + (path[k + 1] - path[k]) * (-a / (b - a))
            if not any(np.allclose(where, p) for p in path[1:]):
                events.append((at(where), "compression ends", "C1", (-8.0, -14.0)))
            break
    events.append((at(path[-1]), "the impact ends", "C0", (-10.0, -14.0)))
    return events


def animation(times: np.ndarray, points: dict[str, np.ndarray], title: str,
              frames: int = 60):
    """The motion after the impact as an animation of the tracked points, with trails.

    Points of one body (``barbell.A``, ``barbell.B``) are joined by its rod. The frame
    count is fixed (the run is resampled), so the same run gives the same animation.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Save it with a Pillow writer (GIF) or, where ffmpeg exists, as MP4.

    Examples
    --------
    >>> import tempfile
    >>> from PIL import Image
    >>> t = np.linspace(0, 1, 11)
    >>> anim = animation(t, {"ball": np.c_[t, 0 * t]}, "demo", frames=4)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     anim.save(f"{folder}/demo.gif", writer="pillow")
    ...     with Image.open(f"{folder}/demo.gif") as film:
    ...         film.n_frames
    4
    """
    from matplotlib.animation import FuncAnimation

    fig, draw = _animated(times, points, title, frames)
    return FuncAnimation(fig, draw, frames=frames, blit=False)


def write_gif(times: np.ndarray, points: dict[str, np.ndarray], title: str, path: str | Path,
              frames: int = 60, fps: int = 20, axes: str = "xy",
              planes: Sequence[tuple[str, np.ndarray, np.ndarray]] = (),
              radii: Mapping[str, float] | None = None) -> None:
    """:func:`animation`'s frames written as a GIF, the still parts (axes, ticks, grid,
    legend) drawn once and only the moving ones each frame: the same pictures as
    saving the animation with Pillow, in a fraction of the time. `axes` names the two
    coordinates drawn, or is ``"views"``: 3-D paths seen from above and from the side,
    with the `planes` drawn edge-on and the spheres at their `radii`.

    Examples
    --------
    >>> import tempfile
    >>> from PIL import Image
    >>> t = np.linspace(0, 1, 11)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_gif(t, {"ball": np.c_[t, 0 * t]}, "demo", f"{folder}/demo.gif", frames=4)
    ...     with Image.open(f"{folder}/demo.gif") as film:
    ...         film.n_frames
    4
    """
    from PIL import Image

    fig, draw = _animated_views(times, points, title, frames, planes, radii) \
        if axes == "views" else _animated(times, points, title, frames, axes)
    moving = draw(0)
    for artist in moving:
        artist.set_animated(True)
    canvas = fig.canvas
    canvas.draw()
    still = canvas.copy_from_bbox(fig.bbox)
    pictures = []
    for i in range(frames):
        canvas.restore_region(still)
        for artist in draw(i):
            fig.draw_artist(artist)
        width, height = canvas.get_width_height()
        pictures.append(Image.frombuffer("RGBA", (width, height),
                                         bytes(canvas.buffer_rgba())).convert("RGB"))
    plt.close(fig)
    pictures[0].save(path, format="GIF", save_all=True, append_images=pictures[1:],
                     loop=0, duration=round(1000 / fps))


def _animated(times: np.ndarray, points: dict[str, np.ndarray], title: str, frames: int,
              axes: str = "xy"):
    """The animation's figure and its frame-drawing function (returning the artists it
    moved); `axes` names the two coordinates drawn ("xz": a 3-D run seen from the
    side)."""
    when = np.linspace(times[0], times[-1], frames)
    tracks = {name: np.c_[np.interp(when, times, xy[:, 0]), np.interp(when, times, xy[:, 1])]
              for name, xy in points.items()}
    mean = np.mean(list(tracks.values()), axis=0)
    moving = {name: xy - mean for name, xy in tracks.items()}
    span = np.ptp(np.concatenate(list(tracks.values())), axis=0).max()
    follow = span > 3 * np.ptp(np.concatenate(list(moving.values())), axis=0).max()
    if follow:  # the pair drifts far: watch it from the points' mean, where it turns
        tracks = moving
    every = np.concatenate(list(tracks.values()))
    low, high = every.min(axis=0), every.max(axis=0)
    pad = 0.08 * max(float((high - low).max()), 1e-9)
    fig, ax = plt.subplots(figsize=(6.0, 4.5), dpi=80)
    ax.set_xlim(low[0] - pad, high[0] + pad)
    ax.set_ylim(low[1] - pad, high[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    h, v = axes[0], axes[1]
    ax.set_xlabel(f"{h} - mean {h} of the points (m)" if follow else f"{h} (m)")
    ax.set_ylabel(f"{v} - mean {v} of the points (m)" if follow else f"{v} (m)")
    ax.grid(alpha=0.3)
    bodies: dict[str, list[str]] = {}
    for name in tracks:
        bodies.setdefault(name.split(".")[0], []).append(name)
    trails = {name: ax.plot([], [], "-", lw=1, alpha=0.5, color=f"C{k}")[0]
              for k, name in enumerate(tracks)}
    dots = {name: ax.plot([], [], "o", ms=7, color=f"C{k}", label=name)[0]
            for k, name in enumerate(tracks)}
    rods = {body: ax.plot([], [], "-", lw=2.5, color="0.3")[0]
            for body, names in bodies.items() if len(names) == 2}
    clock = ax.set_title(title, fontsize="medium")
    ax.legend(fontsize="small", loc="upper left")

    def draw(i: int):
        for name, xy in tracks.items():
            trails[name].set_data(xy[: i + 1, 0], xy[: i + 1, 1])
            dots[name].set_data(xy[i : i + 1, 0], xy[i : i + 1, 1])
        for body, line in rods.items():
            a, b = (tracks[n][i] for n in bodies[body])
            line.set_data([a[0], b[0]], [a[1], b[1]])
        clock.set_text(f"{title}\nt = {when[i]:.4g} s after the impact")
        return [*trails.values(), *dots.values(), *rods.values(), clock]

    return fig, draw


def experiment_comparison(model: dict[str, tuple[np.ndarray, np.ndarray]],
                          data: dict[str, dict[str, tuple[np.ndarray, np.ndarray]]],
                          label: str, title: str,
                          others: dict[str, dict[str, tuple[np.ndarray, np.ndarray]]]
                          | None = None) -> Figure:
    """A model's curves against measured points, one panel per quantity (e_t, rebound
    angle, spin) over the impact angle.

    Parameters
    ----------
    model : quantity -> (angles in degrees, values)
    data : data set name -> quantity -> (angles, values)
    label : the model's legend entry
    others : a second model's legend entry -> its curves (drawn dashed)

    Examples
    --------
    >>> a = np.array([10.0, 40.0])
    >>> fig = experiment_comparison({"e_t": (a, a / 50)}, {"x": {"e_t": (a, a / 40)}},
    ...                             "model", "t")
    >>> len(fig.axes), len(fig.axes[0].lines)
    (1, 2)
    """
    names = {"e_t": r"tangential restitution $e_t$", "rebound_angle": "rebound angle (deg)",
             "omega": r"spin after $\omega$ (rad/s)"}
    shown = [q for q in names if q in model]
    fig, axes = plt.subplots(1, len(shown), figsize=(FIGSIZE[0] * 1.5, FIGSIZE[1]), dpi=DPI,
                             squeeze=False)
    markers = ("o", "s", "^", "D")
    for ax, quantity in zip(axes[0], shown, strict=True):
        angles, values = model[quantity]
        ax.plot(angles, values, color="black", label=label)
        for (name, curves), style in zip((others or {}).items(), ("--", ":"), strict=False):
            if quantity in curves:
                ax.plot(*curves[quantity], style, color="tab:red", label=name)
        for marker, (name, points) in zip(markers, data.items(), strict=False):
            if quantity in points:
                ax.plot(*points[quantity], marker, fillstyle="none", linestyle="none",
                        label=name)
        ax.set_xlabel("impact angle from the normal (deg)")
        ax.set_ylabel(names[quantity])
        ax.grid(alpha=0.3)
    if others:  # two models' long labels: one legend under the panels
        handles, labels = axes[0][0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=2, fontsize="x-small")
        fig.suptitle(title, fontsize="medium")
        fig.tight_layout(rect=(0, 0.16, 1, 1))
        return fig
    axes[0][0].legend(fontsize="x-small")
    fig.suptitle(title, fontsize="medium")
    fig.tight_layout()
    return fig


def impact_picture(bodies: Sequence, contacts: Sequence[tuple], after: dict[str, tuple],
                   title: str) -> Figure:
    """The bodies at the instant of impact, drawn with their shapes, with each centre's
    velocity before (grey, dashed) and after (coloured): the picture of a run that ends
    at the impact (``until = "separation"``), where there is no flight to draw.

    Parameters
    ----------
    bodies : sequence of Body
        With numbers for every field, in the scene frame.
    contacts : sequence of (point, normal, first name, second name)
        Numbers; a fixed body is drawn as a hatched line through each of its contacts.
    after : body name -> (vx, vy, omega)

    Examples
    --------
    >>> from rigidimpact.model.bodies import Body
    >>> ball, floor = Body.disc(1, 1, (0, 1), velocity=(0, -1), name="b"), Body.fixed("f")
    >>> fig = impact_picture([ball, floor], [((0, 0), (0, -1), "b", "f")],
    ...                      {"b": (0.0, 0.5, 0.0)}, "a disc on a floor")
    >>> len(fig.axes[0].patches) >= 3
    True
    """
    from matplotlib.patches import FancyArrowPatch

    fig, ax = plt.subplots(figsize=FIGSIZE, dpi=DPI)
    size = _picture_size(bodies, contacts)
    colours = draw_bodies(ax, bodies, contacts, label=True)
    speeds = [float(np.hypot(*_xy(b.velocity))) for b in bodies if b.support != "fixed"]
    speeds += [float(np.hypot(v[0], v[1])) for v in after.values()]
    scale = 0.35 * size / max(max(speeds, default=0.0), 1e-300)
    for body in bodies:
        if body.support == "fixed":
            continue
        centre = _xy(body.position)
        for velocity, colour, line in ((_xy(body.velocity), "grey", "--"),
                                       (np.asarray(after[body.name][:2], dtype=float),
                                        colours[body.name], "-")):
            if np.hypot(*velocity) > 0:
                tip = centre + scale * velocity
                ax.add_patch(FancyArrowPatch((centre[0], centre[1]), (tip[0], tip[1]),
                                             arrowstyle="-|>", mutation_scale=12, lw=1.5,
                                             color=colour, linestyle=line))
    ax.plot([], [], color="grey", linestyle="--", label="velocity before")
    ax.plot([], [], color="black", label="velocity after")
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize="small", loc="best")
    ax.grid(alpha=0.3)
    ax.set_title(title + ": at the impact", fontsize="medium")
    fig.tight_layout()
    return fig


def draw_bodies(ax, bodies: Sequence, contacts: Sequence[tuple],
                label: bool = False) -> dict[str, str]:
    """Draw each body's outline at the impact on `ax` (discs, rings and spheres as
    circles, rods and barbells as bars, particles and rigid bodies by their centre joined
    to their contacts, pivots as triangles) and each fixed body as a hatched line through
    its contacts; returns the colour given to each movable body."""

    palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    size = _picture_size(bodies, contacts)
    colours: dict[str, str] = {}
    for k, body in enumerate(b for b in bodies if b.support != "fixed"):
        colour = colours[body.name] = palette[k % len(palette)]
        name = body.name if label else None
        centre = _xy(body.position)
        dims = {key: float(value) for key, value in body.dimensions}
        if "radius" in dims:
            ax.add_patch(Circle(tuple(centre), dims["radius"], fill=False, color=colour,
                                lw=1.8, label=name))
        elif body.shape == "rod":
            axis = np.array([np.cos(dims["angle"]), np.sin(dims["angle"])])
            ends = np.array([centre - axis * dims["length"] / 2,
                             centre + axis * dims["length"] / 2])
            ax.plot(ends[:, 0], ends[:, 1], color=colour, lw=3, label=name)
        elif body.parts and len(body.parts) > 1:
            places = np.array([_xy(p.position) for p in body.parts])
            ax.plot(places[:, 0], places[:, 1], "-o", color=colour, lw=1.5, ms=7, label=name)
        else:  # a particle or a rigid body: its centre, joined to its contact points
            ax.plot(*centre, "o", color=colour, ms=7, label=name)
            for point, _, first, second in contacts:
                if body.name in (first, second):
                    ax.plot([centre[0], float(point[0])], [centre[1], float(point[1])],
                            color=colour, lw=1)
        if body.pivot is not None:
            pivot = _xy(body.pivot)
            ax.plot([centre[0], pivot[0]], [centre[1], pivot[1]], color=colour, lw=0.8)
            ax.plot(*pivot, "k^", ms=9)
    fixed = {b.name for b in bodies if b.support == "fixed"}
    for point, normal, first, second in contacts:
        point, normal = _xy(point), _xy(normal)
        normal = normal / np.hypot(*normal)
        tangent = np.array([-normal[1], normal[0]])
        if second in fixed or first in fixed:
            side = normal if second in fixed else -normal  # into the fixed body
            line = np.array([point - 0.3 * size * tangent, point + 0.3 * size * tangent])
            ax.plot(line[:, 0], line[:, 1], "k-", lw=1.5)
            for s in np.linspace(-0.3, 0.3, 9):
                start = point + s * size * tangent
                tick = np.array([start, start + 0.04 * size * (side - tangent)])
                ax.plot(tick[:, 0], tick[:, 1], "k-", lw=0.8)
        ax.plot(*point, "kx", ms=6)
    return colours


def _picture_size(bodies: Sequence, contacts: Sequence[tuple]) -> float:
    """The extent of what is drawn: the distances between centres and contact points."""
    places = [_xy(b.position) for b in bodies if b.support != "fixed"]
    places += [_xy(p) for p, *_ in contacts]
    for b in bodies:
        dims = {key: float(value) for key, value in b.dimensions}
        places += [_xy(b.position) + dims.get("radius", 0.0),
                   _xy(b.position) + dims.get("length", 0.0) / 2]
    spread = np.ptp(np.array(places), axis=0)
    return float(max(spread.max(), 1e-300))


def _xy(vector) -> np.ndarray:
    """A 2-vector (a SymPy column of numbers, a tuple) as floats."""
    return np.array([float(c) for c in vector])


def order_spread(rows: Sequence[dict[str, float]], sample: dict) -> Figure:
    """A histogram of each output that varies over a sample of sequential orders (at
    most six, those that vary most), with its min and max: the spread of a sample, not
    of every order.

    Examples
    --------
    >>> fig = order_spread([{"a.vx": 0.0}, {"a.vx": 1.0}],
    ...                    {"orders": 2, "seed": 0, "distinct": 2})
    >>> len(fig.axes)
    1
    """
    keys = sorted(rows[0], key=lambda k: -(max(r[k] for r in rows) - min(r[k] for r in rows)))
    varying = [k for k in keys if max(r[k] for r in rows) > min(r[k] for r in rows)][:6]
    fig = plt.figure(figsize=FIGSIZE, dpi=DPI)
    if not varying:
        ax = fig.add_subplot()
        ax.text(0.5, 0.5, "every output is the same in every order drawn",
                ha="center", va="center")
        ax.set_axis_off()
        return fig
    columns = min(3, len(varying))
    lines = -(-len(varying) // columns)
    for i, key in enumerate(varying):
        ax = fig.add_subplot(lines, columns, i + 1)
        values = [r[key] for r in rows]
        ax.hist(values, bins=min(30, max(5, len(values) // 5)), color="C0")
        ax.set_title(f"{key}\n[{min(values):.4g}, {max(values):.4g}]", fontsize="small")
        ax.tick_params(labelsize="small")
    fig.suptitle(f"a sample of {sample['orders']} orders (seed {sample['seed']}, "
                 f"{sample['distinct']} distinct)", fontsize="medium")
    fig.tight_layout()
    return fig


def random_outputs(curves: Sequence[tuple[str, np.ndarray, np.ndarray, np.ndarray | None,
                                          np.ndarray | None]], title: str) -> Figure:
    """Each random output in a panel of its own: the histogram of its draws and, where
    it has one in closed form, its exact density over it. Each curve is (the output's
    key, bin edges, sampled density per bin, points and exact density at them, or None
    and None).

    Examples
    --------
    >>> edges = np.linspace(0, 1, 11)
    >>> fig = random_outputs([("ball.vy", edges, np.ones(10), edges[1:-1],
    ...                        np.ones(9))], "a uniform output")
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['ball.vy']
    """
    fig, axes = plt.subplots(len(curves), 1, figsize=(7, 2.2 + 2.2 * len(curves)),
                             squeeze=False)
    for ax, (key, edges, sampled, points, exact) in zip(axes[:, 0], curves, strict=True):
        ax.stairs(sampled, edges, color="C0", alpha=0.45, fill=True,
                  label="Monte Carlo (histogram of the draws)")
        top = float(np.max(sampled)) if len(sampled) else 1.0
        if points is not None:
            ax.plot(points, exact, color="C1", lw=1.4, label="exact density")
        ax.set_ylim(0, 1.3 * top if top > 0 else 1.0)  # an infinite end of a density
        ax.set_xlabel(key)
        ax.set_ylabel("probability density")
        ax.legend(fontsize="small")
    axes[0, 0].set_title(title, fontsize="medium")
    fig.tight_layout()
    return fig


def random_rebound(curves: Sequence[tuple[str, np.ndarray, np.ndarray, np.ndarray,
                                          np.ndarray]], title: str) -> Figure:
    """Histograms of sampled outputs over their exact densities: each curve is (label,
    bin edges, sampled density per bin, points, exact density at the points)."""
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for k, (label, edges, sampled, points, exact) in enumerate(curves):
        colour = f"C{k}"
        ax.stairs(sampled, edges, color=colour, alpha=0.45, fill=True,
                  label=f"{label}: sampled")
        ax.plot(points, exact, color=colour, lw=1.2, label=f"{label}: exact density")
    ax.set_xlabel("rebound velocity of the centre / falling speed")
    ax.set_ylabel("probability density")
    ax.set_title(title, fontsize="medium")
    ax.set_ylim(0, 8)  # the densities' ends are infinite (integrable): the body shown
    ax.legend(fontsize="small")
    fig.tight_layout()
    return fig


