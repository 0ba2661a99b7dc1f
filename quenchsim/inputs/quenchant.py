"""Quenchant files ``materials/quenchants/NAME.toml``, one declaration per ``kind``: a boiling liquid (``"liquid"``,
the bath model's oils), a gas (``"gas"``, still air), a still-bath curve measured or fitted on the ISO 9950 probe
(``"still_bath_curve"``, written by ``quenchsim quenchant``), the probe itself (``"probe"``) and a start shape of the
data-sheet fit (``"shape"``, ``quenchants/data/``). Every number carries its ``source``; what the properties mean:
:mod:`quenchsim.bath.quenchant`, which builds the models from these declarations.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import REQUIRED, DataFile, Table, convert, quantity
from quenchsim.inputs.reader import read_toml, reading
from quenchsim.inputs.steel import Thermal

@dataclass(frozen=True, kw_only=True)
class ViscosityTable(Table):
    """``viscosity_Pa_s = { T_C = [...], value = [...], fit = "vogel", source = "..." }``: three dynamic viscosities,
    decreasing with temperature, through which the Vogel law is fitted exactly."""

    T_C: tuple[float, ...] = quantity(REQUIRED, unit="C", doc="three temperatures, increasing")
    value: tuple[float, ...] = quantity(REQUIRED, unit="Pa s", doc="the viscosities at T_C")
    fit: Literal["vogel"] = quantity("vogel", doc="the law fitted through the points")
    source: str = quantity("", doc="where the values come from")


@dataclass(frozen=True, kw_only=True)
class LiquidProperties(Table):
    """``[liquid]`` of a liquid quenchant: the properties of the oil."""

    viscosity_Pa_s: ViscosityTable = quantity(REQUIRED, doc="dynamic viscosity against temperature")
    density_kg_m3: float = quantity(REQUIRED, unit="kg/m3", gt=0.0, sourced=True, doc="density")
    specific_heat_J_kgK: float = quantity(REQUIRED, unit="J/kgK", gt=0.0, sourced=True, doc="specific heat")
    conductivity_W_mK: float = quantity(REQUIRED, unit="W/mK", gt=0.0, sourced=True, doc="thermal conductivity")
    expansion_1_K: float = quantity(REQUIRED, unit="1/K", gt=0.0, sourced=True, doc="volumetric expansion coefficient")


@dataclass(frozen=True, kw_only=True)
class BoilingProperties(Table):
    """``[boiling]`` of a liquid quenchant: its vapour and the constants of the boiling curve."""

    boiling_point_C: float = quantity(REQUIRED, unit="C", sourced=True, doc="normal boiling point")
    molar_mass_kg_mol: float = quantity(REQUIRED, unit="kg/mol", gt=0.0, sourced=True, doc="molar mass of the vapour")
    latent_heat_J_kg: float = quantity(REQUIRED, unit="J/kg", gt=0.0, sourced=True, doc="heat of vaporisation")
    surface_tension_N_m: float = quantity(REQUIRED, unit="N/m", gt=0.0, sourced=True, doc="near the boiling point")
    vapour_conductivity_W_mK: float = quantity(REQUIRED, unit="W/mK", gt=0.0, sourced=True, doc="of the vapour")
    vapour_viscosity_Pa_s: float = quantity(REQUIRED, unit="Pa s", gt=0.0, sourced=True, doc="of the vapour")
    vapour_specific_heat_J_kgK: float = quantity(REQUIRED, unit="J/kgK", gt=0.0, sourced=True, doc="of the vapour")
    zuber_K: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="Zuber's critical-flux constant")
    ivey_morris_C: float = quantity(REQUIRED, ge=0.0, sourced=True, doc="Ivey & Morris subcooling constant")
    rohsenow_n: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="Rohsenow's Prandtl exponent")
    rohsenow_Csf: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="Rohsenow's surface-fluid constant")
    leidenfrost_still_C: float = quantity(REQUIRED, unit="C", sourced=True, doc="film collapse of still oil")
    film_collapse_resistance_m2K_W: float = quantity(REQUIRED, unit="m2K/W", gt=0.0, sourced=True,
                                                     doc="the film-collapse resistance")
    transition_min_width_K: float = quantity(REQUIRED, unit="K", gt=0.0, sourced=True,
                                             doc="narrowest transition-boiling range")
    bromley_C: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="Bromley's film-boiling coefficient")
    film_forced_C: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="forced-convection film-boiling coefficient")
    surface_emissivity: float = quantity(REQUIRED, ge=0.0, le=1.0, sourced=True, doc="of the steel under the film")


@dataclass(frozen=True, kw_only=True)
class LiquidQuenchant(DataFile):
    """A boiling liquid quenchant (``kind = "liquid"``): a mineral oil of the bath model."""

    kind: Literal["liquid"] = quantity(REQUIRED, doc="\"liquid\"")
    liquid: LiquidProperties = quantity(REQUIRED, doc="properties of the oil")
    boiling: BoilingProperties = quantity(REQUIRED, doc="vapour and boiling-curve constants")


@dataclass(frozen=True, kw_only=True)
class GasTable(Table):
    """``[gas]``: properties at 1 atm against temperature (linear interpolation, clamped)."""

    T_C: tuple[float, ...] = quantity(REQUIRED, unit="C", doc="temperatures, increasing")
    conductivity_W_mK: tuple[float, ...] = quantity(REQUIRED, unit="W/mK", doc="at T_C")
    kinematic_viscosity_m2_s: tuple[float, ...] = quantity(REQUIRED, unit="m2/s", doc="at T_C")
    prandtl: tuple[float, ...] = quantity(REQUIRED, doc="Prandtl number at T_C")

    def check(self) -> None:
        for key in ("conductivity_W_mK", "kinematic_viscosity_m2_s", "prandtl"):
            require(len(getattr(self, key)) == len(self.T_C), key, list(getattr(self, key)),
                    f"needs {len(self.T_C)} values, one per T_C")


@dataclass(frozen=True, kw_only=True)
class GasQuenchant(DataFile):
    """A gas (``kind = "gas"``): still air of the transfer, air and temper stages."""

    kind: Literal["gas"] = quantity(REQUIRED, doc="\"gas\"")
    gas: GasTable = quantity(REQUIRED, doc="properties at 1 atm")


@dataclass(frozen=True, kw_only=True)
class ProbeTest(Table):
    """``[test]`` of a still-bath curve: the probe test it holds for."""

    probe: str = quantity("", doc="the probe file (quenchants/NAME.toml, kind = \"probe\")")
    bath_temperature_C: float = quantity(REQUIRED, unit="C", doc="bath temperature of the test",
                                         allowed="is required (a number)")
    agitation_m_s: float = quantity(REQUIRED, unit="m/s", ge=0.0, doc="agitation of the test",
                                    allowed="is required (a number)")
    start_temperature_C: float | None = quantity(None, unit="C", doc="the probe's start temperature")


@dataclass(frozen=True, kw_only=True)
class CurveTable(Table):
    """``[htc]`` of a still-bath curve: h against the surface temperature."""

    T_C: tuple[float, ...] = quantity(REQUIRED, unit="C", doc="surface temperatures, >= 2, strictly increasing")
    h_W_m2K: tuple[float, ...] = quantity(REQUIRED, unit="W/m2K", doc="positive values, one per T_C")
    h_std_W_m2K: tuple[float, ...] | None = quantity(None, unit="W/m2K", doc="standard deviation of h at T_C (an "
                                                      "inverse fit's)")
    identified_T_C: tuple[float, float] | None = quantity(None, unit="C", doc="the range the probe data saw")
    method: str = quantity("", doc="how the curve was found")
    source: str = quantity("", doc="where it comes from")

    def check(self) -> None:
        T, h = self.T_C, self.h_W_m2K
        require(len(T) >= 2 and all(b > a for a, b in zip(T, T[1:])), "T_C", list(T),
                "needs >= 2 strictly increasing temperatures")
        require(len(h) == len(T) and all(v > 0 for v in h), "h_W_m2K", list(h),
                f"needs {len(T)} positive values (one per T_C)")


@dataclass(frozen=True, kw_only=True)
class StillBathCurve(DataFile):
    """A still-bath curve (``kind = "still_bath_curve"``): h(T_surface) on the ISO 9950 probe in still oil, written by
    ``quenchsim quenchant fit`` / ``from-datasheet``; the fit's provenance tables are kept as written."""

    kind: Literal["still_bath_curve"] = quantity(REQUIRED, doc="\"still_bath_curve\"")
    test: ProbeTest = quantity(REQUIRED, doc="the test conditions")
    htc: CurveTable = quantity(REQUIRED, doc="the curve")
    fit: Mapping[str, Any] = quantity({}, doc="the fit's residuals and figures (provenance)")
    curve: Mapping[str, Any] = quantity({}, doc="the data fitted (provenance)")
    shape: Mapping[str, Any] = quantity({}, doc="a data-sheet fit's shape parameters")
    resimulated: Mapping[str, Any] = quantity({}, doc="the probe's cooling curve with the fitted h (provenance)")


