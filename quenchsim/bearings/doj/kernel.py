"""Numba kernel of the DOJ equilibrium equations (the one implementation of the contact forces; model.py documents
the physics and calls it). Lengths mm, forces N.

Parameter vector ``par`` (see :func:`pack`): operating angle, contact angle, PCR, groove radius - ball radius, flank
gap, cage offset, the four stiffnesses, half the window clearance, the two sphere clearances, torque (N mm), P_n,
the cage's tilt lever, the regularisation, then the vectors d, I, M0, cage axis, tilt basis e1, e2.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

N_BALLS = 6
N_PAR = 35


def pack(theta: float, alpha: float, pcr: float, rho: float, gap: float, offset: float, k_track: float,
         k_window: float, k_inner: float, k_outer: float, half_window: float, c_inner: float, c_outer: float,
         torque_Nmm: float, p_n: float, r_tilt: float, regularisation: float, d_in: np.ndarray,
         inner_centre: np.ndarray, cage_centre0: np.ndarray, cage_axis0: np.ndarray, e1: np.ndarray,
         e2: np.ndarray) -> np.ndarray:
    head = [theta, alpha, pcr, rho, gap, offset, k_track, k_window, k_inner, k_outer, half_window, c_inner, c_outer,
            torque_Nmm, p_n, r_tilt, regularisation]
    return np.concatenate([np.array(head), d_in, inner_centre, cage_centre0, cage_axis0, e1, e2]).astype(np.float64)


@njit(cache=True, inline="always")
def _hertz(k, delta):
    return k * delta ** 1.5 if delta > 0.0 else 0.0


@njit(cache=True)
def _groove(x, px, py, pz, dx, dy, dz, rho, k, out):
    """Force on a ball at x from a groove whose centre line passes through p along unit d; returns delta."""
    vx, vy, vz = x[0] - px, x[1] - py, x[2] - pz
    s = vx * dx + vy * dy + vz * dz
    vx, vy, vz = vx - s * dx, vy - s * dy, vz - s * dz
    dist = math.sqrt(vx * vx + vy * vy + vz * vz)
    delta = dist - rho
    q = _hertz(k, delta)
    out[0], out[1], out[2] = -q * vx / dist, -q * vy / dist, -q * vz / dist
    return delta


@njit(cache=True)
def evaluate(q, phase, par, res, f_out, f_in, p_window, f_ic, f_co, x, frame):
    """Residual ``res`` (24,) and the contact forces on the balls (f_out, f_in: (2, 6, 3) per flank), the net window
    force along the cage axis (6,), the sphere forces on the cage (3,), the ball centres (6, 3) and ``frame``
    (rows: cage centre, cage axis, C_i, C_o, beta / 0 / 0)."""
    theta, alpha, pcr, rho, gap, e = par[0], par[1], par[2], par[3], par[4], par[5]
    kt, kw, kis, kos, hw, cis, cos_ = par[6], par[7], par[8], par[9], par[10], par[11], par[12]
    torque, p_n, r_tilt, reg = par[13], par[14], par[15], par[16]
    d = par[17:20]
    ic = par[20:23]
    m0 = par[23:26]
    a0 = par[26:29]
    e1 = par[29:32]
    e2 = par[32:35]
    beta = q[0] / pcr
    # cage: tilt by the rotation vector w (Rodrigues)
    w = (q[4] * e1 + q[5] * e2) / r_tilt
    ang = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    rot = np.eye(3)
    if ang > 0.0:
        kx, ky, kz = w[0] / ang, w[1] / ang, w[2] / ang
        c, s = math.cos(ang), math.sin(ang)
        cc = 1.0 - c
        rot = np.array([[c + kx * kx * cc, kx * ky * cc - kz * s, kx * kz * cc + ky * s],
                        [ky * kx * cc + kz * s, c + ky * ky * cc, ky * kz * cc - kx * s],
                        [kz * kx * cc - ky * s, kz * ky * cc + kx * s, c + kz * kz * cc]])
    axis = rot @ a0
    centre = m0 + q[1:4]
    ca, sa = math.cos(alpha), math.sin(alpha)
    tan_half = math.tan(theta / 2.0)
    ct, st = math.cos(theta), math.sin(theta)
    tmp = np.empty(3)
    on_race_torque = 0.0
    cage_f = np.zeros(3)
    cage_m = np.zeros(3)
    for i in range(N_BALLS):
        psi = phase + 2.0 * math.pi * i / N_BALLS
        cp, sp = math.cos(psi), math.sin(psi)
        x[i, 0] = q[6 + 3 * i] + pcr * cp
        x[i, 1] = q[7 + 3 * i] + pcr * sp
        x[i, 2] = q[8 + 3 * i] + pcr * sp * tan_half
        # inner race frame: R_x(theta) R_z(phase + beta) applied to the local radial / tangential unit vectors
        a_l = 2.0 * math.pi * i / N_BALLS + phase + beta
        cl, sl = math.cos(a_l), math.sin(a_l)
        ulx, uly, ulz = cl, sl * ct, sl * st
        tlx, tly, tlz = -sl, cl * ct, cl * st
        fx, fy, fz = 0.0, 0.0, 0.0
        for fl in range(2):
            kf = 1.0 if fl == 0 else -1.0
            # outer flank: contact direction n_o = cos(a) u + k sin(a) t, u = (cp, sp, 0), t = (-sp, cp, 0)
            nx, ny = ca * cp - kf * sa * sp, ca * sp + kf * sa * cp
            _groove(x[i], pcr * cp - (rho - gap) * nx, pcr * sp - (rho - gap) * ny, 0.0, 0.0, 0.0, 1.0, rho, kt, tmp)
            f_out[fl, i, 0], f_out[fl, i, 1], f_out[fl, i, 2] = tmp[0], tmp[1], tmp[2]
            fx, fy, fz = fx + tmp[0], fy + tmp[1], fz + tmp[2]
            # inner flank: n_i = -cos(a) u' + k sin(a) t' (inner-race axes)
            nx, ny, nz = -ca * ulx + kf * sa * tlx, -ca * uly + kf * sa * tly, -ca * ulz + kf * sa * tlz
            _groove(x[i], ic[0] + pcr * ulx - (rho - gap) * nx, ic[1] + pcr * uly - (rho - gap) * ny,
                    ic[2] + pcr * ulz - (rho - gap) * nz, d[0], d[1], d[2], rho, kt, tmp)
            f_in[fl, i, 0], f_in[fl, i, 1], f_in[fl, i, 2] = tmp[0], tmp[1], tmp[2]
            fx, fy, fz = fx + tmp[0], fy + tmp[1], fz + tmp[2]
            # torque of the force on the inner race (-tmp) about d through I
            rx, ry, rz = x[i, 0] - ic[0], x[i, 1] - ic[1], x[i, 2] - ic[2]
            on_race_torque -= ((ry * tmp[2] - rz * tmp[1]) * d[0] + (rz * tmp[0] - rx * tmp[2]) * d[1]
                               + (rx * tmp[1] - ry * tmp[0]) * d[2])
        rx, ry, rz = x[i, 0] - centre[0], x[i, 1] - centre[1], x[i, 2] - centre[2]
        sgap = rx * axis[0] + ry * axis[1] + rz * axis[2]
        pw = -(_hertz(kw, sgap - hw) - _hertz(kw, -sgap - hw))
        p_window[i] = pw
        res[3 * i] = (fx + pw * axis[0] - reg * p_n * q[6 + 3 * i]) / p_n
        res[3 * i + 1] = (fy + pw * axis[1] - reg * p_n * q[7 + 3 * i]) / p_n
        res[3 * i + 2] = (fz + pw * axis[2] - reg * p_n * q[8 + 3 * i]) / p_n
        # window force on the cage (-pw axis) through the ball centre
        gx, gy, gz = -pw * axis[0], -pw * axis[1], -pw * axis[2]
        cage_f[0] += gx
        cage_f[1] += gy
        cage_f[2] += gz
        cage_m[0] += ry * gz - rz * gy
        cage_m[1] += rz * gx - rx * gz
        cage_m[2] += rx * gy - ry * gx
    c_in = centre - e * axis
    c_out = centre + e * axis
    v = c_in - ic
    dist = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    qi = _hertz(kis, dist - cis)
    for j in range(3):
        f_ic[j] = -qi * v[j] / dist if dist > 0.0 else 0.0
    rho_o = math.sqrt(c_out[0] * c_out[0] + c_out[1] * c_out[1])
    qo = _hertz(kos, rho_o - cos_)
    f_co[0] = -qo * c_out[0] / rho_o if rho_o > 0.0 else 0.0
    f_co[1] = -qo * c_out[1] / rho_o if rho_o > 0.0 else 0.0
    f_co[2] = 0.0
    cage_f += f_ic + f_co
    for r, f in ((c_in - centre, f_ic), (c_out - centre, f_co)):
        cage_m[0] += r[1] * f[2] - r[2] * f[1]
        cage_m[1] += r[2] * f[0] - r[0] * f[2]
        cage_m[2] += r[0] * f[1] - r[1] * f[0]
    for j in range(3):
        res[18 + j] = (cage_f[j] - reg * p_n * q[1 + j]) / p_n
    b1, b2 = rot @ e1, rot @ e2
    scale = p_n * pcr
    res[21] = (cage_m[0] * b1[0] + cage_m[1] * b1[1] + cage_m[2] * b1[2] - reg * p_n * q[4] * r_tilt) / scale
    res[22] = (cage_m[0] * b2[0] + cage_m[1] * b2[1] + cage_m[2] * b2[2] - reg * p_n * q[5] * r_tilt) / scale
    res[23] = (on_race_torque + torque) / scale
    frame[0, :] = centre
    frame[1, :] = axis
    frame[2, :] = c_in
    frame[3, :] = c_out
    frame[4, 0] = beta


@njit(cache=True)
def residual(q, phase, par):
    res = np.empty(24)
    evaluate(q, phase, par, res, np.empty((2, N_BALLS, 3)), np.empty((2, N_BALLS, 3)), np.empty(N_BALLS),
             np.empty(3), np.empty(3), np.empty((N_BALLS, 3)), np.empty((5, 3)))
    return res


@njit(cache=True)
def jacobian(q, phase, par, h):
    """Central-difference Jacobian of :func:`residual` (step h, mm)."""
    n = q.size
    jac = np.empty((24, n))
    for k in range(n):
        qp = q.copy()
        qm = q.copy()
        qp[k] += h
        qm[k] -= h
        jac[:, k] = (residual(qp, phase, par) - residual(qm, phase, par)) / (2.0 * h)
    return jac
