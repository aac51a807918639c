"""LaTeX in the paper's notation: one fragment per result, and a whole document.

All LaTeX goes through :func:`to_latex`, whose printer settings are fixed here, so a
change in the printed form shows up as a diff in the golden files of the tests.

Examples
--------
>>> from rigidimpact.symbolic.notation import symbol
>>> to_latex(symbol("m") * symbol("v_ix") / (2 * symbol("M") + symbol("m")))
'\\\\frac{m v_{ix}}{2 M + m}'
>>> result_lhs("energy_loss_fraction")
'\\\\frac{\\\\Delta K_{\\\\mathrm{lost}}}{K_i}'
"""

from __future__ import annotations

import re
import shutil
import subprocess
from collections.abc import Iterable, Sequence
from pathlib import Path

import sympy as sp

from rigidimpact.laws.law import Equation
from rigidimpact.outputs.atomic import replace_folder
from rigidimpact.solve.derivation import Derivation
from rigidimpact.symbolic.notation import (
    PRINTER_SETTINGS,
    SYMBOLS,
    Given,
    escape_text,
    latex_name,
    result_lhs,
    to_latex,
)

__all__ = ["to_latex", "result_lhs", "equation_latex", "fragment", "fragments", "document",
           "write_export", "PRINTER_SETTINGS"]

def equation_latex(equation: Equation) -> str:
    """``lhs = rhs`` with the paper's equation number as a tag.

    Examples
    --------
    >>> from rigidimpact.symbolic.notation import symbol
    >>> equation_latex(Equation("x", "(4)", symbol("V_x"), 0))
    'V_{x} = 0 \\\\tag*{(4)}'
    """
    tag = rf" \tag*{{{equation.paper}}}" if equation.paper else ""
    return f"{to_latex(equation.lhs)} = {to_latex(equation.rhs)}{tag}"


def fragment(derivation: Derivation, key: str) -> str:
    """One result as a LaTeX ``equation`` ready to paste.

    Examples
    --------
    >>> from rigidimpact.paper.problems import derive
    >>> print(fragment(derive("discs"), "V_1fx"))  # doctest: +NORMALIZE_WHITESPACE
    % rigidimpact: discs, result V_1fx
    \\begin{equation}
      V_{1fx} = \\frac{V_{1ix} \\left(1 - e\\right)}{2} + \\frac{V_{2ix} \\left(e + 1\\right)}{2}
    \\end{equation}
    <BLANKLINE>
    """
    body = f"{result_lhs(key)} = {to_latex(derivation.results[key])}"
    if key in derivation.named:
        body += f" = {to_latex(derivation.named[key])}"
    return (f"% rigidimpact: {derivation.problem}, result {key}\n"
            f"\\begin{{equation}}\n  {body}\n\\end{{equation}}\n")


def fragments(derivation: Derivation) -> dict[str, str]:
    """File name -> fragment for every result of a derivation."""
    safe = re.sub(r"[^A-Za-z0-9]+", "-", derivation.problem).strip("-")
    return {f"{safe}--{key.replace('.', '-')}.tex": fragment(derivation, key)
            for key in derivation.results}


def _prose(text: str) -> str:
    """Plain text with the problem's symbol names set as mathematics (a name with an
    underscore upright, as its label in the formulas); a
    :class:`~rigidimpact.solve.derivation.Given` line's values are typeset whole."""
    if isinstance(text, Given):
        return "".join(_math(part) if k % 2 else _prose(str(part))
                       for k, part in enumerate(text.parts))
    out = []
    for token in re.split(r"(\w+|->)", text):
        if token == "->":
            out.append("$\\to$")
        elif "_" in token and token not in SYMBOLS:  # a name, set as the formulas set it
            out.append(f"$\\mathrm{{{escape_text(token)}}}$")
        elif token in SYMBOLS and token not in ("a", "b", "d", "l"):
            out.append(f"${latex_name(SYMBOLS[token])}$")
        else:
            out.append(escape_text(token))
    return "".join(out)


def _math(value: object) -> str:
    """A given value as inline mathematics: a tuple in parentheses, a list in brackets."""
    if isinstance(value, (tuple, list)):
        left, right = ("(", ")") if isinstance(value, tuple) else ("[", "]")
        inner = ", ".join(to_latex(sp.sympify(v)) for v in value)
        return f"$\\left{left}{inner}\\right{right}$"
    return f"${to_latex(sp.sympify(value))}$"


def _display(lines: Sequence[str]) -> str:
    rows = " \\\\\n".join(f"  {line}" for line in lines)
    return f"\\begin{{gather*}}\n{rows}\n\\end{{gather*}}\n"


