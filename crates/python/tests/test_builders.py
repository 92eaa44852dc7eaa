"""Scenes built from dicts with every structure builder and the mesh key of the TOML, and a
scene file read into a dict, changed and run."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest

import flexdem

# A square of two triangles (OBJ, 1-based vertex indices).
SQUARE_OBJ = """v 0 0 0
v 0.2 0 0
v 0.2 0.2 0
v 0 0.2 0
f 1 2 3
f 1 3 4
"""

# Every kind of structure: (dict, nodes, connections, PFacets).
KINDS = [
    ({"kind": "chain", "start": [0, 0, 0], "end": [0.4, 0, 0], "segments": 4}, 5, 4, 0),
    ({"kind": "chain", "points": [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0]]}, 3, 2, 0),
    ({"kind": "helix", "center": [0, 0, 0], "radius": 0.1, "pitch": 0.1, "turns": 1,
      "segments_per_turn": 12}, 13, 12, 0),
    # a net: (2+1)·(3+1) nodes, 2·4 links along u and 3·3 along v
    ({"kind": "net", "origin": [0, 0, 0], "u_dir": [1, 0, 0], "v_dir": [0, 1, 0],
      "size": [0.4, 0.6], "cells": [2, 3]}, 12, 17, 0),
    # a membrane: 3·3 nodes, 12 edges of the grid and a diagonal per cell, two PFacets per cell
    ({"kind": "membrane", "size": [0.4, 0.4], "cells": [2, 2], "mass": "plate"}, 9, 16, 8),
    # a disc of 2 rings: 1 + 6 + 12 nodes, 6·2² PFacets
    ({"kind": "disc", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 0.2, "rings": 2},
     19, 42, 24),
    # a tube: 3 rings of 8 nodes, 2·8·2 PFacets
    ({"kind": "tube", "start": [0, 0, 0], "axis": [1, 0, 0], "radius": 0.1, "length": 0.2,
      "around": 8, "along": 2}, 24, 56, 32),
    ({"kind": "sphere_shell", "center": [0, 0, 0], "radius": 0.1, "base": "octahedron",
      "subdivisions": 0}, 6, 12, 8),
    ({"kind": "mesh", "file": "square.obj", "merge_tolerance": 1e-6}, 4, 5, 2),
]


def every_kind_scene():
    structures = []
    for i, (spec, _, _, _) in enumerate(KINDS):
        s = {"name": f"s{i}", "material": "m", "node_radius": 0.005, **spec}
        # each far from the others
        s["placement"] = {"translate": [2.0 * i, 0, 0]}
        structures.append(s)
    # the other placement forms and the common keys
    structures[3]["placement"] = {"translate": [6.0, 0, 0], "rotate_deg": [0, 0, 90]}
    structures[4]["placement"] = {"translate": [8.0, 0, 0], "axis": [0, 0, 1],
                                  "angle_deg": 45, "scale": 2}
    structures[4]["velocity"] = [0, 0, -1.5]
    structures[4]["mask"] = 3
    return {
        "simulation": {"dt": "auto", "steps": 5},
        "materials": {"m": {"young": 1e7, "poisson": 0.3, "density": 1000,
                            "friction_angle_deg": 30}},
        "structures": structures,
    }


def vtp_counts(path):
    return ET.parse(path).getroot().find("PolyData/Piece").attrib


def test_every_structure_kind_from_a_dict(tmp_path):
    (tmp_path / "square.obj").write_text(SQUARE_OBJ)
    sim = flexdem.Simulation.from_dict(every_kind_scene(), base_dir=tmp_path)
    nodes = np.bincount(sim.structures, minlength=len(KINDS))
    assert list(nodes) == [k[1] for k in KINDS]
    links = sim.links()["nodes"]
    per_structure = np.bincount(sim.structures[links[:, 0]], minlength=len(KINDS))
    assert list(per_structure) == [k[2] for k in KINDS]
    paths = sim.write_frame(tmp_path / "frame")
    pfacets = vtp_counts(paths[2])
    assert int(pfacets["NumberOfPolys"]) == sum(k[3] for k in KINDS)
    # placement and velocity: the membrane scaled ×2, turned 45° and moving down
    membrane = sim.structures == 4
    np.testing.assert_allclose(sim.velocities[membrane], [[0, 0, -1.5]] * 9)
    corner = sim.positions[membrane][-1]  # (0.4, 0.4) · 2, turned 45° about z
    np.testing.assert_allclose(corner, [8.0, 0.8 * np.sqrt(2), 0], atol=1e-12)
    sim.run()
    assert sim.steps == 5


def test_builder_errors_name_the_structure_key(tmp_path):
    scene = every_kind_scene()
    scene["structures"] = [scene["structures"][3]]
    scene["structures"][0]["rings"] = 2
    with pytest.raises(flexdem.SceneError, match="`rings` does not apply to kind = \"net\""):
        flexdem.Simulation.from_dict(scene)
    scene["structures"][0].pop("rings")
    scene["structures"][0]["cells"] = [2, 0]
    with pytest.raises(flexdem.SceneError, match="structures.cells"):
        flexdem.Simulation.from_dict(scene)


def test_scene_dict_reads_a_file_to_change_and_run(tube_scene):
    scene = flexdem.scene_dict(tube_scene)
    assert scene["structures"][0]["kind"] == "tube"
    assert scene["spheres"][0]["velocity"] == [0, 0, -2]
    scene["spheres"][0]["velocity"] = [0, 0, -3.5]
    scene["simulation"]["duration"] = 0.001
    sim = flexdem.Simulation.from_dict(scene, base_dir=tube_scene.parent)
    impactor = int(np.argmax(sim.radii))
    np.testing.assert_array_equal(sim.velocities[impactor], [0, 0, -3.5])
    assert sim.particle_count == 337
    # the same scene, unchanged, is the file's
    same = flexdem.Simulation.from_dict(flexdem.scene_dict(tube_scene),
                                        base_dir=tube_scene.parent)
    original = flexdem.Simulation.from_scene(tube_scene)
    np.testing.assert_array_equal(same.positions, original.positions)
    assert same.dt == original.dt


def test_scene_dict_errors(tmp_path):
    with pytest.raises(flexdem.SceneError, match="cannot read the scene file"):
        flexdem.scene_dict(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[simulation\nsteps = 3\n")
    with pytest.raises(flexdem.SceneError, match="bad.toml"):
        flexdem.scene_dict(bad)
