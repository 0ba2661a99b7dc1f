"""The statistical model of the calibration: measured = model(inputs) + discrepancy + measurement error.

For each observable k (:mod:`quenchsim.calibration.data`) of discrepancy group g(k):

    y_k = eta_k(u) + delta_k + e_k,   e_k ~ N(0, sd_k^2),   delta_k ~ N(0, s_g(k)^2),   eta_k(u) ~ N(m_k(u), v_k(u))

eta_k the full chain at the inputs u (unit cube of the priors), emulated by the surrogate (mean m_k, variance v_k:
its own error), delta_k the model discrepancy (Kennedy & O'Hagan, J. R. Stat. Soc. B 63 (2001) 425): what the
model gets wrong at the measured setting whatever the inputs. With one measured setting per observable the
discrepancy is a constant per observable; its size s_g is shared by a group of like data (e.g. the dimensions) and
is itself inferred, with a half-normal prior of a stated scale -- Brynjarsdottir & O'Hagan (Inverse Problems 30
(2014) 114007) show that a calibration without it drives the inputs of an inadequate model to wrong values with
false confidence, and that only prior information on the discrepancy makes the inputs identifiable. Marginally:

* a measured value: y_k ~ N(m_k, sd_k^2 + v_k + s_g^2);
* a bound (lower <= y_k <= upper, soft by sd_k): log Phi((m_k - lower) / s) + log Phi((upper - m_k) / s),
  s^2 = sd_k^2 + v_k + s_g^2 (a probit likelihood of the stated inequality).

Observables are taken as independent given the inputs (their surrogates' errors too).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.special import log_ndtr

from quenchsim.calibration.data import Observable
from quenchsim.calibration.surrogate import Surrogate


@dataclass(frozen=True)
class Likelihood:
    """The likelihood of a set of observables on a surrogate, with discrepancy groups ``groups`` (their names; an
    observable whose group is not among them has no discrepancy)."""

    surrogate: Surrogate
    observables: tuple[Observable, ...]
    groups: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        missing = [o.label for o in self.observables if o.label not in self.surrogate.models]
        if missing:
            raise KeyError(f"no surrogate of {', '.join(missing)}")

    @cached_property
    def _arrays(self) -> tuple[np.ndarray, ...]:
        obs = self.observables
        value = np.array([np.nan if o.value is None else o.value for o in obs])
        lower = np.array([-np.inf if o.lower is None else o.lower for o in obs])
        upper = np.array([np.inf if o.upper is None else o.upper for o in obs])
        sd = np.array([o.sd for o in obs])
        group = np.array([self.groups.index(o.group) if o.group in self.groups else -1 for o in obs])
        return value, lower, upper, sd, group

    def predict(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Surrogate mean and standard deviation of each observable at points ``u`` (n, d): (n, k) each."""
        mean, sd = [], []
        for o in self.observables:
            m, s = self.surrogate.models[o.label].predict(np.atleast_2d(u), return_std=True)
            mean.append(m)
            sd.append(s)
        return np.column_stack(mean), np.column_stack(sd)

    def terms(self, u: np.ndarray, discrepancy_sd: np.ndarray | None = None) -> np.ndarray:
        """The log-likelihood term of each observable at points ``u`` (n, d) with the groups' discrepancy standard
        deviations ``discrepancy_sd`` (n, G; None: no discrepancy): shape (n, k)."""
        value, lower, upper, sd, group = self._arrays
        mean, gp_sd = self.predict(u)
        var = sd[None, :] ** 2 + gp_sd ** 2
        if discrepancy_sd is not None and len(self.groups):
            delta = np.where(group[None, :] >= 0, np.asarray(discrepancy_sd)[:, np.maximum(group, 0)], 0.0)
            var = var + delta ** 2
        s = np.sqrt(var)
        measured = np.isfinite(value)[None, :]
        gauss = -0.5 * ((mean - np.nan_to_num(value)[None, :]) ** 2 / var + np.log(2.0 * np.pi * var))
        bound = (np.where(np.isfinite(lower)[None, :], log_ndtr((mean - lower[None, :]) / s), 0.0)
                 + np.where(np.isfinite(upper)[None, :], log_ndtr((upper[None, :] - mean) / s), 0.0))
        return np.where(measured, gauss, bound)

    def __call__(self, u: np.ndarray, discrepancy_sd: np.ndarray | None = None) -> np.ndarray:
        """The log-likelihood at points ``u`` (n, d): (n,)."""
        return np.sum(self.terms(u, discrepancy_sd), axis=1)

    def misfit(self, u: np.ndarray) -> np.ndarray:
        """-2 log-likelihood without discrepancy and without the normalising constants: the chi-square of the
        measured values plus -2 log Phi of the bounds (0 deep inside a bound), at points ``u`` (n, d): (n,)."""
        value, lower, upper, sd, _ = self._arrays
        mean, gp_sd = self.predict(u)
        var = sd[None, :] ** 2 + gp_sd ** 2
        s = np.sqrt(var)
        measured = np.isfinite(value)[None, :]
        chi2 = (mean - np.nan_to_num(value)[None, :]) ** 2 / var
        bound = -2.0 * (np.where(np.isfinite(lower)[None, :], log_ndtr((mean - lower[None, :]) / s), 0.0)
                        + np.where(np.isfinite(upper)[None, :], log_ndtr((upper[None, :] - mean) / s), 0.0))
        return np.sum(np.where(measured, chi2, bound), axis=1)

    def subset(self, labels: Sequence[str]) -> "Likelihood":
        """The same model on some of the observables."""
        return Likelihood(self.surrogate, tuple(o for o in self.observables if o.label in labels), self.groups)


def half_normal_log_prior(sigma: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Log density (up to a constant) of independent half-normal priors of scales ``scale`` (G,) at ``sigma`` (n, G):
    -inf where any sigma < 0."""
    sigma = np.atleast_2d(sigma)
    out = -0.5 * np.sum((sigma / scale[None, :]) ** 2, axis=1)
    return np.where(np.all(sigma >= 0.0, axis=1), out, -np.inf)
