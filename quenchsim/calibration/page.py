"""The calibration as a Markdown page: posterior table with identifiability, screening, surrogate error,
predictive check, predictions, calibrated run."""

from __future__ import annotations

from typing import Any

from quenchsim.calibration.spec import CalibrationSpec


def _g(x: Any, fmt: str = ".4g") -> str:
    return "-" if x is None else format(x, fmt)


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


def calibration_page(spec: CalibrationSpec, result: dict[str, Any]) -> str:
    runs = result["runs"]
    md = [f"# Calibration {spec.name}", "", spec.description, "",
          f"{result['full_chain_runs']} full-chain runs ({runs['ran_now']} run now, {runs['cached']} from the cache, "
          f"{len(runs['failed'])} failed), wall time {result['wall_time_s']:.0f} s.", "", "## Posterior", "",
          *posterior_rows(result), "",
          f"emcee: {result['sampler']['walkers']} walkers x {result['sampler']['steps']} steps (burn-in "
          f"{result['sampler']['burn']}), acceptance {result['sampler']['acceptance']:.2f}, autocorrelation "
          f"{_g(result['sampler']['autocorr_steps'], '.0f')} steps. Corner plot: corner.png.", "",
          "## Measurements: posterior prediction and full chain at the posterior median", "",
          "| measurement | measured +- sd | posterior median (5-95 %) | z | full chain, calibrated | reached |",
          "|---|---|---|---|---|---|"]
    for row in result["predictive_check"]:
        full = result["calibrated_run"][row["quantity"]]["full_chain"]
        md.append(f"| {row['quantity']} | {row['measured']:.4g} +- {row['uncertainty']:.3g} | {row['posterior_median']:.4g} "
                  f"({row['posterior_5pct']:.4g} to {row['posterior_95pct']:.4g}) | {row['z']:+.1f} | {_g(full)} | "
                  f"{'yes' if row['reached'] else '**no**: the priors cannot explain it'} |")
    if result["predictions"]:
        md += ["", "## Predictions (surrogate over the posterior)", "", "| quantity | median | 5-95 % |", "|---|---|---|"]
        md += [f"| {k} | {v['median']:.4g} | {v['p5']:.4g} to {v['p95']:.4g} |" for k, v in result["predictions"].items()]
    md += ["", "## Surrogate error on held-back runs", "",
           "| quantity | runs | RMS error | max error | mean stated sd | inside its own 90 % band |", "|---|---|---|---|---|---|"]
    for k, h in result["surrogate"]["holdout"].items():
        md.append(f"| {k} | {h['n']} | {h['rms_error']:.3g} | {h['max_abs_error']:.3g} | {h['mean_stated_sd']:.3g} | "
                  f"{h['inside_own_90pct_band']:.2f} |")
    md += ["", "## Sensitivity (which input matters for which measurement)", "",
           "Morris mu* on the full-chain runs (quantity's unit over each input's whole prior range); Sobol first-order / "
           "total indices on the surrogate.", "", "| measurement | input | Morris mu* | Sobol S1 | Sobol ST |",
           "|---|---|---|---|---|"]
    for k, s in result["screening"].items():
        for j, name in enumerate(s["inputs"]):
            mu = s["morris"]["mu_star"][j] if s["morris"] else None
            md.append(f"| {k} | `{name}` | {_g(mu, '.3g')} | {s['sobol_on_surrogate']['S1'][j]:.2f} | "
                      f"{s['sobol_on_surrogate']['ST'][j]:.2f} |")
    md += ["", "Calibrated data files (new files, the priors untouched): "
           + ", ".join(f"`{v}`" for v in result["calibrated_files"].values()), ""]
    return "\n".join(md)
