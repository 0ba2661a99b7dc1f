"""Ring A condition 1 and ring B condition 4 quenched and tempered at 180 C for 2 h (furnace air, then air cooling):
the tempered hardness, retained austenite, size, shape and residual stress beside the as-quenched ones, and the
tempering part of the distortion budget (one run per ring: its summary.json holds both states). No measurement of
the tempered rings is published: the page records the prediction."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.case import load_case
from quenchsim.results import load as load_run
from quenchsim.validation import ROOT, cached_run, study_module

TITLE = "Quench and temper: ring A condition 1 and ring B condition 4, tempered at 180 C / 2 h (not tuned)"
SLOW = True
TEMPER = {"temper": {"temperature_C": 180.0, "time_s": 7200.0, "cool_time_s": 40000.0}}
RINGS = {"A1": (ROOT / "cases" / "crb_outer_ring.toml", "1", "bore"),
         "B4": (ROOT / "cases" / "srb_outer_ring.toml", "4", "raceway")}


def run(workdir: Path) -> dict[str, Any]:
    runs_dir = study_module("quench/ring_a").run_dirs(Path(workdir))
    metrics: dict[str, Any] = {}
    for ring, (path, condition, bore) in RINGS.items():
        case = load_case(path, condition, overrides={"temper.temperature_C": 180.0, "temper.time_s": 7200.0,
                                                     "temper.cool_time_s": 40000.0})
        s = load_run(cached_run(case, runs_dir / f"{path.stem}_{condition}_temper_180C_2h")).summary
        t = s["tempered"]
        metrics[ring] = {"status": s["status"], "bore_name": bore,
                         "as_quenched": _state(s), "tempered": _state(t),
                         "change_by_temper_mm": t["change_by_temper_mm"],
                         "tempering_budget_mm": t["tempering_budget_mm"],
                         "tempering_parameter_K": t["tempering_parameter_K"]}
    return metrics


def _state(s: dict[str, Any]) -> dict[str, Any]:
    return {"core_HRC": s["hardness"]["core_HRC"], "surface_HRC": s["hardness"]["surface_HRC"],
            "retained_austenite_mean": s["phases_final"]["austenite"]["mean"],
            "dimensions_after_mm": s["dimensions_mm"]["after"], "shape_after_mm": s["shape_mm"]["after"],
            "hoop_MPa": s["residual_stress_MPa"]["hoop"], "axial_MPa": s["residual_stress_MPa"]["axial"]}


def page(metrics: dict[str, Any]) -> str:
    md = ["Each ring is run once through quench, air cooling, a 2 h hold in 180 C furnace air (natural convection "
          "and radiation) and air cooling (`[temper]`, docs/guide/temper.md); its summary.json keeps the as-quenched "
          "state beside the tempered one. No dimension of a tempered ring is published for these cases: the page "
          "records the prediction. The tempering model and its sources: validation/materials/tempering "
          "(reports/materials_tempering.md); the stress relaxation law is an assumption with a wide prior "
          "(materials/data/tempering_1C_Cr.toml [relaxation]).", ""]
    for ring, m in metrics.items():
        q, t, bore = m["as_quenched"], m["tempered"], m["bore_name"]
        md += [f"### Ring {ring[0]}, condition {ring[1:]} (status {m['status']})", "",
               "| quantity | as quenched | tempered | change |", "|---|---|---|---|"]
        md.append(f"| core HRC | {q['core_HRC']:.1f} | {t['core_HRC']:.1f} | {t['core_HRC'] - q['core_HRC']:+.1f} |")
        for where in ("od_mid", "bore_mid"):
            a, b = q["surface_HRC"][where], t["surface_HRC"][where]
            md.append(f"| surface HRC {where.replace('bore', bore)} | {a:.1f} | {b:.1f} | {b - a:+.1f} |")
        a, b = q["retained_austenite_mean"], t["retained_austenite_mean"]
        md.append(f"| retained austenite, mean | {a:.4f} | {b:.4f} | {b - a:+.4f} |")
        for k, a in q["dimensions_after_mm"].items():
            b = t["dimensions_after_mm"][k]
            md.append(f"| {bore if k == 'id' else k} (mm) | {a:.3f} | {b:.3f} | {b - a:+.4f} |")
        for k in ("bore_taper", "od_taper", "bore_crown", "od_crown"):
            a, b = q["shape_after_mm"][k], t["shape_after_mm"][k]
            if a is not None and b is not None:
                md.append(f"| {k.replace('bore', bore)} (mm) | {a:.4f} | {b:.4f} | {b - a:+.4f} |")
        for k, a in q["hoop_MPa"].items():
            b = t["hoop_MPa"][k]
            md.append(f"| hoop stress {k.replace('bore', bore)} (MPa) | {a:.0f} | {b:.0f} | {b - a:+.0f} |")
        md += ["", "Tempering part of the distortion budget (each part after the temper minus as quenched, mm):", "",
               f"| part | {bore} | OD | width |", "|---|---|---|---|"]
        for part, v in m["tempering_budget_mm"].items():
            md.append(f"| {part} | {v['id']:+.4f} | {v['od']:+.4f} | {v['width']:+.4f} |")
        P = m["tempering_parameter_K"]
        md += ["", f"Hollomon-Jaffe parameter reached: {P['min']:.0f}-{P['max']:.0f} K (volume mean {P['mean']:.0f} K; "
               "an isothermal 2 h at 180 C gives 7160 K).", ""]
    return "\n".join(md)
