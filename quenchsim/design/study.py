"""A design study of a case: cheap-fidelity trials through the cached Dask runner, the recommendation, its
full-chain confirmation (with the fidelity check and, if asked, the calibration's bands), the effects, and
every output file (:mod:`quenchsim.design.page`).

Files in the study folder ``OUT``: ``study.db`` (the Optuna study: resumable, shareable), ``runs/`` (every run,
cached by a hash of its inputs: :mod:`quenchsim.calibration.runs`), ``trials.csv`` (every trial: variables,
objectives, constraints, feasibility, the summary's key outputs, its run folder), ``optimise.json`` and
``optimise.md`` with the plots beside them.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from tqdm import tqdm

from quenchsim.calibration.runs import request, run_requests
from quenchsim.design.effects import effects
from quenchsim.design.optimise import (Evaluation, Problem, TrialRecord, closest_infeasible, evaluated, open_study,
                                       pareto_front, recommend, records, run_trials)
from quenchsim.design.quantities import value_of
from quenchsim.design.spec import StudySpec
from quenchsim.sweep import flatten_summary

log = logging.getLogger("quenchsim")
STORAGE = "study.db"
RUNS = "runs"


@dataclass
class Confirmation:
    """A full-chain run at a trial's point: its quantities beside the cheap run's, and whether they agree."""

    trial: int
    role: str                                    # "recommended" | "front" | "closest"
    params: dict[str, Any]
    run: str
    error: str | None
    full: dict[str, float | None]
    cheap: dict[str, float | None]
    agree: dict[str, bool | None]
    summary_flat: dict[str, Any] = field(default_factory=dict)
    uncertainty: dict[str, Any] | None = None


@dataclass
class StudyOutcome:
    spec: StudySpec
    out: Path
    trials: list[TrialRecord]
    front: list[TrialRecord]
    recommended: TrialRecord | None
    closest: list[TrialRecord]
    confirmations: list[Confirmation]
    effects: dict[str, Any]
    interrupted: bool
    wall_time_s: float
    files: dict[str, str] = field(default_factory=dict)

    @property
    def feasible(self) -> bool:
        return self.recommended is not None


def problem_of(spec: StudySpec) -> Problem:
    """The optimiser's view of a study; its name carries the study's fingerprint, so a changed study file starts a
    new study in the same SQLite file instead of mixing trials of two problems."""
    return Problem(name=f"{spec.name}-{spec.fingerprint()}", variables=spec.variables, objectives=spec.objectives,
                   constraints=spec.constraints, startup=spec.startup, seed=spec.seed, sampler=spec.sampler)


def _evaluations(spec: StudySpec, points: list[dict[str, Any]], runs_dir: Path, workers: int, scheduler: str | None,
                 full: bool = False) -> list[Evaluation]:
    reqs = [request(spec.case_at(p, full=full), (), ()) for p in points]
    done = run_requests(reqs, runs_dir, workers=workers, progress=False, scheduler=scheduler)
    out = []
    for req in reqs:
        name = req.folder_name()
        summary = done.summaries.get(name)
        info: dict[str, Any] = {"run": f"{RUNS}/{name}"}
        if summary is None:
            out.append(Evaluation(None, error=done.failed.get(name, "not run"), info=info))
        elif summary.get("end_state", {}).get("at_room_temperature") is False:
            # a part still hot at the end: its dimensions and hardness are not those of the finished part
            out.append(Evaluation(None, error="the part is still hot at the end of the run (summary.json end_state); "
                                              "lengthen air.time_s", info=info))
        else:
            info["summary"] = flatten_summary(summary)
            out.append(Evaluation({q: value_of(summary, q) for q in spec.quantities()}, info=info))
    return out


def _confirm_points(spec: StudySpec, front: list[TrialRecord], recommended: TrialRecord | None,
                    closest: list[TrialRecord]) -> list[tuple[str, TrialRecord]]:
    if recommended is None:
        return [("closest", closest[0])] if closest else []
    chosen = [("recommended", recommended)]
    others = [r for r in front if r is not recommended]
    if others and spec.confirm.extra:
        idx = np.unique(np.linspace(0, len(others) - 1, min(spec.confirm.extra, len(others))).round().astype(int))
        chosen += [("front", others[i]) for i in idx]
    return chosen


def confirm(spec: StudySpec, chosen: list[tuple[str, TrialRecord]], runs_dir: Path, workers: int,
            scheduler: str | None) -> list[Confirmation]:
    """Full-chain runs at the chosen trials' points, each compared with its cheap run on the study's quantities."""
    if not chosen:
        return []
    results = _evaluations(spec, [r.params for _, r in chosen], runs_dir, workers, scheduler, full=True)
    out = []
    for (role, rec), res in zip(chosen, results):
        full = res.quantities or {}
        agree: dict[str, bool | None] = {}
        for q in spec.quantities():
            a, b, tol = full.get(q), rec.quantities.get(q), spec.fidelity.tolerance.get(q)
            agree[q] = None if a is None or b is None or tol is None else bool(abs(a - b) <= tol)
        out.append(Confirmation(trial=rec.number, role=role, params=rec.params, run=res.info["run"], error=res.error,
                                full=dict(full), cheap=dict(rec.quantities), agree=agree,
                                summary_flat=res.info.get("summary", {})))
    return out


def study_effects(spec: StudySpec, trials: list[TrialRecord], reference: TrialRecord | None) -> dict[str, Any]:
    """:func:`quenchsim.design.effects.effects` of every study quantity over the ok trials (numeric variables)."""
    numeric = [v for v in spec.variables if v.numeric]
    ok = [t for t in trials if t.state == "ok"]
    if not numeric or len(ok) < len(numeric) + 2:
        return {}
    u = np.array([[v.to_unit(t.params[v.key]) for v in numeric] for t in ok])
    ref = np.array([v.to_unit(reference.params[v.key]) for v in numeric]) if reference else np.full(len(numeric), 0.5)
    values = {q: np.array([t.quantities[q] for t in ok], dtype=float) for q in spec.quantities()}
    return effects(u, values, [v.key for v in numeric], ref)


def run_study(spec: StudySpec, out: str | Path, workers: int = 2, scheduler: str | None = None,
              progress: bool = True) -> StudyOutcome:
    """Run (or resume) the study into ``out`` and write its outputs; Ctrl-C leaves a resumable study."""
    from quenchsim.design.page import write_outputs
    from quenchsim.sweep import _client

    t0 = time.perf_counter()
    out = Path(out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    runs_dir = out / RUNS
    problem = problem_of(spec)
    study = open_study(problem, out / STORAGE)
    n_confirm = 1 + spec.confirm.extra
    bar = tqdm(total=spec.trials + n_confirm, initial=min(evaluated(study), spec.trials),
               desc=f"optimise {spec.name}", unit="run", disable=not progress)
    client: Any = None   # dask's Client and cluster, set together
    cluster: Any = None
    if workers > 0 and scheduler is None:   # one cluster for the whole study
        client, cluster = _client(None, workers)
        scheduler = cluster.scheduler_address
    interrupted = False
    try:
        study, interrupted = run_trials(problem, lambda pts: _evaluations(spec, pts, runs_dir, workers, scheduler),
                                        spec.trials, study=study, batch=max(workers, 1), on_trial=bar.update)
        trials = records(study, problem)
        front = pareto_front(trials, spec.objectives)
        recommended = recommend(front, spec.objectives)
        closest = closest_infeasible(trials, spec.constraints) if recommended is None else []
        confirmations: list[Confirmation] = []
        if not interrupted:
            try:
                confirmations = confirm(spec, _confirm_points(spec, front, recommended, closest), runs_dir, workers,
                                        scheduler)
                bar.update(n_confirm)
                if spec.confirm.uncertainty and confirmations and confirmations[0].error is None:
                    from quenchsim.calibration.propagate import propagate

                    first = confirmations[0]
                    first.uncertainty = propagate(spec.case_at(first.params, full=True), out / first.run,
                                                  spec.confirm.uncertainty, posterior=spec.confirm.posterior,
                                                  workers=workers, progress=False)
            except KeyboardInterrupt:
                interrupted = True
    finally:
        bar.close()
        if client is not None:
            client.close()
            cluster.close()
    outcome = StudyOutcome(spec=spec, out=out, trials=trials, front=front, recommended=recommended, closest=closest,
                           confirmations=confirmations, effects=study_effects(spec, trials, recommended or
                                                                              (closest[0] if closest else None)),
                           interrupted=interrupted, wall_time_s=time.perf_counter() - t0)
    outcome.files = write_outputs(outcome)
    return outcome
