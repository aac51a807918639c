"""Modules imported where they are first used, not where they are named.

``derive barbell`` and ``evaluate`` of a smooth scene never touch numpy, yet the modules
they load name it for the paths that do (the numeric rules, the floating complementarity
solvers). Such a module writes ::

    if TYPE_CHECKING:
        import numpy as np
    else:
        np = deferred("numpy")

and ``np.zeros`` imports numpy at that first call. After it, every name of the module is
an ordinary attribute of the stand-in (copied once), so a loop pays no more than with the
module itself.

A command is a short process, and :data:`SHORT_RUN_THRESHOLD` is the collector setting
it runs under (:func:`rigidimpact.__main__.run`).

>>> math_ = deferred("math")
>>> math_.sqrt(4.0), "sqrt" in vars(math_)
(2.0, True)
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any


class _Deferred(ModuleType):
    """A stand-in for a module, importing it at the first attribute asked of it."""

    def __getattr__(self, name: str) -> Any:  # called only for names not yet copied
        module = importlib.import_module(self.__name__)
        if "__file__" not in vars(self):
            vars(self).update(vars(module))
        value = getattr(module, name)  # a name the module makes on demand, too
        vars(self)[name] = value
        return value


def deferred(name: str) -> Any:
    """A stand-in for the module `name`, imported when first used (see above)."""
    return _Deferred(name)


# The cyclic collector's first generation for a process that is one command: SymPy
# builds and drops many small containers, and Python's default (a pass every 700 new
# ones) spends 5 to 10 per cent of `derive barbell` rescanning the young ones.
SHORT_RUN_THRESHOLD = 20_000
