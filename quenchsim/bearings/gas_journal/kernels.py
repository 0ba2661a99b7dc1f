"""Numba kernels of the finite-volume Reynolds operator (one implementation for every solver).

Vertex-centred finite volumes on the skewed grid (see geometry.py). Each cell (j, i) with corners
a = (j, i), b = (j, i+1), c = (j+1, i+1), d = (j+1, i) carries four half-faces of the control volumes
of its corners: ab and dc (constant xi, length h_eta / 2) and ad and bc (constant eta, length h_xi / 2).
The mass flux through a half-face from node 1 to node 2 (divergence formulation, reference section 1):

    F = [ -P_f (D_main (P_2 - P_1) / dist + D_cross g_cross) + Lambda c (w_1 P_1 + w_2 P_2) ] * length

with P_f = (P_1 + P_2) / 2, the cross derivative g_cross averaged over the cell, the film coefficients
(D_main, D_cross, c) of the half-face (H^3 times the metric of the skew, and H for the Couette term)
and the upwind weights w frozen between updates (Kawabata-type blending, see ``upwind_weights``).
The operator at node p is L_p(P) = sum of outflows + sigma_p P_p (sigma: Crank-Nicolson mass term);
the equations are L(P) = f at every node except the ambient row (P = 1).
Coefficient array ``coef`` has shape (n_eta, n_xi, 4, 3): half-faces [ab, dc, ad, bc] x
[D_main, D_cross, c]; weights ``w`` (n_eta, n_xi, 4) hold w_1 of each half-face.
"""

from __future__ import annotations

import numpy as np
from numba import njit

# Upwind blending of the Couette face value, c = max(1 - 2 / A, 0) (Kawabata et al. scheme as quoted
# in reference section 1). The reference also recommends a "blending parameter 0.85"; read as a
# multiplier of c it leaves a downwind weight 0.075 that makes the off-diagonal coefficients positive
# for A > 13 (coarse grids at Lambda = 100) and point relaxation then diverged (measured), so c is
# used unscaled: the scheme stays positive for every A and is unchanged (c = 0) wherever A <= 2.
UPWIND_BLEND = 1.0
# Largest relative change of P in one point update: far from the solution (P = 1 start at
# Lambda = 100) undamped point-Newton steps compound along a sweep and diverge (measured); near the
# solution the limit is inactive.
MAX_POINT_CHANGE = 0.5


@njit(cache=True, inline="always")
def _flux(p1, p2, dist, cross, dmain, dcross, conv, w1, length):
    pf = 0.5 * (p1 + p2)
    q = dmain * (p2 - p1) / dist + dcross * cross
    f = (-pf * q + conv * (w1 * p1 + (1.0 - w1) * p2)) * length
    d1 = (-0.5 * q + pf * dmain / dist + conv * w1) * length
    d2 = (-0.5 * q - pf * dmain / dist + conv * (1.0 - w1)) * length
    dc = -pf * dcross * length
    return f, d1, d2, dc


@njit(cache=True, inline="always")
def _face_flux(p1, p2, dist, cross, dmain, dcross, conv, w1, length):
    return (-0.5 * (p1 + p2) * (dmain * (p2 - p1) / dist + dcross * cross)
            + conv * (w1 * p1 + (1.0 - w1) * p2)) * length


@njit(cache=True, inline="always")
def _cell_outflow(pa, pb, pc, pd, cf, w, hx, hy, lam, r):
    """Outflow contributions r[4] of one cell to its corners (no derivatives)."""
    ce = (pd + pc - pa - pb) / (2.0 * hy)
    cx = (pb + pc - pa - pd) / (2.0 * hx)
    fab = _face_flux(pa, pb, hx, ce, cf[0, 0], cf[0, 1], lam * cf[0, 2], w[0], 0.5 * hy)
    fdc = _face_flux(pd, pc, hx, ce, cf[1, 0], cf[1, 1], lam * cf[1, 2], w[1], 0.5 * hy)
    fad = _face_flux(pa, pd, hy, cx, cf[2, 0], cf[2, 1], lam * cf[2, 2], w[2], 0.5 * hx)
    fbc = _face_flux(pb, pc, hy, cx, cf[3, 0], cf[3, 1], lam * cf[3, 2], w[3], 0.5 * hx)
    r[0] = fab + fad
    r[1] = -fab + fbc
    r[2] = -fdc - fbc
    r[3] = fdc - fad


