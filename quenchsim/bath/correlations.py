"""Heat-transfer and free-jet correlations used by the bath model (pure, vectorised over numpy arrays).

Each function states its equation and source. Where the `ht` package has the correlation it is called
directly (the ones used here are plain arithmetic and accept arrays); the few written out here are
checked against `ht`'s scalar versions in tests/test_bath_correlations.py.
"""

from __future__ import annotations

import math

import numpy as np
import ht

STEFAN_BOLTZMANN = 5.670374419e-8  # W/(m^2 K^4), CODATA 2018
GRAVITY = 9.80665  # m/s^2

# Round free jet (Pope, Turbulent Flows, 2000, Table 5.1, after Hussein, Capp & George 1994):
# centre-line decay U_c/U_0 = B d/(x - x_0) with B = 5.8, spreading of the half-velocity radius
# dr_1/2/dx = S = 0.094. x_0 ~ 0 is taken, so the potential core ends at x_c = B d (U_c = U_0 there).
JET_DECAY_B = 5.8
JET_SPREAD_S = 0.094
# Plane turbulent wall jet (Launder & Rodi, Annu. Rev. Fluid Mech. 15 (1983) 429; Rajaratnam, Turbulent
# Jets, 1976): U_m/U_0 = 3.5 (x/b_0)^(-1/2), i.e. U_m = 3.5 sqrt(J'/(rho x)) with J' = rho U_0^2 b_0 the
# momentum flux per unit width.
WALL_JET_C = 3.5
# Round jet in a cross-flow (Pratte & Baines, J. Hydraul. Div. ASCE 93 (1967) 53): centre-line trajectory
# y/(R d) = A (x/(R d))^m with R = U_jet/U_cross, y the penetration along the exit direction and x the
# drift with the cross-flow; A = 2.05, m = 0.28.
CROSSFLOW_A = 2.05
CROSSFLOW_M = 0.28
MAX_DRIFT_M = 1e3
"""Cap of the drift (m): a jet this weak never reaches the wall (its arrival speed is then ~0)."""


def jet_centreline_velocity(U0_m_s: np.ndarray | float, d_m: np.ndarray | float, x_m: np.ndarray | float
                            ) -> np.ndarray:
    """Centre-line speed of a submerged round jet at distance x: U_0 min(1, B d/x) (potential core, then 1/x)."""
    x = np.maximum(np.asarray(x_m, dtype=float), 1e-12)
    return np.asarray(U0_m_s, dtype=float) * np.minimum(1.0, JET_DECAY_B * np.asarray(d_m, dtype=float) / x)


def jet_half_width(d_m: np.ndarray | float, x_m: np.ndarray | float) -> np.ndarray:
    """Half-velocity radius of a round jet: max(d/2, S x)."""
    return np.maximum(0.5 * np.asarray(d_m, dtype=float), JET_SPREAD_S * np.asarray(x_m, dtype=float))


def crossflow_drift(U0_m_s: float, d_m: float, penetration_m: float, U_cross_m_s: float) -> float:
    """Drift x of a round jet with the cross-flow while it penetrates ``penetration_m`` toward the wall:
    x = R d (y/(A R d))^(1/m) (Pratte & Baines 1967), 0 without cross-flow."""
    if U_cross_m_s == 0.0:
        return 0.0
    if U0_m_s == 0.0:
        return MAX_DRIFT_M
    Rd = U0_m_s / abs(U_cross_m_s) * d_m
    log_x = math.log(Rd) + (math.log(penetration_m) - math.log(CROSSFLOW_A * Rd)) / CROSSFLOW_M
    return math.exp(min(log_x, math.log(MAX_DRIFT_M)))


def plane_wall_jet_velocity(J_per_width_N_m: np.ndarray, rho_kg_m3: float, x_m: np.ndarray) -> np.ndarray:
    """Maximum speed of a plane wall jet of momentum flux J' (N/m) at run x: 3.5 sqrt(J'/(rho x))."""
    x = np.maximum(np.asarray(x_m, dtype=float), 1e-12)
    return WALL_JET_C * np.sqrt(np.asarray(J_per_width_N_m, dtype=float) / (rho_kg_m3 * x))


