"""The tracked series as numpy arrays (the command line's series.csv), and frames and
series written from Python at any time."""

import base64
import csv
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import flexdem

DT = 1e-4
G = 9.81

FALLING = f"""
[simulation]
dt = {DT}
steps = 95
gravity = [0, 0, -{G}]

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

[output]
directory = "out"
series_every = 10

[[output.series]]
name = "rock"
quantity = "position"
of = {{ spheres = "rock" }}

[[output.series]]
name = "e"
quantity = "energy"

[[output.series]]
name = "n"
quantity = "contacts"
"""


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    header, values = rows[0], np.array(rows[1:], dtype=float)
    return {name: values[:, i] for i, name in enumerate(header)}


def test_series_columns_and_known_values(tmp_path):
    sim = flexdem.Simulation.from_toml(FALLING, base_dir=tmp_path)
    s = sim.series()
    assert list(s) == ["time_s", "step", "rock_x_m", "rock_y_m", "rock_z_m"] + [
        f"e_{t}_J" for t in ("kinetic_translation", "kinetic_rotation", "elastic_links",
                             "elastic_contacts", "gravity_work", "load_work",
                             "boundary_work", "contact_births", "damping",
                             "links_dissipated", "friction", "contact_damping",
                             "contact_releases", "balance")] + ["n_count"]
    assert all(len(a) == 0 for a in s.values())  # nothing recorded before the run

    sim.run(steps=40)
    s = sim.series()
    np.testing.assert_array_equal(s["step"], [0, 10, 20, 30, 40])
    assert s["step"].dtype == np.int64 and s["time_s"].dtype == np.float64
    np.testing.assert_allclose(np.diff(s["time_s"]), 10 * DT, rtol=1e-12)
    # free fall, leapfrog: z_n = z_0 − g·dt²·n(n+1)/2
    n = s["step"]
    np.testing.assert_allclose(s["rock_z_m"], 1 - G * DT**2 * n * (n + 1) / 2, rtol=1e-14)
    # the last row is the state read directly
    assert s["rock_z_m"][-1] == sim.positions[0, 2]
    assert s["e_kinetic_translation_J"][-1] == sim.energy()["kinetic_translation"]
    assert (s["n_count"] == 0).all()

    # the run's end adds the last row, as the CSV's (95 is off the 10-step schedule)
    sim.run()
    sim.finish()
    np.testing.assert_array_equal(sim.series()["step"], list(range(0, 100, 10)) + [95])


def test_series_are_the_csv_the_command_line_writes(tmp_path):
    with_files = flexdem.Simulation.from_toml(FALLING, base_dir=tmp_path, output=True)
    with_files.run()
    summary = with_files.finish()
    written = read_csv(tmp_path / "out" / "series.csv")
    s = with_files.series()
    assert list(s) == list(written)
    for name in s:
        np.testing.assert_array_equal(s[name], written[name], err_msg=name)
    # the summary's tracked values are the last row
    assert summary["tracked"]["rock"]["rock_z_m"] == s["rock_z_m"][-1]

    # without output files the same series, and write_series writes the same file
    quiet = flexdem.Simulation.from_toml(FALLING, base_dir=tmp_path / "q")
    quiet.run()
    quiet.finish()
    assert not (tmp_path / "q" / "out").exists()
    path = quiet.write_series(tmp_path / "again.csv")
    assert path.read_text() == (tmp_path / "out" / "series.csv").read_text()
    # the run's own CSV is not overwritten
    with pytest.raises(ValueError, match="writes this file itself"):
        with_files.write_series(tmp_path / "out" / "series.csv")
    with pytest.raises(ValueError, match="writes this file itself"):
        with_files.write_series(tmp_path / "out" / ".." / "out" / "series.csv")


