"""Pressures and servo walls from Python, with known answers: a pressurised closed shell's
pressure work equals p·ΔV, and a servo platen holds its target stress."""

import math

import pytest

import flexdem

SHELL = """
[simulation]
dt = 2e-6
steps = 2000
damping = 0.3

[materials.rubber]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[structures]]
name = "balloon"
kind = "sphere_shell"
material = "rubber"
node_radius = 0.002
center = [0, 0, 0]
radius = 0.1
subdivisions = 2

[output]
series_every = 100

[[output.series]]
name = "b"
quantity = "volume"
of = { structure = "balloon" }
"""


def test_a_pressure_added_from_python_does_the_work_p_dv():
    sim = flexdem.Simulation.from_toml(SHELL)
    sim.add_pressure("balloon", 2e3)
    (p,) = sim.pressures()
    assert p["pressure"] == 2e3 and not p["flip"] and p["ramp"] is None
    assert len(p["pfacets"]) == 320 and p["current"] == 2e3
    sim.run(steps=2000)
    volumes = sim.series()["b_volume_m3"]
    v0 = volumes[0]
    work = sim.energy()["load_work"]
    # a constant pressure on a closed surface is conservative: its work is p·ΔV
    assert work == pytest.approx(2e3 * (volumes[-1] - v0), rel=1e-3)
    assert volumes[-1] > v0
    sim.clear_pressures()
    assert sim.pressures() == []
    with pytest.raises(ValueError, match="unknown structure `ballon`"):
        sim.add_pressure("ballon", 1.0)
    with pytest.raises(ValueError):
        sim.add_pressure("balloon", math.nan)


COLUMN = """
[simulation]
dt = 1e-5
steps = 1
damping = 0.3

[materials.m]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 0

[[spheres]]
kind = "single"
material = "m"
center = [0, 0, 0.01]
radius = 0.01

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "m"

[[walls]]
point = [0, 0, 0.0201]
normal = [0, 0, -1]
material = "m"
"""


def test_a_servo_wall_set_from_python_holds_its_stress():
    sim = flexdem.Simulation.from_toml(COLUMN)
    area = 4e-4
    sim.set_wall_servo(1, stress=1e4, area=area, max_speed=0.05)
    sim.run(steps=6000)
    # the sphere is pressed by the platen: both its contacts carry the target force σ·A = 4 N
    normal = sim.contacts()["normal_force"]
    assert len(normal) == 2
    for f in normal:
        assert f == pytest.approx(1e4 * area, rel=1e-2)
    assert sim.energy()["boundary_work"] > 0
    with pytest.raises(ValueError, match="area"):
        sim.set_wall_servo(1, stress=1e4, area=-1.0, max_speed=0.05)
