"""Grease life of sealed deep-groove ball bearings (urea and lithium-soap greases).

    log10 L50 = a_V K V + a_T T + a_F F + a_0 + K1

with L50 the grease life reached by half of the bearings (h), V = d_m N (mm rpm), T the bearing
(outer-ring) temperature (deg C), F = P / Cr, K1 the base-oil factor and K the speed factor for
outer-ring rotation, K = (inner-ring speed giving the same cage speed) / (outer-ring speed)
(= 1 for inner-ring rotation; :func:`quenchsim.bearings.kinematics.equivalent_inner_speed_factor`).
Coefficients, base-oil factors and validity ranges are in ``data/grease_life.toml``
(source: Tribology Transactions 44 (2001) 256; reference sec. 4).

Outside the published validity ranges (d_m, dmN, temperature) or the load range of the fitted
data, the result still carries the formula's number but ``within_validity`` is False and each
violated range is named in ``warnings``.
"""

from __future__ import annotations

import functools
import math
import tomllib
from dataclasses import dataclass
from importlib import resources
from typing import Any

from quenchsim.errors import InputError, require


@dataclass(frozen=True)
class GreaseLife:
    """L50 grease life (h) with the inputs that entered the formula and any validity warnings."""

    L50_h: float
    K: float
    dmN: float
    base_oil_factor: float
    within_validity: bool
    warnings: tuple[str, ...]


@functools.cache
def grease_data() -> dict[str, Any]:
    """The coefficient table ``data/grease_life.toml`` (parsed once)."""
    text = resources.files("quenchsim.bearings").joinpath("data/grease_life.toml").read_text("utf-8")
    return tomllib.loads(text)


def grease_types() -> list[str]:
    """Thickener types with a formula: ``["lithium", "urea"]``."""
    return sorted(grease_data()["grease"])


def base_oil_factor(grease: str, base_oil: str) -> float:
    """Base-oil factor K1 for a thickener and a base oil or a mixture joined by "+" (order-free,
    case-insensitive: "PAO+ester" == "ester+pao")."""
    table = _grease_table(grease)["base_oil_factor"]
    parts = [p.strip().lower() for p in str(base_oil).split("+")]
    require(all(parts), "base_oil", base_oil, "must be a base-oil name or names joined by '+'")
    wanted = sorted(parts)
    for key, value in table.items():
        if sorted(key.split("+")) == wanted:
            return float(value)
    raise InputError("base_oil", base_oil, f"no factor for {grease} grease; known: {', '.join(table)}")


def _grease_table(grease: str) -> dict[str, Any]:
    table = grease_data()["grease"]
    key = str(grease).strip().lower()
    if key not in table:
        raise InputError("grease", grease, f"must be one of {', '.join(sorted(table))}")
    return table[key]


def grease_life(grease: str, base_oil: str, dm_mm: float, speed_rpm: float, temperature_C: float,
                load_ratio: float, speed_factor: float = 1.0) -> GreaseLife:
    """L50 grease life (h): log10 L50 = a_V K dmN + a_T T + a_F P/Cr + a_0 + K1 (module docstring).

    ``speed_factor`` is K (1 for inner-ring rotation; for outer-ring rotation use
    :func:`quenchsim.bearings.kinematics.equivalent_inner_speed_factor`).
    """
    c = _grease_table(grease)
    k1 = base_oil_factor(grease, base_oil)
    require(math.isfinite(dm_mm) and dm_mm > 0.0, "dm_mm", dm_mm, "must be a positive pitch diameter in mm")
    require(math.isfinite(speed_rpm) and speed_rpm > 0.0, "speed_rpm", speed_rpm, "must be a positive speed")
    require(math.isfinite(temperature_C), "temperature_C", temperature_C, "must be finite")
    require(math.isfinite(load_ratio) and 0.0 <= load_ratio < 1.0, "load_ratio", load_ratio,
            "P/Cr must lie in [0, 1)")
    require(math.isfinite(speed_factor) and speed_factor >= 1.0, "speed_factor", speed_factor,
            "K must be >= 1 (1 for inner-ring rotation)")
    dmN = dm_mm * speed_rpm
    log_L = (c["a_speed"] * speed_factor * dmN + c["a_temperature"] * temperature_C
             + c["a_load"] * load_ratio + c["a_const"] + k1)
    warnings = _validity_warnings(grease, c, dm_mm, dmN, speed_factor, temperature_C, load_ratio)
    return GreaseLife(L50_h=10.0**log_L, K=speed_factor, dmN=dmN, base_oil_factor=k1,
                      within_validity=not warnings, warnings=warnings)


def _validity_warnings(grease: str, c: dict[str, Any], dm_mm: float, dmN: float, K: float,
                       temperature_C: float, load_ratio: float) -> tuple[str, ...]:
    out: list[str] = []
    lo, hi = c["dm_mm_range"]
    if not lo <= dm_mm <= hi:
        out.append(f"dm = {dm_mm:g} mm outside the validity range {lo:g}..{hi:g} mm")
    if K * dmN > c["dmN_max"]:
        what = "dmN" if K == 1.0 else f"K*dmN (K = {K:.4g}, equivalent inner-ring speed)"
        out.append(f"{what} = {K * dmN:.4g} above the validity limit {c['dmN_max']:.4g}")
    lo, hi = c["temperature_C_range"]
    if not lo <= temperature_C <= hi:
        out.append(f"temperature = {temperature_C:g} C outside the validity range {lo:g}..{hi:g} C for {grease}")
    lo, hi = grease_data()["fitted_data"]["load_ratio_range"]
    if not lo <= load_ratio <= hi:
        out.append(f"P/Cr = {load_ratio:g} outside the load range of the fitted data {lo:g}..{hi:g} (extrapolation)")
    return tuple(out)


def weibull_life(L50_h: float, slope: float, reliability: float = 0.9) -> float:
    """Life reached with the given reliability for a two-parameter Weibull distribution with the
    same L50: L_R = L50 (ln R / ln 0.5)^(1/slope); e.g. L10 = L50 (ln 0.9 / ln 0.5)^(1/slope)."""
    require(math.isfinite(L50_h) and L50_h > 0.0, "L50_h", L50_h, "must be a positive life")
    require(math.isfinite(slope) and slope > 0.0, "slope", slope, "Weibull slope must be positive")
    require(0.0 < reliability < 1.0, "reliability", reliability, "must lie in (0, 1)")
    return L50_h * (math.log(reliability) / math.log(0.5)) ** (1.0 / slope)
