"""An HTC table (``[quench.htc_table]``, ``[air.htc_table]``, ``[temper.htc_table]`` of a case), declared once: h
against the surface temperature or time, per segment or for all; the thermal solver's boundary is built from it by
:func:`quenchsim.thermal.parse_htc_table`. Its own module: the thermal solver reads it and nothing else of the case."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from quenchsim.errors import require
from quenchsim.inputs.declare import Table, quantity


@dataclass(frozen=True, kw_only=True)
class HtcTable(Table):
    """``[quench.htc_table]``, ``[air.htc_table]``, ``[temper.htc_table]``: h against the surface temperature
    (``T_C``) or against time (``time_s``), one table or one per surface segment (``[segments.NAME]``, its
    ``ambient_C`` defaulting to the table's). Every surface segment needs a table: a default (``T_C``/``time_s`` at
    the top) or its own. The values are checked against the section's segments by
    :func:`quenchsim.thermal.parse_htc_table`."""

    T_C: tuple[float, ...] | None = quantity(None, unit="C", doc="surface temperatures, strictly increasing",
                                             allowed="must be a non-empty list")
    time_s: tuple[float, ...] | None = quantity(None, unit="s", doc="times, strictly increasing (instead of T_C)",
                                                allowed="must be a non-empty list")
    h_W_m2K: tuple[float, ...] | None = quantity(None, unit="W/m2K", doc="values, as long as the axis, >= 0")
    ambient_C: float | None = quantity(None, unit="C", doc="the medium's temperature",
                                       allowed="must be a number (degrees C)")
    segments: Mapping[str, HtcTable] = quantity({}, doc="a table of the same keys per surface segment")

    def check(self) -> None:
        if self.T_C is None and self.time_s is None:
            require(self.h_W_m2K is None, "", sorted(self._given), "needs T_C or time_s with h_W_m2K")
            return
        key = "T_C" if self.T_C is not None else "time_s"
        axis = self.axis
        require(len(axis) >= 1, key, list(axis), "must be a non-empty list")
        h = self.h_W_m2K or ()
        require(len(h) == len(axis), "h_W_m2K", list(h) if self.h_W_m2K is not None else None,
                f"must be a list as long as {key}")
        require(all(b > a for a, b in zip(axis, axis[1:])), key, list(axis), "must be strictly increasing")
        require(all(v >= 0 for v in h), "h_W_m2K", list(h), "values must be >= 0")

    @property
    def axis(self) -> tuple[float, ...]:
        """The table's axis: its surface temperatures (``T_C``) or its times (``time_s``); empty for a table of
        segment tables only."""
        return self.T_C if self.T_C is not None else (self.time_s or ())
