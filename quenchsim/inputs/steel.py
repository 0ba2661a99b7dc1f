"""A steel file ``materials/NAME.toml`` (composition, thermal properties, latent heats, austenitisation, kinetics,
hardness) declared once; its mechanics file ``NAME.mechanics.toml`` is :mod:`quenchsim.inputs.steel_mechanics`.

Every number carries a ``source`` (a table's ``source``, or the entry's own ``{ value, source }``). A property takes
one of the forms of :mod:`quenchsim.materials.properties` (a number, a table against T, a polynomial in T, per
phase). The physics builds its models from these declarations without checking again: the kinetics
(:func:`quenchsim.metallurgy.load_kinetics`), the thermal properties (:func:`quenchsim.materials.thermal_properties`)
and the stress model (:func:`quenchsim.mechanics.load_mechanics`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Literal

import numpy as np

from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import REQUIRED, Table, from_table, quantity, resolved
from quenchsim.inputs.properties import ELEMENTS, FORMULA_HELP, Property, check_formula
from quenchsim.inputs.steel_mechanics import SteelMechanics
from quenchsim.inputs.tempering import TemperingData

DIFFUSIONAL = ("pearlite", "bainite")
"""Products of the diffusional (JMAK) reactions, in PHASES order."""


def _increasing(values: tuple[float, ...], minimum: int = 1) -> bool:
    return len(values) >= minimum and all(b > a for a, b in zip(values, values[1:]))


Formula = Mapping[str, float]
"""A linear composition formula ``{ const = a0, C = a_C, sqrt_Mo = b_Mo, ... }`` (wt %)."""


def _element(name: str) -> Any:
    """An optional element of a composition, in wt %."""
    return quantity(None, unit="wt%", ge=0.0, lt=30.0, doc=name)


@dataclass(frozen=True, kw_only=True)
class Composition(Table):
    """``[composition]``: the bulk composition (wt %)."""

    source: str = quantity(REQUIRED, doc="where the composition comes from")
    C: float = quantity(REQUIRED, unit="wt%", ge=0.0, lt=30.0, doc="carbon")
    Si: float | None = _element("silicon")
    Mn: float | None = _element("manganese")
    Ni: float | None = _element("nickel")
    Cr: float | None = _element("chromium")
    Mo: float | None = _element("molybdenum")
    V: float | None = _element("vanadium")
    Cu: float | None = _element("copper")
    Co: float | None = _element("cobalt")
    Al: float | None = _element("aluminium")
    W: float | None = _element("tungsten")
    P: float | None = _element("phosphorus")
    S: float | None = _element("sulphur")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "every data table needs a non-empty 'source'")

    @property
    def wt(self) -> dict[str, float]:
        """The elements given, in file order of :data:`ELEMENTS` (wt %)."""
        return {el: getattr(self, el) for el in ELEMENTS if getattr(self, el) is not None}


@dataclass(frozen=True, kw_only=True)
class Thermal(Table):
    """``[thermal]``: density, conductivity and specific heat, each a property (per phase or not)."""

    OTHER_KEYS = ("source",)

    density_kg_m3: Property = quantity(REQUIRED, unit="kg/m3", doc="density")
    conductivity_W_mK: Property = quantity(REQUIRED, unit="W/mK", doc="thermal conductivity")
    specific_heat_J_kgK: Property = quantity(REQUIRED, unit="J/kgK", doc="specific heat")


ZERO = Property("constant", constant=0.0)


@dataclass(frozen=True, kw_only=True)
class LatentHeat(Table):
    """``[latent_heat]``: heat released by austenite -> each product (default 0)."""

    OTHER_KEYS = ("source",)

    pearlite_J_kg: Property = quantity(ZERO, unit="J/kg", shown="0", doc="austenite -> pearlite")
    bainite_J_kg: Property = quantity(ZERO, unit="J/kg", shown="0", doc="austenite -> bainite")
    martensite_J_kg: Property = quantity(ZERO, unit="J/kg", shown="0", doc="austenite -> martensite")


@dataclass(frozen=True, kw_only=True)
class Austenitisation(Table):
    """``[austenitisation]``: the composition dissolved in austenite along the austenitising temperature (the rest
    stays as undissolved carbide), and the austenite grain size."""

    source: str = quantity(REQUIRED, doc="where the values come from")
    T_aust_C: tuple[float, ...] = quantity(REQUIRED, unit="C", doc="austenitising temperatures, strictly increasing; "
                                           "a case's austenitising temperature must lie within them",
                                           allowed="must be a non-empty list of strictly increasing temperatures")
    dissolved_wt: Mapping[str, tuple[float, ...]] = quantity(REQUIRED, unit="wt%", doc="element -> wt % in austenite "
                                                             "along T_aust_C (at least C; unlisted elements stay at "
                                                             "bulk)")
    grain_size_ASTM: float | None = quantity(None, ge=0.0, le=15.0, sourced=True, doc="ASTM grain size number "
                                             "(needed by the li1998 kinetics)")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "every data table needs a non-empty 'source'")
        require(_increasing(self.T_aust_C), "T_aust_C", list(self.T_aust_C),
                "must be a non-empty list of strictly increasing temperatures")
        require("C" in self.dissolved_wt, "dissolved_wt", dict(self.dissolved_wt),
                "must be a table element -> list (at least C) along T_aust_C")

    def covers(self, T_aust_C: float) -> bool:
        return self.T_aust_C[0] <= T_aust_C <= self.T_aust_C[-1]

    def dissolved_at(self, T_aust_C: float, bulk: Mapping[str, float]) -> dict[str, float]:
        """The composition dissolved in austenite at ``T_aust_C`` (wt %): each listed element interpolated along
        ``T_aust_C``, the others at their ``bulk`` content. The one place the dissolved carbon is computed (the
        kinetics, the hardness and the stress model's specific volumes use it)."""
        out = dict(bulk)
        for el, values in self.dissolved_wt.items():
            out[el] = float(np.interp(T_aust_C, self.T_aust_C, values))
        return out


# -- the reactions ---------------------------------------------------------------------------------------------------
@dataclass(frozen=True, kw_only=True)
class ReactionTable(Table):
    """Common keys of a diffusional reaction ``[kinetics.pearlite]`` / ``[kinetics.bainite]``: its source and its
    upper temperature (a number or a composition formula)."""

    source: str = quantity(REQUIRED, doc="where the law comes from")
    T_upper_C: float | None = quantity(None, unit="C", sourced=True, doc="the reaction runs below it (or "
                                       "T_upper_formula)")
    T_upper_formula: Formula | None = quantity(None, doc="the upper temperature as a linear composition formula")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "every data table needs a non-empty 'source'")
        require((self.T_upper_C is None) != (self.T_upper_formula is None), "T_upper_C", self.T_upper_C,
                "give T_upper_C or T_upper_formula, one of them")
        check_formula(self.T_upper_formula, "T_upper_formula")


