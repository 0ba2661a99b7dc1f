"""HTC(T_surface) per boundary point: boiling curve of the oil under the local flow, and air cooling.

For each point the heat flux q(T_s) (W/m^2) is built on a uniform surface-temperature grid, then
h = q/(T_s - T_oil) is stored; :class:`BoundaryHTC` interpolates it vectorised in the time loop.

Regimes (T_b boiling point, T_L Leidenfrost temperature, T_oil bath temperature):

* Convection, T_s <= T_b: h_c = ((sum_i h_i^2)^(1/2))^3 + h_nat^3)^(1/3) -- each nozzle row gives its impinging-jet
  coefficient h_i = (k/D) Pr^0.42 F_1(U_0 D/nu) <l>_c (Martin 1977, circumferential mean of the local shape,
  quenchsim.bath.flow), the rotation and bulk agitation a local flat-plate coefficient h_i = k Nu_x(U_i x_i/nu,
  Pr)/x_i; combined in quadrature, then blended with natural convection (Churchill 1977, n = 3). Liquid properties
  at the film temperature (T_s + T_oil)/2, capped at (T_b + T_oil)/2 once the wall boils. Martin's correlation is
  fitted for 2e3 <= Re <= 4e5; below (the slow ID jets, Re ~ 300-2000 in the reference oil) it is continued with its
  own laminar-like Re^0.5 form.
* Nucleate boiling, T_b < T_s <= T_peak: q = h_c (T_s - T_oil) + min(q_Rohsenow(T_s - T_b), q_max) --
  forced convection and boiling added (Rohsenow 1952 superposition for subcooled flow boiling), the
  boiling part capped by the critical flux q_max = max(Zuber pool, Katto & Kurata 1980 flow along the wall, each
  flow source at its local speed and run length) raised for subcooling (Ivey & Morris 1962) -- the boiling peak rises with the local
  speed and the subcooling. T_peak is where the Rohsenow flux meets q_max (closed form, Rohsenow q ~ dT_e^3).
* Transition boiling, T_peak < T_s < T_L: q falls log-linearly in T_s from q(T_peak) to q_film(T_L); the
  region is at least ``transition_min_width_K`` wide (T_peak <= T_L - width), as measured still-oil curves
  climb from the film level to the peak over tens of kelvin, not at a point.
* Film boiling, T_s >= T_L: q = h_f (T_s - T_b) + 0.75 h_rad (T_s - T_oil) + h_c (T_b - T_oil): vapour-film
  conduction (Bromley 1950 natural; Bromley-LeRoy-Robbers 1953 forced, per flow source, combined in
  quadrature like h_c; natural and forced blended n = 3), radiation
  through the film (Bromley's 3/4), and convection from the film's liquid face (at T_b) into the
  subcooled oil.
* Film collapse: T_L = T_b + dT_min,sat + R_c h_l (T_b - T_oil) (:func:`film_collapse_temperature`): the saturated
  minimum film boiling superheat (Berenson 1961) raised in proportion to the heat the film's liquid face loses to the
  subcooled oil, h_l the single-phase coefficient at the wall's boiling point -- faster oil and colder oil collapse
  the vapour film earlier, strong flow removes it. R_c (the conduction resistance of the thinnest stable film) is the
  oil file's declared calibration: still oil at 40 C on the ISO 9950 probe collapses at ``leidenfrost_still_C``.

A still-bath curve (a library oil measured on the ISO 9950 probe, ``kind = "still_bath_curve"``) replaces the
boiling curve above by the measured one, on which the local flow acts (:func:`still_curve_heat_flux`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from quenchsim.bath.config import BathConfig, segment_factor
from quenchsim.bath.correlations import (GRAVITY, MARTIN_PR_EXPONENT, berenson_minimum_film_superheat,
                                         bromley_film_htc, churchill_usagi, flat_plate_local_nusselt,
                                         forced_film_htc, horizontal_plate_natural_nusselt, ivey_morris_factor,
                                         katto_kurata_critical_heat_flux, martin_arn_nusselt,
                                         martin_reynolds_function,
                                         subcooled_film_collapse_superheat,
                                         radiation_htc, rohsenow_heat_flux, vertical_plate_natural_nusselt,
                                         zuber_critical_heat_flux)
from quenchsim.bath.flow import LocalFlow, VERTICAL_NZ, local_flow
from quenchsim.bath.quenchant import GasProperties, OilProperties, ProbeQuenchant, load_gas
from quenchsim.errors import InputError
from quenchsim.geometry.boundary import BoundaryPoints


@dataclass(frozen=True)
class BoundaryHTC:
    """HTC curves of every boundary point on a shared uniform surface-temperature grid.

    T_grid_C (m,), h_W_m2K (n_points, m), ambient_C (n_points,), velocity_m_s (n_points,),
    segment (n_points,). Calling it with the surface temperatures (n_points,) interpolates linearly
    (clamped to the grid ends); :meth:`slope` gives dh/dT_s. Diagnostics: length_m (run length of the fastest flow source),
    leidenfrost_C and peak_C per point (NaN for air).
    """

    T_grid_C: np.ndarray
    h_W_m2K: np.ndarray
    ambient_C: np.ndarray
    velocity_m_s: np.ndarray
    segment: np.ndarray
    length_m: np.ndarray
    leidenfrost_C: np.ndarray
    peak_C: np.ndarray
    _rows: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_rows", np.arange(self.h_W_m2K.shape[0]))

    def _cell(self, T_surface_C: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        T0, dT, m = self.T_grid_C[0], self.T_grid_C[1] - self.T_grid_C[0], self.T_grid_C.size
        u = np.clip((np.asarray(T_surface_C, dtype=float) - T0) / dT, 0.0, m - 1.0)
        i = np.minimum(u.astype(np.intp), m - 2)
        return i, u - i, dT

    def __call__(self, T_surface_C: np.ndarray) -> np.ndarray:
        i, w, _ = self._cell(T_surface_C)
        h = self.h_W_m2K
        return h[self._rows, i] * (1.0 - w) + h[self._rows, i + 1] * w

    def slope(self, T_surface_C: np.ndarray) -> np.ndarray:
        """dh/dT_s (W/m^2K^2) of the interpolant, zero outside the grid -- for a Newton linearisation of the
        boundary flux q = h(T_s)(T_s - T_amb): dq/dT_s = h + (T_s - T_amb) dh/dT_s (boiling curves are steep
        near the Leidenfrost point, where a fixed point on h alone can stall)."""
        T = np.asarray(T_surface_C, dtype=float)
        i, _, dT = self._cell(T)
        inside = (T >= self.T_grid_C[0]) & (T <= self.T_grid_C[-1])
        h = self.h_W_m2K
        return np.where(inside, (h[self._rows, i + 1] - h[self._rows, i]) / dT, 0.0)


def _grid(T_low_C: float, T_high_C: float, step_K: float) -> np.ndarray:
    m = int(np.ceil((T_high_C - T_low_C) / step_K)) + 1
    return T_low_C + step_K * np.arange(m)


def convective_htc(oil: OilProperties, flow: LocalFlow, T_s: np.ndarray, T_oil: float) -> np.ndarray:
    """Single-phase h_c (n, m) at wall temperatures T_s (m,) (capped at the boiling point for the film): impinging jets
    (Martin), rotation and agitation (flat plate), natural convection (module docstring)."""
    T_wall = np.minimum(T_s, oil.boiling_point_C)[None, :]
    T_film = 0.5 * (T_wall + T_oil)
    nu, Pr, k = oil.kinematic_viscosity(T_film), oil.prandtl(T_film), oil.conductivity_W_mK
    h_forced_sq = np.zeros((flow.speed_m_s.shape[1], T_s.size))
    n_rows = flow.jet_shape.shape[0]
    for shape, U, D, area, H_D in zip(flow.jet_shape, flow.jet_speed_m_s, flow.jet_diameter_m, flow.jet_area_ratio,
                                      flow.jet_H_D):
        if U > 0.0 and np.any(shape > 0.0):
            Re = U * D / nu
            jet = k / D * (martin_arn_nusselt(Re, Pr, area, H_D) if area > 0.0
                           else Pr**MARTIN_PR_EXPONENT * martin_reynolds_function(Re))        # (1, m)
            h_forced_sq += (shape[:, None] * jet) ** 2
    for U, x in zip(flow.speed_m_s[n_rows:], flow.run_length_m[n_rows:]):
        Re = U[:, None] * x[:, None] / nu
        h_forced_sq += (k * flat_plate_local_nusselt(Re, Pr) / x[:, None]) ** 2
    L = flow.natural_length_m[:, None]
    Gr = GRAVITY * oil.expansion_1_K * np.maximum(T_wall - T_oil, 0.0) * L**3 / nu**2
    vertical = (flow.orientation == 0)[:, None]
    Nu_nat = np.where(vertical, vertical_plate_natural_nusselt(Pr, Gr),
                      horizontal_plate_natural_nusselt(Pr, Gr, (flow.orientation > 0)[:, None]))
    return churchill_usagi(np.sqrt(h_forced_sq), k * Nu_nat / L)


def interface_htc(oil: OilProperties, flow: LocalFlow, T_oil: float) -> np.ndarray:
    """Single-phase coefficient (n,) of a surface at the boiling point: that of a vapour film's liquid face."""
    return convective_htc(oil, flow, np.array([oil.boiling_point_C]), T_oil)[:, 0]


