"""Engine-oil properties from materials/lubricants/*.toml (viscosity at the imposed oil temperature).

Viscosity-temperature: Walther equation (ASTM D341), log10(log10(nu + 0.7)) = A - B log10(T),
nu in mm^2/s, T in K, fitted through the two tabulated points of the data file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from quenchsim.errors import InputError, require
from quenchsim.inputs.reader import read_toml

LUBRICANTS_DIR = Path(__file__).resolve().parents[3] / "materials" / "lubricants"
KELVIN = 273.15


@dataclass(frozen=True)
class OilState:
    """Oil properties at one temperature (SI)."""

    name: str
    temperature_C: float
    dynamic_viscosity_Pa_s: float
    density_kg_m3: float
    pressure_viscosity_1_Pa: float
    temperature_viscosity_1_K: float  # beta = -(1/eta) d eta / dT
    thermal_conductivity_W_mK: float
    limiting_traction_coefficient: float
    traction_slide_roll_scale: float


def available_oils() -> list[str]:
    """Names of the oil data files in materials/lubricants/."""
    return sorted(p.stem for p in LUBRICANTS_DIR.glob("*.toml"))


def walther_viscosity(temperature_C: float, nu1_mm2_s: float, t1_C: float, nu2_mm2_s: float,
                      t2_C: float) -> tuple[float, float]:
    """Kinematic viscosity nu [mm^2/s] and beta = -(1/nu) dnu/dT [1/K] at ``temperature_C``.

    Walther/ASTM D341: W = log10(log10(nu + 0.7)) = A - B log10(T_K) through (t1, nu1), (t2, nu2);
    beta = (nu + 0.7) Z ln(10) B / (nu T_K) with Z = log10(nu + 0.7).
    """
    w1 = math.log10(math.log10(nu1_mm2_s + 0.7))
    w2 = math.log10(math.log10(nu2_mm2_s + 0.7))
    x1, x2 = math.log10(t1_C + KELVIN), math.log10(t2_C + KELVIN)
    b = (w1 - w2) / (x2 - x1)
    a = w1 + b * x1
    t_k = temperature_C + KELVIN
    z = 10.0 ** (a - b * math.log10(t_k))
    nu = 10.0**z - 0.7
    beta = (nu + 0.7) * z * math.log(10.0) * b / (nu * t_k)
    return nu, beta


def load_oil(name: str, temperature_C: float) -> OilState:
    """Load ``materials/lubricants/<name>.toml`` and evaluate it at ``temperature_C``."""
    known = available_oils()
    if name not in known:
        raise InputError("lubrication.oil", name, f"must be one of {known}")
    require(-30.0 <= temperature_C <= 150.0, "lubrication.temperature_C", temperature_C,
            "must be within -30..150 C (range of the Walther fit of the data file)")
    data = read_toml(LUBRICANTS_DIR / f"{name}.toml", "lubrication.oil")
    nu, beta = walther_viscosity(temperature_C, data["kinematic_viscosity_40C_mm2_s"], 40.0,
                                 data["kinematic_viscosity_100C_mm2_s"], 100.0)
    rho = data["density_15C_kg_m3"] * (1.0 - data["density_temperature_coefficient_1_K"]
                                       * (temperature_C - 15.0))
    return OilState(
        name=name,
        temperature_C=temperature_C,
        dynamic_viscosity_Pa_s=nu * 1e-6 * rho,
        density_kg_m3=rho,
        pressure_viscosity_1_Pa=data["pressure_viscosity_1_Pa"],
        temperature_viscosity_1_K=beta,
        thermal_conductivity_W_mK=data["thermal_conductivity_W_mK"],
        limiting_traction_coefficient=data["limiting_traction_coefficient"],
        traction_slide_roll_scale=data["traction_slide_roll_scale"],
    )
