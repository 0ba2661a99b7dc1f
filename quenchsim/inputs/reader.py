"""The one place quenchsim parses TOML: a file or a value, with errors that name the file.

Every input file (a case, a steel, a quenchant, a bath layout, a sweep, ...) is read by :func:`read_toml`; what
its tables mean is declared once in :mod:`quenchsim.inputs` and checked by :func:`quenchsim.inputs.declare.from_table`.
An :class:`~quenchsim.errors.InputError` raised while a file's content is interpreted (inside :func:`reading`) names
that file: ``materials/SUJ3.toml: kinetics.martensite.alpha_per_K = -1.0: must be > 0``.
"""

from __future__ import annotations

import contextlib
import tomllib
from collections.abc import Iterator
from importlib import resources
from pathlib import Path
from typing import Any

from quenchsim.errors import InputError


def read_toml(path: str | Path, what: str = "file") -> dict[str, Any]:
    """The table of TOML file ``path``; a missing file or bad TOML is an :class:`InputError` naming ``what`` (the
    option or key that named the file) and the file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(what, str(path), "file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(what, str(path), f"cannot be read ({exc})") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(what, str(path), f"is not valid TOML ({exc})") from None


def parse_toml(text: str, what: str) -> dict[str, Any]:
    """The table of TOML ``text`` (a file's content read elsewhere, e.g. package data); bad TOML names ``what``."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(what, "", f"is not valid TOML ({exc})") from None


def read_package_toml(package: str, name: str) -> dict[str, Any]:
    """The table of TOML file ``name`` shipped inside package ``package`` (``read_package_toml("quenchsim.bearings",
    "data/doj.toml")``), from a checkout or a wheel."""
    return parse_toml(resources.files(package).joinpath(name).read_text("utf-8"), f"{package}/{name}")


def parse_value(text: str) -> Any:
    """A TOML value written on its own (``600``, ``"SUJ3"``, ``[1, 2]``, ``{ od = 0.8 }``), or the text itself when it
    is not one (a bare word: ``--set material=SUJ3``)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


@contextlib.contextmanager
def reading(path: str | Path | None) -> Iterator[None]:
    """Within the block, an :class:`InputError` that names no file names ``path`` (the file being interpreted)."""
    try:
        yield
    except InputError as exc:
        if path is None:
            raise
        raise exc.in_file(str(path))
