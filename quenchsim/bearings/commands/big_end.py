"""`quenchsim bearings big-end INPUT.toml [--clearance-set N] [--mode engine|static|rig]`.

Runs one case of the big-end needle-bearing dynamics and prints its statistics; writes the time
series (CSV) and plots (PNG) when --out is given.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from quenchsim.bearings.big_end import load_case, plot_run, run_statistics, simulate, write_csv
from quenchsim.bearings.big_end.case import MODES
from quenchsim.bearings.big_end.simulate import DEFAULT_INTEGRATOR, INTEGRATORS
from quenchsim.bearings.commands.ranges import Range
from quenchsim.shipped import resolve_case

RANGES = {"clearance_set": Range(1, 1000, integer=True), "revolutions": Range(0.0, 1e6, low_open=True)}
"""Physical ranges of the numeric options (checked before any work, see :mod:`quenchsim.bearings.commands.ranges`)."""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("input", help="case file (TOML), or a shipped one's name, e.g. big_end_two_stroke")
    parser.add_argument("--clearance-set", type=int, default=2, help="1-based [[clearance_set]] (default 2)")
    parser.add_argument("--mode", choices=MODES, default="engine", help="engine (default), static or rig")
    parser.add_argument("--revolutions", type=float, default=None, help="override the case's revolutions")
    parser.add_argument("--integrator", choices=INTEGRATORS, default=None,
                        help=f"SciPy method (default per mode, measured: {DEFAULT_INTEGRATOR})")
    parser.add_argument("--out", type=Path, default=None, help="directory for the CSV time series and PNG plots")


def run(args: argparse.Namespace) -> dict:
    case = load_case(resolve_case(args.input, field="input"))
    result = simulate(case, args.clearance_set, args.mode, revolutions=args.revolutions, method=args.integrator)
    stats = run_statistics(result)
    if args.out is not None:
        stem = f"big_end_{args.mode}_set{args.clearance_set}"
        stats["csv"] = str(write_csv(result, args.out / f"{stem}.csv"))
        stats["plot"] = str(plot_run(result, args.out / f"{stem}.png", f"{args.mode}, {result.clearance.name}"))
    return stats