def critical_heat_flux(oil: OilProperties, flow: LocalFlow, T_oil: float) -> np.ndarray:
    """Subcooled critical heat flux (n,) W/m^2: max(Zuber pool, Katto-Kurata flow along the wall for each flow source
    at its local speed and run length) times the Ivey-Morris subcooling factor."""
    Tb, rho_l = oil.boiling_point_C, oil.density_kg_m3
    rho_vb = float(oil.vapour_density(Tb))
    pool = zuber_critical_heat_flux(oil.surface_tension_N_m, oil.latent_heat_J_kg, rho_l, rho_vb, oil.zuber_K)
    forced = np.max([katto_kurata_critical_heat_flux(U, x, rho_l, rho_vb, oil.latent_heat_J_kg, oil.surface_tension_N_m)
                     for U, x in zip(flow.speed_m_s, flow.run_length_m)], axis=0, initial=0.0)
    return np.maximum(pool, forced) * ivey_morris_factor(rho_l, rho_vb, oil.specific_heat_J_kgK, Tb - T_oil,
                                                         oil.latent_heat_J_kg, oil.ivey_morris_C)


def film_collapse_temperature(oil: OilProperties, flow: LocalFlow, T_oil: float) -> np.ndarray:
    """Vapour-film collapse (Leidenfrost) temperature T_L (n,) C: T_b + Berenson's saturated minimum superheat
    + R_c h_l (T_b - T_oil) (:func:`quenchsim.bath.correlations.subcooled_film_collapse_superheat`)."""
    Tb = oil.boiling_point_C
    dT_sat = berenson_minimum_film_superheat(oil.density_kg_m3, float(oil.vapour_density(Tb)), oil.latent_heat_J_kg,
                                             oil.vapour_conductivity_W_mK, oil.vapour_viscosity_Pa_s,
                                             oil.surface_tension_N_m)
    return Tb + subcooled_film_collapse_superheat(dT_sat, interface_htc(oil, flow, T_oil), Tb - T_oil,
                                                  oil.film_collapse_resistance_m2K_W)


