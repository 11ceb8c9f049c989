"""The exceptions of flocking: each message is the one the ``flocking`` CLI prints."""

from typing import Optional, Tuple


class FlockError(Exception):
    """Any error of flocking."""


class ScenarioError(FlockError, ValueError):
    """An invalid scenario: a file that cannot be read, RON that is not a scenario, or a value
    out of its domain. The message names the field, its value, why and the fix; ``field`` is the
    field's dotted path (``"alpha.d"``), or None when the error names none."""

    def __init__(self, message: str, field: Optional[str] = None) -> None:
        super().__init__(message)
        self.field = field


class NumericalError(FlockError, ArithmeticError):
    """A numerical blow-up: after ``step`` steps (time ``t``) agent ``agent`` is not finite or
    outran the interaction range in one step; the message gives the likely cause."""

    def __init__(self, message: str, step: int, t: float, agent: int) -> None:
        super().__init__(message)
        self.step = step
        self.t = t
        self.agent = agent


class RunDirectoryError(FlockError, OSError):
    """A run directory that cannot be written or read; ``path`` names it (or the file at
    fault)."""

    def __init__(self, message: str, path: Optional[str] = None) -> None:
        super().__init__(message)
        self.path = path


class ControlsError(FlockError, ValueError):
    """A ``controls`` function returned something other than the inputs u: not an array of
    floats, an array of another shape than ``expected`` (n agents × dim), or a value that is not
    finite. ``given`` is the shape returned (None when it was not an array)."""

    def __init__(self, message: str, expected: Tuple[int, int], given: Optional[Tuple[int, ...]] = None) -> None:
        super().__init__(message)
        self.expected = tuple(expected)
        self.given = None if given is None else tuple(given)


class SimulationError(FlockError, RuntimeError):
    """A :class:`Simulation` that cannot go on: Ctrl-C cut one of its steps short after the step
    had changed the state (inside a vehicle's inner steps or the conditions' stage), which is
    therefore between two steps."""


for _error in (
    FlockError,
    ScenarioError,
    NumericalError,
    RunDirectoryError,
    ControlsError,
    SimulationError,
):
    _error.__module__ = "flocking"
