"""The bearing solvers' case files, declared once: a big-end bearing case (``quenchsim bearings big-end``) and a
run-out case (``quenchsim bearings runout``). Units in the key names where not SI; the solvers' case objects (SI)
are built, and the rules that need several keys checked, by :mod:`quenchsim.bearings.big_end.case` and
:mod:`quenchsim.bearings.runout.case`."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from quenchsim.errors import require
from quenchsim.inputs.declare import REQUIRED, Table, quantity

# -- big-end bearing ------------------------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class BigEndBearing(Table):
    """``[bearing]``: the needle-roller big-end bearing."""

    outer_race_id_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="outer race inner diameter")
    roller_diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="roller diameter")
    effective_roller_length_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="effective roller length")
    width_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="bearing (cage) width")
    n_rollers: int = quantity(REQUIRED, ge=3, doc="rollers", allowed="must be an integer >= 3")
    cage_pocket_section_od_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="OD of the cage's pocket section")
    pocket_contact_length_mm: float = quantity(REQUIRED, unit="mm", gt=0.0,
                                               doc="roller/pocket effective contact length (one side)")
    cage_land_width_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="width of a cage land")
    cage_lands: Literal[1, 2] = quantity(2, doc="cage lands", allowed="must be 1 or 2")
    youngs_modulus_GPa: float = quantity(REQUIRED, unit="GPa", gt=0.0, doc="Young's modulus")
    poisson_ratio: float = quantity(REQUIRED, gt=0.0, lt=0.5, doc="Poisson's ratio")

    def check(self) -> None:
        occupied = self.effective_roller_length_mm + self.cage_lands * self.cage_land_width_mm
        require(occupied <= self.width_mm, "width_mm", self.width_mm,
                f"must hold the roller length + {self.cage_lands} cage land(s) = {occupied:.3f} mm")


@dataclass(frozen=True, kw_only=True)
class BigEndMasses(Table):
    """``[masses]``."""

    roller_kg: float = quantity(REQUIRED, unit="kg", gt=0.0, doc="one roller")
    roller_inertia_kg_m2: float = quantity(REQUIRED, unit="kg m2", gt=0.0, doc="one roller's moment of inertia")
    cage_kg: float = quantity(REQUIRED, unit="kg", gt=0.0, doc="the cage")
    cage_inertia_kg_m2: float = quantity(REQUIRED, unit="kg m2", gt=0.0, doc="the cage's moment of inertia")
    outer_ring_kg: float = quantity(REQUIRED, unit="kg", gt=0.0, doc="the (virtual) outer ring")
    reciprocating_kg: float = quantity(0.0, unit="kg", doc="piston + reciprocating con-rod mass")


@dataclass(frozen=True, kw_only=True)
class BigEndEngine(Table):
    """``[engine]``: crank-slider with a gas force (Wiebe heat release)."""

    crank_radius_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="crank radius")
    rod_length_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="con-rod length (> crank radius)")
    speed_rpm: float = quantity(REQUIRED, unit="rpm", gt=0.0, doc="crank speed")
    gas_force_amplitude_kN: float = quantity(REQUIRED, unit="kN", doc="full amplitude of the gas force")
    revolutions: float = quantity(REQUIRED, gt=0.0, doc="crank revolutions per run")
    compression_ratio: float = quantity(REQUIRED, gt=1.0, doc="compression ratio")
    port_closing_deg: float = quantity(REQUIRED, unit="deg", doc="port closing")
    port_opening_deg: float = quantity(REQUIRED, unit="deg", doc="port opening")
    combustion_start_deg: float = quantity(REQUIRED, unit="deg", doc="start of combustion")
    combustion_duration_deg: float = quantity(REQUIRED, unit="deg", gt=0.0, doc="combustion duration")
    wiebe_a: float = quantity(REQUIRED, gt=0.0, doc="Wiebe efficiency parameter")
    wiebe_m: float = quantity(REQUIRED, gt=0.0, doc="Wiebe form factor")
    polytropic_exponent: float = quantity(REQUIRED, gt=0.0, doc="polytropic exponent")
    heat_release_over_p0_vd: float = quantity(REQUIRED, doc="heat release over p0 V_d")
    blowdown_deg: float = quantity(REQUIRED, unit="deg", gt=0.0, doc="blowdown duration")
    gravity_m_s2: float = quantity(REQUIRED, unit="m/s2", doc="gravity")

    def check(self) -> None:
        require(self.rod_length_mm > self.crank_radius_mm, "rod_length_mm", self.rod_length_mm,
                f"must exceed the crank radius {self.crank_radius_mm} mm")


@dataclass(frozen=True, kw_only=True)
class BigEndStatic(Table):
    """``[static]``: a constant load, the inner ring rotating."""

    load_kN: float = quantity(REQUIRED, unit="kN", doc="load")
    speed_rpm: float = quantity(REQUIRED, unit="rpm", gt=0.0, doc="speed")
    revolutions: float = quantity(REQUIRED, gt=0.0, doc="revolutions per run")


@dataclass(frozen=True, kw_only=True)
class BigEndRig(BigEndStatic):
    """``[rig]``: the validation rig -- pin fixed, outer ring loaded, cage unbalance."""

    cage_unbalance_g_mm: float = quantity(REQUIRED, unit="g mm", doc="cage unbalance")
    gravity_m_s2: float = quantity(REQUIRED, unit="m/s2", doc="gravity")


@dataclass(frozen=True, kw_only=True)
class BigEndLubrication(Table):
    """``[lubrication]``."""

    oil: str = quantity(REQUIRED, doc="materials/lubricants/NAME.toml")
    temperature_C: float = quantity(REQUIRED, unit="C", doc="oil temperature")
    composite_roughness_um: float = quantity(REQUIRED, unit="um", gt=0.0, doc="composite surface roughness")
    film_parameter_boundary: float = quantity(REQUIRED, gt=0.0, doc="Lambda below: boundary friction")
    film_parameter_full: float = quantity(REQUIRED, gt=0.0, doc="Lambda above: full EHL film")

    def check(self) -> None:
        require(self.film_parameter_full > self.film_parameter_boundary, "film_parameter_full",
                self.film_parameter_full, "must exceed film_parameter_boundary")


@dataclass(frozen=True, kw_only=True)
class BigEndModel(Table):
    """``[model]``: contact and friction model."""

    boundary_friction: float = quantity(REQUIRED, ge=0.0, doc="friction when the film breaks down",
                                        allowed="must be >= 0 (a friction coefficient)")
    pocket_friction: float = quantity(REQUIRED, ge=0.0, doc="roller-pocket friction",
                                      allowed="must be >= 0 (a friction coefficient)")
    guide_friction: float = quantity(REQUIRED, ge=0.0, doc="cage-guide friction",
                                     allowed="must be >= 0 (a friction coefficient)")
    contact_damping_ratio: float = quantity(REQUIRED, gt=0.0, doc="contact damping ratio")
    friction_regularisation_m_s: float = quantity(REQUIRED, unit="m/s", gt=0.0, doc="friction regularisation speed")
    entrainment_floor_m_s: float = quantity(REQUIRED, unit="m/s", gt=0.0, doc="smallest entrainment speed")
    guide_min_film_um: float = quantity(REQUIRED, unit="um", gt=0.0, doc="smallest guide film")


@dataclass(frozen=True, kw_only=True)
class BigEndOutput(Table):
    """``[output]``."""

    samples_per_revolution: int = quantity(REQUIRED, ge=36, doc="output samples per revolution",
                                           allowed="must be an integer >= 36")
    transient_revolutions: float = quantity(REQUIRED, doc="revolutions excluded from the statistics")


@dataclass(frozen=True, kw_only=True)
class ClearanceSetTable(Table):
    """``[[clearance_set]]``: one set of clearances (and optionally the load, speed and run length of the
    static/rig section)."""

    name: str | None = quantity(None, doc="a label (default: the clearances)")
    guide_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="cage guide clearance")
    pocket_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="pocket clearance")
    radial_mm: float = quantity(REQUIRED, unit="mm", doc="radial clearance (< 0: interference)")
    load_kN: float | None = quantity(None, unit="kN", gt=0.0, doc="load (overrides the section's)")
    speed_rpm: float | None = quantity(None, unit="rpm", gt=0.0, doc="speed (overrides the section's)")
    revolutions: float | None = quantity(None, gt=0.0, doc="revolutions (overrides the section's)")


@dataclass(frozen=True, kw_only=True)
class BigEndFile(Table):
    """A big-end bearing case file: the bearing, masses, lubrication, model and output, the clearance sets and at
    least one operating mode ([engine], [static], [rig])."""

    UNKNOWN = "unknown table or key"

    bearing: BigEndBearing = quantity(REQUIRED, doc="the bearing", allowed="section [bearing] is required")
    masses: BigEndMasses = quantity(REQUIRED, doc="masses", allowed="section [masses] is required")
    engine: BigEndEngine | None = quantity(None, doc="crank-slider with gas force")
    static: BigEndStatic | None = quantity(None, doc="constant load")
    rig: BigEndRig | None = quantity(None, doc="the validation rig")
    lubrication: BigEndLubrication = quantity(REQUIRED, doc="the oil", allowed="section [lubrication] is required")
    model: BigEndModel = quantity(REQUIRED, doc="contact and friction", allowed="section [model] is required")
    output: BigEndOutput = quantity(REQUIRED, doc="output", allowed="section [output] is required")
    clearance_set: tuple[ClearanceSetTable, ...] = quantity(REQUIRED, doc="the clearance sets (>= 1)",
                                                            allowed="at least one [[clearance_set]] is required")

    def check(self) -> None:
        require(len(self.clearance_set) > 0, "clearance_set", [], "at least one [[clearance_set]] is required")
        require(any(m is not None for m in (self.engine, self.static, self.rig)), "engine|static|rig", None,
                "the case needs at least one of [engine], [static], [rig]")


# -- run-out ---------------------------------------------------------------------------------------------------------
DEFAULT_PEAK_THRESHOLD_REL = 1.0e-3
"""Default relative threshold of the run-out spectrum's peak list: lines below 1e-3 of the strongest line (-60 dB)
are not listed; the Hann window's leakage at 3 bins from a line is already below -60 dB."""



