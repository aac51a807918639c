"""The guide's pages run as a reader runs them: from a folder of their own that holds the
shipped scenes under ``derivations/``, so the files a page writes (figures, animations,
scenes of one's own) land there and not in the clone."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# this file holds no doctests: not collected as a module (--doctest-modules), since it
# would be imported as `conftest` beside tests/conftest.py when both folders are asked
collect_ignore = ["conftest.py"]


@pytest.fixture(autouse=True)
def _in_a_folder_of_its_own(tmp_path: Path):
    (tmp_path / "derivations").symlink_to(ROOT / "derivations")
    before = Path.cwd()
    os.chdir(tmp_path)
    try:
        yield
    finally:
        os.chdir(before)
