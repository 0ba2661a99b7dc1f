"""A steel's mechanics file ``materials/NAME.mechanics.toml`` (elastic, free-strain, plastic and TRIP data of the
quench stress model), declared once; what the data mean: :mod:`quenchsim.mechanics.model`, which builds the model
from this declaration.

Priors for calibration: an uncertain value carries ``range = [lo, hi]`` (lo <= value <= hi) or ``range_factor = f``
(value times/divided by f, f >= 1), checked on load.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from quenchsim.errors import require
from quenchsim.inputs.declare import REQUIRED, Table, quantity
from quenchsim.inputs.properties import Property
from quenchsim.materials.properties import PHASES

FREE_STRAIN_FORMS = ("specific_volume", "expansion")
TRIP_LAWS = ("desalos", "leblond")
CARBON_FROM = ("composition", "austenitisation")
"""A carbon content given by name: the steel file's bulk C (``"composition"``) or the C dissolved in austenite at the
austenitising temperature (``"austenitisation"``, the value the metallurgy uses)."""


@dataclass(frozen=True, kw_only=True)
class Reference(Table):
    """``[reference]``: the stress-free austenitised state (a case's process.austenitising_temperature_C overrides
    it)."""

    austenitizing_T_C: float = quantity(REQUIRED, unit="C", ge=500.0, le=1300.0, sourced=True,
                                        doc="austenitising temperature of the data")


@dataclass(frozen=True, kw_only=True)
class Elastic(Table):
    """``[elastic]``: Young's modulus and Poisson's ratio, properties (per phase or not)."""

    E_Pa: Property = quantity(REQUIRED, unit="Pa", doc="Young's modulus (> 0 over the quench)")
    nu: Property = quantity(REQUIRED, doc="Poisson's ratio (0 <= nu < 0.5 over the quench)")


@dataclass(frozen=True, kw_only=True)
class VolumeChanges(Table):
    """``[free_strain.volume_change_pct]``: dV/V (%) of austenite -> phase at the reference temperature,
    ``[a, b]``: a + b C with C the matrix carbon (wt %)."""

    source: str = quantity("", doc="where the relations come from")
    pearlite: tuple[float, float] = quantity(REQUIRED, unit="%", sourced=True, doc="[a, b]",
                                             allowed="must be [a, b] with dV/V (%) = a + b*C")
    bainite: tuple[float, float] = quantity(REQUIRED, unit="%", sourced=True, doc="[a, b]",
                                            allowed="must be [a, b] with dV/V (%) = a + b*C")
    martensite: tuple[float, float] = quantity(REQUIRED, unit="%", sourced=True, doc="[a, b]",
                                               allowed="must be [a, b] with dV/V (%) = a + b*C")


Carbon = float | Literal["composition", "austenitisation"]
"""A carbon content (wt %), or where the steel file gives it (:data:`CARBON_FROM`)."""


@dataclass(frozen=True, kw_only=True)
class SpecificVolumeStrain(Table):
    """``[free_strain] form = "specific_volume"``: phase volumes from their expansion and their volume change against
    austenite at a reference temperature (Thelning / ASM relations), diluted by the undissolved carbide."""

    form: Literal["specific_volume"] = quantity(REQUIRED, doc="the form")
    source: str = quantity("", doc="where the form comes from")
    reference_T_C: float = quantity(REQUIRED, unit="C", ge=-273.15, le=1500.0, sourced=True,
                                    doc="temperature of the volume changes")
    carbon_bulk_wt_pct: Carbon = quantity(REQUIRED, unit="wt%", sourced=True, doc="bulk carbon, or \"composition\"",
                                          allowed="must be a carbon content in [0, 2.1] wt% or 'composition'")
    carbon_matrix_wt_pct: Carbon = quantity(REQUIRED, unit="wt%", sourced=True, doc="carbon in the austenite, or "
                                            "\"austenitisation\"", allowed="must be a carbon content in [0, 2.1] wt% "
                                            "or 'austenitisation'")
    cementite_carbon_wt_pct: float = quantity(REQUIRED, unit="wt%", le=100.0, sourced=True, doc="carbon of Fe3C")
    steel_to_cementite_density_ratio: float = quantity(REQUIRED, ge=0.5, le=2.0, sourced=True,
                                                       doc="rho_steel / rho_cementite")
    volume_change_pct: VolumeChanges = quantity(REQUIRED, doc="the volume changes")
    alpha_1_K: Property = quantity(REQUIRED, unit="1/K", doc="instantaneous expansion coefficients (per phase)")

    def check(self) -> None:
        for key in ("carbon_bulk_wt_pct", "carbon_matrix_wt_pct"):
            value = getattr(self, key)
            require(isinstance(value, str) or 0.0 <= value <= 2.1, key, value, "must be a number in [0, 2.1]")


@dataclass(frozen=True, kw_only=True)
class ExpansionStrain(Table):
    """``[free_strain] form = "expansion"``: per-phase expansion coefficients and a linear transformation strain of
    austenite -> phase taken where the transformation happens (e.g. Furlan et al. 2025)."""

    form: Literal["expansion"] = quantity(REQUIRED, doc="the form")
    source: str = quantity("", doc="where the form comes from")
    alpha_1_K: Property = quantity(REQUIRED, unit="1/K", doc="instantaneous expansion coefficients (per phase)")
    transformation_strain: Property = quantity(REQUIRED, doc="linear strain of austenite -> phase (per phase)")


@dataclass(frozen=True, kw_only=True)
class Annealed(Table):
    """``[annealed]``: the "before" state (room-temperature annealed part): its free strain, or the phase and
    temperature whose free strain it is (specific-volume form)."""

    phase: Literal["austenite", "pearlite", "bainite", "martensite"] | None = quantity(
        None, doc="the annealed structure's phase", allowed=f"must be one of {PHASES} (or give free_strain)")
    T_C: float | None = quantity(None, unit="C", ge=-273.15, le=1500.0, sourced=True, doc="its temperature")
    free_strain: float | None = quantity(None, ge=-0.1, le=0.1, sourced=True, doc="its free strain (instead)")


@dataclass(frozen=True, kw_only=True)
class MetastableFactor(Table):
    """``metastable_austenite_yield_factor = { value, below_T_C, range_factor, source }``: a factor on the austenite
    yield table's points below ``below_T_C`` (the metastable austenite of a quench, where no hot test applies)."""

    value: float = quantity(REQUIRED, ge=1e-3, le=1e3, doc="the factor")
    below_T_C: float = quantity(REQUIRED, unit="C", ge=-273.15, le=2000.0,
                                doc="the temperature below which the factor applies")
    range: tuple[float, float] | None = quantity(None, doc="prior band of the factor")
    range_factor: float | None = quantity(None, ge=1.0, doc="prior: the factor times/divided by this")
    source: str = quantity("", doc="why")


