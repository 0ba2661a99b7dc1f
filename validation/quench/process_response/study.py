"""What each jet does, and why: for each reference ring, the ID and the OD jet speed moved one at a time over the
report's range from the ring's base condition (ring A condition 1, ring B condition 4), full chain, every summary
quantity (hardness depths, core HRC, ID / OD / width change, shape, hoop stress) and the distortion budget of each
run, so a reader sees what each knob does and through which part of the budget (free strain, thermal plasticity,
transformation plasticity). The report's conditions themselves are the ring pages' runs (shared cache).

The same runs again with the inputs calibrated on every measurement of ring A (calibration/ring_a: every input at its
posterior median, the two-ID-row layout), beside the nominal ones: what each jet does to the calibrated model."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.case import load_case
from quenchsim.results import load as load_run
from quenchsim.validation import ROOT, cached_run, study_module

TITLE = "Process response: what each jet speed does to hardness, size, shape and stress of rings A and B, and why"
SLOW = True
CASE_A = ROOT / "cases" / "crb_outer_ring.toml"
CASE_B = ROOT / "cases" / "srb_outer_ring.toml"
ID_KEY, OD_KEY = "quench.bath.id_jet_speed_mm_s", "quench.bath.od_jet_speed_mm_s"

# ring -> (case, base condition, base ID/OD mm/s, ID values, OD values): the report's range of each jet
# (ring A: Table 1, conditions 1-3; ring B: Table 4, conditions 4-6), the other jet at the base value
RINGS = {
    "A": (CASE_A, "1", (1000.0, 5340.0), (400.0, 1000.0, 2000.0), (1780.0, 5340.0, 10680.0)),
    "B": (CASE_B, "4", (540.0, 3280.0), (540.0, 1440.0), (1470.0, 3280.0)),
}
QUANTITIES = (
    ("HRC58 depth bore / raceway (mm)", lambda s: s["hardness"]["depth_mm"]["HRC58_bore_mid"], "{:.1f}"),
    ("HRC58 depth OD (mm)", lambda s: s["hardness"]["depth_mm"]["HRC58_od_mid"], "{:.1f}"),
    ("core HRC", lambda s: s["hardness"]["core_HRC"], "{:.1f}"),
    ("ID / raceway change (mm)", lambda s: s["dimensions_mm"]["change"]["id"], "{:+.3f}"),
    ("OD change (mm)", lambda s: s["dimensions_mm"]["change"]["od"], "{:+.3f}"),
    ("width change (mm)", lambda s: s["dimensions_mm"]["change"]["width"], "{:+.3f}"),
    ("bore crown change (mm)", lambda s: s["shape_mm"]["change"]["bore_crown"], "{:+.3f}"),
    ("bore taper change (mm)", lambda s: s["shape_mm"]["change"]["bore_taper"], "{:+.3f}"),
    ("hoop stress bore surface (MPa)", lambda s: s["residual_stress_MPa"]["hoop"]["bore_surface_mid"], "{:.0f}"),
    ("hoop stress OD surface (MPa)", lambda s: s["residual_stress_MPa"]["hoop"]["od_surface_mid"], "{:.0f}"),
)
BUDGET_PARTS = ("free_strain", "thermal_plasticity", "transformation_plasticity")


def _points(ring: str) -> list[tuple[str, float, float]]:
    """(label, ID, OD) of every run of a ring: the base, then each jet over its range with the other at base."""
    _, _, (id0, od0), ids, ods = RINGS[ring]
    pts = [("base", id0, od0)]
    pts += [(f"ID {v:g}", v, od0) for v in ids if v != id0]
    pts += [(f"OD {v:g}", id0, v) for v in ods if v != od0]
    return pts


def _summary(ring: str, label: str, id_mm_s: float, od_mm_s: float, workdir: Path,
             calibrated: dict[str, str] | None = None) -> dict[str, Any]:
    """The run of one point (``calibrated``: the overrides of the calibrated data files, else nominal inputs)."""
    case_path, cond, *_ = RINGS[ring]
    case = load_case(case_path, cond, {ID_KEY: id_mm_s, OD_KEY: od_mm_s, **(calibrated or {})})
    tag = f"{case_path.stem}_{cond}" if label == "base" else f"{case_path.stem}_id{id_mm_s:g}_od{od_mm_s:g}"
    folder = study_module("quench/ring_a").run_dirs(workdir) / (f"calibrated_{tag}" if calibrated else tag)
    return load_run(cached_run(case, folder)).summary


def _row(s: dict[str, Any]) -> dict[str, Any]:
    row = {name: float(get(s)) for name, get, _ in QUANTITIES}
    parts = s["distortion_budget_mm"]["parts"]
    row["budget"] = {p: {k: float(parts[p][k]) for k in ("id", "od", "width")} for p in BUDGET_PARTS}
    return row


def run(workdir: Path) -> dict[str, Any]:
    workdir = Path(workdir)
    metrics = _responses(workdir, None)
    calibrated = study_module("calibration/ring_a").calibrated_overrides(workdir)
    metrics["calibrated"] = _responses(workdir, calibrated)
    metrics["calibrated"]["overrides"] = {k: Path(v).name for k, v in calibrated.items()}
    return metrics


def _responses(workdir: Path, calibrated: dict[str, str] | None) -> dict[str, Any]:
    """Every ring's runs, each jet's effect and the report's trends, nominal or with the calibrated data files."""
    metrics: dict[str, Any] = {"rings": {}}
    for ring in RINGS:
        runs = {label: {"id_mm_s": i, "od_mm_s": o, **_row(_summary(ring, label, i, o, workdir, calibrated))}
                for label, i, o in _points(ring)}
        metrics["rings"][ring] = runs
        effects: dict[str, dict[str, float]] = {}
        for jet, key in (("ID", "id_mm_s"), ("OD", "od_mm_s")):
            rows = [r for lab, r in runs.items() if lab == "base" or lab.startswith(jet)]
            lo, hi = min(rows, key=lambda r: r[key]), max(rows, key=lambda r: r[key])
            effects[jet] = {name: hi[name] - lo[name] for name, _, _ in QUANTITIES}
            effects[jet]["range_mm_s"] = [lo[key], hi[key]]
            effects[jet]["budget_id"] = {p: hi["budget"][p]["id"] - lo["budget"][p]["id"] for p in BUDGET_PARTS}
            effects[jet]["budget_od"] = {p: hi["budget"][p]["od"] - lo["budget"][p]["od"] for p in BUDGET_PARTS}
        metrics[f"effects_{ring}"] = effects
        _plot(ring, runs, workdir / f"process_response_{ring}{'_calibrated' if calibrated else ''}.png")
    a = metrics["rings"]["A"]
    # the report's trends for ring A, one jet at a time (the report moved both together: ring_a's page)
    metrics["A_od_fast_minus_slow_depth_od_mm"] = a["OD 10680"]["HRC58 depth OD (mm)"] - a["OD 1780"]["HRC58 depth OD (mm)"]
    metrics["A_id_fast_minus_slow_depth_bore_mm"] = (a["ID 2000"]["HRC58 depth bore / raceway (mm)"]
                                                     - a["ID 400"]["HRC58 depth bore / raceway (mm)"])
    b = metrics["rings"]["B"]
    metrics["B_od_jet_raceway_effect_mm"] = abs(b["base"]["ID / raceway change (mm)"] - b["OD 1470"]["ID / raceway change (mm)"])
    metrics["B_id_jet_raceway_effect_mm"] = abs(b["base"]["ID / raceway change (mm)"] - b["ID 1440"]["ID / raceway change (mm)"])
    return metrics


