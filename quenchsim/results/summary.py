"""The numbers of ``summary.json`` from the final state: probe times, hardness depths and traverses,
surface and core hardness, phase statistics, dimensions and residual stresses at mid-width.

Pure functions of arrays, a section profile and the P1 basis of the nodal fields (x = r, y = z, metres).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import skfem

from quenchsim.geometry.profile import MM, Profile
from quenchsim.results.postprocess import depth_below, time_to_temperature

HRC_THRESHOLD = 58.0
"""Hardness (HRC) whose depth below the surface is reported (HV650, the usual effective hardening depth
criterion of through-hardening bearing steels)."""


PROBE_TEMPERATURES_C = (800, 700, 600, 500, 400, 300, 200, 100)
"""Temperatures whose first passage time is reported per probe (``t_to_C_s``): a measured thermocouple curve is
compared with the run at these (quenchsim.calibration)."""


def probe_times(time_s: np.ndarray, probe_T: dict[str, np.ndarray]) -> dict[str, dict[str, Any]]:
    """Per probe: time to 500 C and 300 C, t8/5 (800 -> 500 C), and the time to each of
    :data:`PROBE_TEMPERATURES_C` (``t_to_C_s``, keyed by the temperature's integer text); None where not reached."""
    return {n: {"t_to_500C_s": time_to_temperature(time_s, T, 500.0),
                "t_to_300C_s": time_to_temperature(time_s, T, 300.0),
                "t8_5_s": _t_between(time_s, T, 800.0, 500.0),
                "t_to_C_s": {str(Tc): time_to_temperature(time_s, T, float(Tc)) for Tc in PROBE_TEMPERATURES_C}}
            for n, T in probe_T.items()}


def probe_state(p1: skfem.Basis, points_m: np.ndarray, names: list[str],
                fields: dict[str, np.ndarray], phases: tuple[str, ...]) -> dict[str, dict[str, Any]]:
    """Per probe: the final phase fractions and HRC at its position (``points_m``, shape (2, n), r and z in the
    coordinates of the basis ``p1``), interpolated from the nodal fields."""
    reading = p1.probes(points_m)
    out: dict[str, dict[str, Any]] = {}
    values = {k: reading @ fields[k] for k in (*phases, "hardness_HRC")}
    for i, name in enumerate(names):
        out[name] = {"phases": {k: float(values[k][i]) for k in phases}, "HRC": float(values["hardness_HRC"][i])}
    return out


def _t_between(time_s: np.ndarray, T: np.ndarray, upper: float, lower: float) -> float | None:
    a, b = time_to_temperature(time_s, T, upper), time_to_temperature(time_s, T, lower)
    return None if a is None or b is None else b - a


@dataclass(frozen=True)
class FinalSection:
    """The part as measured after the quench, at room temperature: its closed outline (n, 2) and a P1 basis
    on the mesh in those coordinates (vertex order of the run's mesh, so nodal P1 fields apply as they are).
    Traverses and depths are taken on it: a depth is measured from the final surface."""

    outline_m: np.ndarray
    p1: skfem.Basis

    @staticmethod
    def of(vertices_m: np.ndarray, triangles: np.ndarray, outline_m: np.ndarray) -> "FinalSection":
        return FinalSection(outline_m, skfem.Basis(skfem.MeshTri(vertices_m, triangles), skfem.ElementTriP1()))

    def mid_width(self) -> tuple[float, float, float]:
        """(z at mid-width, bore radius there, OD radius there), metres."""
        pts = self.outline_m[np.isfinite(self.outline_m[:, 0])]
        z_mid = 0.5 * (pts[:, 1].min() + pts[:, 1].max())
        r = _polygon_cuts(self.outline_m, z_mid)
        return z_mid, float(r.min()), float(r.max())

    def mesh_gaps(self, z: float, r_bore: float, r_od: float) -> tuple[float, float]:
        """How far inside the outline's bore and OD radii (at height z) the straight-edged P1 mesh begins (0 where
        it reaches the outline): a curved (quadratic) surface may bulge beyond the mesh the nodal fields live on."""
        cuts = _mesh_cuts(self.p1.mesh, z)
        return max(0.0, float(cuts.min()) - r_bore), max(0.0, r_od - float(cuts.max()))


def _polygon_cuts(outline_m: np.ndarray, z: float) -> np.ndarray:
    """Radii where the horizontal line at height z crosses a closed outline (loops joined by NaN rows)."""
    x, y = outline_m[:, 0], outline_m[:, 1]
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    ok = np.isfinite(x) & np.isfinite(x2)
    hit = ok & ((y - z) * (y2 - z) <= 0) & (y != y2)
    return x[hit] + (z - y[hit]) * (x2[hit] - x[hit]) / (y2[hit] - y[hit])


def _mesh_cuts(mesh: skfem.MeshTri, z: float) -> np.ndarray:
    """Radii where the horizontal line at height z crosses the boundary edges of a P1 mesh."""
    ends = mesh.p[:, mesh.facets[:, mesh.boundary_facets()]]   # (r/z, end, facet)
    a, b = ends[:, 0, :], ends[:, 1, :]
    hit = ((a[1] - z) * (b[1] - z) <= 0) & (a[1] != b[1])
    return a[0, hit] + (z - a[1, hit]) * (b[0, hit] - a[0, hit]) / (b[1, hit] - a[1, hit])


def hardness_traverse(final: FinalSection, hrc_nodal: np.ndarray, side: str,
                      n: int = 400) -> tuple[np.ndarray, np.ndarray]:
    """HRC along mid-width from the bore ("bore") or OD ("od") surface of the final part into the wall:
    (depth below that surface in mm, HRC). The traverse starts and ends 1 um inside the outline, or inside the
    straight-edged P1 mesh the nodal field lives on where a curved (quadratic) surface bulges beyond it."""
    z_mid, r_bore, r_od = final.mid_width()
    gap_bore, gap_od = final.mesh_gaps(z_mid, r_bore, r_od)
    near, far = (gap_bore, gap_od) if side == "bore" else (gap_od, gap_bore)
    depth = np.linspace(near + 1e-6, r_od - r_bore - far - 1e-6, n)   # 1 um inside: the traverse ends on the surfaces
    r = r_bore + depth if side == "bore" else r_od - depth
    probe = final.p1.probes(np.vstack([r, np.full_like(r, z_mid)]))
    return depth / MM, probe @ hrc_nodal


def hardness_summary(profile: Profile, p1: skfem.Basis, final: FinalSection, hrc_nodal: np.ndarray
                     ) -> tuple[dict[str, Any], dict[str, tuple[np.ndarray, np.ndarray]]]:
    """The summary's ``hardness`` table and the two mid-width traverses {"bore": ..., "od": ...}: surface
    hardness per named segment at its middle (``profile`` and ``p1`` of the run's mesh), depths, traverses
    and the core on the final part. The core is mid-wall of a ring and the axis of a solid section (whose
    "bore" traverse runs from the axis and has no surface to measure a depth from: its depth is None)."""
    solid = any(seg.name == "axis" for seg in profile.segments)
    depth, traverse = {}, {}
    for side in ("bore", "od"):
        d, h = hardness_traverse(final, hrc_nodal, side)
        traverse[side] = (d, h)
        depth[f"HRC58_{side}_mid"] = None if solid and side == "bore" else depth_below(d, h, HRC_THRESHOLD)
    surface = {}
    for seg in profile.segments:
        if seg.name == "axis" or seg.name.startswith(("chamfer", "radius")):
            continue
        a, mid, b = seg.points(3)
        tangent = (b - a) / np.linalg.norm(b - a)
        pt = mid + 1e-6 * np.array([-tangent[1], tangent[0]])   # left of a counter-clockwise outline = inside
        surface[f"{seg.name}_mid"] = float((p1.probes(pt.reshape(2, 1)) @ hrc_nodal)[0])
    z_mid, r_bore, r_od = final.mid_width()
    r_core = r_bore + 1e-6 if solid else 0.5 * (r_bore + r_od)
    core = float((final.p1.probes(np.array([[r_core], [z_mid]])) @ hrc_nodal)[0])
    table = {"depth_mm": depth, "surface_HRC": surface, "core_HRC": core, "threshold_HRC": HRC_THRESHOLD,
             "through_hardened": bool(np.nanmin(hrc_nodal) >= HRC_THRESHOLD),
             # the mid-width traverse never falls below the threshold: its depths are the wall, not a case depth
             "through_hardened_mid": bool(np.nanmin(traverse["od"][1]) >= HRC_THRESHOLD)}
    return table, traverse


def residual_traverse(final: FinalSection, fields: dict[str, np.ndarray],
                      n: int = 200) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Hoop and axial stress (MPa) across the wall of the final part at mid-width: (r_mm, hoop, axial); the ends
    1 um inside the outline, or inside the P1 mesh where the surface bulges beyond it."""
    z_mid, r_bore, r_od = final.mid_width()
    gap_bore, gap_od = final.mesh_gaps(z_mid, r_bore, r_od)
    r = np.linspace(r_bore + gap_bore + 1e-6, r_od - gap_od - 1e-6, n)
    probe = final.p1.probes(np.vstack([r, np.full_like(r, z_mid)]))
    return r / MM, probe @ fields["stress_tt_Pa"] / 1e6, probe @ fields["stress_zz_Pa"] / 1e6


def residual_stress_summary(hoop_MPa: np.ndarray, axial_MPa: np.ndarray) -> dict[str, dict[str, float]]:
    """Hoop and axial residual stress at the OD surface, the bore surface and the core, mid-width."""
    at = {"od_surface_mid": -1, "bore_surface_mid": 0, "core_mid": len(hoop_MPa) // 2}
    return {"hoop": {k: float(hoop_MPa[i]) for k, i in at.items()},
            "axial": {k: float(axial_MPa[i]) for k, i in at.items()}}
