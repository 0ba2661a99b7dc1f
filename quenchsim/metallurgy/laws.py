"""Pure transformation and hardness laws (vectorised over numpy arrays; T in degrees C).

Every coefficient comes from the material file; this module holds only the equations.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from scipy.integrate import quad

R_CAL_MOL_K = 1.98720
"""Gas constant in cal/(mol K) (CODATA 8.314462 J/(mol K) / 4.184 J/cal); Li et al. 1998 give Q in cal/mol."""
R_J_MOL_K = 8.314462
"""Gas constant in J/(mol K) (CODATA)."""

KELVIN = 273.15


def linear_formula(coefficients: Mapping[str, float], composition: Mapping[str, float]) -> float:
    """a0 + sum_j a_j w_j + sum_k b_k sqrt(w_k) for a composition in wt %.

    ``coefficients`` holds ``const`` (a0), element symbols (a_j) and ``sqrt_<element>`` (b_k);
    elements absent from ``composition`` count as zero. This is the form of the Andrews /
    Steven-Haynes Ms formulas, Kirkaldy/Li Bs and the logarithm of Li's composition factors.
    """
    total = float(coefficients.get("const", 0.0))
    for key, a in coefficients.items():
        if key == "const":
            continue
        if key.startswith("sqrt_"):
            total += a * np.sqrt(composition.get(key[5:], 0.0))
        else:
            total += a * composition.get(key, 0.0)
    return total


def li_sigmoid_integral(X: float, exponent: float = 0.4) -> float:
    """Li et al. (1998, Met. Trans. B 29B 661, eq. 13): S(X) = int_0^X dx / [x^{c(1-x)} (1-x)^{c x}], c = 0.4."""
    value, _ = quad(lambda x: 1.0 / (x ** (exponent * (1.0 - x)) * (1.0 - x) ** (exponent * x)), 0.0, X, limit=200)
    return value


def jmak_exponent(X_start: float, X_finish: float, time_ratio: float) -> float:
    """JMAK exponent n through two points of an isothermal curve X = 1 - exp(-(t/tau)^n).

    n = ln[ln(1 - X_f) / ln(1 - X_s)] / ln(t_f / t_s), with ``time_ratio`` = t_f / t_s.
    """
    return float(np.log(np.log1p(-X_finish) / np.log1p(-X_start)) / np.log(time_ratio))


def li_rate(T_C: np.ndarray, T_upper_C: float, ln_F: float, beta_grain: float, grain_ASTM: float,
            n_undercooling: float, Q_cal_mol: float) -> np.ndarray:
    """1/tau_1(T) of Li et al. 1998 (eqs. 18-23): 2^{beta G} (T_u - T)^n exp(-Q/RT) / F, in 1/s.

    tau_1 is the time scale of the isothermal curve t(X) = tau_1 S(X); zero at and above T_upper
    (Ae1 for pearlite, Bs for bainite), where there is no driving force.
    """
    T = np.asarray(T_C, dtype=float)
    dT = np.maximum(T_upper_C - T, 0.0)
    if float(n_undercooling).is_integer():  # dT*dT*dT is several times faster than dT**3.0
        power = np.ones_like(dT)
        for _ in range(int(n_undercooling)):
            power = power * dT
    else:
        power = dT**n_undercooling
    return np.exp(beta_grain * grain_ASTM * np.log(2.0) - ln_F - Q_cal_mol / (R_CAL_MOL_K * (T + KELVIN))) * power


def c_curve_ln_inverse_tau(T_C: np.ndarray, T_upper_C: float, T_ref_C: float, tau_ref_s: float,
                           undercooling_exponent: float, Q_J_mol: float) -> np.ndarray:
    """ln(1/tau) of the C-curve law fitted to diagram data (-inf at and above T_upper).

    1/tau(T) = (1/tau_ref) [(T_u - T)/(T_u - T_ref)]^m exp[-(Q/R)(1/T - 1/T_ref)] (T in K in the Arrhenius
    term): the undercooling x diffusion form of Zener-Hillert / Kirkaldy (Kirkaldy & Venugopalan 1984; Li et
    al. 1998 eqs. 18-23), written about a reference temperature T_ref so that tau_ref (the JMAK time constant
    at T_ref), m and Q are separately identifiable in a fit.
    """
    T = np.asarray(T_C, dtype=float)
    dT = T_upper_C - T
    with np.errstate(divide="ignore", invalid="ignore"):
        ln_under = np.log(np.where(dT > 0.0, dT / (T_upper_C - T_ref_C), 1.0))
    value = (-np.log(tau_ref_s) + undercooling_exponent * ln_under
             - Q_J_mol / R_J_MOL_K * (1.0 / (T + KELVIN) - 1.0 / (T_ref_C + KELVIN)))
    return np.where(dT > 0.0, value, -np.inf)


def koistinen_marburger(T_C: np.ndarray, Ms_C: float | np.ndarray, alpha_per_K: float) -> np.ndarray:
    """Koistinen & Marburger (1959): fraction of austenite turned to martensite, 1 - exp(-alpha (Ms - T)) below Ms
    (``Ms_C`` may be an array: the incremental form of :func:`quenchsim.metallurgy.advance` passes the lowest
    temperature reached so far)."""
    return -np.expm1(-alpha_per_K * np.maximum(Ms_C - np.asarray(T_C, dtype=float), 0.0))


def maynier_hv(coefficients: Mapping[str, Mapping[str, float]], composition: Mapping[str, float],
               log10_rate_C_h: np.ndarray) -> np.ndarray:
    """Maynier et al. (1978) hardness of one product: HV = A(w) + B(w) log10(V_r), V_r in degC/h at 700 C.

    ``coefficients`` = {"base": {...}, "rate": {...}}, each a :func:`linear_formula`.
    """
    return linear_formula(coefficients["base"], composition) + linear_formula(coefficients["rate"], composition) * log10_rate_C_h
