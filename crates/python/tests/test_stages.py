"""Changes between stages of a run: gravity, damping, imposed and wall velocities, each with
a known answer, and refusals that raise ValueError with the engine's message."""

import numpy as np
import pytest

import flexdem

SPHERE = """
[simulation]
dt = 1e-4
steps = 100
gravity = [0, 0, -9.81]
damping = 0

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

[[walls]]
point = [0, 0, -1]
normal = [0, 0, 1]
material = "rock"
"""


def test_gravity_changed_between_stages():
    sim = flexdem.Simulation.from_toml(SPHERE)
    sim.run(steps=100)
    v1 = sim.velocities[0, 2]
    assert v1 == pytest.approx(-9.81 * 100 * 1e-4, rel=1e-9)
    sim.set_gravity([0, 0, 0])
    sim.run(steps=100)
    # free flight without gravity: the velocity stays as it was
    assert sim.velocities[0, 2] == pytest.approx(v1, rel=1e-12)


def test_imposed_velocity_drives_the_particle_and_its_work_is_counted():
    sim = flexdem.Simulation.from_toml(SPHERE)
    sim.impose_velocity([0], [0.5, 0, 0])
    x0 = sim.positions[0].copy()
    sim.run(steps=200)
    moved = sim.positions[0] - x0
    assert moved[0] == pytest.approx(0.5 * 200 * 1e-4, rel=1e-9)
    assert moved[2] == pytest.approx(0.0, abs=1e-12)  # held against gravity
    # the support holds the sphere against gravity: it does no work at constant height,
    # and gravity none either; the balance closes
    assert abs(sim.energy()["relative_balance_error"]) < 1e-9


def test_a_velocity_imposed_mid_run_is_given_by_the_support():
    sim = flexdem.Simulation.from_toml(SPHERE)
    sim.run(steps=1000)  # falling at 0.981 m/s
    sim.impose_velocity([0], [0.5, 0, 0])
    sim.run(steps=200)
    e = sim.energy()
    # the support gave ½m·0.5² and took the fall's ½m·0.981²; the leapfrog's lag of the
    # fall leaves 1/1000 of its kinetic energy, once
    m = 2000 * 4 / 3 * np.pi * 0.1**3
    assert e["boundary_work"] == pytest.approx(0.5 * m * (0.25 - 0.981**2), rel=3e-3)
    assert abs(e["relative_balance_error"]) < 1.5e-3


def test_a_velocity_set_by_hand_is_the_users_work():
    sim = flexdem.Simulation.from_toml(SPHERE)
    sim.run(steps=1000)  # falling at 0.981 m/s
    v0 = sim.velocities[0].copy()
    sim.set_velocity([0], [2.0, 0, 3.0])
    sim.set_angular_velocity([0], [0, 0, 10.0])
    sim.run(steps=100)
    e = sim.energy()
    m = 2000 * 4 / 3 * np.pi * 0.1**3
    inertia = 0.4 * m * 0.1**2
    kick = 0.5 * m * (13.0 - v0 @ v0) + 0.5 * inertia * 100.0
    assert e["load_work"] == pytest.approx(kick, rel=1e-12)
    # the leapfrog's lag, ½·m·g·dt·Δv once, is all the balance is off by
    assert abs(e["relative_balance_error"]) < 1e-3
    assert sim.velocities[0][0] == pytest.approx(2.0)
    with pytest.raises(ValueError):
        sim.set_velocity([0, 7], [0, 0, 0])
    assert sim.velocities[0][0] == pytest.approx(2.0)  # nothing set


def test_wall_velocity_and_damping_are_set():
    sim = flexdem.Simulation.from_toml(SPHERE)
    sim.set_wall_velocity(0, [0, 0, 1.0])
    sim.set_damping(0.2)
    sim.run(steps=100)
    assert sim.energy()["damping"] > 0  # Cundall damping now takes energy out


def test_refused_changes_raise_value_error():
    sim = flexdem.Simulation.from_toml(SPHERE)
    with pytest.raises(ValueError, match="wall"):
        sim.set_wall_velocity(3, [0, 0, 1])
    with pytest.raises(ValueError):
        sim.set_damping(1.5)
    with pytest.raises(ValueError):
        sim.impose_velocity([7], [0, 0, 0])
    with pytest.raises(ValueError):
        sim.set_gravity([0, 0, float("nan")])
    # nothing was changed by the refusals: still falling freely under gravity
    sim.run(steps=10)
    assert sim.velocities[0, 2] == pytest.approx(-9.81 * 10 * 1e-4, rel=1e-9)
