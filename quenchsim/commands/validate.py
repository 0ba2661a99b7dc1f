"""`quenchsim validate [--list | --check] [--only NAME ...] [--fast] [--force] [--strict]`: run the studies of validation/.

Each study (validation/<area>/<study>/: targets.toml + study.py, contract in validation/README.md) is run
unless its metrics in ``<reports>/<area>_<study>.json`` carry the current fingerprint (the code and data the
study depends on: the quenchsim modules it imports, its folder, the case and data files it reads; an
interrupted run resumes where it stopped); its page is written as soon as it finishes. The runner prints the
targets that are missed and the open ones (known misses, with their reasons) and exits 1 on a regression: a
target not declared open is missed. An open target is a miss that is declared, not a pass: it is printed and
fails only with ``--strict``. ``--check`` does the same from the cached metrics without running anything
(a study without cached metrics fails; stale metrics are evaluated and flagged), so CI can run it.
"""

from __future__ import annotations

import argparse
from pathlib import Path


def configure(parser: argparse.ArgumentParser) -> None:
    parser.description = __doc__.splitlines()[0]
    parser.epilog = ("Exit status: 0 when every target is met or declared open (status = \"open\" in its "
                     "targets.toml: a known miss, printed separately with its reason); 1 when a target not declared "
                     "open is missed (a regression), an open one is missed with --strict, or a study failed or has "
                     "no cached metrics (--check); 2 on bad input.")
    parser.add_argument("--reports", type=Path, default=Path("reports"), help="reports folder (default ./reports)")
    parser.add_argument("--runs", type=Path, default=None,
                        help="work folder of the studies and their quench runs (default ./runs/validation)")
    parser.add_argument("--only", nargs="+", metavar="NAME",
                        help="run only these studies: area/study, an area, or a study name (see --list)")
    parser.add_argument("--list", action="store_true", help="list the studies and their targets, run nothing")
    parser.add_argument("--check", action="store_true",
                        help="evaluate the targets on the cached metrics in --reports, run nothing")
    parser.add_argument("--fast", action="store_true", help="only the studies that run in seconds (SLOW = False)")
    parser.add_argument("--force", action="store_true", help="rerun even when the cached metrics are current")
    parser.add_argument("--strict", action="store_true",
                        help="exit 1 on an open target's miss too (by default open targets are reported, exit 0)")


def list_lines(studies: list) -> list[str]:
    lines = []
    for s in studies:
        lines.append(f"{s.key}{'' if s.slow() else '  [fast]'}: {s.title()}")
        for t in s.targets:
            flag = f" [{t.status}]" if t.status else ""
            role = f" ({t.role})" if t.role != "validation" else ""
            lines.append(f"    {t.metric}: {t.describe()}{flag}{role} -- {t.source}")
    return lines


def run(args: argparse.Namespace) -> int:
    from quenchsim import validation as v
    from quenchsim.errors import InputError

    studies = v.discover()
    if not studies:   # an installed wheel: the studies come with a source checkout only
        raise InputError("validation folder", str(v.VALIDATION_ROOT), "holds no studies (<area>/<study>/study.py); "
                         "they come with a clone of the quenchsim repository, not with an installed package: run "
                         "quenchsim validate in a clone")
    chosen = v.select(studies, args.only)
    if args.fast:
        chosen = [s for s in chosen if not s.slow()]
    if not chosen:
        raise InputError("--fast", True, "none of the chosen studies runs in seconds; see quenchsim validate --list")
    if args.list:
        print("\n".join(list_lines(chosen)))
        return 0
    if args.check:
        results = [v.check_study(s, args.reports) for s in chosen]
    else:
        results = []
        for s in chosen:
            print(f"{s.key}: running ...", flush=True)
            r = v.run_study(s, args.reports, args.runs or v.RUNS, force=args.force)
            results.append(r)
            state = r.status if r.status != "failed" else f"FAILED: {r.error}"
            print(f"{s.key}: {state} ({r.seconds:.1f} s), {len(r.misses())} target(s) not met", flush=True)
        v.write_index(args.reports, studies, {**v.previous_results(args.reports, studies),
                                              **{r.key: r for r in results}})
    print("\n".join(v.summary_lines(results)))
    return v.exit_code(results, strict=args.strict)