def _fractions(X_start: float, X_finish: float) -> None:
    require(0.0 < X_start < X_finish < 1.0, "X_finish", X_finish, f"need 0 < X_start ({X_start}) < X_finish < 1")


@dataclass(frozen=True, kw_only=True)
class LiReaction(ReactionTable):
    """``model = "li1998"``: the composition model of Li et al. (1998, Met. Trans. B 29B 661), fed with the
    composition dissolved in austenite."""

    model: Literal["li1998"] = quantity(REQUIRED, doc="the law")
    ln_F: Formula = quantity(REQUIRED, doc="ln of the composition factor (a linear formula)")
    beta_grain: float = quantity(REQUIRED, sourced=True, doc="grain-size exponent")
    n_undercooling: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="undercooling exponent")
    Q_cal_mol: float = quantity(REQUIRED, unit="cal/mol", gt=0.0, sourced=True, doc="activation energy")
    sigmoid_exponent: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="exponent of Li's sigmoid")
    X_start: float = quantity(REQUIRED, sourced=True, doc="fraction of the start line (0 < X_start < X_finish)")
    X_finish: float = quantity(REQUIRED, sourced=True, doc="fraction of the finish line (< 1)")

    def check(self) -> None:
        super().check()
        check_formula(self.ln_F, "ln_F")
        _fractions(self.X_start, self.X_finish)


