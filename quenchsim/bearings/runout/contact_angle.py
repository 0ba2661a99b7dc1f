"""Contact angle of an axially preloaded ball bearing from its radial clearance.

Free (unloaded) contact angle from the diametral (radial internal) clearance P_d and the total
curvature B = f_i + f_o - 1 (f = groove radius / ball diameter D):

    cos(alpha_0) = 1 - P_d / (2 B D)

Loaded contact angle under a pure axial load F_a shared by Z balls (Harris & Kotzalas,
*Rolling Bearing Analysis* 5th ed. 2007, vol. 1 ch. 7, the "thrust-loaded bearing" equation):

    F_a / (Z K_n (B D)^1.5) = sin(alpha) (cos(alpha_0)/cos(alpha) - 1)^1.5

with K_n the ball's inner+outer Hertz constant (Q = K_n delta^1.5) from :mod:`quenchsim.bearings.hertz`.
The radial clearance is taken as ISO 5753 defines it: the total radial play of one ring relative
to the other, i.e. Harris' diametral clearance P_d.
"""

from __future__ import annotations

import math

from scipy.optimize import brentq

from quenchsim.bearings import hertz
from quenchsim.errors import require


def free_contact_angle_rad(radial_clearance_m: float, ball_diameter_m: float,
                           inner_groove_radius_ratio: float, outer_groove_radius_ratio: float) -> float:
    """alpha_0 = acos(1 - P_d / (2 B D)) (Harris & Kotzalas 2007, vol. 1 ch. 2)."""
    B = inner_groove_radius_ratio + outer_groove_radius_ratio - 1.0
    require(B > 0.0, "bearing.inner_groove_radius_ratio + outer_groove_radius_ratio", B + 1.0,
            "must exceed 1 (each groove radius must exceed the ball radius)")
    clearance_um = float(f"{radial_clearance_m * 1e6:.12g}")  # as typed, without the um -> m -> um round-off
    require(radial_clearance_m >= 0.0, "bearing.radial_clearance_um", clearance_um,
            "must be >= 0: the fixed-contact-angle models need a free contact angle "
            "acos(1 - P_d/(2 B D)), which a negative clearance (interference) does not have")
    c = 1.0 - radial_clearance_m / (2.0 * B * ball_diameter_m)
    require(c > 0.0, "bearing.radial_clearance_um", clearance_um,
            f"must be < 2 B D = {2e6 * B * ball_diameter_m:.4g} um (free contact angle would reach 90 deg)")
    return math.acos(c)


def loaded_contact_angle_rad(free_angle_rad: float, axial_load_N: float, balls: int,
                             ball_diameter_m: float, pitch_diameter_m: float,
                             inner_groove_radius_ratio: float, outer_groove_radius_ratio: float,
                             E_Pa: float, nu: float) -> float:
    """Root alpha in (alpha_0, pi/2) of F_a/(Z K_n (B D)^1.5) = sin a (cos a_0 / cos a - 1)^1.5.

    K_n is evaluated at the loaded angle itself (it depends weakly on the angle through the
    raceway curvature in the rolling direction)."""
    B = inner_groove_radius_ratio + outer_groove_radius_ratio - 1.0
    BD = B * ball_diameter_m

    def residual(a: float) -> float:
        K = hertz.ball_race_stiffness(ball_diameter_m, pitch_diameter_m, a, inner_groove_radius_ratio,
                                      outer_groove_radius_ratio, E_Pa, nu).combined_N_m15
        lhs = axial_load_N / (balls * K * BD ** 1.5)
        return math.sin(a) * max(math.cos(free_angle_rad) / math.cos(a) - 1.0, 0.0) ** 1.5 - lhs

    hi = math.radians(89.0)
    require(residual(hi) > 0.0, "operation.axial_load_N", axial_load_N,
            "too large: the loaded contact angle would exceed 89 deg")
    return brentq(residual, free_angle_rad, hi, xtol=1e-12)
