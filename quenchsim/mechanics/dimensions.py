"""Measured dimensions of a (deformed) axisymmetric ring section: inner and outer diameter at
mid-width, width at mid-wall, as a caliper would take them, and the section outline for plots.

The section boundary is the chain of boundary edges of the P2 mesh, each split at its mid-side node,
moved by the displacement.  ID/OD are twice the smallest/largest radius where the horizontal line
through the middle of the section's axial extent cuts the boundary (for a spherical raceway the ID is
the raceway diameter at mid-width); the width is the axial extent where the vertical line through the
middle of the wall at that height cuts the boundary.  The section's area is that of the deformed
(curved) P2 mesh.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from skfem import Basis, ElementTriP2, ElementVector, MeshTri

from quenchsim.errors import InputError


def _boundary_segments(mesh: MeshTri, displacement_m: np.ndarray | None, scale: float) -> np.ndarray:
    """(n_segments, 2 points, 2 coords) of the boundary, deformed by scale * displacement."""
    facets = mesh.boundary_facets()
    v0, v1 = mesh.facets[0, facets], mesh.facets[1, facets]
    p0, p1 = mesh.p[:, v0].T, mesh.p[:, v1].T
    mid = 0.5 * (p0 + p1)
    if displacement_m is not None:
        basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=1)
        u = np.asarray(displacement_m, dtype=float)
        if u.shape != (basis.N,):
            raise InputError("displacement_m", u.shape, f"must have the {basis.N} DOFs of the vector P2 basis")
        p0 = p0 + scale * u[basis.nodal_dofs[:, v0]].T
        p1 = p1 + scale * u[basis.nodal_dofs[:, v1]].T
        mid = mid + scale * u[basis.facet_dofs[:, facets]].T
    return np.concatenate([np.stack([p0, mid], axis=1), np.stack([mid, p1], axis=1)])


def _cuts(segments: np.ndarray, axis: int, level: float) -> np.ndarray:
    """Other coordinate where the segments cross coordinate ``axis`` = level."""
    a, b = segments[:, 0, axis], segments[:, 1, axis]
    hit = ((a - level) * (b - level) <= 0.0) & (a != b)
    t = (level - a[hit]) / (b[hit] - a[hit])
    other = 1 - axis
    return segments[hit, 0, other] + t * (segments[hit, 1, other] - segments[hit, 0, other])


def ring_dimensions(mesh: MeshTri, displacement_m: np.ndarray | None = None) -> dict[str, float]:
    """{"id", "od", "width"} in mm of the section ``mesh`` (metres, x = r) moved by ``displacement_m``
    (vector-P2 DOFs as in :class:`~quenchsim.mechanics.MechanicsSolver`; None = undeformed)."""
    seg = _boundary_segments(mesh, displacement_m, 1.0)
    z = seg[:, :, 1]
    z_mid = 0.5 * (z.min() + z.max())
    r_cut = _cuts(seg, 1, z_mid)
    if r_cut.size < 2:
        raise InputError("mesh", "section", "the mid-width line does not cross the section boundary twice")
    r_in, r_out = r_cut.min(), r_cut.max()
    z_cut = _cuts(seg, 0, 0.5 * (r_in + r_out))
    return {"id": 2e3 * r_in, "od": 2e3 * r_out, "width": 1e3 * float(z_cut.max() - z_cut.min())}


def section_area_mm2(mesh: MeshTri, displacement_m: np.ndarray | None = None) -> float:
    """Area (mm^2) of the section ``mesh`` (metres) moved by ``displacement_m`` (vector-P2 DOFs; None =
    undeformed): int det(I + grad u) dA over the undeformed mesh, exact for the curved P2 elements
    (the integrand is quadratic, integrated at order 2)."""
    basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=2)
    if displacement_m is None:
        return 1e6 * float(np.sum(basis.dx))
    u = np.asarray(displacement_m, dtype=float)
    if u.shape != (basis.N,):
        raise InputError("displacement_m", u.shape, f"must have the {basis.N} DOFs of the vector P2 basis")
    g = basis.interpolate(u).grad  # g[i, j] = d u_i / d x_j, (2, 2, ne, nq)
    det = (1.0 + g[0, 0]) * (1.0 + g[1, 1]) - g[0, 1] * g[1, 0]
    return 1e6 * float(np.sum(det * basis.dx))


def dimension_change(before: dict[str, float], after: dict[str, float]) -> dict[str, dict[str, float]]:
    """The ``dimensions_mm`` block of summary.json: before, after and after - before (mm)."""
    return {"before": dict(before), "after": dict(after),
            "change": {k: after[k] - before[k] for k in ("id", "od", "width")}}


def section_outline(mesh: MeshTri, displacement_m: np.ndarray | None = None, magnification: float = 1.0) -> np.ndarray:
    """Closed boundary polyline(s) (n, 2) in metres, deformed by magnification * displacement
    (e.g. 10 for the report's distortion plot); separate loops are joined by a NaN row."""
    seg = _boundary_segments(mesh, displacement_m, magnification)
    n = len(seg) // 2
    facets = mesh.boundary_facets()
    start, end = mesh.facets[0, facets], mesh.facets[1, facets]
    nxt: dict[Any, list[tuple[int, bool]]] = {}   # vertex -> (edge, the vertex is the edge's end)
    for k in range(n):  # chain the boundary edges (a boundary vertex has exactly two boundary edges)
        nxt.setdefault(start[k], []).append((k, False))
        nxt.setdefault(end[k], []).append((k, True))
    used = np.zeros(n, dtype=bool)
    out = []
    for first in range(n):
        if used[first]:
            continue
        k, flipped, loop = first, False, []
        while not used[k]:
            used[k] = True
            pts = [seg[k, 0], seg[k, 1], seg[n + k, 1]]
            loop.extend(pts[::-1] if flipped else pts)
            vertex = start[k] if flipped else end[k]
            k, flipped = next(((j, f) for j, f in nxt[vertex] if j != k), (k, flipped))
        out.append(np.array(loop))
        out.append(np.full((1, 2), np.nan))
    return np.concatenate(out[:-1])
