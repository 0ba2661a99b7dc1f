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


def probe_times(time_s: np.ndarray, probe_T: dict[str, np.ndarray]) -> dict[str, dict[str, float | None]]:
    """Per probe: time to 500 C and 300 C, and t8/5 (800 -> 500 C), None where not reached."""
    return {n: {"t_to_500C_s": time_to_temperature(time_s, T, 500.0),
                "t_to_300C_s": time_to_temperature(time_s, T, 300.0),
                "t8_5_s": _t_between(time_s, T, 800.0, 500.0)} for n, T in probe_T.items()}


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


def _polygon_cuts(outline_m: np.ndarray, z: float) -> np.ndarray:
    """Radii where the horizontal line at height z crosses a closed outline (loops joined by NaN rows)."""
    x, y = outline_m[:, 0], outline_m[:, 1]
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    ok = np.isfinite(x) & np.isfinite(x2)
    hit = ok & ((y - z) * (y2 - z) <= 0) & (y != y2)
    return x[hit] + (z - y[hit]) * (x2[hit] - x[hit]) / (y2[hit] - y[hit])


def hardness_traverse(final: FinalSection, hrc_nodal: np.ndarray, side: str,
                      n: int = 400) -> tuple[np.ndarray, np.ndarray]:
    """HRC along mid-width from the bore ("bore") or OD ("od") surface of the final part into the wall:
    (depth below that surface in mm, HRC)."""
    z_mid, r_bore, r_od = final.mid_width()
    depth = np.linspace(1e-6, r_od - r_bore - 1e-6, n)   # 1 um inside: the traverse ends on the surfaces
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
    """Hoop and axial stress (MPa) across the wall of the final part at mid-width: (r_mm, hoop, axial)."""
    z_mid, r_bore, r_od = final.mid_width()
    r = np.linspace(r_bore + 1e-6, r_od - 1e-6, n)
    probe = final.p1.probes(np.vstack([r, np.full_like(r, z_mid)]))
    return r / MM, probe @ fields["stress_tt_Pa"] / 1e6, probe @ fields["stress_zz_Pa"] / 1e6


def residual_stress_summary(hoop_MPa: np.ndarray, axial_MPa: np.ndarray) -> dict[str, dict[str, float]]:
    """Hoop and axial residual stress at the OD surface, the bore surface and the core, mid-width."""
    at = {"od_surface_mid": -1, "bore_surface_mid": 0, "core_mid": len(hoop_MPa) // 2}
    return {"hoop": {k: float(hoop_MPa[i]) for k, i in at.items()},
            "axial": {k: float(axial_MPa[i]) for k, i in at.items()}}
