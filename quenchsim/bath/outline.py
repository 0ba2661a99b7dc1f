"""Boundary points of axisymmetric outlines without meshing, for the bath's own diagnostics and checks.

The quench runs take their boundary points (facet quadrature points) from the mesh; the bath command,
report and tests need them without a mesh: for any geometry :class:`Profile` of a case
(:func:`profile_points`), a plain rectangular ring section and the ISO 9950 probe (a solid cylinder).
"""

from __future__ import annotations

import numpy as np

from quenchsim.geometry.boundary import BoundaryPoints, SectionExtent
from quenchsim.geometry.profile import Profile


def _polygon_points(vertices: list[tuple[float, float]], names: list[str], spacing_m: float,
                    extent: SectionExtent) -> BoundaryPoints:
    """Midpoints of equal sub-intervals along each edge of a counter-clockwise polygon in (r, z)."""
    cols: dict[str, list[np.ndarray]] = {k: [] for k in ("r", "z", "nr", "nz", "seg", "s", "L")}
    for k, name in enumerate(names):
        (r0, z0), (r1, z1) = vertices[k], vertices[(k + 1) % len(vertices)]
        length = float(np.hypot(r1 - r0, z1 - z0))
        if length <= 0.0:
            continue
        m = max(2, int(np.ceil(length / spacing_m)))
        t = (np.arange(m) + 0.5) / m
        # outward normal of a counter-clockwise outline: tangent rotated by -90 deg
        tr, tz = (r1 - r0) / length, (z1 - z0) / length
        cols["r"].append(r0 + t * (r1 - r0))
        cols["z"].append(z0 + t * (z1 - z0))
        cols["nr"].append(np.full(m, tz))
        cols["nz"].append(np.full(m, -tr))
        cols["seg"].append(np.full(m, name, dtype=object))
        cols["s"].append(t * length)
        cols["L"].append(np.full(m, length))
    cat = {k: np.concatenate(v) for k, v in cols.items()}
    return BoundaryPoints(r_m=cat["r"], z_m=cat["z"], normal_r=cat["nr"], normal_z=cat["nz"],
                          segment=cat["seg"].astype(str), s_m=cat["s"], segment_length_m=cat["L"], extent=extent)


def ring_section_points(inner_diameter_m: float, outer_diameter_m: float, width_m: float, chamfer_m: float = 0.0,
                        spacing_m: float = 2e-3) -> BoundaryPoints:
    """A rectangular ring section standing on z = 0, with equal 45 deg chamfers on its four corners."""
    ri, ro, c = 0.5 * inner_diameter_m, 0.5 * outer_diameter_m, chamfer_m
    verts = [(ri + c, 0.0), (ro - c, 0.0), (ro, c), (ro, width_m - c), (ro - c, width_m), (ri + c, width_m),
             (ri, width_m - c), (ri, c)]
    names = ["bottom", "chamfer_od_bottom", "od", "chamfer_od_top", "top", "chamfer_id_top", "bore",
             "chamfer_id_bottom"]
    return _polygon_points(verts, names, spacing_m, SectionExtent(ri, ro, 0.0, width_m))


def probe_points(diameter_m: float = 12.5e-3, length_m: float = 60e-3, spacing_m: float = 1e-3) -> BoundaryPoints:
    """The half-section (r >= 0) of a solid cylindrical probe standing vertical, bottom at z = 0."""
    R = 0.5 * diameter_m
    verts = [(0.0, 0.0), (R, 0.0), (R, length_m), (0.0, length_m)]
    pts = _polygon_points(verts[:3] + [verts[3]], ["bottom", "od", "top", "axis"], spacing_m,
                          SectionExtent(0.0, R, 0.0, length_m))
    keep = pts.segment != "axis"
    return BoundaryPoints(r_m=pts.r_m[keep], z_m=pts.z_m[keep], normal_r=pts.normal_r[keep],
                          normal_z=pts.normal_z[keep], segment=pts.segment[keep], s_m=pts.s_m[keep],
                          segment_length_m=pts.segment_length_m[keep], extent=pts.extent)


def profile_points(profile: Profile, spacing_m: float = 2e-3) -> BoundaryPoints:
    """Midpoints of equal sub-arcs of every segment of a counter-clockwise profile (lines and arcs);
    the "axis" segment of a solid section is a symmetry line and gets no points."""
    cols: dict[str, list[np.ndarray]] = {k: [] for k in ("r", "z", "nr", "nz", "seg", "s", "L")}
    for seg in profile.segments:
        if seg.name == "axis":
            continue
        length = seg.length()
        m = max(2, int(np.ceil(length / spacing_m)))
        nodes = seg.points(2 * m + 1)  # ends, midpoints and ends of the m sub-arcs
        mid = nodes[1::2]
        tangent = nodes[2::2] - nodes[0:-1:2]
        tangent /= np.linalg.norm(tangent, axis=1)[:, None]
        cols["r"].append(mid[:, 0])
        cols["z"].append(mid[:, 1])
        cols["nr"].append(tangent[:, 1])   # outward normal: tangent turned clockwise
        cols["nz"].append(-tangent[:, 0])
        cols["seg"].append(np.full(m, seg.name, dtype=object))
        cols["s"].append((np.arange(m) + 0.5) / m * length)
        cols["L"].append(np.full(m, length))
    cat = {k: np.concatenate(v) for k, v in cols.items()}
    r0, r1, z0, z1 = profile.bounds()
    return BoundaryPoints(r_m=cat["r"], z_m=cat["z"], normal_r=cat["nr"], normal_z=cat["nz"],
                          segment=cat["seg"].astype(str), s_m=cat["s"], segment_length_m=cat["L"],
                          extent=SectionExtent(r0, r1, z0, z1))
