"""`quenchsim stability RUN_DIR --temperature-C T --years Y`: the size change of a tempered part held in service.

The tempered state of the run (the last VTK frame: the phases and the tempering clock of every point) is held at the
service temperature for the given time with the same tempering kinetics (:func:`quenchsim.metallurgy.tempering.
service_change`): the retained austenite that decomposes grows the part by the steel's austenite -> bainite strain
(its stress model), the martensite's reactions shrink it. The part's size change is the volume-weighted mean of the
free strain times each dimension (a uniform free strain; the elastic accommodation of its non-uniformity is left
out), measured at room temperature.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

import numpy as np

HOURS_PER_YEAR = 8766.0


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("run_dir", type=Path, help="a run directory of a case with a [temper] (quenchsim run)")
    parser.add_argument("--temperature-C", dest="temperature_C", type=float, required=True,
                        help="service temperature (C)")
    parser.add_argument("--years", type=float, required=True, help="time in service (years of 8766 h)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def vertex_volumes(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Volume per radian belonging to each vertex of an r-z section: each triangle's r dA shared equally by its
    three vertices (lumped)."""
    p = points[:, :2]
    tri = p[triangles]                                           # (ne, 3, 2)
    area = 0.5 * np.abs((tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
                        - (tri[:, 2, 0] - tri[:, 0, 0]) * (tri[:, 1, 1] - tri[:, 0, 1]))
    weight = area * tri[:, :, 0].mean(axis=1) / 3.0
    out = np.zeros(len(p))
    np.add.at(out, triangles.ravel(), np.repeat(weight, 3))
    return out


def stability(run_dir: Path, temperature_C: float, years: float) -> dict[str, Any]:
    """The service change of the tempered part of ``run_dir`` (see the module docstring), as a JSON-ready dict."""
    from quenchsim import mechanics
    from quenchsim.errors import InputError
    from quenchsim.materials import load_material
    from quenchsim.metallurgy import load_kinetics, load_tempering
    from quenchsim.metallurgy.tempering import service_change
    from quenchsim.results import files, load

    if not years > 0.0:
        raise InputError("--years", years, "must be > 0")
    run = load(run_dir)
    summary = run.summary or {}
    if "tempered" not in summary or run.frame is None or run.case is None:
        raise InputError("RUN_DIR", str(run_dir), "holds no tempered part (a finished run of a case with a [temper] "
                         "stage: summary.json 'tempered' and its last frame)")
    temper_C = summary["tempered"]["temper"]["temperature_C"]
    if not -50.0 <= temperature_C < temper_C:
        raise InputError("--temperature-C", temperature_C, f"must lie in [-50, {temper_C:g}) C, below the part's "
                         "tempering temperature (a hotter hold is a temper of its own)")
    case = run.case
    material = load_material(case["material"])
    kin = load_kinetics(material, case["process"]["austenitising_temperature_C"])
    tempering = load_tempering(material, kin)
    data = run.frame.point_data
    change = service_change(tempering, data["tempering_parameter_K"], data["martensite"], data["austenite"],
                            temperature_C, years * HOURS_PER_YEAR)
    product = tempering.reactions["austenite_decomposition"].product or "bainite"
    model = mechanics.load_mechanics(material, {"plasticity": False, "trip": False,
                                                "austenitizing_T_C": kin.T_aust_C})
    room_C = case["process"]["room_temperature_C"]
    gamma = float(mechanics.model.transformation_strain(model, product, room_C))
    volume = vertex_volumes(run.frame.points, run.frame.triangles)
    mean = lambda x: float(np.sum(np.asarray(x) * volume) / np.sum(volume))  # noqa: E731
    growth = change.austenite_decomposed * gamma
    strain = mean(growth + change.martensite_strain)
    after = summary["tempered"]["dimensions_mm"]["after"] if "dimensions_mm" in summary["tempered"] else {}
    return {"run": str(run_dir), "service_temperature_C": temperature_C, "years": years,
            "tempering_parameter_K": {"before": mean(data["tempering_parameter_K"]), "after": mean(change.P_after)},
            "retained_austenite": {"before": mean(data["austenite"]),
                                   "after": mean(data["austenite"] - change.austenite_decomposed)},
            "austenite_to_product_strain": gamma,
            "strain_ppm": {"total": 1e6 * strain, "austenite_decomposition": 1e6 * mean(growth),
                           "martensite_reactions": 1e6 * mean(change.martensite_strain)},
            "dimension_change_mm": {k: strain * v for k, v in after.items()},
            "method": "uniform free strain: the volume-weighted mean of the points' free-strain change times each "
                      f"tempered dimension ({files.SUMMARY_JSON}); elastic accommodation of its non-uniformity left out"}


def run(args: argparse.Namespace) -> int:
    out = stability(args.run_dir, args.temperature_C, args.years)
    if args.json:
        print(json.dumps(out))
        return 0
    ra, s = out["retained_austenite"], out["strain_ppm"]
    rows = [f"{args.run_dir}: held {out['years']:g} years at {out['service_temperature_C']:g} C",
            f"retained austenite (mean)   {ra['before']:.4f} -> {ra['after']:.4f}",
            f"size change (ppm)           {s['total']:+.1f}  (austenite decomposition {s['austenite_decomposition']:+.1f}, "
            f"martensite {s['martensite_reactions']:+.1f})"]
    rows += [f"{k + ' (mm)':<28}{v:+.4f}" for k, v in out["dimension_change_mm"].items()]
    print("\n".join(rows))
    return 0

