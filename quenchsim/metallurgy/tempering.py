"""Tempering of hardened steel: the tempering reactions, the hardness after tempering and the relaxation clock, for the
``[temper]`` stage of a run and for the service stability of a tempered part.

One clock drives every process: the Hollomon-Jaffe parameter (Hollomon & Jaffe 1945)

    P = T (C + log10 t),        T in K, t in h, C = a + b w_C (the steel's ``[tempering.clock]``),

advanced along any temperature history by additivity (:func:`hollomon_jaffe_advance`): the time at the present
temperature that gives the P reached so far, plus the step. Each tempering process k is a JMAK law in the equivalent
time of that clock,

    progress_k(P) = 1 - exp(-ln 2 * 10^((P - P50_k) / w_k)),

(equivalently an Arrhenius-JMAK law with the apparent activation energy ln(10) R P50_k and Avrami exponent
T / w_k), its P50_k and w_k fixed by two published (temperature, time, progress) points (:func:`jmak_through`):

* martensite reactions (transition carbide, cementite): the martensite contracts by its linear strain per unit
  martensite (:func:`tempering_free_strain`); its phase fraction is unchanged;
* the retained austenite's decomposition: a share progress(P) of the austenite at the start of the temper becomes
  the product phase (bainite): the stress model's own austenite -> bainite volume change applies;
* hardness: the martensite's HV is min(as-quenched, HV_TM(P)), a polynomial in P fitted to published hardness
  after tempering (:func:`fit_tempered_martensite`); the other phases keep theirs;
* relaxation: at a fixed strain the deviatoric stress falls as exp(-r(P)), r(P) = ln 2 * 10^((P - P50) / w).

Data: ``materials/data/tempering_1C_Cr.toml`` (named by the steel file's ``tempering`` key), every number with
its source.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from quenchsim.errors import InputError
from quenchsim.inputs.steel import Steel
from quenchsim.inputs.tempering import TemperHardness, TemperingData
from quenchsim.materials import as_steel
from quenchsim.materials.properties import PHASES
from quenchsim.metallurgy.hardness import hrc_to_hv, phase_hardness_HV
from quenchsim.metallurgy.kinetics import Kinetics, load_kinetics
from quenchsim.metallurgy.laws import KELVIN, koistinen_marburger, linear_formula
from quenchsim.metallurgy.transform import PhaseState

LN2 = math.log(2.0)
SECONDS_PER_HOUR = 3600.0
SUBSTEP_K = 5.0
"""Largest temperature change of one sub-step of :func:`hollomon_jaffe_advance` (the step's T taken linear in time)."""
MARTENSITE_REACTIONS = ("martensite_transition_carbide", "martensite_cementite")
AUSTENITE_REACTION = "austenite_decomposition"


@dataclass(frozen=True)
class Process:
    """A process in the clock's equivalent time: progress(P) = 1 - exp(-ln 2 * 10^((P - P50_K) / width_K))."""

    P50_K: float
    width_K: float

    def progress(self, P: Any) -> np.ndarray:
        return -np.expm1(-self.rate_term(P))

    def rate_term(self, P: Any) -> np.ndarray:
        """ln 2 * 10^((P - P50) / w): -ln(1 - progress), the JMAK exponent term."""
        return LN2 * np.power(10.0, np.minimum((np.asarray(P, dtype=float) - self.P50_K) / self.width_K, 30.0))


@dataclass(frozen=True)
class Reaction:
    """A tempering reaction: its parent phase, its ``process`` and its linear strain per unit parent fraction
    (martensite reactions) or product phase (the austenite's decomposition)."""

    name: str
    parent: str
    process: Process
    strain_per_parent: float
    product: str | None
    source: str


@dataclass(frozen=True)
class Tempering:
    """The tempering data of one steel hardened from one austenitising temperature."""

    material: str
    clock_constant: float
    reactions: Mapping[str, Reaction]
    relaxation: Process
    hardness_poly_HV: tuple[float, ...]
    source: str

    def parameter_after(self, T_C: float, time_h: float) -> float:
        """P after an isothermal hold of ``time_h`` hours at ``T_C`` from the as-quenched state."""
        return (T_C + KELVIN) * (self.clock_constant + math.log10(time_h))

    def tempered_martensite_HV(self, P: Any) -> np.ndarray:
        """HV_TM(P), a polynomial in P/1000 (coefficients from the constant term up)."""
        return np.polynomial.polynomial.polyval(np.asarray(P, dtype=float) / 1000.0, self.hardness_poly_HV)


def hollomon_jaffe_advance(P: np.ndarray, T0_C: np.ndarray, T1_C: np.ndarray, dt_s: float, C: float) -> np.ndarray:
    """The Hollomon-Jaffe parameter after a step of ``dt_s`` during which T goes linearly from T0 to T1 (C), by
    additivity on sub-steps of at most :data:`SUBSTEP_K`: at each sub-step's mean temperature T the equivalent time
    t_eq = 10^(P/T - C) h, then P = T (C + log10(t_eq + dt)). Exact for an isothermal hold (P = T (C + log10 t))."""
    P = np.asarray(P, dtype=float).copy()
    T0 = np.broadcast_to(np.asarray(T0_C, dtype=float), P.shape)
    T1 = np.broadcast_to(np.asarray(T1_C, dtype=float), P.shape)
    if dt_s <= 0.0:
        return P
    m = int(max(1, math.ceil(float(np.max(np.abs(T1 - T0), initial=0.0)) / SUBSTEP_K)))
    dt_h = dt_s / SECONDS_PER_HOUR / m
    for k in range(m):
        T = T0 + (T1 - T0) * ((k + 0.5) / m) + KELVIN
        log_t = np.minimum(P / T - C, 30.0)
        P = T * (C + np.log10(np.power(10.0, log_t) + dt_h))
    return P


def jmak_through(points: list[tuple[float, float, float]], C: float, where: str) -> Process:
    """The process through two (T_C, time_h, progress) points of isothermal holds."""
    if len(points) != 2:
        raise InputError(f"{where}.points", points, "needs exactly two {T_C, time_h, progress} points")
    (T1, t1, x1), (T2, t2, x2) = points
    P = [(T + KELVIN) * (C + math.log10(t)) for T, t in ((T1, t1), (T2, t2))]
    y = [math.log10(-math.log1p(-x) / LN2) for x in (x1, x2)]
    if not (P[1] > P[0] and y[1] > y[0]):
        raise InputError(f"{where}.points", points, "the second point must be the later (larger T and t) one with "
                         "the larger progress")
    width = (P[1] - P[0]) / (y[1] - y[0])
    return Process(P50_K=P[0] - y[0] * width, width_K=width)


def has_tempering(material: Steel | Mapping[str, Any]) -> bool:
    """Whether the steel has tempering data (the file its ``tempering`` key names, found)."""
    return isinstance(as_steel(material).tempering, TemperingData)


def load_tempering(material: Steel | Mapping[str, Any], kin: Kinetics) -> Tempering:
    """The tempering data of ``material`` (its ``tempering`` file, :class:`quenchsim.inputs.tempering.TemperingData`,
    resolved by :func:`quenchsim.materials.load_steel`) for the steel hardened as ``kin`` says (its dissolved carbon
    sets the clock constant)."""
    steel = as_steel(material)
    name = steel.name
    data = steel.tempering
    if not isinstance(data, TemperingData):
        raise InputError("temper", name, "the steel has no tempering data (a `tempering` file named in its material "
                         "file, e.g. data/tempering_1C_Cr.toml); a [temper] stage needs it")
    where = f"{name}.tempering"
    composition = kin.dissolved if data.clock.carbon == "dissolved" else kin.composition
    C = linear_formula(data.clock.formula, composition)
    if not 5.0 < C < 40.0:
        raise InputError(f"{where}.clock.constant_formula", round(C, 2), "gives a Hollomon-Jaffe constant outside 5-40")
    reactions = {}
    for rname, table in data.reactions.items():
        w = f"{where}.reactions.{rname}"
        process = jmak_through([(p.T_C, p.time_h, p.progress) for p in table.points], C, w)
        # the austenite's decomposition: the stress model's own austenite -> product volume change
        strain = 0.0 if table.parent == "austenite" else float(cast(float, table.volume_change_pct_per_C)) \
            * kin.dissolved["C"] / 300.0
        reactions[rname] = Reaction(rname, table.parent, process, strain, table.product, table.points_source)
    pts = [(p.T_C, p.time_h, 1.0 - p.stress_ratio) for p in data.relaxation.points]
    relaxation = jmak_through(pts, C, f"{where}.relaxation")
    base = Tempering(name, C, reactions, relaxation, (0.0,), data.source)
    poly = fit_tempered_martensite(base, steel, data.hardness, f"{where}.hardness")
    return Tempering(name, C, reactions, relaxation, poly, base.source)


FAST_RATE_C_S = 30.0
"""Cooling rate at 700 C (C/s) of a small oil-quenched specimen, for the Maynier hardness of its decomposed
austenite (bainite, at its cap there)."""


def specimen_hardness_HV(tempering: Tempering, kin: Kinetics, room_C: float, P: Any, hv_martensite: Any
                         ) -> np.ndarray:
    """HV of a through-hardened specimen of ``kin`` quenched to ``room_C`` (martensite and the Koistinen-Marburger
    retained austenite) after tempering to clock values ``P``, its martensite at ``hv_martensite``: the mixture of
    the martensite, the austenite left (its [hardness.austenite]) and the austenite decomposed (bainite)."""
    x_a0 = 1.0 - float(koistinen_marburger(np.array(room_C), kin.Ms_C, kin.alpha_per_K))
    decomposed = austenite_progress(tempering, P)
    hv_a = float(phase_hardness_HV(kin, "austenite", np.array([FAST_RATE_C_S]))[0])
    hv_b = float(phase_hardness_HV(kin, "bainite", np.array([FAST_RATE_C_S]))[0])
    return (1.0 - x_a0) * np.asarray(hv_martensite) + x_a0 * ((1.0 - decomposed) * hv_a + decomposed * hv_b)


def specimen_austenite(kin: Kinetics, room_C: float) -> float:
    """Retained austenite of a through-hardened specimen quenched to ``room_C`` (Koistinen-Marburger)."""
    return 1.0 - float(koistinen_marburger(np.array(room_C), kin.Ms_C, kin.alpha_per_K))


def austenite_progress(tempering: Tempering, P: Any) -> np.ndarray:
    """The decomposed share of the austenite present at the start of the temper, at clock values ``P``."""
    reaction = tempering.reactions.get(AUSTENITE_REACTION)
    return np.zeros(np.shape(P)) if reaction is None else reaction.process.progress(P)


HARDNESS_LAWS = {"linear_in_P": 1, "quadratic_in_P": 2}
"""The polynomial degree in P of each form of HV_TM(P)."""


def fit_tempered_martensite(tempering: Tempering, material: Steel | Mapping[str, Any], table: TemperHardness,
                            where: str) -> tuple[float, ...]:
    """The coefficients of HV_TM(P), a polynomial in P/1000 of the table's ``law``: least squares to the table's HRC
    after tempering at ``T_C`` for ``time_h`` of a specimen hardened from ``austenitising_temperature_C`` and quenched
    to ``room_temperature_C``, its retained austenite and that austenite's decomposition taken into account
    (:func:`specimen_hardness_HV`)."""
    degree = HARDNESS_LAWS[table.law]
    T, hrc = np.asarray(table.T_C, dtype=float), np.asarray(table.HRC, dtype=float)
    kin = load_kinetics(material, table.austenitising_temperature_C)
    room = table.room_temperature_C
    P = (T + KELVIN) * (tempering.clock_constant + math.log10(table.time_h))
    x_m = 1.0 - specimen_austenite(kin, room)
    hv_m = (hrc_to_hv(hrc) - specimen_hardness_HV(tempering, kin, room, P, 0.0)) / x_m
    if T.size <= degree:
        raise InputError(f"{where}.T_C", list(table.T_C), f"needs more than {degree} points for the {table.law} law")
    return tuple(float(c) for c in np.polynomial.polynomial.polyfit(P / 1000.0, hv_m, degree))


# -- the state of a tempering part ------------------------------------------------------------------------------
@dataclass(frozen=True)
class TemperState:
    """Material points during and after tempering: the clock ``P`` (K) and the phase fractions at the start of the
    temper (``start``); the present fractions and strains are functions of the two (:func:`tempered_fractions`)."""

    P: np.ndarray
    start: Mapping[str, np.ndarray]
    cooling_rate_700_C_s: np.ndarray


def tempered_fractions(tempering: Tempering, state: TemperState) -> dict[str, np.ndarray]:
    """The phase fractions at clock ``state.P``: a share of the starting austenite turned to its product."""
    out = {p: np.array(state.start[p], dtype=float) for p in PHASES}
    reaction = tempering.reactions.get(AUSTENITE_REACTION)
    if reaction is not None:
        moved = state.start["austenite"] * reaction.process.progress(state.P)
        out["austenite"] = state.start["austenite"] - moved
        out[reaction.product or "bainite"] = out[reaction.product or "bainite"] + moved
    return out


def tempering_free_strain(tempering: Tempering, state: TemperState) -> np.ndarray:
    """Linear free strain of the martensite reactions at clock ``state.P`` (isotropic, from the start of the temper):
    sum_k X_M,start strain_k progress_k(P)."""
    out = np.zeros(np.shape(state.P))
    for reaction in tempering.reactions.values():
        if reaction.parent != "austenite":
            out = out + state.start[reaction.parent] * reaction.strain_per_parent * reaction.process.progress(state.P)
    return out


def relaxation_term(tempering: Tempering, P: Any) -> np.ndarray:
    """r(P): at a fixed total strain the deviatoric stress is exp(-r(P)) of its value at the start of the temper."""
    return tempering.relaxation.rate_term(P)


def tempered_hardness_HV(tempering: Tempering, kin: Kinetics, state: TemperState) -> np.ndarray:
    """HV of each point: the phase mixture of :func:`quenchsim.metallurgy.hardness_HV` with the martensite at
    min(its as-quenched HV, HV_TM(P))."""
    fractions = tempered_fractions(tempering, state)
    total = np.zeros(np.shape(state.P))
    for phase in kin.hardness:
        hv = phase_hardness_HV(kin, phase, state.cooling_rate_700_C_s)
        if phase == "martensite":
            hv = np.minimum(hv, tempering.tempered_martensite_HV(state.P))
        total = total + fractions[phase] * hv
    return total


class TemperingPhaseModel:
    """The tempering as the thermal solver's phase model (:class:`quenchsim.thermal.PhaseModel`): the state is a
    :class:`TemperState`; no quench kinetics run during the temper (the austenite changes only by its decomposition;
    no martensite forms: the part stays above the room temperature it was quenched to)."""

    def __init__(self, tempering: Tempering) -> None:
        self.tempering = tempering
        reaction = tempering.reactions.get(AUSTENITE_REACTION)
        # the decomposing austenite's product: ``time.max_dX`` limits its change per step
        self.time_dependent_phases: tuple[str, ...] = () if reaction is None else (reaction.product or "bainite",)

    def start(self, quenched: PhaseState) -> TemperState:
        return TemperState(P=np.zeros_like(quenched.T_min_C), start={p: np.array(quenched.fractions[p])
                                                                        for p in PHASES},
                           cooling_rate_700_C_s=np.array(quenched.cooling_rate_700_C_s))

    def advance(self, state: TemperState, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> TemperState:
        P = hollomon_jaffe_advance(state.P, T_old_C, T_new_C, dt_s, self.tempering.clock_constant)
        return TemperState(P=P, start=state.start, cooling_rate_700_C_s=state.cooling_rate_700_C_s)

    def fractions(self, state: TemperState) -> dict[str, np.ndarray]:
        return tempered_fractions(self.tempering, state)

    def checkpoint_state(self, state: TemperState) -> dict[str, Any]:
        return {"P": state.P, "start": dict(state.start), "cooling_rate_700_C_s": state.cooling_rate_700_C_s}

    def restore_state(self, arrays: dict[str, Any]) -> TemperState:
        return TemperState(P=np.array(arrays["P"]), start={p: np.array(v) for p, v in arrays["start"].items()},
                           cooling_rate_700_C_s=np.array(arrays["cooling_rate_700_C_s"]))


def isothermal_hold(tempering: Tempering, P: Any, T_C: float, time_h: float) -> np.ndarray:
    """The clock after holding points at clock ``P`` for ``time_h`` hours at ``T_C`` (closed form of
    :func:`hollomon_jaffe_advance` for a constant temperature): T (C + log10(10^(P/T - C) + t))."""
    T = T_C + KELVIN
    C = tempering.clock_constant
    return T * (C + np.log10(np.power(10.0, np.minimum(np.asarray(P, dtype=float) / T - C, 30.0)) + time_h))


@dataclass(frozen=True)
class ServiceChange:
    """What a hold in service does to tempered points (arrays over the points): the clock after it, the austenite
    that decomposes (fraction of the point) and the martensite reactions' linear strain."""

    P_after: np.ndarray
    austenite_decomposed: np.ndarray
    martensite_strain: np.ndarray


def service_change(tempering: Tempering, P: Any, martensite: Any, austenite: Any, T_C: float, time_h: float
                   ) -> ServiceChange:
    """The change of tempered points (clock ``P``, present ``martensite`` and ``austenite`` fractions) held for
    ``time_h`` at ``T_C``: the austenite at the start of the temper is austenite / (1 - progress(P)), of which the
    share progress(P_after) - progress(P) decomposes; the martensite reactions add their strain between the two."""
    P0 = np.asarray(P, dtype=float)
    P1 = isothermal_hold(tempering, P0, T_C, time_h)
    done = austenite_progress(tempering, P0)
    start = np.asarray(austenite, dtype=float) / np.maximum(1.0 - done, 1e-12)
    decomposed = start * (austenite_progress(tempering, P1) - done)
    strain = np.zeros_like(P0)
    for reaction in tempering.reactions.values():
        if reaction.parent != "austenite":
            strain = strain + np.asarray(martensite) * reaction.strain_per_parent * (
                reaction.process.progress(P1) - reaction.process.progress(P0))
    return ServiceChange(P1, decomposed, strain)
