# Type stubs of the huygens package (the extension module huygens._huygens and huygens/_errors.py).
import os
from typing import Any, Iterable, Optional, Union

import numpy as np
import numpy.typing as npt

from . import reference as reference

__version__: str

SceneLike = Union[str, os.PathLike[str], dict[str, Any]]

class SceneError(ValueError):
    """A bad scene; ``path`` is the JSON path of the offending value ("$.grid.margin")."""

    path: str
    def __init__(self, message: str, path: str = "$") -> None: ...

class RunStopped(RuntimeError):
    """A run stopped on a non-finite value or a negative LBM depth, at ``stage`` and ``step``."""

    stage: str
    step: int
    time_s: float
    def __init__(self, message: str, stage: str = "", step: int = 0, time_s: float = 0.0) -> None: ...

class MemoryRefused(MemoryError):
    """A scene refused before anything was allocated: the bytes needed and available, by part."""

    needed_bytes: int
    available_bytes: int
    parts: list[dict[str, Any]]
    key: str
    def __init__(
        self,
        message: str,
        needed_bytes: int = 0,
        available_bytes: int = 0,
        parts: Optional[list[dict[str, Any]]] = None,
        key: str = "",
    ) -> None: ...

class CommandRefused(ValueError):
    """A command the solver does not support or refused; ``command`` is its kind ("drop", ...)."""

    command: str
    def __init__(self, message: str, command: str = "") -> None: ...

class Simulation:
    """A scene's solver, stepped from Python (help(huygens.Simulation) has the details)."""

    def __init__(self, scene: SceneLike, *, fast_plans: bool = False) -> None: ...
    def step(self, n: int = 1) -> int:
        """Takes n full steps; returns the steps taken. Ctrl-C: KeyboardInterrupt after the step."""
    def run(self, until_s: float) -> int:
        """Steps until time_s >= until_s; returns the steps taken."""
    def reset(self) -> None:
        """Starts the scene again (a new solver; arrays of the old one stay readable)."""
    @property
    def time_s(self) -> float:
        """Simulated time (s)."""
    @property
    def step_count(self) -> int:
        """Full steps since the start or reset()."""
    @property
    def solver(self) -> str:
        """'huygens', 'sph' or 'lbm'."""
    @property
    def scene(self) -> str:
        """The scene's file, 'built-in NAME.json' or '<dict>'."""
    def field(self, name: str, *, copy: bool = False) -> npt.NDArray[np.float32]:
        """A field of the current state: a read-only view of the solver's buffer (values valid until
        the next step, field call, command or reset), or with copy=True a new writable array."""
    @property
    def fields(self) -> list[str]:
        """The names field() accepts."""
    def _field_address(self, name: str) -> int: ...
    @property
    def meta(self) -> dict[str, Any]:
        """What `huygens run` writes to meta.json."""
    def stats(self) -> list[dict[str, Any]]:
        """The stage table: stage, calls, total_ms, ms_per_call, transforms, bytes."""
    @property
    def memory(self) -> dict[str, Any]:
        """The solver's memory estimate and the bytes available."""
    def drop(self, x_m: float, y_m: float, radius_m: float = 0.05, depth_m: float = 0.01) -> None:
        """Drops a stone as the viewer does (CommandRefused when refused)."""
    def steer_ship(self, ship: int, x_m: float, y_m: float, vx_mps: float = 0.0, vy_mps: float = 0.0) -> None:
        """Steers a ship towards (x_m, y_m) as the viewer's drag does."""
    def toggle(self, feature: str, on: bool = True) -> None:
        """Huygens 'stokes' or 'wind' on or off."""
    def set_param(self, name: str, value: float) -> None:
        """SPH 'gravity_x', 'gravity_y', 'gravity_z' (m/s^2)."""
    def ship_poses(self) -> list[dict[str, float]]:
        """x_m, y_m, heading_rad, speed_mps of every ship now."""

def scenes() -> list[str]:
    """The shipped scenes' names."""

def scene(scene: Union[str, os.PathLike[str]]) -> dict[str, Any]:
    """A shipped scene or a scene file as a dict."""

def validate(cases: Union[None, str, Iterable[str]] = None, *, progress: bool = False) -> list[dict[str, Any]]:
    """Rows of `huygens validate`: case, quantity, measured, expected, error, tolerance, passed, judged."""

def validation_cases() -> list[dict[str, str]]:
    """name, solver, description of every validation case."""

def memory_estimate(scene: SceneLike, ranks: int = 1) -> dict[str, Any]:
    """The memory per rank on `ranks` MPI ranks, as `huygens run --dry-run`."""

def build_isa() -> str:
    """The instruction set the package was compiled for."""

def cpu_isa() -> str:
    """This CPU's model and vector extensions."""
