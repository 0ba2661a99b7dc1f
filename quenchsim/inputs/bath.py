"""The bath model's inputs: a case's ``[quench.bath]`` table, a nozzle layout file and a bath-constants file
(``materials/baths/NAME.toml``, ``kind = "nozzle_layout"`` / ``"bath_constants"``).

What the keys do: :mod:`quenchsim.bath` (the module docstring lists them with an example); the resolved bath the
model runs on (SI units, its quenchant, layout and constants loaded) is :class:`quenchsim.bath.BathConfig`, built by
:func:`quenchsim.bath.config.resolve_bath`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import REQUIRED, DataFile, Table, quantity

SIDES = ("id", "od")
MAX_JET_SPEED_MM_S = 50_000.0
"""Largest nozzle exit speed accepted (50 m/s): quench-tank agitation and spray nozzles run at up to a few m/s (the
reference conditions: 0.4-10.7 m/s); far above, the free-jet and wall-jet correlations of
quenchsim.bath.correlations are extrapolated beyond any quench practice."""
MAX_ROTATION_RPM = 600.0
"""Largest part rotation accepted (turntables turn at ~1-30 rpm; the reference rings at 11 rpm)."""
MAX_AGITATION_M_S = 10.0
"""Largest bulk oil speed accepted: tank agitators move oil past the work at up to ~1-2 m/s (propeller-agitated
tanks; the reference conditions' jets reach 10.7 m/s at the exit), beyond the flat-plate correlations' use here."""
HTC_FACTOR_LIMITS = (0.05, 20.0)
"""Accepted range of a per-surface factor on the bath's heat-transfer coefficient (``[htc_factor]`` of the constants
file, or the case's ``htc_factor`` table)."""
DEFAULT_CONSTANTS = "jet_bath"
"""The declared flow constants used when a case names none (materials/baths/jet_bath.toml)."""
ENTRY_KEYS = ("source", "range", "range_factor")
"""Provenance and prior keys a layout row or a data-file table may carry besides its values."""


@dataclass(frozen=True, kw_only=True)
class NozzleRowTable(Table):
    """``[quench.bath.nozzles.NAME]`` or a layout file's ``[nozzles.NAME]``: one ring of identical nozzles around the
    part, all at one height, aimed radially (a number may be given as ``{ value, range, source }``)."""

    OTHER_KEYS = ENTRY_KEYS

    side: Literal["id", "od"] | None = quantity(None, doc="\"id\" (in the bore, aimed outward) or \"od\" (aimed "
                                                "inward); default: the row name's prefix id_/od_",
                                                allowed="must be 'id' or 'od' (or start the row name with id_/od_)")
    diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, sourced=True, doc="nozzle exit diameter")
    count: int = quantity(REQUIRED, ge=1, sourced=True, doc="nozzles in the row, evenly spaced round the part",
                          allowed="must be an integer >= 1")
    standoff_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, sourced=True,
                                  doc="horizontal distance from the exit to the part surface")
    height_mm: float | None = quantity(None, unit="mm", ge=0.0, sourced=True,
                                       doc="nozzle height above the part's bottom face (or height_fraction)")
    height_fraction: float | None = quantity(None, ge=0.0, le=1.0, sourced=True,
                                             doc="nozzle height as a fraction of the part's height (or height_mm)")
    inclination_deg: float = quantity(0.0, unit="deg", ge=-80.0, le=80.0, sourced=True,
                                      doc="> 0 aims the jet downward")
    jet_speed_mm_s: float | None = quantity(None, unit="mm/s", ge=0.0, le=MAX_JET_SPEED_MM_S, sourced=True,
                                            doc="exit speed of this row (default: the bath's <side>_jet_speed_mm_s)")

    def check(self) -> None:
        require((self.height_mm is None) != (self.height_fraction is None), "height_mm", self.height_mm,
                "give height_mm or height_fraction (of the part's height), one of them")

    def side_of(self, name: str, where: str) -> str:
        """The row's side: its ``side``, else its name's prefix ``id_`` / ``od_``."""
        side = self.side or name.split("_")[0]
        require(side in SIDES, f"{where}.side", side, "must be 'id' or 'od' (or start the row name with id_/od_)")
        return side


