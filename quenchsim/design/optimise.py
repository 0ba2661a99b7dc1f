"""The optimiser: Optuna's samplers driven ask-and-tell over an evaluator of batches of points, the study kept in
SQLite (resumable; several workers may share it), then the recommendation read off the finished trials.

The evaluator is a function ``points -> results`` (one :class:`Evaluation` per point); for a case it runs the
points through the cached Dask runner (:mod:`quenchsim.design.runs`), for the verification problems it is a
formula. A trial is one point: its objective scores (the value, or |value - target|) are told to Optuna with
the constraints' violations (<= 0 met; Optuna's ``constraints_func``). The first ``startup`` points are a
Latin hypercube over the variables (enqueued when the study is created), the rest come from the sampler
(TPE: Watanabe, "Tree-structured Parzen estimator: understanding its algorithm components", 2023, with the
constrained TPE of Watanabe & Hutter 2023 and its multi-objective form; NSGA-II: Deb et al. 2002, with
constrained domination), asked ``batch`` at a time (TPE's constant liar keeps the points of one batch apart).

Interrupting (Ctrl-C) fails the trials of the unfinished batch and enqueues their points again, so the next
call asks for the same points; finished trials are never run again. A call on a study that was killed without
that bookkeeping (trials left RUNNING) does the same for those trials first.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

import numpy as np

from quenchsim.design.spec import Constraint, Objective, Variable

log = logging.getLogger("quenchsim")


@dataclass(frozen=True)
class Problem:
    """What the optimiser needs of a study: the variables, objectives, constraints and the sampler's settings."""

    name: str
    variables: tuple[Variable, ...]
    objectives: tuple[Objective, ...]
    constraints: tuple[Constraint, ...] = ()
    startup: int = 8
    seed: int = 0
    sampler: str = "tpe"


@dataclass
class Evaluation:
    """The quantities of one point (by name; None where the run gave none), or the error of a failed run, and
    anything to keep with the trial (``info``: e.g. the run folder)."""

    quantities: dict[str, float | None] | None
    error: str | None = None
    info: dict[str, Any] = field(default_factory=dict)


@dataclass
class TrialRecord:
    """One finished trial as the outputs use it."""

    number: int
    params: dict[str, Any]
    state: str                                   # "ok" | "failed"
    quantities: dict[str, float | None]
    violations: list[float]
    error: str | None
    info: dict[str, Any]

    @property
    def feasible(self) -> bool:
        return self.state == "ok" and all(v <= 0.0 for v in self.violations)


Evaluator = Callable[[list[dict[str, Any]]], list[Evaluation]]


def _distribution(var: Variable) -> Any:
    import optuna.distributions as d

    if var.choices:
        return d.CategoricalDistribution(list(var.choices))
    assert var.low is not None and var.high is not None   # a variable without choices has a range
    if var.integer:
        return d.IntDistribution(int(var.low), int(var.high), log=var.log)
    return d.FloatDistribution(var.low, var.high, log=var.log, step=var.step)


def _sampler(problem: Problem) -> Any:
    import optuna

    # the constraints reach the samplers through Trial.set_constraint (Optuna >= 5)
    if problem.sampler == "nsga2":
        return optuna.samplers.NSGAIISampler(seed=problem.seed)
    if problem.sampler == "random":
        return optuna.samplers.RandomSampler(seed=problem.seed)
    return optuna.samplers.TPESampler(seed=problem.seed, n_startup_trials=max(problem.startup, 1), multivariate=True,
                                      constant_liar=True)


def latin_hypercube_points(variables: Sequence[Variable], n: int, seed: int) -> list[dict[str, Any]]:
    """``n`` points of a Latin hypercube over the variables (scipy's LHS, optimised by random CD)."""
    from scipy.stats import qmc

    if n == 0:
        return []
    u = qmc.LatinHypercube(d=len(variables), seed=seed, optimization="random-cd" if len(variables) > 1 else None).random(n)
    return [{v.key: v.from_unit(float(row[j])) for j, v in enumerate(variables)} for row in u]


def open_study(problem: Problem, storage: str | Path | None) -> Any:
    """Create the Optuna study (or load it from ``storage``, a SQLite file) with its Latin-hypercube start
    enqueued when new, and the trials a killed call left RUNNING failed and enqueued again."""
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    url = None if storage is None else f"sqlite:///{Path(storage).resolve()}"
    directions = [o.direction for o in problem.objectives]
    study = optuna.create_study(storage=url, study_name=problem.name, directions=directions,
                                sampler=_sampler(problem), load_if_exists=True)
    if not study.trials:
        for point in latin_hypercube_points(problem.variables, problem.startup, problem.seed):
            study.enqueue_trial(point)
    stale = [t for t in study.get_trials(deepcopy=False) if t.state == optuna.trial.TrialState.RUNNING]
    for t in stale:
        study.tell(t.number, state=optuna.trial.TrialState.FAIL)
        study.enqueue_trial(t.params)
    if stale:
        log.warning("%d trial(s) left unfinished by an earlier call are asked again", len(stale))
    return study


