"""The data quenchsim ships, found the same way from a checkout and from an installed wheel, and kept read-only.

A checkout (source or editable install) has ``cases/`` and ``materials/`` beside the package; a wheel carries copies
of both inside it, as ``quenchsim/_data/cases`` and ``quenchsim/_data/materials`` (setup.py). A user reaches a
shipped case by its name (``quenchsim run crb_outer_ring --condition 1``, ``quenchsim cases``) and never writes
into the shipped materials (the fitters refuse such an ``--out``, :func:`refuse_shipped_file`). Where data names are
resolved (the user's folders first, then this shipped data): :mod:`quenchsim.materials`.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from quenchsim.errors import InputError

PACKAGE = Path(__file__).resolve().parent


def shipped_dir(folder: str) -> Path:
    """The shipped data folder ``folder`` ("cases" or "materials"): the checkout's, else the wheel's copy. The one
    place that says where shipped data lie (:func:`quenchsim.materials.materials_dir` is this for "materials"; the
    user's folders searched before it are :func:`quenchsim.materials.data_folders`)."""
    checkout = PACKAGE.parent / folder
    return checkout if checkout.is_dir() else PACKAGE / "_data" / folder


@dataclass(frozen=True)
class ShippedCase:
    """One shipped case file: its ``name`` (the file stem), a one-line ``description`` and its ``conditions``."""

    name: str
    path: Path
    description: str
    conditions: tuple[str, ...]


def _first_comment(text: str) -> str:
    for line in text.splitlines():
        if line.startswith("#"):
            return line.lstrip("# ").strip()
    return ""


def shipped_cases() -> list[ShippedCase]:
    """The shipped case files (``cases/*.toml``), sorted by name: the quench cases (``quenchsim run``) and the
    bearing-solver inputs. The description is the file's ``description``, else its first comment line."""
    out = []
    for path in sorted(shipped_dir("cases").glob("*.toml")):
        text = path.read_text()
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError:
            continue
        description = data.get("description") or _first_comment(text)
        conditions = data.get("conditions", {})
        out.append(ShippedCase(path.stem, path, str(description),
                               tuple(sorted(conditions)) if isinstance(conditions, dict) else ()))
    return out


def shipped_case(name: str, field: str = "case") -> ShippedCase:
    """The shipped case called ``name``; an :class:`InputError` listing the known names otherwise."""
    cases = shipped_cases()
    for case in cases:
        if case.name == name:
            return case
    raise InputError(field, name, f"no such file and no shipped case of that name; shipped cases: "
                                  f"{', '.join(c.name for c in cases) or 'none'} (quenchsim cases)")


def is_bare_name(value: str | Path) -> bool:
    """Whether ``value`` is a bare case name: no path separator, no ``.toml`` and not an existing file."""
    text = str(value)
    return "/" not in text and "\\" not in text and not text.endswith(".toml") and not Path(text).exists()


def resolve_case(value: str | Path) -> Path:
    """The case file of a ``quenchsim run`` argument: a bare name (:func:`is_bare_name`) is a shipped case, anything
    else a path (checked by :func:`quenchsim.case.load_case`)."""
    return shipped_case(str(value)).path if is_bare_name(value) else Path(value)


def refuse_shipped_file(out: str | Path, field: str = "--out", hint: str = "") -> None:
    """Raise :class:`InputError` when ``out`` lies in the shipped ``materials/`` folder: the fitters write the user's
    data into the user's folder (``./materials`` by default), never into the shipped one (an overwritten steel or oil
    silently changes every case and validation study that reads it; a new file there ends up in a built wheel and
    marks the validation studies stale)."""
    shipped = shipped_dir("materials").resolve()
    path = Path(out).expanduser().resolve()
    if path.is_relative_to(shipped):
        what = "a file quenchsim ships" if path.is_file() else "in the folder of the data quenchsim ships"
        raise InputError(field, str(out), f"is {what} (materials/{path.relative_to(shipped).as_posix()}), whose files "
                                          "are never overwritten nor added to: write into your own folder (run from your project folder, "
                                          "whose ./materials is the default, or give another --out)"
                                          + (f" ({hint})" if hint else ""))
