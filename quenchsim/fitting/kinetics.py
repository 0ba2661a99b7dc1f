"""Fit the JMAK + additivity kinetics of a steel to CCT, TTT and Jominy data (``quenchsim material fit``).

The model is the one the simulation runs: each diffusional reaction is a ``c_curve`` JMAK law
(:mod:`quenchsim.metallurgy.kinetics`), integrated along every cooling history by
:func:`quenchsim.metallurgy.advance` (Scheil additivity, competing reactions, Koistinen-Marburger
martensite). No separate approximation is used:

* a CCT curve is integrated with ``advance`` along the printed cooling law (linear or Newtonian); the
  start of a product is where it reaches 1 % of the volume, its finish where it reaches 99 % of the
  amount it ends with (the lines of :mod:`quenchsim.metallurgy.cct`); final fractions and the mixed
  hardness come from the same state;
* a TTT point is the isothermal time to 1 % / 99 % of the reaction, X = 1 - exp(-(t/tau)^n) -- what
  ``advance`` integrates exactly on an isothermal path (tests/test_fitting_kinetics.py checks it);
* a Jominy point is the hardness after ``advance`` along the bar's cooling history at that distance,
  computed once by the thermal solver (:mod:`quenchsim.fitting.jominy`).

Residuals are normalised by each point's stated uncertainty (temperature in K, time as a factor,
fraction, HV) and minimised with scipy's trust-region least squares over the free parameters
(tau_ref in log). The fit refuses parameters the data cannot constrain (no sensitivity, or a direction
of the normalised Jacobian with a singular value below 1e-6 of the largest) and names them.
"""

from __future__ import annotations

import dataclasses
import json
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

import numpy as np
import tomli_w
from scipy.optimize import least_squares

from quenchsim.errors import InputError, QuenchsimError
from quenchsim.fitting.diagram_data import CCTPoint, CoolingCurve, DiagramData, ReactionFitSpec
from quenchsim.materials import find_data_file, load_material
from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy import Kinetics, Reaction, advance, hardness_HV, initial_state, load_kinetics
from quenchsim.metallurgy.cct import FINISH_SHARE, MIN_FINISH_AMOUNT, START_FRACTION, crossing_time

X_START, X_FINISH = 0.01, 0.99
"""Fractions of the TTT start and finish lines (1 % and 99 %)."""
CCT_GRID_GROWTH = 1.1
"""Ratio of successive time steps on a CCT curve (advance sub-steps every 5 K within a step)."""
CONDITION_LIMIT = 1e-6
"""Smallest singular value of the column-normalised Jacobian, relative to the largest, of an identifiable fit."""
FIT_BEGIN = "# >>> kinetics fitted by `quenchsim material fit`: generated, re-run the fit instead of editing"
FIT_END = "# <<< end of fitted kinetics"
WARNING_COMMENT = "# WARNING (quenchsim material fit): "
"""The head of each comment line a fit's warnings put at the top of the written steel (a re-fit replaces them)."""


class FitError(QuenchsimError):
    """The data cannot constrain the requested fit (the message names the parameter)."""


@dataclass(frozen=True)
class Residual:
    """One compared quantity: data and model value, the normalised residual (model - data) / uncertainty."""

    where: str
    quantity: str
    data: float
    model: float
    unit: str
    uncertainty: str
    residual: float
    source: str
    kind: str


@dataclass(frozen=True)
class FitResult:
    data: DiagramData
    kinetics: Kinetics
    parameters: dict[str, dict[str, float | tuple[float, ...]]]
    std_errors: dict[str, dict[str, float | tuple[float, ...]]]
    residuals: list[Residual]
    cost: float


# -- the model along data ---------------------------------------------------------------------------

def c_curve_reaction(spec: ReactionFitSpec, values: Mapping[str, float | tuple[float, ...]], source: str = "fit") -> Reaction:
    """The ``c_curve`` Reaction of a fit spec with the given parameter values (n(T) nodes as arrays)."""
    params = {"T_ref_C": spec.T_ref_C, "n_per_K": 0.0,
              **{k: np.array(v) if isinstance(v, tuple) else float(v) for k, v in values.items() if k != "T_upper_C"}}
    return Reaction(model="c_curve", source=source, T_upper_C=float(cast(float, values["T_upper_C"])), params=params)


