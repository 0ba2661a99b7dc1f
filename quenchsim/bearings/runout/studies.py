"""Parameter studies with the run-out models (reference sec. 2 and 3): which lines each waviness
order excites for Z = 3..20, ball diameter differences placed adjacent or opposite, all balls
wavy with phase differences, and unequal ball spacing against the axial load.

Each study takes a base case dictionary (the TOML layout of :mod:`quenchsim.bearings.runout.case`,
without imperfections) and returns plain records for tables and plots.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any

import numpy as np

from quenchsim.bearings.runout.analysis import run, simulate, spectra_and_peaks
from quenchsim.bearings.runout.case import parse_case

# Bearing and operation of the 3-D reference's standard model (sec. 3, Table 1), with the
# contact angle fixed; Z balls of 1 mm fit on the 7 mm pitch circle up to Z = 21.
STANDARD_3D: dict[str, Any] = {
    "bearing": {"pitch_diameter_mm": 7.0, "ball_diameter_mm": 1.0, "balls": 8, "radial_clearance_um": 10.0,
                "youngs_modulus_Pa": 2.08e11, "poisson": 0.3},
    "operation": {"rotating": "outer", "speed_rpm": 5400, "axial_load_N": 20.0, "revolutions": 72, "samples": 4096},
}
# 695 bearing of the 2-D reference (sec. 2, Table 2): inner rotating, 7.8 N, 1 deg steps, 10 revolutions.
BEARING_695: dict[str, Any] = {
    "bearing": {"pitch_diameter_mm": 9.0, "ball_diameter_mm": 2.0, "balls": 8, "contact_angle_deg": 19.8},
    "operation": {"rotating": "inner", "speed_rpm": 1800, "axial_load_N": 7.8, "revolutions": 10, "step_deg": 1.0},
}


@dataclass(frozen=True)
class LineRecord:
    """One line of a single-waviness run: amplitude ratio = line p-p / waviness p-p."""

    balls: int
    part: str
    order: int
    direction: str
    order_per_rev: float
    amplitude_ratio: float
    source: str


def _with(base: dict[str, Any], model: str, **changes: Any) -> dict[str, Any]:
    data = copy.deepcopy(base)
    data["model"] = model
    for key, value in changes.items():
        if key in ("balls", "contact_angle_deg", "radial_clearance_um"):
            data["bearing"][key] = value
        elif key in ("axial_load_N", "revolutions", "samples", "rotating", "speed_rpm"):
            data["operation"][key] = value
        else:
            data[key] = value
    if "contact_angle_deg" in changes:
        data["bearing"].pop("radial_clearance_um", None)
    if model != "linear2d":
        data["bearing"].pop("ball_spring_N_per_m", None)
    return data


def frequency_map(base: dict[str, Any], balls: range, orders: range, parts: tuple[str, ...] = ("inner", "outer", "ball"),
                  model: str = "linear2d", amplitude_um_pp: float = 0.01) -> list[LineRecord]:
    """Lines (radial whirl and axial) produced by one waviness of each order on each part, for each
    number of balls: the reference's bubble charts / frequency tables."""
    out = []
    for z in balls:
        for part in parts:
            for order in orders:
                w = {"part": part, "order": order, "amplitude_um_pp": amplitude_um_pp}
                if part == "ball":
                    w["ball"] = 0
                case = parse_case(_with(base, model, balls=z, waviness=[w]))
                _, peaks, _ = spectra_and_peaks(case, simulate(case))
                out += [LineRecord(z, part, order, p.direction, p.order_per_rev,
                                   p.amplitude_pp_m / (amplitude_um_pp * 1e-6), p.source)
                        for p in peaks if p.direction in ("radial", "axial")]
    return out


def ball_groups(balls: int, count: int) -> dict[str, list[int]]:
    """Placements of `count` balls with a diameter difference: adjacent, and spread as evenly as
    possible around the bearing ("opposite" for two)."""
    spread = sorted({int(round(i * balls / count)) % balls for i in range(count)})
    return {"adjacent": list(range(count)), "spread": spread}


def diameter_difference_study(base: dict[str, Any], deviation_um: float, counts: tuple[int, ...] = (1, 2, 3, 4),
                              models: tuple[str, ...] = ("linear2d", "hertz3d")) -> list[dict[str, Any]]:
    """Maximum radial run-out (p-p) with `count` balls larger by deviation_um, adjacent vs spread.

    Linear closed form for comparison (reference sec. 2 ratio 4/Z for one ball): the orbit is a
    circle of diameter (4/Z) dD |sum_j exp(i theta_j)| over the larger balls."""
    z = base["bearing"]["balls"]
    rows = []
    for count in counts:
        for placement, group in ball_groups(z, count).items():
            if count == 1 and placement == "spread":
                continue
            closed = 4.0 / z * deviation_um * abs(np.exp(2j * np.pi * np.array(group) / z).sum())
            row = {"balls_larger": count, "placement": placement, "balls": group, "linear_closed_form_um": closed}
            for model in models:
                dev = [{"ball": j, "deviation_um": deviation_um} for j in group]
                result = run(parse_case(_with(base, model, ball_diameter_deviation=dev)))
                row[f"{model}_radial_um"] = result.runout_pp_m["radial"] * 1e6
                row[f"{model}_axial_um"] = result.runout_pp_m["axial"] * 1e6
            rows.append(row)
    return rows


