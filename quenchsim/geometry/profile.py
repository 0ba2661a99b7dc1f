"""Closed (r, z) section profiles made of named line and arc segments.

Builders for the rectangular ring with chamfers or edge radii (case A), the outer ring with a
spherical raceway (case B) and a general profile from points and arcs. All lengths in metres;
z is up and the bottom face is at z = 0 unless a general profile says otherwise. The profile
runs counter-clockwise in the (r, z) plane, so the outward normal of a segment is its tangent
turned clockwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from collections.abc import Mapping
from typing import Any, cast

import numpy as np

from quenchsim.errors import require
from quenchsim.inputs.case import Geometry, ProfileGeometry, RectangularGeometry, SphericalOuterGeometry
from quenchsim.inputs.declare import convert, from_table

MM = 1e-3


@dataclass(frozen=True)
class Segment:
    """A line (``center is None``) or a circular arc (< 180 deg) from ``start`` to ``end``."""

    name: str
    start: tuple[float, float]
    end: tuple[float, float]
    center: tuple[float, float] | None = None

    def length(self) -> float:
        if self.center is None:
            return math.dist(self.start, self.end)
        return abs(self.sweep()) * math.dist(self.center, self.start)

    def sweep(self) -> float:
        """Signed arc angle (rad, counter-clockwise positive), the short way round."""
        c = cast(tuple[float, float], self.center)   # only arcs have a sweep (callers check center)
        a0 = math.atan2(self.start[1] - c[1], self.start[0] - c[0])
        a1 = math.atan2(self.end[1] - c[1], self.end[0] - c[0])
        return (a1 - a0 + math.pi) % (2 * math.pi) - math.pi

    def distance(self, r: float | np.ndarray, z: float | np.ndarray) -> np.ndarray:
        """Shortest distance from points (r, z) to this segment."""
        r, z = np.asarray(r, dtype=float), np.asarray(z, dtype=float)
        if self.center is None:
            d = np.subtract(self.end, self.start)
            t = np.clip(((r - self.start[0]) * d[0] + (z - self.start[1]) * d[1]) / (d @ d), 0.0, 1.0)
            return np.hypot(r - (self.start[0] + t * d[0]), z - (self.start[1] + t * d[1]))
        # arc: distance to the circle where the point's angle lies within the sweep, else to the ends
        c = self.center
        radius = math.dist(c, self.start)
        a0 = math.atan2(self.start[1] - c[1], self.start[0] - c[0])
        rel = (np.arctan2(z - c[1], r - c[0]) - a0) % (2 * math.pi)
        sweep = self.sweep()
        within = (rel <= sweep) if sweep >= 0 else (rel >= 2 * math.pi + sweep)
        to_circle = np.abs(np.hypot(r - c[0], z - c[1]) - radius)
        to_ends = np.minimum(np.hypot(r - self.start[0], z - self.start[1]), np.hypot(r - self.end[0], z - self.end[1]))
        return np.where(within, to_circle, to_ends)

    def points(self, n: int) -> np.ndarray:
        """``n`` points along the segment, shape (n, 2), including both ends."""
        t = np.linspace(0.0, 1.0, n)
        if self.center is None:
            return np.outer(1 - t, self.start) + np.outer(t, self.end)
        c = np.asarray(self.center)
        radius = math.dist(self.center, self.start)
        a0 = math.atan2(self.start[1] - c[1], self.start[0] - c[0])
        ang = a0 + t * self.sweep()
        return c + radius * np.column_stack([np.cos(ang), np.sin(ang)])


@dataclass(frozen=True)
class Profile:
    """A closed section outline: segments in counter-clockwise order, end of each = start of next."""

    segments: tuple[Segment, ...]

    def scaled(self, factor: float) -> "Profile":
        """The profile scaled about the origin (r = 0, z = 0) by ``factor`` (free isotropic strain)."""
        def sc(xy: tuple[float, float]) -> tuple[float, float]:
            return (xy[0] * factor, xy[1] * factor)
        return Profile(tuple(Segment(s.name, sc(s.start), sc(s.end), None if s.center is None else sc(s.center))
                             for s in self.segments))

    def polygon(self, per_segment: int = 32) -> np.ndarray:
        return np.vstack([s.points(per_segment)[:-1] for s in self.segments])

    def area_m2(self) -> float:
        p = self.polygon(256)
        x, y = p[:, 0], p[:, 1]
        return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))

    def contains(self, r: float, z: float) -> bool:
        """Point-in-polygon test (ray casting) on a fine polygon of the outline."""
        p = self.polygon(256)
        x, y = p[:, 0], p[:, 1]
        x2, y2 = np.roll(x, -1), np.roll(y, -1)
        crosses = ((y > z) != (y2 > z)) & (r < (x2 - x) * (z - y) / np.where(y2 == y, 1e-300, y2 - y) + x)
        return bool(np.count_nonzero(crosses) % 2)

    def distance(self, r: float, z: float) -> float:
        """Distance from (r, z) to the outline."""
        return float(min(np.min(s.distance(r, z)) for s in self.segments))

    def bounds(self) -> tuple[float, float, float, float]:
        p = self.polygon(256)
        return float(p[:, 0].min()), float(p[:, 0].max()), float(p[:, 1].min()), float(p[:, 1].max())


def _corner_cut(corner: tuple[float, float], d_in: tuple[float, float], d_out: tuple[float, float],
                size: float, rounded: bool, name: str) -> tuple[tuple[float, float], tuple[float, float], Segment]:
    """Cut the corner between an incoming direction d_in and outgoing d_out by a chamfer or a radius."""
    a = (corner[0] - d_in[0] * size, corner[1] - d_in[1] * size)
    b = (corner[0] + d_out[0] * size, corner[1] + d_out[1] * size)
    if rounded:
        center = (a[0] + d_out[0] * size, a[1] + d_out[1] * size)
        return a, b, Segment(name, a, b, center)
    return a, b, Segment(name, a, b)


def _polygon_with_corners(corners: list[tuple[float, float]], sides: list[str], corner_names: list[str],
                          size: float, rounded: bool) -> Profile:
    """Rectangle-like polygon (counter-clockwise corners) with every corner cut by ``size``."""
    n = len(corners)
    if size <= 0:
        return Profile(tuple(Segment(sides[i], corners[i], corners[(i + 1) % n]) for i in range(n)))
    cuts = []
    for i in range(n):
        prev, here, nxt = corners[i - 1], corners[i], corners[(i + 1) % n]
        d_in = np.subtract(here, prev) / math.dist(here, prev)
        d_out = np.subtract(nxt, here) / math.dist(nxt, here)
        cuts.append(_corner_cut(here, tuple(d_in), tuple(d_out), size, rounded, corner_names[i]))
    segs = []
    for i in range(n):
        segs.append(cuts[i][2])
        segs.append(Segment(sides[i], cuts[i][1], cuts[(i + 1) % n][0]))
    return Profile(tuple(segs))


def rectangular_ring(inner_diameter_m: float, outer_diameter_m: float, width_m: float,
                     chamfer_m: float = 0.0, edge_radius_m: float = 0.0) -> Profile:
    """Rectangular ring section, r in [ID/2, OD/2], z in [0, width], optional 45-deg chamfers or radii."""
    require(inner_diameter_m >= 0, "geometry.inner_diameter_mm", inner_diameter_m / MM, "must be >= 0")
    require(outer_diameter_m > inner_diameter_m, "geometry.outer_diameter_mm", outer_diameter_m / MM,
            f"must exceed geometry.inner_diameter_mm = {inner_diameter_m / MM:g}")
    require(width_m > 0, "geometry.width_mm", width_m / MM, "must be > 0")
    require(not (chamfer_m > 0 and edge_radius_m > 0), "geometry.edge_radius_mm", edge_radius_m / MM,
            "give either chamfer_mm or edge_radius_mm, not both")
    cut = max(chamfer_m, edge_radius_m)
    wall = (outer_diameter_m - inner_diameter_m) / 2
    field = "geometry.chamfer_mm" if chamfer_m > 0 else "geometry.edge_radius_mm"
    require(cut >= 0 and 2 * cut < min(wall, width_m), field, cut / MM,
            f"must be >= 0 and less than {min(wall, width_m) / 2 / MM:g} mm, half the smaller of the wall "
            f"({wall / MM:g} mm) and the width ({width_m / MM:g} mm)")
    ri, ro = inner_diameter_m / 2, outer_diameter_m / 2
    kind = "radius" if edge_radius_m > 0 else "chamfer"
    if ri == 0:  # solid section: the axis is a symmetry line, not a surface; only the two OD corners are cut
        w = width_m
        if cut == 0:
            return Profile((Segment("bottom", (0.0, 0.0), (ro, 0.0)), Segment("od", (ro, 0.0), (ro, w)),
                            Segment("top", (ro, w), (0.0, w)), Segment("axis", (0.0, w), (0.0, 0.0))))
        a0, b0, low = _corner_cut((ro, 0.0), (1.0, 0.0), (0.0, 1.0), cut, edge_radius_m > 0, f"{kind}_od_bottom")
        a1, b1, high = _corner_cut((ro, w), (0.0, 1.0), (-1.0, 0.0), cut, edge_radius_m > 0, f"{kind}_od_top")
        return Profile((Segment("bottom", (0.0, 0.0), a0), low, Segment("od", b0, a1), high,
                        Segment("top", b1, (0.0, w)), Segment("axis", (0.0, w), (0.0, 0.0))))
    corners = [(ri, 0.0), (ro, 0.0), (ro, width_m), (ri, width_m)]
    names = [f"{kind}_bore_bottom", f"{kind}_od_bottom", f"{kind}_od_top", f"{kind}_bore_top"]
    return _polygon_with_corners(corners, ["bottom", "od", "top", "bore"], names, cut, edge_radius_m > 0)


def spherical_outer_ring(raceway_diameter_m: float, outer_diameter_m: float, width_m: float,
                         chamfer_m: float = 0.0) -> Profile:
    """Outer ring of a spherical roller bearing: bore = sphere centred on the axis at mid-width.

    The raceway diameter is measured at mid-width (the sphere's equator), so the bore radius at the
    faces is sqrt(R^2 - (W/2)^2) and the wall is thinnest at mid-width.
    """
    R = raceway_diameter_m / 2
    require(R > 0, "geometry.raceway_diameter_mm", raceway_diameter_m / MM, "must be > 0")
    require(width_m > 0, "geometry.width_mm", width_m / MM, "must be > 0")
    require(width_m / 2 < R, "geometry.width_mm", width_m / MM,
            f"must be < the raceway diameter ({raceway_diameter_m / MM:g} mm)")
    require(outer_diameter_m > raceway_diameter_m, "geometry.outer_diameter_mm", outer_diameter_m / MM,
            f"must exceed geometry.raceway_diameter_mm = {raceway_diameter_m / MM:g}")
    ro, h = outer_diameter_m / 2, width_m / 2
    r_face = math.sqrt(R * R - h * h)
    require(chamfer_m >= 0 and chamfer_m < min(ro - r_face, h) / 2, "geometry.chamfer_mm", chamfer_m / MM,
            "must be >= 0 and less than half the face wall")
    center = (0.0, h)
    if chamfer_m == 0:
        segs = [Segment("bottom", (r_face, 0.0), (ro, 0.0)), Segment("od", (ro, 0.0), (ro, width_m)),
                Segment("top", (ro, width_m), (r_face, width_m)), Segment("bore", (r_face, width_m), (r_face, 0.0), center)]
        return Profile(tuple(segs))
    c = chamfer_m
    segs = [Segment("bottom", (r_face + c, 0.0), (ro - c, 0.0)),
            Segment("chamfer_od_bottom", (ro - c, 0.0), (ro, c)),
            Segment("od", (ro, c), (ro, width_m - c)),
            Segment("chamfer_od_top", (ro, width_m - c), (ro - c, width_m)),
            Segment("top", (ro - c, width_m), (r_face + c, width_m))]
    # bore-side chamfers end on the sphere
    z_top = width_m - c
    r_top = math.sqrt(R * R - (z_top - h) ** 2)
    segs += [Segment("chamfer_bore_top", (r_face + c, width_m), (r_top, z_top)),
             Segment("bore", (r_top, z_top), (r_top, c), center),
             Segment("chamfer_bore_bottom", (r_top, c), (r_face + c, 0.0))]
    return Profile(tuple(segs))


def general_profile(spec: Mapping[str, Any] | ProfileGeometry, field: str = "geometry") -> Profile:
    """Profile from ``start_mm = [r, z]`` and ``[[segments]]`` with ``to_mm``, ``name``, optional ``center_mm`` (a
    table as in a case's ``[geometry]``, or its declaration)."""
    geometry = spec if isinstance(spec, ProfileGeometry) else from_table(ProfileGeometry, {"type": "profile", **spec},
                                                                         field)
    start, items = geometry.start_mm, geometry.segments
    segs, here = [], (start[0] * MM, start[1] * MM)
    for i, item in enumerate(items):
        f = f"{field}.segments[{i}]"
        end = (item.to_mm[0] * MM, item.to_mm[1] * MM)
        require(end != here, f"{f}.to_mm", list(item.to_mm), "must differ from the segment start")
        center = None
        if item.center_mm is not None:
            center = (item.center_mm[0] * MM, item.center_mm[1] * MM)
            r0, r1 = math.dist(center, here), math.dist(center, end)
            require(abs(r0 - r1) <= 1e-6 * max(r0, r1), f"{f}.center_mm", list(item.center_mm),
                    "must be equidistant from the segment's start and end")
        segs.append(Segment(item.name, here, end, center))
        here = end
    require(math.dist(here, segs[0].start) < 1e-9, f"{field}.segments[{len(items) - 1}].to_mm", list(items[-1].to_mm),
            f"the profile must close: last point must equal start_mm = {list(start)}")
    prof = Profile(tuple(segs))
    require(all(p[0] >= -1e-12 for p in prof.polygon(8)), f"{field}.segments", "r < 0", "all points need r >= 0")
    if prof.area_m2() < 0:  # clockwise input: reverse it
        prof = Profile(tuple(Segment(s.name, s.end, s.start, s.center) for s in reversed(segs)))
    require(prof.area_m2() > 0, f"{field}.segments", "area", "the profile encloses no area")
    return prof


def profile_from_geometry(geometry: Geometry) -> Profile:
    """The section of a case's ``[geometry]`` (its declaration, :mod:`quenchsim.inputs.case`; dimensions in mm)."""
    if isinstance(geometry, RectangularGeometry):
        return rectangular_ring(geometry.inner_diameter_mm * MM, geometry.outer_diameter_mm * MM,
                                geometry.width_mm * MM, geometry.chamfer_mm * MM, geometry.edge_radius_mm * MM)
    if isinstance(geometry, SphericalOuterGeometry):
        return spherical_outer_ring(geometry.raceway_diameter_mm * MM, geometry.outer_diameter_mm * MM,
                                    geometry.width_mm * MM, geometry.chamfer_mm * MM)
    return general_profile(geometry)


def profile_from_case(geometry: Mapping[str, Any]) -> Profile:
    """The section of a case's ``[geometry]`` table as read from TOML (checked against its declaration)."""
    return profile_from_geometry(convert(geometry, Geometry, "geometry"))