@dataclass(frozen=True, kw_only=True)
class BathTable(Table):
    """``[quench.bath]``: the bath model -- quenchant, oil temperature, agitation, nozzle rows, part rotation and
    the flow constants (:mod:`quenchsim.bath`). The quenchant and the oil temperature are required when the bath is
    used (a case with ``htc_model = "table"`` may carry a bath table its conditions complete); the bath is resolved,
    and they checked, by :func:`quenchsim.bath.config.resolve_bath`."""

    quenchant: str | None = quantity(None, doc="required: materials/quenchants/NAME.toml, a liquid (boiling-curve) "
                                     "oil, or a still-bath curve from the ISO 9950 probe")
    liquid_properties: str | None = quantity(None, doc="with a still-bath curve only: the liquid file whose "
                                             "properties the flow uses (default reference_quench_oil)")
    oil_temperature_C: float | None = quantity(None, unit="C", ge=-20.0, doc="required: bulk oil temperature; "
                                               "below the (liquid's) boiling point")
    agitation: str = quantity("flow", choices=("flow", "still"),
                              doc="\"still\": no nozzles, rotation or flow (those keys are then errors)")
    agitation_m_s: float = quantity(0.0, unit="m/s", ge=0.0, le=MAX_AGITATION_M_S,
                                    doc="bulk oil speed past every face (tank agitator)")
    support: str = quantity("turntable", choices=("turntable", "fixture", "hanging"),
                            doc="how the part is held (a turntable or fixture covers part of the bottom face)")
    support_open_fraction: float | None = quantity(None, ge=0.0, le=1.0, doc="share of the bottom face open to "
                                                   "the oil on a turntable or fixture (default 0.5)")
    turntable_open_fraction: float | None = quantity(None, ge=0.0, le=1.0,
                                                     doc="older name of support_open_fraction")
    rotation_rpm: float = quantity(0.0, unit="rpm", ge=0.0, le=MAX_ROTATION_RPM, doc="turntable speed")
    id_jet_speed_mm_s: float | None = quantity(None, unit="mm/s", ge=0.0, le=MAX_JET_SPEED_MM_S,
                                               doc="exit speed of every \"id\" row without its own jet_speed_mm_s")
    od_jet_speed_mm_s: float | None = quantity(None, unit="mm/s", ge=0.0, le=MAX_JET_SPEED_MM_S,
                                               doc="same for the \"od\" rows")
    layout: str | None = quantity(None, doc="materials/baths/NAME.toml (kind = \"nozzle_layout\"): the nozzle rows "
                                  "(instead of nozzles tables; not both)")
    nozzles: Mapping[str, NozzleRowTable] = quantity({}, doc="the nozzle rows [quench.bath.nozzles.NAME], any "
                                                     "number (below)")
    constants: str = quantity(DEFAULT_CONSTANTS, doc="materials/baths/NAME.toml (kind = \"bath_constants\"): the "
                              "declared flow constants; a case key of the same name overrides one")
    oil_swirl_fraction: float | None = quantity(None, ge=0.0, le=1.0, doc="share of the part's rotation the oil "
                                                "outside the ring follows (default: the constants file's)")
    bore_swirl_fraction: float | None = quantity(None, ge=0.0, le=1.0, doc="share of the bore's rotation the oil "
                                                 "column in the bore follows (default: the constants file's)")
    corner_carryover: float | None = quantity(None, ge=0.0, le=1.0, doc="share of a wall jet carried round a "
                                              "convex edge (default: the constants file's)")
    id_crossflow_up_m_s: float | None = quantity(None, unit="m/s", ge=-5.0, le=5.0, doc="vertical oil speed (up "
                                                 "> 0) the \"id\" jets cross (default: the constants file's)")
    od_crossflow_up_m_s: float | None = quantity(None, unit="m/s", ge=-5.0, le=5.0,
                                                 doc="same for the \"od\" rows")
    htc_factor: Mapping[str, float] = quantity({}, ge=HTC_FACTOR_LIMITS[0], le=HTC_FACTOR_LIMITS[1], sourced=True,
                                               doc="factors on h(T_s) per surface (bore, od, top, bottom or a "
                                               "segment name); default: the constants file's [htc_factor]")
    T_max_C: float = quantity(1100.0, unit="C", le=2000.0, doc="top of the HTC(T) grid (clamped above); above the "
                              "oil's boiling point")
    T_step_K: float = quantity(2.0, unit="K", ge=0.1, le=50.0, doc="step of the HTC(T) grid")

    FLOW_KEYS = ("rotation_rpm", "nozzles", "layout", "id_jet_speed_mm_s", "od_jet_speed_mm_s", "agitation_m_s",
                 "corner_carryover", "oil_swirl_fraction", "bore_swirl_fraction", "id_crossflow_up_m_s",
                 "od_crossflow_up_m_s")
    """The keys of an agitated bath (errors in a still one)."""

    def check(self) -> None:
        for key, value in self.htc_factor.items():
            lo, hi = HTC_FACTOR_LIMITS
            require(lo <= value <= hi, f"htc_factor.{key}", value, f"must be >= {lo:g} and <= {hi:g}")
        if self.agitation == "still":
            for key in self.FLOW_KEYS:
                if key in self._given:
                    raise InputError(key, self._given[key], "not allowed in a still bath (agitation = \"still\")")
        opened = self.support_open_fraction if self.support_open_fraction is not None else self.turntable_open_fraction
        require(self.support != "hanging" or opened is None, "support_open_fraction", opened,
                "does not apply to a hanging part (every face is open)")
        require(self.support_open_fraction is None or self.turntable_open_fraction is None,
                "turntable_open_fraction", self.turntable_open_fraction,
                "give support_open_fraction or its older name turntable_open_fraction, not both")
        require(self.layout is None or not self.nozzles, "layout", self.layout,
                "give a layout file or a nozzles table, not both")

    @property
    def open_fraction(self) -> float:
        """The share of the bottom face open to the oil (1 for a hanging part)."""
        if self.support == "hanging":
            return 1.0
        given = self.turntable_open_fraction if self.turntable_open_fraction is not None else self.support_open_fraction
        return 0.5 if given is None else given