@dataclass(frozen=True, kw_only=True)
class ProbeFile(DataFile):
    """The ISO 9950 probe (``kind = "probe"``): its size, test temperatures and material (a ``[thermal]`` table as a
    steel's)."""

    kind: Literal["probe"] = quantity(REQUIRED, doc="\"probe\"")
    diameter_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="cylinder diameter")
    length_mm: float = quantity(REQUIRED, unit="mm", gt=0.0, doc="cylinder length")
    start_temperature_C: float = quantity(REQUIRED, unit="C", doc="the probe's start temperature")
    oil_temperature_C: float = quantity(REQUIRED, unit="C", doc="the standard's oil temperature")
    thermal: Thermal = quantity(REQUIRED, doc="density, conductivity, specific heat (property forms, as a steel's)")


@dataclass(frozen=True, kw_only=True)
class ShapeFile(DataFile):
    """A start shape of the data-sheet fit (``kind = "shape"``, ``quenchants/data/``)."""

    kind: Literal["shape"] = quantity(REQUIRED, doc="\"shape\"")
    shape: Mapping[str, Any] = quantity(REQUIRED, doc="the shape parameters (quenchsim.fitting.quenchant)")


Quenchant = LiquidQuenchant | GasQuenchant | StillBathCurve | ProbeFile | ShapeFile
"""A quenchant file, by its ``kind``."""
KINDS = ("liquid", "gas", "still_bath_curve", "probe", "shape")


def read_quenchant(path: Path, field: str) -> Quenchant:
    """The quenchant file ``path`` read against the declaration of its ``kind``; errors name the file (and ``field``,
    the key that named it, when the file cannot be read or has no known kind)."""
    table = read_toml(path, field)
    if table.get("kind") not in KINDS:
        raise InputError(field, str(path), f"is a {table.get('kind', 'untyped')} file; a quenchant file has kind = "
                                           f"{' | '.join(KINDS)}")
    with reading(path):
        quenchant: Quenchant = convert(table, Quenchant, "")
        return quenchant
