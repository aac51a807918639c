from __future__ import annotations

import pytest
import sympy as sp

from rigidimpact.symbolic.notation import SYMBOLS, latex_name, make_symbol, symbol


def test_symbols_carry_their_assumptions():
    assert symbol("m").is_positive and symbol("M").is_positive and symbol("L").is_positive
    assert symbol("e").is_nonnegative and symbol("e").is_positive is None
    assert symbol("theta").is_real and symbol("theta").is_positive is None


def test_a_bare_symbol_is_not_the_project_symbol():
    # the classic silent bug the notation module exists to prevent
    assert sp.Symbol("m") != symbol("m")
    assert make_symbol("m") is symbol("m")


def test_redeclaring_a_known_symbol_differently_is_refused():
    with pytest.raises(ValueError, match="second, unequal symbol"):
        make_symbol("m", real=True)


def test_unknown_symbol():
    with pytest.raises(KeyError, match="unknown symbol"):
        symbol("zeta_9")


@pytest.mark.parametrize(("name", "tex"), [("v_ix", "v_{ix}"), ("V_x", "V_{x}"),
                                           ("omega_z", r"\omega_{z}"), ("theta", r"\theta"),
                                           ("R_1y", "R_{1y}"), ("m", "m")])
def test_latex_names_follow_the_paper(name, tex):
    assert latex_name(SYMBOLS[name]) == tex
