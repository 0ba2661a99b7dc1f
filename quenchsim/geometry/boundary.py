"""Boundary points of a section: what the bath model needs to know about each surface point."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SectionExtent:
    """Bounding values of the ring section (m): bore radius, outer radius, bottom and top z."""

    r_min_m: float
    r_max_m: float
    z_min_m: float
    z_max_m: float


@dataclass(frozen=True)
class BoundaryPoints:
    """Points on the section boundary (usually facet quadrature points), all arrays shaped (n,).

    r_m, z_m       position (z up; the ring's bottom face sits on the turntable at z_min)
    normal_r, normal_z   outward unit normal
    segment        name of the boundary segment ("bore", "od", "top", "bottom", "chamfer_...", ...)
    s_m            arc length from the start of the segment (counter-clockwise around the section)
    segment_length_m    length of the segment the point is on
    extent         the section's bounding box
    """

    r_m: np.ndarray
    z_m: np.ndarray
    normal_r: np.ndarray
    normal_z: np.ndarray
    segment: np.ndarray
    s_m: np.ndarray
    segment_length_m: np.ndarray
    extent: SectionExtent

    def __len__(self) -> int:
        return int(self.r_m.size)
