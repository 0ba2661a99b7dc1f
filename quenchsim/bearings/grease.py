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

The base oil of the paper's urea test grease is not stated, so its K1 is an unknown of the published
fit: :func:`fit_base_oil_factor` estimates it from the published L50 points
(:func:`published_points`) by least squares in log10 L, and :func:`repeat_scatter_log10` gives the
scatter the paper implies (the spread of its repeated L50 values for one nominal condition).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from quenchsim.bearings import kinematics as kin
from quenchsim.errors import InputError, require
from quenchsim.inputs.reader import read_package_toml


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
    return read_package_toml("quenchsim.bearings", "data/grease_life.toml")


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


def log10_life_without_base_oil(grease: str, dm_mm: np.ndarray | float, speed_rpm: np.ndarray | float,
                                temperature_C: np.ndarray | float, load_ratio: np.ndarray | float,
                                speed_factor: np.ndarray | float = 1.0) -> np.ndarray:
    """The formula without its base-oil term, a_V K d_m N + a_T T + a_F P/Cr + a_0 (vectorised, no
    input checks; :func:`grease_life` is the checked entry point): log10 L50 = this + K1."""
    c = _grease_table(grease)
    dmN = np.asarray(dm_mm, dtype=float) * np.asarray(speed_rpm, dtype=float)
    return (c["a_speed"] * np.asarray(speed_factor, dtype=float) * dmN
            + c["a_temperature"] * np.asarray(temperature_C, dtype=float)
            + c["a_load"] * np.asarray(load_ratio, dtype=float) + c["a_const"])


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
    require(math.isfinite(temperature_C) and -60.0 <= temperature_C <= 250.0, "temperature_C", temperature_C,
            "must be within -60..250 C (the range of grease-lubricated rolling bearings; above ~250 C the "
            "thickeners of lithium, lithium-complex and polyurea greases have passed their dropping points)")
    require(math.isfinite(load_ratio) and 0.0 <= load_ratio < 1.0, "load_ratio", load_ratio,
            "P/Cr must lie in [0, 1)")
    require(math.isfinite(speed_factor) and speed_factor >= 1.0, "speed_factor", speed_factor,
            "K must be >= 1 (1 for inner-ring rotation)")
    dmN = dm_mm * speed_rpm
    log_L = float(log10_life_without_base_oil(grease, dm_mm, speed_rpm, temperature_C, load_ratio, speed_factor)) + k1
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


@dataclass(frozen=True)
class PublishedPoints:
    """The published L50 points behind a grease's fit (inner-ring rotation), one array entry per point,
    with the conditions at which the formula is evaluated; ``assumed`` names, per point, the conditions
    the reference does not state (see ``data/grease_life.toml``)."""

    bearing: str
    dm_mm: float
    series: tuple[str, ...]
    speed_rpm: np.ndarray
    temperature_C: np.ndarray
    load_ratio: np.ndarray
    L50_h: np.ndarray
    assumed: tuple[str, ...]


def _fitted_data(grease: str) -> dict[str, Any]:
    key = str(grease).strip().lower()
    _grease_table(key)
    data = grease_data()["fitted_data"]
    if key not in data:
        raise InputError("grease", grease, f"published L50 data only for {', '.join(sorted(set(data) & set(grease_types())))}")
    return data[key]


def published_points(grease: str = "urea") -> PublishedPoints:
    """The paper's L50 data points (every ``*_series`` table of ``[fitted_data.<grease>]``): in each
    series one condition is the list that varies, the others are single values."""
    data = _fitted_data(grease)
    b = kin.bearing(data["bearing"])
    names: list[str] = []
    cols: dict[str, list[float]] = {"speed_rpm": [], "temperature_C": [], "load_ratio": [], "L50_h": []}
    assumed: list[str] = []
    for name, s in data.items():
        if not name.endswith("_series"):
            continue
        n = len(s["L50_h"])
        for var in cols:
            cols[var].extend(np.broadcast_to(np.asarray(s[var], dtype=float), (n,)).tolist())
        names += [name.removesuffix("_series").replace("_", " ")] * n
        assumed += [s.get("assumed", "")] * n
    return PublishedPoints(bearing=b.name, dm_mm=b.pitch_diameter_m * 1e3, series=tuple(names),
                           assumed=tuple(assumed), **{k: np.array(v) for k, v in cols.items()})


