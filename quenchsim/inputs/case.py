"""The tables of a case file (``quenchsim run CASE.toml``), declared once: every key with its unit, default, limits
and meaning. The case itself, which holds these tables with its resolved steel, section and bath and checks what
ties them together, is :class:`quenchsim.case.Case`; the reference docs/reference/case_keys.md is generated from
these declarations (:mod:`quenchsim.inputs.references`).

A case file's lengths are in mm (``*_mm``), times in s, temperatures in C.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

from quenchsim.errors import InputError, require
from quenchsim.inputs.bath import BathTable
from quenchsim.inputs.declare import REQUIRED, Table, quantity
from quenchsim.inputs.htc import HtcTable

TEMPER_MAX_C = 400.0
"""Highest tempering temperature of the tempering data (its third stage ends at 350 C after 1 h; the fourth stage,
carbide coarsening and recovery, is not modelled)."""
EMISSIVITY_SOURCE = ("oxidised iron and steel at 200-600 C, total (FLIR T8xx user's manual, emissivity Table 38.1, "
                     "after Bramson, Infrared Radiation: A Handbook for Applications; 0.89 at 1227 C)")
"""The source of the default emissivity 0.80 of the transfer, air and temper stages."""


# -- geometry ----------------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class RectangularGeometry(Table):
    """``[geometry] type = "rectangular"``: a ring (or a solid cylinder) of rectangular section, dimensions before the
    quench in mm."""

    type: Literal["rectangular"] = quantity("rectangular", doc="the section's kind")
    reference_state: Literal["annealed", "austenitised"] = quantity(
        "annealed", doc="\"annealed\": the dimensions are the annealed part at room temperature; \"austenitised\": "
        "the hot, stress-free section")
    inner_diameter_mm: float = quantity(REQUIRED, unit="mm", ge=0.0, doc="0 for a solid section (the axis is then a "
                                        "symmetry line)", allowed="is required (0 for a solid section)")
    outer_diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="outer diameter")
    width_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="axial width")
    chamfer_mm: float = quantity(0.0, unit="mm", ge=0.0, doc="45-degree edge chamfer; less than half the wall and "
                                 "the width")
    edge_radius_mm: float = quantity(0.0, unit="mm", ge=0.0, doc="edge radius (instead of a chamfer)")


@dataclass(frozen=True, kw_only=True)
class SphericalOuterGeometry(Table):
    """``[geometry] type = "spherical_outer"``: an outer ring with a spherical raceway centred on the axis at
    mid-width."""

    type: Literal["spherical_outer"] = quantity(REQUIRED, doc="the section's kind")
    reference_state: Literal["annealed", "austenitised"] = quantity("annealed", doc="as for a rectangular section")
    raceway_diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="raceway diameter at mid-width")
    outer_diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="outer diameter")
    width_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="axial width")
    chamfer_mm: float = quantity(0.0, unit="mm", ge=0.0, doc="45-degree edge chamfer")


@dataclass(frozen=True, kw_only=True)
class ProfileSegment(Table):
    """One segment of a general profile: a line to ``to_mm``, or an arc about ``center_mm``."""

    to_mm: tuple[float, float] = quantity(REQUIRED, unit="mm", doc="end point [r, z]",
                                          allowed="must be [r, z] in mm")
    name: str = quantity(REQUIRED, doc="the surface's name (HTC tables, the mesh)")
    center_mm: tuple[float, float] | None = quantity(None, unit="mm", doc="centre [r, z] of an arc",
                                                     allowed="must be [r, z] in mm")

    def check(self) -> None:
        require(self.name != "", "name", self.name, "must be a non-empty string")


@dataclass(frozen=True, kw_only=True)
class ProfileGeometry(Table):
    """``[geometry] type = "profile"``: a closed outline of named line and arc segments (at least 3, all r >= 0)."""

    type: Literal["profile"] = quantity(REQUIRED, doc="the section's kind")
    reference_state: Literal["annealed", "austenitised"] = quantity("annealed", doc="as for a rectangular section")
    start_mm: tuple[float, float] = quantity(REQUIRED, unit="mm", doc="first point [r, z]",
                                             allowed="must be [r, z] in mm")
    segments: tuple[ProfileSegment, ...] = quantity(REQUIRED, doc="the segments in order, back to start_mm")

    def check(self) -> None:
        require(len(self.segments) >= 3, "segments", len(self.segments), "needs >= 3 segments")


Geometry = RectangularGeometry | SphericalOuterGeometry | ProfileGeometry
"""A case's ``[geometry]``, by its ``type``."""


