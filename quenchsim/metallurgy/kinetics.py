"""Transformation kinetics of one steel at one austenitising temperature, built from a material file.

The ``[austenitisation]``, ``[kinetics]`` and ``[hardness]`` tables of ``materials/NAME.toml`` are
parsed here into a :class:`Kinetics` (see the material files for the schema, which is documented in
:func:`load_kinetics`). Diffusional reactions (pearlite, bainite) are isothermal JMAK laws
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
from typing import Any

import numpy as np

from quenchsim.errors import InputError
from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy.laws import (c_curve_ln_inverse_tau, jmak_exponent, li_rate, li_sigmoid_integral,
                                       linear_formula)

ELEMENTS = ("C", "Si", "Mn", "Ni", "Cr", "Mo", "V", "Cu", "Co", "Al", "W", "P", "S")
"""Alloying elements a composition (wt %) may list."""

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


def _number(table: Mapping[str, Any], key: str, where: str, positive: bool = False) -> float:
    if key not in table:
        raise InputError(f"{where}.{key}", None, "is required")
    value = table[key]
    if isinstance(value, Mapping):
        if "value" not in value:
            raise InputError(f"{where}.{key}", dict(value), "needs a 'value' (and a 'source')")
        value = value["value"]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value):
        raise InputError(f"{where}.{key}", value, "must be a finite number")
    if positive and value <= 0:
        raise InputError(f"{where}.{key}", value, "must be > 0")
    return float(value)


def _source(table: Mapping[str, Any], where: str) -> str:
    src = table.get("source")
    if not isinstance(src, str) or not src.strip():
        raise InputError(f"{where}.source", src, "every data table needs a non-empty 'source'")
    return src


def _formula(table: Mapping[str, Any], key: str, where: str) -> dict[str, float]:
    spec = table.get(key)
    if not isinstance(spec, Mapping) or not spec:
        raise InputError(f"{where}.{key}", spec, "must be a table {const = a0, C = a_C, Mn = a_Mn, sqrt_Mo = ...}")
    out = {}
    for name, value in spec.items():
        base = name[5:] if name.startswith("sqrt_") else name
        if name != "const" and base not in ELEMENTS:
            raise InputError(f"{where}.{key}.{name}", value, f"term must be 'const', an element of {ELEMENTS} or sqrt_<element>")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"{where}.{key}.{name}", value, "must be a number")
        out[name] = float(value)
    return out


def _fraction_pair(table: Mapping[str, Any], where: str) -> tuple[float, float]:
    Xs = _number(table, "X_start", where)
    Xf = _number(table, "X_finish", where)
    if not 0.0 < Xs < Xf < 1.0:
        raise InputError(f"{where}.X_finish", Xf, f"need 0 < X_start ({Xs}) < X_finish < 1")
    return Xs, Xf


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


def _composition(material: Mapping[str, Any], name: str) -> dict[str, float]:
    comp = material.get("composition")
    if not isinstance(comp, Mapping):
        raise InputError(f"{name}.composition", comp, "the material needs a [composition] table (wt %)")
    _source(comp, f"{name}.composition")
    out = {}
    for el, value in comp.items():
        if el == "source":
            continue
        if el not in ELEMENTS:
            raise InputError(f"{name}.composition.{el}", value, f"element must be one of {ELEMENTS}")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0.0 <= value < 30.0:
            raise InputError(f"{name}.composition.{el}", value, "must be a number in wt % (0 <= w < 30)")
        out[el] = float(value)
    if "C" not in out:
        raise InputError(f"{name}.composition.C", None, "is required")
    return out


def _austenitisation_table(material: Mapping[str, Any], name: str) -> tuple[Mapping[str, Any], np.ndarray]:
    where = f"{name}.austenitisation"
    aus = material.get("austenitisation")
    if not isinstance(aus, Mapping):
        raise InputError(where, aus, "the material needs an [austenitisation] table")
    _source(aus, where)
    T = np.asarray(aus.get("T_aust_C", []), dtype=float)
    if T.ndim != 1 or T.size < 1 or np.any(np.diff(T) <= 0):
        raise InputError(f"{where}.T_aust_C", aus.get("T_aust_C"), "must be a non-empty list of strictly increasing temperatures")
    return aus, T


def check_austenitising_temperature(material: Mapping[str, Any], T_aust_C: float, field: str = "T_aust_C") -> None:
    """Raise :class:`InputError` (naming ``field``) unless ``T_aust_C`` lies within the range the steel's
    ``[austenitisation]`` table covers: its dissolved carbon, Ms and kinetics are known there only (a case checks this
    at load, before any file is written)."""
    name = str(material.get("name", "material"))
    _require_tabulated(_austenitisation_table(material, name)[1], T_aust_C, name, field)


def _require_tabulated(T: np.ndarray, T_aust_C: float, name: str, field: str) -> None:
    if not T[0] <= T_aust_C <= T[-1]:
        raise InputError(field, T_aust_C, f"outside the austenitising range tabulated for {name}: {T[0]:g}-{T[-1]:g} C "
                                          "(its [austenitisation] table)")


def _dissolved(material: Mapping[str, Any], name: str, bulk: Mapping[str, float], T_aust_C: float) -> tuple[dict[str, float], float]:
    where = f"{name}.austenitisation"
    aus, T = _austenitisation_table(material, name)
    _require_tabulated(T, T_aust_C, name, "T_aust_C")
    table = aus.get("dissolved_wt")
    if not isinstance(table, Mapping) or "C" not in table:
        raise InputError(f"{where}.dissolved_wt", table, "must be a table element -> list (at least C) along T_aust_C")
    dissolved = dict(bulk)
    for el, values in table.items():
        v = np.asarray(values, dtype=float)
        if el not in bulk:
            raise InputError(f"{where}.dissolved_wt.{el}", values, "element is not in [composition]")
        if v.shape != T.shape or np.any(v < 0) or np.any(v > bulk[el] + 1e-12):
            raise InputError(f"{where}.dissolved_wt.{el}", values,
                             f"must be {T.size} values between 0 and the bulk content {bulk[el]}")
        dissolved[el] = float(np.interp(T_aust_C, T, v))
    if "grain_size_ASTM" not in aus:
        return dissolved, float("nan")
    grain = _number(aus, "grain_size_ASTM", where)
    if not 0.0 <= grain <= 15.0:
        raise InputError(f"{where}.grain_size_ASTM", grain, "ASTM grain size number must be within 0-15")
    return dissolved, grain


def _upper_temperature(table: Mapping[str, Any], where: str, composition: Mapping[str, float]) -> float:
    if "T_upper_formula" in table:
        return linear_formula(_formula(table, "T_upper_formula", where), composition)
    return _number(table, "T_upper_C", where)


def _reaction(table: Any, where: str, composition: Mapping[str, float], grain: float) -> Reaction:
    if not isinstance(table, Mapping):
        raise InputError(where, table, "must be a table with a 'model'")
    source = _source(table, where)
    model = table.get("model")
    T_upper = _upper_temperature(table, where, composition)
    if model == "li1998":
        if not np.isfinite(grain):
            raise InputError(where.rsplit(".kinetics", 1)[0] + ".austenitisation.grain_size_ASTM", None,
                             "is required by the li1998 kinetics model")
        Xs, Xf = _fraction_pair(table, where)
        c = _number(table, "sigmoid_exponent", where, positive=True)
        S_s, S_f = li_sigmoid_integral(Xs, c), li_sigmoid_integral(Xf, c)
        n = jmak_exponent(Xs, Xf, S_f / S_s)
        params = {
            "ln_F": linear_formula(_formula(table, "ln_F", where), composition),
            "beta_grain": _number(table, "beta_grain", where),
            "grain_ASTM": grain,
            "n_undercooling": _number(table, "n_undercooling", where, positive=True),
            "Q_cal_mol": _number(table, "Q_cal_mol", where, positive=True),
            "n": n,
            # tau_JMAK / tau_1: the JMAK law passes through Li's t(X_start) = tau_1 S(X_start)
            "tau_ratio": S_s / (-np.log1p(-Xs)) ** (1.0 / n),
        }
    elif model == "jmak_polynomial":
        params = {"ln_b": _poly(table, "ln_b_poly_T_C", where), "n": _poly(table, "n_poly_T_C", where),
                  "time_unit_s": _number(table, "time_unit_s", where, positive=True)}
        n_min = np.polynomial.polynomial.polyval(np.linspace(0.0, T_upper, 200), params["n"]).min()
        if not n_min > 0.0:
            raise InputError(f"{where}.n_poly_T_C", table["n_poly_T_C"], f"n(T) must stay > 0 from 0 C to {T_upper:.0f} C")
    elif model == "c_curve":
        params = {"T_ref_C": _number(table, "T_ref_C", where)}
        nodes = any(key in table for key in N_NODES)
        for key in C_CURVE_PARAMETERS:
            if nodes and key in ("n", "n_per_K"):
                if key in table:
                    raise InputError(f"{where}.{key}", table[key], "give n (and n_per_K) or n_nodes_T_C with n_nodes, not both")
                continue
            params[key] = 0.0 if key == "n_per_K" and key not in table else _number(table, key, where,
                                                                                   positive=key != "n_per_K")
        if not params["T_ref_C"] < T_upper:
            raise InputError(f"{where}.T_ref_C", params["T_ref_C"], f"must lie below T_upper = {T_upper:g} C")
        if nodes:
            params.update(n_exponent_nodes(table.get("n_nodes_T_C"), table.get("n_nodes"), where))
        else:
            n_ends = params["n"] + params["n_per_K"] * (np.array([0.0, T_upper]) - params["T_ref_C"])
            if not np.all(n_ends > 0.0):
                raise InputError(f"{where}.n_per_K", params["n_per_K"], f"n(T) must stay > 0 from 0 C to {T_upper:.0f} C")
    elif model == "ttt_table":
        Xs, Xf = _fraction_pair(table, where)
        T = np.asarray(table.get("T_C", []), dtype=float)
        ts = np.asarray(table.get("t_start_s", []), dtype=float)
        tf = np.asarray(table.get("t_finish_s", []), dtype=float)
        if T.ndim != 1 or T.size < 2 or np.any(np.diff(T) <= 0):
            raise InputError(f"{where}.T_C", table.get("T_C"), "must list at least 2 strictly increasing temperatures")
        if ts.shape != T.shape or np.any(ts <= 0):
            raise InputError(f"{where}.t_start_s", table.get("t_start_s"), f"must be {T.size} positive times")
        if tf.shape != T.shape or np.any(tf <= ts):
            raise InputError(f"{where}.t_finish_s", table.get("t_finish_s"), f"must be {T.size} times later than t_start_s")
        n = np.log(np.log1p(-Xf) / np.log1p(-Xs)) / np.log(tf / ts)
        params = {"T_C": T, "n": n, "ln_tau": np.log(ts) - np.log(-np.log1p(-Xs)) / n}
    else:
        raise InputError(f"{where}.model", model, "must be one of li1998, jmak_polynomial, ttt_table, c_curve")
    if model == "ttt_table":  # no reaction above the table either
        T_upper = min(T_upper, float(params["T_C"][-1]))
    return Reaction(model=model, source=source, T_upper_C=T_upper, params=params)


def n_exponent_nodes(T_C: Any, n: Any, where: str) -> dict[str, np.ndarray]:
    """Checked node temperatures and Avrami exponents of a piecewise-linear n(T) (values or {value, source} tables)."""
    T_C, n = (v.get("value") if isinstance(v, Mapping) else v for v in (T_C, n))
    try:
        T = np.asarray(T_C, dtype=float)
        values = np.asarray(n, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{where}.n_nodes", n, "n_nodes_T_C and n_nodes must be lists of numbers") from None
    if T.ndim != 1 or T.size < 2 or not np.all(np.isfinite(T)) or np.any(np.diff(T) <= 0):
        raise InputError(f"{where}.n_nodes_T_C", T_C, "must list at least 2 strictly increasing temperatures")
    if values.shape != T.shape or not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise InputError(f"{where}.n_nodes", n, f"must be {T.size} positive Avrami exponents (one per n_nodes_T_C)")
    return {"n_nodes_T_C": T, "n_nodes": values}


def _poly(table: Mapping[str, Any], key: str, where: str) -> np.ndarray:
    c = np.asarray(table.get(key, []), dtype=float)
    if c.ndim != 1 or c.size < 1 or not np.all(np.isfinite(c)):
        raise InputError(f"{where}.{key}", table.get(key), "must be a list of polynomial coefficients a0, a1, ... in T (C)")
    return c


def _hardness(material: Mapping[str, Any], name: str, bulk: Mapping[str, float], dissolved: Mapping[str, float]) -> dict[str, PhaseHardness]:
    where = f"{name}.hardness"
    table = material.get("hardness")
    if not isinstance(table, Mapping):
        raise InputError(where, table, "the material needs a [hardness] table")
    out = {}
    for phase in PHASES:
        sub = table.get(phase)
        w = f"{where}.{phase}"
        if not isinstance(sub, Mapping):
            raise InputError(w, sub, "needs a table: {HV = ...} or Maynier {composition, base, rate}")
        source = _source(sub, w)
        max_HV = _number(sub, "max_HV", w, positive=True) if "max_HV" in sub else np.inf
        if "HV" in sub:
            out[phase] = PhaseHardness({}, {"const": _number(sub, "HV", w, positive=True)}, {}, max_HV, source)
            continue
        which = sub.get("composition")
        if which not in ("bulk", "dissolved"):
            raise InputError(f"{w}.composition", which, "must be 'bulk' or 'dissolved'")
        out[phase] = PhaseHardness(dict(bulk if which == "bulk" else dissolved), _formula(sub, "base", w),
                                   _formula(sub, "rate", w), max_HV, source)
    return out


def load_kinetics(material: dict[str, Any], T_aust_C: float) -> Kinetics:
    """Build the kinetics of ``material`` (a :func:`quenchsim.materials.load_material` table) austenitised at T_aust_C.

    Schema (every table carries ``source``):

    * ``[austenitisation]``: ``T_aust_C`` list, ``dissolved_wt = {C = [...], Cr = [...]}`` (wt % in
      austenite along T_aust_C; unlisted elements stay at bulk), ``grain_size_ASTM`` (needed by li1998).
    * ``[kinetics] composition = "dissolved" | "bulk"``: which composition feeds the formulas.
    * ``[kinetics.pearlite]``, ``[kinetics.bainite]`` (each optional): ``model`` =
      ``li1998`` {ln_F, beta_grain, n_undercooling, Q_cal_mol, sigmoid_exponent, X_start, X_finish},
      ``jmak_polynomial`` {ln_b_poly_T_C, n_poly_T_C, time_unit_s} or
      ``ttt_table`` {T_C, t_start_s, t_finish_s, X_start, X_finish} or
      ``c_curve`` {T_ref_C, tau_ref_s, undercooling_exponent, Q_J_mol, n, optional n_per_K -- or n_nodes_T_C and
      n_nodes in place of n, n_per_K}; plus the upper temperature
      ``T_upper_C`` (a number) or ``T_upper_formula`` (a linear composition formula).
    * ``[kinetics.martensite]``: ``Ms_C`` or ``Ms_formula``, ``alpha_per_K`` (Koistinen-Marburger).
    * ``[hardness.<phase>]`` for every phase: ``HV`` or Maynier ``composition/base/rate``; optional ``max_HV``.

    Errors name the offending field (``SUJ3.kinetics.martensite.alpha_per_K = ...: must be > 0``).
    """
    name = str(material.get("name", "material"))
    if isinstance(T_aust_C, bool) or not isinstance(T_aust_C, (int, float)) or not np.isfinite(T_aust_C):
        raise InputError("T_aust_C", T_aust_C, "must be a finite temperature in C")
    bulk = _composition(material, name)
    dissolved, grain = _dissolved(material, name, bulk, float(T_aust_C))
    kin = material.get("kinetics")
    if not isinstance(kin, Mapping):
        raise InputError(f"{name}.kinetics", kin, "the material needs a [kinetics] table")
    _source(kin, f"{name}.kinetics")
    which = kin.get("composition")
    if which not in ("bulk", "dissolved"):
        raise InputError(f"{name}.kinetics.composition", which, "must be 'bulk' or 'dissolved'")
    comp = bulk if which == "bulk" else dissolved
    for key in kin:
        if key not in (*DIFFUSIONAL, "martensite", "composition", "source", "fit"):
            raise InputError(f"{name}.kinetics.{key}", kin[key],
                             f"unknown entry; allowed: {DIFFUSIONAL}, martensite, composition, source, fit (provenance)")
    reactions = {p: _reaction(kin[p], f"{name}.kinetics.{p}", comp, grain) for p in DIFFUSIONAL if p in kin}
    mart = kin.get("martensite")
    where = f"{name}.kinetics.martensite"
    if not isinstance(mart, Mapping):
        raise InputError(where, mart, "needs a table with Ms_C or Ms_formula and alpha_per_K")
    _source(mart, where)
    Ms = linear_formula(_formula(mart, "Ms_formula", where), comp) if "Ms_formula" in mart else _number(mart, "Ms_C", where)
    alpha = _number(mart, "alpha_per_K", where, positive=True)
    if not -273.0 < Ms < T_aust_C:
        raise InputError(f"{where}.Ms_C", round(Ms, 1), f"Ms must lie between -273 C and T_aust = {T_aust_C} C")
    return Kinetics(material=name, T_aust_C=float(T_aust_C), composition=bulk, dissolved=dissolved, grain_size_ASTM=grain,
                    reactions=reactions, Ms_C=float(Ms), alpha_per_K=alpha,
                    hardness=_hardness(material, name, bulk, dissolved))
