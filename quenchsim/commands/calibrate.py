"""`quenchsim calibrate CAL.toml --out DIR [--workers 2] [--max-runs N]`."""

from __future__ import annotations

import argparse
import logging
from pathlib import Path


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("calibration", type=Path, help="calibration file (TOML; see quenchsim.calibration.spec)")
    parser.add_argument("--out", type=Path, help="output directory (default runs/calibration_<name>)")
    parser.add_argument("--workers", type=int, default=2, help="Dask worker processes (0: runs in this process)")
    parser.add_argument("--max-runs", type=int, help="stop after this many new full-chain runs (run again to go on); "
                                                     "a call that stops before the design is complete exits with 3")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    from quenchsim.calibration import calibrate, load_calibration
    from quenchsim.calibration.page import discrepancy_rows, posterior_rows
    from quenchsim.errors import require
    from quenchsim.shipped import resolve_case

    require(args.workers >= 0, "--workers", args.workers, "must be >= 0")
    require(args.max_runs is None or args.max_runs >= 0, "--max-runs", args.max_runs, "must be >= 0")
    spec = load_calibration(resolve_case(args.calibration, field="calibration"))
    out = args.out or Path("runs") / f"calibration_{spec.name}"
    logging.basicConfig(level=logging.WARNING, format="quenchsim: %(message)s")
    result = calibrate(spec, out, workers=args.workers, progress=not args.quiet, max_runs=args.max_runs)
    runs = result["runs"]
    if result["status"] == "incomplete":
        print(f"{spec.name}: {runs['ran_now']} runs done now, {runs['pending']} still to run: run the same command "
              f"again to continue ({out})")
        return 3
    print("\n".join(posterior_rows(result)))
    if result["discrepancy"]:
        print("\n".join(["", *discrepancy_rows(result)]))
    unmet = [k for k, row in result["calibrated_run"].items() if row["met"] is False]
    conflicts = [c for c in result["conflicts"] if c["conflict"]]
    print(f"\n{len(result['calibrated_run']) - len(unmet)} of {len(result['calibrated_run'])} observables met by the full "
          f"chain at the posterior median" + (f"; not met: {', '.join(unmet)}" if unmet else ""))
    for c in conflicts:
        print(f"conflict: {c['a']} / {c['b']} (chi2_PG {c['chi2_pg']:.1f})")
    print(f"{result['full_chain_runs']} full-chain runs, {result['wall_time_s']:.0f} s; see {out / 'calibration.md'}")
    return 0
