"""Transformation data a heat treater has -- CCT, TTT, Jominy -- as a checked data file (TOML).

Schema (every entry carries ``source`` and ``kind`` = "printed" (a number printed in the source) or
"read" (read off a figure), and the uncertainty it is weighted with)::

    name = "100Cr6 after Kawulok et al. 2020"
    material = "SUJ2"        # base material file: thermal data, Ms, hardness; the fit replaces its reactions
    T_aust_C = 850

    [[cct]]                  # one cooling curve of a CCT diagram
    cooling_rate_C_s = 12    # linear from T_start_C (default T_aust_C) to T_end_C (default 20), or
                             # t8_5_s = 40 / lambda = 0.4: Newtonian cooling T_end + (T0 - T_end) exp(-t/theta)
                             # with 800 -> 500 C in t8_5_s (= 100 lambda s, the lambda of CCT diagrams)
    start_C = { pearlite = 650 }      # 1 % of the volume transformed
    finish_C = { pearlite = 600 }     # 99 % of the product's final amount
    temperature_uncertainty_K = 10
    fractions = { pearlite = 0.01, bainite = 0.0 }
    fraction_uncertainty = 0.02
    hardness_HV = 800 (or hardness_HRC = 64), hardness_uncertainty_HV = 30
    source = "...", kind = "read"

    [[ttt]]                  # one TTT series (lists of equal length)
    phase = "bainite"
    T_C = [300, 350]; t_start_s = [48, 13.4]; t_finish_s = [361, 134]   (1 % and 99 %)
    time_uncertainty_factor = 1.1
    source = "...", kind = "read"

    [[jominy]]               # one Jominy series: hardness against distance from the quenched end
    distance_mm = [1.5, 5, 10]; hardness_HRC = [65, 64, 55] (or hardness_HV); hardness_uncertainty_HV = 30
    source = "...", kind = "printed"

    data_from = ["other.toml"]   # optional: also fit the points of these files (same T_aust_C)

    [fit.pearlite]           # what the fitter may move: the c_curve parameters of each reaction
    T_upper_C = { value = 724, source = "..." }
    T_ref_C = 600
    free = ["tau_ref_s"]
    tau_ref_s = { value = 1.0, source = "starting value" }
    calibration_tau_factor = { value = 2.0, source = "..." }   # optional: the material gets tau_ref x factor
                             # (a declared calibration of the data's steel to the material's; residuals are the data's);
                             # with range = [lo, hi] (factors on the fitted tau_ref) the material's tau_ref_s carries that
                             # prior (the fit's tau_ref x lo .. x hi), so `quenchsim calibrate` can move it
    undercooling_exponent = { value = 3, source = "Li et al. 1998" }  ...
    # n(T): n (+ n_per_K) or, in their place, piecewise linear through nodes (free = [..., "n_nodes"] frees every node):
    n_nodes_T_C = { value = [240, 350, 440], source = "why these nodes" }
    n_nodes = { value = [3, 2.7, 2], source = "starting value" }

Every rule a point breaks is a one-line :class:`quenchsim.errors.InputError` naming the file, the point
and the rule, before the fit starts (finish before start, a curve that does not cool, hardness outside
100-1000 HV or 20-68 HRC, a Jominy distance beyond the bar, an unknown phase). The plausibility bounds below catch
a unit slip (a time in ms or minutes, a rate in C/min, a temperature in K): T_aust_C within
:data:`T_AUST_RANGE_C`, a CCT curve starting at or below T_aust_C, its rate / t8/5 within :data:`RATE_RANGE_C_S` /
:data:`T85_RANGE_S`, TTT holds between :data:`T_MIN_C` and T_aust_C, start times within :data:`TIME_START_RANGE_S`,
finish times up to :data:`TIME_FINISH_MAX_S`, and a product with a start line on a curve having at least 1 % of it
there, with a finish line more than 2 % (a finish is 99 % of the final amount: with 1 % it would lie above the start).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.errors import InputError
from quenchsim.inputs.declare import from_table
from quenchsim.inputs.diagram import CCTEntry, DiagramFile, FitTable, JominyEntry, Numbers, TTTEntry
from quenchsim.inputs.reader import read_toml, reading
from quenchsim.inputs.steel import n_exponent_nodes
from quenchsim.metallurgy.cct import FINISH_SHARE, MIN_FINISH_AMOUNT, START_FRACTION
from quenchsim.metallurgy.hardness import hrc_to_hv
from quenchsim.metallurgy.kinetics import C_CURVE_PARAMETERS, N_NODES

REACTIONS = ("ferrite", "pearlite", "bainite")
"""Diffusional reactions a diagram may show (ferrite is accepted in data; quenchsim's steels model pearlite and bainite)."""
PHASE_NAMES = ("ferrite", "pearlite", "bainite", "martensite", "austenite")
"""Phase names a data file may use."""
HV_RANGE = (100.0, 1000.0)
"""Plausible Vickers hardness of a steel, as-quenched or annealed."""
FITTABLE = ("T_upper_C", *C_CURVE_PARAMETERS, "n_nodes")
"""Parameters of a reaction a [fit] table may free (T_ref_C only places the reference temperature, n_nodes_T_C the
nodes of a piecewise-linear n(T))."""
T_AUST_RANGE_C = (700.0, 1200.0)
"""Plausible austenitising temperature of a steel, C: above Ac1 of any bearing or tool steel (~720-760 C), below
the grain-coarsening solution treatments; a value outside is a typo or a temperature in K/F."""
T_MIN_C = -200.0
"""Lowest temperature of a cooling curve or TTT hold, C (liquid-nitrogen sub-zero treatment is -196 C); lower is
below absolute zero or a unit slip."""
RATE_RANGE_C_S = (1e-3, 1e3)
"""Plausible linear cooling rate of a CCT curve, C/s: CCT diagrams span ~0.01 C/s (furnace cooling) to a few
hundred C/s (dilatometer gas quench); outside, the rate is likely in C/min or C/h, or in K/ms."""
T85_RANGE_S = (0.1, 1e5)
"""Plausible t8/5 of a Newtonian CCT curve, s (lambda = t8/5 / 100 s): ~1 s (water-quenched thin section) to ~1e4 s
(furnace); outside, a unit slip (ms, minutes x 60 forgotten twice)."""
TIME_START_RANGE_S = (1e-2, 1e5)
"""Plausible TTT start (1 %) time, s: the fastest noses of plain carbon steels lie at ~0.1-1 s, TTT diagrams end at
1e5-1e6 s; a start below 0.01 s or above 1e5 s (28 h) is a time in ms or in minutes/hours read as seconds."""
TIME_FINISH_MAX_S = 1e6
"""Latest plausible TTT finish (99 %) time, s: the right edge of a TTT diagram (about 12 days)."""
JOMINY_BAR_LENGTH_MM = 100.0
"""Length of the standard end-quench bar (ASTM A255 / ISO 642: 25 mm diameter x 100 mm)."""
NEWTON_T_HIGH_C, NEWTON_T_LOW_C = 800.0, 500.0
"""The t8/5 interval by which Newtonian cooling curves of CCT diagrams are labelled."""


@dataclass(frozen=True)
class CoolingCurve:
    """A CCT cooling curve: linear (rate_C_s) or Newtonian (time constant theta_s) from T_start_C towards T_end_C."""

    T_start_C: float
    T_end_C: float
    rate_C_s: float = np.nan
    theta_s: float = np.nan

    @property
    def newtonian(self) -> bool:
        return bool(np.isfinite(self.theta_s))

    def temperature_C(self, t_s: np.ndarray) -> np.ndarray:
        t = np.asarray(t_s, dtype=float)
        if self.newtonian:
            return self.T_end_C + (self.T_start_C - self.T_end_C) * np.exp(-t / self.theta_s)
        return np.maximum(self.T_start_C - self.rate_C_s * t, self.T_end_C)

    def duration_s(self) -> float:
        """Time to reach the end temperature (Newtonian: within 0.5 K of it)."""
        if self.newtonian:
            return self.theta_s * np.log((self.T_start_C - self.T_end_C) / 0.5)
        return (self.T_start_C - self.T_end_C) / self.rate_C_s

    def label(self) -> str:
        return f"t8/5 {self.t8_5_s():.3g} s" if self.newtonian else f"{self.rate_C_s:g} C/s"

    def t8_5_s(self) -> float:
        return self.theta_s * np.log((NEWTON_T_HIGH_C - self.T_end_C) / (NEWTON_T_LOW_C - self.T_end_C))


@dataclass(frozen=True)
class CCTPoint:
    where: str
    curve: CoolingCurve
    start_C: Mapping[str, float]
    finish_C: Mapping[str, float]
    temperature_uncertainty_K: float
    fractions: Mapping[str, float]
    fraction_uncertainty: float
    hardness_HV: float
    hardness_uncertainty_HV: float
    source: str
    kind: str


@dataclass(frozen=True)
class TTTPoint:
    where: str
    phase: str
    T_C: float
    t_start_s: float
    t_finish_s: float
    time_uncertainty_factor: float
    source: str
    kind: str


@dataclass(frozen=True)
class JominyPoint:
    where: str
    distance_mm: float
    hardness_HV: float
    hardness_uncertainty_HV: float
    source: str
    kind: str


@dataclass(frozen=True)
class ReactionFitSpec:
    """The c_curve parameters of one reaction (T_upper_C and C_CURVE_PARAMETERS, or n_nodes_T_C and n_nodes in place of
    n and n_per_K): values (start or fixed; the n(T) nodes as tuples), their sources, and which are free."""

    reaction: str
    T_ref_C: float
    values: Mapping[str, float | tuple[float, ...]]
    sources: Mapping[str, str]
    free: tuple[str, ...]
    tau_factor: float = 1.0
    tau_factor_source: str = ""
    tau_factor_range: tuple[float, float] | None = None
    """A prior on the factor (lo, hi): the material's tau_ref_s gets range = [lo, hi] x the fitted tau_ref."""


@dataclass(frozen=True)
class DiagramData:
    path: Path
    name: str
    material: str
    T_aust_C: float
    source: str
    cct: tuple[CCTPoint, ...] = ()
    ttt: tuple[TTTPoint, ...] = ()
    jominy: tuple[JominyPoint, ...] = ()
    fit: Mapping[str, ReactionFitSpec] = field(default_factory=dict)


def _hardness(hv: Numbers | None, hrc: Numbers | None, where: str, key_hv: str = "hardness_HV",
              key_hrc: str = "hardness_HRC") -> np.ndarray | None:
    """The hardness given as HV or HRC (one of them), in HV."""
    if hv is not None and hrc is not None:
        raise InputError(where, [key_hrc, key_hv], f"give {key_hv} or {key_hrc}, not both")
    if hv is not None:
        return np.atleast_1d(np.asarray(hv, dtype=float))
    if hrc is not None:
        values = np.atleast_1d(np.asarray(hrc, dtype=float))
        out = hrc_to_hv(values)
        for i, (c, v) in enumerate(zip(values, out)):
            if not np.isfinite(v):
                raise InputError(f"{where}.{key_hrc}[{i}]", float(c), "HRC must lie within 20-68 (ASTM E140 table)")
        return out
    return None


def _check_hv(hv: float, where: str) -> None:
    if not HV_RANGE[0] <= hv <= HV_RANGE[1]:
        raise InputError(where, round(float(hv), 1), f"hardness must lie within {HV_RANGE[0]:.0f}-{HV_RANGE[1]:.0f} HV")


def _phases(values: Mapping[str, float], key: str, where: str, allowed: tuple[str, ...]) -> dict[str, float]:
    for phase, value in values.items():
        if phase not in allowed:
            raise InputError(f"{where}.{key}.{phase}", value, f"unknown phase name; allowed: {', '.join(allowed)}")
    return dict(values)


def _curve(entry: CCTEntry, where: str, T_aust_C: float) -> CoolingCurve:
    T0 = entry.T_start_C if entry.T_start_C is not None else T_aust_C
    T1 = entry.T_end_C
    given = {k: v for k, v in (("cooling_rate_C_s", entry.cooling_rate_C_s), ("t8_5_s", entry.t8_5_s),
                               ("lambda", entry.lambda_)) if v is not None}
    if len(given) != 1:
        raise InputError(where, sorted(entry._given), "give exactly one of cooling_rate_C_s, t8_5_s, lambda")
    if T0 > T_aust_C:
        raise InputError(f"{where}.T_start_C", T0, f"a CCT curve starts at or below the austenitising temperature "
                                                   f"T_aust_C = {T_aust_C:g} C")
    if not T1 < T0:
        raise InputError(f"{where}.T_end_C", T1, f"a cooling curve must cool: T_end_C must be below T_start_C = {T0:g}")
    if T1 < T_MIN_C:
        raise InputError(f"{where}.T_end_C", T1, f"must be >= {T_MIN_C:g} C (degrees C)")
    ((key, value),) = given.items()
    if value <= 0:
        raise InputError(f"{where}.{key}", value, "a cooling curve must cool: the rate / cooling time must be > 0")
    lo, hi, unit = {"cooling_rate_C_s": (*RATE_RANGE_C_S, "C/s"), "t8_5_s": (*T85_RANGE_S, "s"),
                    "lambda": (T85_RANGE_S[0] / 100.0, T85_RANGE_S[1] / 100.0, "(t8/5 in 100 s)")}[key]
    if not lo <= value <= hi:
        raise InputError(f"{where}.{key}", value, f"must lie within {lo:g}-{hi:g} {unit} for a CCT curve: is it "
                                                  "in another unit (C/min, ms)?")
    if key == "cooling_rate_C_s":
        return CoolingCurve(T_start_C=T0, T_end_C=T1, rate_C_s=value)
    if not (T1 < NEWTON_T_LOW_C and T0 >= NEWTON_T_HIGH_C):
        raise InputError(f"{where}.{key}", value, f"t8/5 needs T_start_C >= 800 and T_end_C < 500 (got {T0:g}, {T1:g})")
    t85 = value if key == "t8_5_s" else 100.0 * value
    theta = t85 / np.log((NEWTON_T_HIGH_C - T1) / (NEWTON_T_LOW_C - T1))
    return CoolingCurve(T_start_C=T0, T_end_C=T1, theta_s=theta)


def _required(value: float | None, where: str, key: str) -> float:
    if value is None:
        raise InputError(f"{where}.{key}", None, "is required")
    return value


def _cct(i: int, entry: CCTEntry, T_aust_C: float) -> CCTPoint:
    curve = _curve(entry, f"cct[{i}]", T_aust_C)
    where = f"cct[{i}] ({curve.label()})"
    start = _phases(entry.start_C, "start_C", where, (*REACTIONS, "martensite"))
    finish = _phases(entry.finish_C, "finish_C", where, REACTIONS)
    for p, T in finish.items():
        if p in start and not T < start[p]:
            raise InputError(f"{where}.finish_C.{p}", T, f"finish before start: on cooling the finish must lie below the "
                                                          f"start ({start[p]:g} C)")
    for p, T in {**start, **finish}.items():
        if not curve.T_end_C <= T <= curve.T_start_C:
            raise InputError(f"{where}.{p}", T, f"temperature outside the cooling curve {curve.T_end_C:g}-"
                                                f"{curve.T_start_C:g} C")
    fractions = _phases(entry.fractions, "fractions", where, PHASE_NAMES)
    for p, x in fractions.items():
        if not 0.0 <= x <= 1.0 + 1e-9:
            raise InputError(f"{where}.fractions.{p}", x, "a phase fraction must lie within 0-1")
    if sum(fractions.values()) > 1.0 + 1e-6:
        raise InputError(f"{where}.fractions", fractions, "phase fractions must not add up to more than 1")
    for p, T in start.items():
        if p in fractions and fractions[p] < START_FRACTION:
            raise InputError(f"{where}.fractions.{p}", fractions[p], f"contradicts the {p} line at {T:g} C on this "
                             f"curve (a start is {START_FRACTION:.0%} transformed): must be >= {START_FRACTION:g}")
    for p, T in finish.items():
        if p in fractions and fractions[p] <= MIN_FINISH_AMOUNT:
            raise InputError(f"{where}.fractions.{p}", fractions[p], f"contradicts the {p} line at {T:g} C on this "
                             f"curve: a finish line ({FINISH_SHARE:.0%} of the final amount) needs more than "
                             f"{MIN_FINISH_AMOUNT:g} of the product (with less it would lie at or above the "
                             f"{START_FRACTION:.0%} start): drop the finish line")
    hv = _hardness(entry.hardness_HV, entry.hardness_HRC, where)
    if hv is not None:
        _check_hv(hv[0], f"{where}.hardness")
    if not (start or finish or fractions or hv is not None):
        raise InputError(where, sorted(entry._given), "a CCT curve needs start_C, finish_C, fractions or a hardness")
    return CCTPoint(
        where=where, curve=curve, start_C=start, finish_C=finish,
        temperature_uncertainty_K=_required(entry.temperature_uncertainty_K, where, "temperature_uncertainty_K")
        if (start or finish) else np.nan,
        fractions=fractions,
        fraction_uncertainty=_required(entry.fraction_uncertainty, where, "fraction_uncertainty")
        if fractions else np.nan,
        hardness_HV=float(hv[0]) if hv is not None else np.nan,
        hardness_uncertainty_HV=_required(entry.hardness_uncertainty_HV, where, "hardness_uncertainty_HV")
        if hv is not None else np.nan,
        source=entry.source, kind=entry.kind)


def _series(values: dict[str, Numbers], where: str) -> list[np.ndarray]:
    arrays = [np.atleast_1d(np.asarray(v, dtype=float)) for v in values.values()]
    if len({a.size for a in arrays}) != 1:
        raise InputError(where, {k: len(a) for k, a in zip(values, arrays)},
                         f"lists {', '.join(values)} must have equal length")
    return arrays


def _ttt(i: int, entry: TTTEntry, T_aust_C: float) -> list[TTTPoint]:
    where = f"ttt[{i}]"
    phase = entry.phase
    if phase not in REACTIONS:
        raise InputError(f"{where}.phase", phase, f"unknown phase name; a TTT line belongs to one of {', '.join(REACTIONS)}")
    T, ts, tf = _series({"T_C": entry.T_C, "t_start_s": entry.t_start_s, "t_finish_s": entry.t_finish_s}, where)
    points = []
    for k in range(T.size):
        w = f"{where} point {k} (T_C = {T[k]:g})"
        if not T_MIN_C <= T[k] < T_aust_C:
            raise InputError(f"{w}.T_C", float(T[k]), f"an isothermal hold must lie within {T_MIN_C:g} C and the "
                                                      f"austenitising temperature T_aust_C = {T_aust_C:g} C")
        if not ts[k] > 0:
            raise InputError(f"{w}.t_start_s", float(ts[k]), "must be > 0")
        if not TIME_START_RANGE_S[0] <= ts[k] <= TIME_START_RANGE_S[1]:
            raise InputError(f"{w}.t_start_s", float(ts[k]), f"must lie within {TIME_START_RANGE_S[0]:g}-"
                                                             f"{TIME_START_RANGE_S[1]:g} s for a TTT start: is it in "
                                                             "ms, minutes or hours?")
        if not tf[k] > ts[k]:
            raise InputError(f"{w}.t_finish_s", float(tf[k]), f"finish before start: must be later than t_start_s = "
                                                              f"{ts[k]:g}")
        if tf[k] > TIME_FINISH_MAX_S:
            raise InputError(f"{w}.t_finish_s", float(tf[k]), f"must be <= {TIME_FINISH_MAX_S:g} s (the right edge "
                                                              "of a TTT diagram): is it in ms?")
        points.append(TTTPoint(where=w, phase=phase, T_C=float(T[k]), t_start_s=float(ts[k]), t_finish_s=float(tf[k]),
                               time_uncertainty_factor=entry.time_uncertainty_factor, source=entry.source,
                               kind=entry.kind))
    return points


def _jominy(i: int, entry: JominyEntry) -> list[JominyPoint]:
    where = f"jominy[{i}]"
    (d,) = _series({"distance_mm": entry.distance_mm}, where)
    hv = _hardness(entry.hardness_HV, entry.hardness_HRC, where)
    if hv is None:
        raise InputError(where, sorted(entry._given), "needs hardness_HV or hardness_HRC")
    if hv.size != d.size:
        raise InputError(where, {"distance_mm": d.size, "hardness": hv.size},
                         "distance and hardness lists must have equal length")
    points = []
    for k in range(d.size):
        w = f"{where} point {k} (distance_mm = {d[k]:g})"
        if not 0.0 < d[k] <= JOMINY_BAR_LENGTH_MM:
            raise InputError(f"{w}.distance_mm", float(d[k]), "Jominy distance beyond the bar: must lie within "
                                                              f"0-{JOMINY_BAR_LENGTH_MM:g} mm of the quenched end")
        _check_hv(hv[k], f"{w}.hardness")
        points.append(JominyPoint(where=w, distance_mm=float(d[k]), hardness_HV=float(hv[k]),
                                  hardness_uncertainty_HV=entry.hardness_uncertainty_HV, source=entry.source,
                                  kind=entry.kind))
    return points


def _fit_spec(reaction: str, table: FitTable) -> ReactionFitSpec:
    where = f"fit.{reaction}"
    if reaction not in ("pearlite", "bainite"):
        raise InputError(where, reaction, "unknown reaction; quenchsim fits pearlite and bainite (c_curve model)")
    nodes = table.n_nodes_T_C is not None or table.n_nodes is not None
    exponent = N_NODES if nodes else ("n", "n_per_K")
    for key in ("n", "n_per_K") if nodes else N_NODES:
        if getattr(table, key) is not None:
            raise InputError(f"{where}.{key}", table._given[key], "give n (and n_per_K) or n_nodes_T_C with n_nodes, "
                                                                  "not both")
    values: dict[str, Any] = {}   # numbers; the n(T) nodes as tuples (ReactionFitSpec.values)
    sources: dict[str, str] = {}
    for key in ("T_upper_C", "T_ref_C", *C_CURVE_PARAMETERS[:3], *exponent):
        sources[key] = table.source_of(key)
        if key == "n_per_K" and table.n_per_K is None:
            values[key], sources[key] = 0.0, "held constant (n independent of T)"
        elif key not in N_NODES:
            values[key] = _required(getattr(table, key), where, key)
    if nodes:
        checked = n_exponent_nodes(table.n_nodes_T_C, table.n_nodes, where)
        values.update({k: tuple(float(x) for x in v) for k, v in checked.items()})
    free = list(table.free)
    fittable = [k for k in FITTABLE if k not in ("n", "n_per_K", "n_nodes") or k in exponent]
    if any(p not in fittable for p in free):
        raise InputError(f"{where}.free", free, f"must list parameters among {', '.join(fittable)}")
    if nodes and not sources["n_nodes_T_C"]:
        raise InputError(f"{where}.n_nodes_T_C", values["n_nodes_T_C"], "the node temperatures need { value = [...], "
                                                                         "source = ... }")
    for key in fittable:
        if key not in free and not sources[key]:
            raise InputError(f"{where}.{key}", values[key], "a parameter the fit holds fixed needs { value = ..., "
                                                            "source = ... }")
    if not values["T_ref_C"] < values["T_upper_C"]:
        raise InputError(f"{where}.T_ref_C", values["T_ref_C"], f"must lie below T_upper_C = {values['T_upper_C']:g}")
    factor, factor_source, factor_range = 1.0, "", None
    if table.calibration_tau_factor is not None:
        factor = table.calibration_tau_factor
        factor_source = table.source_of("calibration_tau_factor")
        if not factor_source:
            raise InputError(f"{where}.calibration_tau_factor", factor, "a calibration factor needs { value = ..., "
                                                                        "source = ... }")
        spec = table._given["calibration_tau_factor"]
        band = spec.get("range") if isinstance(spec, Mapping) else None
        if band is not None:
            if not band[0] > 0 or not band[0] <= factor <= band[1]:
                raise InputError(f"{where}.calibration_tau_factor.range", band, f"must be [lo, hi] with 0 < lo <= "
                                                                                f"{factor:g} (the factor) <= hi")
            factor_range = (float(band[0]), float(band[1]))
    return ReactionFitSpec(reaction=reaction, T_ref_C=values.pop("T_ref_C"), values=values, sources=sources,
                           free=tuple(free), tau_factor=factor, tau_factor_source=factor_source,
                           tau_factor_range=factor_range)


def load_diagram_data(path: str | Path) -> DiagramData:
    """Read and check a CCT / TTT / Jominy data file (:class:`quenchsim.inputs.diagram.DiagramFile`); an error names
    the file, the point and the rule."""
    path = Path(path)
    if not path.is_file():
        raise InputError("data file", str(path), "does not exist")
    raw = read_toml(path, "data file")
    with reading(path.name):
        return _diagram_data(path, from_table(DiagramFile, raw))


def _diagram_data(path: Path, data: DiagramFile) -> DiagramData:
    T_aust = data.T_aust_C
    if not T_AUST_RANGE_C[0] <= T_aust <= T_AUST_RANGE_C[1]:
        raise InputError("T_aust_C", T_aust, f"an austenitising temperature must lie within {T_AUST_RANGE_C[0]:g}-"
                                             f"{T_AUST_RANGE_C[1]:g} C (degrees C, not K or F)")
    cct = tuple(_cct(i, t, T_aust) for i, t in enumerate(data.cct))
    ttt = tuple(p for i, t in enumerate(data.ttt) for p in _ttt(i, t, T_aust))
    jominy = tuple(p for i, t in enumerate(data.jominy) for p in _jominy(i, t))
    fit = {name: _fit_spec(name, t) for name, t in data.fit.items()}
    for name in data.data_from:
        other = load_diagram_data(path.parent / name)
        if other.T_aust_C != T_aust:
            raise InputError("data_from", name, f"austenitised at {other.T_aust_C:g} C, this file at {T_aust:g} C")
        cct, ttt, jominy = cct + other.cct, ttt + other.ttt, jominy + other.jominy
    if not (cct or ttt or jominy):
        raise InputError("file", sorted(data._given), "holds no data: give [[cct]], [[ttt]] or [[jominy]] entries")
    return DiagramData(path=path, name=data.name, material=data.material, T_aust_C=T_aust, source=data.source, cct=cct,
                       ttt=ttt, jominy=jominy, fit=fit)
