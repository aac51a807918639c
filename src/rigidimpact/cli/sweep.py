"""``rigidimpact sweep``: a scene's outputs over a grid of one or more symbols (or a
random sample), with a table, a plot and a progress bar."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from rigidimpact.cli.common import (
    _check_plot_path,
    _check_workers,
    _derivation,
    _print_json,
    _settings,
)
from rigidimpact.errors import InputError


def _cmd_sweep(args: argparse.Namespace) -> int:
    """Evaluate over a grid, chunk by chunk, into DIR/KEY.npy, DIR/summary.json and
    DIR/table.csv; with --plot, every written result against the swept symbol."""
    import itertools
    import time

    from rigidimpact.outputs.sweep import parse_grid, run_sweep
    from rigidimpact.paper.problems import PROBLEMS
    from rigidimpact.scenes.scene import load_scene

    _check_sweep_plot(args)
    defaults: Mapping[Any, Any] = {}
    if args.target in PROBLEMS:
        derivation = _derivation(args.target)
    else:
        scene = load_scene(args.target)
        if len(scene.contacts) > 1:  # no closed form: each set solved with numbers
            return _point_sweep(args, scene)
        derivation, defaults = scene.derivation(), scene.values
    values, sources = _settings(defaults, args.set)
    grid = parse_grid(args.grid, derivation.symbols)
    results = dict(derivation.results)
    if args.keys:
        chosen = [k.strip() for k in args.keys.split(",") if k.strip()]
        unknown = [k for k in chosen if k not in results]
        if unknown or not chosen:
            raise InputError("--keys", f"no result {unknown[0] if unknown else ''!r}; the "
                             f"results are {', '.join(results)}")
        # the energy lost and the normal impulses are always evaluated, for the warnings
        watched = [k for k in derivation.results if k == "energy_loss_fraction"
                   or k.endswith("normal_impulse")]
        results = {k: results[k] for k in [*chosen, *(w for w in watched
                                                      if w not in chosen)]}
    fixed_names = [n for n in values if n not in grid]
    names = list(grid)
    corners = list(itertools.islice(itertools.product(*((a[0], a[-1])
                                                          for a in grid.values())), 64))
    exact: dict[str, Any] = {}
    for corner in corners or [()]:  # every value, and the grid's corners, checked
        point = {n: values[n] for n in fixed_names} | {
            n: repr(float(x)) for n, x in zip(names, corner, strict=True)}
        where = dict(sources) | {n: f"--grid {n}" for n in names}
        exact = derivation.checked(point, where)
    fixed = {n: float(exact[n]) for n in fixed_names if n in exact}
    started, last = time.perf_counter(), [-1]

    def progress(done: int, count: int) -> None:
        if time.perf_counter() - started < 2.0:
            return  # a short run draws no bar
        percent = 100 * done // count
        if percent != last[0]:  # at most a hundred redraws
            last[0] = percent
            _progress_bar(done, count, "parameter sets")

    _check_workers(args)
    summary = run_sweep(results, grid, fixed, Path(args.out), args.backend, progress,
                        kept=chosen if args.keys else None, workers=args.workers,
                        scheduler=args.scheduler)
    for warning in summary["warnings"]:
        print(f"rigidimpact: warning: {warning}", file=sys.stderr)
    if summary.get("workers"):
        print(f"rigidimpact: note: {summary['workers']}", file=sys.stderr)
    _sweep_plot(args, summary, [k for k in summary["results"]
                                if not args.keys or k in chosen])
    if args.json:
        _print_json(summary)
        return 0
    print(f"{summary['sets']} parameter sets ({' x '.join(map(str, summary['shape'])) or 1})"
          f" in {summary['seconds']:.3g} s with {args.backend}; written to {args.out}/")
    for key, stat in summary["results"].items():
        extra = f", {stat['not_finite']} not finite" if stat["not_finite"] else ""
        if args.keys and key not in chosen:  # evaluated for its warnings only
            print(f"  {key} (checked for the warnings, not written): from {stat['min']!r}"
                  f" to {stat['max']!r}{extra}")
        else:
            print(f"  {key}.npy: from {stat['min']!r} to {stat['max']!r}{extra}")
    _say_table(args, summary)
    return 0


def _check_sweep_plot(args: argparse.Namespace) -> None:
    """--plot is checked before any work: a PNG in a folder that exists, one --grid."""
    if not args.plot:
        return
    if Path(args.out).resolve() in Path(args.plot).resolve().parents:
        raise InputError("--plot", "the --out folder is replaced whole; put the figure "
                         "beside it, not in it")
    _check_plot_path(Path(args.plot))
    if len(args.grid) != 1:
        raise InputError("--plot", f"draws each result against one swept symbol; give "
                         f"exactly one --grid (got {len(args.grid)})")


def _sweep_plot(args: argparse.Namespace, summary: dict[str, Any], keys: list[str]) -> None:
    """Each written result against the swept symbol, read back from the --out folder."""
    if not args.plot:
        return
    import numpy as np

    _files_only()
    from rigidimpact.figures import close
    from rigidimpact.outputs.atomic import write_file
    from rigidimpact.outputs.plots import sweep_curves

    [name] = summary["order"]
    span = summary["grid"][name]
    x = np.linspace(span["start"], span["stop"], span["count"])
    outputs = {k: np.load(Path(args.out) / f"{k}.npy", mmap_mode="r") for k in keys}
    figure = sweep_curves(name, x, outputs,
                          f"{Path(args.target).name}: every result against {name}")
    write_file(Path(args.plot), lambda temporary: figure.savefig(temporary, format="png"),
               "--plot")
    close(figure)
    print(f"rigidimpact: figure written to {args.plot}", file=sys.stderr)


def _say_table(args: argparse.Namespace, summary: dict[str, Any]) -> None:
    from rigidimpact.outputs.sweep import MAX_TABLE, TABLE

    if summary.get("table"):
        print(f"  {TABLE}: one row a set (the swept symbols, then each result)")
    else:
        print(f"  {TABLE} not written: {summary['sets']} sets is past {MAX_TABLE:.0e} rows "
              "(the .npy files hold every value)")


def _point_sweep(args: argparse.Namespace, scene: Any) -> int:
    """A sweep of a scene with several contacts: each set solved with numbers by the
    scene's rule (the compliant one too), in this process or on Dask workers."""
    import time

    from rigidimpact.outputs.sweep import parse_grid, run_point_sweep
    from rigidimpact.symbolic.expr import parse_expression

    if args.keys or args.backend != "numpy":
        raise InputError("--keys" if args.keys else "--backend", "a scene with several "
                         "contacts is solved set by set: every result is written")
    _check_sweep_plot(args)
    _check_workers(args)
    grid = parse_grid(args.grid, scene.symbols)
    fixed: dict[str, float] = {}
    for setting in args.set:
        name, eq, text = setting.partition("=")
        name = name.strip()
        if not eq or name not in scene.symbols:
            raise InputError("--set", f"expected NAME=VALUE with a symbol of the scene, "
                             f"got {setting!r}")
        value = parse_expression(text, f"--set {name}", {})
        if not value.is_number:
            raise InputError(f"--set {name}", "must be a number")
        fixed[name] = float(value)
    started = time.perf_counter()

    def progress(done: int, count: int) -> None:
        if time.perf_counter() - started >= 2.0:
            _progress_bar(done, count, "solves")

    summary = run_point_sweep(args.target, grid, fixed, Path(args.out), progress,
                              args.workers, args.scheduler)
    for warning in summary["warnings"]:
        print(f"rigidimpact: warning: {warning}", file=sys.stderr)
    if summary.get("workers"):
        print(f"rigidimpact: note: {summary['workers']}", file=sys.stderr)
    _sweep_plot(args, summary, list(summary["results"]))
    if args.json:
        _print_json(summary)
        return 0
    print(f"{summary['sets']} parameter sets, each solved with numbers, in "
          f"{summary['seconds']:.3g} s; written to {args.out}/")
    _say_table(args, summary)
    return 0


def _progress_bar(done: int, total: int, label: str) -> None:
    """A one-line bar on standard error, redrawn in place (plain lines when not a TTY)."""
    width = 30
    filled = int(width * done / max(total, 1))
    line = f"[{'#' * filled}{'.' * (width - filled)}] {done}/{total} {label}"
    if sys.stderr.isatty():
        print(f"\r{line[:100]:<100}", end="" if done < total else "\n", file=sys.stderr,
              flush=True)
    elif done == total or done % 10 == 0:
        print(line, file=sys.stderr, flush=True)


def _tasks_bar(done: int, total: int) -> None:
    """The bar of a Monte Carlo's Dask tasks (each a run of draws or of solves)."""
    _progress_bar(done, total, "Dask tasks")


def _files_only() -> None:
    """The command line draws to files: the Agg backend, whatever the machine has."""
    import matplotlib

    matplotlib.use("Agg")
