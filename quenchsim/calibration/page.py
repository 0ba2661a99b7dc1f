"""The calibration as a Markdown page: the data, the posterior with identifiability, the discrepancy, each datum
against the posterior and the calibrated full chain, the fidelities' agreement, which data pull which inputs where,
the conflicting pairs, the predictions, the surrogate's error and the screening."""

from __future__ import annotations

from typing import Any

from quenchsim.calibration.spec import CalibrationSpec


def _g(x: Any, fmt: str = ".4g") -> str:
    return "-" if x is None else format(x, fmt)


def _short(path: str) -> str:
    """An input path without its kind and file (``material.SUJ3.mechanics.trip.K_1_Pa...`` -> ``trip.K_1_Pa...``)."""
    parts = path.split(".")
    keys = parts[2:]
    if keys and keys[0] == "mechanics":
        keys = keys[1:]
    return ".".join(k for k in keys if k != "per_phase")


def posterior_rows(result: dict[str, Any]) -> list[str]:
    """The posterior table (one row per input)."""
    rows = ["| input | prior (factor bounds) | data-file value -> calibrated | posterior factor median | 5-95 % | "
            "width / prior width | identifiability |", "|---|---|---|---|---|---|---|"]
    for r in result["posterior"]:
        lo, hi = r["prior_factor_bounds"]
        value = f"{_g(r.get('value'))} -> {_g(r.get('value_at_median'))}"
        rows.append(f"| `{r['input']}` | {r['prior']} ({lo:.3g}-{hi:.3g}) | {value} | {r['factor_median']:.3g} | "
                    f"{r['factor_5pct']:.3g}-{r['factor_95pct']:.3g} | {r['width_ratio']:.2f} | {r['identifiability']} |")
    return rows


def data_rows(result: dict[str, Any]) -> list[str]:
    rows = ["| datum | kind | observables | discrepancy group | source |", "|---|---|---|---|---|"]
    for d in result["data"]:
        rows.append(f"| {d['label']} | {d['kind']} | {len(d['observables'])} | {d['group'] or '-'} | {d['source']} |")
    return rows


def discrepancy_rows(result: dict[str, Any]) -> list[str]:
    if not result.get("discrepancy"):
        return ["No model-discrepancy term (the file declares no [discrepancy] groups): a datum the model cannot meet "
                "shows as a miss below and as an input at the edge of its prior."]
    reasons = {g["group"]: g["reason"] for g in result.get("discrepancy_priors", [])}
    rows = ["| group | prior: half-normal scale | posterior sd median | 5-95 % | median / prior median | why this prior |",
            "|---|---|---|---|---|---|"]
    for g in result["discrepancy"]:
        u = f" {g['unit']}" if g["unit"] else ""
        rows.append(f"| {g['group']} | {g['prior_scale']:.3g}{u} | {g['median']:.3g}{u} | {g['p5']:.3g}-{g['p95']:.3g} | "
                    f"{g['median_over_prior_median']:.2f} | {reasons.get(g['group'], '')} |")
    return rows


def check_rows(result: dict[str, Any]) -> list[str]:
    rows = ["| observable | measured | posterior, model alone: median (5-95 %) | z | full chain at the posterior "
            "median | met (2 sd) |", "|---|---|---|---|---|---|"]
    for row in result["predictive_check"]:
        full = result["calibrated_run"][row["quantity"]]
        met = "-" if full["met"] is None else ("yes" if full["met"] else "**no**")
        rows.append(f"| {row['quantity']} | {row['target']} | {row['posterior_median']:.4g} ({row['posterior_5pct']:.4g} "
                    f"to {row['posterior_95pct']:.4g}) | {row['z']:+.1f} | {_g(full['full_chain'])} | {met} |")
    return rows


def fidelity_rows(result: dict[str, Any]) -> list[str]:
    confirm = result["confirm"]
    if "confirm" not in confirm:
        return ["The nominal and calibrated points were run on the design's mesh only (no confirm_mesh)."]
    d, c = confirm["design"], confirm["confirm"]
    design = ", ".join(f"{label} x{case['mesh']:g}" for label, case in result.get("cases", {}).items()) or "the design's"
    rows = [f"Element sizes of the design ({design}) against x{c['mesh']:g} (full):", "",
            "| observable | nominal: design | nominal: full | calibrated: design | calibrated: full |",
            "|---|---|---|---|---|"]
    for label in result["calibrated_run"]:
        rows.append(f"| {label} | {_g(d['nominal'].get(label))} | {_g(c['nominal'].get(label))} | "
                    f"{_g(d['calibrated'].get(label))} | {_g(c['calibrated'].get(label))} |")
    return rows


def pull_rows(result: dict[str, Any]) -> list[str]:
    inputs = result["inputs"]
    rows = ["Each datum alone (no discrepancy): the posterior median factor of each input and, in brackets, its 90 % "
            "width over the prior's (below 0.5: that datum pins the input); the smallest misfit it reaches inside the "
            "priors (chi-square; met alone when <= 3.84 per observable).", "",
            "| datum | " + " | ".join(f"`{_short(p)}`" for p in inputs) + " | min misfit | met alone |",
            "|---|" + "---|" * len(inputs) + "---|---|"]
    for p in result["pulls"]:
        cells = [f"{x['factor_median']:.3g} ({x['width_ratio']:.2f})" for x in p["inputs"]]
        rows.append(f"| {p['datum']} | " + " | ".join(cells) + f" | {p['min_misfit']:.2f} | "
                    f"{'yes' if p['met_alone'] else '**no**'} |")
    return rows


