"""Run a run-out case: solve the chosen model, then spectra, identified peaks, run-out and NRRO.

Run-out (p-p) of the ring-centre orbit:
    radial  = largest width of the orbit over all directions, max_phi ptp(x cos phi + y sin phi)
    axial   = ptp(z)
NRRO: the same after removing the repeatable run-out, i.e. the least-squares fit of the harmonics
k f_r (k = 0 .. below Nyquist) of the rotating ring's speed (the part that repeats every
revolution of the rotating ring; exact synchronous averaging when the run covers whole revolutions).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from quenchsim.bearings import kinematics
from quenchsim.bearings.runout import hertz3d, linear2d
from quenchsim.bearings.runout.case import RunoutCase
from quenchsim.bearings.runout.equilibrium import Trajectory
from quenchsim.bearings.runout.excitation import kinematic_frequencies
from quenchsim.bearings.runout.matching import matcher_for
from quenchsim.bearings.runout.spectra import Spectrum, find_peaks, spectrum, whirl_spectrum

# Lines below this p-p amplitude are never listed: 100 x the Newton step tolerance of the
# equilibrium solver (numerical noise of the ring-centre history).
ABSOLUTE_FLOOR_M = 1.0e-13
# Directions over which the orbit width (radial run-out) is maximised.
_DIRECTIONS = 360


@dataclass(frozen=True)
class LinePeak:
    """An identified line: direction x | y | radial (whirl of x + i y, signed frequency) | axial."""

    direction: str
    frequency_hz: float
    order_per_rev: float
    amplitude_pp_m: float
    source: str
    whirl: str | None = None


@dataclass(frozen=True)
class RunoutResult:
    """Everything one run produces."""

    case: RunoutCase
    trajectory: Trajectory
    frequencies: kinematics.BearingFrequencies
    spectra: dict[str, Spectrum]
    peaks: list[LinePeak]
    runout_pp_m: dict[str, float]
    nrro_pp_m: dict[str, float]
    wall_time_s: float


def simulate(case: RunoutCase) -> Trajectory:
    """Ring-centre history from the case's model."""
    return (linear2d if case.model == "linear2d" else hertz3d).solve(case)


def orbit_width_m(x: np.ndarray, y: np.ndarray) -> float:
    """max over directions phi of ptp(x cos phi + y sin phi)."""
    phi = np.linspace(0.0, np.pi, _DIRECTIONS, endpoint=False)
    proj = np.outer(x, np.cos(phi)) + np.outer(y, np.sin(phi))
    return float(np.ptp(proj, axis=0).max())


def repeatable_part(signal: np.ndarray, time_s: np.ndarray, rotating_hz: float) -> np.ndarray:
    """Least-squares fit of sum_k (a_k cos + b_k sin)(2 pi k f_r t), k = 0 .. below Nyquist.

    Over a whole number R of revolutions the harmonics are the DFT bins k R (orthogonal), so the
    fit is the inverse DFT of those bins; otherwise the normal equations are solved."""
    n = signal.size
    duration = n * (time_s[1] - time_s[0])
    revolutions = duration * rotating_hz
    if abs(revolutions - round(revolutions)) < 1e-9:
        r = int(round(revolutions))
        spec = np.fft.rfft(signal)
        keep = np.zeros(spec.size, dtype=bool)
        keep[::r] = True
        return np.fft.irfft(np.where(keep, spec, 0.0), n)
    kmax = int(np.floor(0.5 * n / revolutions - 1e-9))
    arg = 2.0 * np.pi * rotating_hz * np.outer(time_s, np.arange(1, kmax + 1))
    basis = np.hstack([np.ones((n, 1)), np.cos(arg), np.sin(arg)])
    coef = np.linalg.solve(basis.T @ basis, basis.T @ signal)
    return basis @ coef


def spectra_and_peaks(case: RunoutCase, trajectory: Trajectory
                      ) -> tuple[dict[str, Spectrum], list[LinePeak], kinematics.BearingFrequencies]:
    """Spectra of x, y, the whirl x + i y ("radial") and z ("axial"), and their lines above
    case.peak_threshold_rel x the strongest line (and ABSOLUTE_FLOOR_M), each with its kinematic source."""
    f = kinematic_frequencies(case)
    T = case.duration_s
    tr = trajectory
    spectra = {"x": spectrum(tr.x_m, T, "x"), "y": spectrum(tr.y_m, T, "y"),
               "radial": whirl_spectrum(tr.x_m, tr.y_m, T), "axial": spectrum(tr.z_m, T, "axial")}
    strongest = max(float(s.amplitude_pp_m[np.abs(s.frequency_hz) > 1.5 * s.bin_hz].max(initial=0.0))
                    for s in spectra.values())
    threshold = max(case.peak_threshold_rel * strongest, ABSOLUTE_FLOOR_M)
    orders = {part: [w.order for w in case.waviness if w.part == part] for part in ("inner", "outer", "ball")}
    fixed = "outer" if case.rotating == "inner" else "inner"
    matcher = matcher_for(case.speed_hz, f.cage_hz, f.ball_spin_hz, case.rotating, orders[case.rotating],
                          orders[fixed], orders["ball"], case.balls, 1.0 / T)
    peaks = []
    for name, s in spectra.items():
        signed = name == "radial"
        for p in find_peaks(s, threshold):
            # whirl lines are matched with their sign, labelled by their magnitude
            m = matcher.match(p.frequency_hz, signed)
            if m is not None and p.frequency_hz < 0:
                m = matcher.match(-p.frequency_hz, True)
            whirl = None if not signed else ("forward" if p.frequency_hz > 0 else "backward")
            peaks.append(LinePeak(name, p.frequency_hz, p.frequency_hz / case.speed_hz, p.amplitude_pp_m,
                                  "unmatched" if m is None else m.label, whirl))
    return spectra, peaks, f


def analyse(case: RunoutCase, trajectory: Trajectory, wall_time_s: float = 0.0) -> RunoutResult:
    """Spectra, peaks with their kinematic source, run-out and NRRO of a ring-centre history."""
    tr = trajectory
    spectra, peaks, f = spectra_and_peaks(case, tr)
    xr, yr, zr = (v - repeatable_part(v, tr.time_s, case.speed_hz) for v in (tr.x_m, tr.y_m, tr.z_m))
    return RunoutResult(case=case, trajectory=tr, frequencies=f, spectra=spectra, peaks=peaks,
                        runout_pp_m={"radial": orbit_width_m(tr.x_m, tr.y_m), "axial": float(np.ptp(tr.z_m))},
                        nrro_pp_m={"radial": orbit_width_m(xr, yr), "axial": float(np.ptp(zr))},
                        wall_time_s=wall_time_s)


def run(case: RunoutCase) -> RunoutResult:
    """Solve and analyse a case; wall_time_s is the solver time (excitation + equilibrium)."""
    t0 = time.perf_counter()
    tr = simulate(case)
    return analyse(case, tr, time.perf_counter() - t0)
