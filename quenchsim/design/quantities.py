"""The numbers a run of a case will put in summary.json, by dotted name, with the range no run can leave:
what a design study may name as an objective or a constraint, checked before any run.

The names follow the summary's keys (quenchsim.pipeline ``summary``; ``shape_mm`` from
:mod:`quenchsim.results.shape`); probe and surface-segment names come from the case. The ranges are
the ones the quantity has by definition: phase fractions in [0, 1], a hardness depth between 0 and the wall
at mid-width (the depth of a through-hardened wall is the whole traverse; 2 % allowed for the distortion),
hardness on the Rockwell C scale of the conversion table, a straightness >= 0, times >= 0.
"""

from __future__ import annotations

import difflib
import math
from typing import Any

import numpy as np

from quenchsim.case import Case
from quenchsim.geometry.profile import MM
from quenchsim.results.shape import MEASURES, diameters_at

HRC_SCALE = (20.0, 68.0)
"""The Rockwell C span of ASTM E140 Table 1, the HV -> HRC conversion quenchsim uses
(quenchsim.metallurgy.hardness.hv_to_hrc is NaN outside it)."""
PHASES = ("austenite", "pearlite", "bainite", "martensite")
PROBE_TIMES = ("t_to_500C_s", "t_to_300C_s", "t8_5_s")
STRESS_POINTS = ("od_surface_mid", "bore_surface_mid", "core_mid")
WALL_MARGIN = 1.02
INF = math.inf


def _wall_at_mid_width_mm(case: Case) -> float:
    outline = case.profile.polygon(256) / MM
    z = outline[:, 1]
    bore, od = diameters_at(outline, 0.5 * (z.min() + z.max()))
    return 0.5 * (od - (bore or 0.0))


def _transforms(case: Case) -> bool:
    from quenchsim.materials import load_material, transforms   # data lookup only

    return bool(transforms(load_material(case.material)))


def summary_quantities(case: Case) -> dict[str, tuple[float, float]]:
    """Every number a finished run of ``case`` puts in summary.json that a study may aim at, with its range
    (low, high): ``{"dimensions_mm.change.id": (-inf, inf), "hardness.depth_mm.HRC58_bore_mid": (0, 16.9), ...}``."""
    out: dict[str, tuple[float, float]] = {}
    for probe in case.probes:
        for key in PROBE_TIMES:
            out[f"probes.{probe.name}.{key}"] = (0.0, INF)
    solid = any(seg.name == "axis" for seg in case.profile.segments)
    if _transforms(case):
        wall = _wall_at_mid_width_mm(case) * WALL_MARGIN
        for side in ("od",) if solid else ("bore", "od"):
            out[f"hardness.depth_mm.HRC58_{side}_mid"] = (0.0, wall)
        for seg in case.profile.segments:
            if seg.name != "axis" and not seg.name.startswith(("chamfer", "radius")):
                out[f"hardness.surface_HRC.{seg.name}_mid"] = HRC_SCALE
        out["hardness.core_HRC"] = HRC_SCALE
        out["hardness.through_hardened"] = (0.0, 1.0)
        for phase in PHASES:
            for stat in ("min", "mean", "max"):
                out[f"phases_final.{phase}.{stat}"] = (0.0, 1.0)
    if case.mechanics.enabled:
        for part in ("after", "change"):
            for key in ("id", "od", "width"):
                out[f"dimensions_mm.{part}.{key}"] = (-INF, INF)
            for key in MEASURES:
                if solid and key.startswith("bore"):
                    continue
                low = 0.0 if part == "after" and (key.endswith("straightness") or "_at_" in key) else -INF
                out[f"shape_mm.{part}.{key}"] = (low, INF)
        for comp in ("hoop", "axial"):
            for point in STRESS_POINTS:
                out[f"residual_stress_MPa.{comp}.{point}"] = (-INF, INF)
    if case.temper is not None:   # the tempered part: the same numbers under "tempered.", and the temper's change
        out.update({f"tempered.{k}": v for k, v in list(out.items()) if not k.startswith("probes.")})
        if case.mechanics.enabled:
            out.update({f"tempered.change_by_temper_mm.{k}": (-INF, INF) for k in ("id", "od", "width")})
    return out


def unknown_quantity_hint(name: str, known: dict[str, Any]) -> str:
    """What to say about a name that is not a summary quantity of the case: the closest names, and examples."""
    close = difflib.get_close_matches(name, list(known), n=3, cutoff=0.6)
    examples = [k for k in ("dimensions_mm.change.id", "shape_mm.change.bore_crown", "hardness.depth_mm.HRC58_bore_mid",
                            "residual_stress_MPa.hoop.bore_surface_mid") if k in known]
    hint = f"did you mean {', '.join(close)}?" if close else f"e.g. {', '.join(examples)}"
    return f"is not a number of this case's summary.json ({len(known)} are; {hint})"


def value_of(summary: dict[str, Any] | None, dotted: str) -> float | None:
    """A number of summary.json by its dotted name (a yes/no as 1/0); None when absent, not a number or not finite."""
    node: Any = summary
    for key in dotted.split("."):
        if not isinstance(node, dict) or key not in node:
            return None
        node = node[key]
    if isinstance(node, bool):
        return float(node)
    if isinstance(node, (int, float)) and np.isfinite(node):
        return float(node)
    return None
