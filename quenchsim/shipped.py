"""The data quenchsim ships, found the same way from a checkout and from an installed wheel, and kept read-only.

A checkout (source or editable install) has ``cases/`` and ``materials/`` beside the package; a wheel carries copies
of both inside it, as ``quenchsim/_data/cases`` and ``quenchsim/_data/materials`` (setup.py). A user reaches a
shipped case by its name (``quenchsim run crb_outer_ring --condition 1``, ``quenchsim cases``) and never writes
into the shipped materials (the fitters refuse such an ``--out``, :func:`refuse_shipped_file`). Where data names are
resolved (the user's folders first, then this shipped data): :mod:`quenchsim.materials`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from quenchsim.errors import InputError
from quenchsim.inputs.reader import parse_toml

PACKAGE = Path(__file__).resolve().parent


EXAMPLES = ("docs/guide", "first_hour_*")
"""Where the guides' example files lie in a checkout, and their pattern; a wheel carries them as
``quenchsim/_data/examples`` (setup.py)."""


def shipped_dir(folder: str) -> Path:
    """The shipped data folder ``folder`` ("cases" or "materials"): the checkout's, else the wheel's copy. The one
    place that says where shipped data lie (:func:`quenchsim.materials.materials_dir` is this for "materials"; the
    user's folders searched before it are :func:`quenchsim.materials.data_folders`)."""
    checkout = PACKAGE.parent / folder
    return checkout if checkout.is_dir() else PACKAGE / "_data" / folder


def shipped_examples() -> list[Path]:
    """The example files the guides name (``first_hour_probe_curve.csv``, ``first_hour_ttt.toml``) and the example
    scripts among the cases (``example_sweep_script.py``): what ``quenchsim cases copy NAME`` copies besides the
    cases, from a checkout or a wheel."""
    checkout = PACKAGE.parent / EXAMPLES[0]
    folder = checkout if checkout.is_dir() else PACKAGE / "_data" / "examples"
    return sorted([*folder.glob(EXAMPLES[1]), *(p for p in shipped_dir("cases").iterdir() if p.suffix == ".py")])


@dataclass(frozen=True)
class ShippedCase:
    """One shipped case file: its ``name`` (the file stem), a one-line ``description`` and its ``conditions``."""

    name: str
    path: Path
    description: str
    conditions: tuple[str, ...]


def _first_comment(text: str) -> str:
    """The first sentence of the file's first comment paragraph (comment lines up to an empty ``#`` line), joined
    across lines: a line of it ended mid-sentence."""
    lines: list[str] = []
    for line in text.splitlines():
        if not line.startswith("#"):
            if lines or line.strip():
                break
            continue
        words = line.lstrip("#").strip()
        if not words:
            if lines:
                break
            continue
        lines.append(words)
    paragraph = " ".join(lines)
    depth = 0
    for i, char in enumerate(paragraph):
        depth += {"(": 1, ")": -1}.get(char, 0)
        if char == "." and depth == 0 and (i + 1 == len(paragraph) or (paragraph[i + 1] == " " and i + 2 < len(paragraph)
                                                                       and paragraph[i + 2].isupper())):
            return paragraph[:i + 1]
    return paragraph


def shipped_cases() -> list[ShippedCase]:
    """The shipped case files (``cases/*.toml``), sorted by name: the quench cases (``quenchsim run``) and the
    bearing-solver inputs. The description is the file's ``description``, else its first comment line."""
    out = []
    for path in sorted(shipped_dir("cases").glob("*.toml")):
        text = path.read_text()
        try:
            data = parse_toml(text, str(path))
        except InputError:
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


def shipped_file(name: str, field: str = "NAME") -> Path:
    """A shipped case (by name) or example file (by file name or stem, :func:`shipped_examples`)."""
    for path in shipped_examples():
        if name in (path.name, path.stem):
            return path
    try:
        return shipped_case(name, field=field).path
    except InputError as exc:
        examples = ", ".join(p.name for p in shipped_examples())
        raise InputError(field, name, f"{exc.allowed}; example files: {examples}") from None


def is_bare_name(value: str | Path) -> bool:
    """Whether ``value`` is a bare case name: no path separator, no ``.toml`` and not an existing file."""
    text = str(value)
    return "/" not in text and "\\" not in text and not text.endswith(".toml") and not Path(text).exists()


def resolve_case(value: str | Path, field: str = "case") -> Path:
    """The file of a command's case argument (``run``, ``mesh``, ``bath``, ``sweep``, ``optimise``, ``calibrate``,
    ``bearings runout | big-end``): a bare name (:func:`is_bare_name`) is a shipped case file (``cases/NAME.toml``),
    anything else a path (checked by the command's reader). A path that is not there but names a shipped file -- a
    guide's ``cases/crb_outer_ring.toml`` run from a wheel or another folder -- is refused with the name to give."""
    if is_bare_name(value):
        return shipped_case(str(value), field=field).path
    path = Path(value).expanduser()
    if not path.exists() and path.suffix == ".toml" and any(c.name == path.stem for c in shipped_cases()):
        raise InputError(field, str(value), f"no such file; quenchsim ships a file of that name: give its name, "
                                            f"{path.stem} (or `quenchsim cases copy {path.stem}` for a copy to edit)")
    return path


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