# -- the stages ----------------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class Mesh(Table):
    """``[mesh]``: element sizes."""

    size_mm: float = quantity(5.0, unit="mm", gt=0.0, written=True, doc="element size in the core; at most the "
                              "section's larger extent")
    surface_size_mm: float = quantity(1.2, unit="mm", gt=0.0, written=True, doc="element size at the surface")
    surface_layer_mm: float = quantity(10.0, unit="mm", ge=0.0, written=True,
                                       doc="depth over which the size grows from surface to core")


@dataclass(frozen=True, kw_only=True)
class Process(Table):
    """``[process]``: the austenitising and room temperatures."""

    austenitising_temperature_C: float = quantity(845.0, unit="C", ge=600.0, le=1200.0, written=True,
                                                  doc="the start temperature and the temperature the steel's carbon "
                                                  "is dissolved at; within the steel's tabulated range")
    room_temperature_C: float = quantity(25.0, unit="C", ge=-50.0, le=100.0, written=True,
                                         doc="the closing state's temperature")


@dataclass(frozen=True, kw_only=True)
class Transfer(Table):
    """``[transfer]``: from the furnace to the bath, in still air with radiation."""

    time_s: float = quantity(0.0, unit="s", ge=0.0, written=True, doc="transfer time (0: none)")
    temperature_C: float = quantity(25.0, unit="C", ge=-50.0, le=200.0, written=True, doc="air temperature")
    emissivity: float = quantity(0.8, gt=0.0, le=1.0, written=True, source=EMISSIVITY_SOURCE,
                                 doc="surface emissivity (oxidised steel)")


@dataclass(frozen=True, kw_only=True)
class Quench(Table):
    """``[quench]``: the oil stage."""

    time_s: float = quantity(REQUIRED, unit="s", gt=0.0, doc="time in the quenchant")
    htc_model: Literal["bath", "table"] = quantity("table", doc="\"bath\" (the bath model, [quench.bath]) or "
                                                   "\"table\" ([quench.htc_table])")
    bath: BathTable | None = quantity(None, doc="the bath model (below)")
    htc_table: HtcTable | None = quantity(None, doc="HTC tables (below)")
    immersion_speed_mm_s: float | None = quantity(None, unit="mm/s", gt=0.0, doc="lowers the part bottom face "
                                                  "first (none: immersed at once)",
                                                  allowed="leave it out for a part immersed all at once")

    def check(self) -> None:
        if self.htc_model == "bath":
            require(self.bath is not None and self.bath.quenchant is not None, "bath.quenchant", None,
                    "is required: the name of a materials/quenchants/*.toml file")
        else:
            require(self.htc_table is not None, "htc_table", None, "required (a table) when the htc_model is 'table'")


@dataclass(frozen=True, kw_only=True)
class Air(Table):
    """``[air]``: cooling in air after the quench."""

    temperature_C: float = quantity(25.0, unit="C", ge=-50.0, le=200.0, written=True, doc="air temperature")
    until_max_C: float = quantity(40.0, unit="C", written=True, doc="the stage ends when the hottest point is "
                                  "below this (>= temperature_C)")
    time_s: float = quantity(20000.0, unit="s", ge=0.0, written=True, doc="longest air stage; 0 ends the run with "
                             "the quench")
    htc_model: Literal["natural", "table"] = quantity("natural", written=True, doc="\"natural\" (natural convection "
                                                      "and radiation) or \"table\" ([air.htc_table])")
    emissivity: float = quantity(0.8, ge=0.0, le=1.0, written=True, source=EMISSIVITY_SOURCE,
                                 doc="surface emissivity")
    htc_table: HtcTable | None = quantity(None, doc="with htc_model = \"table\" (as [quench.htc_table])")

    def check(self) -> None:
        require(self.until_max_C >= self.temperature_C, "until_max_C", self.until_max_C,
                f"must be >= {self.temperature_C:g}")
        require(self.htc_model != "table" or self.htc_table is not None, "htc_table", None,
                "required (a table) when the htc_model is 'table'")