@njit(cache=True, inline="always")
def _cell_top(pa, pb, pc, pd, cf, w, hx, hy, lam):
    """Outflows of one cell at its top corners c, d and their derivatives with respect to P_c, P_d:
    (r_c, r_d, dr_c/dP_c, dr_c/dP_d, dr_d/dP_c, dr_d/dP_d)."""
    ce = (pd + pc - pa - pb) / (2.0 * hy)
    cx = (pb + pc - pa - pd) / (2.0 * hx)
    ey = 0.5 / hy
    ex = 0.5 / hx
    fdc, dc1, dc2, dcc = _flux(pd, pc, hx, ce, cf[1, 0], cf[1, 1], lam * cf[1, 2], w[1], 0.5 * hy)
    fad, ad1, ad2, adc = _flux(pa, pd, hy, cx, cf[2, 0], cf[2, 1], lam * cf[2, 2], w[2], 0.5 * hx)
    fbc, bc1, bc2, bcc = _flux(pb, pc, hy, cx, cf[3, 0], cf[3, 1], lam * cf[3, 2], w[3], 0.5 * hx)
    dc_c = dc2 + dcc * ey
    dc_d = dc1 + dcc * ey
    bc_c = bc2 + bcc * ex
    bc_d = -bcc * ex
    ad_c = adc * ex
    ad_d = ad2 - adc * ex
    return (-fdc - fbc, fdc - fad, -dc_c - bc_c, -dc_d - bc_d, dc_c - ad_c, dc_d - ad_d)


@njit(cache=True, inline="always")
def _cell_bottom(pa, pb, pc, pd, cf, w, hx, hy, lam):
    """Outflows of one cell at its bottom corners a, b and their derivatives with respect to P_a, P_b:
    (r_a, r_b, dr_a/dP_a, dr_a/dP_b, dr_b/dP_a, dr_b/dP_b)."""
    ce = (pd + pc - pa - pb) / (2.0 * hy)
    cx = (pb + pc - pa - pd) / (2.0 * hx)
    ey = 0.5 / hy
    ex = 0.5 / hx
    fab, ab1, ab2, abc = _flux(pa, pb, hx, ce, cf[0, 0], cf[0, 1], lam * cf[0, 2], w[0], 0.5 * hy)
    fad, ad1, ad2, adc = _flux(pa, pd, hy, cx, cf[2, 0], cf[2, 1], lam * cf[2, 2], w[2], 0.5 * hx)
    fbc, bc1, bc2, bcc = _flux(pb, pc, hy, cx, cf[3, 0], cf[3, 1], lam * cf[3, 2], w[3], 0.5 * hx)
    ab_a = ab1 - abc * ey
    ab_b = ab2 - abc * ey
    ad_a = ad1 - adc * ex
    ad_b = adc * ex
    bc_a = -bcc * ex
    bc_b = bc1 + bcc * ex
    return (fab + fad, -fab + fbc, ab_a + ad_a, ab_b + ad_b, -ab_a + bc_a, -ab_b + bc_b)


