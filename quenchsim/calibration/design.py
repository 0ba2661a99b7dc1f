"""The design of runs in the unit cube of the free inputs, and the global sensitivity from it.

* screening: Morris elementary effects (Morris, Technometrics 33 (1991) 161; Campolongo et al. 2007 mu*),
  ``r`` trajectories of ``d + 1`` runs on a 4-level grid, analysed by SALib (Herman & Usher, JOSS 2 (2017) 97);
* training: a Latin hypercube (scipy.stats.qmc) added to the screening runs and the nominal run;
* held-back runs: a second, independent Latin hypercube the surrogate never sees;
* Sobol first-order and total indices (Saltelli et al., Comput. Phys. Commun. 181 (2010) 259) computed on the
  surrogate, where they cost nothing;
* refinement: runs spread over the posterior of the previous wave (:func:`spread_subset`), so the surrogate is
  accurate where the posterior is -- the sequential design of calibration (cf. the waves of history matching,
  Vernon, Goldstein & Bower, Bayesian Analysis 5 (2010) 619).

Every point is a pure function of the seed, so a resumed calibration asks for exactly the same runs.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

MORRIS_LEVELS = 4
SOBOL_BASE_SAMPLES = 1024
"""Saltelli base sample size for the Sobol indices on the surrogate (N (2d + 2) surrogate evaluations)."""


def _problem(d: int) -> dict[str, object]:
    return {"num_vars": d, "names": [f"x{j}" for j in range(d)], "bounds": [[0.0, 1.0]] * d}


def morris_points(d: int, trajectories: int, seed: int) -> np.ndarray:
    """``trajectories (d + 1)`` points of Morris trajectories in the unit cube."""
    from SALib.sample import morris

    return morris.sample(_problem(d), N=trajectories, num_levels=MORRIS_LEVELS, seed=seed)


def latin_hypercube(d: int, n: int, seed: int) -> np.ndarray:
    """``n`` Latin-hypercube points in the unit cube (empty for n = 0)."""
    from scipy.stats import qmc

    return qmc.LatinHypercube(d=d, seed=seed).random(n) if n else np.empty((0, d))


def morris_indices(points: np.ndarray, values: np.ndarray) -> dict[str, list[float]] | None:
    """mu* (mean |elementary effect|, in the quantity's unit per unit of the input's prior range) and sigma per
    input; None when a run of the trajectories is missing (failed)."""
    from SALib.analyze import morris

    if not np.all(np.isfinite(values)):
        return None
    res = morris.analyze(_problem(points.shape[1]), points, values, num_levels=MORRIS_LEVELS, print_to_console=False)
    return {"mu_star": [float(x) for x in res["mu_star"]], "sigma": [float(x) for x in res["sigma"]]}


def sobol_indices(predict: Callable[[np.ndarray], np.ndarray], d: int, seed: int) -> dict[str, list[float]]:
    """First-order and total Sobol indices of the function ``predict(u) -> values`` over the unit cube."""
    from SALib.analyze import sobol
    from SALib.sample import sobol as sobol_sample

    problem = _problem(d)
    u = sobol_sample.sample(problem, SOBOL_BASE_SAMPLES, calc_second_order=False, seed=seed)
    res = sobol.analyze(problem, predict(u), calc_second_order=False, print_to_console=False, seed=seed)
    return {"S1": [float(x) for x in res["S1"]], "ST": [float(x) for x in res["ST"]]}


def spread_subset(samples: np.ndarray, n: int, seed: int) -> np.ndarray:
    """``n`` of the ``samples`` (m, d) spread over them: greedy farthest-point selection (each next point the sample
    farthest from those chosen), started at the sample nearest the samples' median; deterministic for a seed (ties
    and the thinning of a large sample)."""
    rng = np.random.default_rng(seed)
    pool = samples if len(samples) <= 4000 else samples[rng.choice(len(samples), 4000, replace=False)]
    first = int(np.argmin(np.sum((pool - np.median(pool, axis=0)) ** 2, axis=1)))
    chosen = [first]
    dist = np.sum((pool - pool[first]) ** 2, axis=1)
    for _ in range(min(n, len(pool)) - 1):
        nxt = int(np.argmax(dist))
        chosen.append(nxt)
        dist = np.minimum(dist, np.sum((pool - pool[nxt]) ** 2, axis=1))
    return pool[chosen]
