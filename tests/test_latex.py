"""LaTeX: the printed form is pinned by golden files; the document compiles; export is
all-or-nothing. (Whether the formulas are *right* is verify's job, against the paper.)"""

from __future__ import annotations

import contextlib
import functools
import io
import json
import os
import re
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
    monkeypatch.setattr(latex, "has_pdflatex", lambda: True)  # as where it is installed
    with pytest.raises(RuntimeError):
        latex.write_export(tmp_path / "out", [derive("discs")], pdf=True)
    assert list(tmp_path.iterdir()) == []  # no folder, no staging left behind


def test_failed_export_keeps_the_previous_one_whole(tmp_path, monkeypatch):
    first = latex.write_export(tmp_path / "out", [derive("discs")])
    before = {p.name: p.read_text() for p in first}

    def broken(*args, **kwargs):
        raise RuntimeError("pdflatex failed on derivations.tex: ! Emergency stop")

    monkeypatch.setattr(latex, "compile_pdf", broken)
    monkeypatch.setattr(latex, "has_pdflatex", lambda: True)  # as where it is installed
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


# --- every shipped scene's LaTeX typesets, labels kept whole ---------------------------

ROOT = Path(__file__).resolve().parents[1]
SCENE_FILES = sorted((ROOT / "derivations").glob("*.toml"))


def _scene_labels(path: Path) -> set[str]:
    """The names a scene gives its bodies, contacts, joints and planes."""
    import tomllib

    data = tomllib.loads(path.read_text(encoding="utf-8"))
    tables = [t for key in ("bodies", "contacts", "joints", "planes", "pairs")
              for t in data.get(key, [])]
    found = {t["name"] for t in tables if "name" in t}
    return found | ({"contact"} if "contact" in data or "contacts" in data else set())


def _loose_subscripts(text: str) -> list[str]:
    """Every subscript's text once its upright (\\mathrm) parts and the comments are
    taken out."""
    text = re.sub(r"(?m)^%.*$", "", text)
    text = re.sub(r"\\mathrm\{(?:[^{}]|\\[{}_])*\}", "", text)
    return re.findall(r"_\{([^{}]*)\}", text) + re.findall(r"_([A-Za-z0-9]+)", text)


@functools.cache
def _derived(path: Path, *options: str) -> str:
    """What ``derive PATH OPTIONS`` prints: each shipped scene derived once for the
    tests of this file that read it."""
    from rigidimpact.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["derive", str(path), *options]) == 0
    return out.getvalue()


def _scene_latex(path: Path, capsys) -> str:
    return _derived(path, "--format", "latex")


def test_scene_names_keep_their_labels_whole(capsys):
    """A label (a body's, a contact's) is set upright, whole, after the component; a
    sign is a superscript: no fragment such as ``x^+_cue`` or ``n^cloth_object``."""
    for path in SCENE_FILES:
        text = _scene_latex(path, capsys)
        assert "^+_" not in text and "^{+}_" not in text, path.name
        assert not re.search(r"_\{[^{}]*\^", text), path.name  # a superscript in a subscript
        labels = {x for x in _scene_labels(path) if len(x) > 1}
        for sub in _loose_subscripts(text):
            assert not any(label in sub for label in labels), (path.name, sub)


def test_one_name_for_one_key_in_2d_and_3d():
    from rigidimpact.symbolic.notation import result_lhs

    assert result_lhs("cue.vx") == r"v_{x,\mathrm{cue}}^{+}"
    assert result_lhs("cue.vz") == r"v_{z,\mathrm{cue}}^{+}"
    assert result_lhs("cue.omega_x") == r"\omega_{x,\mathrm{cue}}^{+}"
    assert result_lhs("disc.omega") == r"\omega_{z,\mathrm{disc}}^{+}"
    assert result_lhs("cloth_object.normal_impulse") == r"P_{n,\mathrm{cloth\_object}}"


