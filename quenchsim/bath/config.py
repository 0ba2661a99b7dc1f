"""The ``[quench.bath]`` table of a case file -> :class:`BathConfig`, the bath the model runs on (keys declared in
:mod:`quenchsim.inputs.bath`, documented in :mod:`quenchsim.bath`)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar, cast

from quenchsim.bath.quenchant import (STILL_BATH_KIND, OilProperties, ProbeQuenchant, load_oil,
                                      load_probe_quenchant)
from quenchsim.errors import InputError
from quenchsim.inputs.bath import (SIDES, BathTable, ConstantsFile, LayoutFile, NozzleRowTable, constant_values)
from quenchsim.inputs.declare import check_keys, from_table
from quenchsim.inputs.reader import read_toml, reading
from quenchsim.materials import find_data_file, load_data_file

_File = TypeVar("_File", LayoutFile, ConstantsFile)

AGITATION = ("flow", "still")
"""``agitation = "still"``: no nozzles, no rotation, no bulk flow (every flow key is then an error); ``"flow"``
(default): the nozzles, rotation and bulk flow the table gives (none given is also a still bath)."""
CONSTANT_KEYS = ("corner_carryover", "oil_swirl_fraction", "bore_swirl_fraction", "id_crossflow_up_m_s",
                 "od_crossflow_up_m_s")
"""The declared flow constants: read from the ``constants`` data file (materials/baths/NAME.toml, ``[flow]``), each
overridable by a case key of the same name."""
DEFAULT_LIQUID = "reference_quench_oil"
"""Liquid properties (viscosity, density, ...) and agitation response of the vapour film used with a still-bath
curve when ``liquid_properties`` is not given: the reference mineral oil (materials/SOURCES.md)."""


@dataclass(frozen=True)
class NozzleRow:
    """One ring of identical nozzles around the part, all at one height, aimed radially.

    side "id": inside the bore, aimed outward at the bore; "od": outside, aimed inward at the OD.
    jet_speed_m_s is the exit speed; standoff_m the horizontal distance from the exit to the surface;
    height_m the nozzle height above the turntable (the part's bottom face); inclination_rad > 0 aims
    the jet downward. A layout file gives the height as ``height_fraction`` of the part's height instead.
    """

    name: str
    side: str
    jet_speed_m_s: float
    diameter_m: float
    count: int
    standoff_m: float
    height_m: float | None
    inclination_rad: float
    height_fraction: float | None = None

    def height_above_bottom_m(self, part_height_m: float) -> float:
        """Nozzle height above the part's bottom face: ``height_m``, or ``height_fraction`` of the part's height."""
        # a row gives height_m or height_fraction (_row)
        return self.height_m if self.height_m is not None else float(cast(float, self.height_fraction)) * part_height_m


@dataclass(frozen=True)
class BathConfig:
    """A parsed bath: quenchant, oil temperature, nozzle rows, part rotation and modelling options.

    ``liquid`` is the liquid quenchant file the flow and convection use (the quenchant itself when it is a
    ``kind = "liquid"`` file, else ``liquid_properties``); ``still_curve`` the probe-measured still-bath curve
    h(T_s) when the quenchant is one (the bath then acts on that curve, quenchsim.bath.htc)."""

    liquid: OilProperties
    still_curve: ProbeQuenchant | None
    agitation: str
    agitation_m_s: float
    support: str
    oil_temperature_C: float
    rotation_rpm: float
    rows: tuple[NozzleRow, ...]
    oil_swirl_fraction: float
    bore_swirl_fraction: float
    turntable_open_fraction: float
    corner_carryover: float
    crossflow_up_m_s: dict[str, float]
    T_max_C: float
    T_step_K: float
    htc_factor: dict[str, float] = field(default_factory=dict)
    """Factor on the coefficient h(T_s) of every point of a named boundary segment (``bore``, ``od``, ``top``,
    ``bottom``, or any segment name of the profile); a chamfer ``chamfer_<a>_<b>`` not named itself takes the
    geometric mean of the factors of ``a`` and ``b``; every other segment 1 (:func:`segment_factor`)."""

    @property
    def omega_rad_s(self) -> float:
        return self.rotation_rpm * 2.0 * math.pi / 60.0


def _row(name: str, row: NozzleRowTable, bath: BathTable, where: str, field: str) -> NozzleRow:
    """The nozzle row ``name`` (table ``where``) in SI units, its jet speed its own or the bath's (table ``field``)
    for its side."""
    side = row.side_of(name, where)
    speed = row.jet_speed_mm_s if row.jet_speed_mm_s is not None else getattr(bath, f"{side}_jet_speed_mm_s")
    if speed is None:
        raise InputError(f"{field}.{side}_jet_speed_mm_s", None,
                         f"is required: the exit speed of the {side} rows without their own jet_speed_mm_s")
    return NozzleRow(name=name, side=side, jet_speed_m_s=speed * 1e-3, diameter_m=row.diameter_mm * 1e-3,
                     count=row.count, standoff_m=row.standoff_mm * 1e-3,
                     height_m=None if row.height_mm is None else row.height_mm * 1e-3,
                     height_fraction=row.height_fraction, inclination_rad=math.radians(row.inclination_deg))


def read_baths_file(name: str, kind: type[_File], field: str) -> _File:
    """The nozzle layout or constants file ``materials/baths/NAME.toml`` (:func:`quenchsim.materials.find_data_file`),
    checked; a file of another kind is an :class:`InputError` naming ``field``."""
    path = find_data_file(name, "baths", field)
    table = read_toml(path, field)
    wanted = "nozzle_layout" if kind is LayoutFile else "bath_constants"
    if table.get("kind") != wanted:
        raise InputError(field, name, f"is a {table.get('kind', 'untyped')} file; a {wanted} file is needed")
    with reading(path):
        return from_table(kind, table)


def load_constants(name: str, field: str = "quench.bath.constants") -> dict[str, float]:
    """The declared flow constants of ``materials/baths/NAME.toml`` (``kind = "bath_constants"``, table ``[flow]``)."""
    flow = read_baths_file(name, ConstantsFile, field).flow
    return {key: float(getattr(flow, key)) for key in CONSTANT_KEYS}


def load_htc_factors(name: str, field: str = "quench.bath.constants") -> dict[str, float]:
    """The declared per-surface factors on h of a constants file (table ``[htc_factor]``; none: every factor 1)."""
    return dict(read_baths_file(name, ConstantsFile, field).htc_factor)


def segment_factor(factors: dict[str, float], segment: str) -> float:
    """The factor on h of a boundary segment: its own, else for ``chamfer_<a>_<b>`` the geometric mean of ``a``'s
    and ``b``'s (1 for a name not given), else 1."""
    if segment in factors:
        return factors[segment]
    parts = segment.split("_")
    if len(parts) == 3 and parts[0] == "chamfer":
        side = "bore" if parts[1] == "id" else parts[1]   # the diagnostic outlines name the bore side "id"
        return math.sqrt(factors.get(side, 1.0) * factors.get(parts[2], 1.0))
    return 1.0


def load_layout(name: str, bath: BathTable, field: str = "quench.bath") -> tuple[NozzleRow, ...]:
    """The nozzle rows of a layout file ``materials/baths/NAME.toml`` (``kind = "nozzle_layout"``, ``[nozzles.*]``)
    for the bath table ``bath`` (at ``field``)."""
    layout = read_baths_file(name, LayoutFile, f"{field}.layout")
    return tuple(_row(row, spec, bath, f"{Path(name).stem}.nozzles.{row}", field)
                 for row, spec in layout.nozzles.items())


def check_bath_keys(spec: Any, field: str = "quench.bath") -> None:
    """Every key of a ``[quench.bath]`` table and of its ``[nozzles.<row>]`` tables is known (a misspelt key is
    an error, never ignored); the values are checked by :func:`parse_bath`. For a condition's table too
    (``[conditions.N.quench.bath]``), whichever condition runs."""
    check_keys(BathTable, spec, field)


def parse_bath(spec: Mapping[str, Any], field: str = "quench.bath") -> BathConfig:
    """The bath of a ``[quench.bath]`` table (condition overrides already merged); errors name the field."""
    return resolve_bath(from_table(BathTable, spec, field), field)


def resolve_bath(table: BathTable, field: str = "quench.bath") -> BathConfig:
    """The bath a checked ``[quench.bath]`` table describes: its quenchant (a liquid, or a still-bath curve with the
    liquid whose properties the flow uses), nozzle rows (its own or its layout's) and flow constants (its constants
    file's, overridden by its own keys), in SI units; the checks that need those files here."""
    name, T_oil = table.quenchant, table.oil_temperature_C
    if name is None:
        raise InputError(f"{field}.quenchant", None, "is required: the name of a materials/quenchants/*.toml file")
    if T_oil is None:
        raise InputError(f"{field}.oil_temperature_C", None, "is required (the bulk oil temperature, C)")
    still_curve = None
    if load_data_file(name, "quenchants", f"{field}.quenchant").get("kind") == STILL_BATH_KIND:
        still_curve = load_probe_quenchant(name, f"{field}.quenchant")
        oil = load_oil(table.liquid_properties or DEFAULT_LIQUID, f"{field}.liquid_properties")
    else:
        if table.liquid_properties is not None:
            raise InputError(f"{field}.liquid_properties", table.liquid_properties,
                             f"only applies to a still-bath curve; {name} carries its own liquid properties")
        oil = load_oil(name, f"{field}.quenchant")
    if T_oil >= oil.boiling_point_C:
        raise InputError(f"{field}.oil_temperature_C", T_oil,
                         f"must be below the boiling point of {name} ({oil.boiling_point_C:g} C)")
    if table.layout is not None:
        rows = load_layout(table.layout, table, field)
    else:
        rows = tuple(_row(row_name, row, table, f"{field}.nozzles.{row_name}", field)
                     for row_name, row in table.nozzles.items())
    constants = {**load_constants(table.constants, f"{field}.constants"), **constant_values(table)}
    factors = {**load_htc_factors(table.constants, f"{field}.constants"), **table.htc_factor}
    if table.T_max_C <= oil.boiling_point_C:
        raise InputError(f"{field}.T_max_C", table.T_max_C, f"must exceed the boiling point {oil.boiling_point_C:g} C")
    return BathConfig(
        liquid=oil, still_curve=still_curve, agitation=table.agitation, agitation_m_s=table.agitation_m_s,
        support=table.support, oil_temperature_C=T_oil, rotation_rpm=table.rotation_rpm, rows=rows,
        oil_swirl_fraction=constants["oil_swirl_fraction"], bore_swirl_fraction=constants["bore_swirl_fraction"],
        turntable_open_fraction=table.open_fraction, corner_carryover=constants["corner_carryover"],
        crossflow_up_m_s={side: constants[f"{side}_crossflow_up_m_s"] for side in SIDES},
        T_max_C=table.T_max_C, T_step_K=table.T_step_K, htc_factor=factors)