def test_resumed_series_continue_the_csv(tmp_path):
    sim = flexdem.Simulation.from_toml(FALLING, base_dir=tmp_path, output=True)
    sim.run(steps=30)
    sim.save_checkpoint(tmp_path / "c.flexdem")
    resumed = flexdem.Simulation.resume(tmp_path / "c.flexdem", output=True)
    np.testing.assert_array_equal(resumed.series()["step"], [0, 10, 20, 30])
    resumed.run(steps=20)
    np.testing.assert_array_equal(resumed.series()["step"], [0, 10, 20, 30, 40, 50])
    quiet = flexdem.Simulation.resume(tmp_path / "c.flexdem")
    quiet.run(steps=20)
    np.testing.assert_array_equal(quiet.series()["step"], [30, 40, 50])


def test_a_run_resumed_at_its_end_continues_the_csv_once_moved_on(tmp_path):
    sim = flexdem.Simulation.from_toml(FALLING, base_dir=tmp_path, output=True)
    sim.run()  # to the scene's 95 steps
    sim.save_checkpoint(tmp_path / "c.flexdem")
    sim.finish()  # adds the row of step 95, off the schedule
    csv_path = tmp_path / "out" / "series.csv"
    written = csv_path.read_text()
    resumed = flexdem.Simulation.resume(tmp_path / "c.flexdem", output=True)
    assert resumed.steps == 95
    np.testing.assert_array_equal(resumed.series()["step"], np.arange(0, 91, 10))
    assert csv_path.read_text() == written  # left as the run wrote it
    resumed.run(steps=20)
    resumed.finish()
    steps = list(range(0, 111, 10)) + [115]
    np.testing.assert_array_equal(resumed.series()["step"], steps)
    with open(csv_path) as f:
        assert [int(float(row["step"])) for row in csv.DictReader(f)] == steps
    # the same file as a run of 115 steps without a stop
    whole = flexdem.Simulation.from_toml(FALLING, base_dir=tmp_path / "w", output=True)
    whole.run(steps=115)
    whole.finish()
    assert (tmp_path / "w" / "out" / "series.csv").read_text() == csv_path.read_text()


def pieces(path):
    """The attributes of the <Piece> of a .vtp file."""
    return ET.parse(path).getroot().find("PolyData/Piece").attrib


def frame_points(path):
    """The points of a .vtp file written by flexdem (inline binary: a UInt64 byte count,
    then little-endian float64 values, the whole base64)."""
    array = ET.parse(path).getroot().find("PolyData/Piece/Points/DataArray")
    raw = base64.b64decode(array.text.strip())
    count = int(np.frombuffer(raw[:8], dtype="<u8")[0])
    return np.frombuffer(raw[8:8 + count], dtype="<f8").reshape(-1, 3)


def test_write_frame_at_any_time(tube_scene, tmp_path):
    sim = flexdem.Simulation.from_scene(tube_scene, output=tmp_path / "run")
    sim.run(steps=100)  # the scene writes a frame every 100 steps
    paths = sim.write_frame(tmp_path / "mine")
    assert [p.name for p in paths] == ["particles_000100.vtp", "connections_000100.vtp",
                                       "pfacets_000100.vtp", "contacts_000100.vtp"]
    assert int(pieces(paths[0])["NumberOfPoints"]) == sim.particle_count == 337
    assert int(pieces(paths[1])["NumberOfLines"]) == len(sim.links()["nodes"]) == 976
    assert int(pieces(paths[2])["NumberOfPolys"]) == 640
    assert int(pieces(paths[3])["NumberOfLines"]) == len(sim.contacts()["normal_force"])
    # the files the run itself wrote at this step, byte for byte
    for p in paths:
        assert p.read_bytes() == (tmp_path / "run" / p.name).read_bytes(), p.name

    # off the schedule, into the output folder by default
    sim.run(steps=7)
    paths = sim.write_frame()
    assert paths[0] == tmp_path / "run" / "particles_000107.vtp"
    assert all(p.is_file() for p in paths)
    # the particle positions in the frame are the state's
    np.testing.assert_array_equal(frame_points(paths[0]), sim.positions)
