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
from quenchsim.errors import InputError, require
from quenchsim.inputs.reader import read_toml, reading

MODELS = ("linear2d", "hertz3d")
PARTS = ("inner", "outer", "ball")
# Default relative threshold of the peak list: lines below 1e-3 of the strongest line (-60 dB) are
# not listed; the Hann window's leakage at 3 bins from a line is already below -60 dB.
DEFAULT_PEAK_THRESHOLD_REL = 1.0e-3

_TOP_KEYS = {"model", "bearing", "operation", "analysis", "waviness", "ball_diameter_deviation",
             "ball_position_error"}
_BEARING_KEYS = {"pitch_diameter_mm", "ball_diameter_mm", "balls", "contact_angle_deg", "radial_clearance_um",
                 "inner_groove_radius_ratio", "outer_groove_radius_ratio", "youngs_modulus_Pa", "poisson",
                 "ball_spring_N_per_m"}
_OPERATION_KEYS = {"rotating", "speed_rpm", "axial_load_N", "revolutions", "step_deg", "samples"}
_ANALYSIS_KEYS = {"peak_threshold_rel"}
_WAVINESS_KEYS = {"part", "order", "amplitude_um_pp", "phase_deg", "ball"}


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


def _number(table: dict[str, Any], key: str, prefix: str, default: float | None = None) -> float:
    field = f"{prefix}.{key}"
    if key not in table:
        if default is None:
            raise InputError(field, None, "is required")
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(field, value, "must be a finite number")
    return float(value)


def _integer(table: dict[str, Any], key: str, prefix: str, default: int | None = None) -> int:
    field = f"{prefix}.{key}"
    if key not in table:
        if default is None:
            raise InputError(field, None, "is required")
        return default
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int):
        raise InputError(field, value, "must be an integer")
    return value


def _table(data: dict[str, Any], key: str, allowed: set[str], required: bool = True) -> dict[str, Any]:
    table = data.get(key)
    if table is None:
        require(not required, key, None, "section is required")
        return {}
    require(isinstance(table, dict), key, table, "must be a table")
    _known(table, allowed, key)
    return table


def _known(table: dict[str, Any], allowed: set[str], prefix: str) -> None:
    for key in table:
        require(key in allowed, f"{prefix}.{key}" if prefix else key, table[key],
                f"unknown key; allowed: {', '.join(sorted(allowed))}")


def _array_of_tables(data: dict[str, Any], key: str) -> list[dict[str, Any]]:
    rows = data.get(key, [])
    require(isinstance(rows, list) and all(isinstance(r, dict) for r in rows), key, rows,
            f"must be an array of tables ([[{key}]])")
    return rows


def _ball_index(row: dict[str, Any], prefix: str, balls: int) -> int:
    j = _integer(row, "ball", prefix)
    require(0 <= j < balls, f"{prefix}.ball", j, f"must be a ball index 0 .. {balls - 1}")
    return j


