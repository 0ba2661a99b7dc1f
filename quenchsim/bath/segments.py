"""The bath curves on a section outline, grouped by named boundary segment: what `quenchsim bath` prints
and the bath validation study tabulates and plots."""

from __future__ import annotations

from typing import Any

import numpy as np

from quenchsim.bath.config import BathConfig
from quenchsim.bath.htc import BoundaryHTC, boundary_htc
from quenchsim.bath.outline import profile_points
from quenchsim.geometry.boundary import BoundaryPoints
from quenchsim.geometry.profile import Profile

TABLE_T_C = (100, 200, 300, 400, 500, 550, 600, 700, 800)
"""Surface temperatures of the segment tables (C)."""
MAIN_SEGMENTS = ("bore", "od", "top", "bottom")


def outline_htc(profile: Profile, bath: BathConfig, spacing_m: float = 2e-3) -> tuple[BoundaryPoints, BoundaryHTC]:
    """The bath curves on points spaced ``spacing_m`` along a section outline (no mesh needed)."""
    points = profile_points(profile, spacing_m)
    return points, boundary_htc(bath, points)


def segment_groups(htc: BoundaryHTC) -> dict[str, np.ndarray]:
    """Point indices per displayed segment: the main faces by name, every other segment as it is named."""
    names = list(dict.fromkeys(htc.segment.tolist()))
    ordered = [n for n in MAIN_SEGMENTS if n in names] + [n for n in names if n not in MAIN_SEGMENTS]
    return {n: np.flatnonzero(htc.segment == n) for n in ordered}


def segment_table(htc: BoundaryHTC, T_C: tuple[float, ...] = TABLE_T_C) -> list[dict[str, Any]]:
    """Per segment: speed range, Leidenfrost range and the segment-mean h at the temperatures T_C."""
    rows = []
    for name, idx in segment_groups(htc).items():
        h = np.array([[np.interp(T, htc.T_grid_C, htc.h_W_m2K[i]) for T in T_C] for i in idx])
        rows.append({"segment": name, "points": int(idx.size),
                     "speed_m_s": (float(htc.velocity_m_s[idx].min()), float(htc.velocity_m_s[idx].max())),
                     "leidenfrost_C": (float(np.nanmin(htc.leidenfrost_C[idx])), float(np.nanmax(htc.leidenfrost_C[idx]))),
                     "h_mean_W_m2K": dict(zip(T_C, h.mean(axis=0).round(0).tolist()))})
    return rows


def perimeter_coordinate(points: BoundaryPoints) -> tuple[np.ndarray, list[tuple[str, float, float]]]:
    """Position of each point along the outline (segments in profile order) and the segment spans."""
    x = np.zeros(len(points))
    spans, offset = [], 0.0
    for name in dict.fromkeys(points.segment.tolist()):
        idx = np.flatnonzero(points.segment == name)
        for length in np.unique(points.segment_length_m[idx]):
            part = idx[points.segment_length_m[idx] == length]
            x[part] = offset + points.s_m[part]
            spans.append((name, offset, offset + float(length)))
            offset += float(length)
    return x, spans


RESPONSE_T_C = (200.0, 400.0, 600.0, 800.0)
"""Surface temperatures of the jet-response tables (C)."""


def jet_response(profile: Profile, spec: dict[str, Any], side: str, speeds_mm_s: tuple[float, ...],
                 T_C: tuple[float, ...] = RESPONSE_T_C, spacing_m: float = 2e-3) -> dict[str, Any]:
    """Segment-mean h at the surface temperatures ``T_C`` and the segment-mean film-collapse temperature for each
    ``<side>_jet_speed_mm_s`` in ``speeds_mm_s``, the rest of the ``[quench.bath]`` table ``spec`` as given:
    {speed: {segment: {T: h, ..., "T_L": T_L}}} (speeds and temperatures as strings of their integer values)."""
    from quenchsim.bath.config import parse_bath

    out: dict[str, Any] = {}
    for speed in speeds_mm_s:
        _, htc = outline_htc(profile, parse_bath(dict(spec, **{f"{side}_jet_speed_mm_s": speed})), spacing_m)
        out[str(int(speed))] = {
            seg: {**{str(int(T)): float(np.mean([np.interp(T, htc.T_grid_C, htc.h_W_m2K[i]) for i in idx]))
                     for T in T_C}, "T_L": float(np.mean(htc.leidenfrost_C[idx]))}
            for seg, idx in segment_groups(htc).items()}
    return out