@dataclass(frozen=True, kw_only=True)
class JmakPolynomialReaction(ReactionTable):
    """``model = "jmak_polynomial"``: ln b(T) and n(T) polynomials, X = 1 - exp(-b t^n) (e.g. Furlan et al. 2025)."""

    model: Literal["jmak_polynomial"] = quantity(REQUIRED, doc="the law")
    ln_b_poly_T_C: tuple[float, ...] = quantity(REQUIRED, doc="ln b: coefficients a0, a1, ... in T (C)",
                                                allowed="must be a list of polynomial coefficients a0, a1, ... in T (C)")
    n_poly_T_C: tuple[float, ...] = quantity(REQUIRED, doc="n: coefficients a0, a1, ... in T (C)",
                                             allowed="must be a list of polynomial coefficients a0, a1, ... in T (C)")
    time_unit_s: float = quantity(REQUIRED, unit="s", gt=0.0, sourced=True, doc="the time unit of b")

    def check(self) -> None:
        super().check()
        for key in ("ln_b_poly_T_C", "n_poly_T_C"):
            require(len(getattr(self, key)) >= 1, key, [], "must be a list of polynomial coefficients a0, a1, ... "
                                                          "in T (C)")


@dataclass(frozen=True, kw_only=True)
class TttTableReaction(ReactionTable):
    """``model = "ttt_table"``: tabulated start/finish times of a TTT diagram, n(T) and tau(T) through both."""

    model: Literal["ttt_table"] = quantity(REQUIRED, doc="the law")
    T_C: tuple[float, ...] = quantity(REQUIRED, unit="C", doc="temperatures (>= 2, strictly increasing)")
    t_start_s: tuple[float, ...] = quantity(REQUIRED, unit="s", doc="start times, positive, one per T_C")
    t_finish_s: tuple[float, ...] = quantity(REQUIRED, unit="s", doc="finish times, later than t_start_s")
    X_start: float = quantity(REQUIRED, sourced=True, doc="fraction of the start line")
    X_finish: float = quantity(REQUIRED, sourced=True, doc="fraction of the finish line")

    def check(self) -> None:
        super().check()
        _fractions(self.X_start, self.X_finish)
        require(_increasing(self.T_C, 2), "T_C", list(self.T_C), "must list at least 2 strictly increasing temperatures")
        require(len(self.t_start_s) == len(self.T_C) and all(t > 0 for t in self.t_start_s), "t_start_s",
                list(self.t_start_s), f"must be {len(self.T_C)} positive times")
        require(len(self.t_finish_s) == len(self.T_C) and all(f > s for f, s in zip(self.t_finish_s, self.t_start_s)),
                "t_finish_s", list(self.t_finish_s), f"must be {len(self.T_C)} times later than t_start_s")


