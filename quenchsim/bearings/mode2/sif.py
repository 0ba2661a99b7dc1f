"""Stress-intensity factors of the mode II test specimen and of a penny crack in shear, and the checks of a
test condition against the SUJ2 data (data/mode2_crack.toml; Fujii, Maeda & Ohtsuka, NTN Technical Review 69
(2001) 53).

Specimen (single-edge-cracked plate, rigid grips; the paper's FEM fits, xi = a/W):

    K_II = F_II(xi) sigma sqrt(a),  sigma = P / (W t)          (direct-shear load P)
    K_I  = F_I(xi)  sigma sqrt(a),  sigma = 6 M / (t W^2)      (static opening moment M)

Penny crack of radius a under a uniform in-plane shear tau (M. K. Kassir & G. C. Sih, J. Appl. Mech. 33 (1966)
601; H. Tada, P. C. Paris & G. R. Irwin, *The Stress Analysis of Cracks Handbook*, 3rd ed., ASME 2000, penny-shaped crack under shear):
the largest mode II and mode III factors along the front are

    K_II,max = 4 / (pi (2 - nu)) tau sqrt(pi a),   K_III,max = (1 - nu) K_II,max
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import cast

import numpy as np

from quenchsim.errors import require
from quenchsim.inputs.reader import read_package_toml


@functools.cache
def crack_data() -> dict:
    """data/mode2_crack.toml (the paper's fits and SUJ2 data, each with its source)."""
    return read_package_toml("quenchsim.bearings", "data/mode2_crack.toml")


def _poly(coefficients: list[float], xi: np.ndarray | float) -> np.ndarray | float:
    # a float xi gives np.float64, a float subclass (numpy's stub says floating[Any])
    return cast("np.ndarray | float", np.polynomial.polynomial.polyval(xi, coefficients))


def F_II(xi: np.ndarray | float) -> np.ndarray | float:
    """Printed mode II geometry factor of the specimen (sqrt(a) normalisation).

    >>> round(float(F_II(0.3)), 3)
    0.746
    """
    return _poly(crack_data()["specimen"]["F_II"], xi)


def F_I(xi: np.ndarray | float) -> np.ndarray | float:
    """Printed mode I (bending) geometry factor of the specimen (sqrt(a) normalisation).

    >>> round(float(F_I(0.5)), 3)
    1.119
    """
    return _poly(crack_data()["specimen"]["F_I"], xi)


@dataclass(frozen=True)
class SpecimenState:
    """Specimen SIFs (Pa sqrt(m)): the cyclic mode II range, the static mode I opening and the parasitic mode I
    of the shear rig, with the checks against the SUJ2 data."""

    a_over_W: float
    delta_K_II: float
    K_I_static: float
    K_I_parasitic: float
    above_threshold: bool
    in_mode_II_range: bool
    opening_within_half_K_Ic: bool
    opening_separates_faces: bool
    parasitic_below_K_Ith: bool
    notes: tuple[str, ...]


def specimen_state(crack_length_m: float, width_m: float, thickness_m: float, shear_load_range_N: float,
                   opening_moment_Nm: float) -> SpecimenState:
    """K_II range and static K_I of the specimen, and the paper's test-condition checks: Delta K_II above the
    threshold and within the coplanar growth range (3-10 MPa sqrt(m)); static K_I within 5-7 MPa sqrt(m) (<= K_Ic/2,
    opening the faces); the rig's parasitic K_I (0.8 at K_II = 10, scaled with K_II) below K_Ith = 5.8."""
    for name, v in (("crack_length_m", crack_length_m), ("width_m", width_m), ("thickness_m", thickness_m)):
        require(math.isfinite(v) and v > 0.0, name, v, "must be a positive length")
    require(crack_length_m < width_m, "crack_length_m", crack_length_m, f"must be below width_m = {width_m}")
    require(math.isfinite(shear_load_range_N) and shear_load_range_N >= 0.0, "shear_load_range_N",
            shear_load_range_N, "must be >= 0")
    require(math.isfinite(opening_moment_Nm) and opening_moment_Nm >= 0.0, "opening_moment_Nm", opening_moment_Nm,
            "must be >= 0")
    d = crack_data()["material"]
    xi = crack_length_m / width_m
    root_a = math.sqrt(crack_length_m)
    dK2 = float(F_II(xi)) * shear_load_range_N / (width_m * thickness_m) * root_a
    K1 = float(F_I(xi)) * 6.0 * opening_moment_Nm / (thickness_m * width_m**2) * root_a
    mpa = 1e6
    parasitic = d["parasitic_K_I_at_K_II_10_MPa_sqrt_m"] / 10.0 * dK2
    lo, hi = d["static_opening_MPa_sqrt_m"]
    notes = []
    if xi < 0.1:
        notes.append(f"a/W = {xi:.3f}: the printed F_I is negative at a/W = 0, the fits are not meant for short cracks")
    if dK2 / mpa >= d["mode_II_growth_upper_MPa_sqrt_m"]:
        notes.append("Delta K_II >= 10 MPa sqrt(m): the paper saw oblique tensile-mode growth at 10")
    return SpecimenState(a_over_W=xi, delta_K_II=dK2, K_I_static=K1, K_I_parasitic=parasitic,
                         above_threshold=dK2 / mpa >= d["delta_K_IIth_MPa_sqrt_m"],
                         in_mode_II_range=d["delta_K_IIth_MPa_sqrt_m"] <= dK2 / mpa < d["mode_II_growth_upper_MPa_sqrt_m"],
                         opening_within_half_K_Ic=K1 / mpa <= min(d["K_Ic_MPa_sqrt_m"]) / 2.0,
                         opening_separates_faces=lo <= K1 / mpa <= hi,
                         parasitic_below_K_Ith=parasitic / mpa < d["K_Ith_MPa_sqrt_m"], notes=tuple(notes))


def penny_K_II_max(shear_Pa: float | np.ndarray, radius_m: float | np.ndarray, nu: float) -> float | np.ndarray:
    """K_II,max = 4/(pi (2 - nu)) tau sqrt(pi a) of a penny crack in uniform shear (module docstring).

    >>> round(float(penny_K_II_max(1.0, 1.0, 0.3)), 3)
    1.328
    """
    return 4.0 / (math.pi * (2.0 - nu)) * shear_Pa * np.sqrt(math.pi * radius_m)


def penny_K_III_max(shear_Pa: float | np.ndarray, radius_m: float | np.ndarray, nu: float) -> float | np.ndarray:
    """K_III,max = (1 - nu) K_II,max (Kassir & Sih 1966)."""
    return (1.0 - nu) * penny_K_II_max(shear_Pa, radius_m, nu)


def penny_critical_diameter_m(threshold_Pa_sqrt_m: float, shear_range_Pa: float, nu: float) -> float:
    """Diameter 2a at which the penny crack's Delta K_II,max reaches the threshold:
    2a = (2/pi) (Delta K_th (pi (2 - nu)) / (4 Delta tau))^2."""
    require(math.isfinite(shear_range_Pa) and shear_range_Pa > 0.0, "shear_range_Pa", shear_range_Pa, "must be > 0")
    require(math.isfinite(threshold_Pa_sqrt_m) and threshold_Pa_sqrt_m > 0.0, "threshold_Pa_sqrt_m",
            threshold_Pa_sqrt_m, "must be > 0")
    c = 4.0 / (math.pi * (2.0 - nu))
    return 2.0 / math.pi * (threshold_Pa_sqrt_m / (c * shear_range_Pa)) ** 2
