"""Mechanical material model: built from a steel's mechanics data (``materials/NAME.mechanics.toml``, declared and
checked in :mod:`quenchsim.inputs.steel_mechanics`), and the free (thermal + structural) strain of a phase mixture.

Two forms of the free strain are accepted (``[free_strain] form``):

* ``"specific_volume"`` -- the volume of every phase follows from its thermal expansion and its
  volume change against austenite at a reference temperature, a linear function of the carbon
  dissolved in the austenite at T_aust (Thelning / ASM Handbook Vol. 4 relations
  ``dV/V (%) = a_i + b_i C``; the carbon may be taken from the material's dissolved-carbon table, the
  value the metallurgy uses), diluted by the undissolved carbide that all states share.  The linear
  free strain of phase i relative to austenite at the austenitising temperature T_aust is

      eps_i(T) = (1 + dV_i/V)^(1/3) (1 + e_i(T)) / (1 + e_A(T_aust)) - 1,
      e_i(T)   = int_{T_ref}^{T} alpha_i(T') dT',

  and the free strain of a mixture is the state function ``sum_i X_i eps_i(T)``; transformation
  strains follow from the phases.
* ``"expansion"`` -- the published form of many quench models (e.g. Furlan et al. 2025): per-phase
  instantaneous expansion coefficients alpha_i(T) and a linear transformation strain gamma_i of
  austenite -> phase i, taken at the temperature where the transformation happens.  It is path
  dependent and defined by its rate, d eps = sum_i X_i alpha_i dT + sum_i gamma_i dX_i.

Both are integrated by :func:`free_strain_increment`, which is exact for the first form (product
rule with end-of-step fractions and start-of-step transformation strains) and is the published
update of the second.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from quenchsim.errors import InputError
from quenchsim.inputs.case import SolverOptions
from quenchsim.inputs.declare import from_table
from quenchsim.inputs.steel_mechanics import MetastableFactor, SpecificVolumeStrain, SteelMechanics
from quenchsim.inputs.steel import Steel
from quenchsim.materials import PHASES, Property, as_steel

TRIP_K_BOUNDS_1_PA = (1e-12, 1e-9)
"""Plausible TRIP constants of the product phases (1/Pa); the published ranges for steels are 4-21e-11
(DEFORM manual, section 10.9, TRNSFP: 4-13e-5 /MPa diffusive, 5-21e-5 /MPa martensitic)."""

LEBLOND_CUTOFF = 0.03
"""Leblond's TRIP kinetics use -ln(f); below f = 0.03 the slope is frozen at -ln(0.03)
(Leblond, Devaux, Devaux, Int. J. Plast. 5 (1989) 573 -- cut-off of the logarithm)."""


@dataclass(frozen=True)
class MechanicsModel:
    """Everything the mechanics solver needs about the steel and the case options."""

    name: str
    austenitizing_T_C: float
    E_Pa: Property
    nu: Property
    free_strain_form: str
    alpha_1_K: Property
    reference_T_C: float
    volume_change: Mapping[str, float]
    transformation_strain: Property | None
    annealed_free_strain: float
    plasticity: bool
    yield_Pa: Property | None
    hardening_Pa: Property | None
    hardening_memory: float
    trip: bool
    trip_K_1_Pa: Property | None
    trip_law: str
    newton_rtol: float
    max_newton_iterations: int


def integrate_property(prop: Property, T0_C: Any, T1_C: Any) -> np.ndarray:
    """int_{T0}^{T1} p(T) dT of a phase-independent property (constant, polynomial or clamped table).

    Used for the thermal strain e(T) = int alpha dT of an instantaneous expansion coefficient.
    """
    T0 = np.asarray(T0_C, dtype=float)
    T1 = np.asarray(T1_C, dtype=float)
    if prop.kind == "constant":
        return prop.constant * (T1 - T0)
    if prop.kind == "poly":
        antideriv = np.polynomial.polynomial.polyint(cast(np.ndarray, prop.coefficients))
        return (np.polynomial.polynomial.polyval(T1, antideriv)
                - np.polynomial.polynomial.polyval(T0, antideriv))
    if prop.kind == "table":
        return _table_antiderivative(prop, T1) - _table_antiderivative(prop, T0)
    raise ValueError("integrate_property needs a phase-independent property")


def _table_antiderivative(prop: Property, T: np.ndarray) -> np.ndarray:
    """F(T) = int_{T_C[0]}^{T} p of the linear table p, clamped (constant) outside its range."""
    x, v = cast(np.ndarray, prop.T_C), cast(np.ndarray, prop.values)   # a table property carries both
    if x.size == 1:
        return v[0] * (T - x[0])
    knots = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(x))])
    k = np.clip(np.searchsorted(x, T, side="right") - 1, 0, x.size - 2)
    slope = (v[k + 1] - v[k]) / (x[k + 1] - x[k])
    dT = np.clip(T, x[0], x[-1]) - x[k]
    inside = knots[k] + dT * (v[k] + 0.5 * slope * dT)
    return inside + np.where(T < x[0], (T - x[0]) * v[0], 0.0) + np.where(T > x[-1], (T - x[-1]) * v[-1], 0.0)


def phase_thermal_strain(model: MechanicsModel, phase: str, T_C: Any) -> np.ndarray:
    """e_i(T) = int_{T_ref}^{T} alpha_i dT' (T_ref: the volume reference of the specific-volume form,
    T_aust for the expansion form)."""
    return integrate_property(model.alpha_1_K.for_phase(phase), model.reference_T_C, T_C)


def phase_free_strain(model: MechanicsModel, phase: str, T_C: Any) -> np.ndarray:
    """Linear free strain eps_i(T) of pure phase i relative to austenite at T_aust.

    Specific-volume form: eps_i = (1 + dV_i/V)^(1/3) (1 + e_i(T)) / (1 + e_A(T_aust)) - 1.
    Expansion form: the thermal part e_i(T) = int_{T_aust}^T alpha_i dT' only (the transformation
    strain is added per increment, see :func:`free_strain_increment`).
    """
    e = phase_thermal_strain(model, phase, T_C)
    if model.free_strain_form == "expansion":
        return e
    e_aust = phase_thermal_strain(model, "austenite", model.austenitizing_T_C)
    return (1.0 + model.volume_change[phase]) ** (1.0 / 3.0) * (1.0 + e) / (1.0 + e_aust) - 1.0


def free_strain(model: MechanicsModel, T_C: Any, fractions: Mapping[str, Any]) -> np.ndarray:
    """Isotropic linear free strain (thermal + structural) of a phase mixture relative to austenite at
    T_aust: ``sum_i X_i eps_i(T)``.

    Exact state function for the specific-volume form.  For the path-dependent expansion form it is
    the value of a mixture whose transformations all happened at T (``sum_i X_i (e_i(T) + gamma_i)``);
    the solver integrates the published rate form instead.
    """
    T = np.asarray(T_C, dtype=float)
    out = np.zeros(np.broadcast_shapes(T.shape, *(np.shape(x) for x in fractions.values())))
    for phase, X in fractions.items():
        out += np.asarray(X) * phase_free_strain(model, phase, T)
        if model.free_strain_form == "expansion":   # the expansion form carries its transformation strain
            out += np.asarray(X) * cast(Property, model.transformation_strain).for_phase(phase)(T)
    return out


def transformation_strain(model: MechanicsModel, phase: str, T_C: Any) -> np.ndarray:
    """Linear strain gamma_i(T) of austenite -> phase i at temperature T (zero for austenite)."""
    if model.free_strain_form == "expansion":   # the expansion form carries its transformation strain
        return cast(Property, model.transformation_strain).for_phase(phase)(T_C)
    return phase_free_strain(model, phase, T_C) - phase_free_strain(model, "austenite", T_C)


def free_strain_increment(model: MechanicsModel, T0_C: np.ndarray, T1_C: np.ndarray,
                          X0: Mapping[str, np.ndarray], X1: Mapping[str, np.ndarray]) -> np.ndarray:
    """Increment of the free strain over a step from (T0, X0) to (T1, X1):

        d eps = sum_i X1_i [eps_i(T1) - eps_i(T0)] + sum_i (X1_i - X0_i) gamma_i(T0).

    For the specific-volume form this is exactly free_strain(T1, X1) - free_strain(T0, X0) (product
    rule, sum_i dX_i = 0); for the expansion form it is the update of Furlan et al. 2025
    (``simulations/UMAT/stresses_heatgen.f90``: alpha of the end state times dT plus gamma dX).
    """
    out = np.zeros(np.broadcast_shapes(np.shape(T0_C), np.shape(T1_C)))
    for phase in PHASES:
        x1 = X1.get(phase)
        if x1 is None:
            continue
        out += x1 * (phase_free_strain(model, phase, T1_C) - phase_free_strain(model, phase, T0_C))
        if phase != "austenite":
            out += (x1 - X0.get(phase, 0.0)) * transformation_strain(model, phase, T0_C)
    return out


def trip_saturation(law: str, f: np.ndarray) -> np.ndarray:
    """phi(f) with eps_tp = K sigma phi(f) under constant uniaxial stress sigma (phi(0) = 0).

    Desalos: phi = f (2 - f) (phi' = 2(1 - f)).  Leblond: phi' = -ln f, frozen at -ln f0 for
    f < f0 = LEBLOND_CUTOFF, so phi = -f ln f0 (f < f0) and f (1 - ln f) - f0 above.
    """
    f = np.clip(f, 0.0, 1.0)
    if law == "desalos":
        return f * (2.0 - f)
    f_safe = np.maximum(f, LEBLOND_CUTOFF)
    return np.where(f < LEBLOND_CUTOFF, -f * np.log(LEBLOND_CUTOFF),
                    f_safe * (1.0 - np.log(f_safe)) - LEBLOND_CUTOFF)


METASTABLE_KEY = "metastable_austenite_yield_factor"
"""Optional [plastic] entry ``{ value, below_T_C, range_factor, source }``: a factor on the austenite yield table's
points below ``below_T_C`` -- the metastable austenite of a quench, where no hot test applies and the row is an
assumption -- so that the calibration can move that part alone (its own, wider prior) and leave the sourced hot part."""


def metastable_austenite_scaled(yield_Pa: Property, factor: MetastableFactor | None, where: str) -> Property:
    """The yield stress with the austenite table's points below ``factor.below_T_C`` times ``factor.value``
    (unchanged without a factor). The table interpolates between the last scaled and the first kept point.

    >>> from quenchsim.inputs.properties import read_property
    >>> row = {"T_C": [20.0, 700.0, 750.0], "value": [300e6, 88e6, 81e6]}
    >>> scaled = metastable_austenite_scaled(read_property({"per_phase": {"default": 1e9, "austenite": row}}, "y"),
    ...                                      MetastableFactor(value=2.0, below_T_C=750.0), "plastic")
    >>> scaled.for_phase("austenite").values.tolist()
    [600000000.0, 176000000.0, 81000000.0]
    """
    if factor is None:
        return yield_Pa
    row = yield_Pa.for_phase("austenite") if yield_Pa.phase_dependent and "austenite" in yield_Pa.phases else None
    if row is None or row.kind != "table":
        raise InputError(f"{where}.{METASTABLE_KEY}", factor.value,
                         "needs yield_Pa.per_phase.austenite as a T_C / value table")
    T, values = cast(np.ndarray, row.T_C), cast(np.ndarray, row.values)
    scaled = dataclasses.replace(row, values=np.where(T < factor.below_T_C, values * factor.value, values))
    return dataclasses.replace(yield_Pa, phases={**yield_Pa.phases, "austenite": scaled})


def solver_options(options: Mapping[str, Any] | SolverOptions | None) -> SolverOptions:
    """The stress solver's options checked, names and values (:class:`quenchsim.inputs.case.SolverOptions`:
    ``plasticity`` and ``trip`` (true), ``austenitizing_T_C`` (None: the mechanics file's), ``newton_rtol`` (1e-8),
    ``max_newton_iterations`` (25)); errors name ``mechanics.<key>``."""
    if isinstance(options, SolverOptions):
        return options
    return from_table(SolverOptions, dict(options or {}), "mechanics")


def _carbon(spec: float | str, key: str, prefix: str, steel: Steel, T_aust_C: float) -> float:
    """A carbon content: a number, or "composition" (bulk C of the steel's [composition]), or "austenitisation"
    (C dissolved in austenite at T_aust, :meth:`quenchsim.inputs.steel.Austenitisation.dissolved_at` -- the value the
    metallurgy uses)."""
    if not isinstance(spec, str):
        return float(spec)
    value = None
    if spec == "composition" and steel.composition is not None:
        value = steel.composition.C
    elif spec == "austenitisation" and steel.austenitisation is not None and steel.composition is not None:
        value = steel.austenitisation.dissolved_at(T_aust_C, steel.composition.wt)["C"]
    if value is None or not 0.0 <= value <= 2.1:
        raise InputError(f"{prefix}.{key}", spec, f"resolves to {value!r}, not a carbon content in [0, 2.1] wt% (the "
                         "steel needs its [composition] and [austenitisation])")
    return float(value)


def _volume_changes(fs: SpecificVolumeStrain, prefix: str, steel: Steel, T_aust_C: float) -> dict[str, float]:
    """dV/V of austenite -> phase at reference_T_C, diluted by the undissolved carbide.

    The matrix of the austenite holds carbon_matrix_wt_pct; the rest of the carbon stays as
    cementite (mass fraction w_c = (C_bulk - C_m)/(C_cem - C_m), lever rule) which does not take
    part in any transformation, so dV/V of the mixture is (1 - phi_c) (a_i + b_i C_m)/100 with the
    carbide volume fraction phi_c = w_c * rho_steel/rho_cementite.
    """
    c_bulk = _carbon(fs.carbon_bulk_wt_pct, "carbon_bulk_wt_pct", prefix, steel, T_aust_C)
    c_m = _carbon(fs.carbon_matrix_wt_pct, "carbon_matrix_wt_pct", prefix, steel, T_aust_C)
    if c_m > c_bulk:
        raise InputError(f"{prefix}.carbon_matrix_wt_pct", c_m, f"must not exceed carbon_bulk_wt_pct = {c_bulk}")
    c_cem = fs.cementite_carbon_wt_pct
    if c_cem < c_bulk:
        raise InputError(f"{prefix}.cementite_carbon_wt_pct", c_cem, f"must be >= carbon_bulk_wt_pct = {c_bulk}")
    phi_c = (c_bulk - c_m) / (c_cem - c_m) * fs.steel_to_cementite_density_ratio
    out = {"austenite": 0.0}
    for phase in PHASES[1:]:
        a, b = getattr(fs.volume_change_pct, phase)
        out[phase] = (1.0 - phi_c) * (a + b * c_m) / 100.0
    return out


def load_mechanics(material: Steel | Mapping[str, Any], options: Mapping[str, Any] | SolverOptions | None = None
                   ) -> MechanicsModel:
    """Build the :class:`MechanicsModel` from a steel's mechanics data (:class:`quenchsim.inputs.steel_mechanics.
    SteelMechanics`, its ``NAME.mechanics.toml``) and the stress solver's options (:func:`solver_options`).

    Thermo-elastic mode = plasticity and trip false. Errors name the field (``NAME.mechanics.<field>``: the file
    materials/NAME.mechanics.toml and the key); the data are checked over the quench's temperatures by
    :func:`check_data`.
    """
    steel = as_steel(material)
    name = steel.name
    prefix = f"{name}.mechanics"
    mech = steel.mechanics
    if mech is None:
        raise InputError(prefix, None, f"material needs materials/{name}.mechanics.toml (or a [mechanics] table)")
    checked = solver_options(options)
    T_aust = (checked.austenitizing_T_C if checked.austenitizing_T_C is not None
              else mech.reference.austenitizing_T_C)
    model_args = dict(name=name, austenitizing_T_C=T_aust, E_Pa=mech.elastic.E_Pa, nu=mech.elastic.nu,
                      **_free_strain_args(mech, prefix, steel, T_aust),
                      annealed_free_strain=0.0, plasticity=checked.plasticity,
                      yield_Pa=None, hardening_Pa=None, hardening_memory=0.0, trip=checked.trip,
                      trip_K_1_Pa=None, trip_law="desalos", newton_rtol=checked.newton_rtol,
                      max_newton_iterations=checked.max_newton_iterations)
    model_args["annealed_free_strain"] = _annealed_free_strain(mech, model_args)
    if checked.plasticity:
        if mech.plastic is None:
            raise InputError("mechanics.plasticity", True, f"{name} has no [plastic] table; set plasticity = false")
        model_args.update(yield_Pa=metastable_austenite_scaled(mech.plastic.yield_Pa,
                                                               mech.plastic.metastable_austenite_yield_factor,
                                                               f"{prefix}.plastic"),
                          hardening_Pa=mech.plastic.hardening_Pa, hardening_memory=mech.plastic.hardening_memory)
    if checked.trip:
        if mech.trip is None:
            raise InputError("mechanics.trip", True, f"{name} has no [trip] table; set trip = false")
        model_args.update(trip_K_1_Pa=mech.trip.K_1_Pa, trip_law=mech.trip.law)
    model = MechanicsModel(**model_args)
    check_data(model, prefix)
    return model


def _free_strain_args(mech: SteelMechanics, prefix: str, steel: Steel, T_aust: float) -> dict[str, Any]:
    """The free-strain fields of :class:`MechanicsModel` from the ``[free_strain]`` table (its form, expansion,
    reference temperature, and the volume changes or the transformation strain)."""
    fs = mech.free_strain
    if isinstance(fs, SpecificVolumeStrain):
        return dict(free_strain_form=fs.form, alpha_1_K=fs.alpha_1_K, reference_T_C=fs.reference_T_C,
                    volume_change=_volume_changes(fs, f"{prefix}.free_strain", steel, T_aust),
                    transformation_strain=None)
    return dict(free_strain_form=fs.form, alpha_1_K=fs.alpha_1_K, reference_T_C=T_aust, volume_change={},
                transformation_strain=fs.transformation_strain)


def _annealed_free_strain(mech: SteelMechanics, model_args: dict[str, Any]) -> float:
    """The free strain of the annealed (room-temperature, pre-quench) state: given, or that of the ``[annealed]``
    phase at its temperature (specific-volume form; the declaration requires the phase and temperature then)."""
    annealed = mech.annealed
    if annealed.free_strain is not None:
        return annealed.free_strain
    provisional = MechanicsModel(**model_args)
    return float(phase_free_strain(provisional, cast(str, annealed.phase), cast(float, annealed.T_C)))


def _phase_values(prop: Property, phase: str, T_C: np.ndarray) -> np.ndarray:
    """The values that define a phase's property over T_C: a table's own values (plus T_C), else the samples."""
    sub = prop.for_phase(phase)
    return np.concatenate([sub(T_C), sub.values]) if sub.kind == "table" else sub(T_C)


def check_data(model: MechanicsModel, prefix: str, T_room_C: float = 20.0) -> None:
    """Physical checks of the parsed data over the temperatures a quench uses, [min(T_ref, T_room), T_aust]:
    E > 0, 0 <= nu < 0.5, yield > 0, hardening >= 0 (a flow curve monotone in strain), product-phase TRIP
    constants in TRIP_K_BOUNDS_1_PA (austenite: 0), expansion tables covering the range.  One-line errors
    naming the material file's field."""
    T_lo = min(model.reference_T_C, T_room_C)
    T = np.linspace(T_lo, model.austenitizing_T_C, 50)
    checks = [("elastic.E_Pa", model.E_Pa, lambda v: v > 0.0, "must be > 0 (a Young's modulus)"),
              ("elastic.nu", model.nu, lambda v: (v >= 0.0) & (v < 0.5), "must be in [0, 0.5)")]
    if model.yield_Pa is not None:
        checks += [("plastic.yield_Pa", model.yield_Pa, lambda v: v > 0.0, "must be > 0"),
                   ("plastic.hardening_Pa", cast(Property, model.hardening_Pa), lambda v: v >= 0.0,   # given with yield
                    "must be >= 0: the flow curve sigma_y + H p must not fall with strain")]
    for name, prop, ok, rule in checks:
        for phase in PHASES:
            values = _phase_values(prop, phase, T)
            bad = ~ok(values)
            if bad.any():
                where = f"{prefix}.{name}" + (f".per_phase.{phase}" if prop.phase_dependent else "")
                raise InputError(where, float(values[bad][0]), rule)
    if model.trip_K_1_Pa is not None:
        lo, hi = TRIP_K_BOUNDS_1_PA
        for phase in PHASES:
            K = _phase_values(model.trip_K_1_Pa, phase, T)
            where = f"{prefix}.trip.K_1_Pa" + (f".per_phase.{phase}" if model.trip_K_1_Pa.phase_dependent else "")
            if phase == "austenite" and np.any(K != 0.0):
                raise InputError(where, float(K[K != 0.0][0]), "austenite does not transform: K must be 0")
            if phase != "austenite" and np.any((K < lo) | (K > hi)):
                raise InputError(where, float(K[(K < lo) | (K > hi)][0]), f"a TRIP constant must lie in [{lo:g}, {hi:g}] 1/Pa")
    for phase in PHASES:
        sub = model.alpha_1_K.for_phase(phase)
        x = cast(np.ndarray, sub.T_C)   # read for a table only, which carries it
        if sub.kind == "table" and (x[0] > T_lo + 1e-9 or x[-1] < model.austenitizing_T_C - 1e-9):
            where = f"{prefix}.free_strain.alpha_1_K" + (f".per_phase.{phase}" if model.alpha_1_K.phase_dependent else "")
            raise InputError(f"{where}.T_C", [float(x[0]), float(x[-1])],
                             f"the table must cover the temperatures used, {T_lo:g}-{model.austenitizing_T_C:g} C")


def austenitized_scale(model: MechanicsModel) -> float:
    """Factor that turns the room-temperature annealed ("before") geometry into the stress-free
    austenitised geometry: x_hot = x_before / (1 + eps_annealed), eps_annealed being the free strain of
    the annealed state relative to austenite at T_aust (``model.annealed_free_strain``)."""
    return 1.0 / (1.0 + model.annealed_free_strain)
