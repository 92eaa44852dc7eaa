"""Scenes from files, TOML text and dicts; errors as Python exceptions with the CLI's text."""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import flexdem
from conftest import ROOT, cantilever_dict


def test_from_scene_reads_the_tube_impact(tube_scene):
    sim = flexdem.Simulation.from_scene(tube_scene)
    assert sim.steps == 0 and sim.time == 0.0
    assert sim.dt > 0 and sim.dt <= sim.critical_dt
    # 336 tube nodes and the impactor
    assert sim.particle_count == 337
    assert sim.scene_file == tube_scene
    impactor = int(np.argmax(sim.radii))
    assert sim.radii[impactor] == pytest.approx(0.1)
    np.testing.assert_allclose(sim.positions[impactor], [0.4, 0, 0.207])
    np.testing.assert_allclose(sim.velocities[impactor], [0, 0, -2])
    assert "tube_impact_solid" in repr(sim)


def test_scene_error_is_a_value_error_with_position(tmp_path, cantilever_text):
    bad = cantilever_text.replace("poisson = 0.3", "poison = 0.3")
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    with pytest.raises(flexdem.SceneError) as info:
        flexdem.Simulation.from_scene(path)
    assert isinstance(info.value, ValueError)
    message = str(info.value)
    line = bad.splitlines().index("poison = 0.3") + 1
    assert message.startswith(f"{path}:{line}:1: ")
    assert "poison" in message and "poisson" in message  # the nearest known key


def test_scene_error_text_is_the_command_lines(tmp_path, cantilever_text):
    cli = os.environ.get("FLEXDEM_CLI") or shutil.which("flexdem")
    for candidate in ("target/debug/flexdem", "target/release/flexdem"):
        if cli is None and (ROOT / candidate).exists():
            cli = str(ROOT / candidate)
    if cli is None:
        pytest.skip("no flexdem command line built (cargo build -p flexdem-cli)")
    path = tmp_path / "bad.toml"
    path.write_text(cantilever_text.replace("young = 1e8", "young = -1e8"))
    with pytest.raises(flexdem.SceneError) as info:
        flexdem.Simulation.from_scene(path)
    out = subprocess.run([cli, "run", "--no-output", str(path)], capture_output=True, text=True)
    assert out.returncode == 2
    assert out.stderr.strip() == f"error: {info.value}"


def test_missing_file_is_a_scene_error(tmp_path):
    with pytest.raises(flexdem.SceneError, match="cannot read the scene file"):
        flexdem.Simulation.from_scene(tmp_path / "nothing.toml")


def test_from_toml_names_the_text(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)
    assert sim.particle_count == 11
    with pytest.raises(flexdem.SceneError, match=r"<string>:\d+:\d+: .*segments"):
        flexdem.Simulation.from_toml(cantilever_text.replace("segments = 10", "segments = -1"))


def test_from_dict_is_the_same_scene_as_the_text(cantilever_text):
    a = flexdem.Simulation.from_toml(cantilever_text)
    b = flexdem.Simulation.from_dict(cantilever_dict())
    a.run()
    b.run()
    assert a.steps == b.steps == 50
    assert np.array_equal(a.positions, b.positions)


def test_from_dict_takes_numpy_values_and_paths(tmp_path):
    scene = cantilever_dict()
    scene["structures"][0]["end"] = np.array([1.0, 0.0, 0.0])
    scene["structures"][0]["segments"] = np.int64(10)
    scene["output"] = {"directory": tmp_path / "out"}
    sim = flexdem.Simulation.from_dict(scene)
    assert sim.particle_count == 11
    assert sim.output_directory == tmp_path / "out"


def test_from_dict_checks_keys_as_the_files_do():
    scene = cantilever_dict()
    scene["materials"]["bar"]["yuong"] = 1e8
    with pytest.raises(flexdem.SceneError, match="yuong"):
        flexdem.Simulation.from_dict(scene)
    scene = cantilever_dict()
    scene["simulation"]["damping"] = None
    with pytest.raises(flexdem.SceneError, match=r"`simulation.damping`: None"):
        flexdem.Simulation.from_dict(scene)
    scene = cantilever_dict()
    scene["structures"][0]["start"] = [0, 0, object()]
    with pytest.raises(flexdem.SceneError, match=r"`structures\[0\].start\[2\]`"):
        flexdem.Simulation.from_dict(scene)
    with pytest.raises(flexdem.SceneError):
        flexdem.Simulation.from_dict([1, 2])


def test_to_toml_writes_the_keys():
    text = flexdem.to_toml(cantilever_dict())
    assert "[[structures]]" in text and 'kind = "chain"' in text


def test_relative_paths_start_from_base_dir(cantilever_text):
    text = cantilever_text + '\n[output]\ndirectory = "out"\n'
    sim = flexdem.Simulation.from_toml(text, base_dir=pathlib.Path("/tmp/somewhere"))
    assert sim.output_directory == pathlib.Path("/tmp/somewhere/out")


def test_a_dict_that_contains_itself_is_a_scene_error_not_a_crash():
    d = cantilever_dict()
    d["simulation"]["loop"] = d  # a cycle
    with pytest.raises(flexdem.SceneError, match="nested more than"):
        flexdem.Simulation.from_dict(d)
    looped = []
    looped.append(looped)
    with pytest.raises(flexdem.SceneError, match="nested more than"):
        flexdem.Simulation.from_dict({"simulation": {"x": looped}})
