"""Hertz contact of elastic bodies: elliptical point contact and line contact.

Point contact (two bodies with aligned principal planes, x and y). The gap between the
surfaces is h = x^2 / (2 R_x) + y^2 / (2 R_y) with the curvature sums

    1/R_x = 1/r_x1 + 1/r_x2,   1/R_y = 1/r_y1 + 1/r_y2,   1/R = 1/R_x + 1/R_y

(principal radii of both bodies; a concave radius, e.g. a raceway groove, is negative).
For the contact ellipse with semi-axes a >= b, eccentricity e^2 = m = 1 - 1/k^2 and
ellipticity k = a/b, Hertz's solution (K. L. Johnson, *Contact Mechanics*, CUP 1985, sec. 3.5;
B. J. Hamrock & D. Dowson, *Ball Bearing Lubrication*, Wiley 1981, ch. 3) gives

    R_major / R_minor = (k^2 E(m) - K(m)) / (K(m) - E(m))           (solved exactly for k)
    b = (6 E(m) Q R / (pi k E'))^(1/3),  a = k b,  p_max = 3 Q / (2 pi a b)
    delta = 3 K(m) Q / (pi a E') = K(m) [9/(2 E(m) R) (Q/(pi k E'))^2]^(1/3)
    Q = K_n delta^1.5,  K_n = pi k E' sqrt(2 E(m) R / (9 K(m)^3))

with K, E the complete elliptic integrals of the first and second kind (parameter m) and the
effective modulus E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2). No curve fits are used.

Line contact (two parallel cylinders, length L, load w = Q/L per unit length), Johnson sec. 4.2:

    b = sqrt(8 w R / (pi E')),  p_max = 2 w / (pi b),  1/R = 1/r1 + 1/r2

and, on the symmetry axis, the principal shear stress tau_1 = (p_max/b)(z - z^2/sqrt(b^2 + z^2))
peaks where (z/b)^2 = (sqrt(5) - 1)/2, i.e. z = 0.7862 b, tau_1 = 0.3003 p_max.

Static capacity (ISO 76:2006, data/iso76_static_limits.toml): a contact is at its static load rating when its
peak pressure reaches 4000 MPa (roller bearings), 4200 MPa (ball bearings) or 4600 MPa (self-aligning ball
bearings), where the permanent (brinell) deformation is about 1e-4 of the rolling element's diameter. Since
Q ~ p_max^2 for a line contact and Q ~ p_max^3 for a point contact of fixed geometry, the static safety factor
s0 = C0 / P0 of a contact at p_max is (p_limit / p_max)^2 or ^3 (:func:`static_safety_factor`); s0 < 1 means
a brinell dent deeper than the standard accepts.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

from scipy.optimize import brentq
from scipy.special import ellipe, ellipkm1

from quenchsim.errors import require
from quenchsim.inputs.reader import read_package_toml

# Below this value of (R_major/R_minor - 1) the exact ratio equation suffers cancellation
# (K - E ~ pi m / 4); the first-order expansion k = 1 + 2/3 (ratio - 1) is exact to O(1e-12) there.
_NEAR_CIRCULAR = 1.0e-6
# Largest ellipticity searched (ratio R_major/R_minor ~ 1e16, far beyond any real contact).
_K_MAX = 1.0e8

# Depth and magnitude of the maximum principal shear stress under a line contact (closed form of
# d tau_1 / dz = 0 on the axis: u^2 + u - 1 = 0 with u = (z/b)^2; Johnson 1985, eq. 4.49 and fig. 4.6).
_U_LINE = (math.sqrt(5.0) - 1.0) / 2.0
LINE_SHEAR_DEPTH_RATIO = math.sqrt(_U_LINE)
LINE_SHEAR_RATIO = LINE_SHEAR_DEPTH_RATIO - _U_LINE / math.sqrt(1.0 + _U_LINE)


@dataclass(frozen=True)
class PointContact:
    """Hertz point contact: semi-axes a >= b, peak pressure, mutual approach, ellipticity a/b,
    stiffness K_n with Q = K_n delta^1.5, and the direction ("x" or "y") of the major axis."""

    a_m: float
    b_m: float
    p_max_Pa: float
    approach_m: float
    ellipticity: float
    stiffness_N_m15: float
    major_axis: str


@dataclass(frozen=True)
class LineContact:
    """Hertz line contact: half width, peak pressure, depth and value of the max principal shear."""

    half_width_m: float
    p_max_Pa: float
    depth_max_shear_m: float
    max_shear_Pa: float


@dataclass(frozen=True)
class BallRaceStiffness:
    """Load-deflection constants (Q = K delta^1.5) of the inner and outer ball-race contacts and of
    the two in series: K = K_i K_o / (K_i^(2/3) + K_o^(2/3))^1.5."""

    inner_N_m15: float
    outer_N_m15: float
    combined_N_m15: float


@dataclass(frozen=True)
class _EllipseShape:
    """Load-independent part of a point contact: k, K(m), E(m), R, E' and the major-axis direction."""

    k: float
    K: float
    E: float
    R: float
    E_eff: float
    major_axis: str


