"""`quenchsim sweep SWEEP.toml [--scheduler ADDRESS] [--workers N] [--out DIR]` (see quenchsim.sweep)."""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

from quenchsim.commands.mesh_limit import MAX_TRIANGLES, refuse_large_mesh


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("sweep", type=Path, help="sweep file (TOML): [sweep] case/condition, [set], [grid], [zip]; or a shipped one's name, e.g. sweep_nozzles")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://127.0.0.1:8786 "
                                            "(default: a LocalCluster on this machine)")
    parser.add_argument("--workers", type=int, default=2,
                        help="LocalCluster worker processes, one thread each (0: run serially in this process)")
    parser.add_argument("--out", type=Path, help="output directory (default runs/sweep_<name>)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.add_argument("--force", action="store_true",
                        help=f"run cases whose mesh is above {MAX_TRIANGLES:,} estimated triangles")


def run(args: argparse.Namespace) -> int:
    from quenchsim.case.parse import case_from_dict
    from quenchsim.shipped import resolve_case
    from quenchsim.sweep import load_sweep, run_sweep

    logging.basicConfig(level=logging.WARNING, format="quenchsim: %(message)s")
    spec = load_sweep(resolve_case(args.sweep, field="sweep"))
    for point in spec.points:   # an absurd element size in [set] or [grid] is refused before any case runs
        refuse_large_mesh(case_from_dict(spec.raw_case, spec.condition, spec.overrides(point), path=spec.case_path),
                          args.force)
    out = args.out or Path("runs") / f"sweep_{spec.name}"
    outcome = run_sweep(spec, out, scheduler=args.scheduler, workers=args.workers, progress=not args.quiet)
    print(json.dumps(outcome.as_dict(), indent=2))
    if outcome.interrupted:
        print(f"quenchsim: sweep interrupted; {outcome.pending} case(s) not finished -- run the same command "
              "again to finish them", flush=True)
        return 130
    return 1 if outcome.failed else 0
