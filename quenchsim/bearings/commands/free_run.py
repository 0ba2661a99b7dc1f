"""`quenchsim bearings free-run PULSES.csv`: friction torque from a coast-down record.

    quenchsim bearings free-run pulses.csv --inertia 1.72e-3 [--method n-omega|t-omega|model] \
        [--alpha-percent 1] [--clock-hz 1e6] [--periods] [--plot coastdown.png] --json
    quenchsim bearings free-run pulses.csv --rotor-inertia 1.7e-3 --bearing 6206 --bearings-count 2 \
        [--cage-inertia 2e-5] [--inertia-form energy|published] --json

PULSES.csv: one value per revolution (times in s; clock counts with --clock-hz; per-revolution
periods with --periods). With --rotor-inertia the equivalent inertia adds the cage and the balls
(orbit and spin, from the bearing geometry and the steel density).
"""

from __future__ import annotations

import argparse
import pathlib

from quenchsim.bearings import free_run as fr
from quenchsim.bearings.commands.kinematics import add_geometry_arguments, geometry_from_args
from quenchsim.bearings.commands.ranges import GEOMETRY, Range
from quenchsim.errors import InputError

INERTIA = Range(0.0, 1e6, low_open=True, unit="kg m^2")
RANGES = {**GEOMETRY, "clock_hz": Range(0.0, 1e12, low_open=True, unit="Hz"), "inertia": INERTIA,
          "rotor_inertia": INERTIA, "bearings_count": Range(1, 1000, integer=True),
          "cage_inertia": Range(0.0, 1e6, unit="kg m^2"),
          "alpha_percent": Range(0.0, 100.0, low_open=True, high_open=True, unit="%")}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("pulses", type=pathlib.Path, help="CSV with one pulse time (or count/period) per revolution")
    parser.add_argument("--clock-hz", type=float, default=None, help="values are counts of a clock of this frequency")
    parser.add_argument("--periods", action="store_true", help="values are per-revolution periods, not times")
    which = parser.add_mutually_exclusive_group(required=True)
    which.add_argument("--inertia", type=float, help="equivalent inertia I_eq, kg m^2")
    which.add_argument("--rotor-inertia", type=float, help="rotor + inner rings + spacer inertia, kg m^2")
    add_geometry_arguments(parser, required=False)
    parser.add_argument("--bearings-count", type=int, default=1, help="number of identical bearings (default 1)")
    parser.add_argument("--cage-inertia", type=float, default=0.0, help="cage inertia of all bearings, kg m^2")
    parser.add_argument("--inertia-form", choices=("energy", "published"), default="energy",
                        help="equivalent-inertia formula (default: kinetic-energy form)")
    parser.add_argument("--method", default="n-omega", help="n-omega (default) | t-omega | model")
    parser.add_argument("--alpha-percent", type=float, default=1.0, help="n-omega window tolerance, %% (default 1)")
    parser.add_argument("--plot", type=pathlib.Path, default=None, help="write omega(t) and omega'(n) plots to PNG")


def run(args: argparse.Namespace) -> dict:
    t = fr.read_pulses(args.pulses, clock_hz=args.clock_hz, periods=args.periods)
    geometry, data = geometry_from_args(args)
    if args.inertia is not None:
        if geometry is not None:
            raise InputError("--bearing", args.bearing, "not used with --inertia (use --rotor-inertia)")
        inertia = args.inertia
    else:
        if geometry is None:
            raise InputError("--rotor-inertia", args.rotor_inertia,
                             "needs the bearing: --bearing NAME or explicit dimensions")
        orbit, spin = fr.ball_inertias_kg_m2(geometry, args.bearings_count)
        inertia = fr.equivalent_inertia(args.rotor_inertia, args.cage_inertia + orbit, spin, geometry,
                                        form=args.inertia_form)
    r = fr.friction_torque(t, inertia, args.method, args.alpha_percent)
    out = {"torque_Nm": r.torque_Nm, "omega0_rad_s": r.omega0_rad_s, "decel_rad_s2": r.decel_rad_s2,
           "method": r.method, "n_used": r.n_used, "inertia_kg_m2": inertia, "pulses": int(t.size),
           "bearing": data.name if data else None}
    if r.detail.law is not None:
        out["model_family"] = r.detail.law.family
        out["model_parameters"] = list(r.detail.law.params)  # of g = T / I_eq (rad/s^2 units)
    if args.plot is not None:
        from quenchsim.bearings.free_run_plots import plot_free_run

        out["plot"] = str(plot_free_run(t, r, args.plot))
    return out