def _plot(ring: str, runs: dict[str, Any], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [q[0] for q in QUANTITIES[:8]]
    fig, axes = plt.subplots(2, 4, figsize=(15, 6.5))
    for ax, name in zip(axes.flat, names):
        for jet, key, colour in (("ID", "id_mm_s", "tab:blue"), ("OD", "od_mm_s", "tab:red")):
            rows = sorted((r for lab, r in runs.items() if lab == "base" or lab.startswith(jet)), key=lambda r: r[key])
            ax.plot([r[key] / 1000.0 for r in rows], [r[name] for r in rows], "o-", color=colour, label=f"{jet} jets")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("jet speed (m/s)", fontsize=8)
        ax.grid(lw=0.3)
    axes.flat[0].legend(fontsize=8)
    fig.suptitle(f"ring {ring}: one jet at a time from the base condition (the other jet at its base speed)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _tables(variant: dict[str, Any], ring: str, png: str) -> list[str]:
    """One variant's runs, budgets and jet effects of a ring."""
    runs = variant["rings"][ring]
    labels = list(runs)
    md = ["| quantity | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    for name, _, fmt in QUANTITIES:
        md.append(f"| {name} | " + " | ".join(fmt.format(runs[lab][name]) for lab in labels) + " |")
    md += ["", "Distortion budget of the ID / raceway change (mm): how each run's change splits into the free strain "
           "of the final phases, thermal plasticity and transformation plasticity (summary.json distortion_budget_mm).",
           "", "| part | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    for p in BUDGET_PARTS:
        md.append(f"| {p.replace('_', ' ')} | " + " | ".join(f"{runs[lab]['budget'][p]['id']:+.3f}" for lab in labels) + " |")
    md += ["", "| part (OD) | " + " | ".join(labels) + " |", "|---|" + "---|" * len(labels)]
    for p in BUDGET_PARTS:
        md.append(f"| {p.replace('_', ' ')} | " + " | ".join(f"{runs[lab]['budget'][p]['od']:+.3f}" for lab in labels) + " |")
    return md + ["", f"![ring {ring} response]({png})", ""]


def _effects(metrics: dict[str, Any], ring: str) -> list[str]:
    """What each jet does over its range, nominal and calibrated side by side."""
    nom, cal = metrics[f"effects_{ring}"], metrics["calibrated"][f"effects_{ring}"]
    ids, ods = ("-".join(f"{v:g}" for v in nom[j]["range_mm_s"]) for j in ("ID", "OD"))
    md = ["What each jet does over its range (slow -> fast, the other jet at base), with the nominal and with the "
          "calibrated inputs:", "",
          f"| quantity | ID jets {ids} mm/s, nominal | calibrated | OD jets {ods} mm/s, nominal | calibrated |",
          "|---|---|---|---|---|"]
    for name, _, fmt in QUANTITIES:
        md.append(f"| {name} | {fmt.format(nom['ID'][name])} | {fmt.format(cal['ID'][name])} | "
                  f"{fmt.format(nom['OD'][name])} | {fmt.format(cal['OD'][name])} |")
    for dim in ("id", "od"):
        parts = ", ".join(p.replace("_", " ") for p in BUDGET_PARTS)
        cells = [" / ".join(f"{e[jet][f'budget_{dim}'][p]:+.3f}" for p in BUDGET_PARTS)
                 for jet in ("ID", "OD") for e in (nom, cal)]
        md.append(f"| {dim.upper()} change through: {parts} | " + " | ".join(cells) + " |")
    return md + [""]


def page(metrics: dict[str, Any]) -> str:
    cal = metrics["calibrated"]
    md = ["Each ring starts from its base condition of the report (ring A condition 1: ID 1000 / OD 5340 mm/s; ring B "
          "condition 4: ID 540 / OD 3280 mm/s) and one jet is moved over the report's range with the other held. "
          "Full chain (thermal, metallurgy, stress), default mesh and steps, twice: with the nominal inputs, and with "
          "the inputs calibrated on every measurement of ring A together (reports/calibration_ring_a.md: every "
          "calibrated input at its posterior median, from the data files "
          + ", ".join(f"`{v}`" for v in cal["overrides"].values()) + ", the two-ID-row layout among them).", ""]
    for ring in metrics["rings"]:
        md += [f"## Ring {ring}", "", *_effects(metrics, ring), "### Nominal inputs", "",
               *_tables(metrics, ring, f"process_response_{ring}.png"), "### Calibrated inputs", "",
               *_tables(cal, ring, f"process_response_{ring}_calibrated.png")]
    return "\n".join(md)
