"""A 3-D view of an axisymmetric result: the r-z section revolved about the axis into wedge cells.

The section .vtu holds triangles in the x-y plane (x = r, y = z, metres). Revolving it by
``angle_deg`` in ``segments`` equal steps gives points (r cos t, r sin t, z) and one linear wedge
(VTK_WEDGE) per triangle and step, so ParaView (or pyvista) shows e.g. a 270-degree sector with the
section visible in the cut. Scalar point data are copied to every station; 3-component vectors are
taken as (r, z, theta) components, as the section files write them (e.g. ``displacement_m``), and
rotated into Cartesian (x, y, z). Stress components keep their cylindrical meaning (rr, zz, tt, rz).
"""

from __future__ import annotations

import math
from pathlib import Path

import meshio
import numpy as np

from quenchsim.errors import require


def revolve_mesh(points: np.ndarray, triangles: np.ndarray, point_data: dict[str, np.ndarray],
                 angle_deg: float = 270.0, segments: int = 54) -> meshio.Mesh:
    """Revolve a section (points (n, 2 or 3) with x = r, y = z) about the z axis; see the module docstring."""
    require(0.0 < angle_deg <= 360.0, "angle_deg", angle_deg, "must be in (0, 360]")
    require(isinstance(segments, int) and segments >= 1, "segments", segments, "must be an integer >= 1")
    r, z = points[:, 0], points[:, 1]
    require(bool(np.all(r >= -1e-12)), "points", float(r.min()), "r (x) must be >= 0 for a section")
    full = math.isclose(angle_deg, 360.0)
    n_stations = segments if full else segments + 1
    theta = np.radians(angle_deg) * np.arange(n_stations) / segments
    c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
    n = len(r)
    xyz = np.stack([r[None, :] * c, r[None, :] * s, np.broadcast_to(z, (n_stations, n))], axis=-1).reshape(-1, 3)
    tri = np.asarray(triangles, dtype=np.int64)
    # VTK's wedge has a positive volume when its first triangle's right-hand normal points towards the second
    # one (+e_theta here); a triangle counter-clockwise in (r, z) has normal e_r x e_z = -e_theta: reverse it
    a = (r[tri[:, 1]] - r[tri[:, 0]]) * (z[tri[:, 2]] - z[tri[:, 0]]) \
        - (r[tri[:, 2]] - r[tri[:, 0]]) * (z[tri[:, 1]] - z[tri[:, 0]])
    tri = np.where((a > 0)[:, None], tri[:, [0, 2, 1]], tri)
    k = np.arange(segments)
    lo = (k * n)[:, None, None] + tri[None, :, :]
    hi = (((k + 1) % n_stations) * n)[:, None, None] + tri[None, :, :]
    wedges = np.concatenate([lo, hi], axis=2).reshape(-1, 6)
    data: dict[str, np.ndarray] = {}
    for name, values in point_data.items():
        v = np.asarray(values)
        if v.ndim == 2 and v.shape[1] == 3:
            ur, uz, ut = v[:, 0][None, :], v[:, 1][None, :], v[:, 2][None, :]
            data[name] = np.stack([ur * c - ut * s, ur * s + ut * c, np.broadcast_to(uz, (n_stations, n))],
                                  axis=-1).reshape(-1, 3)
        else:
            data[name] = np.concatenate([v] * n_stations)
    return meshio.Mesh(xyz, [("wedge", wedges)], point_data=data)


def revolve_vtu(vtu_path: str | Path, out_path: str | Path, angle_deg: float = 270.0, segments: int = 54) -> Path:
    """Read a section .vtu (triangles, x = r, y = z) and write its revolved 3-D view to ``out_path`` (.vtu)."""
    mesh = meshio.read(vtu_path)
    triangles = np.concatenate([cell.data for cell in mesh.cells if cell.type == "triangle"])
    out = revolve_mesh(mesh.points, triangles, mesh.point_data, angle_deg, segments)
    out_path = Path(out_path)
    meshio.write(out_path, out, binary=True)
    return out_path
