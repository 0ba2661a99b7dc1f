"""Plots of the fitters (matplotlib is imported inside each function only)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from quenchsim.fitting.quenchant import TIME_TEMPERATURE, ProbeFit


def plot_probe_fit(fit: ProbeFit, path: Path, title: str) -> Path:
    """Probe curve vs the re-simulated curve (temperature-time and rate-temperature) and the fitted h(T_s)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    t, Tc = fit.curve.time_s, fit.curve.centre_C
    rate = -np.gradient(Tc, t)
    axes[0].plot(t, Tc, "-", label="re-simulated (probe model)")
    axes[1].plot(Tc, rate, "-", label="re-simulated")
    if fit.data is not None and fit.data.kind == TIME_TEMPERATURE:
        axes[0].plot(fit.data.time_s, fit.data.temperature_C, ".", ms=3, label="probe curve (data)")
        axes[1].plot(fit.data.temperature_C, -np.gradient(fit.data.temperature_C, fit.data.time_s), ".", ms=3,
                     label="probe curve (data)")
    elif fit.data is not None:
        axes[1].plot(fit.data.temperature_C, fit.data.rate_C_s, ".", ms=3, label="probe curve (data)")
    if "CRmax_C_s" in fit.measured:
        axes[1].plot([fit.measured["T_CRmax_C"]], [fit.measured["CRmax_C_s"]], "k*", ms=10, label="published maximum")
        axes[1].plot([300.0], [fit.measured["CR300_C_s"]], "kx", ms=8, label="published rate at 300 C")
    for key, T in (("t_to_600C_s", 600.0), ("t_to_400C_s", 400.0), ("t_to_200C_s", 200.0)):
        if key in fit.measured and fit.data is None:
            axes[0].plot([fit.measured[key]], [T], "k*", ms=8)
    axes[0].set(xlabel="time (s)", ylabel="centre temperature (C)", title="probe centre")
    axes[1].set(xlabel="centre temperature (C)", ylabel="cooling rate (C/s)", title="cooling rate")
    axes[1].invert_xaxis()
    axes[2].plot(fit.T_C, fit.h_W_m2K, "o-")
    if np.all(np.isfinite(fit.h_std_W_m2K)):
        axes[2].fill_between(fit.T_C, fit.h_W_m2K - 2 * fit.h_std_W_m2K, fit.h_W_m2K + 2 * fit.h_std_W_m2K, alpha=0.3,
                             label="+-2 sigma (linearised)")
    axes[2].axvspan(*fit.identified_C, color="0.9", zorder=0, label="surface range seen by the data")
    axes[2].set(xlabel="surface temperature (C)", ylabel="h (W/m2K)", title=f"h(T_s), bath {fit.bath_C:g} C")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
