"""The ``[quench.bath]`` table of a case file -> :class:`BathConfig` (keys documented in quenchsim.bath)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

from quenchsim.bath.quenchant import (STILL_BATH_KIND, OilProperties, ProbeQuenchant, load_oil,
                                      load_probe_quenchant)
from quenchsim.errors import InputError, require_known_keys
from quenchsim.materials import load_data_file

SIDES = ("id", "od")
AGITATION = ("flow", "still")
"""``agitation = "still"``: no nozzles, no rotation, no bulk flow (every flow key is then an error); ``"flow"``
(default): the nozzles, rotation and bulk flow the table gives (none given is also a still bath)."""
CONSTANT_KEYS = ("corner_carryover", "oil_swirl_fraction", "bore_swirl_fraction", "id_crossflow_up_m_s",
                 "od_crossflow_up_m_s")
"""The declared flow constants: read from the ``constants`` data file (materials/baths/NAME.toml, ``[flow]``), each
overridable by a case key of the same name."""
CONSTANT_LIMITS = {"corner_carryover": (0.0, 1.0), "oil_swirl_fraction": (0.0, 1.0), "bore_swirl_fraction": (0.0, 1.0),
                   "id_crossflow_up_m_s": (-5.0, 5.0), "od_crossflow_up_m_s": (-5.0, 5.0)}
DEFAULT_CONSTANTS = "jet_bath"
"""The declared flow constants used when a case names none (materials/baths/jet_bath.toml)."""
HTC_FACTOR_LIMITS = (0.05, 20.0)
"""Accepted range of a per-surface factor on the bath's heat-transfer coefficient (``[htc_factor]`` of the constants
file, or the case's ``htc_factor`` table)."""
FLOW_KEYS = ("rotation_rpm", "nozzles", "layout", "id_jet_speed_mm_s", "od_jet_speed_mm_s", "agitation_m_s",
             *CONSTANT_KEYS)
BATH_KEYS = ("quenchant", "liquid_properties", "oil_temperature_C", "agitation", "support", "support_open_fraction",
             "turntable_open_fraction", "constants", "htc_factor", "T_max_C", "T_step_K", *FLOW_KEYS)
ROW_KEYS = ("side", "diameter_mm", "count", "standoff_mm", "height_mm", "height_fraction", "inclination_deg",
            "jet_speed_mm_s")
SUPPORTS = ("turntable", "fixture", "hanging")
"""How the part is held: on a turntable or fixture (its bottom face is covered except ``support_open_fraction``;
that covered share is treated as adiabatic), or hanging (every face open to the oil)."""
MAX_AGITATION_M_S = 10.0
"""Largest bulk oil speed accepted: tank agitators move oil past the work at up to ~1-2 m/s (propeller-agitated
tanks; the reference conditions' jets reach 10.7 m/s at the exit), beyond the flat-plate correlations' use here."""
DEFAULT_LIQUID = "reference_quench_oil"
"""Liquid properties (viscosity, density, ...) and agitation response of the vapour film used with a still-bath
curve when ``liquid_properties`` is not given: the reference mineral oil (materials/SOURCES.md)."""
MAX_JET_SPEED_MM_S = 50_000.0
"""Largest nozzle exit speed accepted (50 m/s): quench-tank agitation and spray nozzles run at up to a few
m/s (the reference conditions: 0.4-10.7 m/s); far above, the free-jet and wall-jet correlations of
quenchsim.bath.correlations are extrapolated beyond any quench practice."""
MAX_ROTATION_RPM = 600.0
"""Largest part rotation accepted (turntables turn at ~1-30 rpm; the reference rings at 11 rpm)."""


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


