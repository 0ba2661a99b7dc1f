"""Run-out outputs: the ring-centre trajectory and spectra CSVs and the JSON summary of one run."""

from __future__ import annotations

import pathlib
from typing import Any

import numpy as np

from quenchsim.bearings.runout.analysis import RunoutResult

_UM = 1e6


def write_trajectory_csv(result: RunoutResult, path: pathlib.Path) -> pathlib.Path:
    """time_s, x_um, y_um (free-ring centre, fixed frame), z_um (axial approach incl. preload)."""
    tr = result.trajectory
    path.parent.mkdir(parents=True, exist_ok=True)
    data = np.column_stack([tr.time_s, tr.x_m * _UM, tr.y_m * _UM, tr.z_m * _UM])
    np.savetxt(path, data, delimiter=",", header="time_s,x_um,y_um,z_um", comments="", fmt="%.12g")
    return path


def write_spectra_csv(result: RunoutResult, directory: pathlib.Path) -> list[pathlib.Path]:
    """spectra.csv: frequency_hz and the p-p amplitude spectra (um) of x, y and z; whirl.csv: signed
    frequency_hz and the p-p whirl spectrum (um) of x + i y (positive = forward)."""
    directory.mkdir(parents=True, exist_ok=True)
    sp = result.spectra
    real = directory / "spectra.csv"
    np.savetxt(real, np.column_stack([sp["x"].frequency_hz, sp["x"].amplitude_pp_m * _UM, sp["y"].amplitude_pp_m * _UM,
                                      sp["axial"].amplitude_pp_m * _UM]),
               delimiter=",", header="frequency_hz,x_um_pp,y_um_pp,z_um_pp", comments="", fmt="%.10g")
    whirl = directory / "whirl.csv"
    np.savetxt(whirl, np.column_stack([sp["radial"].frequency_hz, sp["radial"].amplitude_pp_m * _UM]),
               delimiter=",", header="frequency_hz,radial_um_pp", comments="", fmt="%.10g")
    return [real, whirl]


def summary(result: RunoutResult, trajectory_csv: pathlib.Path | None) -> dict[str, Any]:
    """The CLI's JSON object: model, peaks (strongest first), run-out and NRRO (um p-p), kinematics."""
    f = result.frequencies
    peaks = sorted(result.peaks, key=lambda p: -p.amplitude_pp_m)
    return {
        "model": result.case.model,
        "peaks": [{"direction": p.direction, "frequency_hz": p.frequency_hz, "order_per_rev": p.order_per_rev,
                   "amplitude_um_pp": p.amplitude_pp_m * _UM, "source": p.source,
                   **({"whirl": p.whirl} if p.whirl else {})} for p in peaks],
        "runout_um_pp": {k: v * _UM for k, v in result.runout_pp_m.items()},
        "nrro_um_pp": {k: v * _UM for k, v in result.nrro_pp_m.items()},
        "kinematics_hz": {"f_r": result.case.speed_hz, "f_c": f.cage_hz, "f_b": f.ball_spin_hz,
                          "f_i": f.inner_rel_cage_hz, "f_o": f.outer_rel_cage_hz},
        "contact_angle_deg": float(np.degrees(result.case.contact_angle_rad)),
        "preload_approach_um": result.trajectory.preload_approach_m * _UM,
        "newton_iterations": result.trajectory.iterations,
        "trajectory_csv": None if trajectory_csv is None else str(trajectory_csv),
        "wall_time_s": result.wall_time_s,
    }
