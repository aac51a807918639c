"""What the commands share: a problem or scene by name or path, JSON that holds only
finite numbers, a scene's values overridden by ``--set``, and the checks of a worker
count and a figure's path."""

from __future__ import annotations

import argparse
import json
import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rigidimpact.errors import InputError

if TYPE_CHECKING:
    import sympy as sp


def _derivation(target: str):
    """A built-in problem by name, or a scene file by path."""
    from rigidimpact.paper.problems import PROBLEMS, derive

    if target in PROBLEMS:
        return derive(target)
    if target.endswith(".toml") or Path(target).exists():
        from rigidimpact.scenes.space import load_any  # a scene's reader, for scenes

        return load_any(target).derivation()
    raise InputError("problem", f"unknown problem {target!r}; use one of "
                     f"{', '.join(PROBLEMS)} or a scene file (.toml)")


def _expr_json(expr: sp.Expr) -> dict[str, str]:
    from rigidimpact.outputs.latex import to_latex

    return {"sympy": str(expr), "latex": to_latex(expr)}


def _finite_json(data: Any) -> Any:
    """The data with every non-finite float as null: JSON has no NaN or Infinity."""
    if isinstance(data, float):
        return data if data == data and abs(data) != float("inf") else None
    if isinstance(data, dict):
        return {k: _finite_json(v) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [_finite_json(v) for v in data]
    return data


def _print_json(data: Any) -> None:
    print(json.dumps(_finite_json(data), indent=2, allow_nan=False))


def _check_workers(args: argparse.Namespace) -> None:
    """`--workers N`: a count of Dask workers, from 1 to 1024."""
    if args.workers is not None and not 1 <= args.workers <= 1024:
        raise InputError("--workers", f"must lie between 1 and 1024, got {args.workers}")


def _settings(defaults: Any, settings: Sequence[str]) -> tuple[dict, dict]:
    """A scene's [values] overridden by each --set NAME=VALUE, and where each came from."""
    values = {s.name: v for s, v in defaults.items()}
    sources = {name: f"values.{name}" for name in values}
    for setting in settings:
        name, eq, text = setting.partition("=")
        name = name.strip()
        if not eq or not name:
            raise InputError("--set", f"expected NAME=VALUE, got {setting!r}")
        values[name], sources[name] = text, f"--set {name}"
    return values, sources


def _check_plot_path(path: Path, suffixes: tuple[str, ...] = (".png",),
                     option: str = "--plot") -> None:
    if path.suffix.lower() not in suffixes:
        raise InputError(option, f"expected a {' or '.join(suffixes)} file name, got "
                         f"{str(path)!r}")
    if path.suffix.lower() == ".mp4":
        from matplotlib.animation import FFMpegWriter

        if not FFMpegWriter.isAvailable():
            raise InputError(option, "MP4 needs ffmpeg, which is not installed; give a "
                             ".gif file name")
    if path.is_dir():
        raise InputError(option, f"{str(path)!r} is a folder; give a file name")
    if not path.parent.is_dir():
        raise InputError(option, f"no such folder: {str(path.parent)!r}")
    if not os.access(path.parent, os.W_OK | os.X_OK):
        raise InputError(option, f"cannot write in {str(path.parent)!r} (permission "
                         "denied)")