def flat_plate_local_nusselt(Re_x: np.ndarray, Pr: np.ndarray) -> np.ndarray:
    """Local Nusselt number Nu_x of a flat-plate boundary layer at run x.

    For a plate-average law Nu_L = C Re_L^m Pr^a the local value is Nu_x = m Nu_L(Re_x) (differentiate
    x h_avg(x)). Laminar: Churchill & Ozoe (1973) average 0.6774 Re^0.5 Pr^(1/3) (1 + (0.0468/Pr)^(2/3))^-0.25
    (ht.Nu_horizontal_plate_laminar_Churchill_Ozoe), m = 1/2; turbulent: Kreith average 0.036 Re^0.8 Pr^(1/3)
    (ht.Nu_horizontal_plate_turbulent_Kreith), m = 0.8 -- local 0.0288 Re^0.8 Pr^(1/3). Wall jets are turbulent
    from the impingement on (Launder & Rodi 1983), so the larger of the two is taken (the laminar form only
    wins at low Re).
    """
    Re = np.maximum(np.asarray(Re_x, dtype=float), 0.0)
    # ht annotates its laws float -> float; they are numpy arithmetic and take arrays
    laminar = 0.5 * ht.Nu_horizontal_plate_laminar_Churchill_Ozoe(Re=Re, Pr=Pr)  # type: ignore[arg-type]
    turbulent = 0.8 * ht.Nu_horizontal_plate_turbulent_Kreith(Re=Re, Pr=Pr)  # type: ignore[arg-type]
    return np.maximum(laminar, turbulent)


def vertical_plate_natural_nusselt(Pr: np.ndarray, Gr: np.ndarray) -> np.ndarray:
    """Churchill & Chu (1975) vertical plate, all Ra: Nu = (0.825 + 0.387 Ra^(1/6)/(1 + (0.492/Pr)^(9/16))^(8/27))^2
    (ht.Nu_vertical_plate_Churchill)."""
    # ht annotates the law float -> float; it is numpy arithmetic and takes arrays
    return ht.Nu_vertical_plate_Churchill(Pr=Pr, Gr=np.maximum(Gr, 0.0))  # type: ignore[arg-type, return-value]


def horizontal_plate_natural_nusselt(Pr: np.ndarray, Gr: np.ndarray, facing_up: np.ndarray) -> np.ndarray:
    """McAdams (1954) horizontal plate with L = area/perimeter (as ht.Nu_horizontal_plate_McAdams).

    Hot face up (buoyancy-driven plume): Nu = 0.54 Ra^(1/4) for Ra <= 1e7, 0.15 Ra^(1/3) above;
    hot face down: Nu = 0.27 Ra^(1/4) for Ra <= 1e10, 0.15 Ra^(1/3) above.
    """
    Ra = np.maximum(np.asarray(Pr, dtype=float) * np.asarray(Gr, dtype=float), 0.0)
    up = np.where(Ra <= 1e7, 0.54 * Ra**0.25, 0.15 * Ra ** (1.0 / 3.0))
    down = np.where(Ra <= 1e10, 0.27 * Ra**0.25, 0.15 * Ra ** (1.0 / 3.0))
    return np.where(facing_up, up, down)


def churchill_usagi(a: np.ndarray, b: np.ndarray, n: float = 3.0) -> np.ndarray:
    """(a^n + b^n)^(1/n): Churchill & Usagi (1972) blending; n = 3 for assisting forced + natural
    convection (Churchill, 1977)."""
    return (np.asarray(a, dtype=float) ** n + np.asarray(b, dtype=float) ** n) ** (1.0 / n)


def zuber_critical_heat_flux(sigma_N_m: float, h_fg_J_kg: float, rho_l: float, rho_v: float, K: float) -> float:
    """Zuber (1959) pool-boiling critical heat flux q_max = K h_fg rho_v^0.5 (sigma g (rho_l - rho_v))^0.25
    (ht.Zuber)."""
    return float(ht.Zuber(sigma=sigma_N_m, Hvap=h_fg_J_kg, rhol=rho_l, rhog=rho_v, K=K))


def ivey_morris_factor(rho_l: float, rho_v: float, cp_l: float, subcooling_K: float, h_fg_J_kg: float,
                       C: float) -> float:
    """Ivey & Morris (1962) subcooling factor on the critical heat flux:
    1 + C (rho_l/rho_v)^0.75 c_p dT_sub / h_fg (C = 0.1)."""
    return 1.0 + C * (rho_l / rho_v) ** 0.75 * cp_l * max(subcooling_K, 0.0) / h_fg_J_kg


