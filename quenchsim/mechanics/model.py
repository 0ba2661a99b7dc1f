"""Mechanical material model: parsing of ``materials/NAME.mechanics.toml`` and the free (thermal +
structural) strain of a phase mixture.

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

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from quenchsim.errors import InputError, require_known_keys
from quenchsim.materials import PHASES, Property, parse_property

FREE_STRAIN_FORMS = ("specific_volume", "expansion")
TRIP_LAWS = ("desalos", "leblond")
OPTION_KEYS = ("plasticity", "trip", "austenitizing_T_C", "newton_rtol", "max_newton_iterations")

TRIP_K_BOUNDS_1_PA = (1e-12, 1e-9)
"""Plausible TRIP constants of the product phases (1/Pa); the published ranges for steels are 4-21e-11
(DEFORM manual, section 10.9, TRNSFP: 4-13e-5 /MPa diffusive, 5-21e-5 /MPa martensitic)."""
PRIOR_KEYS = ("range", "range_factor")
"""Uncertain values carry a prior for calibration: ``{ value = v, range = [lo, hi], source = ... }`` (lo <= v <= hi)
or ``range_factor = f >= 1`` (the value times/divided by f) on any property table or per-phase entry; the run uses
the value."""

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


def _property(table: Mapping[str, Any], key: str, prefix: str) -> Property:
    if key not in table:
        raise InputError(f"{prefix}.{key}", None, "is required")
    return parse_property(table[key], f"{prefix}.{key}")


METASTABLE_KEY = "metastable_austenite_yield_factor"
"""Optional [plastic] entry ``{ value, below_T_C, range_factor, source }``: a factor on the austenite yield table's
points below ``below_T_C`` -- the metastable austenite of a quench, where no hot test applies and the row is an
assumption -- so that the calibration can move that part alone (its own, wider prior) and leave the sourced hot part."""


def metastable_austenite_scaled(plastic: Mapping[str, Any], prefix: str) -> Mapping[str, Any]:
    """The [plastic] table with the austenite yield points below ``below_T_C`` times :data:`METASTABLE_KEY`'s
    value (unchanged without that entry). The table interpolates between the last scaled and the first kept point.

    >>> row = {"T_C": [20.0, 700.0, 750.0], "value": [300e6, 88e6, 81e6]}
    >>> p = {"yield_Pa": {"per_phase": {"austenite": row}},
    ...      METASTABLE_KEY: {"value": 2.0, "below_T_C": 750.0, "range_factor": 3.0}}
    >>> metastable_austenite_scaled(p, "plastic")["yield_Pa"]["per_phase"]["austenite"]["value"]
    [600000000.0, 176000000.0, 81000000.0]
    """
    if METASTABLE_KEY not in plastic:
        return plastic
    where = f"{prefix}.{METASTABLE_KEY}"
    factor = _number(plastic, METASTABLE_KEY, prefix, 1e-3, 1e3)
    entry = plastic[METASTABLE_KEY]
    below = _number(entry, "below_T_C", where, -273.15, 2000.0) if isinstance(entry, Mapping) else None
    if below is None:
        raise InputError(f"{where}.below_T_C", None, "is required: the temperature below which the factor applies")
    row = plastic.get("yield_Pa", {}).get("per_phase", {}).get("austenite") if isinstance(plastic.get("yield_Pa"), Mapping) else None
    if not (isinstance(row, Mapping) and isinstance(row.get("T_C"), list) and isinstance(row.get("value"), list)):
        raise InputError(where, factor, "needs yield_Pa.per_phase.austenite as a T_C / value table")
    scaled = dict(row, value=[v * factor if T < below else v for T, v in zip(row["T_C"], row["value"])])
    per_phase = dict(plastic["yield_Pa"]["per_phase"], austenite=scaled)
    return dict(plastic, yield_Pa=dict(plastic["yield_Pa"], per_phase=per_phase))


def _table(data: Mapping[str, Any], key: str, prefix: str) -> Mapping[str, Any]:
    sub = data.get(key)
    if not isinstance(sub, Mapping):
        raise InputError(f"{prefix}.{key}", sub, "a table is required")
    return sub


def _number(table: Mapping[str, Any], key: str, prefix: str, lo: float = -np.inf, hi: float = np.inf) -> float:
    value = table.get(key)
    if isinstance(value, Mapping):
        value = value.get("value")
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not lo <= float(value) <= hi:
        raise InputError(f"{prefix}.{key}", value, f"must be a number in [{lo}, {hi}]")
    return float(value)


def _carbon(fs: Mapping[str, Any], key: str, prefix: str, material: Mapping[str, Any], T_aust_C: float) -> float:
    """A carbon content: a number, or "composition" (bulk C of the material's [composition]), or
    "austenitisation" (C dissolved in austenite at T_aust, interpolated in the material's
    [austenitisation] dissolved_wt.C over T_aust_C -- the value the metallurgy uses)."""
    spec = fs.get(key)
    if isinstance(spec, Mapping):
        spec = spec.get("value")
    if spec == "composition":
        value = material.get("composition", {}).get("C")
    elif spec == "austenitisation":
        aus = material.get("austenitisation", {})
        try:
            value = float(np.interp(T_aust_C, np.asarray(aus["T_aust_C"], dtype=float),
                                    np.asarray(aus["dissolved_wt"]["C"], dtype=float)))
        except (KeyError, TypeError, ValueError):
            raise InputError(f"{prefix}.{key}", spec, "the material has no [austenitisation] T_aust_C + dissolved_wt.C") from None
    else:
        return _number(fs, key, prefix, 0.0, 2.1)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0.0 <= value <= 2.1:
        raise InputError(f"{prefix}.{key}", spec, f"resolves to {value!r}, not a carbon content in [0, 2.1] wt%")
    return float(value)


def _volume_changes(fs: Mapping[str, Any], prefix: str, material: Mapping[str, Any], T_aust_C: float) -> dict[str, float]:
    """dV/V of austenite -> phase at reference_T_C, diluted by the undissolved carbide.

    The matrix of the austenite holds carbon_matrix_wt_pct; the rest of the carbon stays as
    cementite (mass fraction w_c = (C_bulk - C_m)/(C_cem - C_m), lever rule) which does not take
    part in any transformation, so dV/V of the mixture is (1 - phi_c) (a_i + b_i C_m)/100 with the
    carbide volume fraction phi_c = w_c * rho_steel/rho_cementite.
    """
    c_bulk = _carbon(fs, "carbon_bulk_wt_pct", prefix, material, T_aust_C)
    c_m = _carbon(fs, "carbon_matrix_wt_pct", prefix, material, T_aust_C)
    if c_m > c_bulk:
        raise InputError(f"{prefix}.carbon_matrix_wt_pct", c_m, f"must not exceed carbon_bulk_wt_pct = {c_bulk}")
    c_cem = _number(fs, "cementite_carbon_wt_pct", prefix, c_bulk, 100.0)
    ratio = _number(fs, "steel_to_cementite_density_ratio", prefix, 0.5, 2.0)
    phi_c = (c_bulk - c_m) / (c_cem - c_m) * ratio
    table = _table(fs, "volume_change_pct", prefix)
    out = {"austenite": 0.0}
    for phase in PHASES[1:]:
        coeffs = table.get(phase)
        if isinstance(coeffs, Mapping):
            coeffs = coeffs.get("value")
        if (not isinstance(coeffs, (list, tuple)) or len(coeffs) != 2
                or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in coeffs)):
            raise InputError(f"{prefix}.volume_change_pct.{phase}", coeffs, "must be [a, b] with dV/V (%) = a + b*C")
        out[phase] = (1.0 - phi_c) * (coeffs[0] + coeffs[1] * c_m) / 100.0
    return out


def solver_options(options: Mapping[str, Any] | None) -> dict[str, Any]:
    """The case's ``[mechanics]`` solver options (:data:`OPTION_KEYS`) checked, names and values, with their
    defaults: ``plasticity`` and ``trip`` (true), ``austenitizing_T_C`` (None: the material file's),
    ``newton_rtol`` (1e-8), ``max_newton_iterations`` (25). Errors name ``mechanics.<key>``; the case is checked
    with this when it loads (:mod:`quenchsim.case.parse`), the model is built with it."""
    options = dict(options or {})
    require_known_keys(options, OPTION_KEYS, "mechanics")
    for key in ("plasticity", "trip"):
        if not isinstance(options.get(key, True), bool):
            raise InputError(f"mechanics.{key}", options[key], "must be true or false")
    return {"plasticity": options.get("plasticity", True), "trip": options.get("trip", True),
            "austenitizing_T_C": (_number(options, "austenitizing_T_C", "mechanics", 500.0, 1300.0)
                                  if "austenitizing_T_C" in options else None),
            "newton_rtol": _number(options, "newton_rtol", "mechanics", 1e-14, 1e-2) if "newton_rtol" in options
            else 1e-8,
            "max_newton_iterations": int(_number(options, "max_newton_iterations", "mechanics", 1, 1000))
            if "max_newton_iterations" in options else 25}


def load_mechanics(material: Mapping[str, Any], options: Mapping[str, Any] | None = None) -> MechanicsModel:
    """Build the :class:`MechanicsModel` from ``material["mechanics"]`` and the case ``[mechanics]`` options.

    Options: ``plasticity`` (bool, default true), ``trip`` (bool, default true),
    ``austenitizing_T_C`` (stress-free temperature; default the material file's
    ``[reference] austenitizing_T_C``), ``newton_rtol`` (default 1e-8), ``max_newton_iterations``
    (default 25).  Thermo-elastic mode = plasticity and trip false.  Errors name the field
    (``NAME.mechanics.<field>``: the file materials/NAME.mechanics.toml and the key); priors
    (:data:`PRIOR_KEYS`) are checked by :func:`check_priors`, the data by :func:`check_data`.
    """
    options = dict(options or {})
    name = str(material.get("name", "material"))
    mech = material.get("mechanics")
    prefix = f"{name}.mechanics"
    if not isinstance(mech, Mapping):
        raise InputError(prefix, mech, f"material needs materials/{name}.mechanics.toml (or a [mechanics] table)")
    check_priors(mech, prefix)
    checked = solver_options(options)
    plasticity, trip = checked["plasticity"], checked["trip"]

    reference = _table(mech, "reference", prefix)
    T_aust = (checked["austenitizing_T_C"] if checked["austenitizing_T_C"] is not None
              else _number(reference, "austenitizing_T_C", f"{prefix}.reference", 500.0, 1300.0))
    newton_rtol, max_it = checked["newton_rtol"], checked["max_newton_iterations"]

    elastic = _table(mech, "elastic", prefix)
    E = _property(elastic, "E_Pa", f"{prefix}.elastic")
    nu = _property(elastic, "nu", f"{prefix}.elastic")

    model_args = dict(name=name, austenitizing_T_C=T_aust, E_Pa=E, nu=nu,
                      **_free_strain_args(mech, prefix, material, T_aust),
                      annealed_free_strain=0.0, plasticity=plasticity,
                      yield_Pa=None, hardening_Pa=None, hardening_memory=0.0, trip=trip,
                      trip_K_1_Pa=None, trip_law="desalos", newton_rtol=newton_rtol,
                      max_newton_iterations=max_it)
    model_args["annealed_free_strain"] = _annealed_free_strain(mech, prefix, model_args)
    if plasticity:
        model_args.update(_plastic_args(mech, name, prefix))
    if trip:
        model_args.update(_trip_args(mech, name, prefix))
    model = MechanicsModel(**model_args)
    check_data(model, prefix)
    return model


def _free_strain_args(mech: Mapping[str, Any], prefix: str, material: Mapping[str, Any], T_aust: float
                      ) -> dict[str, Any]:
    """The free-strain fields of :class:`MechanicsModel` from the ``[free_strain]`` table (its form, expansion,
    reference temperature, and the volume changes or the transformation strain)."""
    fs_prefix = f"{prefix}.free_strain"
    fs = _table(mech, "free_strain", prefix)
    form = fs.get("form")
    if form not in FREE_STRAIN_FORMS:
        raise InputError(f"{fs_prefix}.form", form, f"must be one of {FREE_STRAIN_FORMS}")
    alpha = _property(fs, "alpha_1_K", fs_prefix)
    if alpha.phase_dependent and any(alpha.for_phase(p).phase_dependent for p in PHASES):
        raise InputError(f"{fs_prefix}.alpha_1_K", "nested per_phase", "per-phase entries must be constants, tables or polynomials")
    if form == "specific_volume":
        volume_change = _volume_changes(fs, fs_prefix, material, T_aust)
        gamma = None
        ref_T = _number(fs, "reference_T_C", fs_prefix, -273.15, 1500.0)
    else:
        volume_change = {}
        gamma = _property(fs, "transformation_strain", fs_prefix)
        ref_T = T_aust
    return dict(free_strain_form=form, alpha_1_K=alpha, reference_T_C=ref_T, volume_change=volume_change,
                transformation_strain=gamma)


def _annealed_free_strain(mech: Mapping[str, Any], prefix: str, model_args: dict[str, Any]) -> float:
    """The free strain of the annealed (room-temperature, pre-quench) state: given, or that of the ``[annealed]``
    phase at its temperature (specific-volume form)."""
    annealed = _table(mech, "annealed", prefix)
    if "free_strain" in annealed:
        return _number(annealed, "free_strain", f"{prefix}.annealed", -0.1, 0.1)
    if model_args["free_strain_form"] == "specific_volume":
        phase = annealed.get("phase")
        if phase not in PHASES:
            raise InputError(f"{prefix}.annealed.phase", phase, f"must be one of {PHASES} (or give free_strain)")
        T_ann = _number(annealed, "T_C", f"{prefix}.annealed", -273.15, 1500.0)
        provisional = MechanicsModel(**model_args)
        return float(phase_free_strain(provisional, phase, T_ann))
    raise InputError(f"{prefix}.annealed.free_strain", None, "is required for the expansion form")


def _plastic_args(mech: Mapping[str, Any], name: str, prefix: str) -> dict[str, Any]:
    """Yield stress, hardening modulus and hardening memory from the ``[plastic]`` table."""
    if not isinstance(mech.get("plastic"), Mapping):
        raise InputError("mechanics.plasticity", True, f"{name} has no [plastic] table; set plasticity = false")
    plastic = metastable_austenite_scaled(_table(mech, "plastic", prefix), f"{prefix}.plastic")
    return {"yield_Pa": _property(plastic, "yield_Pa", f"{prefix}.plastic"),
            "hardening_Pa": _property(plastic, "hardening_Pa", f"{prefix}.plastic"),
            "hardening_memory": _number(plastic, "hardening_memory", f"{prefix}.plastic", 0.0, 1.0)}


def _trip_args(mech: Mapping[str, Any], name: str, prefix: str) -> dict[str, Any]:
    """Greenwood-Johnson coefficients and saturation law from the ``[trip]`` table."""
    if not isinstance(mech.get("trip"), Mapping):
        raise InputError("mechanics.trip", True, f"{name} has no [trip] table; set trip = false")
    trip_table = _table(mech, "trip", prefix)
    K = _property(trip_table, "K_1_Pa", f"{prefix}.trip")
    law = trip_table.get("law", "desalos")
    if law not in TRIP_LAWS:
        raise InputError(f"{prefix}.trip.law", law, f"must be one of {TRIP_LAWS}")
    return {"trip_K_1_Pa": K, "trip_law": law}


def check_priors(spec: Any, field: str) -> None:
    """Every ``range`` / ``range_factor`` in a material table (recursively): range = [lo, hi] numbers with
    lo <= hi holding the value when the value is a number; range_factor a number >= 1."""
    if isinstance(spec, Mapping):
        if "range" in spec:
            rng = spec["range"]
            ok = (isinstance(rng, (list, tuple)) and len(rng) == 2
                  and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in rng) and rng[0] <= rng[1])
            if not ok:
                raise InputError(f"{field}.range", rng, "must be [lo, hi] numbers with lo <= hi")
            value = spec.get("value")
            if isinstance(value, (int, float)) and not isinstance(value, bool) and not rng[0] <= value <= rng[1]:
                raise InputError(f"{field}.value", value, f"must lie in its range [{rng[0]}, {rng[1]}]")
        if "range_factor" in spec:
            f = spec["range_factor"]
            if isinstance(f, bool) or not isinstance(f, (int, float)) or f < 1.0:
                raise InputError(f"{field}.range_factor", f, "must be a number >= 1")
        for key, sub in spec.items():
            if key not in PRIOR_KEYS:
                check_priors(sub, f"{field}.{key}")


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
