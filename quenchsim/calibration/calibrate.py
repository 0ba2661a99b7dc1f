"""`quenchsim calibrate`: design of full-chain runs -> screening -> surrogate -> posterior -> calibrated files.

``calibrate(spec, out)`` writes into ``out``:

=========================  ==========================================================================
``runs/``                  every full-chain run, one folder per run named by a hash of its inputs (cache)
``design.json``            the points (unit cube and factors), their role and the measured quantities
``calibration.json``       screening (Morris on the runs, Sobol on the surrogate), the surrogate's held-back
                           error, the posterior table with each input's identifiability, the posterior
                           predictive check, the predictions with bands, the calibrated run, wall time
``posterior.json``         the inputs and posterior samples (what ``quenchsim run --uncertainty`` propagates)
``calibration.md``         the same as a page
``corner.png``             the corner plot
``calibrated/NAME.toml``   the data files at the posterior median (new files; the priors are untouched)
=========================  ==========================================================================

A call with ``max_runs`` stops after that many new runs (status ``incomplete``); the same call again runs
only what is missing.
"""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.calibration.design import latin_hypercube, morris_indices, morris_points, sobol_indices
from quenchsim.calibration.inputs import derived_files
from quenchsim.calibration.posterior import Posterior, posterior_table, predictive_check, sample_posterior
from quenchsim.calibration.runs import RunRequest, quantity, request, run_requests
from quenchsim.calibration.spec import CalibrationSpec
from quenchsim.calibration.surrogate import Surrogate, fit_surrogate, holdout_check
from quenchsim.errors import InputError

POSTERIOR_SAMPLES_KEPT = 2000
"""Posterior samples written to posterior.json (thinned evenly from the chain)."""


@dataclass
class Design:
    """The design's points by role (unit cube) and each target quantity's values there (NaN: run failed)."""

    points: dict[str, np.ndarray]
    values: dict[str, dict[str, np.ndarray]]
    runs: int
    ran: int
    cached: int
    failed: dict[str, str] = field(default_factory=dict)
    pending: list[str] = field(default_factory=list)
    run_wall_s: float = 0.0

    def training(self, labels: Sequence[str]) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """Nominal + screening + training points whose runs finished, and the values there."""
        return self._usable(("nominal", "screening", "training"), labels)

    def holdout(self, labels: Sequence[str]) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        return self._usable(("holdout",), labels)

    def _usable(self, roles: Sequence[str], labels: Sequence[str]) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        u = np.vstack([self.points[r] for r in roles])
        y = {k: np.concatenate([self.values[r][k] for r in roles]) for k in labels}
        ok = np.all(np.isfinite(np.column_stack(list(y.values()))), axis=1)
        return u[ok], {k: v[ok] for k, v in y.items()}


def design_points(spec: CalibrationSpec) -> dict[str, np.ndarray]:
    """The unit-cube points of each role (a pure function of the spec: a resumed design asks for the same)."""
    d, opts = len(spec.inputs), spec.design
    return {"nominal": np.array([[inp.unit(1.0) for inp in spec.inputs]]),
            "screening": morris_points(d, opts["screening_trajectories"], opts["seed"]),
            "training": latin_hypercube(d, opts["training_runs"], opts["seed"]),
            "holdout": latin_hypercube(d, opts["holdout_runs"], opts["seed"] + 1)}


def target_labels(spec: CalibrationSpec) -> list[str]:
    return [t.label for t in (*spec.measurements, *spec.predictions)]


