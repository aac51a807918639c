"""Shared by every test, doctest and notebook check: figures do not outlive their test,
and the guide's pages run as a reader runs them."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pictures  # docs/_ext (pytest's pythonpath): the files the guide asks to save
import pytest

ROOT = Path(__file__).resolve().parent
GUIDE = ROOT / "docs" / "guide"


@pytest.fixture(autouse=True)
def _close_figures():
    """pyplot keeps every figure until it is closed; close them after each test."""
    yield
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:
        pyplot.close("all")


def _as_a_reader_has_it(folder: Path) -> None:
    """`folder` as a reader's: the shipped scenes under ``derivations/`` and each file a
    page of the guide asks the reader to save."""
    (folder / "derivations").symlink_to(ROOT / "derivations")
    for name in pictures.INPUTS:
        (folder / name).write_text(pictures.input_text(name))


@pytest.fixture
def reader_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A test run from a reader's folder (:func:`_as_a_reader_has_it`)."""
    _as_a_reader_has_it(tmp_path)
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture(autouse=True)
def _guide_in_a_folder_of_its_own(request: pytest.FixtureRequest):
    """A page of the guide runs from a reader's folder of its own, so the files it writes
    (figures, animations) land there and not in the clone. (Here rather than in a
    conftest.py of the guide's folder: a second module named conftest would shadow the
    tests' own, which their modules import by that name.)"""
    if GUIDE not in Path(request.node.path).parents:
        yield
        return
    folder = request.getfixturevalue("tmp_path")
    _as_a_reader_has_it(folder)
    before = Path.cwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(before)
