"""Equations of motion of the big-end bearing in the frame rotating with the crank pin.

Frame: origin at the pin centre P, x' along the crank arm, rotating at omega (crank speed; for the
static and rig modes the inner ring speed, with P fixed: crank radius 0). Bodies: N rollers (x, y,
spin angle), cage (x, y, angle), outer ring (x, y; its rotation relative to the frame, Omega_o(t),
is imposed by the mechanism). State y = [q, v], q = [x_r(N), y_r(N), phi_r(N), x_c, y_c, psi_c,
x_o, y_o], v = dq/dt: 6 N + 10 first-order ODEs. For a body of mass m at rho with relative velocity u:
    m du/dt = F + m [ r_c omega^2 e_x' - r_c omega_dot e_y'          (frame-origin acceleration)
                      + omega^2 rho                                (centrifugal)
                      - 2 omega z x u                              (Coriolis)
                      - omega_dot z x rho ] + m g'                 (Euler; gravity rotated into the frame)
    I dOmega/dt = M - I omega_dot                                  (Omega relative to the frame)
Contacts (one compiled pass over the rollers): roller-pin and roller-outer race (Palmgren line
contact with damping, EHL traction), roller-pocket (flat pocket faces at +-w/2 from the pocket's radial line,
Palmgren contact over the pocket contact length, Coulomb friction), cage land-outer ring (short
journal bearing with squeeze film down to the smallest film h_min, solid land contact beyond it),
cage unbalance.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from quenchsim.bearings.big_end.contact import coulomb_friction, damped_contact_force
from quenchsim.bearings.big_end.ehl import (
    hertz_line_max_pressure, pan_hamrock_central_film, thermal_loading, thermal_reduction_factor,
    traction_coefficient)
from quenchsim.bearings.big_end.journal import short_bearing_force
from quenchsim.bearings.big_end.state import cage_index, n_positions, ring_index


class Params(NamedTuple):
    """Flat model parameters (SI) handed to the compiled right-hand side."""

    n: int
    r_roller: float
    r_in: float
    r_out: float
    m_roller: float
    i_roller: float
    m_cage: float
    i_cage: float
    m_ring: float
    pocket_half_width: float
    pocket_angles: np.ndarray
    l_roller: np.ndarray  # (n,) effective roller length
    l_pocket: np.ndarray  # (n,) pocket contact length
    l_land: np.ndarray  # (1,) total land length for the solid guide contact
    land_radius: float
    land_width: float
    lands: float
    guide_clearance: float  # radial
    e_star: float
    damping_ratio: float
    mu_pocket: float
    mu_boundary: float
    mu_guide: float
    v_reg: float
    eta0: float
    alpha: float
    beta_t: float
    k_oil: float
    mu_lim: float
    slide_roll_scale: float
    roughness: float
    film_lo: float
    film_hi: float
    u_floor: float
    eps_max: float
    guide_min_film: float
    r_eff_in: np.ndarray  # (n,)
    r_eff_out: np.ndarray  # (n,)
    omega: float
    omega_dot: float
    crank_radius: float
    gravity_x: float  # inertial
    gravity_y: float
    unbalance: float  # kg m
    table_theta: np.ndarray
    table_fx: np.ndarray  # external force on the outer ring, frame components
    table_fy: np.ndarray
    table_omega_o: np.ndarray  # outer-ring angular velocity relative to the frame


@njit(cache=True)
def _traction(q: float, ue: float, slide: float, r_eff: float, p: Params) -> float:
    """Signed traction coefficient of one roller-race contact (film from Pan-Hamrock + thermal factor)."""
    w = q / p.l_roller[0]
    ue_f = max(ue, p.u_floor)
    s = slide / ue_f
    ph = hertz_line_max_pressure(w, r_eff, p.e_star)
    phi = thermal_reduction_factor(ph, p.e_star, thermal_loading(p.beta_t, p.eta0, ue_f, p.k_oil), s)
    hc = pan_hamrock_central_film(w, ue_f, r_eff, p.e_star, p.eta0, p.alpha) * phi
    return traction_coefficient(s, hc / p.roughness, p.mu_lim, p.slide_roll_scale, p.mu_boundary,
                                p.film_lo, p.film_hi)


@njit(cache=True)
def entrainment_speed(centre_speed: float, surface_speed: float, race_surface_speed: float,
                      centre_distance: float, contact_distance: float) -> float:
    """Entrainment (rolling) speed u_e of a roller-race contact [m/s]: the mean of the two surface
    speeds relative to the contact point, which travels with the roller along the race,
        u_e = | (u_race + u_roller) / 2 - u_centre rho_c / rho_r |,
    all tangential and measured from the race centre (translating with it): u_centre the roller centre
    (distance rho_r), u_roller = u_centre +- r w its surface at the contact (distance rho_c), u_race the
    race surface. Pure rolling at orbit speed Omega gives Omega R_i (pin) and |Omega_o - Omega| R_o
    (bore), i.e. (d_m^2 - D^2) / (4 d_m) |omega_i - omega_o| at the kinematic orbit (Harris &
    Kotzalas, Rolling Bearing Analysis, 5th ed. 2007, vol. 1 ch. 8)."""
    return abs(0.5 * (race_surface_speed + surface_speed) - centre_speed * contact_distance / centre_distance)


@njit(cache=True)
def _pocket_face(sgn: float, q: float, dx: float, dy: float, erx: float, ery: float, etx: float, ety: float,
                 vxr: float, vyr: float, wr: float, vxc: float, vyc: float, wc: float,
                 p: Params) -> tuple[float, float, float, float]:
    """Force (fx, fy) and moment on the roller and moment on the cage of one pocket face (sgn = +-1)."""
    r = p.r_roller
    ax = sgn * r * etx  # contact point relative to roller centre
    ay = sgn * r * ety
    cx = dx + ax  # relative to cage centre
    cy = dy + ay
    vrx = vxr - wr * ay
    vry = vyr + wr * ax
    vcx = vxc - wc * cy
    vcy = vyc + wc * cx
    vs = (vrx - vcx) * erx + (vry - vcy) * ery
    f = coulomb_friction(q, vs, p.mu_pocket, p.v_reg)
    fx = -sgn * q * etx - f * erx
    fy = -sgn * q * ety - f * ery
    return fx, fy, ax * fy - ay * fx, -(cx * fy - cy * fx)


@njit(cache=True)
def evaluate(t: float, y: np.ndarray, p: Params) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Accelerations (3N + 5,) plus per-roller pocket force, pin and outer-race loads.

    One pass over the rollers with scalar contact laws (no temporary arrays: the right-hand side is
    called ~10^5 times per crank revolution).
    """
    n = p.n
    nq, ic, io = n_positions(n), cage_index(n), ring_index(n)
    xc, yc, psi = y[ic], y[ic + 1], y[ic + 2]
    xo, yo = y[io], y[io + 1]
    vxc, vyc, wc = y[nq + ic], y[nq + ic + 1], y[nq + ic + 2]
    vxo, vyo = y[nq + io], y[nq + io + 1]
    r = p.r_roller
    l_r = p.l_roller[0]
    l_p = p.l_pocket[0]
    m_pair = p.m_roller * p.m_cage / (p.m_roller + p.m_cage)

    theta = p.omega * t
    th = theta % (2.0 * np.pi)
    fx_ext = np.interp(th, p.table_theta, p.table_fx)
    fy_ext = np.interp(th, p.table_theta, p.table_fy)
    omega_o = np.interp(th, p.table_theta, p.table_omega_o)
    w = p.omega
    wd = p.omega_dot
    # frame (non-inertial) terms + gravity per unit mass
    ax0 = p.crank_radius * w * w + p.gravity_x * np.cos(theta) + p.gravity_y * np.sin(theta)
    ay0 = -p.crank_radius * wd - p.gravity_x * np.sin(theta) + p.gravity_y * np.cos(theta)

    acc = np.empty(nq)
    pocket = np.empty(n)
    q_in_all = np.empty(n)
    q_out_all = np.empty(n)
    fxc = 0.0
    fyc = 0.0
    mc = 0.0
    fxo = 0.0
    fyo = 0.0
    for j in range(n):
        xr, yr = y[j], y[n + j]
        vxr, vyr, wr = y[nq + j], y[nq + n + j], y[nq + 2 * n + j]

        # roller - pin (inner race, fixed in the frame)
        d = np.sqrt(xr * xr + yr * yr)
        nx = xr / d
        ny = yr / d
        tx = -ny
        ty = nx
        q_in = damped_contact_force(p.r_in + r - d, -(vxr * nx + vyr * ny), l_r, p.e_star, p.m_roller,
                                    p.damping_ratio)
        ut = vxr * tx + vyr * ty
        ue = entrainment_speed(ut, ut - r * wr, 0.0, d, d - r)
        mu = _traction(q_in, ue, ut - r * wr, p.r_eff_in[j], p) if q_in > 0.0 else 0.0
        fxr = q_in * nx - mu * q_in * tx
        fyr = q_in * ny - mu * q_in * ty
        mr = r * mu * q_in

        # roller - outer race
        sx = xr - xo
        sy = yr - yo
        d = np.sqrt(sx * sx + sy * sy)
        nx = sx / d
        ny = sy / d
        tx = -ny
        ty = nx
        q_out = damped_contact_force(d + r - p.r_out, (vxr - vxo) * nx + (vyr - vyo) * ny, l_r, p.e_star,
                                     p.m_roller, p.damping_ratio)
        if q_out > 0.0:
            ut_r = (vxr - vxo) * tx + (vyr - vyo) * ty  # relative to the outer-ring centre
            ut_o = omega_o * p.r_out
            ue = entrainment_speed(ut_r, ut_r + r * wr, ut_o, d, d + r)
            mu = _traction(q_out, ue, ut_r + r * wr - ut_o, p.r_eff_out[j], p)
            fx = q_out * nx + mu * q_out * tx
            fy = q_out * ny + mu * q_out * ty
            fxr -= fx
            fyr -= fy
            mr -= r * mu * q_out
            fxo += fx
            fyo += fy

        # roller - cage pocket (flat faces at +-w/2 from the pocket's radial line)
        ang = psi + p.pocket_angles[j]
        erx = np.cos(ang)
        ery = np.sin(ang)
        etx = -ery
        ety = erx
        dx = xr - xc
        dy = yr - yc
        s = dx * etx + dy * ety
        a = dx * erx + dy * ery
        sdot = (vxr - vxc) * etx + (vyr - vyc) * ety - wc * a
        q_lead = damped_contact_force(s + r - p.pocket_half_width, sdot, l_p, p.e_star, m_pair, p.damping_ratio)
        q_trail = damped_contact_force(-s + r - p.pocket_half_width, -sdot, l_p, p.e_star, m_pair,
                                       p.damping_ratio)
        if q_lead > 0.0:
            fx, fy, m1, m2 = _pocket_face(1.0, q_lead, dx, dy, erx, ery, etx, ety, vxr, vyr, wr, vxc, vyc, wc, p)
            fxr += fx
            fyr += fy
            mr += m1
            fxc -= fx
            fyc -= fy
            mc += m2
        if q_trail > 0.0:
            fx, fy, m1, m2 = _pocket_face(-1.0, q_trail, dx, dy, erx, ery, etx, ety, vxr, vyr, wr, vxc, vyc, wc,
                                          p)
            fxr += fx
            fyr += fy
            mr += m1
            fxc -= fx
            fyc -= fy
            mc += m2

        acc[j] = fxr / p.m_roller + ax0 + w * w * xr + 2.0 * w * vyr + wd * yr
        acc[n + j] = fyr / p.m_roller + ay0 + w * w * yr - 2.0 * w * vxr - wd * xr
        acc[2 * n + j] = mr / p.i_roller - wd
        pocket[j] = q_lead + q_trail
        q_in_all[j] = q_in
        q_out_all[j] = q_out

    # cage land - outer ring: short journal bearing film (+ solid contact when the film is below h_min)
    ex = xc - xo
    ey = yc - yo
    gx, gy, torque = short_bearing_force(ex, ey, vxc - vxo, vyc - vyo, wc, omega_o, p.land_radius,
                                         p.land_width, p.guide_clearance, p.eta0, p.eps_max)
    fxc += p.lands * gx
    fyc += p.lands * gy
    mc += p.lands * torque
    fxo -= p.lands * gx
    fyo -= p.lands * gy
    e = np.hypot(ex, ey)
    gap_limit = p.guide_clearance - p.guide_min_film
    if e > gap_limit:
        ux = ex / e
        uy = ey / e
        rate = (vxc - vxo) * ux + (vyc - vyo) * uy
        qg = damped_contact_force(e - gap_limit, rate, p.l_land[0], p.e_star, p.m_cage, p.damping_ratio)
        slip = ((vxc - vxo) * (-uy) + (vyc - vyo) * ux + wc * p.land_radius
                - omega_o * (p.land_radius + p.guide_clearance))
        fg = coulomb_friction(qg, slip, p.mu_guide, p.v_reg)
        fxc += -qg * ux + fg * uy
        fyc += -qg * uy - fg * ux
        mc -= fg * p.land_radius
        fxo += qg * ux - fg * uy
        fyo += qg * uy + fg * ux

    # cage unbalance (centrifugal force of the unbalance at the absolute cage speed)
    w_abs = w + wc
    fxc += p.unbalance * w_abs * w_abs * np.cos(psi)
    fyc += p.unbalance * w_abs * w_abs * np.sin(psi)

    # external load on the outer ring
    fxo += fx_ext
    fyo += fy_ext

    acc[ic] = fxc / p.m_cage + ax0 + w * w * xc + 2.0 * w * vyc + wd * yc
    acc[ic + 1] = fyc / p.m_cage + ay0 + w * w * yc - 2.0 * w * vxc - wd * xc
    acc[ic + 2] = mc / p.i_cage - wd
    acc[io] = fxo / p.m_ring + ax0 + w * w * xo + 2.0 * w * vyo + wd * yo
    acc[io + 1] = fyo / p.m_ring + ay0 + w * w * yo - 2.0 * w * vxo - wd * xo
    return acc, pocket, q_in_all, q_out_all


