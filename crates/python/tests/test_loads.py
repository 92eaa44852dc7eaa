"""Loads from Python between stages: the keys, checks and messages of a scene file's
[[loads]], a known force on a free sphere, and its work in the energy terms."""

import re
import subprocess
import sys

import numpy as np
import pytest

import flexdem
from conftest import CANTILEVER

DT = 1e-4

# A free sphere, no gravity, no damping: under a constant force F it accelerates at F/m.
FREE = f"""
[simulation]
dt = {DT}
steps = 1000
gravity = [0, 0, 0]

[materials.rock]
young = 1e8
poisson = 0.3
density = 2000
friction_angle_deg = 30

[[spheres]]
name = "rock"
kind = "single"
material = "rock"
center = [0, 0, 1]
radius = 0.1
"""


def located(message):
    """A scene error's message without its `file:line:column: ` prefix."""
    return re.sub(r"^.*?:\d+:\d+: ", "", message)


def test_known_force_on_a_free_sphere_and_its_work():
    sim = flexdem.Simulation.from_toml(FREE)
    m = sim.masses[0]
    assert m == pytest.approx(2000 * 4 / 3 * np.pi * 0.1**3)
    sim.run(steps=50)  # no load yet: at rest
    assert not sim.velocities.any()
    force = np.array([3.0, 0.0, -1.5])
    sim.add_load(select={"spheres": "rock"}, force=force)
    n = 200
    x0 = sim.positions[0].copy()
    sim.run(steps=n)
    a = force / m
    # leapfrog: v_n = a·n·dt exactly, x_n = x_0 + a·dt²·n(n+1)/2
    np.testing.assert_allclose(sim.velocities[0], a * n * DT, rtol=1e-12)
    np.testing.assert_allclose(sim.positions[0] - x0, a * DT**2 * n * (n + 1) / 2, rtol=1e-9)
    e = sim.energy()
    # the leapfrog's kinetic energy at step n: ½·m·v(n−½)·v(n+½) = ½·m·a²·dt²·n(n−1)
    kinetic = 0.5 * m * np.dot(a, a) * DT**2 * n * (n - 1)
    assert e["kinetic_translation"] == pytest.approx(kinetic, rel=1e-12)
    # the load's work is what the sphere gained: the balance closes
    assert e["load_work"] == pytest.approx(kinetic, rel=1e-12)
    assert abs(e["relative_balance_error"]) < 1e-12


def test_total_force_shared_and_loads_read_back():
    sim = flexdem.Simulation.from_toml(CANTILEVER)
    [tip] = sim.loads()  # the scene's own load on the tip
    np.testing.assert_array_equal(tip["select"]["ids"], [10])
    np.testing.assert_array_equal(tip["force"], [0, 0, -0.01])
    np.testing.assert_array_equal(tip["moment"], [0, 0, 0])
    assert "ramp" not in tip

    sim.set_loads([])
    assert sim.loads() == []
    sim.add_load(select={"structure": "beam", "side": "ends"}, total_force=[0, 0, -0.02],
                 ramp={"start": 0.0, "duration": 0.5})
    [ends] = sim.loads()
    np.testing.assert_array_equal(ends["select"]["ids"], [0, 10])
    np.testing.assert_allclose(ends["force"], [0, 0, -0.01])  # shared by the two ends
    assert ends["ramp"] == {"start": 0.0, "duration": 0.5}

    # what loads() gives, set_loads takes back
    sim.set_loads([tip, ends])
    loads = sim.loads()
    assert len(loads) == 2
    np.testing.assert_array_equal(loads[0]["select"]["ids"], [10])
    assert loads[1]["ramp"] == {"start": 0.0, "duration": 0.5}