def rohsenow_heat_flux(dT_excess_K: np.ndarray | float, rho_l: float, rho_v: float, mu_l: float, k_l: float, cp_l: float,
                       h_fg_J_kg: float, sigma_N_m: float, Csf: float, n: float) -> np.ndarray:
    """Rohsenow (1952) nucleate boiling q = mu h_fg sqrt(g (rho_l-rho_v)/sigma) (c_p dT_e/(C_sf h_fg Pr^n))^3.

    ht.Rohsenow returns h = q/dT_e; this returns q (W/m^2) and 0 for dT_e <= 0."""
    dT = np.maximum(np.asarray(dT_excess_K, dtype=float), 0.0)
    h = ht.Rohsenow(rhol=rho_l, rhog=rho_v, mul=mu_l, kl=k_l, Cpl=cp_l, Hvap=h_fg_J_kg, sigma=sigma_N_m,
                    Te=np.maximum(dT, 1e-12), Csf=Csf, n=n)
    return np.where(dT > 0.0, h * dT, 0.0)


def bromley_film_htc(dT_K: np.ndarray, L_m: np.ndarray, k_v: float, rho_v: np.ndarray, rho_l: float, mu_v: float,
                     h_fg_eff_J_kg: np.ndarray, C: float) -> np.ndarray:
    """Bromley (1950) natural-convection film boiling h = C [k_v^3 rho_v (rho_l - rho_v) g h_fg' / (mu_v L dT)]^(1/4)
    with h_fg' = h_fg + 0.4 c_pv dT (C = 0.62)."""
    dT = np.maximum(np.asarray(dT_K, dtype=float), 1e-9)
    return C * (k_v**3 * rho_v * (rho_l - rho_v) * GRAVITY * h_fg_eff_J_kg / (mu_v * L_m * dT)) ** 0.25


def forced_film_htc(U_m_s: np.ndarray, dT_K: np.ndarray, L_m: np.ndarray, k_v: float, rho_v: np.ndarray,
                    h_fg_eff_J_kg: np.ndarray, C: float) -> np.ndarray:
    """Bromley, LeRoy & Robbers (1953) forced-flow film boiling h = C sqrt(U k_v rho_v h_fg' / (L dT)) (C = 2.7)."""
    dT = np.maximum(np.asarray(dT_K, dtype=float), 1e-9)
    return C * np.sqrt(np.maximum(U_m_s, 0.0) * k_v * rho_v * h_fg_eff_J_kg / (L_m * dT))


def radiation_htc(T_surface_C: np.ndarray, T_ambient_C: np.ndarray | float, emissivity: float) -> np.ndarray:
    """Linearised grey-body radiation h_r = eps sigma (T_s^2 + T_a^2)(T_s + T_a), T in K
    (so that h_r (T_s - T_a) = eps sigma (T_s^4 - T_a^4))."""
    Ts = np.asarray(T_surface_C, dtype=float) + 273.15
    Ta = np.asarray(T_ambient_C, dtype=float) + 273.15
    return emissivity * STEFAN_BOLTZMANN * (Ts**2 + Ta**2) * (Ts + Ta)


# --- Impinging round jets (Martin 1977) ------------------------------------------------------------------------------
# H. Martin, "Heat and mass transfer between impinging gas jets and solid surfaces", Adv. Heat Transfer 13 (1977)
# 1-60, as given in Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, sec. 7.7 (single round nozzle, SRN;
# array of round nozzles, ARN). Fitted to the measurements Martin compiled: SRN 2e3 <= Re <= 4e5, 2 <= H/D <= 12,
# 2.5 <= r/D <= 7.5; ARN 2e3 <= Re <= 1e5, 2 <= H/D <= 12, 0.004 <= A_r <= 0.04.
MARTIN_RE_RANGE = (2.0e3, 4.0e5)
MARTIN_H_D_RANGE = (2.0, 12.0)
MARTIN_SRN_R_D_RANGE = (2.5, 7.5)
MARTIN_ARN_AREA_RANGE = (0.004, 0.04)
MARTIN_PR_EXPONENT = 0.42
# Local shape inside r/D < 2.5 (the stagnation zone Martin's average does not resolve): R. J. Goldstein,
# A. I. Behbahani, K. K. Heppelmann, "Streamwise distribution of the recovery factor and the local heat transfer
# coefficient to an impinging circular air jet", Int. J. Heat Mass Transfer 29 (1986) 1227, local fit to their
# measurements Nu/Re^0.76 = (24 - |H/D - 7.75|)/(533 + 44 (r/D)^1.394) (Re 6.1e4-1.24e5, H/D 6-12): the radial shape
# 533/(533 + 44 x^1.394) is used, scaled to Martin's local value at r/D = 2.5.
GOLDSTEIN_A, GOLDSTEIN_B, GOLDSTEIN_N = 533.0, 44.0, 1.394


def martin_reynolds_function(Re: np.ndarray) -> np.ndarray:
    """Martin's F_1(Re) = 2 Re^(1/2) (1 + 0.005 Re^0.55)^(1/2) (single round nozzle)."""
    Re = np.maximum(np.asarray(Re, dtype=float), 0.0)
    return 2.0 * np.sqrt(Re) * np.sqrt(1.0 + 0.005 * Re**0.55)


