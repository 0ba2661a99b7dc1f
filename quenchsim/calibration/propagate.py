"""Prediction with bands: the posterior (or the declared priors) propagated through the full chain.

``propagate(case, out, n)`` runs the case ``n`` times with input factors drawn from a calibration's
``posterior.json`` (``posterior=DIR``: only the calibrated inputs vary) or, when nothing was calibrated, from
every prior declared in the data files the case reads (a Latin hypercube over their log-uniform priors), and
adds to ``out/summary.json`` an ``uncertainty`` block: the median and 5-95 % band of every number of the
summary over those runs. A posterior with model-discrepancy groups (:mod:`quenchsim.calibration.likelihood`) adds
to each draw of a number of a group's table (its key's first part, e.g. ``dimensions_mm``) a normal draw of that
draw's discrepancy standard deviation: the band is then a prediction of a measurement, not of the model alone.
The runs are cached in ``out/uncertainty/`` (a re-run only runs what is missing).
"""

from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.calibration.design import latin_hypercube
from quenchsim.calibration.inputs import KINDS, FreeInput, data_name, declared_priors, free_input, used_by
from quenchsim.calibration.runs import quantity, request, run_requests
from quenchsim.case import Case
from quenchsim.errors import InputError
from quenchsim.results import files
from quenchsim.sweep import flatten

log = logging.getLogger("quenchsim")

BAND_SKIP = ("solver.", "status", "end_state.time_s")
"""Summary entries that are bookkeeping, not results: no band."""
POSTERIOR_JSON = "posterior.json"


def _posterior_rows(folder: Path, n: int, seed: int) -> tuple[dict[str, Any], np.ndarray]:
    path = folder / POSTERIOR_JSON
    if not path.is_file():
        raise InputError("--posterior", str(folder), f"holds no {POSTERIOR_JSON} (the output folder of quenchsim calibrate)")
    data = json.loads(path.read_text())
    return data, np.random.default_rng(seed).choice(len(data["factors"]), size=n, replace=len(data["factors"]) < n)


def _posterior_draws(folder: Path, n: int, seed: int) -> tuple[list[FreeInput], np.ndarray, str]:
    data, rows = _posterior_rows(folder, n, seed)
    inputs = [free_input(p, "--posterior") for p in data["inputs"]]
    return inputs, np.asarray(data["factors"], dtype=float)[rows], f"posterior of the calibration in {folder}"


def discrepancy_draws(folder: Path, n: int, seed: int) -> list[dict[str, float]]:
    """Per draw (the same posterior rows as the inputs' for this ``n`` and ``seed``): each discrepancy group's
    standard deviation (empty for a calibration without discrepancy)."""
    data, rows = _posterior_rows(folder, n, seed)
    groups, sd = data.get("discrepancy_groups") or [], data.get("discrepancy_sd")
    if not groups or sd is None:
        return [{} for _ in range(n)]
    return [dict(zip(groups, sd[r])) for r in rows]


def _prior_draws(case: Case, n: int, seed: int) -> tuple[list[FreeInput], np.ndarray, str]:
    inputs: list[FreeInput] = []
    for kind in KINDS:
        name = data_name(kind, case)
        if isinstance(name, str):
            inputs += declared_priors(kind, name)
    u = latin_hypercube(len(inputs), n, seed)
    factors = np.column_stack([inp.factor(u[:, j]) for j, inp in enumerate(inputs)]) if inputs else np.empty((n, 0))
    return inputs, factors, "priors declared in the data files the case reads"


def uncertain_inputs(case: Case, n: int, posterior: str | Path | None = None,
                     seed: int = 0) -> tuple[list[FreeInput], np.ndarray, str]:
    """The inputs the case reads, ``n`` draws of their factors (n, d) and where they come from; checks the request
    (n >= 2, a calibration folder, inputs the case reads) before anything runs."""
    if isinstance(n, bool) or not isinstance(n, int) or n < 2:
        raise InputError("--uncertainty", n, "must be an integer >= 2 (runs drawn from the posterior or the priors)")
    if posterior is not None:
        inputs, factors, source = _posterior_draws(Path(posterior), n, seed)
    else:
        inputs, factors, source = _prior_draws(case, n, seed)
    used = [j for j, inp in enumerate(inputs) if used_by(inp, case)]
    if not used:
        raise InputError("--uncertainty", n, f"the case reads none of the uncertain inputs ({source})")
    return [inputs[j] for j in used], factors[:, used], source


