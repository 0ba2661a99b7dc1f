"""`quenchsim calibrate`: design of full-chain runs -> screening -> surrogate -> posterior -> calibrated files.

``calibrate(spec, out)`` writes into ``out``:

=========================  ==========================================================================
``runs/``                  every full-chain run, one folder per run named by a hash of its inputs (cache)
``design.json``            the points (unit cube and factors), their role and every observable's value there
``calibration.json``       screening (Morris on the runs, Sobol on the surrogate), the surrogate's held-back
                           error, the posterior table with each input's identifiability, the discrepancy's size
                           per group, the posterior predictive check of every datum, which data pull which
                           inputs where and which pairs conflict, the predictions with bands, the nominal and
                           calibrated runs (and the cheap fidelity against the full one), wall time
``posterior.json``         the inputs and posterior samples (what ``quenchsim run --uncertainty`` propagates),
                           with the discrepancy groups' sizes
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

from quenchsim.calibration.conflicts import conflicts, cosatisfaction, meets, pulls
from quenchsim.calibration.data import Observable, Term, default_group, read_term
from quenchsim.calibration.design import (latin_hypercube, morris_indices, morris_points, sobol_indices,
                                          spread_subset)
from quenchsim.calibration.inputs import derived_files
from quenchsim.calibration.likelihood import Likelihood
from quenchsim.calibration.posterior import (Posterior, discrepancy_table, posterior_table, predictive_check,
                                             sample_posterior)
from quenchsim.calibration.runs import RunRequest, request, run_requests
from quenchsim.calibration.spec import CalibrationSpec
from quenchsim.calibration.surrogate import Surrogate, fit_surrogate, holdout_check
from quenchsim.errors import InputError

POSTERIOR_SAMPLES_KEPT = 2000
"""Posterior samples written to posterior.json (thinned evenly from the chain)."""
REFINE = "refine"
"""The role prefix of the refinement waves' points (``refine1``, ``refine2``, ...)."""


@dataclass
class Design:
    """The design's points by role (unit cube) and each observable's values there (NaN: run failed)."""

    points: dict[str, np.ndarray]
    values: dict[str, dict[str, np.ndarray]]
    runs: int
    ran: int
    cached: int
    failed: dict[str, str] = field(default_factory=dict)
    pending: list[str] = field(default_factory=list)
    run_wall_s: float = 0.0

    def training(self, labels: Sequence[str]) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """Nominal + screening + training (+ refinement) points whose runs finished, and the values there."""
        return self._usable(("nominal", "screening", "training", *self.waves), labels)

    @property
    def waves(self) -> list[str]:
        """The refinement waves' roles, in order."""
        return sorted((r for r in self.points if r.startswith(REFINE)), key=lambda r: int(r[len(REFINE):]))

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


def all_observables(spec: CalibrationSpec) -> tuple[Observable, ...]:
    return (*spec.observables, *spec.predicted)


def target_labels(spec: CalibrationSpec) -> list[str]:
    return [o.label for o in all_observables(spec)]


def _values(spec: CalibrationSpec, read_run: Any) -> dict[str, float | None]:
    """Every observable's value at one design point; ``read_run(case, condition)`` gives (summary, folder)."""
    out: dict[str, float | None] = {}
    for o in all_observables(spec):
        def read(t: Term) -> float | None:
            summary, folder = read_run(t.case, t.condition)
            return read_term(summary, folder, t.path)
        out[o.label] = o.model_value(read)
    return out


def run_points(spec: CalibrationSpec, points: dict[str, np.ndarray], runs_dir: Path, workers: int = 2,
               progress: bool = True, max_runs: int | None = None, mesh: float | None = None,
               desc: str = "runs") -> tuple[dict[str, list[dict[str, float | None]]], Any, int]:
    """Run the full chain at the unit-cube ``points`` of each role for every (case, condition) the observables need
    (element sizes x ``mesh``, default each case's design mesh) and return each point's observable values, the
    runs' outcome and the number of distinct runs."""
    cases = {key: spec.cases[key[0]].load(key[1], mesh=mesh) for key in spec.runs()}
    requests: dict[tuple[str, int, tuple[str, str | None]], RunRequest] = {}
    for role, block in points.items():
        for i, u in enumerate(block):
            factors = [inp.factor(x) for inp, x in zip(spec.inputs, u)]
            for key, case in cases.items():
                requests[(role, i, key)] = request(case, spec.inputs, factors)
    outcome = run_requests(list(requests.values()), runs_dir, workers=workers, progress=progress,
                           max_runs=max_runs, desc=desc)
    values: dict[str, list[dict[str, float | None]]] = {}
    for role, block in points.items():
        values[role] = []
        for i in range(len(block)):
            def read_run(case: str, condition: str | None, role: str = role, i: int = i) -> tuple[Any, Path]:
                name = requests[(role, i, (case, condition))].folder_name()
                return outcome.summaries.get(name), runs_dir / name
            values[role].append(_values(spec, read_run))
    return values, outcome, len({r.folder_name() for r in requests.values()})


