"""Files and folders written whole or not at all, even when the process is killed.

A file is written to a hidden sibling and renamed over its target; a folder (an export)
is filled in a hidden staging sibling and swapped in with one atomic exchange of the two
names, so a reader sees the old export or the new one, never a mix. The hidden names
carry the writer's process id: what a killed run left behind is cleared by the next.

Examples
--------
>>> import tempfile
>>> root = Path(tempfile.mkdtemp())
>>> _ = write_file(root / "a.txt", lambda p: p.write_text("hello"))
>>> sorted(p.name for p in root.iterdir())
['a.txt']
"""

from __future__ import annotations

import ctypes
import errno
import os
import re
import shutil
from collections.abc import Callable, Iterable
from pathlib import Path

from rigidimpact.errors import InputError

__all__ = ["write_file", "replace_folder", "clear_stale", "MARKER"]

MARKER = ".rigidimpact-export"  # marks a folder that export owns and may replace whole
_HIDDEN = re.compile(r"^\.(?P<name>.+)\.(?:partial|staging|old)-(?P<pid>\d+)(?:\..*)?$")


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def clear_stale(folder: Path) -> list[Path]:
    """Remove what a killed writer left in `folder` (its hidden partial, staging and old
    copies whose process is gone); return what was removed."""
    removed: list[Path] = []
    if not folder.is_dir():
        return removed
    for entry in folder.iterdir():
        match = _HIDDEN.match(entry.name)
        if match is None or _alive(int(match["pid"])):
            continue
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            entry.unlink(missing_ok=True)
        removed.append(entry)
    return removed


def _writable_folder(folder: Path, option: str) -> None:
    if not folder.is_dir():
        raise InputError(option, f"no such folder: {str(folder)!r}")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(option, f"cannot write in {str(folder)!r} (permission denied)")


def write_file(path: Path, write: Callable[[Path], object], option: str = "--out") -> Path:
    """Write `path` through `write(temporary)` and one rename; nothing half-written remains.

    Raises
    ------
    InputError
        If `path` is a folder or its folder cannot be written.
    """
    path = Path(path)
    if path.is_dir():
        raise InputError(option, f"{str(path)!r} is a folder; give a file name")
    folder = path.parent
    _writable_folder(folder, option)
    clear_stale(folder)
    temporary = folder / f".{path.name}.partial-{os.getpid()}{path.suffix}"
    try:
        write(temporary)
        os.replace(temporary, path)
    except OSError as exc:
        raise InputError(option, f"cannot write {str(path)!r}: "
                         f"{exc.strerror or exc}") from None
    finally:
        temporary.unlink(missing_ok=True)
    return path


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one atomic step (Linux renameat2); False where unsupported."""
    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError):
        return False
    at_cwd, exchange = -100, 2
    if renameat2(at_cwd, os.fsencode(a), at_cwd, os.fsencode(b), exchange) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP):
        return False
    raise OSError(code, os.strerror(code), str(b))


def _owned(folder: Path, suffixes: Iterable[str]) -> bool:
    """Whether `folder` may be replaced whole: export wrote it, or it holds nothing else."""
    entries = list(folder.iterdir())
    if (folder / MARKER).exists() or not entries:
        return True
    allowed = tuple(suffixes)
    return all(e.is_file() and e.name.endswith(allowed) for e in entries)


def replace_folder(folder: Path, fill: Callable[[Path], list[str]],
                   owned_suffixes: Iterable[str] = (), option: str = "--out") -> list[Path]:
    """Fill a staging folder with `fill(staging)` (it returns the names written) and swap
    it in for `folder` in one step.

    A folder that exists must be one this function wrote (it carries ``MARKER``), empty,
    or hold only files ending in `owned_suffixes`; anything else is refused rather than
    replaced.

    Raises
    ------
    InputError
        If `folder` is a file, holds other files, or cannot be written.
    """
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise InputError(option, f"{str(folder)!r} is a file, not a folder")
    parent = folder.parent
    try:
        parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(option, f"cannot make {str(parent)!r}: {exc.strerror or exc}") \
            from None
    _writable_folder(parent, option)
    if folder.exists() and not _owned(folder, owned_suffixes):
        raise InputError(option, f"{str(folder)!r} holds files that export did not write; "
                         "choose a new or empty folder")
    clear_stale(parent)
    staging = parent / f".{folder.name}.staging-{os.getpid()}"
    shutil.rmtree(staging, ignore_errors=True)
    try:
        staging.mkdir()
        names = fill(staging)
        (staging / MARKER).write_text("written by rigidimpact export; replaced whole by "
                                      "the next export\n", encoding="utf-8")
        if not folder.exists():
            staging.rename(folder)
        elif not _exchange(staging, folder):
            old = parent / f".{folder.name}.old-{os.getpid()}"
            folder.rename(old)
            staging.rename(folder)
            shutil.rmtree(old, ignore_errors=True)
    except OSError as exc:
        raise InputError(option, f"cannot write {str(folder)!r}: {exc.strerror or exc}") \
            from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)  # after an exchange: the old export
    return [folder / name for name in names]
