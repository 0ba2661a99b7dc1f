"""Plots of the fitters: fitted kinetics against the data they were fitted to (CCT overlay, TTT diagram, Jominy
curve) and a probe fit against its ISO 9950 curve.

figures are drawn without pyplot (quenchsim.figures), so importing this module loads no plotting backend.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from quenchsim.figures import save, subplots
from quenchsim.fitting.diagram_data import CoolingCurve, DiagramData, JominyPoint
from quenchsim.fitting.kinetics import X_FINISH, X_START, run_curves
from quenchsim.fitting.quenchant import TIME_TEMPERATURE, ProbeFit
from quenchsim.metallurgy import Kinetics
from quenchsim.metallurgy.cct import cct_diagram

COLOURS = {"pearlite": "tab:red", "bainite": "tab:blue", "ferrite": "tab:green", "martensite": "k"}


def _time_at(curve: CoolingCurve, T_C: float) -> float:
    """Time at which a cooling curve passes T_C."""
    if curve.newtonian:
        return float(curve.theta_s * np.log((curve.T_start_C - curve.T_end_C) / (T_C - curve.T_end_C)))
    return (curve.T_start_C - T_C) / curve.rate_C_s


def plot_cct_overlay(kin: Kinetics, data: DiagramData | None, path: Path,
                     rates_C_s: Sequence[float] = tuple(np.logspace(-1, 3, 33))) -> Path:
    """The model's CCT lines (linear cooling from T_aust) with the data's cooling curves, start/finish points (filled:
    data, open: model on the same curve) and final fractions (data / model) written at the curve's foot."""

    d = cct_diagram(kin, np.asarray(rates_C_s), kin.T_aust_C)
    fig, ax = subplots(figsize=(8.5, 6.0))
    for p in kin.reactions:
        ax.plot(d.start_time_s[p], d.start_T_C[p], "-", color=COLOURS[p], lw=1.8, label=f"model {p} 1 %")
        ax.plot(d.finish_time_s[p], d.finish_T_C[p], "--", color=COLOURS[p], lw=1.2, label=f"model {p} 99 % of final")
    ax.axhline(kin.Ms_C, color="k", lw=1.0, ls="-.", label=f"model Ms = {kin.Ms_C:.0f} C")
    if data is not None and data.cct:
        res = run_curves(kin, [p.curve for p in data.cct])
        for i, point in enumerate(data.cct):
            c = point.curve
            t = np.logspace(-2, np.log10(c.duration_s()), 200)
            ax.plot(t, c.temperature_C(t), color="0.8", lw=0.7, zorder=0)
            for line, table, marker, model in (("start", point.start_C, "o", res.start_T_C),
                                               ("finish", point.finish_C, "s", res.finish_T_C)):
                for phase, T in table.items():
                    ax.plot(_time_at(c, T), T, marker, color=COLOURS[phase], ms=6)
                    if phase in model and np.isfinite(model[phase][i]):
                        Tm = float(model[phase][i])
                        ax.plot(_time_at(c, Tm), Tm, marker, color=COLOURS[phase], ms=8, mfc="none")
            if point.fractions:
                text = ", ".join(f"{p[0].upper()} {x:.2f}/{float(res.fractions[p][i]) if p in res.fractions else float('nan'):.2f}"
                                 for p, x in point.fractions.items())
                T_foot = c.T_end_C + 60.0
                ax.annotate(text, (_time_at(c, T_foot), T_foot), fontsize=6, rotation=-70, color="0.3")
    ax.set_xscale("log")
    ax.set_xlim(0.1, 3e4)
    ax.set_ylim(0.0, kin.T_aust_C + 20.0)
    ax.set_xlabel("time from the austenitising temperature (s)")
    ax.set_ylabel("temperature (C)")
    title = f"{kin.material}: model CCT (T_aust {kin.T_aust_C:g} C)"
    ax.set_title(title + (f" and {data.name}" if data is not None else ""), fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7, loc="upper right")
    fig.text(0.01, 0.01, "filled: data; open: model on the same cooling curve; fractions data/model", fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save(fig, path, dpi=120)
    return path


def ttt_lines(kin: Kinetics, T_C: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Isothermal 1 % and 99 % times of each reaction at T_C (inf where it cannot run)."""
    return {p: (r.isothermal_time_s(X_START, T_C), r.isothermal_time_s(X_FINISH, T_C)) for p, r in kin.reactions.items()}


def plot_ttt(kin: Kinetics, data: DiagramData | None, path: Path) -> Path:
    """The model's TTT diagram (1 % and 99 % of each reaction, Ms) with the data's TTT points."""

    fig, ax = subplots(figsize=(7.5, 6.0))
    T = np.linspace(max(kin.Ms_C - 40.0, 20.0), max(r.T_upper_C for r in kin.reactions.values()), 300)
    for p, (ts, tf) in ttt_lines(kin, T).items():
        ok = np.isfinite(ts)
        ax.plot(ts[ok], T[ok], "-", color=COLOURS[p], lw=1.8, label=f"model {p} 1 %")
        ax.plot(tf[ok], T[ok], "--", color=COLOURS[p], lw=1.2, label=f"model {p} 99 %")
    ax.axhline(kin.Ms_C, color="k", lw=1.0, ls="-.", label=f"Ms = {kin.Ms_C:.0f} C")
    if data is not None:
        for pt in data.ttt:
            ax.plot(pt.t_start_s, pt.T_C, "o", color=COLOURS[pt.phase], ms=5)
            ax.plot(pt.t_finish_s, pt.T_C, "s", color=COLOURS[pt.phase], ms=5, mfc="none")
    ax.set_xscale("log")
    ax.set_xlim(0.1, 1e5)
    ax.set_xlabel("isothermal time (s)")
    ax.set_ylabel("temperature (C)")
    ax.set_title(f"{kin.material}: model TTT" + (f" and {data.name}" if data is not None else ""), fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save(fig, path, dpi=120)
    return path


def plot_jominy(distance_mm: np.ndarray | Sequence[float], model_HRC: np.ndarray, points: Sequence[JominyPoint], path: Path,
                title: str, limits: Sequence[tuple[float, float, str]] = ()) -> Path:
    """Model Jominy curve (HRC vs distance from the quenched end) with data points and optional (distance, HRC, label)
    limits (e.g. a standard's minimum)."""

    from quenchsim.metallurgy import hv_to_hrc

    fig, ax = subplots(figsize=(7.0, 4.5))
    ax.plot(distance_mm, model_HRC, "-", color="tab:purple", label="model")
    if points:
        ax.plot([p.distance_mm for p in points], hv_to_hrc(np.array([p.hardness_HV for p in points])), "o", color="k",
                label="data")
    for d, hrc, label in limits:
        ax.plot(d, hrc, "^", color="tab:red", ms=8, label=label)
    ax.set_xlabel("distance from the quenched end (mm)")
    ax.set_ylabel("HRC")
    ax.set_title(title, fontsize=9)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save(fig, path, dpi=120)
    return path


def plot_probe_fit(fit: ProbeFit, path: Path, title: str) -> Path:
    """Probe curve vs the re-simulated curve (temperature-time and rate-temperature) and the fitted h(T_s)."""
    fig, axes = subplots(1, 3, figsize=(15, 4.5))
    t, Tc = fit.curve.time_s, fit.curve.centre_C
    rate = -np.gradient(Tc, t)
    axes[0].plot(t, Tc, "-", label="re-simulated (probe model)")
    axes[1].plot(Tc, rate, "-", label="re-simulated")
    if fit.data is not None and fit.data.kind == TIME_TEMPERATURE:
        axes[0].plot(fit.data.time_s, fit.data.temperature_C, ".", ms=3, label="probe curve (data)")
        axes[1].plot(fit.data.temperature_C, -np.gradient(fit.data.temperature_C, fit.data.times_s), ".", ms=3,
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
    return save(fig, path)