@functools.cache
def reference_data() -> dict[str, Any]:
    """Published numbers for checks (data/hertz_reference.toml): the Timoshenko-Goodier table of the
    ellipse coefficients m, n and the roller-clutch line contacts of reference sec. 7."""
    return read_package_toml("quenchsim.bearings", "data/hertz_reference.toml")


@functools.lru_cache(maxsize=1)
def iso76_limits() -> dict[str, Any]:
    """The ISO 76 contact-stress limits (data/iso76_static_limits.toml, with its ``source``)."""
    return read_package_toml("quenchsim.bearings", "data/iso76_static_limits.toml")


ISO76_KINDS = ("roller", "ball", "self_aligning_ball")


def static_safety_factor(p_max_Pa: float, kind: str = "roller") -> float:
    """ISO 76's s0 = C0 / P0 of one contact at the peak pressure ``p_max_Pa``: (p_limit / p_max)^2 for a
    roller (line contact), (p_limit / p_max)^3 for a ball (point contact); ``kind`` one of ISO76_KINDS.

    >>> round(static_safety_factor(4000e6, "roller"), 12), round(static_safety_factor(2100e6, "ball"), 12)
    (1.0, 8.0)
    """
    require(kind in ISO76_KINDS, "kind", kind, f"one of {', '.join(ISO76_KINDS)}")
    require(math.isfinite(p_max_Pa) and p_max_Pa > 0.0, "p_max_Pa", p_max_Pa, "must be a positive pressure")
    limit = iso76_limits()[f"{kind}_MPa"] * 1e6
    return (limit / p_max_Pa) ** (2 if kind == "roller" else 3)


def effective_modulus_Pa(E1_Pa: float, nu1: float, E2_Pa: float, nu2: float) -> float:
    """E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2) (Hamrock & Dowson 1981, eq. 3.21)."""
    for name, E, nu in (("E1_Pa", E1_Pa, nu1), ("E2_Pa", E2_Pa, nu2)):
        require(E > 0.0 and math.isfinite(E), name, E, "must be a positive finite modulus")
    for name, nu in (("nu1", nu1), ("nu2", nu2)):
        require(-1.0 < nu < 0.5, name, nu, "Poisson's ratio must lie in (-1, 0.5)")
    return 2.0 / ((1.0 - nu1**2) / E1_Pa + (1.0 - nu2**2) / E2_Pa)


def _ratio_of_ellipticity(log_k: float) -> float:
    """R_major/R_minor = (k^2 E(m) - K(m)) / (K(m) - E(m)) for k = exp(log_k), m = 1 - 1/k^2."""
    p = math.exp(-2.0 * log_k)  # 1 - m, kept separately for accuracy near m = 1
    m = -math.expm1(-2.0 * log_k)
    K = float(ellipkm1(p))
    E = float(ellipe(m))
    return (E / p - K) / (K - E)


def ellipticity_from_radius_ratio(ratio: float) -> float:
    """Exact ellipticity k = a/b >= 1 for R_major/R_minor = ``ratio`` >= 1 (root of the Hertz
    ratio equation, Johnson 1985 eq. 3.70-3.71; the curve fit k ~ ratio^(2/pi) is not used)."""
    require(ratio >= 1.0 and math.isfinite(ratio), "radius_ratio", ratio, "must be a finite number >= 1")
    if ratio - 1.0 < _NEAR_CIRCULAR:
        return 1.0 + 2.0 / 3.0 * (ratio - 1.0)
    hi = math.log(_K_MAX)
    require(_ratio_of_ellipticity(hi) > ratio, "radius_ratio", ratio, f"ellipticity would exceed {_K_MAX:g}")
    # ratio - 1 ~ 1.5 ln k near k = 1, so ln k = 1e-8 lies below every root handled here
    log_k = brentq(lambda u: _ratio_of_ellipticity(u) - ratio, 1.0e-8, hi, xtol=1e-15, rtol=1e-15, maxiter=200)
    return math.exp(log_k)


