"""The example scripts of examples/python, run small."""

import importlib.util
import subprocess
import sys

import pytest

from conftest import EXAMPLES

SWEEP = EXAMPLES / "python" / "parameter_sweep.py"


def load(path):
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_crater_depth_of_the_parameter_sweep():
    sweep = load(SWEEP)
    # at rest and without gravity nothing moves: no crater at all
    depth, error = sweep.crater_depth(0.0, duration=0.005)
    assert depth == 0.0 and error == 0.0
    # the scene's own speed, 2 m/s: the validation case's crater (YADE's run of the same
    # scene: largest tube node displacement 0.143 m; flexdem's report: 0.147 m)
    depth, error = sweep.crater_depth(2.0, duration=0.3)
    assert depth == pytest.approx(0.143, rel=0.1)
    assert abs(error) < 5e-3
    # a short sweep: deeper the faster
    rows = sweep.sweep([1.0, 3.0], duration=0.02, every=5)
    (_, slow, _), (_, fast, _) = rows
    assert 0 < slow < fast


def test_parameter_sweep_script_prints_the_table_and_plots(tmp_path):
    png = tmp_path / "sweep.png"
    out = subprocess.run(
        [sys.executable, str(SWEEP), "--speeds", "0", "2", "--duration", "0.004",
         "--png", str(png)],
        capture_output=True, text=True, timeout=300,
    )
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("2 runs of 0.004 s")
    assert lines[2].split()[:2] == ["0.000", "0.00000"]
    assert float(lines[3].split()[0]) == 2.0
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        assert "no plot" in out.stdout
    else:
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
