"""Stray flux at the Hall sensor: the largest uniform stray field along the sensing direction a design tolerates.

The magnetic-field paper ([MAG] T. Koike, Y. Nagano, NTN Technical Review 69 (2001) 112) rates a sensor bearing by
the coil magnetomotive force (MMF) at which its pulse train turns irregular, the coil driving a motor-like leakage
flux through the bearing. In field terms (the criterion the reference notes suggest, docs/reference/other_seed_
systems.md sec. 2.3): at the sensor the encoder's field B_enc cos(...) adds to the stray field B_s, and the Hall
latch keeps switching once per pole pair only while that sum still rises above the operate point B_op and falls
below the release point B_rel:

    B_enc + B_s >= B_op  and  -B_enc + B_s <= B_rel   <=>   B_op - B_enc <= B_s <= B_enc + B_rel

so a stray field of either sign is tolerated up to min(B_enc - B_op, B_enc + B_rel) (:func:`stray_field_margin_T`).
With unsaturated iron the stray field at the sensor is proportional to the coil MMF, so for two designs whose
stray-flux path is the same (e.g. the paper's cases 1 and 2, which differ only in the magnet's thickness) the
ratio of their malfunction MMFs is the ratio of their margins. Designs that change the path (the paper's bypass
ring and slots) need the field of the rig in an axisymmetric model of the bearing: not modelled here.
"""

from __future__ import annotations

import math

from quenchsim.bearings.encoder.field import Encoder, pole_centre_field_T
from quenchsim.errors import require


def stray_field_margin_T(encoder: Encoder, gap_m: float, operate_T: float, release_T: float) -> float:
    """Largest |B_s| of a uniform stray field along the sensing direction at ``gap_m`` that leaves the switching
    once per pole pair (module docstring); <= 0: the sensor does not switch even without stray field.

    >>> b_r = 0.015 / float(pole_centre_field_T(Encoder(1.5e-3, 1e-3, 1.0), 1e-3))   # 15 mT at 1 mm
    >>> round(stray_field_margin_T(Encoder(1.5e-3, 1e-3, b_r), 1e-3, 3e-3, -3e-3) * 1e3, 6)
    12.0
    """
    require(math.isfinite(operate_T) and math.isfinite(release_T) and release_T < operate_T, "release_T", release_T,
            f"must be below operate_T = {operate_T}")
    b_enc = float(pole_centre_field_T(encoder, gap_m))
    return min(b_enc - operate_T, b_enc + release_T)
