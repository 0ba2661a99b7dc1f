"""Hall-sensor switching over one revolution of a multipole ring encoder and the pulse-accuracy measures of the
rotation-sensor bearing paper (H. Ito & T. Koike, "Bearing with integral revolution sensor", NTN Technical Review 69
(2001) 108, sec. 6.1.1; docs/reference/other_seed_systems.md sec. 2.1):

    adjacent pitch error [%] = |T_n - T_(n+1)| / T_n x 100      (T_n: period of pulse n)
    duty ratio [%]           = T_p / T_n x 100                   (T_p: high time within T_n)
    A-B phase lead [deg]     = T_AB / T_n x 360                  (T_AB: A rising edge to B rising edge)

The ring magnet (radius R, P poles; the planar field of :mod:`.field` applied along its circumference, valid while
the pole width p = 2 pi R / P << R) turns at constant speed; its centre may be offset by e from the rotation axis.
A sensor at radius R + g in the fixed frame sees the ring point on the line from the ring centre to the sensor,
at the gap |S - c| - R. The Hall output goes high when B_y >= B_op and low when B_y <= B_rp (B_rp < B_op,
hysteresis). Each switching time is refined by bisection on the field. An eccentric ring makes the ring angle
seen by the sensor lead and lag once per revolution by about e/(R + g) rad, so the pulse period is modulated once
per revolution with the relative amplitude e/(R + g).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from quenchsim.bearings.encoder.field import Encoder, field_T
from quenchsim.errors import require

SAMPLES_PER_POLE = 64
"""Field samples per pole along a revolution before the switching times are refined (the field is smooth)."""


@dataclass(frozen=True)
class RingEncoder:
    """A ring magnet of ``poles`` alternating poles on the magnetised diameter, read radially at ``gap_m`` by Hall
    sensors with operate / release points (T); sensor B sits downstream of sensor A (in the sense of rotation) by
    ``b_offset_electrical_deg`` electrical degrees plus ``b_offset_pitches`` whole pole pairs, so phase A leads;
    the ring centre is offset by ``eccentricity_m``."""

    poles: int
    magnet_diameter_m: float
    thickness_m: float
    remanence_T: float
    gap_m: float
    operate_T: float
    release_T: float
    recoil_permeability: float = 1.0
    backing: str = "air"
    eccentricity_m: float = 0.0
    b_offset_electrical_deg: float = 90.0
    b_offset_pitches: int = 0

    def __post_init__(self) -> None:
        require(isinstance(self.poles, int) and self.poles >= 2 and self.poles % 2 == 0, "poles", self.poles,
                "must be an even integer >= 2 (north and south alternate)")
        require(math.isfinite(self.magnet_diameter_m) and self.magnet_diameter_m > 0.0, "magnet_diameter_m",
                self.magnet_diameter_m, "must be a positive length")
        require(math.isfinite(self.gap_m) and self.gap_m >= 0.0, "gap_m", self.gap_m, "must be >= 0")
        require(math.isfinite(self.operate_T) and math.isfinite(self.release_T) and self.release_T < self.operate_T,
                "release_T", self.release_T, f"must be below operate_T = {self.operate_T}")
        require(math.isfinite(self.eccentricity_m) and 0.0 <= self.eccentricity_m < self.gap_m + self.thickness_m,
                "eccentricity_m", self.eccentricity_m, "must lie in [0, gap + thickness)")
        Encoder(self.pole_width_m, self.thickness_m, self.remanence_T, self.recoil_permeability, self.backing)

    @property
    def radius_m(self) -> float:
        return self.magnet_diameter_m / 2.0

    @property
    def pole_width_m(self) -> float:
        return math.pi * self.magnet_diameter_m / self.poles

    @property
    def layer(self) -> Encoder:
        return Encoder(self.pole_width_m, self.thickness_m, self.remanence_T, self.recoil_permeability, self.backing)

    @property
    def b_offset_rad(self) -> float:
        """Angle from sensor A to sensor B in the sense of rotation."""
        pair = 4.0 * math.pi / self.poles
        return pair * (self.b_offset_electrical_deg / 360.0 + self.b_offset_pitches)


@dataclass(frozen=True)
class PulseMetrics:
    """The paper's measures over one revolution of phase A (and the A-B lead): per-pulse arrays and extremes."""

    pulses_per_revolution: int
    periods_s: np.ndarray
    pitch_error_pct: np.ndarray
    duty_pct: np.ndarray
    lead_deg: np.ndarray
    once_per_rev_period_modulation: float

    def summary(self) -> dict:
        return {"pulses_per_revolution": self.pulses_per_revolution,
                "pitch_error_max_pct": float(self.pitch_error_pct.max()),
                "pitch_error_mean_pct": float(self.pitch_error_pct.mean()),
                "duty_min_pct": float(self.duty_pct.min()), "duty_max_pct": float(self.duty_pct.max()),
                "lead_min_deg": float(self.lead_deg.min()), "lead_max_deg": float(self.lead_deg.max()),
                "once_per_rev_period_modulation": self.once_per_rev_period_modulation}


