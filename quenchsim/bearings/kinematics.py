"""Rolling-bearing kinematics: cage, ball-spin and ball-pass frequencies, the grease-life speed
factor for outer-ring rotation, the roller slip ratio, and a small table of deep-groove bearings.

With gamma = D cos(alpha) / d_m (ball diameter D, pitch diameter d_m, contact angle alpha) and
pure rolling (no slip) at both raceways, for inner- and outer-ring speeds f_i, f_o
(T. A. Harris & M. N. Kotzalas, *Rolling Bearing Analysis* 5th ed. 2007, vol. 1 ch. 8; the cage
speed also as printed in the grease-life paper, reference sec. 4):

    cage (FTF)                 f_c = (1 - gamma) f_i / 2 + (1 + gamma) f_o / 2
    inner / outer rel. cage    f_i - f_c,  f_o - f_c
    ball-pass inner / outer    BPFI = Z |f_i - f_c|,  BPFO = Z |f_o - f_c|
    ball spin (own axis)       BSF = (d_m / (2 D)) (1 - gamma^2) |f_i - f_o|
    ball defect                BDF = 2 BSF (a ball defect strikes both raceways per spin turn)

The spin is the rotation of the ball about its own axis seen from the cage; the free-run
reference (sec. 5) writes the same rate as omega_a = -(d_m/D - D cos^2(alpha)/d_m) omega_r / 2.
"""

from __future__ import annotations

import functools
import math
import numbers
from dataclasses import dataclass

from quenchsim.errors import InputError, require
from quenchsim.inputs.reader import read_package_toml


@dataclass(frozen=True)
class BearingGeometry:
    """Pitch diameter, ball diameter (m), number of balls and contact angle (rad) of a ball bearing."""

    pitch_diameter_m: float
    ball_diameter_m: float
    balls: int
    contact_angle_rad: float = 0.0

    def __post_init__(self) -> None:
        D, dm = self.ball_diameter_m, self.pitch_diameter_m
        require(math.isfinite(D) and D > 0.0, "ball_diameter_m", D, "must be a positive length")
        require(math.isfinite(dm) and dm > D, "pitch_diameter_m", dm, f"must exceed ball_diameter_m = {D}")
        require(isinstance(self.balls, numbers.Integral) and not isinstance(self.balls, bool) and self.balls >= 1,
                "balls", self.balls, "must be an integer >= 1")
        require(math.isfinite(self.contact_angle_rad) and 0.0 <= self.contact_angle_rad < math.pi / 2.0,
                "contact_angle_rad", self.contact_angle_rad, "must lie in [0, pi/2)")

    @property
    def gamma(self) -> float:
        """gamma = D cos(alpha) / d_m."""
        return self.ball_diameter_m * math.cos(self.contact_angle_rad) / self.pitch_diameter_m


@dataclass(frozen=True)
class BearingFrequencies:
    """Kinematic frequencies (Hz) for given inner- and outer-ring speeds; signed speeds follow the
    sign of the ring speeds, pass and spin frequencies are magnitudes."""

    cage_hz: float
    ball_spin_hz: float
    inner_rel_cage_hz: float
    outer_rel_cage_hz: float
    ball_pass_inner_hz: float
    ball_pass_outer_hz: float
    ball_defect_hz: float


@dataclass(frozen=True)
class BearingData:
    """Catalogue data of one bearing (SI units) and where each number comes from."""

    name: str
    bore_m: float
    outer_diameter_m: float
    width_m: float
    ball_diameter_m: float
    balls: int
    pitch_diameter_m: float
    contact_angle_rad: float
    dynamic_rating_N: float
    source: str
    static_rating_N: float | None = None

    @property
    def geometry(self) -> BearingGeometry:
        """The kinematic geometry of this bearing."""
        return BearingGeometry(self.pitch_diameter_m, self.ball_diameter_m, self.balls, self.contact_angle_rad)


