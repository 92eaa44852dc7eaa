"""Checkpoints that resume bit-identically, and the command line's output files."""

import csv

import numpy as np
import pytest

import flexdem


def test_resume_continues_bit_identically(tube_scene, tmp_path):
    checkpoint = tmp_path / "state.flexdem"
    sim = flexdem.Simulation.from_scene(tube_scene)
    sim.run(steps=200)
    sim.save_checkpoint(checkpoint)
    sim.run(steps=200)

    resumed = flexdem.Simulation.resume(checkpoint)
    assert resumed.steps == 200
    resumed.run(steps=200)
    assert resumed.steps == sim.steps == 400
    assert resumed.time == sim.time
    assert np.array_equal(resumed.positions, sim.positions)
    assert np.array_equal(resumed.velocities, sim.velocities)
    assert resumed.energy() == sim.energy()
    # the checkpoint keeps the scene's run length: a run to its end ends where the scene says
    assert resumed.scene_file == tube_scene


def test_bad_checkpoint_is_a_scene_error(tmp_path):
    path = tmp_path / "broken.flexdem"
    path.write_bytes(b"not a checkpoint")
    with pytest.raises(flexdem.SceneError):
        flexdem.Simulation.resume(path)


def test_output_as_the_command_line_writes_it(tube_scene, tmp_path):
    out = tmp_path / "out"
    sim = flexdem.Simulation.from_scene(tube_scene, output=out)
    assert sim.output_directory == out
    sim.run(steps=200)
    summary = sim.finish()
    assert summary["status"] == "completed" and summary["steps"] == 200
    names = {p.name for p in out.iterdir()}
    pvd = [n for n in names if n.endswith(".pvd")]
    vtp = [n for n in names if n.endswith(".vtp")] + [
        p.name for p in out.rglob("*.vtp")
    ]
    assert pvd and vtp
    series = [p for p in out.iterdir() if p.suffix == ".csv"]
    assert series
    with series[0].open() as f:
        rows = list(csv.reader(f))
    # series_every = 10: steps 0, 10, ..., 200
    assert len(rows) - 1 == 21
    assert any(n.endswith(".png") for n in names)


def test_no_output_by_default(cantilever_text, tmp_path):
    text = cantilever_text + '\n[output]\ndirectory = "out"\nseries_every = 10\n'
    sim = flexdem.Simulation.from_toml(text, base_dir=tmp_path)
    sim.run()
    sim.finish()
    assert not (tmp_path / "out").exists()
    sim = flexdem.Simulation.from_toml(text, base_dir=tmp_path, output=True)
    sim.run()
    sim.finish()
    assert (tmp_path / "out").is_dir()
