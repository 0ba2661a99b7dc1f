"""Boundary points of a section: what the bath model needs to know about each surface point."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from quenchsim.geometry.mesher import SectionMesh


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


def boundary_points(section: "SectionMesh", facets: np.ndarray, r_m: np.ndarray, z_m: np.ndarray,
                    normals: np.ndarray) -> BoundaryPoints:
    """Label points on the facets of a meshed section by segment, with their arc length along it.

    ``facets`` (nf,) are the section-mesh facets the points lie on, ``r_m``, ``z_m`` (nf, nq) their
    coordinates (e.g. facet quadrature points) and ``normals`` (2, nf, nq) the outward unit normals.
    """
    seg_of_facet = np.empty(section.mesh.facets.shape[1], dtype=object)
    for name, on_segment in section.boundaries.items():
        seg_of_facet[on_segment] = name
    nq = r_m.shape[1]
    segment = np.repeat(seg_of_facet[facets], nq).astype(str)
    r, z = r_m.ravel(), z_m.ravel()
    s = np.zeros_like(r)
    length = np.zeros_like(r)
    for seg in section.profile.segments:
        idx = np.flatnonzero(segment == seg.name)
        if seg.center is None:
            s_seg = np.hypot(r[idx] - seg.start[0], z[idx] - seg.start[1])
        else:
            a0 = math.atan2(seg.start[1] - seg.center[1], seg.start[0] - seg.center[0])
            a = np.arctan2(z[idx] - seg.center[1], r[idx] - seg.center[0])
            radius = math.dist(seg.center, seg.start)
            s_seg = radius * np.abs((a - a0 + np.pi) % (2 * np.pi) - np.pi)
        # a name may cover several segments (e.g. chamfers): keep the nearest segment's values
        near = seg.distance(r[idx], z[idx]) < 1e-9 + 1e-6 * seg.length()
        s[idx[near]] = s_seg[near]
        length[idx[near]] = seg.length()
    r0, r1, z0, z1 = section.profile.bounds()
    return BoundaryPoints(r_m=r, z_m=z, normal_r=normals[0].ravel(), normal_z=normals[1].ravel(),
                          segment=segment, s_m=s, segment_length_m=length,
                          extent=SectionExtent(r_min_m=r0, r_max_m=r1, z_min_m=z0, z_max_m=z1))
