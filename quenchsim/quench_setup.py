"""What a quench run is built from: the section in its austenitised and "before" geometries (with the stress model
when the stress is solved), the stages and their boundary HTCs, and the step rule with the case's limits."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import skfem

from quenchsim import mechanics, metallurgy
from quenchsim.case import Case
from quenchsim.errors import InputError
from quenchsim.geometry import BoundaryPoints, SectionMesh, boundary_points, mesh_profile
from quenchsim.geometry.profile import MM, Profile
from quenchsim.fem import INTORDER
from quenchsim.materials import thermal_properties
from quenchsim.results.final_part import FinalPart
from quenchsim.results.postprocess import NodalProjection
from quenchsim.thermal import (AxisymmetricP2, HeatingHTC, ImmersionHTC, SurfaceTemperatureHTC, TableHTC,
                               ThermalSolver, parse_htc_table)
from quenchsim.thermal.steps import REJECT_ABOVE, StepController


# -- section ------------------------------------------------------------------------------------
@dataclass
class Section:
    """The meshed section in the quench's (austenitised) geometry and in the "before" (case-file
    reference) geometry, the stress model when the stress is solved, and the scale between them."""

    hot: SectionMesh
    before_mesh: skfem.MeshTri
    profile_before: Profile
    case_to_hot: float
    mech_model: Any


def build_section(case: Case, msh_path: Path) -> Section:
    """Mesh the case's profile and move it to the austenitised geometry.

    The quench starts from the austenitised section whether or not the stress is solved; the "before"
    section is the room-temperature annealed one, smaller by the free strain between the two states.
    The case file gives one of them (``geometry.reference_state``)."""
    T_aust = case.process.austenitising_temperature_C
    section = mesh_profile(case.profile, case.mesh.size_mm * MM, case.mesh.surface_size_mm * MM,
                           case.mesh.surface_layer_mm * MM, msh_path=msh_path)
    if case.steel.mechanics is None:
        return Section(section, section.mesh, case.profile, 1.0, None)
    solve_stress = case.mechanics.enabled
    # a thermal-only run needs the free strains (for the hot section) but no flow or TRIP data
    mech_model = mechanics.load_mechanics(case.steel, case.mechanics.solver_options(T_aust))
    scale = mechanics.austenitized_scale(mech_model)
    mesh = section.mesh
    if case.geometry.reference_state == "annealed":
        profile_before, profile, case_to_hot = case.profile, case.profile.scaled(scale), scale
        hot, before_mesh = skfem.MeshTri(mesh.p * scale, mesh.t), mesh
    else:
        profile_before, profile, case_to_hot = case.profile.scaled(1.0 / scale), case.profile, 1.0
        hot, before_mesh = mesh, skfem.MeshTri(mesh.p / scale, mesh.t)
    return Section(SectionMesh(mesh=hot, boundaries=section.boundaries, profile=profile), before_mesh, profile_before,
                   case_to_hot, mech_model if solve_stress else None)


# -- boundary and HTC ---------------------------------------------------------------------------
def cooled_surface_points(fe: AxisymmetricP2, section: SectionMesh) -> BoundaryPoints:
    """The facet quadrature points of the cooled surface (everything but the axis), labelled by segment."""
    return boundary_points(section, fe.facets, fe.facet_r, fe.facet_z, fe.facet_normals)


@dataclass(frozen=True)
class Stage:
    """One stage of the run: it lasts ``duration_s`` or ends once the hottest point is at or below
    ``until_max_C``; its boundary is :func:`stage_htc` of its ``name``."""

    name: str
    duration_s: float
    until_max_C: float = -math.inf


TEMPER_STAGES = ("temper", "temper_cool")
"""The stages a ``[temper]`` adds after the air stage: the furnace, then air cooling."""


def stages(case: Case) -> list[Stage]:
    """The stages of a run in order (the progress bar and the checkpoints count them)."""
    plan = [Stage("transfer", case.transfer.time_s), Stage("quench", case.quench.time_s),
            Stage("air", case.air.time_s, case.air.until_max_C)]
    if case.temper is not None:
        cool_until_max_C = case.temper.cool_until_max_C
        assert cool_until_max_C is not None   # the case sets it (default: the air stage's, Case.check)
        plan += [Stage("temper", case.temper.time_s), Stage("temper_cool", case.temper.cool_time_s, cool_until_max_C)]
    return plan


def step_controller(ctl: Any) -> StepController:
    """The quench's step rule (:mod:`quenchsim.thermal.steps`) with the case's ``[time]`` limits."""
    return StepController(ctl.growth, ctl.dt_min_s, ctl.dt_max_s, ctl.max_dT_K, ctl.max_dX,
                          reject_above=REJECT_ABOVE)


def stage_htc(case: Case, stage: str, points: BoundaryPoints) -> Any:
    """The HTC of the transfer, quench or air stage as ``htc(T_surface, t)`` with ``ambient_C`` per point.

    The quench stage starts when the transfer ends (``transfer.time_s``); with ``quench.immersion_speed_mm_s`` the
    part enters the oil bottom face first and the points above the oil level keep the transfer air's HTC."""
    from quenchsim import bath

    if stage == "transfer":
        return SurfaceTemperatureHTC(bath.air_htc(points, case.transfer.temperature_C, case.transfer.emissivity))
    if stage == "temper":
        temper = case.temper
        assert temper is not None   # a temper stage exists only with a [temper] table
        if temper.htc_model == "table":
            assert temper.htc_table is not None   # the "table" model carries its tables (Temper.check)
            return parse_htc_table(temper.htc_table, points.segment, "temper.htc_table")
        return HeatingHTC(SurfaceTemperatureHTC(bath.air_htc(points, temper.temperature_C, temper.emissivity)))
    if stage == "quench":
        # the quench stage carries its htc_table with the "table" model, the case its bath otherwise (Quench.check)
        oil: TableHTC | SurfaceTemperatureHTC
        if case.quench.htc_model == "table":
            assert case.quench.htc_table is not None
            oil = parse_htc_table(case.quench.htc_table, points.segment, "quench.htc_table")
        else:
            assert case.bath is not None
            oil = SurfaceTemperatureHTC(bath.boundary_htc(case.bath, points))
        if case.quench.immersion_speed_mm_s is None:
            return oil
        return ImmersionHTC(oil, stage_htc(case, "transfer", points), points.z_m, points.extent.z_min_m,
                            case.quench.immersion_speed_mm_s * MM, case.transfer.time_s)
    if case.air.htc_model == "table":
        assert case.air.htc_table is not None   # the "table" model carries its tables (Air.check)
        return parse_htc_table(case.air.htc_table, points.segment, "air.htc_table")
    return SurfaceTemperatureHTC(bath.air_htc(points, case.air.temperature_C, case.air.emissivity))


