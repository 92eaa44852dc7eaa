"""Running: steps, durations, callbacks that stop a run, the GIL, the worker threads."""

import subprocess
import sys
import threading

import pytest

import flexdem


def test_run_steps_and_step(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)
    assert sim.run(steps=20) == 20
    assert sim.steps == 20
    sim.step()
    assert sim.steps == 21
    assert sim.time > 0


def test_run_without_length_goes_to_the_scenes_and_steps_past_it(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)  # steps = 50
    assert not sim.done
    assert sim.run() == 50
    assert sim.done and sim.steps == 50
    assert sim.run() == 0
    # an explicit length goes on past the scene's
    assert sim.run(steps=10) == 10
    assert sim.steps == 60


def test_run_duration(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)
    duration = 7.5 * sim.dt
    sim.run(duration=duration)
    assert sim.time >= duration
    assert sim.time - sim.dt < duration
    with pytest.raises(ValueError):
        sim.run(steps=1, duration=1.0)
    with pytest.raises(ValueError):
        sim.run(duration=-1.0)


def test_callback_every_k_steps_sees_the_state(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)
    seen = []

    def record(s):
        assert s is sim
        seen.append((s.steps, s.positions[-1, 2]))

    sim.run(steps=100, callback=record, every=10)
    assert [steps for steps, _ in seen] == list(range(10, 101, 10))
    assert seen[-1][1] < 0  # the tip goes down


def test_callback_returning_false_stops(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)
    calls = []

    def stop_at_30(s):
        calls.append(s.steps)
        return s.steps < 30

    assert sim.run(steps=1000, callback=stop_at_30, every=10) == 30
    assert calls == [10, 20, 30]
    assert sim.steps == 30


def test_callback_that_raises_stops_and_propagates(cantilever_text):
    sim = flexdem.Simulation.from_toml(cantilever_text)

    def boom(s):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        sim.run(steps=100, callback=boom, every=5)
    assert sim.steps == 5
    # the simulation goes on afterwards
    sim.run(steps=5)
    assert sim.steps == 10


def test_gil_is_released_while_stepping(tube_scene):
    sim = flexdem.Simulation.from_scene(tube_scene)
    sim.run(steps=20)  # the pool started, caches warm
    thread = threading.Thread(target=sim.run, kwargs={"steps": 300})
    counted = 0
    thread.start()
    while thread.is_alive():
        counted += 1
    thread.join()
    assert sim.steps == 320
    # with the GIL held by the stepping thread this loop would barely run
    assert counted > 1000


def test_set_threads_once_before_the_first_simulation(cantilever_text):
    script = f"""
import flexdem
assert flexdem.set_threads(1) == 1
assert flexdem.set_threads(1) == 1
try:
    flexdem.set_threads(2)
except RuntimeError as e:
    assert "already set to 1" in str(e), e
else:
    raise AssertionError("set_threads(2) after set_threads(1) passed")
try:
    flexdem.set_threads(0)
except ValueError:
    pass
else:
    raise AssertionError("set_threads(0) passed")
assert flexdem.threads() == 1
sim = flexdem.Simulation.from_toml({cantilever_text!r}, threads=1)
sim.run()
print("ok", sim.steps)
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["ok", "50"]


def test_threads_argument_after_the_pool_started_is_an_error(cantilever_text):
    script = f"""
import flexdem
flexdem.Simulation.from_toml({cantilever_text!r}).run()
try:
    flexdem.set_threads(3)
except RuntimeError as e:
    print("refused")
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "refused"