@njit(cache=True)
def _cell(pa, pb, pc, pd, cf, w, hx, hy, lam, r, jac):
    """Outflow contributions r[4] of one cell to its corners a, b, c, d and their 4x4 Jacobian."""
    ce = (pd + pc - pa - pb) / (2.0 * hy)
    cx = (pb + pc - pa - pd) / (2.0 * hx)
    ey = 0.5 / hy
    ex = 0.5 / hx
    fab, ab1, ab2, abc = _flux(pa, pb, hx, ce, cf[0, 0], cf[0, 1], lam * cf[0, 2], w[0], 0.5 * hy)
    fdc, dc1, dc2, dcc = _flux(pd, pc, hx, ce, cf[1, 0], cf[1, 1], lam * cf[1, 2], w[1], 0.5 * hy)
    fad, ad1, ad2, adc = _flux(pa, pd, hy, cx, cf[2, 0], cf[2, 1], lam * cf[2, 2], w[2], 0.5 * hx)
    fbc, bc1, bc2, bcc = _flux(pb, pc, hy, cx, cf[3, 0], cf[3, 1], lam * cf[3, 2], w[3], 0.5 * hx)
    r[0] = fab + fad
    r[1] = -fab + fbc
    r[2] = -fdc - fbc
    r[3] = fdc - fad
    # derivatives of each half-face flux with respect to corners a, b, c, d
    gab0 = ab1 - abc * ey
    gab1 = ab2 - abc * ey
    gab2 = abc * ey
    gab3 = abc * ey
    gdc0 = -dcc * ey
    gdc1 = -dcc * ey
    gdc2 = dc2 + dcc * ey
    gdc3 = dc1 + dcc * ey
    gad0 = ad1 - adc * ex
    gad1 = adc * ex
    gad2 = adc * ex
    gad3 = ad2 - adc * ex
    gbc0 = -bcc * ex
    gbc1 = bc1 + bcc * ex
    gbc2 = bc2 + bcc * ex
    gbc3 = -bcc * ex
    jac[0, 0] = gab0 + gad0
    jac[0, 1] = gab1 + gad1
    jac[0, 2] = gab2 + gad2
    jac[0, 3] = gab3 + gad3
    jac[1, 0] = -gab0 + gbc0
    jac[1, 1] = -gab1 + gbc1
    jac[1, 2] = -gab2 + gbc2
    jac[1, 3] = -gab3 + gbc3
    jac[2, 0] = -gdc0 - gbc0
    jac[2, 1] = -gdc1 - gbc1
    jac[2, 2] = -gdc2 - gbc2
    jac[2, 3] = -gdc3 - gbc3
    jac[3, 0] = gdc0 - gad0
    jac[3, 1] = gdc1 - gad1
    jac[3, 2] = gdc2 - gad2
    jac[3, 3] = gdc3 - gad3


@njit(cache=True)
def apply_operator(p, coef, w, sigma, hx, hy, lam, out):
    """out = L(P) at every node (row 0 included, unused)."""
    ny, nx = p.shape
    r = np.empty(4)
    for j in range(ny):
        for i in range(nx):
            out[j, i] = sigma[j, i] * p[j, i]
    for j in range(ny - 1):
        for i in range(nx):
            ip = i + 1 if i + 1 < nx else 0
            _cell_outflow(p[j, i], p[j, ip], p[j + 1, ip], p[j + 1, i], coef[j, i], w[j, i], hx, hy, lam, r)
            out[j, i] += r[0]
            out[j, ip] += r[1]
            out[j + 1, ip] += r[2]
            out[j + 1, i] += r[3]


