"""What a design study writes for a process engineer: ``trials.csv`` (every trial), ``optimise.json``, the page
``optimise.md`` (the recommended settings with the hardness, size and shape of the confirmation run, the fidelity
check, the front, what each variable does, the maps) and the plain-text summary the command prints."""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.design import plots
from quenchsim.design.optimise import TrialRecord, scores
from quenchsim.report.run_report import fmt

KEY_RESULTS = ("hardness.depth_mm.HRC58_bore_mid", "hardness.depth_mm.HRC58_od_mid", "hardness.core_HRC",
               "dimensions_mm.change.id", "dimensions_mm.change.od", "dimensions_mm.change.width",
               "shape_mm.change.bore_taper", "shape_mm.change.bore_crown", "shape_mm.change.od_taper",
               "shape_mm.change.od_crown", "shape_mm.change.top_face_dish", "shape_mm.change.bottom_face_dish",
               "residual_stress_MPa.hoop.bore_surface_mid", "residual_stress_MPa.hoop.od_surface_mid")
"""What the page shows of the confirmation run besides the study's own quantities: hardness, size, shape, stress."""
TRIALS_CSV = "trials.csv"
RESULT_JSON = "optimise.json"
PAGE_MD = "optimise.md"


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_")


def write_trials_csv(outcome: Any, path: Path) -> None:
    """Every evaluated trial: number, state, feasible, variables, study quantities, violations, error, run folder,
    then the key outputs of its summary."""
    spec = outcome.spec
    quantities = spec.quantities()
    rows = []
    for t in outcome.trials:
        row = {"trial": t.number, "state": t.state, "feasible": t.feasible, **t.params,
               **{q: t.quantities.get(q) for q in quantities},
               **{f"violation: {c.label()}": v for c, v in zip(spec.constraints, t.violations)},
               "error": t.error or "", "run": t.info.get("run", "")}
        row.update({k: v for k, v in t.info.get("summary", {}).items() if k not in row})
        rows.append(row)
    columns: list[str] = []
    for row in rows:
        columns += [k for k in row if k not in columns]
    tmp = path.with_name(path.name + ".tmp")
    with tmp.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=columns or ["trial"], restval="")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: ("" if v is None else v) for k, v in row.items()})
    tmp.replace(path)


def _trial_json(t: TrialRecord | None) -> dict[str, Any] | None:
    if t is None:
        return None
    return {"trial": t.number, "params": t.params, "state": t.state, "feasible": t.feasible, "quantities": t.quantities,
            "violations": t.violations, "error": t.error, "run": t.info.get("run")}


def result_json(outcome: Any) -> dict[str, Any]:
    spec = outcome.spec
    return {"name": spec.name, "case": str(spec.case.path), "condition": spec.case.condition,
            "variables": [{"key": v.key, "low": v.low, "high": v.high, "log": v.log, "integer": v.integer,
                           "choices": list(v.choices)} for v in spec.variables],
            "objectives": [o.label() for o in spec.objectives], "constraints": [c.label() for c in spec.constraints],
            "fidelity": {"mesh": spec.fidelity.mesh, "step": spec.fidelity.step, "tolerance": spec.fidelity.tolerance},
            "trials": len(outcome.trials), "trials_ok": sum(t.state == "ok" for t in outcome.trials),
            "trials_feasible": sum(t.feasible for t in outcome.trials), "interrupted": outcome.interrupted,
            "constraints_met": outcome.feasible, "recommended": _trial_json(outcome.recommended),
            "front": [_trial_json(t) for t in outcome.front], "closest": [_trial_json(t) for t in outcome.closest],
            "confirmations": [{"trial": c.trial, "role": c.role, "params": c.params, "run": c.run, "error": c.error,
                               "full": c.full, "cheap": c.cheap, "agree": c.agree,
                               "key_results": {k: c.summary_flat.get(k) for k in KEY_RESULTS},
                               "uncertainty": c.uncertainty} for c in outcome.confirmations],
            "effects": outcome.effects, "wall_time_s": outcome.wall_time_s}


def _plots(outcome: Any) -> list[Path]:
    spec, out = outcome.spec, outcome.out
    ok = [t for t in outcome.trials if t.state == "ok"]
    written: list[Path] = []
    if not ok:
        return written
    feasible = np.array([t.feasible for t in ok])
    best = outcome.recommended
    if len(spec.objectives) == 2:
        xy = np.array([scores(t, spec.objectives) for t in ok]) * np.array([-1.0 if o.goal == "max" else 1.0
                                                                             for o in spec.objectives])
        front = np.array([[xy[ok.index(t), 0], xy[ok.index(t), 1]] for t in outcome.front]).reshape(-1, 2)
        labels = [o.label() if o.goal != "target" else f"|{o.quantity} - {o.target:g}|" for o in spec.objectives]
        written.append(plots.pareto_plot(xy, feasible, front, xy[ok.index(best)] if best else None, labels,
                                         f"{spec.name}: trials and Pareto front (cheap fidelity)", out / "pareto.png"))
    if spec.map_variables:
        a, b = (next(v for v in spec.variables if v.key == key) for key in spec.map_variables)
        x = np.array([t.params[a.key] for t in ok], dtype=float)
        y = np.array([t.params[b.key] for t in ok], dtype=float)
        for q in spec.quantities():
            z = np.array([t.quantities[q] for t in ok], dtype=float)
            star = (best.params[a.key], best.params[b.key]) if best else None
            written.append(plots.map_plot(x, y, z, feasible, star, [a.key, b.key, q], f"{spec.name}: {q}",
                                          out / f"map_{_slug(q)}.png"))
    return written