def sensor_field_T(ring: RingEncoder, rotation_rad: np.ndarray, sensor_angle_rad: float = 0.0) -> np.ndarray:
    """B_y seen by a sensor at the fixed angle ``sensor_angle_rad`` when the ring has turned by ``rotation_rad``
    (its eccentricity along the ring's own x axis)."""
    R = ring.radius_m
    phi = np.asarray(rotation_rad, dtype=float)
    cx, cy = ring.eccentricity_m * np.cos(phi), ring.eccentricity_m * np.sin(phi)
    sx, sy = (R + ring.gap_m) * math.cos(sensor_angle_rad), (R + ring.gap_m) * math.sin(sensor_angle_rad)
    gap = np.hypot(sx - cx, sy - cy) - R
    ring_angle = np.arctan2(sy - cy, sx - cx) - phi       # material angle of the ring facing the sensor
    return field_T(ring.layer, ring_angle * R, gap)[1]


def _switch_times(ring: RingEncoder, sensor_angle_rad: float, samples: int) -> tuple[np.ndarray, np.ndarray]:
    """Rising and falling switching angles of one sensor over three revolutions (the first settles the
    hysteresis state), each refined by 50 bisections of its sampling interval on the field."""
    phi = np.linspace(0.0, 3.0 * 2.0 * math.pi, 3 * samples + 1)
    b = sensor_field_T(ring, phi, sensor_angle_rad)
    high = b[0] >= ring.operate_T
    brackets: list[tuple[int, bool]] = []
    for i in range(1, phi.size):
        if not high and b[i] >= ring.operate_T:
            brackets.append((i, True))
            high = True
        elif high and b[i] <= ring.release_T:
            brackets.append((i, False))
            high = False
    idx = np.array([i for i, _ in brackets], dtype=int)
    rising = np.array([r for _, r in brackets], dtype=bool)
    level = np.where(rising, ring.operate_T, ring.release_T)
    lo, hi = phi[idx - 1], phi[idx]
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        beyond = sensor_field_T(ring, mid, sensor_angle_rad) >= level   # past a rising level / not yet past a falling one
        crossed = np.where(rising, beyond, ~beyond)
        hi, lo = np.where(crossed, mid, hi), np.where(crossed, lo, mid)
    t = 0.5 * (lo + hi)
    return t[rising], t[~rising]


def pulse_metrics(ring: RingEncoder, speed_rpm: float = 60.0) -> PulseMetrics:
    """Switch both sensors over a revolution and evaluate the paper's measures (sec. 6.1.1) for phase A; raises
    when the field at the gap never reaches the operate point."""
    require(math.isfinite(speed_rpm) and speed_rpm > 0.0, "speed_rpm", speed_rpm, "must be > 0")
    omega = speed_rpm * 2.0 * math.pi / 60.0
    samples = SAMPLES_PER_POLE * ring.poles
    ra, fa = _switch_times(ring, 0.0, samples)
    rb, _ = _switch_times(ring, ring.b_offset_rad, samples)
    n = ring.poles // 2
    turn = 2.0 * math.pi
    require(ra.size >= 2 * n + 1, "gap_m", ring.gap_m,
            f"the field there does not switch the sensor at every pole pair (operate point {ring.operate_T} T)")
    start = int(np.searchsorted(ra, turn))            # first rising edge of the second revolution
    rises = ra[start:start + n + 1]
    periods = np.diff(rises) / omega
    falls = np.array([fa[np.searchsorted(fa, r)] for r in rises[:-1]])
    duty = 100.0 * (falls - rises[:-1]) / (np.diff(rises))
    b_after = np.array([rb[np.searchsorted(rb, r)] for r in rises[:-1]])
    lead = 360.0 * (b_after - rises[:-1]) / np.diff(rises)
    pitch = 100.0 * np.abs(periods - np.roll(periods, -1)) / periods
    k = np.arange(n)
    design = np.column_stack([np.ones(n), np.cos(2 * math.pi * k / n), np.sin(2 * math.pi * k / n)])
    c = np.linalg.lstsq(design, periods, rcond=None)[0]
    return PulseMetrics(pulses_per_revolution=n, periods_s=periods, pitch_error_pct=pitch, duty_pct=duty, lead_deg=lead,
                        once_per_rev_period_modulation=float(math.hypot(c[1], c[2]) / c[0]))
