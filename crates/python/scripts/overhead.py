"""Stepping from Python against the command line: ms/step of the same scene and steps.

    python crates/python/scripts/overhead.py [--cli target/release/flexdem] [--steps 5000]
        [--repeats 5] [--threads 2] [--scene examples/tube_impact_solid.toml]

Runs, interleaved `--repeats` times: `flexdem run --no-output --steps N` (its JSON summary's
wall time: stepping plus the end of the run, no setup), and from Python `sim.run(steps=N)`
without callback and with a callback every 100 steps (the time of `run` alone). Prints the
best and the median ms/step of each and the overhead of Python over the command line. Build
both in release (`cargo build --release -p flexdem-cli`, `pip install ./crates/python`).
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile
import time

import flexdem

ROOT = pathlib.Path(__file__).resolve().parents[3]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--cli", default=str(ROOT / "target/release/flexdem"))
    p.add_argument("--scene", default=str(ROOT / "examples/tube_impact_solid.toml"))
    p.add_argument("--steps", type=int, default=5000)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    a = p.parse_args()
    flexdem.set_threads(a.threads)
    flexdem.Simulation.from_scene(a.scene).run(steps=50)  # the pool started, pages warm
    times = {"cli": [], "python": [], "python, callback every 100": []}
    calls = []
    with tempfile.TemporaryDirectory() as tmp:
        summary = pathlib.Path(tmp) / "summary.json"
        for _ in range(a.repeats):
            subprocess.run(
                [a.cli, "run", "-q", "--no-output", "--threads", str(a.threads), "--steps",
                 str(a.steps), "--summary", str(summary), a.scene], check=True)
            s = json.loads(summary.read_text())
            assert s["steps_this_run"] == a.steps
            times["cli"].append(s["wall_time"])
            for key, callback in (("python", None),
                                  ("python, callback every 100", lambda sim: calls.append(sim.time))):
                sim = flexdem.Simulation.from_scene(a.scene)
                start = time.perf_counter()
                sim.run(steps=a.steps, callback=callback, every=100)
                times[key].append(time.perf_counter() - start)
                assert sim.steps == a.steps
    best_cli = min(times["cli"])
    med_cli = statistics.median(times["cli"])
    print(f"{a.scene}: {a.steps} steps, {a.threads} threads, {a.repeats} repeats")
    for key, t in times.items():
        best, med = min(t), statistics.median(t)
        print(f"  {key:28s} best {1e3 * best / a.steps:.4f} ms/step "
              f"({100 * (best / best_cli - 1):+.1f} %), median {1e3 * med / a.steps:.4f} ms/step "
              f"({100 * (med / med_cli - 1):+.1f} %)")


if __name__ == "__main__":
    main()