def page_markdown(outcome: Any, images: list[Path]) -> str:
    spec = outcome.spec
    n_ok = sum(t.state == "ok" for t in outcome.trials)
    n_feasible = sum(t.feasible for t in outcome.trials)
    md = [f"Case `{spec.case.path.name}`" + (f", condition {spec.case.condition}" if spec.case.condition else "")
          + f"; {len(outcome.trials)} cheap-fidelity trials (element size x{spec.fidelity.mesh:g}, step limits "
            f"x{spec.fidelity.step:g}; {n_ok} ran, {n_feasible} met the constraints; the first {spec.startup} a Latin "
            f"hypercube, then Optuna's {spec.sampler.upper()} sampler, seed {spec.seed}); "
            f"{len(outcome.confirmations)} full-chain confirmation run(s); {outcome.wall_time_s / 60:.1f} min wall.", ""]
    if outcome.interrupted:
        md += ["**Interrupted**: run the same command again to go on (finished trials are not run again).", ""]
    md += ["| variable | range |", "|---|---|"]
    md += [f"| `{v.key}` | " + (", ".join(map(str, v.choices)) if v.choices else
                                f"{v.low:g} .. {v.high:g}{' (log)' if v.log else ''}{' (integer)' if v.integer else ''}")
           + " |" for v in spec.variables]
    md += ["", "Objectives: " + "; ".join(f"`{o.label()}`" for o in spec.objectives) + ". Constraints: "
           + ("; ".join(f"`{c.label()}`" for c in spec.constraints) or "none") + ".", ""]
    if outcome.recommended is None and not outcome.interrupted:
        md += ["### No run met the constraints", "",
               f"None of the {n_ok} runs meets " + " and ".join(f"`{c.label()}`" for c in spec.constraints)
               + ". The closest runs (smallest miss relative to the bound):", "",
               "| trial | " + " | ".join(f"`{v.key}`" for v in spec.variables) + " | "
               + " | ".join(f"`{c.quantity}` ({c.op} {c.bound:g})" for c in spec.constraints) + " |",
               "|---" * (1 + len(spec.variables) + len(spec.constraints)) + "|"]
        md += [f"| {t.number} | " + " | ".join(fmt(t.params[v.key]) for v in spec.variables) + " | "
               + " | ".join(fmt(t.quantities.get(c.quantity)) for c in spec.constraints) + " |" for t in outcome.closest]
        md.append("")
    for c in outcome.confirmations:
        title = {"recommended": "Recommended settings", "front": f"Front point (trial {c.trial})",
                 "closest": "Closest run to the constraints (they are not met)"}[c.role]
        md += [f"### {title}", "", "| variable | value |", "|---|---|"]
        md += [f"| `{k}` | {fmt(v)} |" for k, v in c.params.items()]
        md += [""]
        if c.error:
            md += [f"The full-chain confirmation run failed: {c.error}", ""]
            continue
        md += [f"Full chain (`{c.run}`) against the cheap run of trial {c.trial}:", "",
               "| quantity | cheap | full chain | full - cheap | tolerance | agree |", "|---|---|---|---|---|---|"]
        for q in spec.quantities():
            full, cheap = c.full.get(q), c.cheap.get(q)
            diff = None if full is None or cheap is None else full - cheap
            md.append(f"| `{q}` | {fmt(cheap)} | {fmt(full)} | {fmt(diff)} | {fmt(spec.fidelity.tolerance.get(q))} | "
                      f"{fmt(c.agree.get(q))} |")
        bands = (c.uncertainty or {}).get("quantities", {})
        md += ["", "Hardness, size and shape at the full-chain run" + (" (5-95 % band of the "
                                                                      f"{c.uncertainty['source']})" if bands else "")
               + ":", "", "| quantity | value |" + (" band |" if bands else ""), "|---|---|" + ("---|" if bands else "")]
        for k in KEY_RESULTS:
            if c.summary_flat.get(k) is None:
                continue
            band = bands.get(k)
            md.append(f"| `{k}` | {fmt(c.summary_flat[k])} |"
                      + ((f" {fmt(band['p5'])} .. {fmt(band['p95'])} |" if band else " - |") if bands else ""))
        md.append("")
    if len(outcome.front) > 1:
        md += ["### Pareto front (cheap fidelity)", "", "| trial | " + " | ".join(f"`{v.key}`" for v in spec.variables)
               + " | " + " | ".join(f"`{o.quantity}`" for o in spec.objectives) + " |",
               "|---" * (1 + len(spec.variables) + len(spec.objectives)) + "|"]
        md += [f"| {t.number} | " + " | ".join(fmt(t.params[v.key]) for v in spec.variables) + " | "
               + " | ".join(fmt(t.quantities[o.quantity]) for o in spec.objectives) + " |" for t in outcome.front]
        md.append("")
    if outcome.effects:
        names = list(next(iter(outcome.effects.values()))["variables"])
        md += ["### What each variable does", "",
               "Change of each quantity from the variable's low to its high bound (the others at the recommended "
               "settings) and, in brackets, the variable's share of the quantity's variance over the whole range "
               "(first-order Sobol index), both from a quadratic response surface through the cheap trials (R^2 "
               "its fit).", "", "| quantity | R^2 | " + " | ".join(f"`{n}`" for n in names) + " |",
               "|---" * (2 + len(names)) + "|"]
        for q, e in outcome.effects.items():
            md.append(f"| `{q}` | {e['r2']:.3f} | " + " | ".join(
                f"{e['variables'][n]['low_to_high']:+.4g} ({e['variables'][n]['variance_share']:.2f})" for n in names)
                + " |")
        md.append("")
    md += [f"![{p.stem}]({p.name})" for p in images]
    md += ["", f"Every trial: `{TRIALS_CSV}`; the study: `study.db` (Optuna, SQLite); the runs: `runs/`."]
    return "\n".join(md)