def require_mechanics_data(case: Case) -> None:
    """Refuse a mechanics run of a steel that has no mechanics data, before any work: the run would compute no
    dimensions, distortion or stresses (a fitted steel, ``material = "path/NAME.toml"``, has none until
    ``NAME.mechanics.toml`` is put beside it). A steel that does not transform is thermal only and passes."""
    if not case.mechanics.enabled or case.steel.mechanics is not None or not case.steel.transforms:
        return
    stem = Path(case.material).with_suffix("") if case.material.endswith(".toml") else Path(case.material)
    raise InputError("material", case.material, f"has no mechanics data ({stem.name}.mechanics.toml beside it or a "
                     "[mechanics] table in it): no dimensions or stresses could be computed; add that file "
                     "(docs/guide/bring_a_steel.md) or run without mechanics: --set mechanics.enabled=false")


class QuenchModel:
    """The discretised quench of a case: the section in its two geometries, the thermal solver with the phase model,
    the stress solver when the stress is solved (``mech``, None otherwise), the final part and the probes' reading
    matrix (their positions move with the section to the austenitised geometry)."""

    def __init__(self, case: Case, mesh_path: Path) -> None:
        """Mesh the case's section (written to ``mesh_path``) and build the solvers on it from the case's steel."""
        steel = case.steel
        self.T_aust = case.process.austenitising_temperature_C
        self.T_room = case.process.room_temperature_C
        built = build_section(case, mesh_path)
        self.section, self.before_mesh, self.profile_before = built.hot, built.before_mesh, built.profile_before
        self.profile, self.case_to_hot, self.mech_model = built.hot.profile, built.case_to_hot, built.mech_model
        cooled = np.concatenate([f for n, f in self.section.boundaries.items() if n != "axis"])
        self.fe = AxisymmetricP2(self.section.mesh, cooled, intorder=INTORDER)
        self.points = cooled_surface_points(self.fe, self.section)
        self.kin = metallurgy.load_kinetics(steel, self.T_aust) if steel.transforms else None
        self.tempering = (None if case.temper is None or self.kin is None
                          else metallurgy.load_tempering(steel, self.kin))
        # the quench's phase model; a [temper] replaces it by the tempering one (pipeline.QuenchRun._start_temper)
        self.phase_model: Any = metallurgy.PhaseModel(self.kin)
        self.thermal = ThermalSolver(self.fe, thermal_properties(steel), self.T_aust, self.phase_model,
                                     self.phase_model.initial_state(self.fe.r_qp.shape))
        self.projection = NodalProjection(self.section.mesh, INTORDER)
        fixed = case.mechanics.fixed_point_mm
        fixed_m = None if fixed is None else (fixed[0] * MM * self.case_to_hot, fixed[1] * MM * self.case_to_hot)
        self.mech = mechanics.MechanicsSolver(self.section.mesh, self.mech_model, fixed_m) if self.mech_model else None
        self.final_part = FinalPart(self.section.mesh, self.before_mesh, self.mech)
        pts = np.array([[p.r_mm * MM, p.z_mm * MM] for p in case.probes]).reshape(-1, 2)
        self.probe_matrix = self.fe.basis.probes(pts.T * self.case_to_hot) if len(pts) else None
