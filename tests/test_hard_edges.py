"""Hard edges met by hostile inputs: each case a scene or call that once crashed, was
refused though valid, or ran past any reasonable time; each is answered rightly now, or
refused in one line naming what is wrong."""

from __future__ import annotations

from helpers import refused, scene_file

_TURNED_BOX = """
[symbols]
a = {}
[[bodies]]
name = "floor"
shape = "fixed"
[[bodies]]
name = "box"
shape = "rigid"
mass = "1"
inertia = ["1", "2", "2"]
orientation = { axis = ["a", "a", "a"], angle = "30 deg" }
position = ["0.3", "0.2", "1"]
velocity = ["0", "0", "-1"]
[contact]
bodies = ["floor", "box"]
point = ["0", "0", "0"]
normal = ["0", "0", "1"]
restitution = "1/2"
"""


def test_an_orientation_axis_that_the_values_make_zero_is_refused(tmp_path, capsys):
    path = scene_file(tmp_path, _TURNED_BOX)
    refused(capsys, ["evaluate", path, "--set", "a=0"], "box.orientation.axis")
    with_values = _TURNED_BOX.replace("a = {}\n", "a = {}\n[values]\na = 0\n")
    for command in ("evaluate", "simulate"):
        refused(capsys, [command, scene_file(tmp_path, with_values, "v.toml")],
                "box.orientation.axis: is the zero vector")


def _rough_rod(angle_deg, vx, vy, restitution="e", friction="mu", beta="beta"):
    return f"""
[symbols]
e = {{ nonnegative = true }}
mu = {{ nonnegative = true }}
beta = {{}}
[[bodies]]
name = "rod"
shape = "rod"
mass = "1"
length = "2"
angle = "{angle_deg} deg"
struck_at = "1"
velocity = ["{vx}", "{vy}"]
[[bodies]]
name = "floor"
shape = "fixed"
[contact]
bodies = ["rod", "floor"]
normal = ["0", "-1"]
restitution = "{restitution}"
tangential = "rough"
friction = "{friction}"
tangential_restitution = "{beta}"
"""


def _walton_broken(angle_deg, u, e, mu, beta, got):
    """How far an answer is from Walton's law, solved apart: the rod's lower end at
    O, its centre r = (cos a, sin a) from it, the floor's normal -y; the end leaves
    with -e times its normal velocity and -beta times its slip where friction mu
    allows, and otherwise slides with mu P_n straight against the slip before."""
    import math

    a = math.radians(angle_deg)
    rx, ry = -math.cos(a), -math.sin(a)  # from the centre to the end
    inertia = 1 / 3

    def end(vx, vy, w):
        return vx - w * ry, vy + w * rx

    vx, vy, w = got["rod.vx"], got["rod.vy"], got["rod.omega"]
    p_t, p_n = vx - u[0], vy - u[1]  # the floor pushes the rod up (+y) and along x
    moment = rx * p_n - ry * p_t
    slip0, up0 = end(u[0], u[1], 0.0)
    slip1, up1 = end(vx, vy, w)
    gaps = [abs(moment / inertia - w), abs(up1 + e * up0)]
    if abs(p_t) < mu * p_n * (1 - 1e-9):
        gaps.append(abs(slip1 + beta * slip0))
    else:
        gaps += [abs(abs(p_t) - mu * p_n), max(0.0, p_t * slip0)]
    return max(gaps)


def test_walton_on_the_cones_edge_is_checked_by_its_own_promise(tmp_path, capsys):
    """Walton's law slides with its friction against the slip before; where the normal
    couples to the slip, the slip after may pass -beta times the slip before, which the
    certificate once took for a broken law and refused every such derivation."""
    from helpers import evaluated

    from rigidimpact.cli import main

    path = scene_file(tmp_path, _rough_rod(45, "0.6", "-1"))
    assert main(["derive", path]) == 0
    capsys.readouterr()
    # mu = 0 or beta = 1 leaves no tangential impulse: P = (0, 0.8), by hand
    for setting in (["mu=0", "beta=1/2"], ["mu=2/5", "beta=1"]):
        got = evaluated(capsys, ["evaluate", path, "--set", "e=1",
                                 *(x for s in setting for x in ("--set", s))])
        assert abs(got["rod.vx"] - 0.6) < 1e-12 and abs(got["rod.vy"] + 0.2) < 1e-12
        assert abs(got["rod.omega"] + 1.2 * 2**0.5) < 1e-12


def test_a_seeded_family_of_rough_rods_is_answered_by_walton(tmp_path, capsys):
    import random

    from helpers import evaluated

    from rigidimpact.cli import main

    rng = random.Random(70)
    for k in range(6):
        angle = rng.randint(10, 80)
        u = (round(rng.uniform(-2, 2), 2), round(rng.uniform(-2, -0.1), 2))
        path = scene_file(tmp_path, _rough_rod(angle, *u), f"rod{k}.toml")
        assert main(["derive", path]) == 0, (angle, u)
        capsys.readouterr()
        e, mu, beta = rng.choice([0, 0.5, 1]), rng.uniform(0, 1), rng.uniform(-1, 1)
        got = evaluated(capsys, ["evaluate", path, "--set", f"e={e}", "--set",
                                 f"mu={mu!r}", "--set", f"beta={beta!r}"])
        assert _walton_broken(angle, u, e, mu, beta, got) < 1e-9, (angle, u, e, mu, beta)