@dataclass(frozen=True, kw_only=True)
class RunoutBearing(Table):
    """``[bearing]`` of a run-out case: a deep-groove ball bearing under a pure axial load."""

    pitch_diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="pitch diameter")
    ball_diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="ball diameter (< pitch diameter)")
    balls: int = quantity(REQUIRED, ge=3, doc="balls", allowed="fewer balls cannot hold the free ring radially "
                                                              "under a pure axial load")
    contact_angle_deg: float | None = quantity(None, unit="deg", gt=0.0, lt=90.0, doc="contact angle (or "
                                               "radial_clearance_um)", allowed="a pure axial load needs a contact "
                                                                               "angle")
    radial_clearance_um: float | None = quantity(None, unit="um", doc="radial clearance (or contact_angle_deg)")
    inner_groove_radius_ratio: float = quantity(0.52, gt=0.5, doc="inner groove radius over ball diameter",
                                                allowed="groove radius > ball radius")
    outer_groove_radius_ratio: float = quantity(0.53, gt=0.5, doc="outer groove radius over ball diameter",
                                                allowed="groove radius > ball radius")
    youngs_modulus_Pa: float = quantity(2.08e11, unit="Pa", gt=0.0, doc="Young's modulus")
    poisson: float = quantity(0.3, ge=0.0, lt=0.5, doc="Poisson's ratio")
    ball_spring_N_per_m: float | None = quantity(None, unit="N/m", gt=0.0, doc="linear2d: each ball-race contact's "
                                                 "stiffness")

    def check(self) -> None:
        require(self.ball_diameter_mm < self.pitch_diameter_mm, "ball_diameter_mm", self.ball_diameter_mm,
                f"must be < pitch_diameter_mm = {self.pitch_diameter_mm}")
        require((self.contact_angle_deg is None) != (self.radial_clearance_um is None),
                "contact_angle_deg|radial_clearance_um", None,
                "give exactly one of contact_angle_deg or radial_clearance_um")


