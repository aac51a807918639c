"""LaTeX: the printed form is pinned by golden files; the document compiles; export is
all-or-nothing. (Whether the formulas are *right* is verify's job, against the paper.)"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from rigidimpact.outputs import latex
from rigidimpact.paper.problems import PROBLEMS, derive

GOLDEN = Path(__file__).resolve().parent / "golden"
PINNED = ["barbell--v_fx.tex", "barbell--energy_loss_fraction.tex", "sticking--omega_z.tex",
          "discs--V_1fx.tex"]


@pytest.mark.parametrize("name", PINNED)
def test_fragments_match_golden_files(name):
    # refresh after a deliberate change: UPDATE_GOLDEN=1 make test, then read the diff
    problem = name.split("--")[0]
    text = latex.fragments(derive(problem))[name]
    golden = GOLDEN / name
    if os.environ.get("UPDATE_GOLDEN"):
        golden.write_text(text, encoding="utf-8")
    assert text == golden.read_text(encoding="utf-8")


def test_fragments_use_the_paper_notation():
    text = latex.fragments(derive("barbell"))["barbell--omega_z.tex"]
    assert r"\omega_{z} =" in text and r"v_{ix}" in text and r"\theta" in text


def test_export_writes_one_fragment_per_result_and_a_document(tmp_path):
    derivations = [derive(n) for n in PROBLEMS]
    written = latex.write_export(tmp_path, derivations)
    names = {p.name for p in written}
    assert "derivations.tex" in names
    assert len(names) == 1 + sum(len(d.results) for d in derivations)
    assert not [p for p in tmp_path.parent.iterdir() if p.name.startswith(f".{tmp_path.name}.")]


def test_failed_export_leaves_nothing_behind(tmp_path, monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("pdflatex failed on derivations.tex: ! Emergency stop")

    monkeypatch.setattr(latex, "compile_pdf", broken)
    with pytest.raises(RuntimeError):
        latex.write_export(tmp_path / "out", [derive("discs")], pdf=True)
    assert list(tmp_path.iterdir()) == []  # no folder, no staging left behind


def test_failed_export_keeps_the_previous_one_whole(tmp_path, monkeypatch):
    first = latex.write_export(tmp_path / "out", [derive("discs")])
    before = {p.name: p.read_text() for p in first}

    def broken(*args, **kwargs):
        raise RuntimeError("pdflatex failed on derivations.tex: ! Emergency stop")

    monkeypatch.setattr(latex, "compile_pdf", broken)
    with pytest.raises(RuntimeError):
        latex.write_export(tmp_path / "out", [derive("barbell")], pdf=True)
    assert {p.name: p.read_text() for p in first} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed")
def test_document_compiles_with_pdflatex(tmp_path):
    from rigidimpact.verify import run_checks

    derivations = [derive(n) for n in PROBLEMS]
    written = latex.write_export(tmp_path, derivations, run_checks(), pdf=True)
    pdf = tmp_path / "derivations.pdf"
    assert pdf in written
    assert pdf.read_bytes().startswith(b"%PDF")