def _shape(rx1_m: float, ry1_m: float, rx2_m: float, ry2_m: float,
           E1_Pa: float, nu1: float, E2_Pa: float, nu2: float) -> _EllipseShape:
    for name, r in (("rx1_m", rx1_m), ("ry1_m", ry1_m), ("rx2_m", rx2_m), ("ry2_m", ry2_m)):
        require(r != 0.0 and math.isfinite(r), name, r, "radius of curvature must be non-zero and finite "
                "(use a very large value for a flat surface; concave radii are negative)")
    cx = 1.0 / rx1_m + 1.0 / rx2_m
    cy = 1.0 / ry1_m + 1.0 / ry2_m
    require(cx > 0.0, "rx1_m, rx2_m", (rx1_m, rx2_m),
            "curvature sum 1/rx1 + 1/rx2 must be positive (a concave surface must be larger than the convex one)")
    require(cy > 0.0, "ry1_m, ry2_m", (ry1_m, ry2_m),
            "curvature sum 1/ry1 + 1/ry2 must be positive (a concave surface must be larger than the convex one)")
    Rx, Ry = 1.0 / cx, 1.0 / cy
    major_axis = "y" if Ry >= Rx else "x"
    k = ellipticity_from_radius_ratio(max(Rx, Ry) / min(Rx, Ry))
    m = 1.0 - 1.0 / k**2
    return _EllipseShape(k=k, K=float(ellipkm1(1.0 / k**2)), E=float(ellipe(m)), R=1.0 / (cx + cy),
                         E_eff=effective_modulus_Pa(E1_Pa, nu1, E2_Pa, nu2), major_axis=major_axis)


def _stiffness(s: _EllipseShape) -> float:
    """K_n = pi k E' sqrt(2 E R / (9 K^3)) (Hamrock & Dowson 1981, eq. 3.32 rearranged)."""
    return math.pi * s.k * s.E_eff * math.sqrt(2.0 * s.E * s.R / (9.0 * s.K**3))


def point_contact(load_N: float, rx1_m: float, ry1_m: float, rx2_m: float, ry2_m: float,
                  E1_Pa: float, nu1: float, E2_Pa: float, nu2: float) -> PointContact:
    """Hertz elliptical point contact of two bodies under normal load ``load_N`` (>= 0).

    b = (6 E Q R / (pi k E'))^(1/3), a = k b, p_max = 3Q/(2 pi a b), delta = 3 K Q / (pi a E')
    (module docstring; Johnson 1985 sec. 3.5). Zero load gives a zero-size contact.
    """
    require(math.isfinite(load_N) and load_N >= 0.0, "load_N", load_N, "must be a finite load >= 0")
    s = _shape(rx1_m, ry1_m, rx2_m, ry2_m, E1_Pa, nu1, E2_Pa, nu2)
    K_n = _stiffness(s)
    if load_N == 0.0:
        return PointContact(0.0, 0.0, 0.0, 0.0, s.k, K_n, s.major_axis)
    b = (6.0 * s.E * load_N * s.R / (math.pi * s.k * s.E_eff)) ** (1.0 / 3.0)
    a = s.k * b
    return PointContact(a_m=a, b_m=b, p_max_Pa=3.0 * load_N / (2.0 * math.pi * a * b),
                        approach_m=3.0 * s.K * load_N / (math.pi * a * s.E_eff),
                        ellipticity=s.k, stiffness_N_m15=K_n, major_axis=s.major_axis)


def point_contact_stiffness(rx1_m: float, ry1_m: float, rx2_m: float, ry2_m: float,
                            E1_Pa: float, nu1: float, E2_Pa: float, nu2: float) -> float:
    """K_n (N/m^1.5) with Q = K_n delta^1.5: K_n = pi k E' sqrt(2 E(m) R / (9 K(m)^3))."""
    return _stiffness(_shape(rx1_m, ry1_m, rx2_m, ry2_m, E1_Pa, nu1, E2_Pa, nu2))