def oil_heat_flux(oil: OilProperties, flow: LocalFlow, T_s: np.ndarray, T_oil: float) -> tuple[np.ndarray, ...]:
    """Boiling curve q (n, m) on the grid T_s (m,), with T_L (n,) and T_peak (n,)."""
    Tb, rho_l, cp_l = oil.boiling_point_C, oil.density_kg_m3, oil.specific_heat_J_kgK
    h_c = convective_htc(oil, flow, T_s, T_oil)
    dT_oil = (T_s - T_oil)[None, :]
    q_conv = h_c * dT_oil
    # nucleate boiling, liquid properties at the boiling point, vapour at the boiling point
    rho_vb = float(oil.vapour_density(Tb))
    mu_b = float(oil.viscosity(Tb))
    q_max = critical_heat_flux(oil, flow, T_oil)                                # (n,)
    boil = dict(rho_l=rho_l, rho_v=rho_vb, mu_l=mu_b, k_l=oil.conductivity_W_mK, cp_l=cp_l,
                h_fg_J_kg=oil.latent_heat_J_kg, sigma_N_m=oil.surface_tension_N_m, Csf=oil.rohsenow_Csf,
                n=oil.rohsenow_n)
    q_nb = np.minimum(rohsenow_heat_flux(T_s - Tb, **boil)[None, :], q_max[:, None])
    T_peak_nb = Tb + (q_max / float(rohsenow_heat_flux(1.0, **boil))) ** (1.0 / 3.0)
    q_wet = q_conv + q_nb
    # film boiling, vapour properties at the film mean temperature
    dT_b = np.maximum(T_s - Tb, 1e-9)
    rho_v = oil.vapour_density(0.5 * (T_s + Tb))
    h_fg_eff = oil.latent_heat_J_kg + 0.4 * oil.vapour_specific_heat_J_kgK * dT_b
    h_nat_film = bromley_film_htc(dT_b[None, :], flow.natural_length_m[:, None], oil.vapour_conductivity_W_mK, rho_v,
                                  rho_l, oil.vapour_viscosity_Pa_s, h_fg_eff, oil.bromley_C)
    h_forced_film_sq = sum(forced_film_htc(U[:, None], dT_b[None, :], x[:, None], oil.vapour_conductivity_W_mK, rho_v,
                                           h_fg_eff, oil.film_forced_C) ** 2
                           for U, x in zip(flow.speed_m_s, flow.run_length_m))
    h_forced_film = np.sqrt(h_forced_film_sq)
    h_c_interface = h_c[:, -1:]  # wall capped at T_b: the coefficient of the film's liquid face
    q_film = (churchill_usagi(h_nat_film, h_forced_film) * dT_b
              + 0.75 * radiation_htc(T_s, T_oil, oil.surface_emissivity) * dT_oil
              + h_c_interface * (Tb - T_oil))
    # regimes
    T_L = film_collapse_temperature(oil, flow, T_oil)
    T_peak = np.minimum(T_peak_nb, T_L - oil.transition_min_width_K)
    q_peak = _interp_rows(T_s, q_wet, T_peak)
    q_film_L = _interp_rows(T_s, q_film, T_L)
    theta = np.clip((T_s[None, :] - T_peak[:, None]) / np.maximum(T_L - T_peak, 1e-9)[:, None], 0.0, 1.0)
    q_transition = q_peak[:, None] * (q_film_L / q_peak)[:, None] ** theta
    T = T_s[None, :]
    q = np.where(T <= T_peak[:, None], q_wet, np.where(T < T_L[:, None], q_transition, q_film))
    return q, h_c, T_L, T_peak