@dataclass(frozen=True, kw_only=True)
class Temper(Table):
    """``[temper]``: optional, a temper after the air stage (docs/guide/temper.md); the steel needs tempering data
    (its material file's ``tempering`` key)."""

    temperature_C: float = quantity(REQUIRED, unit="C", doc="furnace temperature; above the room "
                                    "temperature, below the austenitising temperature and at most 400 C (the range "
                                    "of the tempering data)")
    time_s: float = quantity(REQUIRED, unit="s", gt=0.0, doc="time in the furnace from the part's entry; the core "
                             "heats later than the surface", allowed="the time in the furnace")
    htc_model: Literal["natural", "table"] = quantity("natural", written=True, doc="\"natural\" (still furnace air: "
                                                      "natural convection and radiation) or \"table\" "
                                                      "([temper.htc_table])")
    emissivity: float = quantity(0.8, gt=0.0, le=1.0, written=True, source=EMISSIVITY_SOURCE,
                                 doc="surface emissivity (natural)")
    htc_table: HtcTable | None = quantity(None, doc="with htc_model = \"table\" (as [quench.htc_table])")
    cool_until_max_C: float | None = quantity(None, unit="C", doc="after the furnace the part cools in the [air] "
                                              "stage's air until its hottest point is below this (default "
                                              "air.until_max_C)")
    cool_time_s: float = quantity(20000.0, unit="s", ge=0.0, written=True, doc="longest cooling after the furnace")

    def check(self) -> None:
        require(self.htc_model != "table" or self.htc_table is not None, "htc_table", None,
                "required (a table) when the htc_model is 'table'")


@dataclass(frozen=True, kw_only=True)
class TimeControl(Table):
    """``[time]``: adaptive step control.

    A thermal step is limited by the largest nodal temperature change (``max_dT_K``, K) and the largest change of a
    diffusional product's fraction (``max_dX``: pearlite, bainite; martensite follows the temperature and is limited
    through ``max_dT_K``); it grows by at most ``growth`` per step between ``dt_min_s`` and ``dt_max_s``. The stress
    solver (rate-independent: its increments depend on the changes of temperature and phases, not on time) takes one
    step over as many thermal steps as keep the change since its last step within ``mechanics_max_dT_K`` (K, at any
    quadrature point) and ``mechanics_max_dX`` (any phase fraction, martensite included); 0 steps it with every
    thermal step. A thermal step beyond them is split into as many stress steps as keep each within them, along the
    step's own path (temperatures linear in time, phases as the kinetics form them on it). The thermal march is second
    order (BDF2); the stress update is first order in the temperature step (ring A condition 1's ID change moves by
    ~3e-5 mm per kelvin of ``mechanics_max_dT_K``, its stresses not measurably). The defaults (30 K and 0.02 for
    both) keep the time-discretisation error of ring A condition 1 within the project's tolerances
    (validation/quench/convergence)."""

    dt_initial_s: float = quantity(0.02, unit="s", gt=0.0, written=True, doc="first step")
    dt_min_s: float = quantity(1e-3, unit="s", gt=0.0, written=True, doc="smallest step")
    dt_max_s: float = quantity(120.0, unit="s", gt=0.0, written=True, doc="largest step")
    max_dT_K: float = quantity(30.0, unit="K", gt=0.0, written=True,
                               doc="largest nodal temperature change per thermal step")
    max_dX: float = quantity(0.02, gt=0.0, written=True,
                             doc="largest change of a pearlite or bainite fraction per thermal step")
    growth: float = quantity(1.5, gt=1.0, written=True, doc="largest step growth factor")
    mechanics_max_dT_K: float = quantity(30.0, unit="K", ge=0.0, le=200.0, written=True,
                                         doc="temperature change that triggers a stress step (0: every thermal step)")
    mechanics_max_dX: float = quantity(0.02, ge=0.0, le=1.0, written=True, doc="phase-fraction change that "
                                       "triggers a stress step (0: every thermal step)")

    def check(self) -> None:
        require(self.dt_min_s <= self.dt_max_s, "dt_min_s", self.dt_min_s,
                f"must not exceed time.dt_max_s = {self.dt_max_s:g}")


