"""`quenchsim sweep SWEEP.toml [--scheduler ADDRESS] [--workers N] [--out DIR]` (see quenchsim.sweep)."""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("sweep", type=Path, help="sweep file (TOML): [sweep] case/condition, [set], [grid], [zip]")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://127.0.0.1:8786 "
                                            "(default: a LocalCluster on this machine)")
    parser.add_argument("--workers", type=int, default=2,
                        help="LocalCluster worker processes, one thread each (0: run serially in this process)")
    parser.add_argument("--out", type=Path, help="output directory (default runs/sweep_<name>)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    from quenchsim.sweep import load_sweep, run_sweep

    logging.basicConfig(level=logging.WARNING, format="quenchsim: %(message)s")
    spec = load_sweep(args.sweep)
    out = args.out or Path("runs") / f"sweep_{spec.name}"
    outcome = run_sweep(spec, out, scheduler=args.scheduler, workers=args.workers, progress=not args.quiet)
    print(json.dumps(outcome.as_dict(), indent=2))
    if outcome.interrupted:
        print(f"quenchsim: sweep interrupted; {outcome.pending} case(s) not finished -- run the same command "
              "again to finish them", flush=True)
        return 130
    return 1 if outcome.failed else 0