def phase_patterns(balls: int, seed: int = 7) -> dict[str, np.ndarray]:
    """Phase of the same waviness on every ball: equal, random (fixed seed), progressing by one
    and by two turns around the ball set."""
    rng = np.random.default_rng(seed)
    j = np.arange(balls)
    return {"equal phases": np.zeros(balls), "random phases": rng.uniform(0.0, 360.0, balls),
            "phase step 360/Z": 360.0 * j / balls, "phase step 720/Z": 720.0 * j / balls}


def wavy_balls_study(base: dict[str, Any], order: int, amplitude_um_pp: float,
                     model: str = "linear2d") -> list[dict[str, Any]]:
    """All balls with the same waviness order and amplitude, phases per :func:`phase_patterns`:
    run-out and the lines at order f_b (axial) and order f_b -+ f_c (radial whirl).

    Linear expectation: the axial line adds the balls as |sum_j exp(i phi_j)|, the radial
    sidebands order f_b - f_c and order f_b + f_c as |sum_j exp(i (phi_j + theta_j))| and
    |sum_j exp(i (phi_j - theta_j))| (theta_j = 2 pi j / Z; a ball's diameter varies as
    cos(order psi - phi_j) while it whirls with exp(i theta_j(t)))."""
    z = base["bearing"]["balls"]
    rows = []
    for name, phases in phase_patterns(z).items():
        w = [{"part": "ball", "ball": j, "order": order, "amplitude_um_pp": amplitude_um_pp, "phase_deg": float(ph)}
             for j, ph in enumerate(phases)]
        result = run(parse_case(_with(base, model, waviness=w)))
        f = result.frequencies
        tol = 0.5 / result.case.duration_s
        lines = {}
        for label, direction, freq in (("axial_kfb", "axial", order * f.ball_spin_hz),
                                       ("radial_kfb_minus_fc", "radial", order * f.ball_spin_hz - f.cage_hz),
                                       ("radial_kfb_plus_fc", "radial", order * f.ball_spin_hz + f.cage_hz)):
            found = [p.amplitude_pp_m for p in result.peaks
                     if p.direction == direction and abs(abs(p.frequency_hz) - freq) < tol]
            lines[label + "_um"] = (found[0] if found else 0.0) * 1e6
        th = 2.0 * np.pi * np.arange(z) / z
        ph = np.radians(phases)
        rows.append({"pattern": name, "phases_deg": [round(float(p), 1) for p in phases],
                     "radial_runout_um": result.runout_pp_m["radial"] * 1e6,
                     "axial_runout_um": result.runout_pp_m["axial"] * 1e6, **lines,
                     "sum_axial": float(abs(np.exp(1j * ph).sum())),
                     "sum_minus": float(abs(np.exp(1j * (ph + th)).sum())),
                     "sum_plus": float(abs(np.exp(1j * (ph - th)).sum()))})
    return rows


def spacing_study(base: dict[str, Any], loads_N: np.ndarray, arrangements: dict[str, tuple[int, list[float]]],
                  models: tuple[str, ...] = ("linear2d", "hertz3d")) -> list[dict[str, Any]]:
    """Radial run-out against axial load for unequal ball spacing; arrangements maps a name to
    (balls, position error in deg of each ball)."""
    rows = []
    for name, (z, errors) in arrangements.items():
        for load in loads_N:
            row = {"arrangement": name, "axial_load_N": float(load)}
            for model in models:
                pos = [{"ball": j, "angle_deg": e} for j, e in enumerate(errors) if e]
                result = run(parse_case(_with(base, model, balls=z, axial_load_N=float(load),
                                              ball_position_error=pos)))
                row[f"{model}_radial_um"] = result.runout_pp_m["radial"] * 1e6
            rows.append(row)
    return rows


def crown_cage_errors(pockets: int, balls: int) -> list[float]:
    """Position errors (deg) of `balls` balls sitting in the first `balls` of `pockets` equally
    spaced pockets, relative to `balls` equally spaced positions."""
    return [j * (360.0 / pockets - 360.0 / balls) for j in range(balls)]