@dataclass(frozen=True, kw_only=True)
class RunoutOperation(Table):
    """``[operation]``."""

    rotating: Literal["inner", "outer"] = quantity("inner", doc="the rotating ring",
                                                   allowed="must be 'inner' or 'outer'")
    speed_rpm: float = quantity(REQUIRED, unit="rpm", gt=0.0, doc="speed of the rotating ring")
    axial_load_N: float = quantity(REQUIRED, unit="N", gt=0.0, doc="axial preload",
                                   allowed="the constant-pressure preload keeps every ball in contact")
    revolutions: float = quantity(REQUIRED, gt=0.0, doc="revolutions of the rotating ring")
    step_deg: float | None = quantity(None, unit="deg", gt=0.0, doc="sampling step (or samples)")
    samples: int | None = quantity(None, doc="samples (or step_deg)")

    def check(self) -> None:
        require((self.step_deg is None) != (self.samples is None), "step_deg|samples",
                {k: v for k, v in (("step_deg", self.step_deg), ("samples", self.samples)) if v is not None},
                "give exactly one of step_deg or samples")
        require(self.sample_count >= 64, "samples", self.sample_count,
                "must be >= 64 (revolutions * 360 / step_deg)")

    @property
    def sample_count(self) -> int:
        """The samples, given or from the step."""
        if self.samples is not None:
            return self.samples
        return int(round(self.revolutions * 360.0 / (self.step_deg or 1.0)))