def repeat_scatter_log10(grease: str = "urea") -> float:
    """Scatter the paper implies, log10(max/min) of its repeated L50 values for one nominal condition
    (``nominal_repeats_L50_h`` of ``[fitted_data.<grease>]``)."""
    L = np.asarray(_fitted_data(grease)["nominal_repeats_L50_h"], dtype=float)
    return float(np.log10(L.max() / L.min()))


@dataclass(frozen=True)
class BaseOilFit:
    """Base-oil factor K1 of a test grease estimated from its L50 points.

    ``offsets_log10[i]`` = log10 L_i(paper) - (formula without K1)_i is the K1 that would reproduce
    point i alone; the residual of point i for a factor K1 is log10(formula / paper) = K1 - offset_i.
    """

    k1_least_squares: float
    k1_standard_error: float
    k1_minimax: float
    offsets_log10: np.ndarray

    def residuals_log10(self, k1: float) -> np.ndarray:
        """log10(formula / paper) of every point for the base-oil factor ``k1``."""
        return k1 - self.offsets_log10

    def feasible_interval(self, tolerance_log10: float) -> tuple[float, float]:
        """The K1 range for which every |residual| <= tolerance: [max(offset) - tol, min(offset) + tol]
        (empty when the lower end exceeds the upper)."""
        return (float(self.offsets_log10.max() - tolerance_log10),
                float(self.offsets_log10.min() + tolerance_log10))


def fit_base_oil_factor(grease: str, dm_mm: np.ndarray | float, speed_rpm: np.ndarray, temperature_C: np.ndarray,
                        load_ratio: np.ndarray, L50_h: np.ndarray, speed_factor: np.ndarray | float = 1.0) -> BaseOilFit:
    """Estimate the one unknown K1 of the formula from L50 points with the published coefficients fixed.

    Least squares in log10 L: minimise sum_i (K1 - d_i)^2 with d_i = log10 L_i - (a_V K V_i + a_T T_i
    + a_F F_i + a_0), so K1 = mean(d_i), standard error s / sqrt(n) with s^2 = sum (d_i - K1)^2 / (n - 1).
    Log space because grease-life scatter is multiplicative (the published fit is linear in log10 L).
    Also returned: the minimax (Chebyshev) estimate (max d + min d) / 2, which minimises the largest
    |residual| and is set by the two extreme points only.
    """
    L = np.asarray(L50_h, dtype=float)
    require(L.ndim == 1 and L.size >= 2 and bool(np.all(np.isfinite(L) & (L > 0.0))), "L50_h", L50_h,
            "must be at least two positive lives")
    conditions = (dm_mm, speed_rpm, temperature_C, load_ratio, speed_factor)
    try:
        shape = np.broadcast_shapes(L.shape, *(np.shape(x) for x in conditions))
    except ValueError:
        shape = None
    require(shape == L.shape, "conditions", [np.shape(x) for x in conditions],
            f"must be scalars or arrays of the {L.size} lives' length")
    d = np.log10(L) - log10_life_without_base_oil(grease, *conditions)
    require(bool(np.all(np.isfinite(d))), "conditions", d, "must be finite")
    k1 = float(d.mean())
    return BaseOilFit(k1_least_squares=k1, k1_standard_error=float(d.std(ddof=1) / math.sqrt(d.size)),
                      k1_minimax=float(0.5 * (d.max() + d.min())), offsets_log10=d)
