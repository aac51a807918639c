"""A cache of what ``derive`` prints, so that asking again for a derivation already made
answers at once, without loading SymPy.

A derivation is a pure function of its input: the command's arguments, the scene file's
bytes (for a scene), the package's own source and the SymPy it runs on. The cache keys
each answer by a hash of all four, so a change to any of them (an edited scene, a new
version of rigidimpact or of SymPy) derives again. Only a successful run is kept
(status 0), with its standard output and error; one that ran on Dask workers, or a
scene with a ``[random]`` table (whose sampling shows its progress as it runs), is not.

Where: ``$RIGIDIMPACT_CACHE`` if set (``off`` turns the cache off), else
``$XDG_CACHE_HOME/rigidimpact``, else ``~/.cache/rigidimpact``. Each entry is one small
JSON file written atomically; an entry that cannot be read (or a folder that cannot be
written) is passed over, never trusted and never an error.

Examples
--------
>>> import os
>>> kept = os.environ.get("RIGIDIMPACT_CACHE")
>>> os.environ["RIGIDIMPACT_CACHE"] = "off"
>>> folder() is None
True
>>> os.environ["RIGIDIMPACT_CACHE"] = "/tmp/rigidimpact-cache"
>>> folder().name
'rigidimpact-cache'
>>> _ = os.environ.pop("RIGIDIMPACT_CACHE") if kept is None else os.environ.update(
...     RIGIDIMPACT_CACHE=kept)
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import tempfile
from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path

__all__ = ["folder", "key", "replay", "store", "OFF"]

OFF = ("off", "0", "no", "false")
PACKAGE = Path(__file__).resolve().parents[1]
# the line that says how long the derivation took: on replay it says when
TIMING = re.compile(r"^\((\d+(?:\.\d+)?) s\)$", re.MULTILINE)


def folder() -> Path | None:
    """The cache's folder, or None where the cache is off."""
    chosen = os.environ.get("RIGIDIMPACT_CACHE")
    if chosen is not None:
        return None if chosen.strip().lower() in OFF or not chosen.strip() else \
            Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "rigidimpact"


@lru_cache(maxsize=1)
def _source() -> str:
    """A hash of the package's own source (every module, in a fixed order) and of the
    SymPy version beside it."""
    digest = hashlib.sha256()
    for path in sorted(PACKAGE.rglob("*.py")):
        digest.update(str(path.relative_to(PACKAGE)).encode())
        digest.update(path.read_bytes())
    digest.update(_sympy_version().encode())
    return digest.hexdigest()


def _sympy_version() -> str:
    """SymPy's version, read from its metadata (importing it is what the cache spares)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("sympy")
    except PackageNotFoundError:
        return "none"


def key(argv: Sequence[str], target: str) -> str | None:
    """The entry's name for a run of `argv` on `target` (a built-in problem's name or a
    scene file), or None where the file cannot be read (the run then says why)."""
    digest = hashlib.sha256(_source().encode())
    digest.update(json.dumps(list(argv)).encode())
    path = Path(target)
    if path.suffix == ".toml" or path.is_file():
        try:
            data = path.read_bytes()
        except OSError:
            return None
        if b"[random]" in data:  # a sampled run shows its progress as it goes
            return None
        digest.update(data)
    return digest.hexdigest()


def replay(name: str) -> tuple[str, str] | None:
    """The kept standard output and error of entry `name`, or None (not kept, or not
    readable as kept). The timing line says that the answer was read from the cache."""
    place = folder()
    if place is None:
        return None
    try:
        data = json.loads((place / f"{name}.json").read_text(encoding="utf-8"))
        out, err = data["stdout"], data["stderr"]
        if not isinstance(out, str) or not isinstance(err, str):
            return None
    except (OSError, ValueError, KeyError, TypeError):
        return None
    return TIMING.sub(r"(\1 s when derived; read from the cache)", out), err


def store(name: str, out: str, err: str) -> None:
    """Keep a successful run's output under `name`, atomically (a temporary file renamed
    into place); a folder that cannot be written is passed over."""
    place = folder()
    if place is None:
        return
    try:
        place.mkdir(parents=True, exist_ok=True)
        handle, temporary = tempfile.mkstemp(dir=place, suffix=".part")
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            json.dump({"stdout": out, "stderr": err}, stream)
        os.replace(temporary, place / f"{name}.json")
    except OSError:
        return
