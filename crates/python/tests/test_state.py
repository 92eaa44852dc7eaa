"""State as numpy arrays: particles, contacts, links, energy."""

import numpy as np
import pytest

import flexdem

ENERGY_TERMS = [
    "kinetic_translation",
    "kinetic_rotation",
    "elastic_links",
    "elastic_contacts",
    "gravity_work",
    "load_work",
    "boundary_work",
    "contact_births",
    "contact_releases",
    "damping",
    "links_dissipated",
    "friction",
    "contact_damping",
]


def test_particle_arrays(tube_scene):
    sim = flexdem.Simulation.from_scene(tube_scene)
    n = sim.particle_count
    for name in ("positions", "velocities", "angular_velocities", "forces"):
        a = getattr(sim, name)
        assert isinstance(a, np.ndarray) and a.shape == (n, 3) and a.dtype == np.float64, name
    assert sim.radii.shape == sim.masses.shape == sim.structures.shape == (n,)
    assert not sim.forces.any()  # no step yet
    impactor = int(np.argmax(sim.radii))
    assert sim.structures[impactor] == -1 and (sim.structures[:impactor] == 0).all()
    assert sim.masses[impactor] == pytest.approx(0.1121, rel=1e-3)
    # copies: changing them changes nothing in the simulation
    sim.positions[:] = 0
    assert sim.positions[impactor, 2] == pytest.approx(0.207)


def test_contacts_and_forces_during_the_impact(tube_scene):
    sim = flexdem.Simulation.from_scene(tube_scene)
    empty = sim.contacts()
    assert empty["pairs"].shape == (0, 2) and empty["points"].shape == (0, 3)
    # the sphere touches the tube after 2.5 ms (the tube's wall bounces off and back):
    # stop at the first step with contacts
    sim.run(steps=500, callback=lambda s: len(s.contacts()["normal_force"]) == 0, every=1)
    c = sim.contacts()
    m = len(c["normal_force"])
    assert m > 0
    assert c["pairs"].shape == c["kinds"].shape == (m, 2)
    for name in ("points", "normals", "shear_force", "force"):
        assert c[name].shape == (m, 3), name
    np.testing.assert_allclose(np.linalg.norm(c["normals"], axis=1), 1.0, rtol=1e-9)
    assert (c["normal_force"] > 0).any()
    impactor = int(np.argmax(sim.radii))
    # the impactor is a free sphere: site 1 (a particle feature), the tube's site 2
    touching = (c["kinds"][:, 0] == 0) & (c["pairs"][:, 0] == impactor)
    assert touching.any()
    # the tube pushes the sphere up
    assert sim.forces[impactor, 2] > 0


def test_links(tube_scene):
    sim = flexdem.Simulation.from_scene(tube_scene)
    links = sim.links()
    assert links["nodes"].shape == (976, 2)
    assert (links["status"] == 0).all()
    assert not links["force"].any()
    sim.run(duration=0.02)
    links = sim.links()
    assert links["normal_force"].shape == (976,)
    assert links["shear_force"].shape == links["force"].shape == (976, 3)
    assert np.abs(links["normal_force"]).max() > 0


def test_energy_terms_and_balance(tube_scene):
    sim = flexdem.Simulation.from_scene(tube_scene)
    e = sim.energy()
    for term in ENERGY_TERMS + ["stored", "put_in", "taken_out", "balance",
                                "initial_balance", "relative_balance_error",
                                "late_births"]:
        assert term in e, term
    # ½·m·v², m = 0.1121 kg, v = 2 m/s
    assert e["kinetic_translation"] == pytest.approx(0.2242, rel=1e-3)
    sim.run(duration=0.05)
    e = sim.energy()
    assert e["elastic_links"] > 0
    assert e["stored"] == pytest.approx(
        e["kinetic_translation"] + e["kinetic_rotation"] + e["elastic_links"]
        + e["elastic_contacts"])
    assert e["balance"] == pytest.approx(e["stored"] - e["put_in"] + e["taken_out"])
    assert abs(e["relative_balance_error"]) < 5e-3


def test_time_steps_dt(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)
    dt = sim.dt
    sim.run(steps=10)
    assert sim.steps == 10
    assert sim.time == pytest.approx(10 * dt)
    assert sim.warnings == []


def bouncing_ball(**damping):
    """A sphere dropped at 0.5 m/s onto a wall, both of a material with `damping` keys."""
    material = {"young": 1e8, "poisson": 0.3, "density": 2650, "friction_angle_deg": 30,
                **damping}
    return {
        "simulation": {"dt": 1e-7, "steps": 1},
        "materials": {"m": material},
        "walls": [{"point": [0, 0, 0], "normal": [0, 0, 1], "material": "m"}],
        "spheres": [{"kind": "single", "material": "m", "center": [0, 0, 0.01001],
                     "radius": 0.01, "velocity": [0, 0, -0.5]}],
    }


def test_contact_damping_from_a_dict():
    # restitution 0.5: ζ = 0.2155, and the clamped dashpot's restitution
    # exp(−2ζ·arccos ζ/√(1 − ζ²)) = 0.5503 (docs/model.md §7)
    sim = flexdem.Simulation.from_dict(bouncing_ball(restitution=0.5))
    sim.run(steps=6000)
    assert sim.velocities[0, 2] / 0.5 == pytest.approx(0.5503, rel=1e-2)
    e = sim.energy()
    # the dashpot took what the bounce lost: ½·m·v0²·(1 − e²), with ½·m·v² = e²·½·m·v0²
    lost = e["kinetic_translation"] * (1 - 0.5503**2) / 0.5503**2
    assert e["contact_damping"] == pytest.approx(lost, rel=3e-2)
    assert abs(e["relative_balance_error"]) < 1e-9
    with pytest.raises(flexdem.SceneError, match="materials.m.gamma_n.*conflicts"):
        flexdem.Simulation.from_dict(bouncing_ball(restitution=0.5, gamma_n=100.0))