@dataclass(frozen=True, kw_only=True)
class CCurveReaction(ReactionTable):
    """``model = "c_curve"``: 1/tau = (1/tau_ref) [(T_u - T)/(T_u - T_ref)]^m exp[-(Q/R)(1/T - 1/T_ref)], with n(T) =
    n + n_per_K (T - T_ref) or piecewise linear through ``n_nodes`` at ``n_nodes_T_C``; the parameters ``quenchsim
    material fit`` finds (its provenance in ``[kinetics.fit]``)."""

    model: Literal["c_curve"] = quantity(REQUIRED, doc="the law")
    T_ref_C: float = quantity(REQUIRED, unit="C", sourced=True, doc="reference temperature (below T_upper)")
    tau_ref_s: float = quantity(REQUIRED, unit="s", gt=0.0, sourced=True, doc="time constant at T_ref")
    undercooling_exponent: float = quantity(REQUIRED, gt=0.0, sourced=True, doc="m")
    Q_J_mol: float = quantity(REQUIRED, unit="J/mol", gt=0.0, sourced=True, doc="activation energy")
    n: float | None = quantity(None, gt=0.0, sourced=True, doc="Avrami exponent at T_ref (or the nodes)")
    n_per_K: float | None = quantity(None, unit="1/K", sourced=True, doc="slope of n(T) (default 0)")
    n_nodes_T_C: tuple[float, ...] | None = quantity(None, unit="C", sourced=True, doc="node temperatures of n(T), "
                                                     "strictly increasing (instead of n, n_per_K)")
    n_nodes: tuple[float, ...] | None = quantity(None, sourced=True, doc="Avrami exponents at the nodes, positive")

    def check(self) -> None:
        super().check()
        nodes = self.n_nodes_T_C is not None or self.n_nodes is not None
        if nodes:
            for key in ("n", "n_per_K"):
                require(getattr(self, key) is None, key, getattr(self, key),
                        "give n (and n_per_K) or n_nodes_T_C with n_nodes, not both")
            n_exponent_nodes(self.n_nodes_T_C, self.n_nodes, "")
        else:
            require(self.n is not None, "n", None, "is required (or n_nodes_T_C with n_nodes)")
        if self.T_upper_C is not None:
            require(self.T_ref_C < self.T_upper_C, "T_ref_C", self.T_ref_C,
                    f"must lie below T_upper = {self.T_upper_C:g} C")


def n_exponent_nodes(T_C: Any, n: Any, where: str) -> dict[str, np.ndarray]:
    """Checked node temperatures and Avrami exponents of a piecewise-linear n(T) (values or {value, source} tables),
    as a c_curve reaction or a fit's start values give them."""
    T_C, n = (v.get("value") if isinstance(v, Mapping) else v for v in (T_C, n))
    where = f"{where}." if where else ""
    try:
        T = np.asarray(T_C, dtype=float)
        values = np.asarray(n, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{where}n_nodes", n, "n_nodes_T_C and n_nodes must be lists of numbers") from None
    if T.ndim != 1 or T.size < 2 or not np.all(np.isfinite(T)) or np.any(np.diff(T) <= 0):
        raise InputError(f"{where}n_nodes_T_C", T_C, "must list at least 2 strictly increasing temperatures")
    if values.shape != T.shape or not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise InputError(f"{where}n_nodes", n, f"must be {T.size} positive Avrami exponents (one per n_nodes_T_C)")
    return {"n_nodes_T_C": T, "n_nodes": values}


Reaction = LiReaction | JmakPolynomialReaction | TttTableReaction | CCurveReaction
"""A diffusional reaction's table, by its ``model``."""


@dataclass(frozen=True, kw_only=True)
class Martensite(Table):
    """``[kinetics.martensite]``: Koistinen-Marburger below Ms."""

    source: str = quantity(REQUIRED, doc="where Ms and alpha come from")
    Ms_C: float | None = quantity(None, unit="C", sourced=True, doc="martensite start (or Ms_formula)")
    Ms_formula: Formula | None = quantity(None, doc="Ms as a linear formula of the kinetics' composition")
    alpha_per_K: float = quantity(REQUIRED, unit="1/K", gt=0.0, sourced=True, doc="Koistinen-Marburger rate")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "every data table needs a non-empty 'source'")
        require((self.Ms_C is None) != (self.Ms_formula is None), "Ms_C", self.Ms_C, "give Ms_C or Ms_formula")
        check_formula(self.Ms_formula, "Ms_formula")


