"""Subsurface stresses under a Hertz pressure that rolls over a point: the normal stress sigma_z and the shear
tau_zx on planes parallel to the surface, along the centre line of the track (y = 0), at depth z.

Line contact (half-width b, peak p0; W. E. McEwen, Phil. Mag. 40 (1949) 454; K. L. Johnson, *Contact Mechanics*,
CUP 1985, eq. 4.49; compressive stresses negative):

    m^2 = [sqrt((b^2 - x^2 + z^2)^2 + 4 x^2 z^2) + (b^2 - x^2 + z^2)] / 2,  n^2 = [... - (b^2 - x^2 + z^2)] / 2
    sigma_z = -(p0/b) m (1 - (z^2 + n^2)/(m^2 + n^2)),  tau_zx = -(p0/b) n (m^2 - z^2)/(m^2 + n^2)

(m has the sign of z, n that of x); max |tau_zx| = 0.25 p0 at x = +-0.866 b, z = 0.5 b.

Elliptical contact (semi-axis b along the rolling direction x, k b across it; pressure
p0 sqrt(1 - x^2/b^2 - y^2/(k b)^2)): the Boussinesq point-load fields (Johnson 1985, eq. 3.20)

    sigma_z = -(3/(2 pi)) P z^3 / rho^5,   tau_zx = -(3/(2 pi)) P x z^2 / rho^5

(independent of Poisson's ratio) integrated over the ellipse by Gauss-Legendre rules in x and y, each after the
substitution u = sin(psi) that removes the square-root edge of the pressure. On the axis of a circular contact
sigma_z = -p0 / (1 + z^2/a^2) (Johnson 1985 eq. 3.44) checks the rule.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.special import roots_legendre

from quenchsim.errors import require


@dataclass(frozen=True)
class PassStresses:
    """sigma_z and tau_zx (Pa) at depth z as the contact centre passes at the offsets x (m) of the point."""

    x_m: np.ndarray
    sigma_z_Pa: np.ndarray
    tau_zx_Pa: np.ndarray


def line_contact_stresses(x_m: np.ndarray, z_m: float, half_width_m: float, p0_Pa: float) -> PassStresses:
    """McEwen's closed form (module docstring) at the points (x, z), z > 0."""
    require(math.isfinite(z_m) and z_m > 0.0, "z_m", z_m, "must be a positive depth")
    require(math.isfinite(half_width_m) and half_width_m > 0.0, "half_width_m", half_width_m, "must be positive")
    x = np.asarray(x_m, dtype=float)
    b, z = half_width_m, z_m
    A = b * b - x * x + z * z
    s = np.sqrt(A * A + 4.0 * x * x * z * z)
    m = np.sqrt(0.5 * (s + A))
    n = np.sqrt(np.clip(0.5 * (s - A), 0.0, None)) * np.sign(x)
    mn = m * m + n * n
    sz = -(p0_Pa / b) * m * (1.0 - (z * z + n * n) / mn)
    txz = -(p0_Pa / b) * n * (m * m - z * z) / mn
    return PassStresses(x, sz, txz)


@functools.lru_cache(maxsize=16)
def _sine_rule(points: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nodes u in (-1, 1), weights for int f(u) du, and sqrt(1 - u^2), from Gauss-Legendre in psi, u = sin(psi)."""
    g, w = roots_legendre(points)
    psi = g * math.pi / 2.0
    wu = w * math.pi / 2.0 * np.cos(psi)
    return np.sin(psi), wu, np.cos(psi)


def elliptical_contact_stresses(x_m: np.ndarray, z_m: float, rolling_semi_axis_m: float, ellipticity: float,
                                p0_Pa: float, *, points_x: int = 96, points_y: int | None = None) -> PassStresses:
    """sigma_z and tau_zx at (x, 0, z) under the elliptical Hertz pressure of semi-axes b (along x) and k b
    (module docstring); ``ellipticity`` k >= 1 (1: circular contact). ``points_y`` defaults to 96 (k + 1), which
    keeps the transverse spacing at the track centre below z/3 for z >= b/2."""
    require(math.isfinite(z_m) and z_m > 0.0, "z_m", z_m, "must be a positive depth")
    require(math.isfinite(rolling_semi_axis_m) and rolling_semi_axis_m > 0.0, "rolling_semi_axis_m",
            rolling_semi_axis_m, "must be positive")
    require(math.isfinite(ellipticity) and 1.0 <= ellipticity <= 20.0, "ellipticity", ellipticity,
            "must lie in [1, 20] (transverse / rolling semi-axis; beyond, use the line contact)")
    b = rolling_semi_axis_m
    u, wu, fu = _sine_rule(points_x)
    v, wv, fv = _sine_rule(points_y if points_y is not None else int(96 * (ellipticity + 1.0)))
    xs = b * u[:, None]
    half = ellipticity * b * fu[:, None]           # transverse half-chord at x
    ys = half * v[None, :]
    load = p0_Pa * fu[:, None] * fv[None, :] * (b * wu)[:, None] * (half * wv[None, :])   # pressure x area
    x = np.asarray(x_m, dtype=float)
    flat = x.ravel()
    sz, txz = np.empty(flat.size), np.empty(flat.size)
    y2z2 = ys * ys + z_m * z_m
    for i in range(0, flat.size, 16):   # chunks keep the (points, x, y) arrays small
        dx = flat[i:i + 16, None, None] - xs[None]
        k = -3.0 / (2.0 * math.pi) * load[None] / (dx * dx + y2z2[None]) ** 2.5
        sz[i:i + 16] = np.sum(k, axis=(1, 2)) * z_m**3
        txz[i:i + 16] = np.sum(k * dx, axis=(1, 2)) * z_m**2
    return PassStresses(x, sz.reshape(x.shape), txz.reshape(x.shape))


def effective_shear_range(stresses: PassStresses, friction: float) -> tuple[float, np.ndarray]:
    """Range over the pass of the crack-face shear left after friction, tau_eff = sign(tau) max(|tau_zx| -
    mu |sigma_z|, 0) (faces closed by sigma_z < 0): max(tau_eff) - min(tau_eff), and tau_eff itself."""
    require(math.isfinite(friction) and friction >= 0.0, "friction", friction, "must be >= 0")
    t = stresses.tau_zx_Pa
    eff = np.sign(t) * np.clip(np.abs(t) - friction * np.abs(stresses.sigma_z_Pa), 0.0, None)
    return float(eff.max() - eff.min()), eff
