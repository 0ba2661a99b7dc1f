"""EHL laws of the roller-race line contacts (pure functions, numba-compiled; float64 scalars or arrays).

- Hertz line contact: p_h = sqrt(w E' / (2 pi R)), w = Q / l (Johnson, Contact Mechanics, 1985, eq. 4.45).
- Pan & Hamrock (J. Tribol. 111, 1989) central film thickness of an isothermal line contact:
      h_c / R = 2.922 W^-0.166 U^0.692 G^0.470,  W = w/(E'R), U = eta0 u_e/(E'R), G = alpha E'.
- Thermal (inlet shear heating) reduction of the film, with slide-roll ratio S and thermal loading
  L = beta eta0 u_e^2 / k_f: phi_T = (1 - 13.2 (p_h/E') L^0.42) / (1 + 0.213 (1 + 2.23 S^0.83) L^0.64)
  (Gupta, Cheng, Zhu, Forster & Schrand, Tribol. Trans. 35, 1992; used here in place of the
  Ghosh-Pandey inlet-zone fit of the reference, which reduces the film by the same mechanism).
- Traction: Kannel-Walowit-type curve of the film, mu_f = mu_lim (1 - exp(-|S|/S0)) sign(S), blended
  with boundary friction mu_b (same shape) when the film breaks down: weight of the film
  w = clip((Lambda - Lambda_lo) / (Lambda_hi - Lambda_lo), 0, 1), Lambda = h_c / sigma (Tallian's
  film-parameter regimes: boundary below 1, full film above 3; Hamrock et al. 2004, ch. 23).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from quenchsim.bearings.big_end.contact import FloatOrArray

PAN_HAMROCK_COEFFICIENT = 2.922  # Pan & Hamrock 1989, central film thickness
PAN_HAMROCK_W_EXP = -0.166
PAN_HAMROCK_U_EXP = 0.692
PAN_HAMROCK_G_EXP = 0.470
GUPTA_LOAD_COEFF = 13.2  # Gupta et al. 1992 thermal reduction factor
GUPTA_LOAD_EXP = 0.42
GUPTA_DEN_COEFF = 0.213
GUPTA_SLIP_COEFF = 2.23
GUPTA_SLIP_EXP = 0.83
GUPTA_DEN_EXP = 0.64


@njit(cache=True)
def hertz_line_max_pressure(load_per_length_n_m: FloatOrArray, radius_m: FloatOrArray,
                            e_star_pa: float) -> FloatOrArray:
    """Maximum Hertz pressure p_h = sqrt(w E' / (2 pi R)) of a line contact [Pa]."""
    return np.sqrt(np.maximum(load_per_length_n_m, 0.0) * e_star_pa / (2.0 * np.pi * radius_m))


@njit(cache=True)
def pan_hamrock_central_film(load_per_length_n_m: FloatOrArray, entrainment_m_s: FloatOrArray,
                             radius_m: FloatOrArray, e_star_pa: float, viscosity_pa_s: float,
                             pressure_viscosity_1_pa: float) -> FloatOrArray:
    """Isothermal central film thickness h_c [m] (Pan & Hamrock 1989), h_c = R 2.922 W^-0.166 U^0.692 G^0.47."""
    er = e_star_pa * radius_m
    w = np.maximum(load_per_length_n_m, 1e-9) / er
    u = viscosity_pa_s * np.maximum(entrainment_m_s, 1e-12) / er
    g = pressure_viscosity_1_pa * e_star_pa
    return radius_m * PAN_HAMROCK_COEFFICIENT * w**PAN_HAMROCK_W_EXP * u**PAN_HAMROCK_U_EXP * g**PAN_HAMROCK_G_EXP


@njit(cache=True)
def thermal_loading(temperature_viscosity_1_k: float, viscosity_pa_s: float,
                    entrainment_m_s: FloatOrArray, conductivity_w_mk: float) -> FloatOrArray:
    """Thermal loading parameter L = beta eta0 u_e^2 / k_f (dimensionless)."""
    return temperature_viscosity_1_k * viscosity_pa_s * entrainment_m_s**2 / conductivity_w_mk


@njit(cache=True)
def thermal_reduction_factor(max_pressure_pa: FloatOrArray, e_star_pa: float, loading: FloatOrArray,
                             slide_roll: FloatOrArray) -> FloatOrArray:
    """phi_T = (1 - 13.2 (p_h/E') L^0.42) / (1 + 0.213 (1 + 2.23 |S|^0.83) L^0.64), clipped to [0, 1]."""
    num = 1.0 - GUPTA_LOAD_COEFF * (max_pressure_pa / e_star_pa) * loading**GUPTA_LOAD_EXP
    den = 1.0 + GUPTA_DEN_COEFF * (1.0 + GUPTA_SLIP_COEFF * np.abs(slide_roll) ** GUPTA_SLIP_EXP) \
        * loading**GUPTA_DEN_EXP
    return np.minimum(np.maximum(num / den, 0.0), 1.0)


@njit(cache=True)
def traction_coefficient(slide_roll: FloatOrArray, film_parameter: FloatOrArray, limiting_traction: float,
                         slide_roll_scale: float, boundary_friction: float, film_lo: float,
                         film_hi: float) -> FloatOrArray:
    """Signed traction coefficient mu(S, Lambda) (Kannel-Walowit-type film + boundary friction)."""
    shape = np.sign(slide_roll) * (1.0 - np.exp(-np.abs(slide_roll) / slide_roll_scale))
    weight = np.minimum(np.maximum((film_parameter - film_lo) / (film_hi - film_lo), 0.0), 1.0)
    return (weight * limiting_traction + (1.0 - weight) * boundary_friction) * shape