def _interp_rows(x: np.ndarray, Y: np.ndarray, x_row: np.ndarray) -> np.ndarray:
    """Y[j](x_row[j]) for every row j of Y sampled on the shared grid x (uniform)."""
    u = np.clip((x_row - x[0]) / (x[1] - x[0]), 0.0, x.size - 1.0)
    i = np.minimum(u.astype(np.intp), x.size - 2)
    w = u - i
    rows = np.arange(Y.shape[0])
    return Y[rows, i] * (1.0 - w) + Y[rows, i + 1] * w


def still_curve_features(curve: ProbeQuenchant) -> tuple[float, float]:
    """(T_peak0, T_L0) of a still-bath curve: the temperature of its highest h (the boiling peak) and, above it, the
    temperature where h reaches its lowest value (the film level: the vapour film's collapse temperature)."""
    i_peak = int(np.argmax(curve.h_W_m2K))
    i_film = i_peak + int(np.argmin(curve.h_W_m2K[i_peak:]))
    return float(curve.T_C[i_peak]), float(curve.T_C[i_film])


def still_curve_heat_flux(curve: ProbeQuenchant, liquid: OilProperties, flow: LocalFlow, T_s: np.ndarray,
                          T_oil: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Heat flux q (n, m) of a probe-measured still-bath curve h_0(T_s) under the local flow, with T_L (n,) and the
    peak temperature (n,).

    h_0 is used as a function of the surface temperature, with the driving difference T_s - T_oil of this bath (a
    bath temperature other than the test's changes only that difference). With the local speed U (m/s):

    * Vapour-film collapse: T_L = T_L0 + [T_L(flow) - T_L(still)] with the liquid's film-collapse law of the model
      above (:func:`film_collapse_temperature`) -- agitation shortens the vapour stage, strong agitation removes it
      (Totten/MacKenzie, "Understanding the cooling curve test", Thermal Processing 2017). T_L0 and the peak T_p0 are
      read off h_0 (:func:`still_curve_features`).
    * Boiling: below T_p0 the still flux q_0(T_s) = h_0 (T_s - T_oil); from T_p0 to T_p0 + (T_L - T_L0) the wall
      stays in nucleate boiling at the still curve's peak flux q_0(T_p0) raised by the liquid's critical-flux ratio
      q_max(flow)/q_max(still) (:func:`critical_heat_flux`); the still transition follows, shifted up by T_L - T_L0
      and interpolated log-linearly so that q meets the film flux q_0(T_L) at T_L; above T_L the still film flux
      q_0(T_s); the nucleate flux between T_b and T_p0 is raised by the same ratio, growing linearly from 1 at T_b
      (continuous at T_p0). With U = 0 this is q_0 exactly.
    * Convection: the forced-convection increment h_c(U) - h_c(0) of the liquid (flat-plate and Churchill-Usagi
      blend of :func:`convective_htc`, liquid properties of ``liquid``) is added to every regime on the
      difference min(T_s, T_b) - T_oil (Rohsenow's superposition of forced convection and boiling; in film
      boiling, convection from the film's liquid face at T_b) -- the still curve already holds the natural
      convection of the probe test.

    Not modelled: forced flow thickening the film flux itself (Bromley-LeRoy-Robbers), the bath temperature's
    effect on the film stage, and the difference between the probe's and the part's natural convection.
    """
    T_peak0, T_L0 = still_curve_features(curve)
    dT_oil = np.maximum(T_s - T_oil, 1e-9)
    q_still = curve.h(T_s) * dT_oil                                            # (m,)

    def q_of(T: Any) -> np.ndarray:
        return np.interp(T, T_s, q_still)

    still = flow.without_flow()
    T_L = T_L0 + film_collapse_temperature(liquid, flow, T_oil) - film_collapse_temperature(liquid, still, T_oil)
    shift = (T_L - T_L0)[:, None]
    q_peak = float(curve.h(T_peak0)) * max(T_peak0 - T_oil, 1e-9)
    q_peak_flow = (q_peak * critical_heat_flux(liquid, flow, T_oil) / critical_heat_flux(liquid, still, T_oil))[:, None]
    T = T_s[None, :]
    span = np.log(max(float(q_of(T_L0)), 1e-9) / q_peak)
    theta_still = np.log(np.maximum(q_of(np.clip(T - shift, T_peak0, T_L0)), 1e-9) / q_peak) \
        / (span if span != 0.0 else 1.0)                                       # 0 at the peak, 1 at the film
    q_film_L = curve.h(T_L)[:, None] * (T_L[:, None] - T_oil)
    q_transition = q_peak_flow * (q_film_L / q_peak_flow) ** np.clip(theta_still, 0.0, 1.0)
    Tb = liquid.boiling_point_C
    rise = 1.0 + (q_peak_flow / q_peak - 1.0) * np.clip((T - Tb) / max(T_peak0 - Tb, 1e-9), 0.0, 1.0)
    q = np.where(T <= T_peak0, q_still[None, :] * rise,
                 np.where(T <= T_peak0 + shift, q_peak_flow,
                          np.where(T < T_L[:, None], q_transition, q_still[None, :])))
    h_c_increment = convective_htc(liquid, flow, T_s, T_oil) - convective_htc(liquid, still, T_s, T_oil)
    q = q + h_c_increment * (np.minimum(T_s, liquid.boiling_point_C) - T_oil)[None, :]
    return q, h_c_increment + curve.h(T_s)[None, :], T_L, np.full(T_L.shape, T_peak0)


def boundary_htc(cfg: BathConfig, points: BoundaryPoints) -> BoundaryHTC:
    """HTC(T_surface) curves of every boundary point in the oil bath ``cfg`` (build once per stage)."""
    flow = local_flow(cfg, points)
    T_oil = cfg.oil_temperature_C
    T_grid = _grid(T_oil, cfg.T_max_C, cfg.T_step_K)
    if cfg.still_curve is None:
        q, h_c, T_L, T_peak = oil_heat_flux(cfg.liquid, flow, T_grid, T_oil)
    else:
        q, h_c, T_L, T_peak = still_curve_heat_flux(cfg.still_curve, cfg.liquid, flow, T_grid, T_oil)
    dT = (T_grid - T_oil)[None, :]
    h = np.where(dT > 0.0, q / np.where(dT > 0.0, dT, 1.0), h_c) * flow.exposed_fraction[:, None]
    if cfg.htc_factor:
        factor = {name: segment_factor(cfg.htc_factor, name) for name in set(points.segment.tolist())}
        h = h * np.array([factor[name] for name in points.segment.tolist()])[:, None]
    n = len(points)
    return BoundaryHTC(T_grid_C=T_grid, h_W_m2K=h, ambient_C=np.full(n, T_oil), velocity_m_s=flow.velocity_m_s,
                       segment=np.asarray(points.segment), length_m=flow.length_m, leidenfrost_C=T_L,
                       peak_C=T_peak)


def air_natural_htc(gas: GasProperties, points: BoundaryPoints, T_s: np.ndarray, T_air: float) -> np.ndarray:
    """Natural-convection h (n, m) in still gas: Churchill-Chu on vertical faces (L = section height),
    McAdams on horizontal faces (L = half the radial width = area/perimeter of an annular face)."""
    ext = points.extent
    vertical = (np.abs(points.normal_z) < VERTICAL_NZ)[:, None]
    L = np.where(vertical, ext.z_max_m - ext.z_min_m, 0.5 * (ext.r_max_m - ext.r_min_m))
    T_film = 0.5 * (T_s + T_air)[None, :]
    nu, Pr, k = gas.kinematic_viscosity(T_film), gas.prandtl(T_film), gas.conductivity(T_film)
    Gr = GRAVITY * gas.expansion_1_K(T_film) * np.abs(T_s - T_air)[None, :] * L**3 / nu**2
    Nu = np.where(vertical, vertical_plate_natural_nusselt(Pr, Gr),
                  horizontal_plate_natural_nusselt(Pr, Gr, (points.normal_z > 0)[:, None]))
    return k * Nu / L


def air_htc(points: BoundaryPoints, air_temperature_C: float, emissivity: float, T_max_C: float = 1100.0,
            T_step_K: float = 2.0, gas: str = "air") -> BoundaryHTC:
    """HTC(T_surface) in still air: natural convection (ht correlations) + linearised radiation
    eps sigma (T_s^2 + T_a^2)(T_s + T_a)."""
    if not 0.0 < emissivity <= 1.0:
        raise InputError("air.emissivity", emissivity, "must be in (0, 1]")
    if not -50.0 <= air_temperature_C < T_max_C:
        raise InputError("air.temperature_C", air_temperature_C, f"must be in [-50, {T_max_C:g}) C")
    props = load_gas(gas)
    T_grid = _grid(air_temperature_C, T_max_C, T_step_K)
    h = air_natural_htc(props, points, T_grid, air_temperature_C) \
        + radiation_htc(T_grid, air_temperature_C, emissivity)[None, :]
    n = len(points)
    nan = np.full(n, np.nan)
    return BoundaryHTC(T_grid_C=T_grid, h_W_m2K=h, ambient_C=np.full(n, float(air_temperature_C)),
                       velocity_m_s=np.zeros(n), segment=np.asarray(points.segment),
                       length_m=np.where(np.abs(points.normal_z) < VERTICAL_NZ,
                                         points.extent.z_max_m - points.extent.z_min_m,
                                         0.5 * (points.extent.r_max_m - points.extent.r_min_m)),
                       leidenfrost_C=nan, peak_C=nan)
