"""Hertz point-contact stiffness of the four contact pairs of a DOJ: Q = K delta^1.5 (N, mm).

Exact elliptic integrals (quenchsim.bearings.hertz). Principal radii (concave negative), the physical ones:

* ball - track (straight track of circular groove): ball r_b in both directions; track infinite along it and
  -r_groove across it;
* ball - cage window (flat face): ball r_b; flat;
* inner-race sphere - cage inner sphere: R_is against -R_ci (both directions);
* cage outer sphere - outer-race bore (cylinder): R_co; bore infinite along its axis and -R_ob around it.

The paper (Hayama 2001, sec. 2.2, Fig. 5) prints r_bx = r_by for every pair, i.e. a radius ratio of 1 even for the
straight track and the flat window; the physical radii are used here (docs/reference/other_seed_systems.md sec. 1.2
developer note). Its stiffness uses the curve fits k ~ a^0.634, F ~ 1.539 + 0.5961 ln a, E ~ 1 + 0.576 / a
(a = R_y / R_x >= 1) in K = pi k E' sqrt(2 E R / (9 F^3)): :func:`hayama_fit_stiffness` for comparison.

A conformal pair with equal radii (the zero-clearance cases) has no Hertz stiffness (R -> infinity): its radius
difference is floored at CONFORMAL_FLOOR_MM for the stiffness only (an assumption: Hertz theory is not valid for such
conformal contacts anyway; the floor makes the contact a stiff penalty).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from quenchsim.bearings import hertz
from quenchsim.bearings.doj.geometry import Clearances, DOJGeometry

FLAT_M = 1e12  # radius of a flat face for hertz.py (finite radii only)
CONFORMAL_FLOOR_MM = 1e-3  # smallest radius difference of a conformal pair used for its stiffness
_N_M15_TO_N_MM15 = 1e-3 ** 1.5


@dataclass(frozen=True)
class ContactStiffness:
    """K (N/mm^1.5) of the ball-track, ball-window, inner-sphere and outer-sphere contacts."""

    track: float
    window: float
    inner_sphere: float
    outer_sphere: float


def _k(rx1_mm: float, ry1_mm: float, rx2_mm: float, ry2_mm: float, geo: DOJGeometry) -> float:
    to_m = lambda r: r * 1e-3 if abs(r) < FLAT_M else r  # noqa: E731
    k = hertz.point_contact_stiffness(to_m(rx1_mm), to_m(ry1_mm), to_m(rx2_mm), to_m(ry2_mm),
                                      geo.youngs_modulus_Pa, geo.poisson, geo.youngs_modulus_Pa, geo.poisson)
    return k * _N_M15_TO_N_MM15


def contact_stiffness(geo: DOJGeometry, clearances: Clearances) -> ContactStiffness:
    """Hertz stiffness of the four pairs with the physical principal radii (module docstring)."""
    rb = geo.ball_radius_mm
    r_ci = geo.inner_race_sphere_radius_mm + max(clearances.inner_sphere_mm, CONFORMAL_FLOOR_MM)
    r_ob = geo.cage_outer_sphere_radius_mm + max(clearances.outer_sphere_mm, CONFORMAL_FLOOR_MM)
    return ContactStiffness(
        track=_k(rb, rb, FLAT_M, -geo.groove_radius_mm, geo),
        window=_k(rb, rb, FLAT_M, FLAT_M, geo),
        inner_sphere=_k(geo.inner_race_sphere_radius_mm, geo.inner_race_sphere_radius_mm, -r_ci, -r_ci, geo),
        outer_sphere=_k(geo.cage_outer_sphere_radius_mm, geo.cage_outer_sphere_radius_mm, FLAT_M, -r_ob, geo))


def hayama_fit_stiffness(Rx_mm: float, Ry_mm: float, effective_modulus_Pa: float) -> float:
    """K (N/mm^1.5) by the paper's Eqs. (3)-(11): pi k E' sqrt(2 E R / (9 F^3)) with k = a^0.634,
    F = 1.539 + 0.5961 ln a, E = 1 + 0.576 / a, a = max/min of the curvature-sum radii R_x, R_y (mm) and
    R = (1/R_x + 1/R_y)^-1 (E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2), Pa).

    >>> Ep = 2.08e11 / (1 - 0.3 ** 2)                       # two steel bodies
    >>> exact = 4.0 / 3.0 * (Ep / 2) * 1e-6 * 1.0 ** 0.5     # sphere of radius 1 mm on a flat, N/mm^1.5
    >>> round(hayama_fit_stiffness(1.0, 1.0, Ep) / exact, 4)  # the fits are 3.3 % stiff at a = 1
    1.0329
    """
    a = max(Rx_mm, Ry_mm) / min(Rx_mm, Ry_mm)
    R = 1.0 / (1.0 / Rx_mm + 1.0 / Ry_mm)
    k, F, E = a ** 0.634, 1.539 + 0.5961 * math.log(a), 1.0 + 0.576 / a
    return math.pi * k * effective_modulus_Pa * 1e-6 * math.sqrt(2.0 * E * R / (9.0 * F ** 3))