def frequencies(geometry: BearingGeometry, inner_hz: float, outer_hz: float) -> BearingFrequencies:
    """Cage, ball-spin and ball-pass frequencies for inner/outer ring speeds (any combination,
    signed, Hz) under pure rolling; equations in the module docstring."""
    require(math.isfinite(inner_hz), "inner_hz", inner_hz, "must be finite")
    require(math.isfinite(outer_hz), "outer_hz", outer_hz, "must be finite")
    g = geometry.gamma
    cage = 0.5 * (1.0 - g) * inner_hz + 0.5 * (1.0 + g) * outer_hz
    spin = 0.5 * geometry.pitch_diameter_m / geometry.ball_diameter_m * (1.0 - g * g) * abs(inner_hz - outer_hz)
    z = geometry.balls
    return BearingFrequencies(cage_hz=cage, ball_spin_hz=spin, inner_rel_cage_hz=inner_hz - cage,
                              outer_rel_cage_hz=outer_hz - cage, ball_pass_inner_hz=z * abs(inner_hz - cage),
                              ball_pass_outer_hz=z * abs(outer_hz - cage), ball_defect_hz=2.0 * spin)


def equivalent_inner_speed_factor(geometry: BearingGeometry) -> float:
    """K = (inner-ring speed giving the same cage speed) / (outer-ring speed) = (1 + gamma)/(1 - gamma),
    from equating the cage speeds (1 - gamma) n_i / 2 = (1 + gamma) n_o / 2 (grease-life paper,
    reference sec. 4)."""
    g = geometry.gamma
    return (1.0 + g) / (1.0 - g)


def roller_slip_ratio_pct(measured_cage_speed: float, theoretical_cage_speed: float) -> float:
    """C_s = (1 - N_c / N_tc) * 100 % (measured over theoretical cage speed, same units; reference sec. 7)."""
    require(math.isfinite(theoretical_cage_speed) and theoretical_cage_speed != 0.0,
            "theoretical_cage_speed", theoretical_cage_speed, "must be finite and non-zero")
    require(math.isfinite(measured_cage_speed), "measured_cage_speed", measured_cage_speed, "must be finite")
    return (1.0 - measured_cage_speed / theoretical_cage_speed) * 100.0


def _load_table() -> dict[str, BearingData]:
    table = read_package_toml("quenchsim.bearings", "data/deep_groove_bearings.toml")
    out: dict[str, BearingData] = {}
    for name, row in table["bearing"].items():
        out[name] = BearingData(
            name=name, bore_m=row["bore_mm"] * 1e-3, outer_diameter_m=row["outer_diameter_mm"] * 1e-3,
            width_m=row["width_mm"] * 1e-3, ball_diameter_m=row["ball_diameter_mm"] * 1e-3,
            balls=int(row["balls"]), pitch_diameter_m=row["pitch_diameter_mm"] * 1e-3,
            contact_angle_rad=math.radians(row["contact_angle_deg"]),
            dynamic_rating_N=row["dynamic_rating_kN"] * 1e3, source=row["source"],
            static_rating_N=row["static_rating_kN"] * 1e3 if "static_rating_kN" in row else None)
    return out


def bearing_names() -> list[str]:
    """Designations in the built-in bearing table."""
    return sorted(_table())


@functools.cache
def steel_properties() -> dict[str, float]:
    """Bearing steel (100Cr6 / AISI 52100): density_kg_m3, youngs_modulus_Pa, poisson, from
    data/bearing_steel.toml (sources in that file)."""
    steel = read_package_toml("quenchsim.bearings", "data/bearing_steel.toml")["steel"]
    return {k: v for k, v in steel.items() if k != "source"}


@functools.cache
def _table() -> dict[str, BearingData]:
    return _load_table()


def bearing(name: str) -> BearingData:
    """Data of a bearing from the built-in table (quenchsim/bearings/data/deep_groove_bearings.toml)."""
    table = _table()
    key = str(name).strip().upper()
    if key not in table:
        raise InputError("bearing", name, f"unknown bearing; known: {', '.join(sorted(table))}")
    return table[key]