def martin_srn_geometry(r_D: np.ndarray, H_D: np.ndarray) -> np.ndarray:
    """Martin's G for a single round nozzle as a function of r/D and H/D:
    G = (D/r)(1 - 1.1 D/r)/(1 + 0.1 (H/D - 6) D/r) (Incropera's 2 A_r^0.5 (1 - 2.2 A_r^0.5)/(1 + 0.2 (H/D - 6) A_r^0.5),
    A_r = D^2/(4 r^2))."""
    x = np.asarray(r_D, dtype=float)
    return (1.0 / x) * (1.0 - 1.1 / x) / (1.0 + 0.1 * (np.asarray(H_D, dtype=float) - 6.0) / x)


def martin_srn_nusselt(Re: np.ndarray, Pr: np.ndarray, r_D: np.ndarray, H_D: np.ndarray) -> np.ndarray:
    """Area-mean Nusselt number (on D) over the disc of radius r round a single round jet's stagnation point:
    Nu = Pr^0.42 G(r/D, H/D) F_1(Re) (Martin 1977)."""
    return np.asarray(Pr, dtype=float) ** MARTIN_PR_EXPONENT * martin_srn_geometry(r_D, H_D) \
        * martin_reynolds_function(Re)


def martin_arn_nusselt(Re: np.ndarray, Pr: np.ndarray, area_ratio: np.ndarray, H_D: np.ndarray) -> np.ndarray:
    """Area-mean Nusselt number (on D) of an array of round nozzles, A_r = nozzle area / cell area:
    Nu = Pr^0.42 K G F_2 with K = (1 + ((H/D)/(0.6/A_r^0.5))^6)^-0.05, G = 2 A_r^0.5 (1 - 2.2 A_r^0.5)/(1 + 0.2 (H/D - 6)
    A_r^0.5), F_2 = 0.5 Re^(2/3) (Martin 1977)."""
    s = np.sqrt(np.asarray(area_ratio, dtype=float))
    H_D = np.asarray(H_D, dtype=float)
    K = (1.0 + (H_D / (0.6 / s)) ** 6) ** -0.05
    G = 2.0 * s * (1.0 - 2.2 * s) / (1.0 + 0.2 * (H_D - 6.0) * s)
    return np.asarray(Pr, dtype=float) ** MARTIN_PR_EXPONENT * K * G * 0.5 * np.asarray(Re, dtype=float) ** (2.0 / 3.0)


def martin_srn_local_shape(r_D: np.ndarray, H_D: np.ndarray | float) -> np.ndarray:
    """Local Nusselt number of a single round jet over Pr^0.42 F_1(Re), as a function of r/D and H/D.

    For r/D >= 2.5 it is the local value whose disc mean is Martin's G: Nu_loc = d(r^2 Nu_mean)/dr / (2 r), i.e.
    (x^2 + 2 a x - 1.1 a) / (2 x (x + a)^2) with x = r/D, a = 0.1 (H/D - 6) (exact: its mean over any disc 2.5 <= r/D
    reproduces G up to the constant of the inner zone). Inside, the measured radial shape of Goldstein et al. (1986),
    533/(533 + 44 x^1.394), continued from Martin's value at r/D = 2.5 (stagnation point 1.30 times that value). H/D is
    clamped to Martin's 2-12.
    """
    x = np.maximum(np.asarray(r_D, dtype=float), 0.0)
    a = 0.1 * (np.clip(np.asarray(H_D, dtype=float), *MARTIN_H_D_RANGE) - 6.0)
    x0 = MARTIN_SRN_R_D_RANGE[0]
    xo = np.maximum(x, x0)
    outer = (xo**2 + 2.0 * a * xo - 1.1 * a) / (2.0 * xo * (xo + a) ** 2)
    at_x0 = (x0**2 + 2.0 * a * x0 - 1.1 * a) / (2.0 * x0 * (x0 + a) ** 2)

    def goldstein(y: np.ndarray | float) -> np.ndarray:
        return GOLDSTEIN_A / (GOLDSTEIN_A + GOLDSTEIN_B * np.asarray(y, dtype=float) ** GOLDSTEIN_N)

    return np.where(x >= x0, outer, at_x0 * goldstein(x) / goldstein(x0))


