"""Transformation kinetics of one steel at one austenitising temperature, built from a steel file.

The ``[austenitisation]``, ``[kinetics]`` and ``[hardness]`` tables of ``materials/NAME.toml`` (declared and checked
in :mod:`quenchsim.inputs.steel`) become a :class:`Kinetics` here (:func:`load_kinetics`). Diffusional reactions (pearlite, bainite) are isothermal JMAK laws
X = 1 - exp(-(t/tau(T))^n(T)) from one of three sources:

* ``li1998``: the composition model of Li et al. (1998, Met. Trans. B 29B 661), t(X, T) = tau_1(T) S(X),
  fed with the composition dissolved in austenite; the JMAK law is fitted through Li's times to
  X_start and X_finish (the usual 1 % / 99 % TTT start and finish lines);
* ``jmak_polynomial``: ln b(T) and n(T) polynomials, X = 1 - exp(-b t^n) (e.g. Furlan et al. 2025);
* ``ttt_table``: tabulated start/finish times of a TTT diagram, n(T) and tau(T) through both points;
* ``c_curve``: the C-curve law 1/tau = (1/tau_ref) [(T_u - T)/(T_u - T_ref)]^m exp[-(Q/R)(1/T - 1/T_ref)] with
  n(T) = n + n_per_K (T - T_ref), or n(T) piecewise linear through values ``n_nodes`` at temperatures
  ``n_nodes_T_C`` (constant beyond the end nodes: the ``ttt_table`` interpolation of n, on a few nodes), whose
  parameters ``quenchsim material fit`` finds from CCT / TTT / Jominy data (:mod:`quenchsim.fitting.kinetics`);
  the fit's provenance sits in the sub-table ``fit``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from quenchsim.errors import InputError
from quenchsim.inputs.steel import (CCurveReaction, HardnessTable, JmakPolynomialReaction, LiReaction,
                                    ReactionTable)
from quenchsim.inputs.steel import PhaseHardness as PhaseHardnessTable
from quenchsim.inputs.steel import Reaction as ReactionSpec
from quenchsim.inputs.steel import Steel
from quenchsim.materials import as_steel
from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy.laws import (c_curve_ln_inverse_tau, jmak_exponent, li_rate, li_sigmoid_integral,
                                       linear_formula)

DIFFUSIONAL = ("pearlite", "bainite")
"""Products of the diffusional (JMAK) reactions, in PHASES order."""

C_CURVE_PARAMETERS = ("tau_ref_s", "undercooling_exponent", "Q_J_mol", "n", "n_per_K")
"""Parameters of the ``c_curve`` model a fit may free (T_upper_C and T_ref_C are always given)."""
N_NODES = ("n_nodes_T_C", "n_nodes")
"""The ``c_curve`` alternative to n, n_per_K: the Avrami exponent at node temperatures, linear in between (a fit may
free ``n_nodes``; the node temperatures are chosen, like T_ref_C)."""

DEFAULT_SUBSTEP_K = 5.0
"""Largest temperature change (K) of one internal sub-step of :func:`quenchsim.metallurgy.advance`.

