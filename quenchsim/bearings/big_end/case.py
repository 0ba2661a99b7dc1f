"""Big-end bearing case files (TOML): schema, unit conversion to SI and input validation.

Layout: [bearing], [masses], [lubrication], [model], [output], [[clearance_set]] and one section per
operating mode: [engine] (crank-slider + gas force), [static] (constant load, rotating inner ring),
[rig] (validation rig: pin fixed, outer ring loaded, cage unbalance). A clearance set may override
the load, speed and run length of the static/rig section (``load_kN``, ``speed_rpm``, ``revolutions``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from quenchsim.bearings.big_end.engine import GasCycle
from quenchsim.bearings.big_end.lubricant import available_oils
from quenchsim.errors import InputError, require
from quenchsim.inputs.reader import read_toml, reading

MODES = ("engine", "static", "rig")
MAX_INTERFERENCE_FRACTION = 0.01  # preload (negative radial clearance) limited to 1 % of the roller
# diameter: beyond it the Palmgren law (small elastic approach) no longer describes the contact.


@dataclass(frozen=True)
class Bearing:
    outer_race_id: float
    roller_diameter: float
    roller_length: float
    n_rollers: int
    pocket_section_od: float
    pocket_contact_length: float
    land_width: float
    lands: int
    youngs_modulus: float
    poisson: float


@dataclass(frozen=True)
class Masses:
    roller: float
    roller_inertia: float
    cage: float
    cage_inertia: float
    outer_ring: float
    reciprocating: float


@dataclass(frozen=True)
class ClearanceSet:
    guide: float
    pocket: float
    radial: float
    load_n: float | None
    speed_rpm: float | None
    revolutions: float | None
    name: str


@dataclass(frozen=True)
class Operation:
    """One operating mode: speed, revolutions, constant load (static/rig) or engine data."""

    mode: str
    speed_rpm: float
    revolutions: float
    load_n: float
    crank_radius: float
    rod_length: float
    gas_amplitude_n: float
    gas_cycle: GasCycle | None
    gravity: float
    cage_unbalance_kg_m: float


@dataclass(frozen=True)
class Lubrication:
    oil: str
    temperature_C: float
    roughness: float
    film_lo: float
    film_hi: float


@dataclass(frozen=True)
class Model:
    boundary_friction: float
    pocket_friction: float
    guide_friction: float
    damping_ratio: float
    friction_regularisation: float
    entrainment_floor: float
    guide_min_film: float


@dataclass(frozen=True)
class BigEndCase:
    path: Path
    bearing: Bearing
    masses: Masses
    clearance_sets: tuple[ClearanceSet, ...]
    operations: dict[str, Operation]
    lubrication: Lubrication
    model: Model
    samples_per_revolution: int
    transient_revolutions: float


def _get(table: dict[str, Any], section: str, key: str, positive: bool = True) -> float:
    field = f"{section}.{key}"
    if key not in table:
        raise InputError(field, None, "is required")
    value = table[key]
    require(isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value),
            field, value, "must be a finite number")
    if positive:
        require(value > 0, field, value, "must be > 0")
    return float(value)


def _section(data: dict[str, Any], name: str) -> dict[str, Any]:
    if name not in data or not isinstance(data[name], dict):
        raise InputError(name, None, f"section [{name}] is required")
    return data[name]


def _bearing(t: dict[str, Any]) -> Bearing:
    n: Any = t.get("n_rollers")   # checked by require below
    require(isinstance(n, int) and not isinstance(n, bool) and n >= 3, "bearing.n_rollers", n,
            "must be an integer >= 3")
    lands = t.get("cage_lands", 2)
    require(lands in (1, 2), "bearing.cage_lands", lands, "must be 1 or 2")
    nu = _get(t, "bearing", "poisson_ratio")
    require(nu < 0.5, "bearing.poisson_ratio", nu, "must be < 0.5")
    width = _get(t, "bearing", "width_mm")
    occupied = _get(t, "bearing", "effective_roller_length_mm") + lands * _get(t, "bearing", "cage_land_width_mm")
    require(occupied <= width, "bearing.width_mm", width,
            f"must hold the roller length + {lands} cage land(s) = {occupied:.3f} mm")
    return Bearing(
        outer_race_id=_get(t, "bearing", "outer_race_id_mm") * 1e-3,
        roller_diameter=_get(t, "bearing", "roller_diameter_mm") * 1e-3,
        roller_length=_get(t, "bearing", "effective_roller_length_mm") * 1e-3,
        n_rollers=n,
        pocket_section_od=_get(t, "bearing", "cage_pocket_section_od_mm") * 1e-3,
        pocket_contact_length=_get(t, "bearing", "pocket_contact_length_mm") * 1e-3,
        land_width=_get(t, "bearing", "cage_land_width_mm") * 1e-3,
        lands=lands,
        youngs_modulus=_get(t, "bearing", "youngs_modulus_GPa") * 1e9,
        poisson=nu,
    )


def _clearance_sets(data: dict[str, Any], bearing: Bearing, model: Model) -> tuple[ClearanceSet, ...]:
    sets: Any = data.get("clearance_set")
    require(isinstance(sets, list) and len(sets) > 0, "clearance_set", sets,
            "at least one [[clearance_set]] is required")
    out = []
    d = bearing.roller_diameter
    for i, s in enumerate(sets, start=1):
        sec = f"clearance_set[{i}]"
        guide = _get(s, sec, "guide_mm") * 1e-3
        pocket = _get(s, sec, "pocket_mm") * 1e-3
        radial = _get(s, sec, "radial_mm", positive=False) * 1e-3
        require(radial > -MAX_INTERFERENCE_FRACTION * d, f"{sec}.radial_mm", radial * 1e3,
                f"interference must be < {MAX_INTERFERENCE_FRACTION * d * 1e3:.4f} mm "
                f"({MAX_INTERFERENCE_FRACTION:.0%} of the roller diameter)")
        inner_od = bearing.outer_race_id - 2 * d - radial
        require(inner_od > 0.0, "bearing.roller_diameter_mm", d * 1e3,
                f"rollers must fit in the annulus: 2 x roller diameter + radial clearance "
                f"({(2 * d + radial) * 1e3:.3f} mm) must be < outer race ID {bearing.outer_race_id * 1e3:.3f} mm")
        pitch = 0.5 * (inner_od + bearing.outer_race_id) / 2
        require(bearing.n_rollers * (d + pocket) < 2 * math.pi * pitch, "bearing.n_rollers",
                bearing.n_rollers, f"rollers + pockets do not fit on the pitch circle "
                f"(n x (d + pocket clearance) must be < pi x pitch diameter = {2e3 * math.pi * pitch:.3f} mm)")
        require(guide > 2 * model.guide_min_film, f"{sec}.guide_mm", guide * 1e3,
                f"must exceed twice model.guide_min_film_um = {model.guide_min_film * 1e6} um")
        require(bearing.outer_race_id - guide > bearing.pocket_section_od, f"{sec}.guide_mm", guide * 1e3,
                "cage land OD (outer race ID - guide clearance) must exceed the pocket-section OD")
        require(bearing.pocket_section_od > 2 * pitch, "bearing.cage_pocket_section_od_mm",
                bearing.pocket_section_od * 1e3, "must exceed the roller pitch diameter")
        load = s.get("load_kN")
        speed = s.get("speed_rpm")
        revs = s.get("revolutions")
        out.append(ClearanceSet(
            guide=guide, pocket=pocket, radial=radial,
            load_n=None if load is None else _get(s, sec, "load_kN") * 1e3,
            speed_rpm=None if speed is None else _get(s, sec, "speed_rpm"),
            revolutions=None if revs is None else _get(s, sec, "revolutions"),
            name=str(s.get("name", f"set {i}: guide {guide * 1e3:.3f} / pocket {pocket * 1e3:.3f} / "
                                   f"radial {radial * 1e3:.3f} mm")),
        ))
    return tuple(out)


def _operations(data: dict[str, Any]) -> dict[str, Operation]:
    ops: dict[str, Operation] = {}
    eng = data.get("engine")
    gravity = 0.0
    if isinstance(eng, dict):
        gravity = _get(eng, "engine", "gravity_m_s2", positive=False)
        cycle = GasCycle(
            compression_ratio=_get(eng, "engine", "compression_ratio"),
            port_closing_deg=_get(eng, "engine", "port_closing_deg", positive=False),
            port_opening_deg=_get(eng, "engine", "port_opening_deg", positive=False),
            combustion_start_deg=_get(eng, "engine", "combustion_start_deg", positive=False),
            combustion_duration_deg=_get(eng, "engine", "combustion_duration_deg"),
            wiebe_a=_get(eng, "engine", "wiebe_a"),
            wiebe_m=_get(eng, "engine", "wiebe_m"),
            polytropic_exponent=_get(eng, "engine", "polytropic_exponent"),
            heat_release_over_p0_vd=_get(eng, "engine", "heat_release_over_p0_vd", positive=False),
            blowdown_deg=_get(eng, "engine", "blowdown_deg"),
        )
        require(cycle.compression_ratio > 1, "engine.compression_ratio", cycle.compression_ratio, "must be > 1")
        crank = _get(eng, "engine", "crank_radius_mm") * 1e-3
        rod = _get(eng, "engine", "rod_length_mm") * 1e-3
        require(rod > crank, "engine.rod_length_mm", rod * 1e3, f"must exceed the crank radius {crank * 1e3} mm")
        ops["engine"] = Operation("engine", _get(eng, "engine", "speed_rpm"), _get(eng, "engine", "revolutions"),
                                  0.0, crank, rod, _get(eng, "engine", "gas_force_amplitude_kN", positive=False) * 1e3,
                                  cycle, gravity, 0.0)
    st = data.get("static")
    if isinstance(st, dict):
        ops["static"] = Operation("static", _get(st, "static", "speed_rpm"), _get(st, "static", "revolutions"),
                                  _get(st, "static", "load_kN", positive=False) * 1e3, 0.0, 1.0, 0.0, None,
                                  gravity, 0.0)
    rig = data.get("rig")
    if isinstance(rig, dict):
        ops["rig"] = Operation("rig", _get(rig, "rig", "speed_rpm"), _get(rig, "rig", "revolutions"),
                               _get(rig, "rig", "load_kN", positive=False) * 1e3, 0.0, 1.0, 0.0, None,
                               _get(rig, "rig", "gravity_m_s2", positive=False),
                               _get(rig, "rig", "cage_unbalance_g_mm", positive=False) * 1e-6)
    require(bool(ops), "engine|static|rig", None, "the case needs at least one of [engine], [static], [rig]")
    return ops


def load_case(path: str | Path) -> BigEndCase:
    """Read and validate a big-end case file; every length in SI (m) afterwards."""
    path = Path(path)
    data = read_toml(path, "INPUT")
    with reading(path):
        return _case(data, path)


def _case(data: dict[str, Any], path: Path) -> BigEndCase:
    """The checked case of a big-end case file's table ``data``."""
    bearing = _bearing(_section(data, "bearing"))
    m = _section(data, "masses")
    roller, roller_inertia, cage, cage_inertia, outer_ring = (
        _get(m, "masses", k) for k in ("roller_kg", "roller_inertia_kg_m2", "cage_kg", "cage_inertia_kg_m2",
                                       "outer_ring_kg"))
    masses = Masses(roller, roller_inertia, cage, cage_inertia, outer_ring,
                    reciprocating=(_get(m, "masses", "reciprocating_kg", positive=False)
                                   if "reciprocating_kg" in m else 0.0))
    lub = _section(data, "lubrication")
    oil: Any = lub.get("oil")
    require(isinstance(oil, str) and oil in available_oils(), "lubrication.oil", oil,
            f"must be one of {available_oils()} (materials/lubricants/*.toml)")
    lubrication = Lubrication(oil, _get(lub, "lubrication", "temperature_C", positive=False),
                              _get(lub, "lubrication", "composite_roughness_um") * 1e-6,
                              _get(lub, "lubrication", "film_parameter_boundary"),
                              _get(lub, "lubrication", "film_parameter_full"))
    require(lubrication.film_hi > lubrication.film_lo, "lubrication.film_parameter_full", lubrication.film_hi,
            "must exceed film_parameter_boundary")
    mod = _section(data, "model")
    frictions = []
    for k in ("boundary_friction", "pocket_friction", "guide_friction"):
        frictions.append(_get(mod, "model", k, positive=False))
        require(frictions[-1] >= 0.0, f"model.{k}", frictions[-1], "must be >= 0 (a friction coefficient)")
    damping_ratio, friction_regularisation, entrainment_floor = (_get(mod, "model", k) for k in (
        "contact_damping_ratio", "friction_regularisation_m_s", "entrainment_floor_m_s"))
    model = Model(frictions[0], frictions[1], frictions[2], damping_ratio, friction_regularisation,
                  entrainment_floor, guide_min_film=_get(mod, "model", "guide_min_film_um") * 1e-6)
    out = _section(data, "output")
    spr: Any = out.get("samples_per_revolution")
    require(isinstance(spr, int) and spr >= 36, "output.samples_per_revolution", spr, "must be an integer >= 36")
    return BigEndCase(path, bearing, masses, _clearance_sets(data, bearing, model), _operations(data), lubrication,
                      model, spr, _get(out, "output", "transient_revolutions", positive=False))