def run_design(spec: CalibrationSpec, out: Path, workers: int = 2, progress: bool = True,
               max_runs: int | None = None, waves: dict[str, np.ndarray] | None = None) -> Design:
    """Every run of the design (cached in ``out/runs``) and the observables' values at each point; ``waves``: the
    refinement waves' points by role, run with the rest."""
    points = {**design_points(spec), **(waves or {})}
    t0 = time.perf_counter()
    per_point, outcome, n_runs = run_points(spec, points, out / "runs", workers, progress, max_runs,
                                            desc=f"calibrate {spec.name}")
    values = {role: {label: np.array([np.nan if row[label] is None else row[label] for row in rows])
                     for label in target_labels(spec)} for role, rows in per_point.items()}
    if any(s is not None for s in outcome.summaries.values()):
        for label in target_labels(spec):
            if not any(np.any(np.isfinite(v[label])) for v in values.values()):
                raise InputError("quantity", label, "is not a number in any finished run of the design (a summary.json "
                                                    "path the runs do not write, or a temperature no run reaches)")
    return Design(points=points, values=values, runs=n_runs, ran=outcome.ran, cached=outcome.cached,
                  failed=outcome.failed, pending=outcome.pending, run_wall_s=time.perf_counter() - t0)


def fit_design(spec: CalibrationSpec, design: Design) -> tuple[Surrogate, dict[str, dict[str, float]]]:
    """The surrogate on the training runs and its error on the held-back runs."""
    labels = target_labels(spec)
    u, y = design.training(labels)
    if len(u) < len(spec.inputs) + 2:
        raise InputError("design", len(u), f"too few finished runs to train a surrogate of {len(spec.inputs)} inputs")
    surrogate = fit_surrogate(u, y, seed=spec.design["seed"])
    u_h, y_h = design.holdout(labels)
    return surrogate, holdout_check(surrogate, u_h, y_h) if len(u_h) else {}


def likelihood(spec: CalibrationSpec, surrogate: Surrogate, observed: Sequence[float] | None = None) -> Likelihood:
    """The likelihood of the measured observables (``observed``: other values in place of the measured ones, for
    a synthetic problem; measured values only)."""
    obs = spec.observables
    if observed is not None:
        obs = tuple(Observable(o.label, o.terms, o.relation, value=float(v), sd=o.sd, group=o.group)
                    for o, v in zip(obs, observed))
    return Likelihood(surrogate, obs, tuple(g.name for g in spec.discrepancy))