def parse_case(data: dict[str, Any]) -> RunoutCase:
    """Validate a case dictionary (as read from TOML) and convert it to SI units."""
    _known(data, _TOP_KEYS, "")
    model = data.get("model", "linear2d")
    require(model in MODELS, "model", model, f"must be one of {', '.join(MODELS)}")

    b = _table(data, "bearing", _BEARING_KEYS)
    pd_mm = _number(b, "pitch_diameter_mm", "bearing")
    bd_mm = _number(b, "ball_diameter_mm", "bearing")
    require(bd_mm > 0.0, "bearing.ball_diameter_mm", bd_mm, "must be > 0")
    require(bd_mm < pd_mm, "bearing.ball_diameter_mm", bd_mm, f"must be < pitch_diameter_mm = {pd_mm}")
    balls = _integer(b, "balls", "bearing")
    require(balls >= 3, "bearing.balls", balls,
            "must be >= 3 (fewer balls cannot hold the free ring radially under a pure axial load)")
    # balls must fit on the pitch circle: Z * 2 asin(D/d_m) <= 2 pi
    z_max = int(math.pi / math.asin(bd_mm / pd_mm))
    require(balls <= z_max, "bearing.balls", balls,
            f"must be <= {z_max}: more balls of {bd_mm} mm do not fit on a {pd_mm} mm pitch circle")
    fi = _number(b, "inner_groove_radius_ratio", "bearing", 0.52)
    fo = _number(b, "outer_groove_radius_ratio", "bearing", 0.53)
    require(fi > 0.5, "bearing.inner_groove_radius_ratio", fi, "must be > 0.5 (groove radius > ball radius)")
    require(fo > 0.5, "bearing.outer_groove_radius_ratio", fo, "must be > 0.5 (groove radius > ball radius)")
    E = _number(b, "youngs_modulus_Pa", "bearing", 2.08e11)
    require(E > 0.0, "bearing.youngs_modulus_Pa", E, "must be > 0")
    nu = _number(b, "poisson", "bearing", 0.3)
    require(0.0 <= nu < 0.5, "bearing.poisson", nu, "must lie in [0, 0.5)")
    k_ball = None
    if "ball_spring_N_per_m" in b:
        k_ball = _number(b, "ball_spring_N_per_m", "bearing")
        require(k_ball > 0.0, "bearing.ball_spring_N_per_m", k_ball, "must be > 0")
        require(model == "linear2d", "bearing.ball_spring_N_per_m", k_ball,
                "only for model = 'linear2d' (hertz3d takes its stiffness from the Hertz contacts)")

    op = _table(data, "operation", _OPERATION_KEYS)
    rotating = op.get("rotating", "inner")
    require(rotating in ("inner", "outer"), "operation.rotating", rotating, "must be 'inner' or 'outer'")
    speed_rpm = _number(op, "speed_rpm", "operation")
    require(speed_rpm > 0.0, "operation.speed_rpm", speed_rpm, "must be > 0")
    load = _number(op, "axial_load_N", "operation")
    require(load > 0.0, "operation.axial_load_N", load,
            "must be > 0 (the constant-pressure preload keeps every ball in contact)")
    revolutions = _number(op, "revolutions", "operation")
    require(revolutions > 0.0, "operation.revolutions", revolutions, "must be > 0")
    require(("step_deg" in op) != ("samples" in op), "operation.step_deg|samples",
            {k: op[k] for k in ("step_deg", "samples") if k in op}, "give exactly one of step_deg or samples")
    if "step_deg" in op:
        step = _number(op, "step_deg", "operation")
        require(step > 0.0, "operation.step_deg", step, "must be > 0")
        samples = int(round(revolutions * 360.0 / step))
    else:
        samples = _integer(op, "samples", "operation")
    require(samples >= 64, "operation.samples", samples, "must be >= 64 (revolutions * 360 / step_deg)")

    a = _table(data, "analysis", _ANALYSIS_KEYS, required=False)
    threshold = _number(a, "peak_threshold_rel", "analysis", DEFAULT_PEAK_THRESHOLD_REL)
    require(0.0 < threshold < 1.0, "analysis.peak_threshold_rel", threshold, "must lie in (0, 1)")

    has_angle, has_clearance = "contact_angle_deg" in b, "radial_clearance_um" in b
    require(has_angle != has_clearance, "bearing.contact_angle_deg|radial_clearance_um",
            None, "give exactly one of contact_angle_deg or radial_clearance_um")
    clearance = None
    if has_angle:
        angle_deg = _number(b, "contact_angle_deg", "bearing")
        require(0.0 < angle_deg < 90.0, "bearing.contact_angle_deg", angle_deg,
                "must lie in (0, 90) (a pure axial load needs a contact angle)")
        angle = math.radians(angle_deg)
    else:
        clearance = _number(b, "radial_clearance_um", "bearing") * 1e-6
        free = free_contact_angle_rad(clearance, bd_mm * 1e-3, fi, fo)
        angle = loaded_contact_angle_rad(free, load, balls, bd_mm * 1e-3, pd_mm * 1e-3, fi, fo, E, nu)

    waviness = []
    for i, row in enumerate(_array_of_tables(data, "waviness")):
        prefix = f"waviness[{i}]"
        _known(row, _WAVINESS_KEYS, prefix)
        part: Any = row.get("part")   # checked by require: one of PARTS
        require(part in PARTS, f"{prefix}.part", part, f"must be one of {', '.join(PARTS)}")
        order = _integer(row, "order", prefix)
        require(order >= 1, f"{prefix}.order", order, "must be an integer >= 1 (lobes per circumference)")
        amp = _number(row, "amplitude_um_pp", prefix)
        require(amp >= 0.0, f"{prefix}.amplitude_um_pp", amp, "must be >= 0")
        phase = math.radians(_number(row, "phase_deg", prefix, 0.0))
        ball = _ball_index(row, prefix, balls) if part == "ball" else None
        require(part == "ball" or "ball" not in row, f"{prefix}.ball", row.get("ball"),
                "only allowed with part = 'ball'")
        waviness.append(Waviness(part, order, amp * 1e-6, phase, ball))

    deviation = [0.0] * balls
    for i, row in enumerate(_array_of_tables(data, "ball_diameter_deviation")):
        prefix = f"ball_diameter_deviation[{i}]"
        _known(row, {"ball", "deviation_um"}, prefix)
        deviation[_ball_index(row, prefix, balls)] += _number(row, "deviation_um", prefix) * 1e-6
    position = [0.0] * balls
    for i, row in enumerate(_array_of_tables(data, "ball_position_error")):
        prefix = f"ball_position_error[{i}]"
        _known(row, {"ball", "angle_deg"}, prefix)
        position[_ball_index(row, prefix, balls)] += math.radians(_number(row, "angle_deg", prefix))
    # the displaced balls must keep their order and not overlap: neighbouring centres at least
    # 2 asin(D/d_m) apart on the pitch circle
    centres = [2.0 * math.pi * j / balls + position[j] for j in range(balls)]
    min_gap = 2.0 * math.asin(bd_mm / pd_mm)
    for j in range(balls):
        gap = (centres[(j + 1) % balls] + (2.0 * math.pi if j + 1 == balls else 0.0)) - centres[j]
        require(gap >= min_gap, "ball_position_error", f"balls {j} and {(j + 1) % balls}",
                f"are {math.degrees(gap):.4g} deg apart; balls of {bd_mm} mm on a {pd_mm} mm pitch circle "
                f"need at least {math.degrees(min_gap):.4g} deg")

    case = RunoutCase(model=model, pitch_diameter_m=pd_mm * 1e-3, ball_diameter_m=bd_mm * 1e-3, balls=balls,
                      contact_angle_rad=angle, inner_groove_radius_ratio=fi, outer_groove_radius_ratio=fo,
                      youngs_modulus_Pa=E, poisson=nu, rotating=rotating, speed_hz=speed_rpm / 60.0,
                      axial_load_N=load, revolutions=revolutions, samples=samples, waviness=tuple(waviness),
                      ball_diameter_deviation_m=tuple(deviation), ball_position_error_rad=tuple(position),
                      ball_spring_N_m=k_ball, radial_clearance_m=clearance, peak_threshold_rel=threshold)
    _check_sampling(case)
    return case


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
