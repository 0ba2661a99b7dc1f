"""Benchmarks of the quench chain: cost of each stage and its growth with the mesh size.

Case A condition 1 at three refinements (the runs of quench/convergence, cached under ``runs/validation``;
run here if missing): the wall time of each stage of the time loop. Timings are measurements on the
machine that ran ``quenchsim validate``, not tests.
"""

from __future__ import annotations

import json
import os
import platform
from pathlib import Path

from quenchsim.validation import study_module

TITLE = "Benchmarks of the quench chain"
SLOW = True
STAGES = ("bath_htc_s", "thermal_metallurgy_s", "mechanics_s", "output_s")
LOOP_STAGES = ("thermal_metallurgy_s", "mechanics_s")
"""The time loop: its cost per DOF per step should not grow with the mesh (issue 18 item 2)."""


def run(workdir: Path) -> dict:
    convergence = study_module("quench/convergence")
    rows = []
    for f in convergence.MESH_FACTORS:
        s = json.loads((convergence.case_a_run(workdir, mesh=f) / "summary.json").read_text())["solver"]
        loop_s = sum(s["stage_time_s"].get(k, 0.0) for k in LOOP_STAGES)
        rows.append({"mesh_factor": f, "elements": s["elements"], "dofs": s["dofs"], "steps": s["steps"],
                     "total_s": s["wall_time_s"], **{k: s["stage_time_s"].get(k, 0.0) for k in STAGES},
                     "loop_us_per_dof_step": 1e6 * loop_s / (s["dofs"] * s["steps"])})
    cols = ("mesh_factor", "elements", "dofs", "steps", "total_s", *STAGES, "loop_us_per_dof_step")
    md = ["Case A (crb_outer_ring), condition 1, full chain (bath model, thermal + metallurgy, mechanics with "
          "plasticity and TRIP), at three mesh refinements (element sizes times the factor). Wall-clock seconds "
          f"measured on {platform.machine()} with {os.cpu_count()} cores, Python {platform.python_version()}, "
          "by `quenchsim validate`. `total_s` includes meshing, setup and "
          "post-processing; the stage columns are the time spent in each stage of the time loop "
          "(thermal_metallurgy_s is the thermal solve with the kinetics inside its iteration). The runs are the "
          "validation runs: when several ran at once on the two cores, their wall times include that sharing -- "
          "compare them with `quenchsim run` on an idle machine before quoting absolute times.", "",
          "| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        md.append("| " + " | ".join(f"{r[c]:.3g}" if isinstance(r[c], float) else str(r[c]) for c in cols) + " |")
    base = [r for r in rows if r["mesh_factor"] == 1.0][0]
    fine, coarse = rows[-1], rows[0]
    growth = (fine["total_s"] / coarse["total_s"]) / (fine["dofs"] / coarse["dofs"])
    per_dof_step = [r["loop_us_per_dof_step"] for r in rows]
    loop_spread = max(per_dof_step) / min(per_dof_step)
    md += ["", f"The bath model (each boundary point's HTC(T) curve, built once per stage) takes "
           f"{base['bath_htc_s']:.3f} s of the {base['total_s']:.1f} s run at the default mesh "
           f"({100 * base['bath_htc_s'] / base['total_s']:.2f} %); its per-iteration interpolation is inside the "
           "thermal stage.",
           f"From the coarsest to the finest mesh the dofs grow x{fine['dofs'] / coarse['dofs']:.1f} and the run time "
           f"x{fine['total_s'] / coarse['total_s']:.1f} (time per dof per step ratio {growth:.2f}).",
           f"The time loop's cost per DOF per step (`loop_us_per_dof_step`, thermal + metallurgy + mechanics) ranges "
           f"over the meshes by a factor {loop_spread:.2f} (max/min). `python dev/bench.py` compares these timings with an "
           "earlier commit side by side (docs/experiments/bench.md).", ""]
    return {"rows": rows, "loop_cost_spread": loop_spread, "page_md": "\n".join(md) + "\n"}


def page(metrics: dict) -> str:
    return metrics["page_md"]
