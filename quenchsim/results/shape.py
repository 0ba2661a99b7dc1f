"""The shape measures a ring inspector takes on the finished outline: diameters at stated heights, taper,
crown and straightness of the bore and the OD, and the dish of the two faces (summary.json ``shape_mm``).

Outline in (a closed r-z polygon in mm, x = r, loops joined by NaN rows, as ``outline.csv`` holds it),
measures out; nothing else is read. The measures are taken the way a gauge takes them:

* gauge heights: ``inset`` above the lowest point of the outline (bottom), mid-way between the lowest and
  the highest point (mid), ``inset`` below the highest point (top); ``inset`` is a stated fraction
  (:data:`GAUGE_INSET_FRACTION`) of the width before the quench, the same millimetres before and after, so
  the gauge stays off the chamfers and edge radii;
* a diameter at a height: twice the smallest (bore) or largest (OD) radius where the horizontal line at that
  height cuts the outline (a bore gauge and a snap gauge);
* taper: diameter at the top gauge height minus at the bottom one (positive: wider at the top);
* crown: diameter at mid-width minus the mean of the two end diameters, i.e. the deviation at mid-width from
  the straight line through the ends (positive: larger at mid-width, a barrel; negative: an hourglass);
  on a spherical raceway the crown is the sphere's own sagitta over the gauge length, and its change is what
  the quench did to it;
* straightness: the largest |deviation| of the diameter from that straight line over the gauge length
  (:data:`STRAIGHTNESS_POINTS` heights), unsigned;
* face dish: the height of a face at the radius ``inset_fraction`` of the wall in from the OD minus its
  height at the same distance in from the bore (wall and radii taken at the nearer gauge height); positive:
  the face rises towards the OD. A cone of the face, as a dial gauge run across the face on a surface
  plate reads it.

Every measure is a difference of two readings along the same direction, so the rigid motion of an
axisymmetric section (an axial translation) drops out. A solid section (its outline reaches the axis)
has no bore: its bore measures are None.
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

GAUGE_INSET_FRACTION = 0.1
"""Gauge heights sit this fraction of the (pre-quench) width in from each face; face readings this fraction of
the wall in from the bore and the OD."""
STRAIGHTNESS_POINTS = 41
"""Heights (evenly spaced over the gauge length, ends included) at which straightness is read."""
AXIS_TOLERANCE_MM = 1e-6
"""An outline whose smallest radius is below this reaches the axis: a solid section, no bore."""

MEASURES = ("bore_at_bottom", "bore_at_mid", "bore_at_top", "od_at_bottom", "od_at_mid", "od_at_top",
            "bore_taper", "od_taper", "bore_crown", "od_crown", "bore_straightness", "od_straightness",
            "top_face_dish", "bottom_face_dish")
"""The measures of one outline, in mm, in the order of ``shape_mm.before`` / ``after`` / ``change``."""


def _cuts(outline_mm: np.ndarray, axis: int, level: float) -> np.ndarray:
    """The other coordinate where the closed outline (loops joined by NaN rows) crosses coordinate ``axis`` =
    ``level``."""
    a = outline_mm[:, axis]
    b = np.roll(outline_mm, -1, axis=0)
    # a loop closes on itself: the row before a NaN row joins the first row of its loop
    starts = np.r_[0, np.flatnonzero(~np.isfinite(a)) + 1]
    ends = np.r_[np.flatnonzero(~np.isfinite(a)) - 1, len(a) - 1]
    b = b.copy()
    b[ends] = outline_mm[starts]
    ok = np.isfinite(a) & np.isfinite(b[:, axis])
    a1, a2 = a[ok], b[ok, axis]
    o1, o2 = outline_mm[ok, 1 - axis], b[ok, 1 - axis]
    hit = ((a1 - level) * (a2 - level) <= 0) & (a1 != a2)
    return o1[hit] + (level - a1[hit]) * (o2[hit] - o1[hit]) / (a2[hit] - a1[hit])


def diameters_at(outline_mm: np.ndarray, z_mm: float) -> tuple[float | None, float]:
    """(bore, OD) diameters in mm where the horizontal line at ``z_mm`` cuts the outline; bore None on a solid
    section.

    >>> square = np.array([[10.0, 0.0], [20.0, 0.0], [20.0, 5.0], [10.0, 5.0]])
    >>> diameters_at(square, 2.5)
    (20.0, 40.0)
    """
    r = _cuts(outline_mm, 1, z_mm)
    if r.size < 2:
        raise ValueError(f"the line z = {z_mm:g} mm does not cross the outline twice")
    bore = None if r.min() < AXIS_TOLERANCE_MM else float(2.0 * r.min())
    return bore, float(2.0 * r.max())


def _face_heights(outline_mm: np.ndarray, r_mm: float) -> tuple[float, float]:
    """(bottom, top) height of the outline on the vertical line at radius ``r_mm``."""
    z = _cuts(outline_mm, 0, r_mm)
    if z.size < 2:
        raise ValueError(f"the line r = {r_mm:g} mm does not cross the outline twice")
    return float(z.min()), float(z.max())


def _line_deviation(outline_mm: np.ndarray, z_lo: float, z_hi: float, side: int) -> tuple[float | None, float | None]:
    """(crown, straightness) of the bore (side 0) or OD (side 1) between the gauge heights, mm on the diameter."""
    heights = np.linspace(z_lo, z_hi, STRAIGHTNESS_POINTS)
    d_read = [diameters_at(outline_mm, z)[side] for z in heights]
    if any(v is None for v in d_read):
        return None, None
    d = np.asarray(d_read, dtype=float)
    line = d[0] + (d[-1] - d[0]) * (heights - z_lo) / (z_hi - z_lo)
    z_mid = 0.5 * (z_lo + z_hi)
    # the mid height lies between the gauge heights, where every reading above exists
    d_mid = cast(float, diameters_at(outline_mm, z_mid)[side])
    return float(d_mid - 0.5 * (d[0] + d[-1])), float(np.max(np.abs(d - line)))


def shape_measures(outline_mm: np.ndarray, inset_mm: float, inset_fraction: float = GAUGE_INSET_FRACTION
                   ) -> dict[str, float | None]:
    """The :data:`MEASURES` of one closed outline (mm), with the gauge ``inset_mm`` from each face.

    >>> ring = np.array([[100.0, 0.0], [120.0, 0.0], [120.0, 50.0], [100.0, 50.0]])
    >>> m = shape_measures(ring, 5.0)
    >>> m["bore_at_mid"], m["od_taper"], m["bore_crown"], m["top_face_dish"]
    (200.0, 0.0, 0.0, 0.0)
    """
    pts = outline_mm[np.isfinite(outline_mm[:, 0])]
    z_min, z_max = float(pts[:, 1].min()), float(pts[:, 1].max())
    z_lo, z_hi = z_min + inset_mm, z_max - inset_mm
    if not z_lo < z_hi:
        raise ValueError(f"the gauge inset {inset_mm:g} mm leaves no gauge length on a section {z_max - z_min:g} mm wide")
    z_mid = 0.5 * (z_min + z_max)
    out: dict[str, float | None] = {}
    for name, z in (("bottom", z_lo), ("mid", z_mid), ("top", z_hi)):
        bore, od = diameters_at(outline_mm, z)
        out[f"bore_at_{name}"], out[f"od_at_{name}"] = bore, od
    for side, surface in ((0, "bore"), (1, "od")):
        lo, hi = out[f"{surface}_at_bottom"], out[f"{surface}_at_top"]
        out[f"{surface}_taper"] = None if lo is None or hi is None else hi - lo
        out[f"{surface}_crown"], out[f"{surface}_straightness"] = _line_deviation(outline_mm, z_lo, z_hi, side)
    for face, z in (("top", z_hi), ("bottom", z_lo)):
        r = _cuts(outline_mm, 1, z)
        r_in, r_out = float(r.min()), float(r.max())
        if r_in < AXIS_TOLERANCE_MM:   # a solid section's face runs from the axis
            r_in = 0.0
        inner, outer = r_in + inset_fraction * (r_out - r_in), r_out - inset_fraction * (r_out - r_in)
        pick = 1 if face == "top" else 0
        out[f"{face}_face_dish"] = _face_heights(outline_mm, outer)[pick] - _face_heights(outline_mm, inner)[pick]
    return {k: out[k] for k in MEASURES}


def _difference(a: float | None, b: float | None) -> float | None:
    """a - b, None where either is None."""
    return None if b is None or a is None else a - b


def shape_change(before_mm: np.ndarray, after_mm: np.ndarray,
                 inset_fraction: float = GAUGE_INSET_FRACTION) -> dict[str, Any]:
    """The ``shape_mm`` block of summary.json: the gauge (inset and the pre-quench heights), the measures
    of the outline before and after the quench and after - before (mm; None where a measure does not
    exist, e.g. the bore of a solid section)."""
    pts = before_mm[np.isfinite(before_mm[:, 0])]
    z_min, z_max = float(pts[:, 1].min()), float(pts[:, 1].max())
    inset = inset_fraction * (z_max - z_min)
    before = shape_measures(before_mm, inset, inset_fraction)
    after = shape_measures(after_mm, inset, inset_fraction)
    change = {k: _difference(after[k], before[k]) for k in MEASURES}
    gauge = {"inset_mm": inset, "inset_fraction": inset_fraction,
             "heights_before_mm": {"bottom": z_min + inset, "mid": 0.5 * (z_min + z_max), "top": z_max - inset}}
    return {"gauge": gauge, "before": before, "after": after, "change": change}