def write_outputs(outcome: Any) -> dict[str, str]:
    """Write trials.csv, optimise.json, the plots and optimise.md into the study folder; their paths by name."""
    out = outcome.out
    write_trials_csv(outcome, out / TRIALS_CSV)
    (out / RESULT_JSON).write_text(json.dumps(result_json(outcome), indent=2, default=str))
    images = _plots(outcome)
    (out / PAGE_MD).write_text(f"# Design study {outcome.spec.name}\n\n" + page_markdown(outcome, images) + "\n")
    return {"trials": str(out / TRIALS_CSV), "json": str(out / RESULT_JSON), "page": str(out / PAGE_MD),
            **{p.stem: str(p) for p in images}}


def summary_text(outcome: Any) -> str:
    """The plain-text summary ``quenchsim optimise`` prints."""
    spec = outcome.spec
    n_ok = sum(t.state == "ok" for t in outcome.trials)
    rows = [f"optimise {spec.name}: {len(outcome.trials)} trials at mesh x{spec.fidelity.mesh:g} / steps "
            f"x{spec.fidelity.step:g} ({n_ok} ok, {sum(t.feasible for t in outcome.trials)} meet the constraints), "
            f"{len(outcome.confirmations)} full-chain, {outcome.wall_time_s / 60:.1f} min -> {outcome.out}"]
    if outcome.interrupted:
        rows.append("interrupted: run the same command again to go on (finished trials are not run again)")
    elif outcome.recommended is None:
        rows.append("NO RUN MET THE CONSTRAINTS (" + "; ".join(c.label() for c in spec.constraints) + "); closest runs:")
        for t in outcome.closest:
            rows.append(f"  trial {t.number}: " + ", ".join(f"{k} = {fmt(v)}" for k, v in t.params.items()) + " -> "
                        + ", ".join(f"{c.quantity} = {fmt(t.quantities.get(c.quantity))}" for c in spec.constraints))
    for c in outcome.confirmations:
        rows.append(f"{c.role} (trial {c.trial}): " + ", ".join(f"{k} = {fmt(v)}" for k, v in c.params.items()))
        if c.error:
            rows.append(f"  full-chain run failed: {c.error}")
            continue
        rows.append(f"  {'quantity':<40}{'cheap':>12}{'full chain':>12}{'tolerance':>11}  agree")
        for q in spec.quantities():
            rows.append(f"  {q:<40}{fmt(c.cheap.get(q)):>12}{fmt(c.full.get(q)):>12}"
                        f"{fmt(spec.fidelity.tolerance.get(q)):>11}  {fmt(c.agree.get(q))}")
    for q, e in outcome.effects.items():
        rows.append(f"effect on {q} (low -> high bound, variance share; R^2 {e['r2']:.2f}): " + ", ".join(
            f"{n.split('.')[-1]} {v['low_to_high']:+.3g} ({v['variance_share']:.2f})" for n, v in e["variables"].items()))
    rows.append(f"page: {outcome.files.get('page')}; every trial: {outcome.files.get('trials')}")
    return "\n".join(rows)