@dataclass(frozen=True)
class CurveResult:
    """Along each CCT curve: start/finish temperature of each diffusional product (NaN: none), final fractions, HV."""

    start_T_C: dict[str, np.ndarray]
    finish_T_C: dict[str, np.ndarray]
    fractions: dict[str, np.ndarray]
    hardness_HV: np.ndarray


def run_curves(kin: Kinetics, curves: Sequence[CoolingCurve], growth: float = CCT_GRID_GROWTH) -> CurveResult:
    """Integrate ``advance`` along every cooling curve at once (one geometric time grid) and read the CCT lines."""
    first = min(10.0 / c.rate_C_s if not c.newtonian else c.theta_s * 10.0 / (c.T_start_C - c.T_end_C) for c in curves)
    last = max(c.duration_s() for c in curves)
    t_first = 0.05 * first
    n = int(np.ceil(np.log(last / t_first) / np.log(growth))) + 1
    times = np.concatenate([[0.0], t_first * growth ** np.arange(n)])
    T = np.array([c.temperature_C(times) for c in curves]).T           # (steps, curves)
    state = initial_state((len(curves),), kin)
    hist = {p: [state.fractions[p]] for p in kin.reactions}
    for k in range(1, times.size):
        state = advance(state, kin, T[k - 1], T[k], times[k] - times[k - 1])
        for p in hist:
            hist[p].append(state.fractions[p])
    start, finish = {}, {}
    cols = range(len(curves))
    for p in kin.reactions:
        X = np.array(hist[p])
        final = X[-1]
        ts = crossing_time(times, X, np.full_like(final, START_FRACTION))
        tf = np.where(final > MIN_FINISH_AMOUNT, crossing_time(times, X, FINISH_SHARE * final), np.nan)
        start[p] = np.array([curves[i].temperature_C(ts[i]) if np.isfinite(ts[i]) else np.nan for i in cols])
        finish[p] = np.array([curves[i].temperature_C(tf[i]) if np.isfinite(tf[i]) else np.nan for i in cols])
    return CurveResult(start_T_C=start, finish_T_C=finish, fractions={p: state.fractions[p].copy() for p in PHASES},
                       hardness_HV=hardness_HV(state, kin))