BAND_TABLE_KEYS = ("dimensions_mm.change.", "hardness.depth_mm.", "hardness.core_HRC", "residual_stress_MPa.hoop.")
"""The quantities `quenchsim run --uncertainty` prints (every one is in summary.json)."""


def band_table(block: dict[str, Any]) -> str:
    """The key bands as plain text."""
    rows = [f"uncertainty: {block['runs_ok']} of {block['runs']} runs from the {block['source']}; median (5-95 %)"]
    for key, b in block["quantities"].items():
        if key.startswith(BAND_TABLE_KEYS):
            rows.append(f"  {key:<44}{b['median']:>11.4g}  ({b['p5']:.4g} to {b['p95']:.4g})")
    return "\n".join(rows)


def bands(summaries: list[dict[str, Any]], discrepancy: list[dict[str, float]] | None = None,
          seed: int = 0) -> dict[str, dict[str, float]]:
    """Median and 5-95 % of every number of the summaries (over those that hold it); with ``discrepancy`` (per
    summary, a group's standard deviation by the group's name) each number of a group's table gets a normal draw of
    it added."""
    rng = np.random.default_rng(seed)
    values: dict[str, list[float]] = {}
    for i, s in enumerate(summaries):
        groups = discrepancy[i] if discrepancy else {}
        for key, v in flatten(s):
            if isinstance(v, (int, float)) and not isinstance(v, bool) and not key.startswith(BAND_SKIP):
                sd = groups.get(key.split(".")[0], 0.0)
                values.setdefault(key, []).append(float(v) + (sd * float(rng.standard_normal()) if sd else 0.0))
    out = {}
    for key, vs in values.items():
        p5, p50, p95 = np.quantile(vs, [0.05, 0.5, 0.95])
        out[key] = {"median": float(p50), "p5": float(p5), "p95": float(p95)}
    return out


def propagate(case: Case, out: str | Path, n: int, posterior: str | Path | None = None, workers: int = 2,
              progress: bool = True, seed: int = 0, keep: tuple[str, ...] = ()) -> dict[str, Any]:
    """Run ``n`` draws of the case's uncertain inputs and return (and add to ``out/summary.json``, when the
    nominal run is there) the ``uncertainty`` block. ``keep``: quantities whose value in every draw is returned
    too (``samples``, in draw order: the same ``seed`` and ``n`` draw the same inputs for every case, so two
    cases' samples pair up)."""
    out = Path(out)
    inputs, factors, source = uncertain_inputs(case, n, posterior, seed)
    reqs = [request(case, inputs, row) for row in factors]
    done = run_requests(reqs, out / "uncertainty", workers=workers, progress=progress, desc="uncertainty")
    per_draw = [done.summaries.get(r.folder_name()) for r in reqs]
    ok = [s for s in per_draw if s is not None]
    groups = discrepancy_draws(Path(posterior), n, seed) if posterior is not None else [{} for _ in per_draw]
    ok_groups = [g for s, g in zip(per_draw, groups) if s is not None]
    block = {"source": source, "runs": n, "runs_ok": len(ok), "failed": len(done.failed),
             "failures": done.failed, "inputs": [inp.path for inp in inputs], "band": "5-95 %",
             "discrepancy": sorted({k for g in groups for k in g}), "quantities": bands(ok, ok_groups, seed)}
    if done.failed:   # a failed draw narrows the band: say which and why (the folders keep what they wrote)
        name, error = next(iter(done.failed.items()))
        log.warning("%d of %d uncertainty runs failed (summary.json 'uncertainty.failures'); %s: %s",
                    len(done.failed), n, name, error)
    summary_path = out / files.SUMMARY_JSON
    if summary_path.is_file():
        summary = json.loads(summary_path.read_text())
        summary["uncertainty"] = block
        tmp = summary_path.with_name(summary_path.name + ".tmp")
        tmp.write_text(json.dumps(summary, indent=2))
        tmp.replace(summary_path)
    if keep:
        block["samples"] = {q: [quantity(s, q) for s in per_draw] for q in keep}
    return block
