"""Benchmarks of the quench chain: cost of each stage and its growth with the mesh size.

``write(reports_dir)`` runs case A condition 1 at three refinements with thermal + metallurgy only
and with the full chain, and writes ``bench.md`` (+ ``bench.json``). Timings are wall-clock seconds
on the machine that ran ``quenchsim validate`` (this project's reference: 2 cores); they are
measurements, not tests.
"""

from __future__ import annotations

import json
import os
import platform
import tempfile
import time
from pathlib import Path
from typing import Any

from quenchsim.case import load_case

CASE_A = Path(__file__).resolve().parents[2] / "cases" / "crb_outer_ring.toml"
MESH_FACTORS = (2.0, 1.0, 0.5)


def _run(mesh_factor: float, mechanics: bool) -> dict[str, Any]:
    from quenchsim.simulation import run_case

    case = load_case(CASE_A, "1")
    case.data["mesh"]["size_mm"] *= mesh_factor
    case.data["mesh"]["surface_size_mm"] *= mesh_factor
    case.data["mechanics"]["enabled"] = mechanics
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        s = run_case(case, Path(tmp), progress=False).summary
        total = time.perf_counter() - t0
    return {"mesh_factor": mesh_factor, "mechanics": mechanics, "elements": s["solver"]["elements"],
            "dofs": s["solver"]["dofs"], "steps": s["solver"]["steps"], "total_s": total, **s["solver"]["stage_time_s"]}


def write(reports_dir: Path) -> list[Path]:
    reports_dir = Path(reports_dir)
    rows = [_run(f, mech) for mech in (False, True) for f in MESH_FACTORS]
    cols = ("elements", "dofs", "steps", "total_s", "bath_htc_s", "thermal_metallurgy_s", "mechanics_s", "output_s")
    md = ["# Benchmarks of the quench chain", "",
          f"Case A, condition 1, at three mesh refinements (element sizes x{', x'.join(f'{f:g}' for f in MESH_FACTORS)} of "
          "the default). Wall-clock seconds, measured by `quenchsim validate` (quenchsim/report/bench.py) on "
          f"{platform.machine()} with {os.cpu_count()} cores, Python {platform.python_version()}. "
          "`total_s` includes meshing, setup and post-processing; the stage columns are the time spent in each stage "
          "of the time loop.", ""]
    for mech in (False, True):
        md += [f"## {'Full chain (thermal + metallurgy + mechanics)' if mech else 'Thermal + metallurgy only'}", "",
               "| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
        for r in rows:
            if r["mechanics"] == mech:
                md.append("| " + " | ".join(f"{r.get(c, 0.0):.3g}" if isinstance(r.get(c, 0.0), float) else str(r[c])
                                            for c in cols) + " |")
        md.append("")
    base = [r for r in rows if r["mechanics"] and r["mesh_factor"] == 1.0][0]
    share = base.get("bath_htc_s", 0.0) / base["total_s"]
    md += [f"The bath model (building every boundary point's HTC(T) curve, once per stage) takes "
           f"{base.get('bath_htc_s', 0.0):.3f} s of the {base['total_s']:.1f} s full run at the default mesh "
           f"({100 * share:.2f} %); its per-iteration interpolation is inside the thermal stage.", ""]
    (reports_dir / "bench.md").write_text("\n".join(md) + "\n")
    (reports_dir / "bench.json").write_text(json.dumps(rows, indent=2))
    return [reports_dir / "bench.md", reports_dir / "bench.json"]
