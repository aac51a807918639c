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

from collections.abc import Mapping
from types import MappingProxyType

import sympy as sp

__all__ = ["SYMBOLS", "symbol", "make_symbol", "latex_name", "latex_names", "GREEK",
           "PRINTER_SETTINGS", "to_latex", "result_lhs", "escape_text", "aligned"]

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


def latex_name(sym: sp.Symbol) -> str:
    r"""LaTeX for a symbol name in the paper's style: ``V_1ix`` -> ``V_{1ix}``.

    Examples
    --------
    >>> latex_name(symbol("theta"))
    '\\theta'
    >>> latex_name(symbol("R_2y"))
    'R_{2y}'
    """
    head, _, tail = sym.name.partition("_")
    head_tex = "\\" + head if head in GREEK else head
    if not tail:
        return head_tex
    tail_tex = "\\" + tail if tail in GREEK else tail
    return f"{head_tex}_{{{tail_tex}}}"


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
_COMPONENT = {"vx": "V_x", "vy": "V_y", "omega": r"\omega", "normal_impulse": "P_n",
              "tangential_impulse": "P_t"}


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
    """The left-hand side for a result key: ``V_1fx`` -> ``V_{1fx}``, ``ball.vx`` ->
    ``V_x^{(\\mathrm{ball})}``.

    Examples
    --------
    >>> result_lhs("ball.omega")
    '\\\\omega^{(\\\\mathrm{ball})}'
    >>> result_lhs("v_fx")
    'v_{fx}'
    """
    if key in _LHS:
        return _LHS[key]
    body, dot, component = key.partition(".")
    if dot:
        return rf"{_COMPONENT.get(component, component)}^{{(\mathrm{{{escape_text(body)}}})}}"
    if key in SYMBOLS:
        return latex_name(SYMBOLS[key])
    return latex_name(sp.Symbol(key))


def escape_text(text: str) -> str:
    """Text made safe inside LaTeX (its special characters escaped).

    Examples
    --------
    >>> escape_text("a_b")
    'a\\\\_b'
    """
    for char, repl in (("\\", r"\textbackslash{}"), ("&", r"\&"), ("%", r"\%"),
                       ("$", r"\$"), ("#", r"\#"), ("_", r"\_"), ("{", r"\{"),
                       ("}", r"\}"), ("~", r"\textasciitilde{}"), ("^", r"\^{}")):
        text = text.replace(char, repl)
    return text


def aligned(rows: list[tuple[str, str, str]]) -> str:
    r"""Display math for Jupyter: one ``lhs = rhs`` per row with a note, aligned at ``=``.

    Examples
    --------
    >>> print(aligned([("x", "1", "a note"), ("y", "2", "")]))
    $$\begin{aligned} x &= 1 && \text{a note} \\ y &= 2 \end{aligned}$$
    """
    lines = [rf"{lhs} &= {rhs}" + (rf" && \text{{{escape_text(note)}}}" if note else "")
             for lhs, rhs, note in rows]
    return r"$$\begin{aligned} " + r" \\ ".join(lines) + r" \end{aligned}$$"
