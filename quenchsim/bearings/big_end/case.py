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
from quenchsim.errors import require
from quenchsim.inputs.bearings import BigEndBearing, BigEndFile, ClearanceSetTable
from quenchsim.inputs.declare import from_table
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


def _bearing(t: BigEndBearing) -> Bearing:
    return Bearing(
        outer_race_id=t.outer_race_id_mm * 1e-3,
        roller_diameter=t.roller_diameter_mm * 1e-3,
        roller_length=t.effective_roller_length_mm * 1e-3,
        n_rollers=t.n_rollers,
        pocket_section_od=t.cage_pocket_section_od_mm * 1e-3,
        pocket_contact_length=t.pocket_contact_length_mm * 1e-3,
        land_width=t.cage_land_width_mm * 1e-3,
        lands=t.cage_lands,
        youngs_modulus=t.youngs_modulus_GPa * 1e9,
        poisson=t.poisson_ratio,
    )


def _clearance_sets(sets: tuple[ClearanceSetTable, ...], bearing: Bearing, model: Model
                    ) -> tuple[ClearanceSet, ...]:
    """The clearance sets in SI, each checked against the bearing's geometry (the rollers fit the annulus and the
    pitch circle, the cage guide and pocket section fit)."""
    out = []
    d = bearing.roller_diameter
    for i, s in enumerate(sets):
        sec = f"clearance_set[{i}]"
        guide, pocket, radial = s.guide_mm * 1e-3, s.pocket_mm * 1e-3, s.radial_mm * 1e-3
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
        out.append(ClearanceSet(
            guide=guide, pocket=pocket, radial=radial,
            load_n=None if s.load_kN is None else s.load_kN * 1e3, speed_rpm=s.speed_rpm, revolutions=s.revolutions,
            name=s.name if s.name is not None else (f"set {i + 1}: guide {guide * 1e3:.3f} / pocket {pocket * 1e3:.3f}"
                                                    f" / radial {radial * 1e3:.3f} mm"),
        ))
    return tuple(out)


def _operations(case: BigEndFile) -> dict[str, Operation]:
    ops: dict[str, Operation] = {}
    eng = case.engine
    gravity = 0.0
    if eng is not None:
        gravity = eng.gravity_m_s2
        cycle = GasCycle(
            compression_ratio=eng.compression_ratio, port_closing_deg=eng.port_closing_deg,
            port_opening_deg=eng.port_opening_deg, combustion_start_deg=eng.combustion_start_deg,
            combustion_duration_deg=eng.combustion_duration_deg, wiebe_a=eng.wiebe_a, wiebe_m=eng.wiebe_m,
            polytropic_exponent=eng.polytropic_exponent, heat_release_over_p0_vd=eng.heat_release_over_p0_vd,
            blowdown_deg=eng.blowdown_deg,
        )
        ops["engine"] = Operation("engine", eng.speed_rpm, eng.revolutions, 0.0, eng.crank_radius_mm * 1e-3,
                                  eng.rod_length_mm * 1e-3, eng.gas_force_amplitude_kN * 1e3, cycle, gravity, 0.0)
    st = case.static
    if st is not None:
        ops["static"] = Operation("static", st.speed_rpm, st.revolutions, st.load_kN * 1e3, 0.0, 1.0, 0.0, None,
                                  gravity, 0.0)
    rig = case.rig
    if rig is not None:
        ops["rig"] = Operation("rig", rig.speed_rpm, rig.revolutions, rig.load_kN * 1e3, 0.0, 1.0, 0.0, None,
                               rig.gravity_m_s2, rig.cage_unbalance_g_mm * 1e-6)
    return ops


def load_case(path: str | Path) -> BigEndCase:
    """Read and validate a big-end case file; every length in SI (m) afterwards."""
    path = Path(path)
    data = read_toml(path, "INPUT")
    with reading(path):
        return _case(data, path)


def _case(data: dict[str, Any], path: Path) -> BigEndCase:
    """The checked case of a big-end case file's table ``data`` (:class:`quenchsim.inputs.bearings.BigEndFile`)."""
    case = from_table(BigEndFile, data)
    bearing = _bearing(case.bearing)
    m = case.masses
    masses = Masses(m.roller_kg, m.roller_inertia_kg_m2, m.cage_kg, m.cage_inertia_kg_m2, m.outer_ring_kg,
                    reciprocating=m.reciprocating_kg)
    lub = case.lubrication
    require(lub.oil in available_oils(), "lubrication.oil", lub.oil,
            f"must be one of {available_oils()} (materials/lubricants/*.toml)")
    lubrication = Lubrication(lub.oil, lub.temperature_C, lub.composite_roughness_um * 1e-6,
                              lub.film_parameter_boundary, lub.film_parameter_full)
    mod = case.model
    model = Model(mod.boundary_friction, mod.pocket_friction, mod.guide_friction, mod.contact_damping_ratio,
                  mod.friction_regularisation_m_s, mod.entrainment_floor_m_s,
                  guide_min_film=mod.guide_min_film_um * 1e-6)
    return BigEndCase(path, bearing, masses, _clearance_sets(case.clearance_set, bearing, model), _operations(case),
                      lubrication, model, case.output.samples_per_revolution, case.output.transient_revolutions)
