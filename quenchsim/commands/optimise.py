"""`quenchsim optimise STUDY.toml [--out DIR] [--workers N] [--scheduler ADDRESS] [--trials N]` (see
quenchsim.design.spec for the study file)."""

from __future__ import annotations

import argparse
import dataclasses
import logging
from pathlib import Path

from quenchsim.errors import require


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("study", type=Path, help="study file (TOML): [study] case, [variables], [objectives], "
                                                 "[constraints], [fidelity], [confirm]")
    parser.add_argument("--out", type=Path, help="study folder (default runs/optimise_<name>); an existing one is resumed")
    parser.add_argument("--workers", type=int, default=2,
                        help="LocalCluster worker processes, one thread each (0: run serially in this process)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    parser.add_argument("--trials", type=int, help="cheap-fidelity trials in all (overrides study.trials)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    from quenchsim.design.page import summary_text
    from quenchsim.design.spec import load_study
    from quenchsim.shipped import resolve_case
    from quenchsim.design.study import run_study

    require(isinstance(args.workers, int) and args.workers >= 0, "--workers", args.workers, "must be an integer >= 0")
    spec = load_study(resolve_case(args.study, field="study"))
    if args.trials is not None:
        require(args.trials >= spec.startup, "--trials", args.trials, f"must be >= study.startup ({spec.startup})")
        spec = dataclasses.replace(spec, trials=args.trials)
    logging.basicConfig(level=logging.WARNING, format="quenchsim: %(message)s")
    out = args.out or Path("runs") / f"optimise_{spec.name}"
    outcome = run_study(spec, out, workers=args.workers, scheduler=args.scheduler, progress=not args.quiet)
    print(summary_text(outcome))
    if outcome.interrupted:
        return 130
    return 0 if outcome.feasible else 1