@njit(cache=True)
def relax(p, f, coef, w, sigma, hx, hy, lam, omega, sweeps):
    """Point Gauss-Seidel-Newton sweeps, P_p <- P_p + omega (f_p - L_p(P)) / max(dL_p / dP_p, floor_p).

    omega = 1: Gauss-Seidel (and the optional point smoother of the multigrid); omega > 1: SOR.
    Lexicographic order, downstream (increasing xi) inner loop; |dP| <= MAX_POINT_CHANGE * P per
    update. floor_p is the frozen-coefficient diffusive diagonal (keeps the step bounded where the
    Newton diagonal is small). Uses the cell functions of the line smoother (_cell_top, _cell_bottom).
    """
    ny, nx = p.shape
    rx = 0.25 * hy / hx
    ry = 0.25 * hx / hy
    for _ in range(sweeps):
        for j in range(1, ny):
            for i in range(nx):
                im = i - 1 if i > 0 else nx - 1
                ip = i + 1 if i + 1 < nx else 0
                pc = p[j, i]
                lp = sigma[j, i] * pc
                dl = sigma[j, i]
                # cell (j-1, i-1): node is corner c
                cf = coef[j - 1, im]
                pa, pb, pd = p[j - 1, im], p[j - 1, i], p[j, im]
                r_c, r_d, j_cc, j_cd, j_dc, j_dd = _cell_top(pa, pb, pc, pd, cf, w[j - 1, im], hx, hy, lam)
                lp += r_c
                dl += j_cc
                floor = (pd + pc) * cf[1, 0] * rx + (pb + pc) * cf[3, 0] * ry
                # cell (j-1, i): node is corner d
                cf = coef[j - 1, i]
                pa, pb, pcc = p[j - 1, i], p[j - 1, ip], p[j, ip]
                r_c, r_d, j_cc, j_cd, j_dc, j_dd = _cell_top(pa, pb, pcc, pc, cf, w[j - 1, i], hx, hy, lam)
                lp += r_d
                dl += j_dd
                floor += (pc + pcc) * cf[1, 0] * rx + (pa + pc) * cf[2, 0] * ry
                if j < ny - 1:
                    # cell (j, i-1): node is corner b
                    cf = coef[j, im]
                    pa, pcc, pd = p[j, im], p[j + 1, i], p[j + 1, im]
                    r_a, r_b, j_aa, j_ab, j_ba, j_bb = _cell_bottom(pa, pc, pcc, pd, cf, w[j, im], hx, hy, lam)
                    lp += r_b
                    dl += j_bb
                    floor += (pa + pc) * cf[0, 0] * rx + (pc + pcc) * cf[3, 0] * ry
                    # cell (j, i): node is corner a
                    cf = coef[j, i]
                    pb, pcc, pd = p[j, ip], p[j + 1, ip], p[j + 1, i]
                    r_a, r_b, j_aa, j_ab, j_ba, j_bb = _cell_bottom(pc, pb, pcc, pd, cf, w[j, i], hx, hy, lam)
                    lp += r_a
                    dl += j_aa
                    floor += (pc + pb) * cf[0, 0] * rx + (pc + pd) * cf[2, 0] * ry
                step = omega * (f[j, i] - lp) / max(dl, floor + sigma[j, i])
                if not np.isfinite(step):
                    step = 0.0
                limit = MAX_POINT_CHANGE * pc
                p[j, i] = pc + min(max(step, -limit), limit)


@njit(cache=True)
def jacobian_values(p, coef, w, hx, hy, lam, out):
    """Local 4x4 Jacobians of every cell, out shape (n_eta, n_xi, 4, 4) (rows: corners a, b, c, d)."""
    ny, nx = p.shape
    r = np.empty(4)
    for j in range(ny - 1):
        for i in range(nx):
            ip = i + 1 if i + 1 < nx else 0
            _cell(p[j, i], p[j, ip], p[j + 1, ip], p[j + 1, i], coef[j, i], w[j, i], hx, hy, lam, r, out[j, i])


@njit(cache=True)
def upwind_weights(p, coef, hx, hy, lam, out):
    """Weight w_1 of the first node of each half-face from the current P.

    Face value of P = (1 + c)/2 P_upwind + (1 - c)/2 P_downwind, c = UPWIND_BLEND * max(1 - 2/A, 0),
    A = |Lambda c_face| dist / (P_f D_main) (cell Peclet number; reference section 1, Kawabata et al.).
    """
    ny, nx = p.shape
    for j in range(ny - 1):
        for i in range(nx):
            ip = i + 1 if i + 1 < nx else 0
            pairs = ((p[j, i], p[j, ip], hx), (p[j + 1, i], p[j + 1, ip], hx),
                     (p[j, i], p[j + 1, i], hy), (p[j, ip], p[j + 1, ip], hy))
            for k in range(4):
                p1, p2, dist = pairs[k]
                conv = lam * coef[j, i, k, 2]
                if conv == 0.0:
                    out[j, i, k] = 0.5
                    continue
                peclet = abs(conv) * dist / (0.5 * (p1 + p2) * coef[j, i, k, 0])
                c = UPWIND_BLEND * max(1.0 - 2.0 / peclet, 0.0)
                out[j, i, k] = 0.5 * (1.0 + c) if conv > 0.0 else 0.5 * (1.0 - c)