def run_design(spec: CalibrationSpec, out: Path, workers: int = 2, progress: bool = True,
               max_runs: int | None = None) -> Design:
    """Every run of the design (cached in ``out/runs``) and the target quantities of each point."""
    points = design_points(spec)
    cases = {key: spec.cases[key[0]].load(key[1]) for key in spec.runs()}
    requests: dict[tuple[str, int, tuple[str, str | None]], RunRequest] = {}
    for role, block in points.items():
        for i, u in enumerate(block):
            factors = [inp.factor(x) for inp, x in zip(spec.inputs, u)]
            for key, case in cases.items():
                requests[(role, i, key)] = request(case, spec.inputs, factors)
    t0 = time.perf_counter()
    outcome = run_requests(list(requests.values()), out / "runs", workers=workers, progress=progress,
                           max_runs=max_runs, desc=f"calibrate {spec.name}")
    values: dict[str, dict[str, np.ndarray]] = {}
    for role, block in points.items():
        values[role] = {}
        for target in (*spec.measurements, *spec.predictions):
            column = []
            for i in range(len(block)):
                summary = outcome.summaries.get(requests[(role, i, (target.case, target.condition))].folder_name())
                value = quantity(summary, target.quantity)
                if summary is not None and value is None:
                    raise InputError("quantity", target.quantity,
                                     f"is not a number of summary.json in the runs of case {target.case!r}")
                column.append(np.nan if value is None else value)
            values[role][target.label] = np.array(column)
    return Design(points=points, values=values, runs=len({r.folder_name() for r in requests.values()}),
                  ran=outcome.ran, cached=outcome.cached, failed=outcome.failed, pending=outcome.pending,
                  run_wall_s=time.perf_counter() - t0)


def fit_design(spec: CalibrationSpec, design: Design) -> tuple[Surrogate, dict[str, dict[str, float]]]:
    """The surrogate on the training runs and its error on the held-back runs."""
    labels = target_labels(spec)
    u, y = design.training(labels)
    if len(u) < len(spec.inputs) + 2:
        raise InputError("design", len(u), f"too few finished runs to train a surrogate of {len(spec.inputs)} inputs")
    surrogate = fit_surrogate(u, y, seed=spec.design["seed"])
    u_h, y_h = design.holdout(labels)
    return surrogate, holdout_check(surrogate, u_h, y_h) if len(u_h) else {}


def observations(spec: CalibrationSpec) -> tuple[np.ndarray, np.ndarray]:
    return (np.array([m.value for m in spec.measurements]), np.array([m.uncertainty for m in spec.measurements]))


def measurement_surrogate(spec: CalibrationSpec, surrogate: Surrogate) -> Surrogate:
    """The surrogate restricted to the measured quantities (the likelihood's)."""
    return Surrogate(models={m.label: surrogate.models[m.label] for m in spec.measurements}, n_train=surrogate.n_train)


