"""Case B, the spherical-roller-bearing outer ring (SUJ3), conditions 4-6 of cases/srb_outer_ring.toml, full chain
(not tuned). The report prints no dimensions after quench for case B: no targets, the page records the prediction."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.case import load_case
from quenchsim.results import load as load_run
from quenchsim.validation import ROOT, cached_run, study_module

TITLE = "Quench validation, case B: spherical-roller-bearing outer ring (SUJ3), conditions 4-6 (not tuned)"
SLOW = True
CASE_B = ROOT / "cases" / "srb_outer_ring.toml"
CONDITIONS = ("4", "5", "6")


def _ring_a() -> Any:
    """The case-A study module (its plot and table helpers)."""
    return study_module("quench/ring_a")


def run(workdir: Path) -> dict[str, Any]:
    a = _ring_a()
    workdir = Path(workdir)
    runs = {c: load_run(cached_run(load_case(CASE_B, c), a.run_dirs(workdir) / f"srb_outer_ring_{c}")) for c in CONDITIONS}
    metrics: dict[str, Any] = {"conditions": {}, "plots_md": {}}
    for c, r in runs.items():
        s = r.summary
        metrics["conditions"][c] = {
            "HRC58_depth_bore_mm": s["hardness"]["depth_mm"]["HRC58_bore_mid"],
            "HRC58_depth_od_mm": s["hardness"]["depth_mm"]["HRC58_od_mid"], "core_HRC": s["hardness"]["core_HRC"],
            "martensite_mean": s["phases_final"]["martensite"]["mean"], "dimensions_mm": s.get("dimensions_mm"),
            "hoop_MPa": s.get("residual_stress_MPa", {}).get("hoop", {}), "phases_final": s.get("phases_final"),
            "residual_stress_MPa": s.get("residual_stress_MPa"), "distortion_budget_mm": s.get("distortion_budget_mm"),
            "shape_mm": s.get("shape_mm")}
        metrics["plots_md"][c] = [a.cooling_plot(r, f"B{c}", f"case B, condition {c}", workdir), "",
                                  *a.mechanics_plots(r, f"B{c}", f"case B, condition {c}", workdir)]
    return metrics


def page(metrics: dict[str, Any]) -> str:
    a = _ring_a()
    cond = metrics["conditions"]
    md = ["| condition | raceway dia after | OD after | width after | raceway change | OD change | width change |",
          "|---|---|---|---|---|---|---|"]
    md += [a.dims_row(c, s["dimensions_mm"]) for c, s in cond.items()]
    md += ["", "| condition | HRC58 depth raceway / OD mm | core HRC | martensite mean | hoop stress OD / raceway / core MPa |",
           "|---|---|---|---|---|"]
    for c, s in cond.items():
        hoop = s["hoop_MPa"]
        md.append(f"| {c} | {s['HRC58_depth_bore_mm']:.1f} / {s['HRC58_depth_od_mm']:.1f} | {s['core_HRC']:.1f} | "
                  f"{s['martensite_mean']:.3f} | "
                  + (" / ".join(f"{hoop[k]:.0f}" for k in ("od_surface_mid", "bore_surface_mid", "core_mid")) if hoop else "-")
                  + " |")
    md += ["", "### Shape of the raceway, the OD and the faces", ""] + a.shape_table(cond, bore="raceway")
    md += ["### Old versus new", ""] + a.old_versus_new(a.model_history(__file__), cond, ("raceway", "OD", "width"))
    md += ["### Distortion budget", ""] + a.budget_table(cond, ("raceway", "OD", "width"))
    for c in cond:
        md += metrics["plots_md"][c]
    return "\n".join(md)
