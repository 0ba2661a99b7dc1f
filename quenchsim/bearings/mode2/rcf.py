"""Rolling-contact use of the mode II threshold (Fujii, Maeda & Ohtsuka, NTN Technical Review 69 (2001) 53,
sec. 5): the smallest subsurface crack that grows in mode II under a rolling Hertz contact.

A penny crack of diameter 2a lies parallel to the surface under the centre line of the track at depth z = b/2
(b: the contact's semi-axis along the rolling direction, the semi-minor axis of a ball-type contact), where the
shear on planes parallel to the surface is about largest. As the contact passes, tau_zx reverses; crack-face
friction mu under the compressive sigma_z holds back mu |sigma_z|, so the effective shear range is

    Delta tau_eff = range over the pass of sign(tau_zx) max(|tau_zx| - mu |sigma_z|, 0)

(:mod:`.subsurface`), and the crack grows once Delta K_II,max = 4/(pi (2 - nu)) Delta tau_eff sqrt(pi a) reaches
Delta K_IIth (:mod:`.sif`). For a crack much smaller than the contact, Delta tau_eff = c(shape) p_max, so

    2a_crit = (2/pi) (Delta K_IIth pi (2 - nu) / (4 c p_max))^2   ~ p_max^-2  exactly.

An inclusion is compared with the critical crack through Murakami's sqrt(area) parameter (Y. Murakami, M. Endo,
"Effects of defects, inclusions and inhomogeneities on fatigue strength", Int. J. Fatigue 16 (1994) 163: a defect
acts as a crack of the same projected area): a penny crack of diameter 2a has sqrt(area) = sqrt(pi) a
(:func:`inclusion_over_critical`).

The paper computes its Fig. 14 curve with the handbook SIF of Murakami (1987, p. 1155) and does not print the
contact shape; a line contact (c = 0.209 with mu = 0.5) and a circular one (c = 0.154) bound the shapes between.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from quenchsim.bearings.mode2 import sif
from quenchsim.bearings.mode2.subsurface import (effective_shear_range, elliptical_contact_stresses,
                                                 line_contact_stresses)
from quenchsim.errors import require

PASS_HALF_LENGTH = 4.0
"""The pass is searched over |x| <= 4 b (the stresses at z = b/2 are below 1 % of p0 beyond)."""
PASS_POINTS = 81
"""Coarse grid of the pass; the largest and smallest effective shear are then refined by a bounded search."""


@dataclass(frozen=True)
class CriticalCrack:
    """Critical penny-crack diameter at one contact pressure, with the shape factor c = Delta tau_eff / p_max."""

    p_max_Pa: float
    shape: str
    ellipticity: float
    shear_range_factor: float
    shear_range_Pa: float
    critical_diameter_m: float


@functools.lru_cache(maxsize=64)
def shear_range_factor(shape: str, ellipticity: float = 1.0, friction: float = 0.5, depth_over_b: float = 0.5) -> float:
    """c = Delta tau_eff / p_max at depth ``depth_over_b`` b for a ``shape`` "line" or "ellipse" (``ellipticity``
    k = transverse / rolling semi-axis; 1 is circular)."""
    require(shape in ("line", "ellipse"), "shape", shape, "must be 'line' or 'ellipse'")
    require(math.isfinite(depth_over_b) and depth_over_b > 0.0, "depth_over_b", depth_over_b, "must be > 0")

    def stresses(x: np.ndarray):
        if shape == "line":
            return line_contact_stresses(x, depth_over_b, 1.0, 1.0)
        return elliptical_contact_stresses(x, depth_over_b, 1.0, ellipticity, 1.0)

    def tau_eff(x: float) -> float:
        return float(effective_shear_range(stresses(np.array([x])), friction)[1][0])

    x = np.linspace(-PASS_HALF_LENGTH, PASS_HALF_LENGTH, PASS_POINTS)
    eff = effective_shear_range(stresses(x), friction)[1]
    step = x[1] - x[0]
    extremes = []
    for sign, i in ((1.0, int(np.argmax(eff))), (-1.0, int(np.argmin(eff)))):
        r = minimize_scalar(lambda q: -sign * tau_eff(q), bounds=(x[i] - step, x[i] + step), method="bounded",
                            options={"xatol": 1e-6})
        extremes.append(max(sign * eff[i], -r.fun))
    return extremes[0] + extremes[1]


def critical_crack(p_max_Pa: float, shape: str = "line", ellipticity: float = 1.0, *, threshold_Pa_sqrt_m: float | None = None,
                   friction: float | None = None, nu: float = 0.3, depth_over_b: float | None = None) -> CriticalCrack:
    """Critical 2a at the peak contact pressure ``p_max_Pa`` (module docstring); the threshold, friction and depth
    default to the paper's (data/mode2_crack.toml)."""
    require(math.isfinite(p_max_Pa) and p_max_Pa > 0.0, "p_max_Pa", p_max_Pa, "must be a positive pressure")
    d = sif.crack_data()
    th = d["material"]["delta_K_IIth_MPa_sqrt_m"] * 1e6 if threshold_Pa_sqrt_m is None else threshold_Pa_sqrt_m
    mu = d["rolling_contact"]["face_friction"] if friction is None else friction
    zb = d["rolling_contact"]["depth_over_b"] if depth_over_b is None else depth_over_b
    c = shear_range_factor(shape, float(ellipticity) if shape == "ellipse" else 1.0, mu, zb)
    require(c > 0.0, "friction", mu, "leaves no effective shear: no mode II growth at any crack size")
    return CriticalCrack(p_max_Pa=p_max_Pa, shape=shape, ellipticity=ellipticity if shape == "ellipse" else math.inf,
                         shear_range_factor=c, shear_range_Pa=c * p_max_Pa,
                         critical_diameter_m=sif.penny_critical_diameter_m(th, c * p_max_Pa, nu))


def ellipticity_for(shear_range_factor_needed: float, friction: float = 0.5, depth_over_b: float = 0.5) -> float:
    """The ellipticity k whose shape factor c(k) equals the one needed (c grows from 0.154 at k = 1 toward the
    line-contact 0.209); raises when the value lies outside that interval."""
    from scipy.optimize import brentq

    lo, hi = (shear_range_factor("ellipse", k, friction, depth_over_b) for k in (1.0, 20.0))
    require(lo <= shear_range_factor_needed <= hi, "shear_range_factor", shear_range_factor_needed,
            f"must lie between the circular {lo:.4f} and the k = 20 {hi:.4f} contact")
    return brentq(lambda k: shear_range_factor("ellipse", k, friction, depth_over_b) - shear_range_factor_needed,
                  1.0, 20.0, xtol=1e-4)


def inclusion_over_critical(sqrt_area_m: float, critical_diameter_m: float) -> float:
    """sqrt(area) of an inclusion over that of the critical penny crack of diameter ``critical_diameter_m``
    (sqrt(pi (2a/2)^2) = (sqrt(pi) / 2) 2a; Murakami & Endo 1994): above 1 the inclusion, taken as a crack of
    its area, grows in mode II under that contact.

    >>> round(inclusion_over_critical(math.sqrt(math.pi) * 5e-6, 10e-6), 12)
    1.0
    """
    require(math.isfinite(sqrt_area_m) and sqrt_area_m > 0.0, "sqrt_area_m", sqrt_area_m, "must be > 0")
    require(math.isfinite(critical_diameter_m) and critical_diameter_m > 0.0, "critical_diameter_m",
            critical_diameter_m, "must be > 0")
    return sqrt_area_m / (0.5 * math.sqrt(math.pi) * critical_diameter_m)
