"""A sweep file (``quenchsim sweep SWEEP.toml``): a base case and the case keys varied over it, declared once; what a
sweep does: :mod:`quenchsim.sweep`."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from quenchsim.inputs.declare import REQUIRED, Table, quantity


@dataclass(frozen=True, kw_only=True)
class SweepHead(Table):
    """``[sweep]``: the base case."""

    case: str = quantity(REQUIRED, doc="the base case file, relative to the sweep file",
                         allowed="required: the base case file (relative to the sweep file)")
    condition: str | int | None = quantity(None, doc="the base case's condition (if it has conditions)")
    name: str | None = quantity(None, doc="the sweep's name (default: the file stem)")


@dataclass(frozen=True, kw_only=True)
class SweepFile(Table):
    """A sweep file: ``[sweep]``, and the case keys (dotted, or nested tables of them) fixed in ``[set]``, varied as a
    Cartesian product in ``[grid]`` or together in ``[zip]`` (lists of equal length)."""

    UNKNOWN = "unknown table"

    sweep: SweepHead = quantity(REQUIRED, doc="the base case")
    set: Mapping[str, Any] = quantity({}, doc="case keys fixed for every case")
    grid: Mapping[str, Any] = quantity({}, doc="case keys -> lists of values, every combination")
    zip: Mapping[str, Any] = quantity({}, doc="case keys -> lists of equal length, varied together")