def test_the_laws_unknowns_are_the_results_names(capsys):
    """One notation from the laws to the results: every speed after that a scene's laws
    solve for is the left-hand side of one of its results."""
    from rigidimpact.symbolic.notation import result_lhs

    after = re.compile(r"(?:\\omega|v)_\{[xyz],\\mathrm\{[^{}]*\}\}\^\{\+\}")
    for path in SCENE_FILES:
        out = json.loads(_derived(path, "--json"))
        named = {result_lhs(key) for key in out["results"]}
        for eq in out["equations"]:
            assert set(after.findall(eq["latex"])) <= named, (path.name, eq["label"])


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed")
def test_every_scene_latex_compiles(tmp_path, capsys):
    parts = []
    for path in SCENE_FILES:
        body = _scene_latex(path, capsys)
        parts.append(f"\\section*{{{path.stem}}}\n{body}\n")
    tex = tmp_path / "scenes.tex"
    tex.write_text("\\documentclass{article}\n\\usepackage{amsmath}\n\\allowdisplaybreaks\n"
                   "\\begin{document}\n" + "".join(parts) + "\\end{document}\n",
                   encoding="utf-8")
    assert latex.compile_pdf(tex).read_bytes().startswith(b"%PDF")


# --- the document reads as lecture notes: every symbol typeset -------------------------

def _text_only(tex: str) -> str:
    """The document's running text: displays, inline mathematics, comments and
    environment names taken out."""
    tex = re.sub(r"(?s)\\begin\{(equation|gather)\*\}.*?\\end\{\1\*\}", "", tex)
    tex = re.sub(r"(?s)(?<!\\)\$.*?(?<!\\)\$", "", tex)
    tex = re.sub(r"\\(begin|end)\{[a-z]+\*?\}", "", tex)
    return re.sub(r"(?m)^%.*$", "", tex)


def _exported(tmp_path: Path, targets: list[str], pdf: bool) -> str:
    from rigidimpact.cli import main

    assert main(["export", "--out", str(tmp_path / "out"), *targets,
                 *(["--pdf"] if pdf else [])]) == 0
    return (tmp_path / "out" / "derivations.tex").read_text(encoding="utf-8")


def test_document_text_holds_no_code(tmp_path, capsys):
    """No raw ``*`` (code's product) nor escaped ``_`` (a symbol as text) in the running
    text of the document of every built-in problem and every shipped scene; each
    section prints a body's speed after in one notation, in its laws and results."""
    pdf = shutil.which("pdflatex") is not None
    tex = _exported(tmp_path, [*PROBLEMS, *map(str, SCENE_FILES)], pdf)
    capsys.readouterr()
    text = _text_only(tex)
    assert "*" not in text
    assert "\\_" not in text
    assert "^{(\\mathrm" not in tex  # the old results-only notation
    if pdf:
        assert (tmp_path / "out" / "derivations.pdf").read_bytes().startswith(b"%PDF")


def test_a_named_group_is_defined_before_a_result_uses_it(tmp_path, capsys):
    tex = _exported(tmp_path, ["two-body"], pdf=False)
    capsys.readouterr()
    solution = tex[tex.index("\\paragraph{Solution.}"):]
    defined = solution.index("J = ")
    used = min(m.start() for m in re.finditer(r"J\b(?! =)", solution))
    assert defined < used


def test_a_scene_setup_sets_its_values_as_mathematics(tmp_path, capsys):
    tex = _exported(tmp_path, [str(ROOT / "derivations" / "discs.toml")], pdf=False)
    capsys.readouterr()
    assert r"velocity $\left(v \cos{\left(\phi \right)}, v \sin{\left(\phi \right)}\right)$" \
        in tex


def test_pdf_without_pdflatex_writes_the_tex_and_says_so(tmp_path, monkeypatch, capsys):
    """Where pdflatex is missing, ``export --pdf`` writes the document all the same and
    says in one line what the PDF needs (as ``make run`` does)."""
    from rigidimpact.cli import main

    monkeypatch.setenv("PATH", str(tmp_path / "empty"))  # no pdflatex on this PATH
    assert latex.has_pdflatex() is False
    assert main(["export", "--out", str(tmp_path / "out"), "--pdf", "discs"]) == 0
    out, err = capsys.readouterr()
    assert (tmp_path / "out" / "derivations.tex").read_text().startswith("\\documentclass")
    assert not (tmp_path / "out" / "derivations.pdf").exists()
    assert "derivations.pdf" not in out
    assert len(err.strip().splitlines()) == 1
    assert "pdflatex" in err and "texlive-latex-base" in err