@dataclass(frozen=True, kw_only=True)
class Output(Table):
    """``[output]``: VTK frames and checkpoints."""

    frames: int = quantity(40, ge=2, written=True, doc="VTK frames over the cooling",
                           allowed="must be an integer >= 2")
    checkpoint_minutes: float = quantity(5.0, unit="min", ge=0.0, le=1440.0, written=True,
                                         doc="wall time between checkpoints (0: after every step)")


@dataclass(frozen=True, kw_only=True)
class StressSolverOptions(Table):
    """The stress solver's options (:func:`quenchsim.mechanics.load_mechanics`): a thermo-elastic model has
    ``plasticity`` and ``trip`` false."""

    plasticity: bool = quantity(True, written=True, doc="J2 plasticity")
    trip: bool = quantity(True, written=True, doc="transformation plasticity")
    newton_rtol: float = quantity(1e-8, ge=1e-14, le=1e-2, doc="Newton tolerance relative to the step's residual")
    max_newton_iterations: int = quantity(25, ge=1, le=1000, doc="Newton iterations per stress step")


@dataclass(frozen=True, kw_only=True)
class SolverOptions(StressSolverOptions):
    """The options of a stress model built in code: the case's, with the stress-free temperature (a case sets it
    once, as process.austenitising_temperature_C; None: the mechanics file's ``[reference]``)."""

    austenitizing_T_C: float | None = quantity(None, unit="C", ge=500.0, le=1300.0,
                                               doc="stress-free temperature (default: the mechanics file's)")


@dataclass(frozen=True, kw_only=True)
class MechanicsOptions(StressSolverOptions):
    """``[mechanics]``: whether the stress is solved, the fixed point and the stress solver's options."""

    OTHER_KEYS = ("austenitizing_T_C", "austenitising_T_C", "austenitising_temperature_C")
    """Refused with their own message: a case has one austenitising temperature (its [process] one)."""

    enabled: bool = quantity(True, written=True, doc="false: thermal and metallurgy only")
    fixed_point_mm: tuple[float, float] | None = quantity(None, unit="mm", doc="[r, z] (case geometry) of the point "
                                                          "held axially", allowed="must be [r, z] in mm (case "
                                                          "geometry)")

    def check(self) -> None:
        for key in self.OTHER_KEYS:
            if key in self._given:
                raise InputError(key, self._given[key], "is not a mechanics option: a case has one austenitising "
                                 "temperature, process.austenitising_temperature_C (the stress-free state too); set "
                                 "that")

    def solver_options(self, austenitizing_T_C: float) -> SolverOptions:
        """The stress solver's options of a run austenitised at ``austenitizing_T_C`` (plasticity and TRIP off when
        the stress is not solved: the model then gives the free strains only)."""
        if not self.enabled:
            return SolverOptions(plasticity=False, trip=False, austenitizing_T_C=austenitizing_T_C)
        return SolverOptions(plasticity=self.plasticity, trip=self.trip, newton_rtol=self.newton_rtol,
                             max_newton_iterations=self.max_newton_iterations, austenitizing_T_C=austenitizing_T_C)


@dataclass(frozen=True, kw_only=True)
class Probe(Table):
    """``[[probes]]``: a point whose temperature is recorded (``probes.csv``, column ``<name>_C``)."""

    name: str = quantity(REQUIRED, doc="unique; the column <name>_C of probes.csv", allowed="must be a string")
    r_mm: float = quantity(REQUIRED, unit="mm", ge=0.0, doc="radius from the axis")
    z_mm: float = quantity(REQUIRED, unit="mm", doc="height from the bottom face; the point must lie in the section")


FreeTable = Mapping[str, Any]
"""A table kept as given (``[measured]``, ``[peer]``): read by reports, not by the run."""
