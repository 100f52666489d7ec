"""Huygens water waves from Python: step a scene, change it between steps, read its fields.

    import huygens
    sim = huygens.Simulation("ring")          # a shipped scene, a scene file or a dict
    sim.run(until_s=1.0)                      # GIL released; Ctrl-C stops at a step boundary
    eta = sim.field("eta")                    # a read-only NumPy view of the solver's buffer

Simulation steps one solver (Huygens FFT propagator, SPH, shallow-water LBM) as ``huygens run``
does; its methods drop stones and steer ships as the viewer does. validate() runs the cases of
``huygens validate`` and returns their table; memory_estimate() sizes a scene as ``huygens run
--dry-run``; scenes() and scene() give the shipped scenes; huygens.reference holds the analytic
solutions the validation compares against. Errors carry what the CLI prints: SceneError (a
ValueError with the JSON path), RunStopped (stage and step), MemoryRefused (the figures),
CommandRefused. The package's page: python/README.md.
"""

import os as _os

# OpenMP threads that spin briefly at a barrier, then sleep, as every huygens program sets for
# itself (common/program.hpp, run_program): libgomp's longer default spin made 2 threads up to
# 20x slower than 1 on a loaded machine (docs/robustness.md). libgomp reads it when it loads, with
# the extension module below, so it is set here unless the user chose a policy.
if "OMP_WAIT_POLICY" not in _os.environ and "GOMP_SPINCOUNT" not in _os.environ:
    _os.environ["GOMP_SPINCOUNT"] = "3000"

from ._errors import CommandRefused, MemoryRefused, RunStopped, SceneError  # noqa: E402
from ._huygens import (  # noqa: E402
    Simulation,
    build_isa,
    cpu_isa,
    memory_estimate,
    reference,
    scene,
    scenes,
    validate,
    validation_cases,
)

import sys as _sys  # noqa: E402

_sys.modules[__name__ + ".reference"] = reference  # import huygens.reference works too
Simulation.__module__ = __name__  # help() and repr() say huygens.Simulation

__version__ = "0.1.0"

__all__ = [
    "Simulation",
    "SceneError",
    "RunStopped",
    "MemoryRefused",
    "CommandRefused",
    "scenes",
    "scene",
    "validate",
    "validation_cases",
    "memory_estimate",
    "reference",
    "build_isa",
    "cpu_isa",
]