@dataclass(frozen=True, kw_only=True)
class RunoutAnalysis(Table):
    """``[analysis]``."""

    peak_threshold_rel: float = quantity(DEFAULT_PEAK_THRESHOLD_REL, gt=0.0, lt=1.0, doc="lines below this share of the strongest "
                                         "are not listed (-60 dB: 1e-3)")


@dataclass(frozen=True, kw_only=True)
class WavinessTable(Table):
    """``[[waviness]]``: one harmonic of a form error, R(phi) = R0 + (amplitude_pp/2) cos(order phi - phase)."""

    part: Literal["inner", "outer", "ball"] = quantity(REQUIRED, doc="the part", allowed="must be one of inner, "
                                                                                       "outer, ball")
    order: int = quantity(REQUIRED, ge=1, doc="lobes per circumference", allowed="must be an integer >= 1 (lobes "
                                                                                 "per circumference)")
    amplitude_um_pp: float = quantity(REQUIRED, unit="um", ge=0.0, doc="peak-to-peak amplitude")
    phase_deg: float = quantity(0.0, unit="deg", doc="phase")
    ball: int | None = quantity(None, doc="the ball's index (part = \"ball\" only)")

    def check(self) -> None:
        require(self.part == "ball" or self.ball is None, "ball", self.ball, "only allowed with part = 'ball'")
        require(self.part != "ball" or self.ball is not None, "ball", None, "is required")


@dataclass(frozen=True, kw_only=True)
class BallDiameterDeviation(Table):
    """``[[ball_diameter_deviation]]``."""

    ball: int = quantity(REQUIRED, doc="the ball's index")
    deviation_um: float = quantity(REQUIRED, unit="um", doc="diameter deviation")


@dataclass(frozen=True, kw_only=True)
class BallPositionError(Table):
    """``[[ball_position_error]]``."""

    ball: int = quantity(REQUIRED, doc="the ball's index")
    angle_deg: float = quantity(REQUIRED, unit="deg", doc="angular position error")


@dataclass(frozen=True, kw_only=True)
class RunoutFile(Table):
    """A run-out case file."""

    model: Literal["linear2d", "hertz3d"] = quantity("linear2d", doc="the bearing model",
                                                     allowed="must be one of linear2d, hertz3d")
    bearing: RunoutBearing = quantity(REQUIRED, doc="the bearing", allowed="section is required")
    operation: RunoutOperation = quantity(REQUIRED, doc="the operation", allowed="section is required")
    analysis: RunoutAnalysis = quantity(RunoutAnalysis(), doc="the spectrum's analysis")
    waviness: tuple[WavinessTable, ...] = quantity((), doc="form errors")
    ball_diameter_deviation: tuple[BallDiameterDeviation, ...] = quantity((), doc="ball size errors")
    ball_position_error: tuple[BallPositionError, ...] = quantity((), doc="ball spacing errors")

    def check(self) -> None:
        require(self.bearing.ball_spring_N_per_m is None or self.model == "linear2d", "bearing.ball_spring_N_per_m",
                self.bearing.ball_spring_N_per_m,
                "only for model = 'linear2d' (hertz3d takes its stiffness from the Hertz contacts)")