@dataclass(frozen=True, kw_only=True)
class LayoutFile(DataFile):
    """A nozzle layout ``materials/baths/NAME.toml`` (``kind = "nozzle_layout"``): the nozzle rows of a tank, each
    number with its prior (addressable by the calibration as ``layout.NAME.nozzles.<row>.<key>``)."""

    kind: Literal["nozzle_layout"] = quantity(REQUIRED, doc="\"nozzle_layout\"")
    nozzles: Mapping[str, NozzleRowTable] = quantity(REQUIRED, doc="the rows [nozzles.NAME] (keys as a case's "
                                                     "[quench.bath.nozzles.NAME])")

    def check(self) -> None:
        require(bool(self.nozzles), "nozzles", dict(self.nozzles), "needs at least one [nozzles.<row>] table")


@dataclass(frozen=True, kw_only=True)
class FlowConstants(Table):
    """A constants file's ``[flow]``: the declared flow constants, each ``{ value, range, source }``."""

    corner_carryover: float = quantity(REQUIRED, ge=0.0, le=1.0, sourced=True,
                                       doc="share of a wall jet carried round a convex edge onto a face turned ~90 deg")
    oil_swirl_fraction: float = quantity(REQUIRED, ge=0.0, le=1.0, sourced=True,
                                         doc="share of the part's rotation the oil outside the ring follows")
    bore_swirl_fraction: float = quantity(REQUIRED, ge=0.0, le=1.0, sourced=True,
                                          doc="share of the bore's rotation the oil column in the bore follows")
    id_crossflow_up_m_s: float = quantity(REQUIRED, unit="m/s", ge=-5.0, le=5.0, sourced=True,
                                          doc="vertical oil speed (up > 0) the \"id\" jets cross")
    od_crossflow_up_m_s: float = quantity(REQUIRED, unit="m/s", ge=-5.0, le=5.0, sourced=True,
                                          doc="same for the \"od\" rows")


@dataclass(frozen=True, kw_only=True)
class ConstantsFile(DataFile):
    """A bath-constants file ``materials/baths/NAME.toml`` (``kind = "bath_constants"``): the flow constants no data
    sheet gives and the per-surface factors on h, each an assumption with its prior (addressable by the calibration
    as ``bath.NAME.flow.<key>`` and ``bath.NAME.htc_factor.<surface>``)."""

    kind: Literal["bath_constants"] = quantity(REQUIRED, doc="\"bath_constants\"")
    flow: FlowConstants = quantity(REQUIRED, doc="the declared flow constants")
    htc_factor: Mapping[str, float] = quantity({}, ge=HTC_FACTOR_LIMITS[0], le=HTC_FACTOR_LIMITS[1], sourced=True,
                                               doc="factors on h per surface (none: every factor 1)")

    def check(self) -> None:
        for key, value in self.htc_factor.items():
            lo, hi = HTC_FACTOR_LIMITS
            require(lo <= value <= hi, f"htc_factor.{key}", value, f"must be >= {lo:g} and <= {hi:g}")


def constant_values(table: BathTable) -> dict[str, Any]:
    """The flow constants a case's bath table sets itself (overriding its constants file's)."""
    return {key: getattr(table, key) for key in ("corner_carryover", "oil_swirl_fraction", "bore_swirl_fraction",
                                                 "id_crossflow_up_m_s", "od_crossflow_up_m_s")
            if getattr(table, key) is not None}
