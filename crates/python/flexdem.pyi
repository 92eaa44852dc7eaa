"""Type stubs of the flexdem module (a Rust extension built with maturin: see src/lib.rs).

flexdem is a discrete element method engine for deformable structures. A script builds a
Simulation from a scene file, TOML text or a dict with the keys of a scene file, runs it in
stages with callbacks, changes loads and boundaries between stages, and reads the state as
numpy arrays. Lengths in m, times in s, forces in N, energies in J.
"""

import os
import pathlib
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]
_Vec3 = Union[Sequence[float], npt.NDArray[np.float64]]
_Output = Union[None, bool, _Path]

__version__: str

class SceneError(ValueError):
    """Bad input: a scene (file, TOML text or dict), a load, a checkpoint or an argument that
    cannot be simulated. The message is the command line's, with the file, line, column and
    key."""

class SimulationError(RuntimeError):
    """A run that went wrong: an unstable step, energy created beyond the tolerance, output or
    checkpoint files that cannot be written."""

def set_threads(n: int) -> int:
    """Sets the number of worker threads of the process, once, before the first simulation;
    returns the number in use. RuntimeError when the pool already runs with another count."""

def threads() -> int:
    """The number of worker threads in use (the machine's cores unless set)."""

def to_toml(scene: Mapping[str, Any]) -> str:
    """A scene dict written as the TOML text Simulation.from_dict reads (where the line numbers
    of its errors point)."""

def scene_dict(path: _Path) -> dict[str, Any]:
    """The scene file at `path` as a dict with the keys of the file, to change and give to
    Simulation.from_dict(scene, base_dir=path.parent)."""

