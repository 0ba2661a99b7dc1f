"""Flow stress of hot austenite from published hot-deformation laws, for the austenite yield of a quench (a maintainer's
tool: ``python dev/austenite_flow.py`` prints the austenite yield row of materials/SUJ2.mechanics.toml and
SUJ3.mechanics.toml; the package reads those files, not this).

Two laws, both fitted to measured hot tests (sources in ``materials/data/austenite_flow.toml``):

* :func:`kozlowski_III_stress_MPa` -- Kozlowski et al., Metall. Trans. A 23A (1992) 903, Model III: strain
  rate = f_C [sigma - f1 eps |eps|^(f2-1)]^f3 exp(-Q/T), strain dependent, carbon dependent.
* :func:`zener_hollomon_peak_stress_MPa` -- the hyperbolic-sine Arrhenius law strain rate =
  A [sinh(alpha sigma)]^n exp(-Q/RT) of hot-compression studies (peak stress).

:func:`austenite_yield_table` combines them at a quench's strain rate into the (T, yield) points of a material's
austenite row: the geometric mean of Kozlowski's 0.2 %-offset stress and the Zener-Hollomon peak times a stated
small-strain fraction, from 750 C up; below, the data file's metastable-austenite assumption joined
log-linearly to the 750 C value.

>>> round(zener_hollomon_peak_stress_MPa(850.0, 1e-3, A_1_s=1e18, alpha_1_MPa=0.0083, n=5.78, Q_J_mol=481363.0))
159
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from quenchsim.errors import InputError
from quenchsim.inputs.reader import read_toml

R_J_molK = 8.314462618
"""Molar gas constant, J/(mol K)."""

DATA_FILE = Path(__file__).resolve().parents[1] / "materials" / "data" / "austenite_flow.toml"
"""The data file, in the repository beside dev/ (a maintainer's tool: the numbers it prints are written into the steels'
mechanics files, which the package reads)."""


def kozlowski_III_stress_MPa(T_C: float, strain: float, strain_rate_1_s: float, carbon_wt_pct: float,
                             Q_K: float = 44465.0, f1: tuple[float, float] = (130.5, -5.128e-3),
                             f2: tuple[float, float] = (-0.6289, 1.114e-3), f3: tuple[float, float] = (8.132, -1.54e-3),
                             f_C: tuple[float, float, float] = (46550.0, 71400.0, 12000.0)) -> float:
    """Stress (MPa) of austenite at inelastic ``strain`` (> 0) and ``strain_rate_1_s`` by Kozlowski's Model III,
    sigma = f1 eps^f2 + [rate / (f_C exp(-Q_K/T))]^(1/f3), T in K, carbon in wt% (Kozlowski et al. 1992)."""
    if strain <= 0.0 or strain_rate_1_s <= 0.0:
        raise ValueError("strain and strain rate must be > 0")
    T_K = T_C + 273.15
    a1, a2, a3 = f1[0] + f1[1] * T_K, f2[0] + f2[1] * T_K, f3[0] + f3[1] * T_K
    fc = f_C[0] + f_C[1] * carbon_wt_pct + f_C[2] * carbon_wt_pct ** 2
    hardening = a1 * strain ** a2
    thermal = (strain_rate_1_s / (fc * math.exp(-Q_K / T_K))) ** (1.0 / a3)
    return hardening + thermal


def zener_hollomon_peak_stress_MPa(T_C: float, strain_rate_1_s: float, A_1_s: float, alpha_1_MPa: float,
                                   n: float, Q_J_mol: float) -> float:
    """Peak stress (MPa) of the hyperbolic-sine law rate = A sinh(alpha sigma)^n exp(-Q/RT), inverted:
    sigma = asinh[(Z/A)^(1/n)] / alpha with Z = rate exp(Q/RT) (Sellars & McTegart form)."""
    if strain_rate_1_s <= 0.0:
        raise ValueError("strain rate must be > 0")
    T_K = T_C + 273.15
    ln_z_over_a = math.log(strain_rate_1_s) + Q_J_mol / (R_J_molK * T_K) - math.log(A_1_s)
    return math.asinh(math.exp(ln_z_over_a / n)) / alpha_1_MPa


@dataclass(frozen=True)
class YieldTable:
    """Austenite yield points (T in C, yield in Pa) and the prior factor that spans the laws and the rate band."""

    T_C: tuple[float, ...]
    yield_Pa: tuple[float, ...]
    range_factor: float


def _value(entry: Any) -> float:
    return float(entry["value"] if isinstance(entry, dict) else entry)


def _law_stresses_MPa(data: dict[str, Any], T_C: float, rate: float) -> tuple[float, float]:
    koz, huo = data["laws"]["KOZLOWSKI1992"], data["laws"]["HUO2013"]
    s_koz = kozlowski_III_stress_MPa(T_C, _value(data["offset_strain"]), rate, _value(data["carbon_wt_pct"]),
                                     Q_K=koz["Q_K"], f1=tuple(koz["f1"]), f2=tuple(koz["f2"]), f3=tuple(koz["f3"]),
                                     f_C=tuple(koz["f_C"]))
    s_huo = _value(huo["small_strain_fraction"]) * zener_hollomon_peak_stress_MPa(
        T_C, rate, huo["A_1_s"], huo["alpha_1_MPa"], huo["n"], huo["Q_J_mol"])
    return s_koz, s_huo


def austenite_yield_table(data: dict[str, Any]) -> YieldTable:
    """The austenite yield row from the data file's laws: sourced points at ``sourced_T_C``, the metastable
    assumption below; ``range_factor`` is the largest factor that takes in both laws over the strain-rate range
    at any sourced point (and at least the metastable assumption's)."""
    rate = _value(data["strain_rate_1_s"])
    lo_rate, hi_rate = data["strain_rate_1_s"]["range"]
    hot_T = [float(t) for t in data["sourced_T_C"]]
    hot_MPa, factor = [], float(data["metastable"]["range_factor"])
    for T in hot_T:
        mean = math.sqrt(math.prod(_law_stresses_MPa(data, T, rate)))
        spread = [s for r in (lo_rate, hi_rate) for s in _law_stresses_MPa(data, T, r)]
        factor = max(factor, max(spread) / mean, mean / min(spread))
        hot_MPa.append(mean)
    meta = data["metastable"]
    cold_T = [float(t) for t in meta["T_C"]]
    if cold_T[-1] >= hot_T[0]:
        raise InputError("metastable.T_C", cold_T, f"must lie below the first sourced temperature {hot_T[0]:g} C")
    ln0, ln1 = math.log(meta["yield_20C_MPa"]), math.log(hot_MPa[0])
    cold_MPa = [math.exp(ln0 + (ln1 - ln0) * (T - cold_T[0]) / (hot_T[0] - cold_T[0])) for T in cold_T]
    return YieldTable(T_C=tuple(cold_T + hot_T), yield_Pa=tuple(1e6 * s for s in cold_MPa + hot_MPa),
                      range_factor=round(factor, 2))


def load_data(path: Path = DATA_FILE) -> dict[str, Any]:
    """The austenite flow data file (TOML) as a dict."""
    return read_toml(path, "austenite flow data")


def _main() -> None:  # pragma: no cover - prints the material row
    data = load_data()
    table = austenite_yield_table(data)
    rate = _value(data["strain_rate_1_s"])
    print(f"{'T_C':>6} {'KOZ MPa':>8} {'HUO MPa':>8} {'yield MPa':>9}")
    for T, s in zip(table.T_C, table.yield_Pa):
        koz, huo = _law_stresses_MPa(data, T, rate) if T >= data["sourced_T_C"][0] else (float("nan"),) * 2
        print(f"{T:6.0f} {koz:8.1f} {huo:8.1f} {s / 1e6:9.1f}")
    print(f"range_factor = {table.range_factor}")
    print("T_C = [" + ", ".join(f"{t:.1f}" for t in table.T_C) + "]")
    print("value = [" + ", ".join(f"{s:.4g}" for s in table.yield_Pa) + "]")


if __name__ == "__main__":  # pragma: no cover
    _main()
