"""`quenchsim bearings doj`: quasi-static internal forces of a six-ball double-offset joint over one revolution.

    quenchsim bearings doj --case 3 --angle-deg 10 --json
    quenchsim bearings doj --case 1 --angle-deg 5 --torque-Nm 200 --out runs/doj

Clearances from the paper's Table 1 (--case) or given one by one (mm); the geometry is the assumed one of
quenchsim/bearings/data/doj.toml unless overridden. Prints P_n (Eq. 12), the ranges of the internal forces
over the revolution and the axial force on the outer race (with --friction: ball - track friction to first
order); --out writes the per-phase CSV and a plot. A --pitch-circle-radius-mm moves the inner-race and cage
spheres with it (they keep their distances from the pitch circle, geometry.scaled_reference_geometry).
"""

from __future__ import annotations

import argparse
import dataclasses
import pathlib

import numpy as np

from quenchsim.bearings.commands.ranges import Range
from quenchsim.bearings.doj import Clearances, DOJModel, reference_case, reference_data, scaled_reference_geometry
from quenchsim.bearings.doj.axial import axial_force_summary
from quenchsim.bearings.doj.output import Revolution, plot_runs, summary, write_csv

RANGES = {"angle_deg": Range(0.0, 25.0, unit="deg"), "torque_Nm": Range(0.0, 1e5, low_open=True, unit="N m"),
          "phase_step_deg": Range(0.0, 60.0, low_open=True, unit="deg"),
          "track_clearance_mm": Range(0.0, 1.0, unit="mm"), "window_clearance_mm": Range(-0.1, 1.0, unit="mm"),
          "outer_sphere_clearance_mm": Range(0.0, 1.0, unit="mm"), "inner_sphere_clearance_mm": Range(0.0, 1.0, unit="mm"),
          "pitch_circle_radius_mm": Range(0.0, 500.0, low_open=True, unit="mm"),
          "ball_diameter_mm": Range(0.0, 200.0, low_open=True, unit="mm"),
          "contact_angle_deg": Range(0.0, 90.0, low_open=True, high_open=True, unit="deg"),
          "cage_offset_mm": Range(0.0, 100.0, low_open=True, unit="mm"), "friction": Range(0.0, 1.0)}
"""Physical ranges of the numeric options (a DOJ articulates to ~25 deg; window interference at most 0.1 mm);
the geometry's own consistency (balls inside the races, cage around the pitch circle) is checked by DOJGeometry."""
_CLEARANCE_OPTIONS = {"track_clearance_mm": "track_mm", "window_clearance_mm": "window_mm",
                      "outer_sphere_clearance_mm": "outer_sphere_mm", "inner_sphere_clearance_mm": "inner_sphere_mm"}
_GEOMETRY_OPTIONS = {"pitch_circle_radius_mm": "pitch_circle_radius_mm", "ball_diameter_mm": "ball_diameter_mm",
                     "contact_angle_deg": "track_contact_angle_deg", "cage_offset_mm": "cage_offset_mm"}


def configure(parser: argparse.ArgumentParser) -> None:
    cond = reference_data()["conditions"]
    parser.add_argument("--case", choices=("1", "2", "3"), default="3", help="clearances of Table 1 (default 3)")
    parser.add_argument("--angle-deg", type=float, default=10.0, help="operating angle, deg (default 10)")
    parser.add_argument("--torque-Nm", type=float, default=cond["torque_Nm"],
                        help=f"transmitted torque, N m (default {cond['torque_Nm']:g})")
    parser.add_argument("--phase-step-deg", type=float, default=2.0, help="phase step over the revolution (default 2)")
    for opt in _CLEARANCE_OPTIONS:
        parser.add_argument("--" + opt.replace("_", "-"), type=float, default=None, help="override the case, mm")
    for opt in _GEOMETRY_OPTIONS:
        parser.add_argument("--" + opt.replace("_", "-"), type=float, default=None,
                            help="override the assumed geometry")
    parser.add_argument("--friction", type=float, default=0.0,
                        help="Coulomb friction at the ball - outer-track contacts for the axial force on the outer race "
                        "(first order, axial.py; default 0: frictionless, axial force 0)")
    parser.add_argument("--out", type=pathlib.Path, default=None, help="directory for doj.csv and doj.png")


def run(args: argparse.Namespace) -> dict:
    clear = reference_case(args.case)
    clear = Clearances(**{**dataclasses.asdict(clear), **{field: getattr(args, opt) for opt, field in
                                                          _CLEARANCE_OPTIONS.items() if getattr(args, opt) is not None}})
    geo = scaled_reference_geometry(args.pitch_circle_radius_mm)
    geo = dataclasses.replace(geo, **{field: getattr(args, opt) for opt, field in _GEOMETRY_OPTIONS.items()
                                      if getattr(args, opt) is not None})
    model = DOJModel(geo, clear, args.angle_deg, args.torque_Nm)
    phases = np.arange(0.0, 360.0 + 1e-9, args.phase_step_deg)
    rev = Revolution.from_phases(model.revolution(phases), model.p_n)
    out = {"operating_angle_deg": args.angle_deg, "torque_Nm": args.torque_Nm, "clearances_mm": dataclasses.asdict(clear),
           "geometry": {**dataclasses.asdict(geo), "assumed": True}, **summary(rev, args.torque_Nm),
           "axial_force": axial_force_summary(rev, args.friction)}
    if args.out is not None:
        out["csv"] = str(write_csv(rev, args.out / "doj.csv"))
        out["plot"] = str(plot_runs({f"case {args.case}, {args.angle_deg:g} deg": rev},
                                    "DOJ internal forces (assumed geometry)", args.out / "doj.png"))
    return out
