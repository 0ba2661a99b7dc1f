"""The Bayesian posterior of the free inputs (and of the model discrepancy's size) on the surrogate, its summary and
each input's identifiability.

Model: :mod:`quenchsim.calibration.likelihood` (measured = surrogate + discrepancy + error). Prior: uniform on the
unit cube of the inputs (log-uniform factors, :mod:`quenchsim.calibration.inputs`), half-normal on each discrepancy
group's standard deviation. Sampler: emcee's affine-invariant ensemble (Foreman-Mackey et al., PASP 125 (2013)
306), walkers started from the prior.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from typing import Any
from dataclasses import dataclass

import numpy as np

from quenchsim.calibration.inputs import FreeInput, first_value
from quenchsim.calibration.likelihood import Likelihood, half_normal_log_prior

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
    """Samples in the unit cube (n, d) and the factors they mean, the discrepancy groups' standard deviations
    (n, G) with their names, and the sampler's diagnostics."""

    u: np.ndarray
    acceptance: float
    autocorr_steps: float | None
    discrepancy_sd: np.ndarray | None = None
    groups: tuple[str, ...] = ()

    def factors(self, inputs: Sequence[FreeInput]) -> np.ndarray:
        return np.column_stack([inp.factor(self.u[:, j]) for j, inp in enumerate(inputs)])


def sample_posterior(likelihood: Likelihood, d: int, scales: Sequence[float] = (), walkers: int = 32,
                     steps: int = 3000, burn: int = 1000, seed: int = 0, thin: int = 5) -> Posterior:
    """emcee over the inputs' unit cube (d) and the discrepancy groups' standard deviations (half-normal priors of
    ``scales``, one per ``likelihood.groups``); returns the thinned chain after ``burn`` steps."""
    import emcee

    scale = np.asarray(scales, dtype=float)
    G = len(scale)
    if G != len(likelihood.groups):
        raise ValueError(f"{len(likelihood.groups)} discrepancy groups but {G} prior scales")
    rng = np.random.default_rng(seed)

    def log_prob(theta: np.ndarray) -> np.ndarray:
        theta = np.atleast_2d(theta)
        u, sigma = theta[:, :d], theta[:, d:]
        inside = np.all((u >= 0.0) & (u <= 1.0), axis=1) & np.all(sigma >= 0.0, axis=1)
        out = np.full(len(theta), -np.inf)
        if inside.any():
            out[inside] = likelihood(u[inside], sigma[inside] if G else None)
            if G:
                out[inside] += half_normal_log_prior(sigma[inside], scale)
        return out

    start = np.column_stack([rng.uniform(size=(walkers, d)), np.abs(rng.standard_normal((walkers, G))) * scale])
    sampler = emcee.EnsembleSampler(walkers, d + G, log_prob, vectorize=True)
    sampler.random_state = np.random.RandomState(seed).get_state()
    sampler.run_mcmc(start, steps, progress=False)
    autocorr_log = logging.getLogger("emcee.autocorr")   # its "chain too short" warning: the value is recorded
    level = autocorr_log.level
    autocorr_log.setLevel(logging.ERROR)
    try:
        tau = float(np.max(sampler.get_autocorr_time(discard=burn, quiet=True)))
    except Exception:  # noqa: BLE001 -- emcee raises on a too-short chain; the diagnostic is then unknown
        tau = None
    finally:
        autocorr_log.setLevel(level)
    chain = sampler.get_chain(discard=burn, thin=thin, flat=True)
    return Posterior(u=chain[:, :d], acceptance=float(np.mean(sampler.acceptance_fraction)), autocorr_steps=tau,
                     discrepancy_sd=chain[:, d:] if G else None, groups=tuple(likelihood.groups))


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


def predictive_check(likelihood: Likelihood, posterior: Posterior) -> list[dict[str, Any]]:
    """The posterior's prediction of each measured observable by the model alone (median and 5-95 % of the surrogate
    over the posterior, its own error included; no discrepancy), and whether it reaches the datum: a value within
    :data:`MISS_SIGMAS` of the measurement's and the prediction's spread together, a bound not violated by more than
    that (``z`` is then the distance past the bound, negative inside it)."""
    mean, sd = likelihood.predict(posterior.u)
    rng = np.random.default_rng(1)
    draws = mean + sd * rng.standard_normal(mean.shape)
    rows = []
    for k, o in enumerate(likelihood.observables):
        p5, p50, p95 = np.quantile(draws[:, k], [0.05, 0.5, 0.95])
        spread = float(np.hypot(o.sd, np.std(draws[:, k])))
        if o.value is not None:
            z = float((p50 - o.value) / spread)
            reached = abs(z) <= MISS_SIGMAS
            inside = None
        else:
            past = max((o.lower - p50) if o.lower is not None else -np.inf,
                       (p50 - o.upper) if o.upper is not None else -np.inf)
            z = float(past / spread)
            reached = z <= MISS_SIGMAS
            ok = np.ones(len(draws), bool)
            if o.lower is not None:
                ok &= draws[:, k] >= o.lower
            if o.upper is not None:
                ok &= draws[:, k] <= o.upper
            inside = float(np.mean(ok))
        rows.append({"quantity": o.label, "measured": o.value, "lower": o.lower, "upper": o.upper,
                     "target": o.target_text(), "uncertainty": o.sd, "group": o.group,
                     "posterior_median": float(p50), "posterior_5pct": float(p5), "posterior_95pct": float(p95),
                     "z": z, "share_inside_bound": inside, "reached": bool(reached)})
    return rows


def discrepancy_table(posterior: Posterior, scales: Sequence[float], units: Sequence[str]) -> list[dict[str, Any]]:
    """One row per discrepancy group: the prior's scale and the posterior's median and 5-95 % of its standard
    deviation, and their ratio (above ~1: the data ask for more discrepancy than the prior expected)."""
    if posterior.discrepancy_sd is None:
        return []
    rows = []
    for g, (name, scale, unit) in enumerate(zip(posterior.groups, scales, units)):
        p5, p50, p95 = np.quantile(posterior.discrepancy_sd[:, g], [0.05, 0.5, 0.95])
        rows.append({"group": name, "unit": unit, "prior_scale": float(scale), "median": float(p50), "p5": float(p5),
                     "p95": float(p95), "median_over_prior_median": float(p50 / (0.6745 * scale))})
    return rows
