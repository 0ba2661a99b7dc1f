"""Quenchant properties from ``materials/quenchants/NAME.toml`` (liquid oils, still-bath curves and air).

A liquid quenchant file has a ``[liquid]`` table (viscosity table fitted by Vogel, density, specific
heat, conductivity, expansion coefficient) and a ``[boiling]`` table (boiling point, vapour data,
boiling-curve constants). A gas file (``kind = "gas"``) has a ``[gas]`` table of properties at 1 atm
tabulated against temperature. A still-bath curve (``kind = "still_bath_curve"``, written by ``quenchsim quenchant
fit`` / ``from-datasheet``) holds h(T_surface) measured on the ISO 9950 probe in still oil with its test conditions.
Every entry carries a ``source``; see the files themselves.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.optimize import brentq

from quenchsim.errors import InputError
from quenchsim.inputs.declare import declared_fields
from quenchsim.inputs.quenchant import (BoilingProperties, GasQuenchant, LiquidProperties, LiquidQuenchant,
                                        Quenchant, StillBathCurve, read_quenchant)
from quenchsim.inputs.reader import read_toml
from quenchsim.materials import find_data_file, materials_dir

KELVIN = 273.15
GAS_CONSTANT = 8.314462618  # J/(mol K), CODATA 2018
ATMOSPHERE_Pa = 101325.0


@dataclass(frozen=True)
class Vogel:
    """Vogel viscosity law mu(T) = exp(A + B/(T_K - C)) (Vogel 1921), T in C, mu in Pa s."""

    A: float
    B_K: float
    C_K: float

    def __call__(self, T_C: Any) -> np.ndarray:
        T_K = np.asarray(T_C, dtype=float) + KELVIN
        return np.exp(self.A + self.B_K / (T_K - self.C_K))


def fit_vogel(T_C: np.ndarray, mu_Pa_s: np.ndarray, field: str) -> Vogel:
    """The Vogel law through three (T, mu) points, solved exactly.

    With y = ln mu, (y1 - y2)/(y2 - y3) fixes C (root of a monotone function between 0 K and the lowest
    point); B and A follow linearly. Raises InputError unless the points are three, increasing in T and
    decreasing in mu with a positive Vogel temperature below the first point.
    """
    T = np.asarray(T_C, dtype=float) + KELVIN
    mu = np.asarray(mu_Pa_s, dtype=float)
    if T.size != 3 or mu.size != 3 or np.any(np.diff(T) <= 0) or np.any(mu <= 0) or np.any(np.diff(mu) >= 0):
        raise InputError(field, list(mu_Pa_s), "needs 3 positive viscosities decreasing with increasing T_C")
    y = np.log(mu)
    target = (y[0] - y[1]) / (y[1] - y[2])

    def residual(C: float) -> float:
        a, b, c = 1.0 / (T - C)
        return (a - b) / (b - c) - target

    lo, hi = 0.0, T[0] - 1e-6
    if residual(lo) * residual(hi) > 0:
        raise InputError(field, list(mu_Pa_s), "cannot be fitted by a Vogel law with 0 K < C < T_1")
    C = brentq(residual, lo, hi, xtol=1e-10)
    B = (y[0] - y[1]) / (1.0 / (T[0] - C) - 1.0 / (T[1] - C))
    return Vogel(A=float(y[0] - B / (T[0] - C)), B_K=float(B), C_K=float(C))


@dataclass(frozen=True)
class OilProperties:
    """A boiling liquid quenchant (mineral oil). SI units, T in C."""

    name: str
    viscosity: Vogel
    density_kg_m3: float
    specific_heat_J_kgK: float
    conductivity_W_mK: float
    expansion_1_K: float
    boiling_point_C: float
    molar_mass_kg_mol: float
    latent_heat_J_kg: float
    surface_tension_N_m: float
    vapour_conductivity_W_mK: float
    vapour_viscosity_Pa_s: float
    vapour_specific_heat_J_kgK: float
    zuber_K: float
    ivey_morris_C: float
    rohsenow_n: float
    rohsenow_Csf: float
    leidenfrost_still_C: float
    film_collapse_resistance_m2K_W: float
    transition_min_width_K: float
    bromley_C: float
    film_forced_C: float
    surface_emissivity: float

    def kinematic_viscosity(self, T_C: Any) -> np.ndarray:
        """nu = mu(T)/rho (m^2/s)."""
        return self.viscosity(T_C) / self.density_kg_m3

    def prandtl(self, T_C: Any) -> np.ndarray:
        """Pr = mu c_p / k."""
        return self.viscosity(T_C) * self.specific_heat_J_kgK / self.conductivity_W_mK

    def vapour_density(self, T_C: Any) -> np.ndarray:
        """Ideal-gas vapour density at 1 atm, rho_v = p M / (R T)."""
        return ATMOSPHERE_Pa * self.molar_mass_kg_mol / (GAS_CONSTANT * (np.asarray(T_C, dtype=float) + KELVIN))


@dataclass(frozen=True)
class GasProperties:
    """A gas at 1 atm tabulated against temperature (linear interpolation, clamped)."""

    name: str
    T_C: np.ndarray
    conductivity_W_mK: np.ndarray
    kinematic_viscosity_m2_s: np.ndarray
    prandtl_table: np.ndarray

    def conductivity(self, T_C: Any) -> np.ndarray:
        return np.interp(T_C, self.T_C, self.conductivity_W_mK)

    def kinematic_viscosity(self, T_C: Any) -> np.ndarray:
        return np.interp(T_C, self.T_C, self.kinematic_viscosity_m2_s)

    def prandtl(self, T_C: Any) -> np.ndarray:
        return np.interp(T_C, self.T_C, self.prandtl_table)

    @staticmethod
    def expansion_1_K(T_C: Any) -> np.ndarray:
        """Ideal gas: beta = 1/T_K."""
        return 1.0 / (np.asarray(T_C, dtype=float) + KELVIN)


def _quenchant(name: str, field: str) -> Quenchant:
    """The quenchant file ``name`` (quenchants/NAME.toml on the search path, or a path), read against its kind."""
    return read_quenchant(find_data_file(name, "quenchants", field), field)


def load_oil(name: str, field: str = "quench.bath.quenchant") -> OilProperties:
    """Load a boiling liquid quenchant ``materials/quenchants/NAME.toml``; errors name ``field``."""
    data = _quenchant(name, field)
    if not isinstance(data, LiquidQuenchant):
        raise InputError(field, name, f"is a {data.kind} quenchant; a liquid (oil) is needed here")
    liquid, boiling = data.liquid, data.boiling
    visc = liquid.viscosity_Pa_s
    values = {f.name: getattr(liquid, f.name) for f in declared_fields(LiquidProperties) if f.name != "viscosity_Pa_s"}
    values.update({f.name: getattr(boiling, f.name) for f in declared_fields(BoilingProperties)})
    return OilProperties(name=name, viscosity=fit_vogel(np.asarray(visc.T_C), np.asarray(visc.value),
                                                        f"{name}.liquid.viscosity_Pa_s"), **values)


def load_gas(name: str, field: str = "air") -> GasProperties:
    """Load a gas quenchant ``materials/quenchants/NAME.toml`` (``kind = "gas"``)."""
    data = _quenchant(name, field)
    if not isinstance(data, GasQuenchant):
        raise InputError(field, name, "is not a gas quenchant file (kind = \"gas\")")
    gas = data.gas
    return GasProperties(name=name, T_C=np.asarray(gas.T_C, float),
                         conductivity_W_mK=np.asarray(gas.conductivity_W_mK, float),
                         kinematic_viscosity_m2_s=np.asarray(gas.kinematic_viscosity_m2_s, float),
                         prandtl_table=np.asarray(gas.prandtl, float))


# --- still-bath curves: h(T_surface) measured on the ISO 9950 probe (written by `quenchsim quenchant`) -----------

STILL_BATH_KIND = "still_bath_curve"


@dataclass(frozen=True)
class ProbeQuenchant:
    """A still-bath HTC curve h(T_surface) from a probe test, with the test conditions it holds for.

    ``h(T_surface_C)`` interpolates linearly, constant beyond the ends. ``identified_C`` is the surface-
    temperature range the probe data saw (outside it the curve is the regularised extrapolation)."""

    name: str
    T_C: np.ndarray
    h_W_m2K: np.ndarray
    bath_temperature_C: float
    agitation_m_s: float
    identified_C: tuple[float, float]
    method: str
    source: str

    def h(self, T_surface_C: Any) -> np.ndarray:
        return np.interp(np.asarray(T_surface_C, dtype=float), self.T_C, self.h_W_m2K)


def load_probe_quenchant(path_or_name: str | Path, field: str = "quenchant") -> ProbeQuenchant:
    """Load a still-bath curve ``materials/quenchants/NAME.toml`` (or a path ending in .toml) written by
    ``quenchsim quenchant fit`` / ``from-datasheet``; errors name ``field``."""
    name = str(path_or_name)
    data = _quenchant(name, field)
    if not isinstance(data, StillBathCurve):
        raise InputError(field, name, f"is a {data.kind} quenchant file; a still-bath curve "
                                      f"(kind = \"{STILL_BATH_KIND}\", from `quenchsim quenchant fit`) is needed")
    htc, test = data.htc, data.test
    T, h = np.asarray(htc.T_C, dtype=float), np.asarray(htc.h_W_m2K, dtype=float)
    lo, hi = htc.identified_T_C if htc.identified_T_C is not None else (T[0], T[-1])
    return ProbeQuenchant(name=data.name or Path(name).stem, T_C=T, h_W_m2K=h,
                          bath_temperature_C=test.bath_temperature_C, agitation_m_s=test.agitation_m_s,
                          identified_C=(float(lo), float(hi)), method=htc.method, source=data.source)


def library() -> list[str]:
    """Names of the still-bath curves shipped in materials/quenchants/."""
    names = []
    for p in sorted((materials_dir() / "quenchants").glob("*.toml")):
        if read_toml(p, "quenchant").get("kind") == STILL_BATH_KIND:
            names.append(p.stem)
    return names
