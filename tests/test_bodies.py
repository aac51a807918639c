from __future__ import annotations

import pytest
import sympy as sp

from rigidimpact.errors import InputError
from rigidimpact.model.bodies import Body, join
from rigidimpact.symbolic.notation import symbol

m, M, L, theta, v = (symbol(n) for n in ("m", "M", "L", "theta", "v_ix"))


def test_barbell_is_two_point_masses_on_a_massless_rod():
    bar = Body.barbell(M, L, theta)
    # independent: sum of m r^2 of the two spheres about the centre
    assert bar.inertia == 2 * M * L**2
    a, b = bar.parts
    assert (a.label, b.label) == ("A", "B")
    assert sp.simplify((a.position + b.position) / 2 - bar.position) == sp.zeros(2, 1)


@pytest.mark.parametrize(("maker", "factor"), [(Body.disc, sp.Rational(1, 2)),
                                               (Body.ring, 1), (Body.sphere, sp.Rational(2, 5))])
def test_round_bodies_have_textbook_inertia(maker, factor):
    r = symbol("r")
    body = maker(m, r)
    assert body.inertia == factor * m * r**2
    assert list(body.position) == [r, 0]
    assert list(maker(m, r, side=-1).position) == [-r, 0]


def test_rod_inertia_and_centre():
    rod = Body.rod(m, 2 * L, theta, L / 2)
    assert rod.inertia == m * (2 * L) ** 2 / 12
    assert list(rod.position) == [L / 2 * sp.cos(theta), L / 2 * sp.sin(theta)]


def test_contact_velocity_is_eq_11():
    w, Rx, Ry, Vx, Vy = sp.symbols("w R_x R_y V_x V_y", real=True)
    body = Body.rigid(1, 1, (Rx, Ry), (Vx, Vy), w)
    # v = V - omega x R, with omega x R = (-w Ry, w Rx)
    assert list(body.contact_velocity) == [Vx + w * Ry, Vy - w * Rx]


def test_join_uses_the_parallel_axis_theorem():
    ball = Body.particle(m, (v, 0), "ball")
    bar = Body.barbell(M, L, 0)
    both = join(ball, bar)
    h = m * L / (2 * M + m)  # the paper's offset of S from C (section 2)
    # independent: S sits at s from O on the rod; sum m_k d_k^2 over A, B and the ball
    s = 2 * M * L / (2 * M + m)
    expected = M * s**2 + M * (2 * L - s) ** 2 + m * s**2
    assert sp.simplify(both.inertia - expected) == 0
    assert sp.simplify(s - (L - h)) == 0
    # momentum is kept
    assert sp.simplify(both.momentum[0] - m * v) == 0


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"mass": -1}, "ball.mass"),
    ({"mass": sp.nan}, "ball.mass"),
    ({"mass": 0}, "ball.mass"),
    ({"mass": 1, "velocity": (1,)}, "ball.velocity"),
])
def test_bad_particles_name_the_field(kwargs, field):
    with pytest.raises(InputError) as info:
        Body.particle(name="ball", **kwargs)
    assert info.value.field == field


def test_strings_are_never_taken_as_expressions():
    with pytest.raises(InputError, match="not text"):
        Body.particle("__import__('os')")


def test_point_mass_must_sit_at_the_contact_point():
    # a body is placed freely (several contacts use a world frame); an impact at O
    # refuses a point mass elsewhere, since nothing could touch it there
    from rigidimpact.laws.contact import Contact
    from rigidimpact.solve.impact import Impact

    lump = Body.rigid(1, 0, (1, 0), velocity=(1, 0), name="lump")
    with pytest.raises(InputError, match="contact point"):
        Impact(lump, Body.fixed("wall"), Contact())


def test_rod_contact_must_lie_on_the_rod():
    with pytest.raises(InputError, match="struck_at"):
        Body.rod(1, 2, 0, 3)


def test_repr_reads_as_a_constructor_call():
    assert repr(Body.particle(1, (2, 0), "p")).startswith("Body(name='p', mass=1")