@dataclass(frozen=True, kw_only=True)
class KineticsTable(Table):
    """``[kinetics]``: which composition feeds the formulas, the diffusional reactions and the martensite."""

    source: str = quantity(REQUIRED, doc="where the kinetics come from")
    composition: Literal["bulk", "dissolved"] = quantity(REQUIRED, doc="the composition the formulas take")
    pearlite: Reaction | None = quantity(None, doc="austenite -> pearlite (optional)")
    bainite: Reaction | None = quantity(None, doc="austenite -> bainite (optional)")
    martensite: Martensite = quantity(REQUIRED, doc="austenite -> martensite")
    fit: Mapping[str, Any] | None = quantity(None, doc="the fit's provenance (quenchsim material fit)")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "every data table needs a non-empty 'source'")

    def reactions(self) -> dict[str, Reaction]:
        """The diffusional reactions given, in PHASES order."""
        return {p: r for p in DIFFUSIONAL if (r := getattr(self, p)) is not None}


@dataclass(frozen=True, kw_only=True)
class PhaseHardness(Table):
    """``[hardness.<phase>]``: a constant ``HV``, or the Maynier form A(w) + B(w) log10 V_r on the ``bulk`` or
    ``dissolved`` composition; optionally capped at ``max_HV``."""

    source: str = quantity(REQUIRED, doc="where the values come from")
    HV: float | None = quantity(None, unit="HV", gt=0.0, sourced=True, doc="a constant hardness")
    composition: Literal["bulk", "dissolved"] | None = quantity(None, doc="the composition of the Maynier form")
    base: Formula | None = quantity(None, doc="A(w), a linear formula")
    rate: Formula | None = quantity(None, doc="B(w), a linear formula (times log10 of the rate at 700 C in C/h)")
    max_HV: float | None = quantity(None, unit="HV", gt=0.0, sourced=True, doc="cap")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "every data table needs a non-empty 'source'")
        if self.HV is None:
            require(self.composition is not None, "composition", self.composition, "must be 'bulk' or 'dissolved'")
            for key in ("base", "rate"):
                require(getattr(self, key) is not None, key, None, FORMULA_HELP)
                check_formula(getattr(self, key), key)


@dataclass(frozen=True, kw_only=True)
class HardnessTable(Table):
    """``[hardness]``: HV = sum_i X_i HV_i (Li et al. 1998 eq. 26), one table per phase."""

    OTHER_KEYS = ("source",)

    austenite: PhaseHardness = quantity(REQUIRED, doc="retained austenite")
    pearlite: PhaseHardness = quantity(REQUIRED, doc="pearlite")
    bainite: PhaseHardness = quantity(REQUIRED, doc="bainite")
    martensite: PhaseHardness = quantity(REQUIRED, doc="martensite")


THERMAL_ONLY = ("a non-transforming material is thermal only: remove its mechanics table/file (the stress model "
                "needs the phases)")
TRANSFORMATIONS = ("austenite", "none")
"""``transformations`` of a steel file: ``"austenite"`` (default: the austenite decomposes on cooling; the file needs
[composition], [austenitisation], [kinetics] and [hardness]) or ``"none"`` (nothing transforms, e.g. an austenitic or
nickel alloy: only [thermal] is needed, the run is thermal only and reports no phases and no hardness)."""


