"""The command line's pictures of a run: a planar run's trajectories (or the bodies at
the impact, for a run that ends there) and its animation; a 3-D run's path from above and
from the side, still and animated. Each file is written whole or not at all.

The command line loads this module only when a picture is asked for, after choosing the
Agg backend (it draws to files, whatever the machine has).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from matplotlib.animation import FFMpegWriter

from rigidimpact.analyses.distributions import distribution_curves, distributions
from rigidimpact.errors import InputError
from rigidimpact.outputs.atomic import write_file
from rigidimpact.outputs.plots import (
    animation,
    impact_picture,
    random_outputs,
    trajectories,
    write_gif,
)
from rigidimpact.outputs.views import space_impact, space_views
from rigidimpact.scenes.space import SpaceScene, load_any
from rigidimpact.simulate import impact_view

__all__ = ["draw", "animate", "draw_distributions", "plot_outcome", "animate_outcome", "plot_space",
           "animate_space", "ends_at_impact", "close"]


def draw(scene: Any, outcome: Any, path: str | Path) -> None:
    """Draw a run of :func:`rigidimpact.run` to a PNG, as ``simulate --plot`` does: a
    planar run's paths (or the bodies at the impact, for a run that ends there), a 3-D
    run's path from above and from the side.

    Examples
    --------
    >>> import rigidimpact as ri
    >>> scene = ri.load_any("derivations/restrike.toml")
    >>> ri.draw(scene, ri.run(scene), "restrike.png")  # doctest: +SKIP
    """
    if not isinstance(scene, SpaceScene):
        plot_outcome(scene, outcome, Path(path))
    elif getattr(outcome, "trajectory", None) is None:
        plot_space_impact(scene, outcome, Path(path))
    else:
        plot_space(scene, outcome, Path(path))


def animate(scene: Any, outcome: Any, path: str | Path) -> None:
    """Animate a run of :func:`rigidimpact.run` to a GIF, as ``simulate --animate``
    does (a 3-D run seen from above and from the side at once). A run that ends at the
    impact has nothing to animate: :class:`~rigidimpact.errors.InputError` says so."""
    if isinstance(scene, SpaceScene):
        if getattr(outcome, "trajectory", None) is None:
            raise InputError("--animate", "this 3-D run ends at the impact: nothing moves "
                             "to animate; give [simulate] until a time or impacts a count")
        animate_space(scene, outcome, Path(path))
    else:
        animate_outcome(scene, outcome, Path(path))


def draw_distributions(scene: Any, path: str | Path,
                       found: dict[str, dict[str, Any]] | None = None) -> list[str]:
    """Draw each random output of a scene to a PNG, as ``derive SCENE --plot`` does: the
    histogram of its draws at the scene's ``[values]`` and, where it has one, its exact
    density over it.

    Parameters
    ----------
    scene : Scene, str or Path
        A scene with a ``[random]`` table, or the path of its TOML file.
    path : str or Path
        The PNG to write (whole or not at all).
    found : dict, optional
        The distributions :func:`rigidimpact.distributions` gave for this scene, so
        their closed forms are not derived again; derived here when not given.

    Returns
    -------
    list of str
        The random outputs left out of the picture (driven by two or more random
        inputs, or by a symbol without a value), for the caller to say so.

    Raises
    ------
    InputError
        When the scene has no ``[random]`` table, or no random output is driven by one
        random input with every other symbol given a value (nothing to draw).

    Examples
    --------
    >>> import rigidimpact as ri
    >>> ri.draw_distributions("derivations/random-barbell.toml",
    ...                       "random-barbell.png")  # doctest: +SKIP
    """
    if isinstance(scene, (str, Path)):
        scene = load_any(scene)
    if found is None:
        found = distributions(scene)
    curves = distribution_curves(scene, dict(scene.derivation().results), found)
    if not curves:
        raise InputError("--plot", "no [random] output here is driven by one random input "
                         "with every other symbol given: nothing to draw")
    figure = random_outputs(curves, f"{scene.title or scene.name}: draws at [values] "
                            f"(seed {scene.random.seed})")
    try:
        write_file(Path(path), lambda temporary: figure.savefig(temporary, format="png"),
                   "--plot")
    finally:
        close(figure)
    drawn = {curve[0] for curve in curves}
    return [key for key in found if key not in drawn]


def plot_space(scene: Any, outcome: Any, path: Path) -> None:
    """A 3-D run's path from above and from the side, its impacts marked, to a PNG
    written whole or not at all."""
    track = outcome.trajectory
    _, points = track.every()
    said = {"impact": "impact", "rolls": "starts to roll", "stops": "stops"}
    marks = [(said[e.kind], np.array([float(x) for x in e.position]))
             for e in track.run.events if e.kind in said]
    figure = space_views({f"{name}'s centre": path for name, path in points.items()},
                         scene.title, marks, planes=_planes(track),
                         radii={f"{b.name}'s centre": float(b.radius) for b in track.balls})
    try:
        write_file(path, lambda temporary: figure.savefig(temporary, format="png"), "--plot")
    finally:
        close(figure)


def plot_space_impact(scene: Any, outcome: Any, path: Path) -> None:
    """A 3-D run that ends at the impact: each moving body's velocity before and after,
    seen from above and from the side, the contact points marked; a PNG written whole or
    not at all."""
    moving = [b.at(scene.values) for b in scene.bodies if b.support != "fixed"]
    centres = {b.name: np.array(b.position, dtype=float).ravel() for b in moving}
    before = {b.name: np.array(b.velocity, dtype=float).ravel() for b in moving}
    after = {b.name: np.array([float(outcome.final[f"{b.name}.v{axis}"]) for axis in "xyz"])
             for b in moving}
    points = [(c.name, np.array(sp.Matrix(c.point).xreplace(scene.values), dtype=float)
               .ravel()) for c in scene.contacts]
    radii = {b.name: float(b.radius) for b in moving if b.radius is not None}
    figure = space_impact(centres, before, after, points, scene.title, radii)
    try:
        write_file(path, lambda temporary: figure.savefig(temporary, format="png"), "--plot")
    finally:
        close(figure)


def _planes(track: Any) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """The run's planes, each once, as (name, point, unit normal) in floats."""
    return [(name, np.array([float(x) for x in p]), np.array([float(x) for x in n]))
            for name, p, n in track.run.planes]


