"""Which data pull which inputs where, and which data no input set meets together.

* Co-satisfaction on the full chain (no surrogate): of the design's runs, how many meet each datum, each pair of
  data, and the largest set of data one run meets -- evidence that does not depend on the surrogate's error, as
  dense as the design (a pair no run meets together is a conflict unless the runs missed the region where both
  hold; the refinement waves put runs where the posterior is).
* Pulls: the posterior of the inputs given each datum alone (no discrepancy), on the same surrogate: where each
  datum would put each input, and how much it narrows it.
* Conflicts: the parameter goodness-of-fit statistic of Maltoni & Schwetz (Phys. Rev. D 68 (2003) 033020),
  chi2_PG = min chi2(A and B) - min chi2(A) - min chi2(B), each minimum over the inputs' prior box: zero when one
  input set meets both data as well as each alone, large when the inputs that meet one miss the other.
  chi2 is :meth:`~quenchsim.calibration.likelihood.Likelihood.misfit` (measured values: squared standardised
  residuals; bounds: -2 log Phi). A pair is reported as in conflict above :data:`CONFLICT_CHI2` (the 95 % point
  of chi-square with one degree of freedom); the minimum of a datum alone above the same limit means no input set
  inside the priors meets it at all.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations
from typing import Any

import numpy as np
from scipy.optimize import minimize

from quenchsim.calibration.data import Measurement, Observable
from quenchsim.calibration.inputs import FreeInput
from quenchsim.calibration.likelihood import Likelihood
from quenchsim.calibration.posterior import identifiability, sample_posterior

CONFLICT_CHI2 = 3.841458820694124
"""chi-square's 95 % point with one degree of freedom."""
SCREEN_POINTS = 4000
"""Random points of the prior box screened before the local searches of a minimum."""
LOCAL_STARTS = 4
STEP = 1e-6
"""Finite-difference step of the misfit's gradient (unit cube)."""


def _value_and_gradient(likelihood: Likelihood, x: np.ndarray) -> tuple[float, np.ndarray]:
    """The misfit and its forward-difference gradient in one surrogate call (backward at the upper bound)."""
    step = np.where(x + STEP <= 1.0, STEP, -STEP)
    points = np.vstack([x, x[None, :] + np.diag(step)])
    f = likelihood.misfit(points)
    return float(f[0]), (f[1:] - f[0]) / step


def minimum_misfit(likelihood: Likelihood, d: int, seed: int = 0) -> tuple[float, np.ndarray]:
    """The smallest misfit over the unit cube and where: a screen of random points, then L-BFGS-B from the best."""
    rng = np.random.default_rng(seed)
    screen = rng.uniform(size=(SCREEN_POINTS, d))
    values = likelihood.misfit(screen)
    best_value, best_u = float(np.min(values)), screen[int(np.argmin(values))]
    for start in screen[np.argsort(values)[:LOCAL_STARTS]]:
        res = minimize(lambda x: _value_and_gradient(likelihood, x), start, jac=True, method="L-BFGS-B",
                       bounds=[(0.0, 1.0)] * d)
        if res.fun < best_value:
            best_value, best_u = float(res.fun), np.asarray(res.x)
    return best_value, best_u


def _datum_likelihood(likelihood: Likelihood, datum: Measurement) -> Likelihood:
    return likelihood.subset([o.label for o in datum.observables])


def pulls(likelihood: Likelihood, data: Sequence[Measurement], inputs: Sequence[FreeInput], walkers: int = 32,
          steps: int = 1500, seed: int = 0) -> list[dict[str, Any]]:
    """Per datum: the posterior of every input given that datum alone (factor median, 5-95 %, width over the prior's),
    its best misfit and where (unit cube)."""
    d = len(inputs)
    rows = []
    for datum in data:
        lk = _datum_likelihood(likelihood, datum)
        post = sample_posterior(Likelihood(lk.surrogate, lk.observables), d, walkers=max(walkers, 2 * d + 2),
                                steps=steps, burn=steps // 3, seed=seed)
        factors = post.factors(inputs)
        best, where = minimum_misfit(lk, d, seed)
        per_input = []
        for j, inp in enumerate(inputs):
            p5, p50, p95 = np.quantile(factors[:, j], [0.05, 0.5, 0.95])
            ratio, _ = identifiability(post.u[:, j])
            per_input.append({"input": inp.path, "factor_median": float(p50), "factor_5pct": float(p5),
                              "factor_95pct": float(p95), "width_ratio": ratio})
        rows.append({"datum": datum.label, "observables": len(datum.observables), "min_misfit": best,
                     "met_alone": best <= CONFLICT_CHI2 * len(datum.observables),
                     "best_factors": [inp.factor(float(x)) for inp, x in zip(inputs, where)], "inputs": per_input})
    return rows


def conflicts(likelihood: Likelihood, data: Sequence[Measurement], d: int, seed: int = 0) -> list[dict[str, Any]]:
    """The parameter goodness-of-fit statistic of every pair of data (see the module docstring)."""
    alone = {m.label: minimum_misfit(_datum_likelihood(likelihood, m), d, seed)[0] for m in data}
    rows = []
    for a, b in combinations(data, 2):
        joint = likelihood.subset([o.label for o in (*a.observables, *b.observables)])
        both, _ = minimum_misfit(joint, d, seed)
        pg = both - alone[a.label] - alone[b.label]
        rows.append({"a": a.label, "b": b.label, "chi2_a": alone[a.label], "chi2_b": alone[b.label], "chi2_both": both,
                     "chi2_pg": pg, "conflict": pg > CONFLICT_CHI2})
    return rows


MET_SIGMAS = 2.0
"""A run meets a measured value within this many of its standard deviations, a bound not violated by more."""


def meets(o: Observable, value: float | None, sigmas: float = MET_SIGMAS) -> bool:
    """Whether a run's value of an observable meets its datum (within ``sigmas`` standard deviations)."""
    if value is None or not np.isfinite(value):
        return False
    if o.value is not None:
        return abs(value - o.value) <= sigmas * o.sd
    return ((o.lower is None or value >= o.lower - sigmas * o.sd)
            and (o.upper is None or value <= o.upper + sigmas * o.sd))


def cosatisfaction(data: Sequence[Measurement], runs: Sequence[dict[str, float | None]],
                   factors: Sequence[Sequence[float]], best: int = 5) -> dict[str, Any]:
    """Of the full-chain runs (each a dict of observable values, with its input ``factors``): how many meet each
    datum (every observable of it), each pair of data together, all of them; the runs that meet the most data
    and what they miss."""
    met = np.array([[all(meets(o, run.get(o.label)) for o in m.observables) for m in data] for run in runs], dtype=bool)
    labels = [m.label for m in data]
    pairs = []
    for a, b in combinations(range(len(data)), 2):
        pairs.append({"a": labels[a], "b": labels[b], "runs_a": int(met[:, a].sum()), "runs_b": int(met[:, b].sum()),
                      "runs_both": int((met[:, a] & met[:, b]).sum())})
    order = np.argsort(-met.sum(axis=1), kind="stable")[:best]
    return {"runs": len(runs), "per_datum": dict(zip(labels, met.sum(axis=0).tolist())),
            "all": int(met.all(axis=1).sum()), "most": int(met.sum(axis=1).max()) if len(runs) else 0,
            "pairs": pairs,
            "best_runs": [{"met": int(met[i].sum()), "missed": [lab for lab, ok in zip(labels, met[i]) if not ok],
                           "factors": list(map(float, factors[i]))} for i in order]}
