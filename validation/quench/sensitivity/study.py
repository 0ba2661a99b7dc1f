"""How far each declared prior of SUJ3 moves ring A's dimension change: a one-at-a-time screening at the
priors' bounds.

Every entry of materials/SUJ3.toml and SUJ3.mechanics.toml that carries a prior (``range`` or
``range_factor``, with its source) is set, alone, to the lower and to the upper end of its prior
(:func:`quenchsim.calibration.declared_priors`: a factor on the entry), and case A condition 1 is rerun on the
mesh x2 of the convergence study (dimensions within 0.002 mm of the default mesh). Two mechanism switches
(no TRIP; no plasticity and no TRIP) show the budget's parts. The page ranks the inputs by the swing of the ID
change: the candidates for calibration (validation/calibration/ring_a uses the global Morris/Sobol screening
of the inputs it calibrates). Runs: ``runs/validation/sensitivity/<code fingerprint>/`` (an interrupted run
resumes; a changed model starts afresh).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.calibration import declared_priors
from quenchsim.calibration.runs import quantity, request, run_requests
from quenchsim.validation import code_fingerprint, refined_case, study_module, study_targets

TITLE = "Sensitivity of ring A's dimension change to every declared SUJ3 prior (one at a time, at the prior's bounds)"
SLOW = True
MESH_FACTOR = 2.0
WORKERS = 2
SWITCHES = {"no TRIP": {"mechanics.trip": False},
            "thermo-elastic (no plasticity, no TRIP)": {"mechanics.trip": False, "mechanics.plasticity": False}}
DIMENSIONS = ("id", "od", "width")


def run(workdir: Path) -> dict[str, Any]:
    ring_a = study_module("quench/ring_a")
    folder = ring_a.run_dirs(workdir) / "sensitivity" / code_fingerprint()[:12]
    base = refined_case(ring_a.CASE_A, "1", mesh=MESH_FACTOR)
    inputs = declared_priors("material", base.material)
    reqs = {"baseline": request(base, [], [])}
    for inp in inputs:
        for end, factor in zip(("lower", "upper"), inp.factor_bounds):
            reqs[f"{inp.path}|{end}"] = request(base, [inp], [factor])
    for label, overrides in SWITCHES.items():
        reqs[label] = request(base.with_overrides(overrides), [], [])
    done = run_requests(list(reqs.values()), folder, workers=WORKERS, desc="sensitivity")
    change = {label: {k: quantity(done.summaries.get(r.folder_name()), f"dimensions_mm.change.{k}") for k in DIMENSIONS}
              for label, r in reqs.items()}
    rows = []
    for inp in inputs:
        lo, hi = change[f"{inp.path}|lower"], change[f"{inp.path}|upper"]
        swing = {k: (None if lo[k] is None or hi[k] is None else hi[k] - lo[k]) for k in DIMENSIONS}
        rows.append({"input": inp.path, "prior": inp.prior, "factor_bounds": list(inp.factor_bounds),
                     "lower": lo, "upper": hi, "swing": swing})
    rows.sort(key=lambda r: -abs(r["swing"]["id"] or 0.0))
    return {"baseline_change_mm": change["baseline"], "inputs": rows,
            "switches": {label: change[label] for label in SWITCHES}, "failed_runs": len(done.failed),
            "largest_id_swing_mm": max(abs(r["swing"]["id"] or 0.0) for r in rows),
            "sum_of_id_swings_mm": sum(abs(r["swing"]["id"] or 0.0) for r in rows)}


def _mm(x: float | None) -> str:
    return "-" if x is None else f"{x:+.3f}"


def page(metrics: dict[str, Any]) -> str:
    targets = study_targets(__file__)
    measured = {k: targets[f"baseline_change_mm.{k}"].value for k in ("id", "od")}
    base = metrics["baseline_change_mm"]
    md = [f"Case A, condition 1, mesh x2. Baseline (every input at its value): ID {_mm(base['id'])}, OD {_mm(base['od'])}, "
          f"width {_mm(base['width'])} mm; measured ID {measured['id']:+.2f}, OD {measured['od']:+.2f} mm (reference "
          "report, Table 3). Each row: one declared prior at its lower / upper bound, the others at their values.", "",
          "| input | prior | ID change at lower / upper | OD change at lower / upper | swing of ID / OD (upper - lower) |",
          "|---|---|---|---|---|"]
    for r in metrics["inputs"]:
        md.append(f"| `{r['input'].split('.', 2)[-1]}` | {r['prior']} | {_mm(r['lower']['id'])} / {_mm(r['upper']['id'])} | "
                  f"{_mm(r['lower']['od'])} / {_mm(r['upper']['od'])} | {_mm(r['swing']['id'])} / {_mm(r['swing']['od'])} |")
    md += ["", "| mechanism switch | ID change | OD change | width change |", "|---|---|---|---|"]
    for label, c in metrics["switches"].items():
        md.append(f"| {label} | {_mm(c['id'])} | {_mm(c['od'])} | {_mm(c['width'])} |")
    gap = measured["id"] - base["id"]
    md += ["", f"To reach the measured ID the inputs would have to move it by {gap:+.2f} mm. The largest single swing over "
           f"a whole prior is {metrics['largest_id_swing_mm']:.2f} mm and the swings add up to "
           f"{metrics['sum_of_id_swings_mm']:.2f} mm (an upper bound of one-at-a-time reach if the effects added, which "
           "the global screening and the posterior of validation/calibration/ring_a test properly).", ""]
    return "\n".join(md)
