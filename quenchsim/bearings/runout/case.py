"""Run-out case files (TOML): parsing and validation into a :class:`RunoutCase` (SI units).

Layout (units in the key names where not SI)::

    model = "linear2d" | "hertz3d"
    [bearing]    pitch_diameter_mm, ball_diameter_mm, balls, contact_angle_deg | radial_clearance_um,
                 inner_groove_radius_ratio, outer_groove_radius_ratio, youngs_modulus_Pa, poisson,
                 ball_spring_N_per_m (optional, linear2d: the paper's k of each ball-race contact)
    [operation]  rotating = "inner" | "outer", speed_rpm, axial_load_N, revolutions,
                 step_deg | samples
    [analysis]   peak_threshold_rel (optional)
    [[waviness]] part = "inner" | "outer" | "ball", order, amplitude_um_pp, phase_deg, ball (for part = ball)
    [[ball_diameter_deviation]] ball, deviation_um
    [[ball_position_error]]     ball, angle_deg

Every user error raises :class:`quenchsim.errors.InputError` naming the key, the value and what
is allowed. Unknown keys are errors too (a misspelt key must not be silently ignored).
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass
from typing import Any

from quenchsim.bearings.runout.contact_angle import free_contact_angle_rad, loaded_contact_angle_rad
from quenchsim.bearings.runout.excitation import kinematic_frequencies
from quenchsim.errors import require
from quenchsim.inputs.bearings import DEFAULT_PEAK_THRESHOLD_REL, RunoutFile
from quenchsim.inputs.declare import from_table
from quenchsim.inputs.reader import read_toml, reading

MODELS = ("linear2d", "hertz3d")
PARTS = ("inner", "outer", "ball")
# the keys of a run-out case file, and their defaults, are declared in quenchsim/inputs/bearings.py

@dataclass(frozen=True)
class Waviness:
    """One harmonic of a form error: R(phi) = R0 + (amplitude_pp/2) cos(order phi - phase).

    For a ball the angle is the spin angle on the great circle through both contacts."""

    part: str
    order: int
    amplitude_pp_m: float
    phase_rad: float
    ball: int | None = None


@dataclass(frozen=True)
class RunoutCase:
    """A fully validated run-out case, SI units (angles in rad, speeds in Hz)."""

    model: str
    pitch_diameter_m: float
    ball_diameter_m: float
    balls: int
    contact_angle_rad: float
    inner_groove_radius_ratio: float
    outer_groove_radius_ratio: float
    youngs_modulus_Pa: float
    poisson: float
    rotating: str
    speed_hz: float
    axial_load_N: float
    revolutions: float
    samples: int
    waviness: tuple[Waviness, ...] = ()
    ball_diameter_deviation_m: tuple[float, ...] = ()
    ball_position_error_rad: tuple[float, ...] = ()
    ball_spring_N_m: float | None = None
    radial_clearance_m: float | None = None
    peak_threshold_rel: float = DEFAULT_PEAK_THRESHOLD_REL

    @property
    def duration_s(self) -> float:
        """Simulated time: revolutions of the rotating ring."""
        return self.revolutions / self.speed_hz


def _ball_index(j: int, prefix: str, balls: int) -> int:
    require(0 <= j < balls, f"{prefix}.ball", j, f"must be a ball index 0 .. {balls - 1}")
    return j


def parse_case(data: dict[str, Any]) -> RunoutCase:
    """Validate a case dictionary (as read from TOML, :class:`quenchsim.inputs.bearings.RunoutFile`) and convert it to
    SI units."""
    case = from_table(RunoutFile, data)
    b, op = case.bearing, case.operation
    pd_mm, bd_mm, balls = b.pitch_diameter_mm, b.ball_diameter_mm, b.balls
    # balls must fit on the pitch circle: Z * 2 asin(D/d_m) <= 2 pi
    z_max = int(math.pi / math.asin(bd_mm / pd_mm))
    require(balls <= z_max, "bearing.balls", balls,
            f"must be <= {z_max}: more balls of {bd_mm} mm do not fit on a {pd_mm} mm pitch circle")
    fi, fo, E, nu = b.inner_groove_radius_ratio, b.outer_groove_radius_ratio, b.youngs_modulus_Pa, b.poisson
    load = op.axial_load_N
    clearance = None
    if b.contact_angle_deg is not None:
        angle = math.radians(b.contact_angle_deg)
    else:
        clearance = float(b.radial_clearance_um or 0.0) * 1e-6   # one of the two (RunoutBearing.check)
        free = free_contact_angle_rad(clearance, bd_mm * 1e-3, fi, fo)
        angle = loaded_contact_angle_rad(free, load, balls, bd_mm * 1e-3, pd_mm * 1e-3, fi, fo, E, nu)

    waviness = []
    for i, row in enumerate(case.waviness):
        prefix = f"waviness[{i}]"
        ball = _ball_index(row.ball, prefix, balls) if row.ball is not None else None
        waviness.append(Waviness(row.part, row.order, row.amplitude_um_pp * 1e-6, math.radians(row.phase_deg), ball))

    deviation = [0.0] * balls
    for i, dev in enumerate(case.ball_diameter_deviation):
        deviation[_ball_index(dev.ball, f"ball_diameter_deviation[{i}]", balls)] += dev.deviation_um * 1e-6
    position = [0.0] * balls
    for i, err in enumerate(case.ball_position_error):
        position[_ball_index(err.ball, f"ball_position_error[{i}]", balls)] += math.radians(err.angle_deg)
    # the displaced balls must keep their order and not overlap: neighbouring centres at least
    # 2 asin(D/d_m) apart on the pitch circle
    centres = [2.0 * math.pi * j / balls + position[j] for j in range(balls)]
    min_gap = 2.0 * math.asin(bd_mm / pd_mm)
    for j in range(balls):
        gap = (centres[(j + 1) % balls] + (2.0 * math.pi if j + 1 == balls else 0.0)) - centres[j]
        require(gap >= min_gap, "ball_position_error", f"balls {j} and {(j + 1) % balls}",
                f"are {math.degrees(gap):.4g} deg apart; balls of {bd_mm} mm on a {pd_mm} mm pitch circle "
                f"need at least {math.degrees(min_gap):.4g} deg")

    runout = RunoutCase(model=case.model, pitch_diameter_m=pd_mm * 1e-3, ball_diameter_m=bd_mm * 1e-3, balls=balls,
                        contact_angle_rad=angle, inner_groove_radius_ratio=fi, outer_groove_radius_ratio=fo,
                        youngs_modulus_Pa=E, poisson=nu, rotating=op.rotating, speed_hz=op.speed_rpm / 60.0,
                        axial_load_N=load, revolutions=op.revolutions, samples=op.sample_count,
                        waviness=tuple(waviness), ball_diameter_deviation_m=tuple(deviation),
                        ball_position_error_rad=tuple(position), ball_spring_N_m=b.ball_spring_N_per_m,
                        radial_clearance_m=clearance, peak_threshold_rel=case.analysis.peak_threshold_rel)
    _check_sampling(runout)
    return runout


def _check_sampling(case: RunoutCase) -> None:
    """The first-order lines of every waviness must lie below the Nyquist frequency."""
    f = kinematic_frequencies(case)
    nyquist = 0.5 * case.samples / case.duration_s
    for i, w in enumerate(case.waviness):
        if w.part == "ball":
            top = w.order * f.ball_spin_hz + abs(f.cage_hz)
        else:
            rel = f.inner_rel_cage_hz if w.part == "inner" else f.outer_rel_cage_hz
            top = w.order * abs(rel) + abs(f.cage_hz)
        require(top < nyquist, f"waviness[{i}].order", w.order,
                f"its first-order line at {top:.4g} Hz exceeds the Nyquist frequency {nyquist:.4g} Hz: "
                "use a smaller operation.step_deg or more samples")


def load_case(path: str | pathlib.Path) -> RunoutCase:
    """Read and validate a run-out case file (TOML)."""
    p = pathlib.Path(path)
    data = read_toml(p, "input")
    with reading(p):
        return parse_case(data)