def evaluated(study: Any) -> int:
    """Trials whose point was evaluated (finished, or failed in the run; not those failed by an interruption)."""
    return sum(1 for t in study.get_trials(deepcopy=False) if t.user_attrs.get("evaluated"))


def _tell(study: Any, problem: Problem, trial: Any, result: Evaluation) -> None:
    import optuna

    trial.set_user_attr("evaluated", True)
    trial.set_user_attr("info", result.info)
    q = result.quantities or {}
    missing = [name for name in [o.quantity for o in problem.objectives] + [c.quantity for c in problem.constraints]
               if q.get(name) is None]
    error = result.error or (f"the run gave no {', '.join(missing)}" if missing else None)
    trial.set_user_attr("quantities", {k: v for k, v in q.items()})
    if error:
        trial.set_user_attr("error", error)
        study.tell(trial, state=optuna.trial.TrialState.FAIL)
        return
    given = cast(dict[str, float], q)   # no quantity of an objective or a constraint is missing (checked above)
    violations = [c.violation(given[c.quantity]) for c in problem.constraints]
    trial.set_user_attr("violations", violations)
    for c, v in zip(problem.constraints, violations):
        trial.set_constraint(c.label(), v)
    study.tell(trial, [o.score(given[o.quantity]) for o in problem.objectives])


def run_trials(problem: Problem, evaluate: Evaluator, n_trials: int, storage: str | Path | None = None,
               batch: int = 1, on_trial: Callable[[int], None] | None = None, study: Any = None) -> tuple[Any, bool]:
    """Evaluate trials until ``n_trials`` are done (counting those of an earlier call), ``batch`` points per call
    of ``evaluate``; returns (the study, interrupted). ``on_trial(k)`` is told of every ``k`` trials evaluated."""
    import optuna

    study = study if study is not None else open_study(problem, storage)
    distributions = {v.key: _distribution(v) for v in problem.variables}
    while (done := evaluated(study)) < n_trials:
        trials = [study.ask(distributions) for _ in range(min(batch, n_trials - done))]
        try:
            results = evaluate([dict(t.params) for t in trials])
        except KeyboardInterrupt:
            for t in trials:
                study.tell(t, state=optuna.trial.TrialState.FAIL)
                study.enqueue_trial(dict(t.params))
            return study, True
        for trial, result in zip(trials, results):
            _tell(study, problem, trial, result)
        if on_trial is not None:
            on_trial(len(trials))
    return study, False


def records(study: Any, problem: Problem) -> list[TrialRecord]:
    """The evaluated trials of a study, in order."""
    out = []
    for t in study.get_trials(deepcopy=False):
        if not t.user_attrs.get("evaluated"):
            continue
        ok = t.state.name == "COMPLETE"
        out.append(TrialRecord(number=t.number, params=dict(t.params), state="ok" if ok else "failed",
                               quantities=dict(t.user_attrs.get("quantities", {})),
                               violations=list(t.user_attrs.get("violations", [])), error=t.user_attrs.get("error"),
                               info=dict(t.user_attrs.get("info", {}))))
    return out


def scores(record: TrialRecord, objectives: Sequence[Objective]) -> np.ndarray:
    """The objective scores of a trial, signed so that smaller is better for every objective."""
    given = cast(dict[str, float], record.quantities)   # an ok trial has every objective's quantity
    return np.array([(-1.0 if o.goal == "max" else 1.0) * o.score(given[o.quantity]) for o in objectives])


def pareto_front(recs: Sequence[TrialRecord], objectives: Sequence[Objective]) -> list[TrialRecord]:
    """The feasible trials no other feasible trial dominates (for one objective: the best one(s))."""
    feasible = [r for r in recs if r.feasible]
    s = [scores(r, objectives) for r in feasible]
    front = [r for i, r in enumerate(feasible)
             if not any(np.all(s[j] <= s[i]) and np.any(s[j] < s[i]) for j in range(len(feasible)) if j != i)]
    return sorted(front, key=lambda r: tuple(scores(r, objectives)))


def recommend(front: Sequence[TrialRecord], objectives: Sequence[Objective]) -> TrialRecord | None:
    """The front point nearest the utopia point (each score scaled to its range over the front); for one
    objective, the best trial."""
    if not front:
        return None
    s = np.array([scores(r, objectives) for r in front])
    span = np.ptp(s, axis=0)
    span[span == 0] = 1.0
    distance = np.linalg.norm((s - s.min(axis=0)) / span, axis=1)
    return front[int(np.argmin(distance))]


def closest_infeasible(recs: Sequence[TrialRecord], constraints: Sequence[Constraint], n: int = 3) -> list[TrialRecord]:
    """The ``n`` finished trials that miss the constraints least (largest miss relative to the bound's size)."""
    def miss(r: TrialRecord) -> float:
        return max(max(v, 0.0) / max(abs(c.bound), 1e-12) for v, c in zip(r.violations, constraints))

    return sorted((r for r in recs if r.state == "ok"), key=miss)[:n]
