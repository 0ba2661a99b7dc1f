"""User-facing errors: every message names the field, the value and what is allowed."""

from __future__ import annotations

import difflib
from typing import Any


class QuenchsimError(Exception):
    """Base class of every error a user can cause; the CLI prints it on one line and exits 2."""


class InputError(QuenchsimError, ValueError):
    """A bad input value: ``InputError("geometry.od_mm", 10.0, "must exceed geometry.id_mm = 20")``; with ``file``
    (the input file it came from, set by :func:`quenchsim.inputs.reading` when the error leaves that file's reading)
    the message starts with it: ``cases/ring.toml: geometry.od_mm = 10.0: must exceed geometry.id_mm = 20``."""

    def __init__(self, field: str, value: Any, allowed: str, file: str | None = None) -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        self.file = file
        super().__init__(self._message())

    def _message(self) -> str:
        where = f"{self.file}: " if self.file else ""
        return f"{where}{self.field} = {self.value!r}: {self.allowed}"

    def in_file(self, file: str) -> "InputError":
        """This error, naming ``file`` (unless it names one already: the innermost file read is the one at fault)."""
        if self.file is None:
            self.file = file
            self.args = (self._message(),)
        return self


class SolverError(QuenchsimError, RuntimeError):
    """A solver that did not converge; the message says where it stopped."""


def require(condition: object, field: str, value: Any, allowed: str) -> None:
    """Raise :class:`InputError` unless ``condition`` holds."""
    if not condition:
        raise InputError(field, value, allowed)


def require_known_keys(table: Any, allowed: tuple[str, ...], where: str) -> None:
    """Raise :class:`InputError` for the first key of ``table`` (the input's ``[where]`` table) not in ``allowed``:
    a misspelt key is an error, never ignored."""
    for key in table:
        require(key in allowed, f"{where}.{key}", table[key],
                f"unknown key; [{where}] takes {', '.join(allowed)}{did_you_mean(key, allowed)}")


def did_you_mean(name: str, known: Any) -> str:
    """``"; did you mean NAME?"`` for the known name closest to a misspelt ``name`` (difflib's ratio >= 0.75), else
    ``""``: the end of an unknown-key message."""
    close = difflib.get_close_matches(str(name), [str(k) for k in known], n=1, cutoff=0.75)
    return f"; did you mean {close[0]}?" if close else ""


class RunInterrupted(QuenchsimError):
    """A run stopped by Ctrl-C or SIGTERM; what it had computed is in its folder (status "interrupted")."""
