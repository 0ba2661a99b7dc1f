"""The Bayesian posterior of the free inputs on the surrogate, its summary and each input's identifiability.

Model: measurement_k = surrogate_k(u) + e_k, e_k ~ N(0, sigma_k^2 + s_k(u)^2), sigma_k the measurement's
standard deviation and s_k(u) the surrogate's own (Kennedy & O'Hagan, J. R. Stat. Soc. B 63 (2001) 425, without
a discrepancy term: a discrepancy shows up as a posterior at the edge of its prior and as a miss of the
posterior predictive check). Prior: uniform on the unit cube (log-uniform factors,
:mod:`quenchsim.calibration.inputs`). Sampler: emcee's affine-invariant ensemble (Foreman-Mackey et al.,
PASP 125 (2013) 306), walkers started from the prior.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from typing import Any
from dataclasses import dataclass

import numpy as np

from quenchsim.calibration.inputs import FreeInput, first_value
from quenchsim.calibration.surrogate import Surrogate

IDENTIFIED_BELOW = 0.5
"""Posterior 90 % width / prior 90 % width below which an input counts as identified by the measurements."""
NOT_IDENTIFIED_ABOVE = 0.85
"""... and above which the measurements say (almost) nothing about it: the posterior is the prior."""
EDGE = 0.1
"""A posterior whose median lies within this share of the unit interval of a prior bound is 'at the edge'."""
MISS_SIGMAS = 2.0
"""A posterior prediction more than this many standard deviations from a measurement misses it."""


@dataclass
class Posterior:
    """Samples in the unit cube (n, d) and the factors they mean, with the sampler's diagnostics."""

    u: np.ndarray
    acceptance: float
    autocorr_steps: float | None

    def factors(self, inputs: Sequence[FreeInput]) -> np.ndarray:
        return np.column_stack([inp.factor(self.u[:, j]) for j, inp in enumerate(inputs)])


def log_likelihood(surrogate: Surrogate, observed: np.ndarray, sigma: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Gaussian log-likelihood of the measurements at points ``u`` (n, d), surrogate error included."""
    mean, sd = surrogate.predict(u)
    var = sigma[None, :] ** 2 + sd ** 2
    return -0.5 * np.sum((mean - observed[None, :]) ** 2 / var + np.log(2.0 * np.pi * var), axis=1)


def sample_posterior(surrogate: Surrogate, observed: np.ndarray, sigma: np.ndarray, d: int, walkers: int = 32,
                     steps: int = 3000, burn: int = 1000, seed: int = 0, thin: int = 5) -> Posterior:
    """emcee on the surrogate; returns the thinned chain after ``burn`` steps."""
    import emcee

    rng = np.random.default_rng(seed)

    def log_prob(u: np.ndarray) -> np.ndarray:
        u = np.atleast_2d(u)
        inside = np.all((u >= 0.0) & (u <= 1.0), axis=1)
        out = np.full(len(u), -np.inf)
        if inside.any():
            out[inside] = log_likelihood(surrogate, observed, sigma, u[inside])
        return out

    sampler = emcee.EnsembleSampler(walkers, d, log_prob, vectorize=True)
    sampler.random_state = np.random.RandomState(seed).get_state()
    sampler.run_mcmc(rng.uniform(size=(walkers, d)), steps, progress=False)
    autocorr_log = logging.getLogger("emcee.autocorr")   # its "chain too short" warning: the value is recorded
    level = autocorr_log.level
    autocorr_log.setLevel(logging.ERROR)
    try:
        tau = float(np.max(sampler.get_autocorr_time(discard=burn, quiet=True)))
    except Exception:  # noqa: BLE001 -- emcee raises on a too-short chain; the diagnostic is then unknown
        tau = None
    finally:
        autocorr_log.setLevel(level)
    return Posterior(u=sampler.get_chain(discard=burn, thin=thin, flat=True),
                     acceptance=float(np.mean(sampler.acceptance_fraction)), autocorr_steps=tau)


def identifiability(u: np.ndarray) -> tuple[float, str]:
    """The posterior's 90 % width over the prior's (both in the unit interval) and a plain statement."""
    lo, med, hi = np.quantile(u, [0.05, 0.5, 0.95])
    ratio = float((hi - lo) / 0.9)
    if med < EDGE or med > 1.0 - EDGE:
        side = "lower" if med < EDGE else "upper"
        return ratio, (f"at the {side} edge of its prior: the measurements push it beyond the declared range "
                       "(a model-form discrepancy to report, not a calibration)")
    if ratio < IDENTIFIED_BELOW:
        return ratio, f"identified: the measurements narrow the prior to {100 * ratio:.0f} % of its width"
    if ratio > NOT_IDENTIFIED_ABOVE:
        return ratio, "not identified: the posterior is about the prior (the measurements say little about it)"
    return ratio, f"weakly identified: the posterior keeps {100 * ratio:.0f} % of the prior's width"


def posterior_table(posterior: Posterior, inputs: Sequence[FreeInput]) -> list[dict[str, Any]]:
    """One row per input: factor median and 5-95 %, prior bounds, the data file's (first) value and that value at the
    median, identifiability."""
    rows = []
    factors = posterior.factors(inputs)
    for j, inp in enumerate(inputs):
        p5, p50, p95 = np.quantile(factors[:, j], [0.05, 0.5, 0.95])
        ratio, statement = identifiability(posterior.u[:, j])
        nominal = first_value(inp.nominal)
        rows.append({"input": inp.path, "label": inp.label, "prior": inp.prior,
                     "prior_factor_bounds": list(inp.factor_bounds), "value": nominal,
                     "value_at_median": None if nominal is None else nominal * float(p50), "factor_median": float(p50),
                     "factor_5pct": float(p5), "factor_95pct": float(p95), "width_ratio": ratio,
                     "identifiability": statement})
    return rows


def predictive_check(surrogate: Surrogate, posterior: Posterior, names: Sequence[str], observed: np.ndarray,
                     sigma: np.ndarray) -> list[dict[str, object]]:
    """The posterior's prediction of each measurement (median and 5-95 %, surrogate error included) and
    whether it reaches it."""
    mean, sd = surrogate.predict(posterior.u)
    rng = np.random.default_rng(1)
    draws = mean + sd * rng.standard_normal(mean.shape)
    rows = []
    for k, name in enumerate(names):
        p5, p50, p95 = np.quantile(draws[:, k], [0.05, 0.5, 0.95])
        spread = np.hypot(sigma[k], np.std(draws[:, k]))
        z = float((p50 - observed[k]) / spread)
        rows.append({"quantity": name, "measured": float(observed[k]), "uncertainty": float(sigma[k]),
                     "posterior_median": float(p50), "posterior_5pct": float(p5), "posterior_95pct": float(p95),
                     "z": z, "reached": abs(z) <= MISS_SIGMAS})
    return rows