def infer(spec: CalibrationSpec, surrogate: Surrogate, observed: Sequence[float] | None = None, seed: int | None = None,
          steps: int | None = None) -> Posterior:
    """The posterior of the inputs (and discrepancy sizes) given the measurements (or ``observed`` in their place)."""
    opts = spec.sampler
    n = steps or opts["steps"]
    return sample_posterior(likelihood(spec, surrogate, observed), len(spec.inputs),
                            [g.scale for g in spec.discrepancy], walkers=opts["walkers"], steps=n,
                            burn=min(opts["burn"], n // 2), seed=spec.design["seed"] if seed is None else seed)


def prediction_bands(spec: CalibrationSpec, surrogate: Surrogate, posterior: Posterior,
                     seed: int = 0) -> dict[str, dict[str, float]]:
    """Median and 5-95 % of each prediction over the posterior, the surrogate's own error included, and the model
    discrepancy of the prediction's group (its quantity's table) when that group has one."""
    rng = np.random.default_rng(seed)
    out = {}
    for p in spec.predictions:
        model = surrogate.models[p.label]
        mean, sd = model.predict(posterior.u, return_std=True)
        draws = mean + sd * rng.standard_normal(len(mean))
        group = default_group(p.quantity)
        if posterior.discrepancy_sd is not None and group in posterior.groups:
            draws = draws + posterior.discrepancy_sd[:, posterior.groups.index(group)] * rng.standard_normal(len(mean))
        p5, p50, p95 = np.quantile(draws, [0.05, 0.5, 0.95])
        out[p.label] = {"median": float(p50), "p5": float(p5), "p95": float(p95)}
    return out


def _screening(spec: CalibrationSpec, design: Design, surrogate: Surrogate) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for o in spec.observables:
        morris = morris_indices(design.points["screening"], design.values["screening"][o.label])
        model = surrogate.models[o.label]
        sobol = sobol_indices(lambda u: model.predict(u), len(spec.inputs), spec.design["seed"])
        out[o.label] = {"inputs": [inp.path for inp in spec.inputs], "morris": morris, "sobol_on_surrogate": sobol}
    return out


def confirm_runs(spec: CalibrationSpec, medians: Sequence[float], out: Path,
                 progress: bool) -> tuple[dict[str, Any], int]:
    """The full chain at the nominal inputs and at the posterior median, on the design's mesh and (where a case
    names one) its ``confirm_mesh``: every observable's value by fidelity and point (the fidelity's agreement), and
    how many runs that took beyond the design's."""
    points = {"nominal": np.array([[inp.unit(1.0) for inp in spec.inputs]]),
              "calibrated": np.array([[inp.unit(f) for inp, f in zip(spec.inputs, medians)]])}
    meshes: dict[str, float | None] = {"design": None}
    confirm = {c.confirm_mesh for c in spec.cases.values() if c.confirm_mesh is not None}
    if confirm:
        if len(confirm) > 1:
            raise InputError("cases.*.confirm_mesh", sorted(confirm), "must be the same for every case")
        meshes["confirm"] = confirm.pop()
    table: dict[str, Any] = {}
    ran = 0
    for fidelity, mesh in meshes.items():
        values, outcome, _ = run_points(spec, points, out / "runs", workers=0, progress=progress, mesh=mesh,
                                        desc=f"{fidelity} runs")
        table[fidelity] = {role: rows[0] for role, rows in values.items()}
        table[fidelity]["failed"] = outcome.failed
        table[fidelity]["mesh"] = mesh
        ran += outcome.ran + outcome.cached
    return table, ran - len(spec.runs())   # the nominal design run is the design's own


SMALL_ALGEBRA_THREADS = 1
"""BLAS threads while the surrogate is fitted and sampled: its matrices are ~100 x 100, and a multi-threaded BLAS on
a machine whose cores the runs (or anything else) keep busy spends 10-40x the time spinning (measured: a Gaussian
process's prediction of 48 points 14 ms with the default threads on a loaded 2-core machine, 0.3 ms with one)."""


def calibrate(spec: CalibrationSpec, out: str | Path, workers: int = 2, progress: bool = True,
              max_runs: int | None = None) -> dict[str, Any]:
    """Run the whole calibration into ``out`` (see the module docstring) and return calibration.json's table."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=SMALL_ALGEBRA_THREADS):
        return _calibrate(spec, Path(out), workers, progress, max_runs)


def _calibrate(spec: CalibrationSpec, out: Path, workers: int, progress: bool, max_runs: int | None) -> dict[str, Any]:
    t0 = time.perf_counter()
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
    waves: dict[str, np.ndarray] = {}
    refine_check: dict[str, dict[str, dict[str, float]]] = {}
    for wave in range(1, spec.design["refine_waves"] + 1):
        role = f"{REFINE}{wave}"
        waves[role] = spread_subset(posterior.u, spec.design["refine_runs"], spec.design["seed"] + 100 + wave)
        left = None if max_runs is None else max(max_runs - result["runs"]["ran_now"], 0)   # the call's budget
        design = run_design(spec, out, workers=workers, progress=progress, max_runs=left, waves=waves)
        _write_design(spec, design, out / "design.json")
        ran = result["runs"]["ran_now"] + design.ran
        result["runs"].update(total=design.runs, ran_now=ran, cached=design.runs - ran - len(design.pending),
                              pending=len(design.pending), failed=design.failed)
        if design.pending:
            result["status"] = "incomplete"
            _write_json(out / "calibration.json", result)
            return result
        u_w, y_w = design._usable((role,), target_labels(spec))
        refine_check[role] = holdout_check(surrogate, u_w, y_w)   # the surrogate so far, where the posterior is
        surrogate, holdout = fit_design(spec, design)
        posterior = infer(spec, surrogate)
    lk = likelihood(spec, surrogate)
    factors = posterior.factors(spec.inputs)
    table = posterior_table(posterior, spec.inputs)
    medians = [row["factor_median"] for row in table]
    calibrated = derived_files(list(spec.inputs), medians, out / "calibrated",
                               note=f"calibrated by quenchsim calibrate ({spec.name}, posterior median)")
    confirmed, confirm_count = confirm_runs(spec, medians, out, progress)
    from quenchsim.calibration.plots import corner_plot

    corner_plot(factors, spec.inputs, out / "corner.png")
    keep = np.linspace(0, len(posterior.u) - 1, min(POSTERIOR_SAMPLES_KEPT, len(posterior.u))).astype(int)
    _write_json(out / "posterior.json", {
        "name": spec.name, "inputs": [inp.path for inp in spec.inputs],
        "factor_bounds": [list(inp.factor_bounds) for inp in spec.inputs], "u": posterior.u[keep].tolist(),
        "factors": [[inp.factor(x) for inp, x in zip(spec.inputs, row)] for row in posterior.u[keep]],
        "discrepancy_groups": list(posterior.groups),
        "discrepancy_sd": None if posterior.discrepancy_sd is None else posterior.discrepancy_sd[keep].tolist()})
    sampler = spec.sampler
    result.update({
        "status": "ok", "description": spec.description, "inputs": [inp.path for inp in spec.inputs],
        "cases": {label: {"mesh": c.mesh, "confirm_mesh": c.confirm_mesh, "file": str(c.path)}
                  for label, c in spec.cases.items()},
        "data": [{"label": m.label, "kind": m.kind, "group": m.group, "source": m.source,
                  "observables": [o.label for o in m.observables]} for m in spec.measurements],
        "screening": _screening(spec, design, surrogate),
        "surrogate": {"training_runs": surrogate.n_train, "holdout": holdout,
                      "refinement_before_training": refine_check},
        "posterior": table,
        "discrepancy": discrepancy_table(posterior, [g.scale for g in spec.discrepancy],
                                         [g.unit for g in spec.discrepancy]),
        "discrepancy_priors": [{"group": g.name, "scale": g.scale, "unit": g.unit, "reason": g.reason}
                               for g in spec.discrepancy],
        "sampler": {"acceptance": posterior.acceptance, "autocorr_steps": posterior.autocorr_steps,
                    "samples": len(posterior.u), **sampler},
        "predictive_check": predictive_check(lk, posterior),
        "pulls": pulls(lk, spec.measurements, spec.inputs, walkers=sampler["walkers"],
                       steps=max(300, sampler["steps"] // 2), seed=spec.design["seed"]),
        "conflicts": conflicts(lk, spec.measurements, len(spec.inputs), seed=spec.design["seed"]),
        "full_chain_cosatisfaction": _cosatisfaction(spec, design),
        "predictions": prediction_bands(spec, surrogate, posterior),
        "calibrated_files": calibrated, "confirm": confirmed,
        "calibrated_run": _calibrated_rows(spec, confirmed),
        "wall_time_s": time.perf_counter() - t0, "run_wall_time_s": design.run_wall_s,
        "full_chain_runs": design.runs + confirm_count})
    _write_json(out / "calibration.json", result)
    from quenchsim.calibration.page import calibration_page

    (out / "calibration.md").write_text(calibration_page(spec, result))
    return result


def _cosatisfaction(spec: CalibrationSpec, design: Design) -> dict[str, Any]:
    """Which data the design's full-chain runs meet together (:func:`~quenchsim.calibration.conflicts.cosatisfaction`)."""
    runs, factors = [], []
    for role, block in design.points.items():
        for i, u in enumerate(block):
            runs.append({o.label: (None if not np.isfinite(design.values[role][o.label][i])
                                   else float(design.values[role][o.label][i])) for o in spec.observables})
            factors.append([inp.factor(x) for inp, x in zip(spec.inputs, u)])
    out = cosatisfaction(spec.measurements, runs, factors)
    out["inputs"] = [inp.path for inp in spec.inputs]
    return out


def _calibrated_rows(spec: CalibrationSpec, confirmed: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """Per measured observable: the full chain at the posterior median (the finest fidelity run) against the datum."""
    best = confirmed.get("confirm", confirmed["design"])
    rows = {}
    for o in spec.observables:
        value = best["calibrated"].get(o.label)
        rows[o.label] = {"full_chain": value, "measured": o.value, "lower": o.lower, "upper": o.upper,
                         "uncertainty": o.sd, "target": o.target_text(),
                         "met": None if value is None else meets(o, value)}
    return rows


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