def _number(spec: dict[str, Any], key: str, field: str, default: float | None = None, *, lo: float | None = None,
            hi: float | None = None, lo_open: bool = False) -> float:
    value = spec.get(key, default)
    name = f"{field}.{key}"
    if value is None:
        raise InputError(name, None, "is required")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(name, value, "must be a finite number")
    if lo is not None and (value <= lo if lo_open else value < lo):
        raise InputError(name, value, f"must be {'>' if lo_open else '>='} {lo:g}")
    if hi is not None and value > hi:
        raise InputError(name, value, f"must be <= {hi:g}")
    return float(value)


def _plain(spec: dict[str, Any]) -> dict[str, Any]:
    """A layout row with its ``{value, range, source}`` entries replaced by their values."""
    return {k: (v["value"] if isinstance(v, dict) and "value" in v else v) for k, v in spec.items()
            if k not in ("source", "range", "range_factor")}


def _row(name: str, spec: Any, bath: dict[str, Any], field: str, where: str | None = None) -> NozzleRow:
    where = where or f"{field}.nozzles.{name}"
    if not isinstance(spec, dict):
        raise InputError(where, spec, "must be a table {diameter_mm, count, standoff_mm, height_mm, ...}")
    spec = _plain(spec)
    require_known_keys(spec, ROW_KEYS, where)
    side = spec.get("side", name.split("_")[0])
    if side not in SIDES:
        raise InputError(f"{where}.side", side, "must be 'id' or 'od' (or start the row name with id_/od_)")
    if "jet_speed_mm_s" in spec:
        speed = _number(spec, "jet_speed_mm_s", where, lo=0.0, hi=MAX_JET_SPEED_MM_S)
    else:
        speed = _number(bath, f"{side}_jet_speed_mm_s", field, lo=0.0, hi=MAX_JET_SPEED_MM_S)
    count = spec.get("count")
    if isinstance(count, float) and count.is_integer():
        count = int(count)
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise InputError(f"{where}.count", count, "must be an integer >= 1")
    if ("height_mm" in spec) == ("height_fraction" in spec):
        raise InputError(f"{where}.height_mm", spec.get("height_mm"), "give height_mm or height_fraction (of the "
                                                                      "part's height), one of them")
    height = _number(spec, "height_mm", where, lo=0.0) * 1e-3 if "height_mm" in spec else None
    fraction = _number(spec, "height_fraction", where, lo=0.0, hi=1.0) if "height_fraction" in spec else None
    return NozzleRow(name=name, side=side, jet_speed_m_s=speed * 1e-3,
                     diameter_m=_number(spec, "diameter_mm", where, lo=0.0, lo_open=True) * 1e-3, count=count,
                     standoff_m=_number(spec, "standoff_mm", where, lo=0.0, lo_open=True) * 1e-3,
                     height_m=height, height_fraction=fraction,
                     inclination_rad=math.radians(_number(spec, "inclination_deg", where, 0.0, lo=-80.0, hi=80.0)))


def _constants_file(name: str, field: str) -> dict[str, Any]:
    data = load_data_file(name, "baths", field)
    if data.get("kind") != "bath_constants":
        raise InputError(field, name, f"is a {data.get('kind', 'untyped')} file; a bath_constants file is needed")
    return data


def load_constants(name: str, field: str = "quench.bath.constants") -> dict[str, float]:
    """The declared flow constants of ``materials/baths/NAME.toml`` (``kind = "bath_constants"``, table ``[flow]``)."""
    flow = _plain(_constants_file(name, field).get("flow", {}))
    for key in CONSTANT_KEYS:
        lo, hi = CONSTANT_LIMITS[key]
        _number(flow, key, f"{Path(name).stem}.flow", lo=lo, hi=hi)
    return {key: float(flow[key]) for key in CONSTANT_KEYS}


def htc_factors(spec: Any, field: str) -> dict[str, float]:
    """A table of per-segment factors on h: ``{segment: factor}`` (or ``{segment: {value, range, source}}``), each in
    :data:`HTC_FACTOR_LIMITS`."""
    if not isinstance(spec, dict):
        raise InputError(field, spec, "must be a table {bore = f, od = f, top = f, bottom = f} of factors on h")
    plain = _plain(spec)
    lo, hi = HTC_FACTOR_LIMITS
    return {str(k): _number(plain, k, field, lo=lo, hi=hi) for k in plain}


