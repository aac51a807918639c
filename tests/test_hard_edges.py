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