@dataclass(frozen=True, kw_only=True)
class Plastic(Table):
    """``[plastic]``: linear isotropic hardening, sigma_y(T, X, p) = sum_i X_i sigma_y,i(T) + sum_i X_i H_i(T) p."""

    source: str = quantity("", doc="where the data come from")
    hardening_memory: float = quantity(REQUIRED, ge=0.0, le=1.0, sourced=True,
                                       doc="share of the hardening a new phase inherits (Leblond's theta)")
    metastable_austenite_yield_factor: MetastableFactor | None = quantity(None, doc="factor on the cold austenite "
                                                                          "yield points")
    yield_Pa: Property = quantity(REQUIRED, unit="Pa", doc="yield stress per phase (> 0)")
    hardening_Pa: Property = quantity(REQUIRED, unit="Pa", doc="hardening modulus per phase (>= 0)")


@dataclass(frozen=True, kw_only=True)
class Trip(Table):
    """``[trip]``: transformation plasticity, eps_tp = K sigma phi(f)."""

    law: Literal["desalos", "leblond"] = quantity("desalos", doc="the saturation law phi(f)")
    source: str = quantity("", doc="where the law comes from")
    K_1_Pa: Property = quantity(REQUIRED, unit="1/Pa", doc="Greenwood-Johnson coefficient per phase (austenite 0)")


FreeStrain = SpecificVolumeStrain | ExpansionStrain
"""``[free_strain]``, by its ``form``."""


@dataclass(frozen=True, kw_only=True)
class SteelMechanics(Table):
    """A steel's mechanics file ``materials/NAME.mechanics.toml``."""

    reference: Reference = quantity(REQUIRED, doc="the stress-free state")
    elastic: Elastic = quantity(REQUIRED, doc="elastic constants")
    free_strain: FreeStrain = quantity(REQUIRED, doc="thermal and structural strain")
    annealed: Annealed = quantity(REQUIRED, doc="the \"before\" state")
    plastic: Plastic | None = quantity(None, doc="plasticity (needed with mechanics.plasticity)")
    trip: Trip | None = quantity(None, doc="transformation plasticity (needed with mechanics.trip)")

    def check(self) -> None:
        if self.annealed.free_strain is None:
            require(isinstance(self.free_strain, SpecificVolumeStrain), "annealed.free_strain", None,
                    "is required for the expansion form")
            require(self.annealed.phase is not None, "annealed.phase", None,
                    f"must be one of {PHASES} (or give free_strain)")
            require(self.annealed.T_C is not None, "annealed.T_C", None, "is required with annealed.phase")
        alpha = self.free_strain.alpha_1_K
        require(not (alpha.phase_dependent and any(alpha.for_phase(p).phase_dependent for p in PHASES)),
                "free_strain.alpha_1_K", "nested per_phase", "per-phase entries must be constants, tables or "
                                                             "polynomials")
