"""Plot of a free-run (coast-down) analysis: speed from the pulse periods and the method's slope series.
matplotlib is imported inside the function only."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from quenchsim.bearings import free_run as fr
from quenchsim.figures import save, subplots


def plot_free_run(pulse_times_s: np.ndarray, result: fr.FreeRunResult, path: pathlib.Path) -> pathlib.Path:
    """Two panels: omega(t) from the pulse periods (with the model curve for the model method) and
    the method's slope series (omega'(n) or omega'(t)) with the retained window and its line fit."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    s = fr.speed_samples(pulse_times_s)
    d = result.detail

    fig, (ax1, ax2) = subplots(1, 2, figsize=(11, 4))
    ax1.plot(s.t_s, s.omega_rad_s, ".", ms=2, label="2 pi / period")
    if d.method == "model":
        theta = 2.0 * math.pi * np.arange(pulse_times_s.size)
        assert d.law is not None   # the model method always returns its fitted law
        t_model = fr.model_pulse_times(theta, d.omega0_rad_s, d.law, 0.5 * float(s.omega_rad_s.min()),
                                       3 * pulse_times_s.size)
        w_model = 2.0 * math.pi / np.diff(t_model)
        ax1.plot(0.5 * (t_model[1:] + t_model[:-1]), w_model, "-", lw=1, label="model fit")
    ax1.set_xlabel("t (s)")
    ax1.set_ylabel("omega (rad/s)")
    ax1.legend()
    ax1.set_title(f"free run: {pulse_times_s.size} pulses")
    x, y, keep = d.slope_x, d.slope_rad_s2, d.retained
    if d.method == "model":
        fd = np.diff(s.omega_rad_s) / np.diff(s.t_s)
        ax2.plot(s.t_s[:-1], fd, ".", ms=2, color="0.6", label="finite differences (for reference)")
        ax2.plot(x, y, "-", lw=1.5, label="fitted law: omega' = -g(omega(t))")
        ax2.set_ylim(1.5 * float(y.min()), 0.0)
    else:
        ax2.plot(x[~keep], y[~keep], ".", ms=2, color="0.6", label="not retained")
        ax2.plot(x[keep], y[keep], ".", ms=2, label="retained")
        p, q = d.line
        xs = (np.linspace(0.0, float(x.max()), 200) if d.method == "t-omega"
              else np.geomspace(1.0, float(x.max()), 200))
        ax2.plot(xs, p + q * xs, "-", lw=1, label="line fit (value at t = 0 / n = 1)")
    ax2.set_xlabel("n (samples)" if d.method == "n-omega" else "t (s)")
    ax2.set_ylabel("omega' (rad/s^2)")
    ax2.set_title(f"{d.method}: T = {result.torque_Nm:.5g} N m")
    if d.method == "n-omega":
        ax2.set_xscale("log")
    ax2.legend()
    fig.tight_layout()
    save(fig, path)
    return path