@njit(cache=True)
def rhs(t: float, y: np.ndarray, p: Params) -> np.ndarray:
    """dy/dt = [v, a(q, v, t)]."""
    nq = n_positions(p.n)
    acc, _, _, _ = evaluate(t, y, p)
    out = np.empty(2 * nq)
    out[:nq] = y[nq:]
    out[nq:] = acc
    return out


@njit(cache=True)
def jacobian(t: float, y: np.ndarray, p: Params, typical: np.ndarray) -> np.ndarray:
    """Forward-difference Jacobian d(rhs)/dy, all 6N + 10 columns in one compiled call
    (step sqrt(eps) max(|y_k|, typical_k)); handed to the implicit SciPy methods."""
    f0 = rhs(t, y, p)
    m = y.size
    jac = np.empty((m, m))
    yp = y.copy()
    for k in range(m):
        h = 1.4901161193847656e-08 * max(abs(y[k]), typical[k])
        yp[k] = y[k] + h
        jac[:, k] = (rhs(t, yp, p) - f0) / h
        yp[k] = y[k]
    return jac


SCALAR_FIELDS = (
    "n", "r_roller", "r_in", "r_out", "m_roller", "i_roller", "m_cage", "i_cage", "m_ring",
    "pocket_half_width", "land_radius", "land_width", "lands", "guide_clearance", "e_star", "damping_ratio",
    "mu_pocket", "mu_boundary", "mu_guide", "v_reg", "eta0", "alpha", "beta_t", "k_oil", "mu_lim",
    "slide_roll_scale", "roughness", "film_lo", "film_hi", "u_floor", "eps_max", "guide_min_film", "omega",
    "omega_dot", "crank_radius", "gravity_x", "gravity_y", "unbalance",
)
ROLLER_FIELDS = ("pocket_angles", "l_roller", "l_pocket", "r_eff_in", "r_eff_out")
TABLE_FIELDS = ("table_theta", "table_fx", "table_fy", "table_omega_o")