def infer(spec: CalibrationSpec, surrogate: Surrogate, observed: np.ndarray | None = None, seed: int | None = None,
          steps: int | None = None) -> Posterior:
    """The posterior of the inputs given the measurements (or ``observed`` values in their place)."""
    obs, sigma = observations(spec)
    opts = spec.sampler
    return sample_posterior(measurement_surrogate(spec, surrogate), obs if observed is None else observed, sigma,
                            len(spec.inputs), walkers=opts["walkers"], steps=steps or opts["steps"],
                            burn=min(opts["burn"], (steps or opts["steps"]) // 2),
                            seed=spec.design["seed"] if seed is None else seed)


def prediction_bands(spec: CalibrationSpec, surrogate: Surrogate, posterior: Posterior,
                     seed: int = 0) -> dict[str, dict[str, float]]:
    """Median and 5-95 % of each prediction over the posterior, the surrogate's own error included."""
    rng = np.random.default_rng(seed)
    out = {}
    for p in spec.predictions:
        model = surrogate.models[p.label]
        mean, sd = model.predict(posterior.u, return_std=True)
        draws = mean + sd * rng.standard_normal(len(mean))
        p5, p50, p95 = np.quantile(draws, [0.05, 0.5, 0.95])
        out[p.label] = {"median": float(p50), "p5": float(p5), "p95": float(p95)}
    return out


def _screening(spec: CalibrationSpec, design: Design, surrogate: Surrogate) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for m in spec.measurements:
        morris = morris_indices(design.points["screening"], design.values["screening"][m.label])
        model = surrogate.models[m.label]
        sobol = sobol_indices(lambda u: model.predict(u), len(spec.inputs), spec.design["seed"])
        out[m.label] = {"inputs": [inp.path for inp in spec.inputs], "morris": morris, "sobol_on_surrogate": sobol}
    return out


def calibrate(spec: CalibrationSpec, out: str | Path, workers: int = 2, progress: bool = True,
              max_runs: int | None = None) -> dict[str, Any]:
    """Run the whole calibration into ``out`` (see the module docstring) and return calibration.json's table."""
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    design = run_design(spec, out, workers=workers, progress=progress, max_runs=max_runs)
    _write_design(spec, design, out / "design.json")
    result: dict[str, Any] = {"name": spec.name, "runs": {"total": design.runs, "ran_now": design.ran,
                                                          "cached": design.cached, "failed": design.failed,
                                                          "pending": len(design.pending)}}
    if design.pending:
        result["status"] = "incomplete"
        _write_json(out / "calibration.json", result)
        return result
    surrogate, holdout = fit_design(spec, design)
    posterior = infer(spec, surrogate)
    factors = posterior.factors(spec.inputs)
    table = posterior_table(posterior, spec.inputs)
    obs, sigma = observations(spec)
    check = predictive_check(measurement_surrogate(spec, surrogate), posterior, [m.label for m in spec.measurements],
                             obs, sigma)
    medians = [row["factor_median"] for row in table]
    calibrated = derived_files(list(spec.inputs), medians, out / "calibrated",
                               note=f"calibrated by quenchsim calibrate ({spec.name}, posterior median)")
    calibrated_run = _calibrated_run(spec, medians, out, progress)
    from quenchsim.calibration.plots import corner_plot

    corner_plot(factors, spec.inputs, out / "corner.png")
    keep = posterior.u[np.linspace(0, len(posterior.u) - 1, min(POSTERIOR_SAMPLES_KEPT, len(posterior.u))).astype(int)]
    _write_json(out / "posterior.json", {"name": spec.name, "inputs": [inp.path for inp in spec.inputs],
                                         "factor_bounds": [list(inp.factor_bounds) for inp in spec.inputs],
                                         "u": keep.tolist(),
                                         "factors": [[inp.factor(x) for inp, x in zip(spec.inputs, row)] for row in keep]})
    result.update({
        "status": "ok", "inputs": [inp.path for inp in spec.inputs],
        "screening": _screening(spec, design, surrogate),
        "surrogate": {"training_runs": surrogate.n_train, "holdout": holdout},
        "posterior": table, "sampler": {"acceptance": posterior.acceptance, "autocorr_steps": posterior.autocorr_steps,
                                        "samples": len(posterior.u), **spec.sampler},
        "predictive_check": check, "predictions": prediction_bands(spec, surrogate, posterior),
        "calibrated_files": calibrated, "calibrated_run": calibrated_run,
        "wall_time_s": time.perf_counter() - t0, "run_wall_time_s": design.run_wall_s,
        "full_chain_runs": design.runs + len(calibrated_run)})
    _write_json(out / "calibration.json", result)
    from quenchsim.calibration.page import calibration_page

    (out / "calibration.md").write_text(calibration_page(spec, result))
    return result


def _calibrated_run(spec: CalibrationSpec, factors: Sequence[float], out: Path,
                    progress: bool) -> dict[str, dict[str, float | None]]:
    """The full chain at the posterior median for every measured case: the surrogate's answer checked."""
    keys = list(dict.fromkeys((m.case, m.condition) for m in spec.measurements))
    reqs = {key: request(spec.cases[key[0]].load(key[1]), spec.inputs, factors) for key in keys}
    done = run_requests(list(reqs.values()), out / "runs", workers=0, progress=progress,
                        desc="calibrated run")
    return {m.label: {"full_chain": quantity(done.summaries.get(reqs[(m.case, m.condition)].folder_name()), m.quantity),
                      "measured": m.value, "uncertainty": m.uncertainty} for m in spec.measurements}


def _write_design(spec: CalibrationSpec, design: Design, path: Path) -> None:
    rows = []
    for role, block in design.points.items():
        for i, u in enumerate(block):
            rows.append({"role": role, "u": u.tolist(), "factors": [inp.factor(x) for inp, x in zip(spec.inputs, u)],
                         **{k: (None if not np.isfinite(v[i]) else float(v[i])) for k, v in design.values[role].items()}})
    _write_json(path, {"inputs": [inp.path for inp in spec.inputs], "points": rows})


def _write_json(path: Path, data: Any) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=2, default=float))
    tmp.replace(path)
