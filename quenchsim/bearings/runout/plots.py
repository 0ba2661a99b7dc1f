"""Plots of one run: ring-centre orbit (Lissajous figure) and the run-out spectra (matplotlib, Agg)."""

from __future__ import annotations

import pathlib


from quenchsim.bearings.runout.analysis import RunoutResult
from quenchsim.figures import save, subplots

_NM = 1e9


def orbit_plot(result: RunoutResult, path: pathlib.Path, title: str = "") -> pathlib.Path:
    """x-y orbit of the free ring's centre (nm) and z(t)."""
    tr = result.trajectory
    fig, (ax, az) = subplots(1, 2, figsize=(10, 4.4), gridspec_kw={"width_ratios": [1, 1.4]})
    ax.plot((tr.x_m - tr.x_m.mean()) * _NM, (tr.y_m - tr.y_m.mean()) * _NM, lw=0.6)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [nm]")
    ax.set_ylabel("y [nm]")
    ax.set_title(f"orbit, radial run-out {result.runout_pp_m['radial'] * _NM:.3g} nm p-p")
    az.plot(tr.time_s, (tr.z_m - tr.z_m.mean()) * _NM, lw=0.6)
    az.set_xlabel("t [s]")
    az.set_ylabel("axial - mean [nm]")
    az.set_title(f"axial run-out {result.runout_pp_m['axial'] * _NM:.3g} nm p-p")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save(fig, path)
    return path


def spectrum_plot(result: RunoutResult, path: pathlib.Path, title: str = "", label_peaks: int = 8) -> pathlib.Path:
    """Whirl (radial) and axial p-p spectra against order per revolution of the rotating ring,
    with the strongest identified lines labelled by their kinematic source."""
    fr = result.case.speed_hz
    fig, axes = subplots(2, 1, figsize=(10, 6.5))
    for ax, name in zip(axes, ("radial", "axial")):
        s = result.spectra[name]
        ax.plot(s.frequency_hz / fr, s.amplitude_pp_m * _NM, lw=0.7)
        peaks = sorted((p for p in result.peaks if p.direction == name), key=lambda p: -p.amplitude_pp_m)
        for p in peaks[:label_peaks]:
            ax.annotate(p.source, (p.order_per_rev, p.amplitude_pp_m * _NM), fontsize=7, rotation=60,
                        xytext=(2, 4), textcoords="offset points")
        ax.set_ylabel(f"{name} [nm p-p]")
        ax.set_xlabel("frequency / rotating-ring speed" + (" (negative: backward whirl)" if name == "radial" else ""))
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save(fig, path)
    return path
