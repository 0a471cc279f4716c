"""Exceptions raised by unimo. Each carries the diagnostic's ``code`` (``E2003``,
``E4006``...), ``message``, ``location`` (``file:line:col`` or ``None``) and
``rendered`` (every diagnostic with its source line, as the command line prints it)."""

from __future__ import annotations

from typing import Any, Optional


class UnimoError(Exception):
    """Base class of unimo's errors."""

    def __init__(
        self,
        code: str,
        message: str,
        location: Optional[str] = None,
        rendered: Optional[str] = None,
    ) -> None:
        super().__init__(code, message, location, rendered)
        self.code = code
        self.message = message
        self.location = location
        self.rendered = rendered if rendered is not None else f"error[{code}]: {message}"
        #: For a failed simulation: the :class:`unimo.Result` with the rows computed
        #: before the failure.
        self.result: Any = None

    def __str__(self) -> str:
        where = f" ({self.location})" if self.location else ""
        return f"[{self.code}] {self.message}{where}"


class ModelError(UnimoError):
    """The model has errors: syntax, names, types, balance, structure (codes E1xxx-E3xxx)."""


class UsageError(UnimoError, ValueError):
    """A request was wrong: an unknown parameter, a value of the wrong type, a missing
    file, an unknown output or method (codes E00xx)."""


class SimulationError(UnimoError):
    """The simulation failed (codes E4xxx); ``.result`` keeps the rows computed before."""


def from_tuple(error: tuple) -> UnimoError:
    """The exception for a sweep row's error ``(kind, code, message, location, rendered)``."""
    kind, code, message, location, rendered = error
    cls = {"model": ModelError, "usage": UsageError, "simulation": SimulationError}[kind]
    return cls(code, message, location, rendered)
