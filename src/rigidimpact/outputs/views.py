"""Figures of runs in three dimensions: paths seen from above (x, y) over the same seen
from the side (x, z) at one scale, the planes they meet drawn edge-on; their animation;
an impact's velocities before and after. Each function returns its Figure.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from rigidimpact.outputs.style import DPI

__all__ = ["space_views", "space_impact"]


def space_views(points: np.ndarray | Mapping[str, np.ndarray], title: str,
                marks: Sequence[tuple[str, np.ndarray]] = (), name: str = "centre",
                planes: Sequence[tuple[str, np.ndarray, np.ndarray]] = (),
                radii: Mapping[str, float] | None = None) -> Figure:
    """3-D paths (one, labelled `name`, or several by their labels) seen from above
    (x, y) and from the side (x, z), one over the other at the same scale, each view
    spanning what moves (with the spheres' sizes, `radii` by label, and the planes each
    meets edge-on); marked points (each impact, where a sphere starts to roll) on both;
    each plane (name, point, normal) drawn as a line in the view it is seen edge-on in;
    each sphere drawn at its size where it starts and where it ends.

    Examples
    --------
    >>> t = np.linspace(0, 1, 5)
    >>> fig = space_views(np.c_[t, 0 * t, 1 - t * t], "demo", [("impact", np.array([1, 0, 0]))])
    >>> [ax.get_xlabel() + " " + ax.get_ylabel() for ax in fig.axes]
    ['x (m) y (m)', 'x (m) z (m)']
    """
    paths = dict(points) if isinstance(points, Mapping) else {name: points}
    sizes = {label: float((radii or {}).get(label, 0.0)) for label in paths}
    fig, views = _two_views(paths, sizes, planes, 8.0, DPI, title)
    for ax, (i, j) in views:
        for k, (label, path) in enumerate(paths.items()):
            ax.plot(path[:, i], path[:, j], "-", lw=1.8, color=f"C{k}", label=label)
            ax.plot(path[:1, i], path[:1, j], "k.", ms=6,
                    label="start (t = 0)" if k == 0 else None)
            if sizes[label] > 0:
                for end, alpha in ((path[0], 0.25), (path[-1], 0.55)):
                    ax.add_patch(Circle((end[i], end[j]), sizes[label], color=f"C{k}",
                                        alpha=alpha, lw=0))
        for k, (kind, where) in enumerate(marks):
            first = all(m[0] != kind for m in marks[:k])
            style = {"impact": ("x", "C3"), "stops": ("o", "0.2")}.get(kind, ("s", "C2"))
            ax.plot([where[i]], [where[j]], style[0], ms=7, color=style[1],
                    label=kind if first else None)
    _taller(views).legend(fontsize="small", loc="best", ncol=2)  # short: off the paths
    return fig


def _two_views(paths: Mapping[str, np.ndarray], radii: Mapping[str, float],
               planes: Sequence[tuple[str, np.ndarray, np.ndarray]], width: float,
               dpi: int, title: str) -> tuple[Figure, list]:
    """A figure with 3-D paths' view from above over their view from the side, at one
    scale (equal axes, the same x range): each spans the paths with their spheres'
    radii and the levels of the planes seen edge-on in it, padded; those planes drawn as
    lines, named. Returns the figure and [(axes, (i, j)) for the two views]."""
    every = np.concatenate([np.c_[p - radii[k], p + radii[k]].reshape(-1, 3)
                            for k, p in paths.items()])
    low, high = every.min(axis=0), every.max(axis=0)
    for _, p, n in planes:  # a plane along an axis: its level is part of the view
        if np.count_nonzero(np.abs(n) > 1e-12) == 1:
            axis = int(np.argmax(np.abs(n)))
            low[axis], high[axis] = min(low[axis], p[axis]), max(high[axis], p[axis])
    size = max(float((high - low).max()), max(radii.values(), default=0.0), 1e-9)
    pad = np.maximum(0.04 * size, 0.15 * (high - low))
    low, high = low - pad, high + pad
    spans = high - low
    axes_width = width - 1.3
    tall = [axes_width * spans[1] / spans[0], axes_width * spans[2] / spans[0]]
    scale = min(1.0, 7.5 / sum(tall))  # a tall run is drawn narrower
    fig = plt.figure(figsize=(width, max(2.5, scale * sum(tall) + 1.6)), dpi=dpi)
    grid = fig.add_gridspec(2, 1, height_ratios=[max(h, 0.05) for h in tall])
    views = []
    for row, (j, view) in enumerate(((1, "from above"), (2, "from the side"))):
        ax = fig.add_subplot(grid[row])
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[j], high[j])
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("yz"[j - 1] + " (m)")
        ax.set_title(view, fontsize="small")
        ax.grid(alpha=0.3)
        for label, p, n in planes:
            _draw_plane(ax, (0, j), label, p, n)
        views.append((ax, (0, j)))
    fig.suptitle(title, fontsize="medium")
    fig.tight_layout()
    for ax, _ in views:  # each box at its equal-axes size, then laid out again: room
        ax.apply_aspect()  # for the labels of the boxes as drawn, not one over another
    fig.tight_layout()
    return fig, views


def _taller(views: list) -> Any:
    """The view drawn taller: the one with room for a legend."""
    return max((ax for ax, _ in views), key=lambda ax: ax.get_position().height)


def _draw_plane(ax, view: tuple[int, int], label: str, p: np.ndarray, n: np.ndarray) -> None:
    """A plane seen edge-on in `view` (its normal has no part out of the view) as a grey
    line across the axes, its name on it."""
    i, j = view
    if abs(n[3 - i - j]) > 1e-12:
        return
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    level = float(np.dot(n, p))  # n_i x + n_j y = level in this view
    if abs(n[j]) >= abs(n[i]):
        xs = np.array([x0, x1])
        ys = (level - n[i] * xs) / n[j]
    else:
        ys = np.array([y0, y1])
        xs = (level - n[j] * ys) / n[i]
    ax.plot(xs, ys, "-", color="0.45", lw=3, alpha=0.5, solid_capstyle="butt")
    upper = np.mean(ys) > np.mean((y0, y1))  # the name on the side away from the middle
    ax.annotate(label, (float(np.mean(xs)), float(np.mean(ys))), fontsize="small",
                color="0.3", ha="center", va="bottom" if upper else "top")


def _animated_views(times: np.ndarray, points: dict[str, np.ndarray], title: str,
                    frames: int, planes: Sequence[tuple[str, np.ndarray, np.ndarray]] = (),
                    radii: Mapping[str, float] | None = None):
    """Like :func:`_animated`, for 3-D paths: from above (x, y) over from the side
    (x, z) at one scale spanning what moves (:func:`_two_views`), the planes drawn
    edge-on, each sphere's trail and the sphere itself at its size (`radii` by name; a
    dot where none is given)."""
    when = np.linspace(times[0], times[-1], frames)
    tracks = {name: np.stack([np.interp(when, times, xyz[:, j]) for j in range(3)], axis=1)
              for name, xyz in points.items()}
    sizes = {name: float((radii or {}).get(name, 0.0)) for name in tracks}
    fig, views = _two_views(tracks, sizes, planes, 8.0, 80, f"{title}\nt = 0 s")
    artists = []
    for ax, (i, j) in views:
        for k, name in enumerate(tracks):
            trail = ax.plot([], [], "-", lw=1, alpha=0.5, color=f"C{k}")[0]
            if sizes[name] > 0:
                body = ax.add_patch(Circle((tracks[name][0, i], tracks[name][0, j]),
                                           sizes[name], color=f"C{k}", alpha=0.8, lw=0,
                                           label=name))
            else:
                body = ax.plot([], [], "o", ms=7, color=f"C{k}", label=name)[0]
            artists.append((tracks[name], (i, j), trail, body))
    _taller(views).legend(fontsize="small", loc="upper right")
    clock = fig.texts[-1]  # the title, room made for its clock line

    def draw(n: int):
        for xyz, (i, j), trail, body in artists:
            trail.set_data(xyz[: n + 1, i], xyz[: n + 1, j])
            if isinstance(body, Circle):
                body.set_center((xyz[n, i], xyz[n, j]))
            else:
                body.set_data(xyz[n : n + 1, i], xyz[n : n + 1, j])
        clock.set_text(f"{title}\nt = {when[n]:.4g} s")
        return [*(a[2] for a in artists), *(a[3] for a in artists), clock]

    return fig, draw


def space_impact(centres: Mapping[str, np.ndarray], before: Mapping[str, np.ndarray],
                 after: Mapping[str, np.ndarray], points: Sequence[tuple[str, np.ndarray]],
                 title: str, radii: Mapping[str, float] | None = None) -> Figure:
    """A 3-D impact seen from above (x, y) and from the side (x, z): each moving body's
    centre (a sphere at its size), its velocity before (grey, dashed) and after (in its
    colour) as arrows from the centre, and each contact point marked.

    Examples
    --------
    >>> c = {"ball": np.array([0.0, 0.0, 1.0])}
    >>> fig = space_impact(c, {"ball": np.array([1.0, 0, -2])},
    ...                    {"ball": np.array([0.7, 0, 1])}, [("floor", np.zeros(3))], "demo",
    ...                    {"ball": 1.0})
    >>> [ax.get_xlabel() + " " + ax.get_ylabel() for ax in fig.axes]
    ['x (m) y (m)', 'x (m) z (m)']
    """
    speed = max([float(np.linalg.norm(v)) for v in [*before.values(), *after.values()]]
                + [1e-12])
    sizes = {name: float((radii or {}).get(name, 0.0)) for name in centres}
    reach = max([*sizes.values(), *(float(np.linalg.norm(c - p)) for c in centres.values()
                                   for _, p in points), 1e-9])
    scale = 2.0 * reach / speed  # the fastest arrow twice as long as the scene is wide
    paths = {name: np.array([c, c + scale * before[name], c + scale * after[name]])
             for name, c in centres.items()}
    for label, p in points:
        paths[f"contact {label}"] = np.array([p])
        sizes[f"contact {label}"] = 0.0
    fig, views = _two_views(paths, sizes, (), 8.0, DPI, title)
    for ax, (i, j) in views:
        for k, (name, c) in enumerate(centres.items()):
            if sizes[name] > 0:
                ax.add_patch(Circle((c[i], c[j]), sizes[name], color=f"C{k}", alpha=0.3,
                                    lw=0))
            ax.plot([c[i]], [c[j]], "k.", ms=6)
            for velocity, style, label in ((before[name], dict(color="0.5", ls="--"),
                                            f"{name}: velocity before"),
                                           (after[name], dict(color=f"C{k}", ls="-"),
                                            f"{name}: velocity after")):
                tip = c + scale * velocity
                ax.annotate("", xy=(tip[i], tip[j]), xytext=(c[i], c[j]),
                            arrowprops=dict(arrowstyle="->", lw=1.8, **style))
                ax.plot([], [], label=label, **style)
        for k, (_, p) in enumerate(points):
            ax.plot([p[i]], [p[j]], "x", ms=8, color="C3",
                    label="contact point" if k == 0 else None)
    _taller(views).legend(fontsize="small", loc="best")
    return fig