def goldstein_local_nusselt(Re: np.ndarray, r_D: np.ndarray, H_D: np.ndarray) -> np.ndarray:
    """Goldstein, Behbahani & Heppelmann (1986) local Nusselt number of a round air jet (their fit to measurements,
    Re 6.1e4-1.24e5, H/D 6-12): Nu = Re^0.76 (24 - |H/D - 7.75|)/(533 + 44 (r/D)^1.394)."""
    return np.asarray(Re, dtype=float) ** 0.76 * (24.0 - np.abs(np.asarray(H_D, dtype=float) - 7.75)) \
        / (GOLDSTEIN_A + GOLDSTEIN_B * np.asarray(r_D, dtype=float) ** GOLDSTEIN_N)


# --- Boiling under forced flow: critical heat flux and the collapse of the vapour film -------------------------------
# Y. Katto, C. Kurata, "Critical heat flux of saturated convective boiling on uniformly heated plates in a parallel
# flow", Int. J. Multiphase Flow 6 (1980) 575: q_c/(G h_fg) = 0.186 (rho_v/rho_l)^0.559 (sigma rho_l/(G^2 l))^0.264,
# G = rho_l U, l the heated length along the flow (fitted to water and R-113 data).
KATTO_KURATA_C, KATTO_KURATA_DENSITY, KATTO_KURATA_WEBER = 0.186, 0.559, 0.264
# P. J. Berenson, "Film-boiling heat transfer from a horizontal surface", J. Heat Transfer 83 (1961) 351: minimum
# film boiling superheat dT_min = 0.127 (rho_v h_fg/k_v) [g drho/(rho_l + rho_v)]^(2/3) [sigma/(g drho)]^(1/2)
# [mu_v/(g drho)]^(1/3) (saturated liquid; every bracket is dimensional, the product is in K).
BERENSON_C = 0.127


def katto_kurata_critical_heat_flux(U_m_s: np.ndarray, length_m: np.ndarray, rho_l: float, rho_v: float,
                                    h_fg_J_kg: float, sigma_N_m: float) -> np.ndarray:
    """Saturated critical heat flux (W/m^2) of flow parallel to a heated plate of length l (Katto & Kurata 1980);
    0 without flow."""
    U = np.maximum(np.asarray(U_m_s, dtype=float), 0.0)
    G = rho_l * U
    l = np.maximum(np.asarray(length_m, dtype=float), 1e-6)
    with np.errstate(divide="ignore"):
        weber = np.where(G > 0.0, sigma_N_m * rho_l / (np.maximum(G, 1e-300) ** 2 * l), np.inf)
    return np.where(G > 0.0, KATTO_KURATA_C * G * h_fg_J_kg * (rho_v / rho_l) ** KATTO_KURATA_DENSITY
                    * np.minimum(weber, 1e300) ** KATTO_KURATA_WEBER, 0.0)


def berenson_minimum_film_superheat(rho_l: float, rho_v: float, h_fg_J_kg: float, k_v: float, mu_v: float,
                                    sigma_N_m: float) -> float:
    """Berenson (1961) saturated minimum film boiling superheat T_MFB - T_b (K)."""
    drho = rho_l - rho_v
    return float(BERENSON_C * rho_v * h_fg_J_kg / k_v * (GRAVITY * drho / (rho_l + rho_v)) ** (2.0 / 3.0)
                 * math.sqrt(sigma_N_m / (GRAVITY * drho)) * (mu_v / (GRAVITY * drho)) ** (1.0 / 3.0))


def subcooled_film_collapse_superheat(dT_min_sat_K: float, h_liquid_W_m2K: np.ndarray, subcooling_K: float,
                                      collapse_resistance_m2K_W: float) -> np.ndarray:
    """Wall superheat T_L - T_b at which a subcooled vapour film collapses:
    dT_L = dT_min,sat + R_c h_l (T_b - T_oil).

    A vapour film lives on the difference between the heat it conducts from the wall and the heat its liquid face
    loses to the subcooled liquid, h_l (T_b - T_oil); with a film of conduction resistance R_c at its thinnest stable
    thickness (R_c = delta_c/k_v) it collapses once that loss reaches the conduction dT_L/R_c. Linear in subcooling as
    measured by Dhir & Purohit (Nucl. Eng. Des. 47 (1978) 49: dT_min = 101 + 8 dT_sub K, water on spheres) and rising
    with the liquid-side coefficient h_l, i.e. with flow speed (faster liquid: earlier wetting, Tensi's wetting
    kinematics; strong agitation removes the vapour stage, Totten/MacKenzie). dT_min,sat: Berenson (1961).
    """
    return dT_min_sat_K + collapse_resistance_m2K_W * np.asarray(h_liquid_W_m2K, dtype=float) * max(subcooling_K, 0.0)