def test_loads_from_a_generator_that_reads_the_simulation():
    # The generator reads sim while set_loads runs: that waited for the simulation's own
    # lock for ever (with the GIL held, so not even Ctrl-C stopped it). In a child process,
    # so that a regression fails by its timeout instead of hanging the suite.
    code = (
        "import sys, flexdem\n"
        "sim = flexdem.Simulation.from_toml(sys.stdin.read())\n"
        "sim.set_loads({'select': {'ids': [i]}, 'force': [0, 0, -9.81 * sim.masses[i]]}"
        " for i in (0, 10))\n"
        "print(len(sim.loads()), sim.loads()[1]['force'][2] / sim.masses[10])\n"
    )
    done = subprocess.run([sys.executable, "-c", code], input=CANTILEVER, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    count, g = done.stdout.split()
    assert count == "2"
    assert float(g) == pytest.approx(-9.81, rel=1e-12)


def test_replacing_the_load_between_stages_reverses_the_motion():
    sim = flexdem.Simulation.from_toml(FREE)
    sim.add_load(select={"ids": [0]}, force=[2.0, 0, 0])
    sim.run(steps=100)
    v = sim.velocities[0, 0]
    assert v > 0
    sim.set_loads([{"select": {"ids": [0]}, "force": [-2.0, 0, 0]}])
    sim.run(steps=100)
    # the same force backwards for as long: at rest again
    assert sim.velocities[0, 0] == pytest.approx(0.0, abs=1e-15)
    assert sim.energy()["load_work"] == pytest.approx(0.0, abs=1e-12)


def test_box_selects_by_current_positions():
    sim = flexdem.Simulation.from_toml(FREE)
    sim.add_load(select={"ids": [0]}, force=[0, 0, 50.0])
    sim.run(steps=1000)  # the sphere rises
    z = sim.positions[0, 2]
    assert z > 1.01
    with pytest.raises(flexdem.SceneError, match="matches no particle"):
        sim.add_load(select={"box": {"min": [-1, -1, 0.9], "max": [1, 1, 1.001]}},
                     force=[0, 0, 1])
    sim.add_load(select={"box": {"min": [-1, -1, z - 0.001], "max": [1, 1, z + 0.001]}},
                 force=[0, 0, 1])
    assert len(sim.loads()) == 2


def test_errors_are_the_scene_readers(tmp_path):
    sim = flexdem.Simulation.from_toml(CANTILEVER)
    # the same mistake in a scene file and from Python: the same message after the location
    bad = CANTILEVER.replace('select = { structure = "beam", side = "end" }',
                             'select = { structure = "bem", side = "end" }')
    with pytest.raises(flexdem.SceneError) as in_file:
        flexdem.Simulation.from_toml(bad)
    with pytest.raises(flexdem.SceneError) as from_python:
        sim.add_load(select={"structure": "bem", "side": "end"}, force=[0, 0, -1])
    assert isinstance(from_python.value, ValueError)
    assert str(from_python.value).startswith("<loads>:")
    assert located(str(from_python.value)) == located(str(in_file.value))
    assert "did you mean `beam`" in str(from_python.value)

    with pytest.raises(flexdem.SceneError, match="not both"):
        sim.add_load(select={"ids": [3]}, force=[0, 0, 1], total_force=[0, 0, 1])
    with pytest.raises(flexdem.SceneError, match="give `force`, `total_force` or `moment`"):
        sim.add_load(select={"ids": [3]})
    with pytest.raises(flexdem.SceneError, match="forc"):
        sim.add_load(select={"ids": [3]}, forc=[0, 0, 1])
    with pytest.raises(flexdem.SceneError, match="particle id 99 does not exist"):
        sim.add_load(select={"ids": [99]}, force=[0, 0, 1])
    with pytest.raises(flexdem.SceneError, match="loads.ramp.duration"):
        sim.add_load(select={"ids": [3]}, force=[0, 0, 1], ramp={"start": 0, "duration": 0})
    with pytest.raises(flexdem.SceneError, match="side"):
        sim.add_load(select={"structure": "beam", "side": "middle"}, force=[0, 0, 1])
    # a bad entry in set_loads changes nothing
    with pytest.raises(flexdem.SceneError):
        sim.set_loads([{"select": {"ids": [3]}, "force": [0, 0, 1]}, {"select": {"ids": [3]}}])
    assert len(sim.loads()) == 1


def test_resumed_simulation_selects_by_ids_not_names(tmp_path):
    sim = flexdem.Simulation.from_toml(CANTILEVER)
    sim.run(steps=10)
    sim.save_checkpoint(tmp_path / "c.flexdem")
    resumed = flexdem.Simulation.resume(tmp_path / "c.flexdem")
    assert len(resumed.loads()) == 1  # the checkpoint keeps the loads
    with pytest.raises(flexdem.SceneError, match="resumed from a checkpoint"):
        resumed.add_load(select={"structure": "beam", "side": "end"}, force=[0, 0, -1])
    resumed.add_load(select={"ids": [10]}, force=[0, 0, -1])
    assert len(resumed.loads()) == 2