def animate_space(scene: Any, outcome: Any, path: Path) -> None:
    """A 3-D run seen from above and from the side, animated to a GIF, whole or not at
    all."""
    track = outcome.trajectory
    times, points = track.every()
    write_file(path, lambda temporary: write_gif(
        times, points, scene.title, temporary, fps=20, axes="views",
        planes=_planes(track), radii={b.name: float(b.radius) for b in track.balls}),
        "--animate")


def animate_outcome(scene: Any, outcome: Any, path: Path) -> None:
    """Animate a run to a GIF (Pillow) or MP4 (ffmpeg), written whole or not at all."""
    if ends_at_impact(outcome):
        raise InputError("--animate", "this run ends at the impact (until = "
                         f"{outcome.plan.until!r}): nothing moves to animate; give "
                         "[simulate] until a time, or draw the impact with --plot")
    track = outcome.trajectory
    if path.suffix.lower() != ".mp4":  # a GIF: the still parts drawn once
        write_file(path, lambda temporary: write_gif(
            np.asarray(track.t), track.points(), scene.title, temporary, fps=20),
            "--animate")
        return
    movie = animation(np.asarray(track.t), track.points(), scene.title)

    def save(temporary: Path) -> None:
        movie.save(str(temporary), writer=FFMpegWriter(fps=20))

    try:
        write_file(path, save, "--animate")
    finally:
        close(movie._fig)


def ends_at_impact(outcome: Any) -> bool:
    """Whether a run has nothing after the impact to draw (it stops at separation)."""
    return float(outcome.final.get("t", 0.0)) == 0.0 and outcome.ode_steps == 0


def plot_outcome(scene: Any, outcome: Any, path: Path) -> None:
    """Draw a run's trajectories to a PNG (or, for a run that ends at the impact, the
    bodies at the impact with their velocities), written whole or not at all."""
    if ends_at_impact(outcome):
        figure = impact_picture(*impact_view(scene, outcome), scene.title)
        try:
            write_file(path, lambda temporary: figure.savefig(temporary, format="png"),
                       "--plot")
        finally:
            close(figure)
        return
    track = outcome.trajectory
    velocity = None
    if hasattr(track, "contact_velocity"):
        name = scene.contact.second
        velocity = (f"{name} at O", track.contact_velocity(name))
    bodies, contacts, _ = impact_view(scene, outcome)
    figure = trajectories(track.t, track.points(), scene.title, velocity,
                          (bodies, contacts) if len(scene.contacts) > 1 else None)
    try:
        write_file(path, lambda temporary: figure.savefig(temporary, format="png"), "--plot")
    finally:
        close(figure)


def close(figure: Any) -> None:
    """Release a figure (pyplot keeps every figure it made until closed)."""
    plt.close(figure)
