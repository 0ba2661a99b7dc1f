"""A transformation data file (CCT, TTT, Jominy data for ``quenchsim material fit``), declared once: its keys, types
and the rules of one entry; the rules that tie entries to the steel, to the cooling curve or to each other (finish
below start, a unit slip, the fit's parameters) and the schema with an example are :mod:`quenchsim.fitting.diagram_data`."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from quenchsim.errors import require
from quenchsim.inputs.declare import REQUIRED, Table, quantity

KINDS = ("printed", "read")
"""How a point was obtained: a number printed in the source, or read off a figure."""

Numbers = tuple[float, ...] | float
"""A number or a list of numbers (a series)."""


@dataclass(frozen=True, kw_only=True)
class Entry(Table):
    """The provenance every entry carries: its source and how the numbers were obtained."""

    source: str = quantity(REQUIRED, doc="where the numbers come from", allowed="is required (a non-empty string)")
    kind: str = quantity(REQUIRED, choices=KINDS, doc="\"printed\" (a number in the source) or \"read\" (off a figure)",
                         allowed="must be one of ('printed', 'read') (a printed number or read off a figure)")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "is required (a non-empty string)")


@dataclass(frozen=True, kw_only=True)
class CCTEntry(Entry):
    """``[[cct]]``: one cooling curve of a CCT diagram and what was seen on it."""

    cooling_rate_C_s: float | None = quantity(None, unit="C/s", doc="a linear curve's rate (or t8_5_s, lambda)")
    t8_5_s: float | None = quantity(None, unit="s", doc="a Newtonian curve's 800 -> 500 C time")
    # the key is "lambda", a Python keyword
    lambda_: float | None = quantity(None, key="lambda", doc="a Newtonian curve's t8/5 in 100 s")
    T_start_C: float | None = quantity(None, unit="C", doc="start of the curve (default T_aust_C)")
    T_end_C: float = quantity(20.0, unit="C", doc="end of the curve")
    start_C: Mapping[str, float] = quantity({}, unit="C", doc="phase -> temperature where 1 % has formed")
    finish_C: Mapping[str, float] = quantity({}, unit="C", doc="phase -> temperature where 99 % of its amount has "
                                             "formed")
    temperature_uncertainty_K: float | None = quantity(None, unit="K", gt=0.0, doc="of start_C and finish_C")
    fractions: Mapping[str, float] = quantity({}, doc="phase -> final fraction")
    fraction_uncertainty: float | None = quantity(None, gt=0.0, doc="of the fractions")
    hardness_HV: float | None = quantity(None, unit="HV", doc="final hardness (or hardness_HRC)")
    hardness_HRC: float | None = quantity(None, unit="HRC", doc="final hardness (or hardness_HV)")
    hardness_uncertainty_HV: float | None = quantity(None, unit="HV", gt=0.0, doc="of the hardness")


@dataclass(frozen=True, kw_only=True)
class TTTEntry(Entry):
    """``[[ttt]]``: one TTT series of one product (lists of equal length)."""

    phase: str = quantity(REQUIRED, doc="the product of the line")
    T_C: Numbers = quantity(REQUIRED, unit="C", doc="hold temperatures",
                            allowed="must be a number or a list of numbers")
    t_start_s: Numbers = quantity(REQUIRED, unit="s", doc="1 % times", allowed="must be a number or a list of numbers")
    t_finish_s: Numbers = quantity(REQUIRED, unit="s", doc="99 % times", allowed="must be a number or a list of numbers")
    time_uncertainty_factor: float = quantity(REQUIRED, gt=1.0, doc="the times' uncertainty, a factor",
                                              allowed="a factor on time")


@dataclass(frozen=True, kw_only=True)
class JominyEntry(Entry):
    """``[[jominy]]``: hardness against distance from the quenched end."""

    distance_mm: Numbers = quantity(REQUIRED, unit="mm", doc="distances from the quenched end",
                                    allowed="must be a number or a list of numbers")
    hardness_HV: Numbers | None = quantity(None, unit="HV", doc="hardness (or hardness_HRC)")
    hardness_HRC: Numbers | None = quantity(None, unit="HRC", doc="hardness (or hardness_HV)")
    hardness_uncertainty_HV: float = quantity(REQUIRED, unit="HV", gt=0.0, doc="of the hardness")


@dataclass(frozen=True, kw_only=True)
class FitTable(Table):
    """``[fit.pearlite]`` / ``[fit.bainite]``: the c_curve parameters the fitter may move (each a number or
    ``{ value, source }``; a parameter held fixed needs its source), which are ``free``, and an optional calibration
    factor on tau_ref."""

    T_upper_C: float | None = quantity(None, unit="C", sourced=True, doc="upper temperature")
    T_ref_C: float | None = quantity(None, unit="C", sourced=True, doc="reference temperature (below T_upper_C)")
    tau_ref_s: float | None = quantity(None, unit="s", sourced=True, doc="time constant at T_ref")
    undercooling_exponent: float | None = quantity(None, sourced=True, doc="m")
    Q_J_mol: float | None = quantity(None, unit="J/mol", sourced=True, doc="activation energy")
    n: float | None = quantity(None, sourced=True, doc="Avrami exponent (or the nodes)")
    n_per_K: float | None = quantity(None, unit="1/K", sourced=True, doc="slope of n(T) (default 0)")
    n_nodes_T_C: Any = quantity(None, doc="node temperatures of a piecewise-linear n(T)")
    n_nodes: Any = quantity(None, doc="Avrami exponents at the nodes")
    free: tuple[str, ...] = quantity((), doc="the parameters the fit frees")
    calibration_tau_factor: float | None = quantity(None, gt=0.0, sourced=True, doc="the material's tau_ref x this")

    def source_of(self, key: str) -> str:
        """The source the file gives a parameter (its ``{ value, source }``), else ``""``."""
        given = self._given.get(key)
        return str(given.get("source", "")) if isinstance(given, Mapping) else ""


@dataclass(frozen=True, kw_only=True)
class DiagramFile(Table):
    """A CCT / TTT / Jominy data file."""

    UNKNOWN = "unknown entry"

    name: str = quantity(REQUIRED, doc="the data's name", allowed="is required (a non-empty string)")
    material: str = quantity(REQUIRED, doc="the base steel file: thermal data, Ms, hardness",
                             allowed="is required (a non-empty string)")
    T_aust_C: float = quantity(REQUIRED, unit="C", gt=0.0, doc="the austenitising temperature of the data")
    source: str = quantity(REQUIRED, doc="where the data come from", allowed="is required (a non-empty string)")
    cct: tuple[CCTEntry, ...] = quantity((), doc="CCT curves")
    ttt: tuple[TTTEntry, ...] = quantity((), doc="TTT series")
    jominy: tuple[JominyEntry, ...] = quantity((), doc="Jominy series")
    fit: Mapping[str, FitTable] = quantity({}, doc="the reactions to fit")
    data_from: tuple[str, ...] = quantity((), doc="other data files (same T_aust_C) whose points are fitted too",
                                          allowed="must be a list of data file names (relative to this file)")

    def check(self) -> None:
        for key in ("name", "material", "source"):
            require(getattr(self, key).strip() != "", key, getattr(self, key), "is required (a non-empty string)")
