"""The surrogate of the full chain: one Gaussian process per measured quantity over the unit cube of the inputs.

scikit-learn's ``GaussianProcessRegressor`` (Rasmussen & Williams, *Gaussian Processes for Machine
Learning*, MIT Press 2006, ch. 2, 4 and 5): a constant times an anisotropic Matern kernel of smoothness 5/2 (one
length scale per input, so an input the quantity does not depend on gets a long one; twice differentiable, where
the squared exponential is infinitely smooth: the chain's responses bend at regime changes -- a vapour film's
collapse, a wall that hardens through -- and ring A's held-back errors were 5-30 % lower with it) plus a small white
noise for the run-to-run scatter of an adaptive-step solver, hyper-parameters by maximum marginal
likelihood with restarts, targets normalised. Its predictive standard deviation is the surrogate's own
error, added to the measurement's in the likelihood; :func:`holdout_check` measures it on runs the
surrogate never saw.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

RESTARTS = 4
"""Optimiser restarts of the marginal likelihood (from random length scales): the optimum is multimodal."""
Z_90 = 1.6448536269514722
"""The standard normal's 95 % quantile: mean +- Z_90 sd holds 90 %."""


class FastGP:
    """The prediction of a fitted ``GaussianProcessRegressor`` of this module's kernel (constant x anisotropic
    Matern 5/2 + white noise, targets normalised), without scikit-learn's per-call checks: the same formulas
    (Rasmussen & Williams, Algorithm 2.1: mean k*^T alpha, variance k(x, x) - |L^-1 k*|^2, the white noise included
    as in scikit-learn's ``kernel_.diag``; eq. 4.17: k(r) = c (1 + sqrt(5) r + 5 r^2 / 3) exp(-sqrt(5) r)), ~3x
    faster on the posterior sampler's small batches."""

    def __init__(self, gp: Any) -> None:
        self.fitted = gp
        """The scikit-learn model (its hyper-parameters, and the reference of :meth:`predict`)."""
        const, matern, white = gp.kernel_.k1.k1, gp.kernel_.k1.k2, gp.kernel_.k2
        self.scale = np.asarray(matern.length_scale, dtype=float)
        self.X = gp.X_train_ / self.scale
        self.amplitude = float(const.constant_value)
        self.noise = float(white.noise_level)
        self.alpha = np.asarray(gp.alpha_, dtype=float).ravel()
        self.L = np.asarray(gp.L_, dtype=float)
        self.y_mean = float(np.ravel(gp._y_train_mean)[0])
        self.y_std = float(np.ravel(gp._y_train_std)[0])

    def predict(self, u: np.ndarray, return_std: bool = False) -> Any:
        from scipy.linalg import solve_triangular

        x = np.atleast_2d(u) / self.scale
        sq = np.sum(x ** 2, axis=1)[:, None] + np.sum(self.X ** 2, axis=1)[None, :] - 2.0 * x @ self.X.T
        r5 = np.sqrt(5.0 * np.maximum(sq, 0.0))
        k = self.amplitude * (1.0 + r5 + r5 ** 2 / 3.0) * np.exp(-r5)
        mean = k @ self.alpha * self.y_std + self.y_mean
        if not return_std:
            return mean
        v = solve_triangular(self.L, k.T, lower=True, check_finite=False)
        var = self.amplitude + self.noise - np.sum(v ** 2, axis=0)
        return mean, np.sqrt(np.maximum(var, 0.0)) * self.y_std


@dataclass
class Surrogate:
    """Fitted Gaussian processes by quantity name."""

    models: dict[str, Any]
    n_train: int

    def predict(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Mean and standard deviation, shape (n points, n quantities) each, at unit-cube points ``u`` (n, d)."""
        u = np.atleast_2d(u)
        means, sds = [], []
        for model in self.models.values():
            m, s = model.predict(u, return_std=True)
            means.append(m)
            sds.append(s)
        return np.column_stack(means), np.column_stack(sds)


def fit_surrogate(u: np.ndarray, y: dict[str, np.ndarray], seed: int = 0) -> Surrogate:
    """One GP per column of ``y`` (quantity -> values at the points ``u``, shape (n, d))."""
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel

    d = u.shape[1]
    models = {}
    for name, values in y.items():
        kernel = (ConstantKernel(1.0, (1e-3, 1e3))
                  * Matern(length_scale=np.full(d, 0.5), length_scale_bounds=(0.03, 30.0), nu=2.5)
                  + WhiteKernel(1e-4, (1e-8, 1e-1)))
        gp = GaussianProcessRegressor(kernel=kernel, normalize_y=True, n_restarts_optimizer=RESTARTS, random_state=seed)
        with warnings.catch_warnings():   # a length scale at its bound: the quantity ignores that input (expected)
            warnings.simplefilter("ignore", ConvergenceWarning)
            gp.fit(u, values)
        models[name] = FastGP(gp)
    return Surrogate(models=models, n_train=len(u))


def holdout_check(surrogate: Surrogate, u: np.ndarray, y: dict[str, np.ndarray]) -> dict[str, dict[str, float]]:
    """The surrogate against held-back runs, per quantity: RMS and largest error, and the share of the runs
    inside the surrogate's own 90 % band (near 0.9 when its stated error is honest)."""
    mean, sd = surrogate.predict(u)
    out = {}
    for j, name in enumerate(surrogate.models):
        err = mean[:, j] - y[name]
        out[name] = {"rms_error": float(np.sqrt(np.mean(err ** 2))), "max_abs_error": float(np.max(np.abs(err))),
                     "mean_stated_sd": float(np.mean(sd[:, j])),
                     "inside_own_90pct_band": float(np.mean(np.abs(err) <= Z_90 * sd[:, j])), "n": int(len(err))}
    return out