def _section(derivation: Derivation, checks: Iterable) -> str:
    parts = [f"\\section{{{_prose(derivation.title)}}}\n",
             "\\paragraph{Setup.}\n\\begin{itemize}\n"
             + "".join(f"  \\item {_prose(line)}\n" for line in derivation.setup)
             + "\\end{itemize}\n",
             "\\paragraph{Laws.} Each equation is a conservation or contact law written for "
             "these bodies; the tag is its number in the paper.\n"]
    for eq in derivation.equations:
        parts.append(f"\\noindent {_prose(eq.label)}:\n"
                     f"\\begin{{equation*}}\n  {equation_latex(eq)}\n\\end{{equation*}}\n")
    unknowns = ", ".join(f"${to_latex(u)}$" for u in derivation.unknowns)
    defined = derivation.definitions.keys() - derivation.results.keys()
    parts.append(f"\\paragraph{{Solution.}} The laws are linear in {unknowns}; solving them "
                 "and putting each result over one denominator gives"
                 + (" the named group\n" if defined else "\n"))
    if defined:  # a named group is defined before a result uses it
        parts.append(_display([f"{latex_name(sp.Symbol(k))} = "
                               f"{to_latex(derivation.definitions[k])}"
                               for k in derivation.definitions if k in defined])
                     + "and through it the results\n")
    lines = []
    for key, value in derivation.results.items():
        shown = derivation.named.get(key)
        if shown is not None and (defined or sp.count_ops(value) > 40):
            lines.append(f"{result_lhs(key)} = {to_latex(shown)}")
        else:
            lines.append(f"{result_lhs(key)} = {to_latex(value)}")
    parts.append(_display(lines))
    shorter = [k for k in derivation.named if k in derivation.results and not defined]
    if shorter:  # a named group that is itself a result: the results again, through it
        parts.append("or, through "
                     + ", ".join(f"${latex_name(sp.Symbol(k))}$"
                                 for k in derivation.definitions)
                     + ",\n" + _display([f"{result_lhs(k)} = {to_latex(derivation.named[k])}"
                                         for k in shorter]))
    rows = [c for c in checks if c.id.split(".")[0] == derivation.problem]
    if rows:
        parts.append("\\paragraph{Checked against the paper.}\n\\begin{tabular}{lll}\n"
                     "check & paper & status \\\\ \\hline\n"
                     + "".join(f"{escape_text(c.id)} & {escape_text(c.paper)} & {c.status} \\\\\n"
                               for c in rows)
                     + "\\end{tabular}\n")
    return "\n".join(parts)


def document(derivations: Sequence[Derivation], checks: Iterable = ()) -> str:
    """A whole LaTeX document walking each derivation from its laws to its results.

    Examples
    --------
    >>> from rigidimpact.paper.problems import derive
    >>> text = document([derive("discs")])
    >>> text.startswith("\\\\documentclass") and text.rstrip().endswith("\\\\end{document}")
    True
    """
    checks = list(checks)
    body = "\n".join(_section(d, checks) for d in derivations)
    return (
        "\\documentclass[11pt]{article}\n"
        "\\usepackage[margin=2cm]{geometry}\n"
        "\\usepackage{amsmath}\n"
        "\\allowdisplaybreaks\n"
        "\\title{Impulsive collisions of rigid bodies: derivations}\n"
        "\\author{rigidimpact}\n"
        "\\date{}\n"
        "\\begin{document}\n"
        "\\maketitle\n"
        "\\noindent Each problem below is built from rigid-body primitives, its conservation "
        "and contact laws are solved exactly, and the results are compared with C.~E.~Mungan, "
        "\\emph{Collision of a ball with a barbell and related impulse problems}, "
        "Eur.\\ J.\\ Phys.\\ \\textbf{28} (2007) 563--568. Equation tags are the paper's "
        "numbers.\n\n"
        f"{body}\n"
        "\\end{document}\n"
    )


def write_export(out_dir: Path, derivations: Sequence[Derivation], checks: Iterable = (),
                 pdf: bool = False) -> list[Path]:
    """Write every fragment and ``derivations.tex`` (and ``.pdf``) as the folder `out_dir`.

    With `pdf` the document is compiled where ``pdflatex`` is installed
    (:func:`has_pdflatex`); where it is not, the ``.tex`` is written all the same.

    Everything is rendered (and, with `pdf`, compiled) in a staging folder beside
    `out_dir`, which is then swapped in with one atomic rename: a reader sees the old
    export or the new one, never a mix, also when the process is killed (see
    :mod:`rigidimpact.outputs.atomic`). An existing `out_dir` must be an earlier export (or
    empty, or hold only LaTeX output); anything else is refused, not replaced.

    Returns
    -------
    list of Path
        The files written.
    """
    files: dict[str, str] = {}
    for derivation in derivations:
        files.update(fragments(derivation))
    files["derivations.tex"] = document(derivations, checks)

    def fill(staging: Path) -> list[str]:
        for name, text in files.items():
            (staging / name).write_text(text, encoding="utf-8")
        names = list(files)
        if pdf and has_pdflatex():
            compile_pdf(staging / "derivations.tex")
            names.append("derivations.pdf")
            for leftover in ("derivations.aux", "derivations.log", "derivations.out"):
                (staging / leftover).unlink(missing_ok=True)
        return names

    return replace_folder(Path(out_dir), fill, LATEX_OUTPUT)


LATEX_OUTPUT = (".tex", ".pdf", ".aux", ".log", ".out")  # what export writes
PDFLATEX_PACKAGE = "texlive-latex-base"  # the Debian package that gives pdflatex


def has_pdflatex() -> bool:
    """Whether ``pdflatex`` is on the PATH (without it `write_export` writes the
    ``.tex`` alone)."""
    return shutil.which("pdflatex") is not None


def compile_pdf(tex: Path) -> Path:
    """Run pdflatex twice on `tex` in its folder; raise RuntimeError if it fails."""
    if not has_pdflatex():
        raise RuntimeError(f"pdflatex is not installed (Debian: {PDFLATEX_PACKAGE})")
    for _ in range(2):
        run = subprocess.run(
            ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", tex.name],
            cwd=tex.parent, capture_output=True, text=True, timeout=120, check=False)
        if run.returncode != 0:
            tail = [line for line in run.stdout.splitlines() if line.startswith("!")]
            raise RuntimeError(f"pdflatex failed on {tex.name}: "
                               f"{tail[0] if tail else 'see its log'}")
    return tex.with_suffix(".pdf")
