"""Field of a multipole magnetic encoder: a layer of thickness h magnetised normal to its face in alternating poles
of width p (wavelength 2p), remanence B_r, recoil permeability mu_r (B = mu0 mu_r H + B_r in the magnet), on air
or on an ideal iron back plate, in the linear, iron-free (apart from the plate) case.

Each Fourier harmonic of the magnetisation, wavenumber k, is a Laplace problem in three layers (air above, magnet,
air or iron below; scalar potential continuous and normal B continuous at the faces, potential zero on the iron).
The normal and tangential flux density at the height g above the magnet face are

    B_y = sum_m B_r c_m F(k_m) exp(-k_m g) cos(k_m x + phi_m),  B_x = sum_m B_r c_m F(k_m) exp(-k_m g) sin(...)

    F(k) = (1 - e^{-k h'}) / ((mu_r + 1) + (mu_r - 1) e^{-k h'}),  h' = h (air backing), 2 h (iron backing)

with c_m, phi_m the amplitude and phase of the magnetisation's harmonic m. For equal poles (square wave with
pole centres at x = 0, 2p, ...) k_n = n pi / p and c_n = (4/(n pi)) sin(n pi / 2), n odd; with mu_r = 1 this is the
reference notes' sum (1/2)(1 - e^{-n pi h/p}) (4/(n pi)) e^{-n pi g/p} (docs/reference/other_seed_systems.md
sec. 2.4; the method is that of the magnetic-scale / planar-array literature, e.g. E. P. Furlani, *Permanent Magnet
and Electromechanical Devices*, Academic Press 2001, ch. 4, and J. C. Mallinson, IEEE Trans. Magn. 9 (1973) 678).
On a ring magnet of radius R the planar form holds while p << R: outside a cylinder a harmonic of m periods per turn
decays as (R/(R + g))^(m+1) instead of exp(-m g / R), 0.1 % apart for 32 pole pairs on R = 15.3 mm at g = 1 mm.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq

from quenchsim.errors import require
from quenchsim.inputs.reader import read_package_toml

MAGNET_DATA = "data/encoder_magnet.toml"
"""Plastic-bonded ferrite: remanence, coercivity and the temperature coefficient of remanence, with sources."""

@dataclass(frozen=True)
class Encoder:
    """A straight (or p << R) multipole layer: pole width p, thickness h (m), remanence B_r (T), recoil permeability,
    backing "air" or "iron"."""

    pole_width_m: float
    thickness_m: float
    remanence_T: float
    recoil_permeability: float = 1.0
    backing: str = "air"

    def __post_init__(self) -> None:
        for name in ("pole_width_m", "thickness_m"):
            v = getattr(self, name)
            require(math.isfinite(v) and v > 0.0, name, v, "must be a positive length")
        require(math.isfinite(self.remanence_T) and 0.0 < self.remanence_T <= 2.0, "remanence_T", self.remanence_T,
                "must lie in (0, 2] T")
        require(math.isfinite(self.recoil_permeability) and 1.0 <= self.recoil_permeability <= 20.0,
                "recoil_permeability", self.recoil_permeability, "must lie in [1, 20]")
        require(self.backing in ("air", "iron"), "backing", self.backing, "must be 'air' or 'iron'")


def layer_factor(k_1_m: np.ndarray | float, thickness_m: float, recoil_permeability: float = 1.0,
                 backing: str = "air") -> np.ndarray | float:
    """F(k) of the module docstring: the face field of harmonic k per unit magnetisation harmonic (B_r c_m = 1).

    >>> round(float(layer_factor(math.pi / 1.5e-3, 1e-3)), 4)
    0.4384
    """
    h = thickness_m * (2.0 if backing == "iron" else 1.0)
    e = np.exp(-np.asarray(k_1_m) * h)
    mu = recoil_permeability
    return (1.0 - e) / ((mu + 1.0) + (mu - 1.0) * e)


def _odd_harmonics(encoder: Encoder) -> tuple[np.ndarray, np.ndarray]:
    """k_n and B_r c_n (F(k_n) - F_inf) of the odd harmonics, until F - F_inf has fallen below e^-36 of F_inf."""
    h = encoder.thickness_m * (2.0 if encoder.backing == "iron" else 1.0)
    top = int(min(20001, 2 * math.ceil(36.0 * encoder.pole_width_m / (math.pi * h)) + 3))
    n = np.arange(1, top + 1, 2, dtype=float)
    k = n * math.pi / encoder.pole_width_m
    f_inf = 1.0 / (encoder.recoil_permeability + 1.0)
    c = 4.0 / (n * math.pi) * np.sin(n * math.pi / 2.0)
    rest = c * (layer_factor(k, encoder.thickness_m, encoder.recoil_permeability, encoder.backing) - f_inf)
    return k, encoder.remanence_T * rest


def field_T(encoder: Encoder, x_m: np.ndarray | float, gap_m: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """(B_x, B_y) at the positions ``x_m`` along the layer (centre of a north pole at x = 0) and heights ``gap_m``
    above the face (broadcast together), T. The series is split as F = F_inf + (F - F_inf), F_inf = 1/(mu_r + 1):
    the F_inf part sums in closed form, sum_n odd (4/(n pi)) sin(n pi/2) z^n = (4/pi) arctan(z) with
    z = exp(-pi (g - i x)/p), and the rest converges like exp(-k h')."""
    x, g = np.broadcast_arrays(np.asarray(x_m, dtype=float), np.asarray(gap_m, dtype=float))
    require(bool(np.all(np.isfinite(g)) and np.all(g >= 0.0)), "gap_m", gap_m, "must be >= 0")
    p = encoder.pole_width_m
    f_inf = 1.0 / (encoder.recoil_permeability + 1.0)
    closed = 4.0 / math.pi * np.arctan(np.exp(-math.pi * (g - 1j * x) / p))
    k, rest = _odd_harmonics(encoder)
    decay = rest * np.exp(-g[..., None] * k)
    kx = x[..., None] * k
    bx = encoder.remanence_T * f_inf * closed.imag + np.sum(decay * np.sin(kx), axis=-1)
    by = encoder.remanence_T * f_inf * closed.real + np.sum(decay * np.cos(kx), axis=-1)
    return bx, by


def pole_centre_field_T(encoder: Encoder, gap_m: np.ndarray | float) -> np.ndarray | float:
    """B_y at a pole centre at the height ``gap_m`` above the magnet face (equal poles), T.

    >>> e = Encoder(1.5e-3, 1e-3, 1.0)
    >>> round(float(pole_centre_field_T(e, 1e-3)), 4)
    0.0684
    """
    by = field_T(encoder, 0.0, gap_m)[1]
    return by if np.ndim(by) else float(by)


def remanence_for_field_T(field_T_at_gap: float, gap_m: float, pole_width_m: float, thickness_m: float,
                          recoil_permeability: float = 1.0, backing: str = "air") -> float:
    """The remanence B_r that gives the pole-centre field ``field_T_at_gap`` at ``gap_m`` (the field is linear
    in B_r).

    >>> round(remanence_for_field_T(0.015, 1e-3, 1.5e-3, 1e-3), 3)
    0.219
    """
    require(math.isfinite(field_T_at_gap) and field_T_at_gap > 0.0, "field_T", field_T_at_gap, "must be > 0")
    unit = Encoder(pole_width_m, thickness_m, 1.0, recoil_permeability, backing)
    return field_T_at_gap / float(pole_centre_field_T(unit, gap_m))


def working_gap_m(encoder: Encoder, switching_field_T: float) -> float:
    """Largest gap at which the pole-centre field still reaches ``switching_field_T`` (a Hall sensor's operate
    point); 0 when even the face field is weaker."""
    require(math.isfinite(switching_field_T) and switching_field_T > 0.0, "switching_field_T", switching_field_T,
            "must be > 0")
    if pole_centre_field_T(encoder, 0.0) < switching_field_T:
        return 0.0
    hi = encoder.pole_width_m
    while pole_centre_field_T(encoder, hi) > switching_field_T:
        hi *= 2.0
    return brentq(lambda g: pole_centre_field_T(encoder, g) - switching_field_T, 0.0, hi, xtol=1e-12)


@functools.cache
def magnet_data() -> dict[str, Any]:
    """data/encoder_magnet.toml (bonded ferrite; Modelica Standard Library's PlasticHardFerrite, with ``source``)."""
    return read_package_toml("quenchsim.bearings", MAGNET_DATA)


def remanence_at_temperature_T(remanence_T: float, temperature_C: float, coefficient_per_K: float | None = None,
                               reference_C: float | None = None) -> float:
    """B_r(T) = B_r,ref (1 + alpha (T - T_ref)): the reversible temperature law of a magnet's remanence (defaults:
    bonded ferrite, alpha = -0.002 1/K at 20 C, data/encoder_magnet.toml). The encoder's field is linear in B_r, so
    it scales alike; the recoil permeability does not change (H_cB follows the same law).

    >>> round(remanence_at_temperature_T(0.2, 120.0), 4), round(remanence_at_temperature_T(0.2, -40.0), 4)
    (0.16, 0.224)
    """
    data = magnet_data()
    alpha = data["remanence_temperature_coefficient_per_K"] if coefficient_per_K is None else coefficient_per_K
    t_ref = data["reference_temperature_C"] if reference_C is None else reference_C
    require(math.isfinite(temperature_C) and -273.15 < temperature_C < 500.0, "temperature_C", temperature_C,
            "must be in (-273.15, 500) C")
    factor = 1.0 + alpha * (temperature_C - t_ref)
    require(factor > 0.0, "temperature_C", temperature_C, f"beyond the linear law's range (factor {factor:.3g})")
    return remanence_T * factor
