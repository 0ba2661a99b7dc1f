"""Statistics of a run (after the start-up transient): the JSON keys of the `big-end` CLI."""

from __future__ import annotations

import numpy as np

from quenchsim.bearings.big_end.simulate import RunResult


def steady_mask(result: RunResult) -> np.ndarray:
    """Samples after the transient revolutions (start from the kinematic state)."""
    return result.crank_angle >= 2 * np.pi * result.transient_revolutions


def run_statistics(result: RunResult) -> dict:
    """Cage slip (mean |.|, min, max), roller orbital/spin slip (mean |.| over rollers and time),
    pocket force of one roller (max over rollers and time, time-mean |force| averaged over rollers)."""
    k = steady_mask(result)
    cage = result.cage_slip_pct[k]
    pocket = result.pocket_force_n[:, k]
    return {
        "cage_slip_pct": {"mean_abs": float(np.mean(np.abs(cage))), "min": float(cage.min()),
                          "max": float(cage.max())},
        "roller_orbital_slip_mean_abs_pct": float(np.mean(np.abs(result.roller_orbital_slip_pct[:, k]))),
        "roller_spin_slip_mean_abs_pct": float(np.mean(np.abs(result.roller_spin_slip_pct[:, k]))),
        "pocket_force_N": {"max": float(pocket.max()), "mean_abs": float(np.mean(np.abs(pocket)))},
        "revolutions": float(result.revolutions),
        "transient_revolutions_excluded": float(result.transient_revolutions),
        "wall_time_s": float(result.wall_time_s),
        "integrator": result.integrator,
        "rhs_evaluations": int(result.n_rhs),
        "mode": result.mode,
        "clearance_set": result.clearance.name,
    }
