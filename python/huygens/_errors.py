"""The exceptions of the huygens package; each carries what ``huygens run`` prints."""


class SceneError(ValueError):
    """A bad scene (``huygens run`` exits 2): ``path`` is the JSON path of the offending value
    (``"$.grid.margin"``, ``"$.drops[2].t_s"``; ``"$"`` for a syntax error), ``str(e)`` the
    full message."""

    def __init__(self, message: str, path: str = "$"):
        super().__init__(message)
        self.path = path


class RunStopped(RuntimeError):
    """A run stopped on a non-finite value or a negative LBM depth (``huygens run`` exits 3):
    ``stage`` names the stage (``"propagate"``, ``"drops"``, ``"negative_depth"``, ...), ``step``
    the step, ``time_s`` the simulated time of the state before it. The simulation refuses to
    step on; ``Simulation.reset()`` starts it again."""

    def __init__(self, message: str, stage: str = "", step: int = 0, time_s: float = 0.0):
        super().__init__(message)
        self.stage = stage
        self.step = step
        self.time_s = time_s


class MemoryRefused(MemoryError):
    """A scene that needs more memory than is available, refused before anything was allocated
    (``huygens run`` exits 4). ``needed_bytes`` and ``available_bytes`` are the two figures,
    ``parts`` the estimate by part (dicts with ``name``, ``bytes`` and ``key``, the JSON path
    of the key that sets the part's size) and ``key`` the key of the largest part."""

    def __init__(self, message: str, needed_bytes: int = 0, available_bytes: int = 0,
                 parts: list = None, key: str = ""):
        super().__init__(message)
        self.needed_bytes = needed_bytes
        self.available_bytes = available_bytes
        self.parts = parts or []
        self.key = key


class CommandRefused(ValueError):
    """A command (drop, steer_ship, toggle, set_param) the solver does not support or refused
    (outside the grid, no such ship or feature); ``command`` is its kind (``"drop"``, ...)."""

    def __init__(self, message: str, command: str = ""):
        super().__init__(message)
        self.command = command


for _cls in (SceneError, RunStopped, MemoryRefused, CommandRefused):
    _cls.__module__ = "huygens"  # tracebacks say huygens.SceneError
