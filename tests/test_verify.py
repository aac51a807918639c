"""The verifier passes the paper's results and, just as important, fails wrong ones."""

from __future__ import annotations

import sympy as sp

from rigidimpact.paper.published import REFERENCES
from rigidimpact.symbolic.notation import symbol
from rigidimpact.verify import agree, run_checks, same_equation, symbolic_zero

m, M, theta, e = (symbol(n) for n in ("m", "M", "theta", "e"))


def test_every_check_passes():
    rows = run_checks()
    assert len(rows) >= 18
    assert [r.id for r in rows if r.status != "pass"] == []


def test_a_wrong_formula_fails_both_ways():
    wrong = REFERENCES["barbell.f"].expr * (1 + sp.Rational(1, 10**30))  # tiny, not zero
    verdict = agree(wrong, REFERENCES["barbell.f"].expr)
    assert not verdict.passed
    assert "NOT a symbolic zero" in verdict.detail


def test_a_sign_slip_in_eq_7_fails():
    paper = REFERENCES["barbell.energy_loss_fraction"].expr
    slipped = (1 + e**2) / (1 + m / (2 * M) * (1 + sp.sin(theta) ** 2))
    assert not agree(slipped, paper).passed


def test_symbolic_zero_sees_trig_identities_simplify_might_miss():
    t = symbol("theta")
    assert symbolic_zero(sp.sin(t) ** 4 - sp.cos(t) ** 4 - (sp.sin(t) ** 2 - sp.cos(t) ** 2))
    assert not symbolic_zero(sp.sin(t) - sp.cos(t))


def test_same_equation_requires_a_factor_free_of_the_unknowns():
    x = sp.Symbol("x")
    assert same_equation(3 * M * (x - m), x - m, [x]).passed
    assert not same_equation(x * (x - m), x - m, [x]).passed


def test_references_are_the_paper_not_the_solver():
    # the reference module must not import the solver (its values are typed from the paper)
    from pathlib import Path

    import rigidimpact.paper.published as paper

    source = Path(paper.__file__).read_text(encoding="utf-8")
    assert "import impact" not in source and "problems" not in source


def test_worker_processes_give_the_same_checks_in_the_same_order():
    def small(check_id):
        return check_id.split(".")[0] in ("discs", "barbell")

    alone = run_checks(small)
    together = run_checks(small, jobs=2)
    assert [(c.id, c.status) for c in together] == [(c.id, c.status) for c in alone]
    assert len(alone) > 5 and all(c.status == "pass" for c in together)
