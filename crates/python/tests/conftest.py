"""Shared fixtures: the repository's example scenes and small scenes written for the tests."""

import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "examples"

# A chain clamped at one end under a tip load (a small version of examples/cantilever.toml).
CANTILEVER = """
[simulation]
dt = "auto"
safety = 0.5
steps = 50
gravity = [0, 0, 0]
damping = 0.3

[materials.bar]
young = 1e8
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[structures]]
name = "beam"
kind = "chain"
material = "bar"
node_radius = 0.01
start = [0, 0, 0]
end = [1, 0, 0]
segments = 10

[[boundary]]
select = { structure = "beam", side = "start" }
block = "xyzXYZ"

[[loads]]
select = { structure = "beam", side = "end" }
force = [0, 0, -0.01]
"""


def cantilever_dict():
    """CANTILEVER as a dict with the same keys."""
    return {
        "simulation": {
            "dt": "auto",
            "safety": 0.5,
            "steps": 50,
            "gravity": [0, 0, 0],
            "damping": 0.3,
        },
        "materials": {
            "bar": {"young": 1e8, "poisson": 0.3, "density": 1000, "friction_angle_deg": 30}
        },
        "structures": [
            {
                "name": "beam",
                "kind": "chain",
                "material": "bar",
                "node_radius": 0.01,
                "start": (0, 0, 0),
                "end": [1.0, 0, 0],
                "segments": 10,
            }
        ],
        "boundary": [{"select": {"structure": "beam", "side": "start"}, "block": "xyzXYZ"}],
        "loads": [{"select": {"structure": "beam", "side": "end"}, "force": [0, 0, -0.01]}],
    }


@pytest.fixture
def tube_scene():
    """The tube impact of the paper (examples/tube_impact_solid.toml)."""
    return EXAMPLES / "tube_impact_solid.toml"


@pytest.fixture
def cantilever_text():
    return CANTILEVER
