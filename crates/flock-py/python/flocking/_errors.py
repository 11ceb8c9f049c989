"""The exceptions of flocking: each message is the one the ``flocking`` CLI prints."""

from typing import Optional


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


for _error in (FlockError, ScenarioError, NumericalError, RunDirectoryError):
    _error.__module__ = "flocking"