@njit(cache=True)
def _solve_periodic_tridiagonal(lower, diag, upper, rhs, out):
    """Solve the cyclic system lower[i] x[i-1] + diag[i] x[i] + upper[i] x[i+1] = rhs[i] (indices mod n)
    by the Thomas algorithm with a Sherman-Morrison correction for the two corner entries."""
    n = diag.size
    gamma = -diag[0]
    b = diag.copy()
    b[0] -= gamma
    b[n - 1] -= upper[n - 1] * lower[0] / gamma
    u = np.zeros(n)
    u[0] = gamma
    u[n - 1] = upper[n - 1]
    c = np.empty(n)
    x = rhs.copy()
    z = u.copy()
    c[0] = upper[0] / b[0]
    x[0] /= b[0]
    z[0] /= b[0]
    for i in range(1, n):
        m = b[i] - lower[i] * c[i - 1]
        c[i] = upper[i] / m
        x[i] = (x[i] - lower[i] * x[i - 1]) / m
        z[i] = (z[i] - lower[i] * z[i - 1]) / m
    for i in range(n - 2, -1, -1):
        x[i] -= c[i] * x[i + 1]
        z[i] -= c[i] * z[i + 1]
    factor = (x[0] + lower[0] * x[n - 1] / gamma) / (1.0 + z[0] + lower[0] * z[n - 1] / gamma)
    for i in range(n):
        out[i] = x[i] - factor * z[i]


@njit(cache=True)
def relax_lines(p, f, coef, w, sigma, hx, hy, lam, sweeps):
    """Circumferential-line Gauss-Seidel-Newton: each row of nodes (constant eta, periodic in xi) takes
    one Newton step of its own equations with the other rows frozen (cyclic tridiagonal solve),
    rows swept from the ambient end to the mid-plane. Same flux formulas as ``relax``.
    The row step is scaled so that no |dP| exceeds MAX_POINT_CHANGE * P."""
    ny, nx = p.shape
    res = np.empty(nx)
    dia = np.empty(nx)
    low = np.empty(nx)
    upp = np.empty(nx)
    delta = np.empty(nx)
    for _ in range(sweeps):
        for j in range(1, ny):
            for i in range(nx):
                res[i] = f[j, i] - sigma[j, i] * p[j, i]
                dia[i] = sigma[j, i]
                low[i] = 0.0
                upp[i] = 0.0
            for i in range(nx):
                ip = i + 1 if i + 1 < nx else 0
                # cell (j-1, i): row nodes are its corners d = (j, i) and c = (j, i+1)
                rc, rd, jcc, jcd, jdc, jdd = _cell_top(p[j - 1, i], p[j - 1, ip], p[j, ip], p[j, i], coef[j - 1, i],
                                                       w[j - 1, i], hx, hy, lam)
                res[i] -= rd
                dia[i] += jdd
                upp[i] += jdc
                res[ip] -= rc
                dia[ip] += jcc
                low[ip] += jcd
                if j < ny - 1:
                    # cell (j, i): row nodes are its corners a = (j, i) and b = (j, i+1)
                    ra, rb, jaa, jab, jba, jbb = _cell_bottom(p[j, i], p[j, ip], p[j + 1, ip], p[j + 1, i], coef[j, i],
                                                              w[j, i], hx, hy, lam)
                    res[i] -= ra
                    dia[i] += jaa
                    upp[i] += jab
                    res[ip] -= rb
                    dia[ip] += jbb
                    low[ip] += jba
            _solve_periodic_tridiagonal(low, dia, upp, res, delta)
            scale = 1.0
            for i in range(nx):
                if not np.isfinite(delta[i]):
                    scale = 0.0
                elif abs(delta[i]) * scale > MAX_POINT_CHANGE * p[j, i]:
                    scale = MAX_POINT_CHANGE * p[j, i] / abs(delta[i])
            for i in range(nx):
                p[j, i] += scale * delta[i]
