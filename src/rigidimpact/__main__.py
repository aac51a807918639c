"""``python -m rigidimpact`` and the ``rigidimpact`` console script: the command line as a
process of its own (:func:`run`)."""

from __future__ import annotations

import gc
import sys
from collections.abc import Sequence
from typing import NoReturn

from rigidimpact.cli import main
from rigidimpact.lazy import SHORT_RUN_THRESHOLD

__all__ = ["run"]


def run(argv: Sequence[str] | None = None) -> NoReturn:
    """The ``rigidimpact`` command as a process of its own: :func:`main`, then exit.

    A command is a short-lived process, so the cyclic collector runs less often while
    it works, and at exit what it built is frozen (:func:`gc.freeze`) rather than
    searched for cycles once more: the process's memory goes back to the system whole.
    Nothing is lost by that: exit handlers still run, and every file the command writes
    is whole and closed before :func:`main` returns (:mod:`rigidimpact.outputs.atomic`).
    :func:`rigidimpact.cli.main` called from Python (a notebook, the tests) leaves the
    collector as it was.
    """
    gc.set_threshold(SHORT_RUN_THRESHOLD, *gc.get_threshold()[1:])
    status = main(argv)
    gc.freeze()
    sys.exit(status)


if __name__ == "__main__":
    run()
