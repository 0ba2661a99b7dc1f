"""Design study, case B: the ID and OD jet speeds of the spherical-roller-bearing outer ring (cases/srb_outer_ring.toml)
that keep condition 4's through-hardening at mid-width and change the raceway's diameter and crown least
(ring_b.study.toml), run with `quenchsim optimise`'s code: cheap-fidelity trials, full-chain confirmations.

Runs: ``runs/validation/design_ring_b/<code fingerprint>/`` (an interrupted validate resumes the study; a changed
model starts afresh). The helpers here serve design/ring_a too."""

from __future__ import annotations

import json
import os
import shutil
import time
from pathlib import Path
from typing import Any

from quenchsim.validation import code_fingerprint, study_module

TITLE = "Design study, case B: ID/OD jet speeds for the least raceway diameter change and crown at condition 4's hardness"
SLOW = True
STUDY_FILE = Path(__file__).with_name("ring_b.study.toml")
WORKERS = 2


def run_design(study_file: Path, workdir: Path, label: str) -> dict[str, Any]:
    """Run (or resume) a design study into the validation runs folder; metrics for the page and the targets, its
    PNGs copied into ``workdir`` as ``design_<label>_*.png``."""
    from quenchsim.design.page import page_markdown
    from quenchsim.design.spec import load_study
    from quenchsim.design.study import run_study

    spec = load_study(study_file)
    out = study_module("quench/ring_a").run_dirs(workdir) / f"design_{label}" / code_fingerprint()[:12]
    load_before = os.getloadavg()
    t0 = time.perf_counter()
    outcome = run_study(spec, out, workers=WORKERS, progress=False)
    # the study's wall time summed over every call that worked on it (an interrupted validate resumes it)
    timing_file = out / "validation_timing.json"
    calls = json.loads(timing_file.read_text()) if timing_file.is_file() else []
    calls.append({"wall_s": time.perf_counter() - t0, "load_before_1min": load_before[0],
                  "load_after_15min": os.getloadavg()[2]})
    longest = max(calls, key=lambda c: c["wall_s"])   # the call that ran the study: its load
    timing_file.write_text(json.dumps(calls))
    wall = sum(c["wall_s"] for c in calls)
    if outcome.interrupted:   # an unfinished study is no result: validate stops, the next call resumes it
        raise KeyboardInterrupt(f"design study {label} interrupted; run quenchsim validate again to resume it")
    images = []
    for png in sorted(out.glob("*.png")):
        target = Path(workdir) / f"design_{label}_{png.name}"
        shutil.copy2(png, target)
        images.append(target)
    body = page_markdown(outcome, [])
    for png, target in zip(sorted(out.glob("*.png")), images):
        body += f"\n\n![{png.stem}]({target.name})"
    fidelity_ratio = [abs(c.full[q] - c.cheap[q]) / spec.fidelity.tolerance[q] for c in outcome.confirmations
                      if c.error is None for q in spec.quantities() if c.full.get(q) is not None and c.cheap.get(q) is not None]
    rec = next((c for c in outcome.confirmations if c.role == "recommended"), None)
    return {"label": label, "page_body": body, "wall_time_min": wall / 60.0, "calls": len(calls),
            "load_average": {"before_1min": longest["load_before_1min"], "after_15min": longest["load_after_15min"]},
            "trials": len(outcome.trials), "trials_ok": sum(t.state == "ok" for t in outcome.trials),
            "trials_feasible": sum(t.feasible for t in outcome.trials), "full_chain_runs": len(outcome.confirmations),
            "fidelity": {"mesh": spec.fidelity.mesh, "step": spec.fidelity.step, "tolerance": spec.fidelity.tolerance,
                         "max_diff_over_tolerance": max(fidelity_ratio) if fidelity_ratio else None,
                         "compared": len(fidelity_ratio)},
            "constraints_met": 1.0 if outcome.feasible else 0.0,
            "recommended": None if rec is None else {"params": rec.params, "full": rec.full, "cheap": rec.cheap},
            "effects": outcome.effects, "interrupted": outcome.interrupted, "out": str(out)}


JET_NAMES = {"quench.bath.id_jet_speed_mm_s": "ID jets", "quench.bath.od_jet_speed_mm_s": "OD jets"}
QUANTITY_NAMES = {"dimensions_mm.change.id": ("raceway diameter change", "mm"),
                  "shape_mm.change.bore_crown": ("raceway crown change", "mm"),
                  "hardness.depth_mm.HRC58_bore_mid": ("HRC58 depth below the raceway", "mm")}


def jet_sentences(metrics: dict[str, Any]) -> list[str]:
    """What each jet does to each objective and to the hardness, in words, from the study's effects."""
    study = metrics.get("effects") or {}
    lines = []
    for key, jet in JET_NAMES.items():
        parts = []
        for q, (name, unit) in QUANTITY_NAMES.items():
            e = study.get(q, {}).get("variables", {}).get(key)
            if e is not None:
                parts.append(f"the {name} by {e['low_to_high']:+.4f} {unit} ({100 * e['variance_share']:.0f} % of its "
                             f"variance over the box)")
        if parts:
            lines.append(f"- **{jet}** from the low to the high end of their range (the other jets at the recommended "
                         f"speed) change " + "; ".join(parts) + ".")
    return lines


def design_page(metrics: dict[str, Any], note: str) -> str:
    rec = metrics.get("recommended")
    md = [note, "", f"Run by `quenchsim validate` on this 2-core machine, shared: {metrics['trials']} cheap-fidelity "
          f"trials (element sizes x{metrics['fidelity']['mesh']:g}, step limits x{metrics['fidelity']['step']:g}) and "
          f"{metrics['full_chain_runs']} full-chain confirmation runs on 2 Dask workers in "
          f"{metrics['wall_time_min']:.1f} min (summed over {metrics['calls']} call(s) of validate; load average {metrics['load_average']['before_1min']:.1f} at the start, "
          f"{metrics['load_average']['after_15min']:.1f} over the last 15 min). Largest cheap-vs-full difference over "
          f"its tolerance: {metrics['fidelity']['max_diff_over_tolerance']:.2f} ({metrics['fidelity']['compared']} "
          "comparisons).", ""]
    if rec:
        md += ["### What each jet does", ""] + jet_sentences(metrics) + [""]
    md += ["## The study (`quenchsim optimise` output)", "", metrics["page_body"]]
    return "\n".join(md)


NOTE_B = ("The page reports the chain with issue 33's physics (hot austenite from published laws, the pearlite-calibrated "
          "SUJ3, the jet bath with Berenson's film collapse fixed); ring B hardens through over the whole box, so the "
          "hardness constraint does not bind.")


def run(workdir: Path) -> dict[str, Any]:
    return run_design(STUDY_FILE, Path(workdir), "ring_b")


def page(metrics: dict[str, Any]) -> str:
    return design_page(metrics, NOTE_B)