Each sub-step integrates 1/tau(T(t)) with 2-point Gauss-Legendre quadrature (T linear in time), so
the additivity error is O(substep^4) for a single reaction; 5 K keeps it far below 1e-4 in fraction
for the steels here (see tests/test_metallurgy_kinetics.py and reports/cct.md)."""


@dataclass(frozen=True)
class Reaction:
    """One diffusional reaction as an isothermal JMAK law with temperature-dependent tau and n.

    ``inverse_tau(T)`` is 1/tau in 1/s (0 where the reaction cannot run), ``exponent(T)`` is n.
    """

    model: str
    source: str
    T_upper_C: float
    params: Mapping[str, Any] = field(default_factory=dict)

    def inverse_tau(self, T_C: np.ndarray) -> np.ndarray:
        T = np.asarray(T_C, dtype=float)
        p = self.params
        if self.model == "li1998":
            return li_rate(T, self.T_upper_C, p["ln_F"], p["beta_grain"], p["grain_ASTM"], p["n_undercooling"],
                           p["Q_cal_mol"]) / p["tau_ratio"]
        if self.model == "c_curve":
            return np.exp(c_curve_ln_inverse_tau(T, self.T_upper_C, p["T_ref_C"], p["tau_ref_s"],
                                                 p["undercooling_exponent"], p["Q_J_mol"]))
        if self.model == "jmak_polynomial":
            n = self.exponent(T)
            ln_b = np.polynomial.polynomial.polyval(T, p["ln_b"])
            return np.where(T < self.T_upper_C, np.exp(ln_b / n) / p["time_unit_s"], 0.0)
        inside = (T >= p["T_C"][0]) & (T <= p["T_C"][-1]) & (T < self.T_upper_C)
        return np.where(inside, np.exp(-np.interp(T, p["T_C"], p["ln_tau"])), 0.0)

    def exponent(self, T_C: np.ndarray) -> np.ndarray:
        T = np.asarray(T_C, dtype=float)
        p = self.params
        if self.model == "li1998":
            return np.asarray(p["n"])  # constant (isokinetic): a scalar broadcasts
        if self.model == "c_curve":
            if "n_nodes" in p:
                return np.interp(T, p["n_nodes_T_C"], p["n_nodes"])
            return np.asarray(p["n"]) if p["n_per_K"] == 0.0 else p["n"] + p["n_per_K"] * (T - p["T_ref_C"])
        if self.model == "jmak_polynomial":
            return np.polynomial.polynomial.polyval(T, p["n"])
        return np.interp(T, p["T_C"], p["n"])

    def isothermal_time_s(self, X: float, T_C: np.ndarray) -> np.ndarray:
        """Isothermal time to reach a fraction X of the reaction: tau (-ln(1 - X))^{1/n} (inf where it cannot run)."""
        with np.errstate(divide="ignore"):
            return (-np.log1p(-X)) ** (1.0 / self.exponent(T_C)) / self.inverse_tau(T_C)


@dataclass(frozen=True)
class PhaseHardness:
    """Hardness of one phase: Maynier form A(w) + B(w) log10(V_r) or a constant, optionally capped."""

    composition: Mapping[str, float]
    base: Mapping[str, float]
    rate: Mapping[str, float]
    max_HV: float
    source: str


@dataclass(frozen=True)
class Kinetics:
    """Everything :func:`quenchsim.metallurgy.advance` and :func:`hardness_HV` need for one steel and T_aust."""

    material: str
    T_aust_C: float
    composition: Mapping[str, float]
    dissolved: Mapping[str, float]
    grain_size_ASTM: float
    reactions: Mapping[str, Reaction]
    Ms_C: float
    alpha_per_K: float
    hardness: Mapping[str, PhaseHardness]
    substep_K: float = DEFAULT_SUBSTEP_K


def check_austenitising_temperature(material: Steel | Mapping[str, Any], T_aust_C: float, field: str = "T_aust_C"
                                    ) -> None:
    """Raise :class:`InputError` (naming ``field``) unless ``T_aust_C`` lies within the range the steel's
    ``[austenitisation]`` table covers: its dissolved carbon, Ms and kinetics are known there only (a case checks this
    at load, before any file is written)."""
    as_steel(material).check_austenitising_temperature(T_aust_C, field)


def _upper_temperature(table: ReactionTable, composition: Mapping[str, float]) -> float:
    if table.T_upper_formula is not None:
        return linear_formula(table.T_upper_formula, composition)
    return float(cast(float, table.T_upper_C))   # one of the two (ReactionTable.check)


def _n_exponent_end_check(n_ends: np.ndarray, key: str, value: Any, T_upper: float, where: str) -> None:
    if not np.all(n_ends > 0.0):
        raise InputError(f"{where}.{key}", value, f"n(T) must stay > 0 from 0 C to {T_upper:.0f} C")


def _reaction(table: ReactionSpec, where: str, composition: Mapping[str, float], grain: float) -> Reaction:
    """The JMAK law of a declared reaction table, its temperature-dependent checks here (they need the composition
    the formulas take)."""
    T_upper = _upper_temperature(table, composition)
    params: dict[str, Any]
    if isinstance(table, LiReaction):
        if not np.isfinite(grain):
            raise InputError(where.rsplit(".kinetics", 1)[0] + ".austenitisation.grain_size_ASTM", None,
                             "is required by the li1998 kinetics model")
        Xs, Xf, c = table.X_start, table.X_finish, table.sigmoid_exponent
        S_s, S_f = li_sigmoid_integral(Xs, c), li_sigmoid_integral(Xf, c)
        n = jmak_exponent(Xs, Xf, S_f / S_s)
        params = {
            "ln_F": linear_formula(table.ln_F, composition),
            "beta_grain": table.beta_grain,
            "grain_ASTM": grain,
            "n_undercooling": table.n_undercooling,
            "Q_cal_mol": table.Q_cal_mol,
            "n": n,
            # tau_JMAK / tau_1: the JMAK law passes through Li's t(X_start) = tau_1 S(X_start)
            "tau_ratio": S_s / (-np.log1p(-Xs)) ** (1.0 / n),
        }
    elif isinstance(table, JmakPolynomialReaction):
        params = {"ln_b": np.asarray(table.ln_b_poly_T_C, float), "n": np.asarray(table.n_poly_T_C, float),
                  "time_unit_s": table.time_unit_s}
        n_min = np.polynomial.polynomial.polyval(np.linspace(0.0, T_upper, 200), params["n"]).min()
        if not n_min > 0.0:
            raise InputError(f"{where}.n_poly_T_C", list(table.n_poly_T_C),
                             f"n(T) must stay > 0 from 0 C to {T_upper:.0f} C")
    elif isinstance(table, CCurveReaction):
        params = {"T_ref_C": table.T_ref_C, "tau_ref_s": table.tau_ref_s,
                  "undercooling_exponent": table.undercooling_exponent, "Q_J_mol": table.Q_J_mol}
        if not table.T_ref_C < T_upper:
            raise InputError(f"{where}.T_ref_C", table.T_ref_C, f"must lie below T_upper = {T_upper:g} C")
        if table.n_nodes is not None and table.n_nodes_T_C is not None:
            params.update(n_nodes_T_C=np.asarray(table.n_nodes_T_C, float), n_nodes=np.asarray(table.n_nodes, float))
        else:
            params.update(n=cast(float, table.n), n_per_K=table.n_per_K or 0.0)   # n given (CCurveReaction.check)
            n_ends = params["n"] + params["n_per_K"] * (np.array([0.0, T_upper]) - params["T_ref_C"])
            _n_exponent_end_check(n_ends, "n_per_K", params["n_per_K"], T_upper, where)
    else:
        Xs, Xf = table.X_start, table.X_finish
        T, ts, tf = (np.asarray(v, float) for v in (table.T_C, table.t_start_s, table.t_finish_s))
        n = np.log(np.log1p(-Xf) / np.log1p(-Xs)) / np.log(tf / ts)
        params = {"T_C": T, "n": n, "ln_tau": np.log(ts) - np.log(-np.log1p(-Xs)) / n}
        T_upper = min(T_upper, float(T[-1]))   # no reaction above the table either
    return Reaction(model=table.model, source=table.source, T_upper_C=T_upper, params=params)


def _hardness(table: HardnessTable, bulk: Mapping[str, float], dissolved: Mapping[str, float]
              ) -> dict[str, PhaseHardness]:
    out = {}
    for phase in PHASES:
        sub: PhaseHardnessTable = getattr(table, phase)
        max_HV = sub.max_HV if sub.max_HV is not None else np.inf
        if sub.HV is not None:
            out[phase] = PhaseHardness({}, {"const": sub.HV}, {}, max_HV, sub.source)
            continue
        out[phase] = PhaseHardness(dict(bulk if sub.composition == "bulk" else dissolved), dict(sub.base or {}),
                                   dict(sub.rate or {}), max_HV, sub.source)
    return out


def load_kinetics(material: Steel | Mapping[str, Any], T_aust_C: float) -> Kinetics:
    """The kinetics of a steel (:func:`quenchsim.materials.load_steel`, or a table in its file's form) austenitised
    at ``T_aust_C``: its ``[austenitisation]``, ``[kinetics]`` and ``[hardness]`` tables (declared in
    :mod:`quenchsim.inputs.steel`, which says what each key takes) with the composition dissolved at ``T_aust_C``.

    * ``[kinetics] composition = "dissolved" | "bulk"``: which composition feeds the formulas.
    * ``[kinetics.pearlite]``, ``[kinetics.bainite]`` (each optional): ``model`` = ``li1998``, ``jmak_polynomial``,
      ``ttt_table`` or ``c_curve``, with the upper temperature ``T_upper_C`` or ``T_upper_formula``.
    * ``[kinetics.martensite]``: ``Ms_C`` or ``Ms_formula``, ``alpha_per_K`` (Koistinen-Marburger).
    * ``[hardness.<phase>]`` for every phase: ``HV`` or Maynier ``composition/base/rate``; optional ``max_HV``.

    Errors name the offending key (``SUJ3.kinetics.martensite.Ms_C = ...``).
    """
    steel = as_steel(material)
    name = steel.name
    if isinstance(T_aust_C, bool) or not isinstance(T_aust_C, (int, float)) or not np.isfinite(T_aust_C):
        raise InputError("T_aust_C", T_aust_C, "must be a finite temperature in C")
    steel.check_austenitising_temperature(float(T_aust_C))
    composition, austenitisation, kin, hardness = steel.composition, steel.austenitisation, steel.kinetics, steel.hardness
    if composition is None or austenitisation is None or kin is None or hardness is None:
        steel.require_run_data(name)
        raise InputError(f"{name}.transformations", steel.transformations, "a steel whose austenite does not "
                         "transform has no kinetics")
    bulk = composition.wt
    dissolved = austenitisation.dissolved_at(float(T_aust_C), bulk)
    grain = austenitisation.grain_size_ASTM if austenitisation.grain_size_ASTM is not None else float("nan")
    comp = bulk if kin.composition == "bulk" else dissolved
    reactions = {p: _reaction(table, f"{name}.kinetics.{p}", comp, grain) for p, table in kin.reactions().items()}
    mart = kin.martensite
    Ms = linear_formula(mart.Ms_formula, comp) if mart.Ms_formula is not None else float(cast(float, mart.Ms_C))
    if not -273.0 < Ms < T_aust_C:
        raise InputError(f"{name}.kinetics.martensite.Ms_C", round(Ms, 1),
                         f"Ms must lie between -273 C and T_aust = {T_aust_C} C")
    return Kinetics(material=name, T_aust_C=float(T_aust_C), composition=bulk, dissolved=dissolved,
                    grain_size_ASTM=grain, reactions=reactions, Ms_C=float(Ms), alpha_per_K=mart.alpha_per_K,
                    hardness=_hardness(hardness, bulk, dissolved))