@dataclass(frozen=True, kw_only=True)
class Steel(Table):
    """A steel file ``materials/NAME.toml`` with its mechanics (``NAME.mechanics.toml`` beside it, or a
    ``[mechanics]`` table) and its tempering data (the file its ``tempering`` key names) resolved."""

    name: str = quantity("", doc="the steel's name (default: the file stem)")
    description: str = quantity("", doc="one line")
    transformations: str = quantity("austenite", choices=TRANSFORMATIONS, doc="\"none\": nothing transforms "
                                    "(thermal only)")
    tempering: str | TemperingData | None = quantity(None, doc="the tempering data file, relative to this file or a "
                                                     "data folder (data/tempering_1C_Cr.toml); not found: none")
    composition: Composition | None = quantity(None, doc="bulk composition")
    thermal: Thermal | None = quantity(None, doc="thermal properties (required for a run)")
    latent_heat: LatentHeat = quantity(LatentHeat(), doc="latent heats")
    austenitisation: Austenitisation | None = quantity(None, doc="dissolved composition and grain size")
    kinetics: KineticsTable | None = quantity(None, doc="transformation kinetics")
    hardness: HardnessTable | None = quantity(None, doc="hardness of each phase")
    mechanics: SteelMechanics | None = quantity(None, doc="the stress model's data (usually NAME.mechanics.toml)")

    path: Path | None = resolved()
    """The steel file (None for a steel built from a table)."""
    table: Mapping[str, Any] = resolved(init=True)
    """The file's table as read (the mechanics and tempering data merged), for the calibration's scaled copies."""

    @classmethod
    def check_keys_given(cls, table: Mapping[str, Any]) -> None:
        require(table.get("transformations") != "none" or "mechanics" not in table, "transformations",
                table.get("transformations"), THERMAL_ONLY)

    def check(self) -> None:
        require(self.transforms or self.mechanics is None, "transformations", self.transformations, THERMAL_ONLY)
        if self.composition is None or self.austenitisation is None:
            return
        bulk = self.composition.wt
        aus = self.austenitisation
        for el, values in aus.dissolved_wt.items():
            require(el in bulk, f"austenitisation.dissolved_wt.{el}", list(values), "element is not in [composition]")
            require(len(values) == len(aus.T_aust_C) and all(0.0 <= v <= bulk[el] + 1e-12 for v in values),
                    f"austenitisation.dissolved_wt.{el}", list(values),
                    f"must be {len(aus.T_aust_C)} values between 0 and the bulk content {bulk[el]}")

    def require_run_data(self, where: str = "") -> None:
        """The tables a run of this steel needs: [thermal]; for a steel that transforms also [composition],
        [austenitisation], [kinetics] and [hardness] (errors name them under ``where``)."""
        needed = [("thermal", "a [thermal] table")]
        if self.transforms:
            needed += [("composition", "a [composition] table (wt %)"), ("austenitisation",
                       "an [austenitisation] table"), ("kinetics", "a [kinetics] table"), ("hardness", "a [hardness] table")]
        for key, what in needed:
            require(getattr(self, key) is not None, f"{where}.{key}" if where else key, None,
                    f"the material needs {what}")

    @property
    def transforms(self) -> bool:
        """Whether the austenite transforms on cooling."""
        return self.transformations != "none"

    def check_austenitising_temperature(self, T_aust_C: float, field: str = "T_aust_C") -> None:
        """Raise :class:`InputError` (naming ``field``) unless ``T_aust_C`` lies within the range the steel's
        ``[austenitisation]`` table covers: its dissolved carbon, Ms and kinetics are known there only."""
        aus = self.austenitisation
        if aus is not None and not aus.covers(T_aust_C):
            raise InputError(field, T_aust_C, f"outside the austenitising range tabulated for {self.name}: "
                             f"{aus.T_aust_C[0]:g}-{aus.T_aust_C[-1]:g} C (its [austenitisation] table)")


def steel_from_table(table: Mapping[str, Any], where: str = "", path: Path | None = None) -> Steel:
    """The steel of a table as read (:func:`quenchsim.materials.load_material`'s, its mechanics merged as
    ``"mechanics"``), keys named under ``where`` (the steel's name for a table built in code, ``""`` for a file's)."""
    steel = from_table(Steel, table, where, path=path, table=table)
    return steel if steel.name else replace(steel, name=path.stem if path is not None else where or "material")