def line_contact(load_N: float, length_m: float, r1_m: float, r2_m: float,
                 E1_Pa: float, nu1: float, E2_Pa: float, nu2: float) -> LineContact:
    """Hertz contact of two parallel cylinders (radii r1, r2; concave negative) of length L.

    b = sqrt(8 w R / (pi E')), p_max = 2w/(pi b), w = Q/L, 1/R = 1/r1 + 1/r2; max principal shear
    0.3003 p_max at depth 0.7862 b (Johnson 1985, eqs. 4.43-4.49).
    """
    require(math.isfinite(load_N) and load_N >= 0.0, "load_N", load_N, "must be a finite load >= 0")
    require(math.isfinite(length_m) and length_m > 0.0, "length_m", length_m, "must be a positive length")
    for name, r in (("r1_m", r1_m), ("r2_m", r2_m)):
        require(r != 0.0 and math.isfinite(r), name, r, "radius must be non-zero and finite (concave negative)")
    c = 1.0 / r1_m + 1.0 / r2_m
    require(c > 0.0, "r1_m, r2_m", (r1_m, r2_m), "curvature sum 1/r1 + 1/r2 must be positive")
    E_eff = effective_modulus_Pa(E1_Pa, nu1, E2_Pa, nu2)
    w = load_N / length_m
    b = math.sqrt(8.0 * w / (c * math.pi * E_eff))
    p_max = 2.0 * w / (math.pi * b) if b > 0.0 else 0.0
    return LineContact(half_width_m=b, p_max_Pa=p_max, depth_max_shear_m=LINE_SHEAR_DEPTH_RATIO * b,
                       max_shear_Pa=LINE_SHEAR_RATIO * p_max)


def race_radii_m(ball_diameter_m: float, pitch_diameter_m: float, contact_angle_rad: float,
                 inner_groove_radius_ratio: float, outer_groove_radius_ratio: float
                 ) -> tuple[tuple[float, float], tuple[float, float]]:
    """Principal radii (rolling direction x, transverse y) of the inner and outer raceways at the
    contact: r_x,i = (d_m - D cos a)/(2 cos a), r_y,i = -f_i D, r_x,o = -(d_m + D cos a)/(2 cos a),
    r_y,o = -f_o D (Harris & Kotzalas, *Rolling Bearing Analysis* 5th ed. 2007, vol. 1 ch. 2)."""
    D, dm, a = ball_diameter_m, pitch_diameter_m, contact_angle_rad
    require(D > 0.0 and math.isfinite(D), "ball_diameter_m", D, "must be positive")
    require(dm > D and math.isfinite(dm), "pitch_diameter_m", dm, f"must exceed ball_diameter_m = {D}")
    require(0.0 <= a < math.pi / 2.0, "contact_angle_rad", a, "must lie in [0, pi/2)")
    for name, f in (("inner_groove_radius_ratio", inner_groove_radius_ratio),
                    ("outer_groove_radius_ratio", outer_groove_radius_ratio)):
        require(f > 0.5 and math.isfinite(f), name, f, "groove radius / ball diameter must exceed 0.5")
    c = math.cos(a)
    inner = ((dm - D * c) / (2.0 * c), -inner_groove_radius_ratio * D)
    outer = (-(dm + D * c) / (2.0 * c), -outer_groove_radius_ratio * D)
    return inner, outer


def ball_race_stiffness(ball_diameter_m: float, pitch_diameter_m: float, contact_angle_rad: float,
                        inner_groove_radius_ratio: float, outer_groove_radius_ratio: float,
                        E_Pa: float, nu: float) -> BallRaceStiffness:
    """Hertz stiffness of the inner and outer ball-race contacts of a ball bearing (ball and rings
    of the same material) and of the two in series (Harris & Kotzalas 2007, vol. 1 ch. 7):
    1/K^(2/3) = 1/K_i^(2/3) + 1/K_o^(2/3)."""
    (rxi, ryi), (rxo, ryo) = race_radii_m(ball_diameter_m, pitch_diameter_m, contact_angle_rad,
                                          inner_groove_radius_ratio, outer_groove_radius_ratio)
    r_ball = ball_diameter_m / 2.0
    Ki = point_contact_stiffness(r_ball, r_ball, rxi, ryi, E_Pa, nu, E_Pa, nu)
    Ko = point_contact_stiffness(r_ball, r_ball, rxo, ryo, E_Pa, nu, E_Pa, nu)
    return BallRaceStiffness(inner_N_m15=Ki, outer_N_m15=Ko,
                             combined_N_m15=Ki * Ko / (Ki ** (2.0 / 3.0) + Ko ** (2.0 / 3.0)) ** 1.5)
