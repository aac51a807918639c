r"""The paper's symbols, made once with their assumptions, and their LaTeX names.

Every other module takes its symbols from here: a SymPy symbol with assumptions is
not equal to a bare one of the same name, so making them in one place keeps the
algebra from silently splitting into two variables.

Examples
--------
>>> from rigidimpact.symbolic.notation import symbol, latex_name
>>> symbol("M").is_positive
True
>>> latex_name(symbol("v_ix"))
'v_{ix}'
>>> latex_name(symbol("omega_1iz"))
'\\omega_{1iz}'
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import sympy as sp

__all__ = ["SYMBOLS", "symbol", "make_symbol", "labelled", "latex_name", "latex_names", "GREEK",
           "PRINTER_SETTINGS", "to_latex", "result_lhs", "escape_text", "aligned", "COMPONENTS",
           "speed_names", "Given"]

GREEK = frozenset(
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi pi rho sigma "
    "tau upsilon phi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Phi Psi Omega".split()
)

# name -> assumptions; the problem symbols of docs/scenes.md plus a few generic names scenes use.
_ASSUMPTIONS: dict[str, dict[str, bool]] = {
    # section 1: ball and barbell
    "m": {"positive": True},
    "M": {"positive": True},
    "L": {"positive": True},
    "theta": {"real": True},
    "e": {"nonnegative": True},
    "v_ix": {"positive": True},
    # results named by the paper
    "f": {"positive": True},
    "h": {"positive": True},
    "J": {"real": True},
    "v_fx": {"real": True},
    "v_fy": {"real": True},
    "V_x": {"real": True},
    "V_y": {"real": True},
    "omega_z": {"real": True},
    "u_x": {"real": True},
    "u_y": {"real": True},
    # after the impact (section 2): the angle the barbell has turned through
    "tau": {"nonnegative": True},
    # section 3: two extended bodies
    "m_1": {"positive": True},
    "m_2": {"positive": True},
    "I_1": {"positive": True},
    "I_2": {"positive": True},
    "R_1x": {"real": True},
    "R_1y": {"real": True},
    "R_2x": {"real": True},
    "R_2y": {"real": True},
    "V_1ix": {"real": True},
    "V_1iy": {"real": True},
    "omega_1iz": {"real": True},
    "V_2ix": {"real": True},
    "V_2iy": {"real": True},
    "omega_2iz": {"real": True},
    "V_1fx": {"real": True},
    "V_1fy": {"real": True},
    "omega_1fz": {"real": True},
    "V_2fx": {"real": True},
    "V_2fy": {"real": True},
    "omega_2fz": {"real": True},
    # generic names a scene may use without declaring them
    "r": {"positive": True},
    "r_1": {"positive": True},
    "r_2": {"positive": True},
    "l": {"positive": True},
    "d": {"real": True},
    "b": {"real": True},
    "I": {"positive": True},
    "v": {"real": True},
    "u": {"real": True},
    "w": {"real": True},
    "omega": {"real": True},
    "phi": {"real": True},
    "alpha": {"real": True},
    "psi": {"real": True},
    "mu": {"nonnegative": True},  # Coulomb's friction coefficient
    "beta": {"real": True},  # the tangential restitution coefficient, in [-1, 1]
}

SYMBOLS: Mapping[str, sp.Symbol] = MappingProxyType(
    {name: sp.Symbol(name, **assumptions) for name, assumptions in _ASSUMPTIONS.items()}
)


def symbol(name: str) -> sp.Symbol:
    """Return the project's symbol called `name`, with its assumptions.

    Parameters
    ----------
    name : str
        A name from :data:`SYMBOLS`.

    Returns
    -------
    sympy.Symbol

    Raises
    ------
    KeyError
        If no symbol of that name is known.

    Examples
    --------
    >>> symbol("e").is_nonnegative
    True
    """
    try:
        return SYMBOLS[name]
    except KeyError:
        raise KeyError(f"unknown symbol {name!r}") from None


def make_symbol(name: str, **assumptions: bool) -> sp.Symbol:
    """Return the known symbol `name`, or a new one with the given assumptions.

    A scene may declare its own symbols; a declaration of a known name must not
    contradict the project's assumptions, or the two would be different symbols.

    Examples
    --------
    >>> make_symbol("k", positive=True).is_positive
    True
    >>> make_symbol("m") is symbol("m")
    True
    """
    if name in SYMBOLS and (not assumptions or assumptions == _ASSUMPTIONS[name]):
        return SYMBOLS[name]
    if name in SYMBOLS:
        raise ValueError(
            f"symbol {name!r} is already defined with {_ASSUMPTIONS[name]}; "
            f"redeclaring it with {assumptions} would make a second, unequal symbol"
        )
    return sp.Symbol(name, **assumptions)


def labelled(head: str, sub: str, label: str, after: bool = False,
             **assumptions: bool) -> sp.Symbol:
    r"""A quantity of one body, contact or joint: ``head`` with subscript ``sub``, the
    label, and a ``+`` for a value after the impact. Every such symbol in 2-D and 3-D
    is made here, so one name typesets one way.

    Its name is ``head_sub^+_label`` after the impact and ``head_sub^label`` otherwise;
    :func:`latex_name` reads it back as ``head_{sub,\mathrm{label}}^{+}``.

    Examples
    --------
    >>> labelled("v", "x", "cue", after=True)
    v_x^+_cue
    >>> latex_name(labelled("P", "n", "cloth_object"))
    'P_{n,\\mathrm{cloth\\_object}}'
    """
    return sp.Symbol(f"{head}_{sub}" + (f"^+_{label}" if after else f"^{label}"),
                     **assumptions)


def speed_names(label: str) -> tuple[str, str, str]:
    """The names of a planar body's (vx, vy, omega) after the impact, by its label.

    Examples
    --------
    >>> speed_names("ball")
    ('v_x^+_ball', 'v_y^+_ball', 'omega_z^+_ball')
    """
    vx, vy, omega = (labelled(*COMPONENTS[k][:2], label, after=True).name
                     for k in ("vx", "vy", "omega"))
    return vx, vy, omega


def _plain_name(name: str) -> tuple[str, str]:
    """``V_1ix`` -> (``V``, ``1ix``) in LaTeX: the head and its subscript. A subscript
    that is a word (``e_balls``, ``mu_cloth_object``) is set upright, as a label is;
    one of letters that each stand for something (``ix``, ``1fz``, ``kix``: body k,
    initial, along x) is not."""
    head, _, tail = name.partition("_")
    head_tex = "\\" + head if head in GREEK else head
    if tail in GREEK:
        return head_tex, "\\" + tail
    if "_" in tail or (len(tail) > 2 and tail.isalpha()
                       and not re.fullmatch(r"[A-Za-z]?[if][xyz]", tail)):
        return head_tex, rf"\mathrm{{{escape_text(tail)}}}"
    return head_tex, tail


def latex_name(sym: sp.Symbol) -> str:
    r"""LaTeX for a symbol name in the paper's style: ``V_1ix`` -> ``V_{1ix}``; a name
    from :func:`labelled` sets its label upright after the subscript, and its sign as a
    superscript: ``v_x^+_cue`` -> ``v_{x,\mathrm{cue}}^{+}``.

    Examples
    --------
    >>> latex_name(symbol("theta"))
    '\\theta'
    >>> latex_name(symbol("R_2y"))
    'R_{2y}'
    >>> latex_name(sp.Symbol("omega_z^+_cue"))
    '\\omega_{z,\\mathrm{cue}}^{+}'
    >>> latex_name(sp.Symbol("u1^+"))
    'u_{1}^{+}'
    """
    stem, hat, rest = sym.name.partition("^")
    sign = ""
    if hat and rest[:1] in ("+", "-"):
        sign, rest = rest[0], rest[1:].removeprefix("_")
    head, sub = _plain_name(stem)
    if not sub and not hat:
        return head
    if not sub:  # a mechanics speed ``u1``: its digits are its subscript
        found = re.fullmatch(r"([A-Za-z]+)(\d+)", stem)
        if found:
            head, sub = _plain_name(found[1])[0], found[2]
    parts = [p for p in (sub, rf"\mathrm{{{escape_text(rest)}}}" if rest else "") if p]
    text = f"{head}_{{{','.join(parts)}}}" if parts else head
    return text + (f"^{{{sign}}}" if sign else "")


def latex_names(expr: sp.Basic) -> dict[sp.Symbol, str]:
    """Map every free symbol of `expr` to its LaTeX name.

    Examples
    --------
    >>> sorted(latex_names(symbol("m") * symbol("v_ix")).values())
    ['m', 'v_{ix}']
    """
    return {s: latex_name(s) for s in expr.free_symbols if isinstance(s, sp.Symbol)}


# fixed printer settings: changing any of these changes every golden file
PRINTER_SETTINGS = {
    "mul_symbol": None,
    "fold_short_frac": False,
    "inv_trig_style": "abbreviated",
    "long_frac_ratio": None,
}

_LHS = {
    "energy_loss_fraction": r"\frac{\Delta K_{\mathrm{lost}}}{K_i}",
    "impulse": "J",
    "impulse_t": "J_t",
}
# a result key's component -> the symbol, its subscript, and whether it is a value after
# the impact; the equations' unknowns are made from the same table (labelled), so a
# key prints the same in the laws and in the results, in 2-D and 3-D
COMPONENTS: Mapping[str, tuple[str, str, bool]] = MappingProxyType({
    "vx": ("v", "x", True), "vy": ("v", "y", True), "vz": ("v", "z", True),
    "omega": ("omega", "z", True), "omega_x": ("omega", "x", True),
    "omega_y": ("omega", "y", True), "omega_z": ("omega", "z", True),
    "normal_impulse": ("P", "n", False), "tangential_impulse": ("P", "t", False),
    "tangential_impulse_1": ("P", "t1", False), "tangential_impulse_2": ("P", "t2", False),
    "impulse_x": ("Q", "x", False), "impulse_y": ("Q", "y", False),
    "impulse_z": ("Q", "z", False), "moment_1": ("M", "1", False),
    "moment_2": ("M", "2", False), "pivot_impulse_x": ("R", "x", False),
    "pivot_impulse_y": ("R", "y", False),
})


def to_latex(expr: sp.Basic) -> str:
    """LaTeX for an expression, symbols in the paper's notation.

    Examples
    --------
    >>> from rigidimpact.symbolic.notation import symbol
    >>> to_latex(symbol("omega_z") * symbol("L"))
    'L \\\\omega_{z}'
    """
    return sp.latex(expr, symbol_names=latex_names(expr), **PRINTER_SETTINGS)


def result_lhs(key: str) -> str:
    r"""The left-hand side for a result key: ``V_1fx`` -> ``V_{1fx}``, ``ball.vx`` ->
    ``v_{x,\mathrm{ball}}^{+}`` (the same symbol the laws solve for).

    Examples
    --------
    >>> result_lhs("ball.omega")
    '\\omega_{z,\\mathrm{ball}}^{+}'
    >>> result_lhs("v_fx")
    'v_{fx}'
    """
    if key in _LHS:
        return _LHS[key]
    label, dot, component = key.partition(".")
    if dot:
        head, sub, after = COMPONENTS.get(component, (component, "", False))
        return latex_name(labelled(head, sub, label, after)) if sub else \
            rf"{latex_name(sp.Symbol(head))}_{{\mathrm{{{escape_text(label)}}}}}"
    if key in SYMBOLS:
        return latex_name(SYMBOLS[key])
    return latex_name(sp.Symbol(key))


def escape_text(text: str, angles: bool = True) -> str:
    """Text made safe inside LaTeX (its special characters escaped); with `angles`, < and
    > too, which pdflatex's default text font sets as other glyphs (Jupyter's MathJax
    sets them as they are, and shows the escapes literally: its displays pass False).

    Examples
    --------
    >>> escape_text("a_b")
    'a\\\\_b'
    >>> escape_text("x >= 0"), escape_text("x >= 0", angles=False)
    ('x \\\\textgreater{}= 0', 'x >= 0')
    """
    for char, repl in (("\\", r"\textbackslash{}"), ("&", r"\&"), ("%", r"\%"),
                       ("$", r"\$"), ("#", r"\#"), ("_", r"\_"), ("{", r"\{"),
                       ("}", r"\}"), ("~", r"\textasciitilde{}"), ("^", r"\^{}"),
                       *((("<", r"\textless{}"), (">", r"\textgreater{}")) if angles
                         else ())):
        text = text.replace(char, repl)
    return text


class Given(str):
    """One line of a problem's givens: words with values in them. It reads as its text
    (values in SymPy's plain form); the LaTeX document sets each value as mathematics.

    A tuple is a vector in parentheses, a list one in brackets.

    Examples
    --------
    >>> line = Given("ball: mass {}, velocity {}", sp.Symbol("m"), (sp.Symbol("v"), 0))
    >>> line
    'ball: mass m, velocity (v, 0)'
    >>> line.parts
    ('ball: mass ', m, ', velocity ', (v, 0), '')
    >>> (line + Given(", spin {}", 0)).values
    (m, (v, 0), 0)
    """

    template: str
    values: tuple[Any, ...]

    def __new__(cls, template: str, *values: Any) -> Given:
        line = super().__new__(cls, template.format(*(_plain(v) for v in values)))
        line.template, line.values = template, values
        return line

    def __add__(self, other: str) -> Given:  # type: ignore[override]
        if isinstance(other, Given):
            return Given(self.template + other.template, *self.values, *other.values)
        return Given(self.template + other.replace("{", "{{").replace("}", "}}"),
                     *self.values)

    @property
    def parts(self) -> tuple[Any, ...]:
        """Words and values in turn: text, value, text, ..., text."""
        words = self.template.split("{}")
        out: list[Any] = [words[0]]
        for value, text in zip(self.values, words[1:], strict=True):
            out += [value, text]
        return tuple(out)


def _plain(value: Any) -> str:
    """A value as the text line shows it."""
    if isinstance(value, tuple):
        return "(" + ", ".join(_plain(v) for v in value) + ")"
    if isinstance(value, list):
        return "[" + ", ".join(_plain(v) for v in value) + "]"
    return str(value)



def aligned(rows: list[tuple[str, str, str]]) -> str:
    r"""Display math for Jupyter: one ``lhs = rhs`` per row with a note, aligned at ``=``.

    Examples
    --------
    >>> print(aligned([("x", "1", "a note"), ("y", "2", "")]))
    $$\begin{aligned} x &= 1 && \text{a note} \\ y &= 2 \end{aligned}$$
    """
    lines = [rf"{lhs} &= {rhs}" + (rf" && \text{{{escape_text(note, angles=False)}}}"
                                   if note else "")
             for lhs, rhs, note in rows]
    return r"$$\begin{aligned} " + r" \\ ".join(lines) + r" \end{aligned}$$"
