"""Mesh and time-step convergence of case A, condition 1 (full chain): element sizes x2 / x1 / x0.5 and the
per-step temperature/phase limits x2 / x1 / x0.5. The runs are shared with quench/ring_a (the x1 run),
speed/quench_chain (the mesh runs) and quench/sensitivity (mesh x2)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.validation import cached_run, refined_case, study_module

TITLE = "Mesh and time-step convergence (case A, condition 1)"
SLOW = True
MESH_FACTORS = (2.0, 1.0, 0.5)
"""Element-size multipliers of the convergence study."""
STEP_FACTORS = (2.0, 1.0, 0.5)
"""Multipliers of the per-step temperature/phase limits."""


def run_name(mesh: float = 1.0, step: float = 1.0) -> str:
    """Folder of a case-A condition-1 run (as the validation page named them)."""
    if mesh != 1.0:
        return f"crb_outer_ring_1_mesh{mesh:g}"
    if step != 1.0:
        return f"crb_outer_ring_1_step{step:g}"
    return "crb_outer_ring_1"


def case_a_run(workdir: Path, mesh: float = 1.0, step: float = 1.0) -> Path:
    """The cached case-A condition-1 run at these factors (run when missing)."""
    ring_a = study_module("quench/ring_a")
    return cached_run(refined_case(ring_a.CASE_A, "1", mesh=mesh, step=step),
                      ring_a.run_dirs(workdir) / run_name(mesh, step))


def run(workdir: Path) -> dict[str, Any]:
    import json

    rows = {}
    for kind, factors in (("mesh", MESH_FACTORS), ("step limits", STEP_FACTORS)):
        for f in factors:
            path = case_a_run(workdir, **({"mesh": f} if kind == "mesh" else {"step": f}))
            s = json.loads((path / "summary.json").read_text())
            d = s.get("dimensions_mm", {}).get("change", {})
            rows[f"{kind} x{f:g}"] = {"elements": s["solver"]["elements"], "steps": s["solver"]["steps"],
                                      "P1_t500_s": s["probes"]["P1"]["t_to_500C_s"],
                                      "P3_t500_s": s["probes"]["P3"]["t_to_500C_s"],
                                      "HRC58_depth_bore_mm": s["hardness"]["depth_mm"]["HRC58_bore_mid"],
                                      "change_mm": d}
    fine, coarse = rows["mesh x0.5"], rows["mesh x2"]
    spread = {k: max(abs(r["change_mm"][k] - rows["mesh x1"]["change_mm"][k]) for r in (fine, coarse)) for k in ("id", "od")}
    return {"runs": rows, "mesh_spread_change_mm": spread}


def page(metrics: dict[str, Any]) -> str:
    md = ["| run | elements | steps | P1 t(500 C) s | P3 t(500 C) s | HRC58 depth bore mm | OD change mm | ID change mm |",
          "|---|---|---|---|---|---|---|---|"]
    for label, r in metrics["runs"].items():
        d = r["change_mm"]
        md.append(f"| {label} | {r['elements']} | {r['steps']} | {r['P1_t500_s']:.2f} | {r['P3_t500_s']:.2f} | "
                  f"{r['HRC58_depth_bore_mm']:.2f} | {d.get('od', float('nan')):+.4f} | {d.get('id', float('nan')):+.4f} |")
    return "\n".join(md)