class Simulation:
    """A simulation: a scene set up for running, with its output and checkpoints.

    Build one with from_scene, from_toml, from_dict or resume; step it with run or step; read
    its state as numpy arrays (positions, contacts(), energy(), series(), ...)."""

    # -- set-up --------------------------------------------------------------------------
    @staticmethod
    def from_scene(
        path: _Path, *, output: _Output = None, threads: Optional[int] = None
    ) -> "Simulation":
        """Reads the scene file at `path`. `output`: None/False writes nothing, True the
        scene's [output] into its folder, a folder the same output there."""
    @staticmethod
    def from_toml(
        text: str,
        base_dir: Optional[_Path] = None,
        *,
        output: _Output = None,
        threads: Optional[int] = None,
    ) -> "Simulation":
        """A scene given as TOML text; relative paths start from `base_dir` (default: the
        current folder); errors name the text `<string>`."""
    @staticmethod
    def from_dict(
        scene: Mapping[str, Any],
        base_dir: Optional[_Path] = None,
        *,
        output: _Output = None,
        threads: Optional[int] = None,
    ) -> "Simulation":
        """A scene given as a dict with the keys of a scene file (values: str, int, float,
        bool, lists, tuples, dicts, numpy arrays and scalars, paths)."""
    @staticmethod
    def resume(
        path: _Path, *, output: bool = False, threads: Optional[int] = None
    ) -> "Simulation":
        """Continues the checkpoint at `path` bit-identically; `output=True` continues the
        checkpointed run's output."""

    # -- running -------------------------------------------------------------------------
    def run(
        self,
        steps: Optional[int] = None,
        duration: Optional[float] = None,
        callback: Optional[Callable[["Simulation"], Optional[bool]]] = None,
        every: int = 100,
    ) -> int:
        """Runs `steps` steps, or `duration` s, or (neither) to the scene's run length;
        returns the steps done. `callback(sim)` every `every` steps and at the end stops the
        run by returning False. The GIL is released while the engine steps."""
    def step(self) -> None:
        """One step."""
    def save_checkpoint(self, path: _Path) -> None:
        """Writes a checkpoint of the current state (flexdem resume continues it too)."""
    def finish(self) -> dict[str, Any]:
        """Ends the run: the last output frame and row, the .pvd and the plot; returns the
        summary (what flexdem run --summary writes)."""

    # -- changes between stages ----------------------------------------------------------
    def set_damping(self, damping: float) -> None:
        """Cundall damping coefficient, 0 <= d < 1."""
    def set_gravity(self, gravity: _Vec3) -> None:
        """Gravity [gx, gy, gz] (m/s²)."""
    def set_wall_velocity(self, wall: int, velocity: _Vec3) -> None:
        """Velocity of wall `wall` (its index in the scene), m/s."""
    def impose_velocity(self, particles: Sequence[int], velocity: _Vec3) -> None:
        """Imposes a velocity (m/s) on `particles`; the supports' work is `boundary_work`."""
    def set_velocity(self, particles: Sequence[int], velocity: _Vec3) -> None:
        """Sets the velocity (m/s) of `particles` by hand: a kick on free DOFs, whose change of
        kinetic energy is `load_work` (from the first step on), a new imposed velocity on
        blocked ones (`boundary_work`). All or nothing."""
    def set_angular_velocity(self, particles: Sequence[int], spin: _Vec3) -> None:
        """Sets the angular velocity (rad/s) of `particles` by hand, as `set_velocity`."""
    def set_wall_servo(
        self,
        wall: int,
        stress: float,
        area: float,
        max_speed: float,
        gain: Optional[float] = None,
    ) -> None:
        """Wall `wall` holds the normal stress `stress` (Pa) over `area` (m²) by a servo."""
    def add_pressure(
        self,
        structure: str,
        pressure: float,
        flip: bool = False,
        ramp: Optional[Tuple[float, float]] = None,
    ) -> None:
        """A pressure (Pa) on every PFacet of a structure; `flip=True` pushes inward."""
    def clear_pressures(self) -> None:
        """Removes every pressure."""
    def pressures(self) -> List[Dict[str, Any]]:
        """The pressures: pfacets, pressure, flip, ramp, current (Pa now)."""
    def add_load(
        self,
        *,
        select: Mapping[str, Any],
        force: Optional[_Vec3] = None,
        total_force: Optional[_Vec3] = None,
        moment: Optional[_Vec3] = None,
        ramp: Optional[Mapping[str, float]] = None,
    ) -> None:
        """Adds a load with the keys of a scene file's [[loads]] table: `select` (structure
        with side, spheres, ids, box, plane; box and plane by the current positions),
        `force` on each particle or `total_force` shared equally, `moment` on each, `ramp`
        {"start": s, "duration": s}. SceneError with the scene reader's message."""
    def set_loads(self, loads: Iterable[Mapping[str, Any]]) -> None:
        """Replaces every load by `loads` (dicts with the keys of add_load; [] removes them
        all); nothing changes on an error."""
    def loads(self) -> list[dict[str, Any]]:
        """The loads acting, as dicts set_loads takes back: select={"ids": array}, force and
        moment on each particle (arrays of 3), ramp when ramped."""

    # -- state ---------------------------------------------------------------------------
    @property
    def time(self) -> float:
        """Simulated time (s)."""
    @property
    def steps(self) -> int:
        """Steps done since the start of the simulation."""
    @property
    def dt(self) -> float:
        """The current time step (s)."""
    @property
    def critical_dt(self) -> float:
        """The critical time step at the last estimate (s)."""
    @property
    def done(self) -> bool:
        """Whether the scene's run length is reached."""
    @property
    def particle_count(self) -> int:
        """Number of particles (free spheres and structure nodes)."""
    @property
    def warnings(self) -> list[str]:
        """Warnings raised by the engine so far."""
    @property
    def scene_file(self) -> pathlib.Path:
        """The scene file the simulation came from."""
    @property
    def output_directory(self) -> pathlib.Path:
        """The output folder."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """Particle centres, n×3 (m); a copy."""
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """Particle velocities, n×3 (m/s)."""
    @property
    def angular_velocities(self) -> npt.NDArray[np.float64]:
        """Particle angular velocities, n×3 (rad/s)."""
    @property
    def forces(self) -> npt.NDArray[np.float64]:
        """Total force on each particle at the last step, n×3 (N)."""
    @property
    def radii(self) -> npt.NDArray[np.float64]:
        """Particle radii, n (m)."""
    @property
    def masses(self) -> npt.NDArray[np.float64]:
        """Particle masses, n (kg)."""
    @property
    def structures(self) -> npt.NDArray[np.int64]:
        """The structure of each particle, n; -1 for a free sphere."""
    def contacts(self) -> dict[str, npt.NDArray[Any]]:
        """The contacts of the last step: pairs and kinds (m×2), points and normals (m×3),
        normal_force (m, compression positive), shear_force and force (m×3, on body 2)."""
    def links(self) -> dict[str, npt.NDArray[Any]]:
        """The beam links: nodes (m×2), status (m: 0 cohesive, 1 frictional, 2 broken),
        normal_force (m, compression positive), shear_force and force (m×3, on node 2)."""
    def energy(self) -> dict[str, float]:
        """Every energy term (J), then stored, put_in, taken_out, balance,
        initial_balance, lowest_balance, scale, relative_balance_error and late_births
        (what contacts found late put in after the first step; the energy watch stops a
        run when it passes the tolerance times the scale)."""
    def series(self) -> dict[str, npt.NDArray[Any]]:
        """The tracked series, one array per column of series.csv: time_s, step (int64),
        then NAME_COMPONENT_UNIT columns; recorded whether or not output is written."""

    # -- files ---------------------------------------------------------------------------
    def write_series(self, path: _Path) -> pathlib.Path:
        """Writes the series recorded so far as the command line's CSV to `path`."""
    def write_frame(self, directory: Optional[_Path] = None) -> list[pathlib.Path]:
        """Writes the VTK frame of the current state (particles_N.vtp, connections_N.vtp,
        pfacets_N.vtp, contacts_N.vtp) into `directory` (default: the output folder)."""