def load_htc_factors(name: str, field: str = "quench.bath.constants") -> dict[str, float]:
    """The declared per-surface factors on h of a constants file (table ``[htc_factor]``; none: every factor 1)."""
    return htc_factors(_constants_file(name, field).get("htc_factor", {}), f"{Path(name).stem}.htc_factor")


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


def load_layout(name: str, bath: dict[str, Any], field: str = "quench.bath.layout") -> tuple[NozzleRow, ...]:
    """The nozzle rows of a layout file ``materials/baths/NAME.toml`` (``kind = "nozzle_layout"``, ``[nozzles.*]``)."""
    data = load_data_file(name, "baths", field)
    if data.get("kind") != "nozzle_layout":
        raise InputError(field, name, f"is a {data.get('kind', 'untyped')} file; a nozzle_layout file is needed")
    rows = data.get("nozzles", {})
    if not isinstance(rows, dict) or not rows:
        raise InputError(f"{Path(name).stem}.nozzles", rows, "needs at least one [nozzles.<row>] table")
    return tuple(_row(row, spec, bath, field, where=f"{Path(name).stem}.nozzles.{row}") for row, spec in rows.items())


def check_bath_keys(spec: Any, field: str = "quench.bath") -> None:
    """Every key of a ``[quench.bath]`` table and of its ``[nozzles.<row>]`` tables is known (a misspelt key is
    an error, never ignored); the values are checked by :func:`parse_bath`. For a condition's table too
    (``[conditions.N.quench.bath]``), whichever condition runs."""
    if not isinstance(spec, dict):
        raise InputError(field, spec, "must be a table")
    require_known_keys(spec, BATH_KEYS, field)
    nozzles = spec.get("nozzles", {})
    for name, row in (nozzles.items() if isinstance(nozzles, dict) else ()):
        if isinstance(row, dict):
            require_known_keys(_plain(row), ROW_KEYS, f"{field}.nozzles.{name}")