def pack(p: Params) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Params as four arrays (scalars, per-roller rows, table rows, land length): passing four arrays
    to compiled code costs ~1 us per call, a 48-field named tuple ~10 us."""
    s = np.array([float(getattr(p, f)) for f in SCALAR_FIELDS])
    rolls = np.ascontiguousarray(np.vstack([getattr(p, f) for f in ROLLER_FIELDS]), dtype=np.float64)
    tables = np.ascontiguousarray(np.vstack([getattr(p, f) for f in TABLE_FIELDS]), dtype=np.float64)
    return s, rolls, tables, np.asarray(p.l_land, dtype=np.float64)


@njit(cache=True)
def _unpack(s: np.ndarray, rolls: np.ndarray, tables: np.ndarray, l_land: np.ndarray) -> Params:
    """Rebuild :class:`Params` inside compiled code (field order of the class)."""
    return Params(int(s[0]), s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8], s[9], rolls[0], rolls[1],
                  rolls[2], l_land, s[10], s[11], s[12], s[13], s[14], s[15], s[16], s[17], s[18], s[19],
                  s[20], s[21], s[22], s[23], s[24], s[25], s[26], s[27], s[28], s[29], s[30], s[31],
                  rolls[3], rolls[4], s[32], s[33], s[34], s[35], s[36], s[37], tables[0], tables[1],
                  tables[2], tables[3])


@njit(cache=True)
def rhs_packed(t: float, y: np.ndarray, s: np.ndarray, rolls: np.ndarray, tables: np.ndarray,
               l_land: np.ndarray) -> np.ndarray:
    """:func:`rhs` with the parameters from :func:`pack`."""
    return rhs(t, y, _unpack(s, rolls, tables, l_land))


@njit(cache=True)
def jacobian_packed(t: float, y: np.ndarray, s: np.ndarray, rolls: np.ndarray, tables: np.ndarray,
                    l_land: np.ndarray, typical: np.ndarray) -> np.ndarray:
    """:func:`jacobian` with the parameters from :func:`pack`."""
    return jacobian(t, y, _unpack(s, rolls, tables, l_land), typical)