def run_histories(kin: Kinetics, times_s: np.ndarray, T_C: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Final fractions and hardness after ``advance`` along tabulated histories T_C (steps, points)."""
    state = initial_state((T_C.shape[1],), kin)
    for k in range(1, times_s.size):
        state = advance(state, kin, T_C[k - 1], T_C[k], float(times_s[k] - times_s[k - 1]))
    return state.fractions, hardness_HV(state, kin)


# -- residuals --------------------------------------------------------------------------------------

def _cct_residuals(kin: Kinetics, points: Sequence[CCTPoint]) -> list[Residual]:
    if not points:
        return []
    res = run_curves(kin, [p.curve for p in points])
    out = []
    for i, p in enumerate(points):
        for line, table, model in (("start", p.start_C, res.start_T_C), ("finish", p.finish_C, res.finish_T_C)):
            for phase, T_data in table.items():
                if phase == "martensite":
                    T_model = kin.Ms_C
                else:
                    _require_modelled(kin, phase, f"{p.where}.{line}_C.{phase}")
                    T_model = float(model[phase][i])
                    if not np.isfinite(T_model):  # no such line on the model's curve: count it at the curve's end
                        T_model = p.curve.T_end_C
                out.append(Residual(p.where, f"{phase} {line} T", T_data, T_model, "C", f"{p.temperature_uncertainty_K:g} K",
                                    (T_model - T_data) / p.temperature_uncertainty_K, p.source, p.kind))
        for phase, X_data in p.fractions.items():
            if phase == "ferrite":
                _require_modelled(kin, phase, f"{p.where}.fractions.{phase}")
            X_model = float(res.fractions[phase][i])
            out.append(Residual(p.where, f"{phase} fraction", X_data, X_model, "-", f"{p.fraction_uncertainty:g}",
                                (X_model - X_data) / p.fraction_uncertainty, p.source, p.kind))
        if np.isfinite(p.hardness_HV):
            hv = float(res.hardness_HV[i])
            out.append(Residual(p.where, "hardness", p.hardness_HV, hv, "HV", f"{p.hardness_uncertainty_HV:g} HV",
                                (hv - p.hardness_HV) / p.hardness_uncertainty_HV, p.source, p.kind))
    return out


def _require_modelled(kin: Kinetics, phase: str, where: str) -> None:
    if phase not in kin.reactions:
        raise InputError(where, phase, f"the material {kin.material} has no {phase} reaction "
                                       f"(modelled: {', '.join(kin.reactions) or 'none'}); remove the point or add the reaction to [fit]")


def _ttt_residuals(kin: Kinetics, data: DiagramData) -> list[Residual]:
    out = []
    for p in data.ttt:
        _require_modelled(kin, p.phase, f"{p.where}.phase")
        reaction = kin.reactions[p.phase]
        ln_f = np.log(p.time_uncertainty_factor)
        for X, t_data, line in ((X_START, p.t_start_s, "start"), (X_FINISH, p.t_finish_s, "finish")):
            t_model = float(reaction.isothermal_time_s(X, np.array([p.T_C]))[0])
            r = (np.log(t_model) - np.log(t_data)) / ln_f if np.isfinite(t_model) else 50.0
            out.append(Residual(p.where, f"{p.phase} {line} time", t_data, t_model, "s",
                                f"x{p.time_uncertainty_factor:g}", r, p.source, p.kind))
    return out


def _jominy_residuals(kin: Kinetics, data: DiagramData, histories: tuple[np.ndarray, np.ndarray] | None) -> list[Residual]:
    if not data.jominy:
        return []
    if histories is None:
        raise InputError(f"{data.path.name}: jominy", len(data.jominy), "Jominy points need the bar's cooling histories")
    _, hv = run_histories(kin, *histories)
    return [Residual(p.where, "hardness", p.hardness_HV, float(hv[i]), "HV", f"{p.hardness_uncertainty_HV:g} HV",
                     (float(hv[i]) - p.hardness_HV) / p.hardness_uncertainty_HV, p.source, p.kind)
            for i, p in enumerate(data.jominy)]


def residuals(kin: Kinetics, data: DiagramData, jominy_histories: tuple[np.ndarray, np.ndarray] | None = None) -> list[Residual]:
    """Every data point of ``data`` against the model ``kin`` (normalised residuals)."""
    return _cct_residuals(kin, data.cct) + _ttt_residuals(kin, data) + _jominy_residuals(kin, data, jominy_histories)


# -- the fit ----------------------------------------------------------------------------------------

def jominy_histories(data: DiagramData, progress: bool = False) -> tuple[np.ndarray, np.ndarray] | None:
    """Cooling histories of the standard Jominy bar at the data's Jominy distances (None without Jominy data), computed
    once with the base material's thermal data and kinetics (latent heat included)."""
    if not data.jominy:
        return None
    from quenchsim.fitting.jominy import cooling_histories

    material = load_material(data.material, field=f"{data.path.name}: material")
    return cooling_histories(material, load_kinetics(material, data.T_aust_C),
                             np.array([p.distance_mm for p in data.jominy]), progress=progress)


def base_kinetics(data: DiagramData) -> Kinetics:
    """The data file's base material at its austenitising temperature, with the reactions the fit replaces dropped."""
    material = load_material(data.material, field=f"{data.path.name}: material")
    material = dict(material)
    material["kinetics"] = {k: v for k, v in material["kinetics"].items() if k not in data.fit}
    return load_kinetics(material, data.T_aust_C)


def _free_entries(data: DiagramData) -> list[tuple[str, str, int | None]]:
    """(reaction, parameter, node index or None) of every free number, in the order of the fit vector."""
    return [(r, p, k) for r, spec in data.fit.items() for p in spec.free for k in _node_indices(spec.values[p])]


def _node_indices(value: float | tuple[float, ...]) -> Sequence[int | None]:
    """The node index of every number of one parameter: 0, 1, ... for n(T) nodes, None for a single number."""
    return range(len(value)) if isinstance(value, tuple) else (None,)


def _label(r: str, p: str, k: int | None) -> str:
    return f"{r}.{p}" if k is None else f"{r}.{p}[{k}]"


def _unpack(data: DiagramData, x: np.ndarray) -> dict[str, dict[str, float | tuple[float, ...]]]:
    values = {r: dict(spec.values) for r, spec in data.fit.items()}
    for (r, name, k), xi in zip(_free_entries(data), x):
        if k is None:
            values[r][name] = float(np.exp(xi)) if name == "tau_ref_s" else float(xi)
        else:
            nodes = cast(tuple[float, ...], values[r][name])   # k is a node index: the value is a tuple of nodes
            values[r][name] = (*nodes[:k], float(xi), *nodes[k + 1:])
    return values


def _kinetics_with(base: Kinetics, data: DiagramData,
                   values: Mapping[str, Mapping[str, float | tuple[float, ...]]]) -> Kinetics:
    reactions = dict(base.reactions)
    for r, spec in data.fit.items():
        reactions[r] = c_curve_reaction(spec, values[r])
    ordered = {p: reactions[p] for p in PHASES if p in reactions}
    return dataclasses.replace(base, reactions=ordered)


_BOUNDS = {"T_upper_C": (100.0, 1000.0), "tau_ref_s": (-40.0, 40.0), "undercooling_exponent": (0.1, 12.0),
           "Q_J_mol": (0.0, 1.0e6), "n": (0.5, 4.0), "n_per_K": (-0.1, 0.1), "n_nodes": (1.0, 4.0)}
"""Bounds of the free parameters (tau_ref_s in ln s). n <= 4: the largest Avrami exponent of the theory (3-D growth
at a constant nucleation rate; Christian, The Theory of Transformations in Metals and Alloys, 2002, ch. 12); the
nodes of a piecewise n(T) >= 1: interface-controlled growth of pre-existing nuclei in one dimension, the smallest
exponent of interface-controlled growth (Christian, ch. 12; lower values belong to diffusion-controlled thickening).
The fitted SUJ2 nodes (1.8-3.5) lie off both bounds."""


def fit_kinetics(data: DiagramData, jominy_histories: tuple[np.ndarray, np.ndarray] | None = None) -> FitResult:
    """Least-squares fit of the free ``c_curve`` parameters of ``data.fit`` to every point of ``data``."""
    if not data.fit:
        raise InputError(f"{data.path.name}: fit", None, "name the reactions to fit in [fit.pearlite] / [fit.bainite]")
    base = base_kinetics(data)
    entries = _free_entries(data)
    names = [_label(*e) for e in entries]
    x0 = np.array([np.log(data.fit[r].values[p]) if p == "tau_ref_s" else
                   data.fit[r].values[p] if k is None else cast(tuple[float, ...], data.fit[r].values[p])[k]
                   for r, p, k in entries])
    lo = np.array([data.fit[r].T_ref_C + 1.0 if p == "T_upper_C" else _BOUNDS[p][0] for r, p, _ in entries])
    hi = np.array([_BOUNDS[p][1] for _, p, _ in entries])

    def vector(x: np.ndarray) -> np.ndarray:
        kin = _kinetics_with(base, data, _unpack(data, x))
        return np.array([r.residual for r in residuals(kin, data, jominy_histories)])

    n_res = vector(x0).size
    if names and n_res < len(names):
        raise FitError(f"{data.path.name}: {len(names)} free parameters ({', '.join(names)}) "
                       f"but only {n_res} data residuals: the data cannot constrain them; fix some in [fit]")
    x = x0
    std: dict[str, dict[str, Any]] = {r: {} for r in data.fit}   # a float, or a tuple for n(T) nodes
    if names:
        sol = least_squares(vector, np.clip(x0, lo, hi), bounds=(lo, hi), x_scale="jac", diff_step=1e-4,
                            xtol=1e-10, ftol=1e-10, gtol=1e-10)
        x = sol.x
        _check_identifiable(data, names, sol.jac)
        dof = max(n_res - len(names), 1)
        scale = max(2.0 * sol.cost / dof, 1.0) if n_res > len(names) else 1.0
        cov = np.linalg.pinv(sol.jac.T @ sol.jac) * scale
        for (r, p, k), s in zip(entries, np.sqrt(np.diag(cov))):
            # tau_ref_s: relative (log) standard error; others: absolute; n(T) nodes: one per node
            std[r][p] = float(s) if k is None else (*std[r].get(p, ()), float(s))
    values = _unpack(data, x)
    kin = _kinetics_with(base, data, values)
    res = residuals(kin, data, jominy_histories)
    return FitResult(data=data, kinetics=kin, parameters=values, std_errors=std, residuals=res,
                     cost=0.5 * float(sum(r.residual**2 for r in res)))


def _check_identifiable(data: DiagramData, names: list[str], jac: np.ndarray) -> None:
    norms = np.linalg.norm(jac, axis=0)
    for name, nrm in zip(names, norms):
        if not nrm > 1e-12:
            raise FitError(f"{data.path.name}: fit.{name}: the data cannot constrain this parameter "
                           f"(no data point is sensitive to it); hold it fixed with a sourced value")
    J = jac / norms
    _, s, vt = np.linalg.svd(J, full_matrices=False)
    if s[-1] < CONDITION_LIMIT * s[0]:
        worst = np.argsort(-np.abs(vt[-1]))[:2]
        pair = " and ".join(f"fit.{names[k]}" for k in worst)
        raise FitError(f"{data.path.name}: the data cannot constrain {pair} separately (singular value ratio "
                       f"{s[-1] / s[0]:.1e}); hold one of them fixed with a sourced value")


# -- the material file ------------------------------------------------------------------------------

def _fmt(x: float | tuple[float, ...]) -> float | list[float]:
    return [float(f"{v:.6g}") for v in x] if isinstance(x, tuple) else float(f"{x:.6g}")


def fitted_block(result: FitResult, data_file: str, quality: Mapping[str, Any] | None = None) -> str:
    """TOML text of the fitted reactions and the fit record (data file, its ``quality`` entries --
    :func:`quenchsim.fitting.fit_quality.fit_record` --, the residual of every point, its source)."""
    data = result.data
    lines = [FIT_BEGIN]
    for r, spec in data.fit.items():
        values = result.parameters[r]
        lines += ["", f"[kinetics.{r}]", 'model = "c_curve"',
                  "source = " + _value(f"fitted by `quenchsim material fit {data_file}` ({data.name}); free: "
                                       f"{', '.join(spec.free) or 'none'}; every parameter carries its own source"),
                  "T_ref_C = " + _inline({"value": spec.T_ref_C, "source": spec.sources["T_ref_C"]
                                          or "reference temperature of the fit"})]
        for p, v in values.items():
            if p in spec.free:
                err = result.std_errors[r].get(p, float("nan"))
                err_text = ", ".join(f"{e:.2g}" for e in err) if isinstance(err, tuple) else f"{err:.2g}"
                what = f"relative std. error {err_text}" if p == "tau_ref_s" else f"std. error {err_text}"
                source = f"fitted to {data_file} ({what})"
            else:
                source = spec.sources[p]
            entry: dict[str, Any] = {}
            if p == "tau_ref_s" and spec.tau_factor_range is not None:   # the factor's prior on the material's value
                entry["range"] = [_fmt(cast(float, v) * f) for f in spec.tau_factor_range]
            if p == "tau_ref_s" and spec.tau_factor != 1.0:
                source = (f"{_fmt(v)} s ({source}) x calibration factor {spec.tau_factor:g}: {spec.tau_factor_source}")
                v = cast(float, v) * spec.tau_factor   # tau_ref_s is a single number
            lines.append(f"{p} = " + _inline({"value": _fmt(v), **entry, "source": source}))
    sources = list(dict.fromkeys(x.source for x in result.residuals))
    lines += ["", "[kinetics.fit]", "data_file = " + _value(data_file), f"T_aust_C = {_value(data.T_aust_C)}",
              f"cost = {_value(_fmt(result.cost))}"]
    lines += [f"{k} = {_value(_fmt(v) if isinstance(v, float) else v)}" for k, v in (quality or {}).items()]
    lines += ["sources = ["]
    lines += [f"    {_value(x)}," for x in sources] + ["]", "# source = index into sources", "residuals = ["]
    lines += [f"    {_inline(row)}," for row in (
        {"point": x.where, "quantity": x.quantity, "data": _fmt(x.data), "model": _fmt(x.model), "unit": x.unit,
         "uncertainty": x.uncertainty, "normalised": _fmt(x.residual), "kind": x.kind,
         "source": sources.index(x.source)} for x in result.residuals)]
    lines += ["]", FIT_END]
    return "\n".join(lines) + "\n"


def _value(v: Any) -> str:
    """One TOML value (a list of numbers on one line)."""
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return tomli_w.dumps({"v": v})[4:].strip()


def _inline(row: Mapping[str, Any]) -> str:
    """A flat mapping as a one-line TOML inline table."""
    return "{ " + ", ".join(f"{k} = {_value(v)}" for k, v in row.items()) + " }"


def _strip_reactions(text: str, reactions: Sequence[str]) -> str:
    """Remove the [kinetics.<reaction>] tables (with sub-tables) of ``reactions`` and the old fit record; reactions of
    an earlier fit that this one does not cover stay (with their sources), the old block markers go."""
    text = "".join(line for line in text.splitlines(keepends=True) if line.rstrip("\n") not in (FIT_BEGIN, FIT_END))
    heads = tuple(f"kinetics.{r}" for r in (*reactions, "fit"))
    out, skipping = [], False
    for line in text.splitlines(keepends=True):
        m = re.match(r"\s*\[\[?([^\]]+)\]\]?\s*(#.*)?$", line)
        if m:
            name = m.group(1).strip()
            skipping = any(name == h or name.startswith(h + ".") for h in heads)
        if not skipping:
            out.append(line)
    return "".join(out).rstrip() + "\n"


def _identity(text: str, name: str, description: str) -> str:
    """``text`` (a material file) with its top-level ``name`` and ``description`` replaced by these."""
    header = re.search(r"^\[", text, flags=re.MULTILINE)
    head, tables = (text[:header.start()], text[header.start():]) if header else (text, "")
    head = re.sub(r"^(name|description)\s*=.*\n?", "", head, flags=re.MULTILINE)
    own = f"name = {json.dumps(name)}\ndescription = {json.dumps(description)}\n"
    return head.rstrip("\n") + ("\n" if head.strip() else "") + own + "\n" + tables


def write_material(result: FitResult, out: Path, data_file: str, name: str | None = None,
                   description: str = "", quality: Mapping[str, Any] | None = None) -> Path:
    """Write the base material with its fitted reactions replaced, once, and check that the file loads. With
    ``name`` the file's top-level ``name`` and ``description`` are these (a new steel is the user's, not the base
    material it was fitted from); without, the base material's are kept (a shipped steel regenerated in place).
    ``quality`` goes into the fit record; its ``warnings`` also head the file as comments."""
    data = result.data
    text = _strip_reactions(find_data_file(data.material, field=f"{data.path.name}: material").read_text(),
                            list(data.fit))
    text = "".join(line for line in text.splitlines(keepends=True) if not line.startswith(WARNING_COMMENT))
    if name is not None:
        text = _identity(text, name, description)
    warnings = (quality or {}).get("warnings", [])
    head = "".join(f"{WARNING_COMMENT}{w}\n" for w in warnings)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(head + text + "\n" + fitted_block(result, data_file, quality))
    load_kinetics(load_material(str(out)), data.T_aust_C)
    return out
