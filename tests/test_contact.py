from __future__ import annotations

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.laws.contact import Contact
from rigidimpact.symbolic.notation import symbol


def test_frame_rows_are_the_unit_normal_and_tangent():
    frame = Contact(normal=(3, 4)).frame
    assert list(frame.row(0)) == [sp.Rational(3, 5), sp.Rational(4, 5)]
    assert list(frame.row(1)) == [-sp.Rational(4, 5), sp.Rational(3, 5)]
    assert frame * frame.T == sp.eye(2)


@pytest.mark.parametrize("e", [-sp.Rational(1, 10), sp.Rational(11, 10), -1])
def test_restitution_outside_unit_interval_is_refused(e):
    with pytest.raises(InputError, match="contact.restitution"):
        Contact(restitution=e)


def test_symbolic_restitution_is_accepted():
    assert Contact(restitution=symbol("e")).restitution == symbol("e")


def test_zero_normal_and_unknown_tangential_are_refused():
    with pytest.raises(InputError, match="contact.normal"):
        Contact(normal=(0, 0))
    with pytest.raises(InputError, match="contact.tangential"):
        Contact(tangential="rough")