def parse_bath(spec: dict[str, Any], field: str = "quench.bath") -> BathConfig:
    """Parse a ``[quench.bath]`` table (condition overrides already merged); errors name the field."""
    check_bath_keys(spec, field)
    name = spec.get("quenchant")
    if not isinstance(name, str) or not name:
        raise InputError(f"{field}.quenchant", name, "is required: the name of a materials/quenchants/*.toml file")
    still_curve = None
    if load_data_file(name, "quenchants", f"{field}.quenchant").get("kind") == STILL_BATH_KIND:
        still_curve = load_probe_quenchant(name, f"{field}.quenchant")
        liquid_name = spec.get("liquid_properties", DEFAULT_LIQUID)
        if not isinstance(liquid_name, str) or not liquid_name:
            raise InputError(f"{field}.liquid_properties", liquid_name, "must be the name of a liquid quenchant file")
        oil = load_oil(liquid_name, f"{field}.liquid_properties")
    else:
        if "liquid_properties" in spec:
            raise InputError(f"{field}.liquid_properties", spec["liquid_properties"],
                             f"only applies to a still-bath curve; {name} carries its own liquid properties")
        oil = load_oil(name, f"{field}.quenchant")
    agitation = spec.get("agitation", "flow")
    if agitation not in AGITATION:
        raise InputError(f"{field}.agitation", agitation, f"must be one of {', '.join(AGITATION)}")
    if agitation == "still":
        for key in FLOW_KEYS:
            if key in spec:
                raise InputError(f"{field}.{key}", spec[key], "not allowed in a still bath (agitation = \"still\")")
    support = spec.get("support", "turntable")
    if support not in SUPPORTS:
        raise InputError(f"{field}.support", support, f"must be one of {', '.join(SUPPORTS)}")
    if support == "hanging" and ("support_open_fraction" in spec or "turntable_open_fraction" in spec):
        raise InputError(f"{field}.support_open_fraction", spec.get("support_open_fraction",
                         spec.get("turntable_open_fraction")), "does not apply to a hanging part (every face is open)")
    if "support_open_fraction" in spec and "turntable_open_fraction" in spec:
        raise InputError(f"{field}.turntable_open_fraction", spec["turntable_open_fraction"],
                         "give support_open_fraction or its older name turntable_open_fraction, not both")
    open_key = "turntable_open_fraction" if "turntable_open_fraction" in spec else "support_open_fraction"
    open_fraction = 1.0 if support == "hanging" else _number(spec, open_key, field, 0.5, lo=0.0, hi=1.0)
    T_oil = _number(spec, "oil_temperature_C", field, lo=-20.0)
    if T_oil >= oil.boiling_point_C:
        raise InputError(f"{field}.oil_temperature_C", T_oil,
                         f"must be below the boiling point of {name} ({oil.boiling_point_C:g} C)")
    for side in SIDES:
        if f"{side}_jet_speed_mm_s" in spec:
            _number(spec, f"{side}_jet_speed_mm_s", field, lo=0.0, hi=MAX_JET_SPEED_MM_S)
    nozzles = spec.get("nozzles", {})
    if not isinstance(nozzles, dict):
        raise InputError(f"{field}.nozzles", nozzles, "must be a table of named rows [nozzles.<name>]")
    if "layout" in spec:
        if nozzles:
            raise InputError(f"{field}.layout", spec["layout"], "give a layout file or a nozzles table, not both")
        if not isinstance(spec["layout"], str) or not spec["layout"]:
            raise InputError(f"{field}.layout", spec["layout"], "must be the name of a materials/baths/*.toml layout")
        rows = load_layout(spec["layout"], spec, f"{field}.layout")
    else:
        rows = tuple(_row(row_name, row, spec, field) for row_name, row in nozzles.items())
    constants_name = spec.get("constants", DEFAULT_CONSTANTS)
    if not isinstance(constants_name, str) or not constants_name:
        raise InputError(f"{field}.constants", constants_name, "must be the name of a materials/baths/*.toml file")
    constants = load_constants(constants_name, f"{field}.constants")
    for key in CONSTANT_KEYS:
        if key in spec:
            constants[key] = _number(spec, key, field, lo=CONSTANT_LIMITS[key][0], hi=CONSTANT_LIMITS[key][1])
    factors = {**load_htc_factors(constants_name, f"{field}.constants"),
               **htc_factors(spec.get("htc_factor", {}), f"{field}.htc_factor")}
    T_max = _number(spec, "T_max_C", field, 1100.0, hi=2000.0)
    if T_max <= oil.boiling_point_C:
        raise InputError(f"{field}.T_max_C", T_max, f"must exceed the boiling point {oil.boiling_point_C:g} C")
    return BathConfig(
        liquid=oil, still_curve=still_curve, agitation=agitation,
        agitation_m_s=_number(spec, "agitation_m_s", field, 0.0, lo=0.0, hi=MAX_AGITATION_M_S),
        support=support, oil_temperature_C=T_oil,
        rotation_rpm=_number(spec, "rotation_rpm", field, 0.0, lo=0.0, hi=MAX_ROTATION_RPM),
        rows=rows,
        oil_swirl_fraction=constants["oil_swirl_fraction"], bore_swirl_fraction=constants["bore_swirl_fraction"],
        turntable_open_fraction=open_fraction,
        corner_carryover=constants["corner_carryover"],
        crossflow_up_m_s={side: constants[f"{side}_crossflow_up_m_s"] for side in SIDES},
        T_max_C=T_max,
        T_step_K=_number(spec, "T_step_K", field, 2.0, lo=0.1, hi=50.0),
        htc_factor=factors)