def conflict_rows(result: dict[str, Any]) -> list[str]:
    pairs = result["conflicts"]
    rows = ["Parameter goodness-of-fit (Maltoni & Schwetz 2003): chi2_PG = min chi2(both) - min chi2(a) - min chi2(b) "
            "over the prior box; above 3.84 no input set meets the two together as well as each alone.", "",
            "| datum a | datum b | min chi2 a | min chi2 b | min chi2 both | chi2_PG | conflict |",
            "|---|---|---|---|---|---|---|"]
    for c in sorted(pairs, key=lambda c: -c["chi2_pg"]):
        rows.append(f"| {c['a']} | {c['b']} | {c['chi2_a']:.2f} | {c['chi2_b']:.2f} | {c['chi2_both']:.2f} | "
                    f"{c['chi2_pg']:.2f} | {'**yes**' if c['conflict'] else 'no'} |")
    return rows


def cosatisfaction_rows(result: dict[str, Any]) -> list[str]:
    """Which data the full-chain runs of the design meet together (no surrogate)."""
    c = result.get("full_chain_cosatisfaction")
    if not c:
        return []
    data = list(c["per_datum"])
    short = {lab: f"d{i + 1}" for i, lab in enumerate(data)}
    both = {(p["a"], p["b"]): p["runs_both"] for p in c["pairs"]}
    rows = [f"Of the design's {c['runs']} full-chain runs (no surrogate), how many meet each datum (every observable "
            f"within 2 sd), each pair together (below the diagonal), and all: **{c['all']}**; the most data one run "
            f"meets: {c['most']} of {len(data)}.", "",
            "| datum | runs meeting it | " + " | ".join(short[d] for d in data) + " |",
            "|---|---|" + "---|" * len(data)]
    for i, a in enumerate(data):
        cells = [str(both.get((b, a), both.get((a, b), ""))) if j < i else ("-" if j == i else "") for j, b in enumerate(data)]
        rows.append(f"| {short[a]}: {a} | {c['per_datum'][a]} | " + " | ".join(cells) + " |")
    rows += ["", "The runs that meet the most data:", "", "| data met | missed | input factors |", "|---|---|---|"]
    for r in c["best_runs"]:
        rows.append(f"| {r['met']} | {', '.join(short[m] for m in r['missed']) or '-'} | "
                    + ", ".join(f"{f:.3g}" for f in r["factors"]) + " |")
    rows += ["", "Input order: " + ", ".join(f"`{_short(p)}`" for p in c["inputs"]) + "."]
    return rows


def calibration_page(spec: CalibrationSpec, result: dict[str, Any]) -> str:
    runs = result["runs"]
    s = result["sampler"]
    md = [f"# Calibration {spec.name}", "", spec.description, "",
          f"{result['full_chain_runs']} full-chain runs ({runs['ran_now']} run now, {runs['cached']} from the cache, "
          f"{len(runs['failed'])} failed), wall time {result['wall_time_s']:.0f} s.", "", "## Data", "",
          *data_rows(result), "", "## Posterior", "", *posterior_rows(result), "",
          f"emcee: {s['walkers']} walkers x {s['steps']} steps (burn-in {s['burn']}), acceptance {s['acceptance']:.2f}, "
          f"autocorrelation {_g(s['autocorr_steps'], '.0f')} steps. Corner plot: corner.png.", "",
          "## Model discrepancy", "", *discrepancy_rows(result), "",
          "## Each datum: posterior prediction and full chain at the posterior median", "", *check_rows(result), "",
          "## Cheap against full fidelity", "", *fidelity_rows(result), "",
          "## Which data pull which inputs where", "", *pull_rows(result), "",
          "## Which data conflict", "", *conflict_rows(result), "",
          "## Which data the full chain meets together", "", *cosatisfaction_rows(result)]
    if result["predictions"]:
        md += ["", "## Predictions (surrogate over the posterior, with the discrepancy of their group)", "",
               "| quantity | median | 5-95 % |", "|---|---|---|"]
        md += [f"| {k} | {v['median']:.4g} | {v['p5']:.4g} to {v['p95']:.4g} |" for k, v in result["predictions"].items()]
    md += ["", "## Surrogate error on held-back runs", "", "| observable | runs | RMS error | max error | mean stated sd | inside its own 90 % band |",
           "|---|---|---|---|---|---|"]
    for k, h in result["surrogate"]["holdout"].items():
        md.append(f"| {k} | {h['n']} | {h['rms_error']:.3g} | {h['max_abs_error']:.3g} | {h['mean_stated_sd']:.3g} | "
                  f"{h['inside_own_90pct_band']:.2f} |")
    md += ["", "## Sensitivity (which input matters for which observable)", "",
           "Morris mu* on the full-chain runs (observable's unit over each input's whole prior range); Sobol first-order "
           "/ total indices on the surrogate.", "", "| observable | input | Morris mu* | Sobol S1 | Sobol ST |",
           "|---|---|---|---|---|"]
    for k, sc in result["screening"].items():
        for j, name in enumerate(sc["inputs"]):
            mu = sc["morris"]["mu_star"][j] if sc["morris"] else None
            md.append(f"| {k} | `{_short(name)}` | {_g(mu, '.3g')} | {sc['sobol_on_surrogate']['S1'][j]:.2f} | "
                      f"{sc['sobol_on_surrogate']['ST'][j]:.2f} |")
    md += ["", "Calibrated data files (new files, the priors untouched): "
           + ", ".join(f"`{v}`" for v in result["calibrated_files"].values()), ""]
    return "\n".join(md)
