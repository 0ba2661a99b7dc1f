"""`quenchsim cases [list]` and `quenchsim cases copy NAME [DIR] [--force]`: the case files quenchsim ships.

``list`` prints each shipped case's name, description and conditions (also from a wheel installed outside the
checkout, where the cases live inside the package); ``copy`` writes one into the user's folder (default: the
working directory) to read and edit, refusing to overwrite an existing file unless ``--force``. A shipped case also
runs by its name: ``quenchsim run crb_outer_ring --condition 1``.
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from quenchsim.errors import InputError
from quenchsim.shipped import shipped_case, shipped_cases


def configure(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="action")
    sub.add_parser("list", help="name, description and conditions of every shipped case (the default)")
    copy = sub.add_parser("copy", help="copy a shipped case file into your folder")
    copy.add_argument("name", help="a shipped case's name (quenchsim cases lists them)")
    copy.add_argument("dir", nargs="?", type=Path, default=Path("."), help="folder to copy into (default: here)")
    copy.add_argument("--force", action="store_true", help="overwrite an existing file of that name")


def run(args: argparse.Namespace) -> int:
    if getattr(args, "action", None) == "copy":
        case = shipped_case(args.name, field="NAME")
        if args.dir.exists() and not args.dir.is_dir():
            raise InputError("DIR", str(args.dir), "is a file: give a folder to copy the case into")
        target = args.dir / case.path.name
        if target.exists() and not args.force:
            raise InputError("DIR", str(args.dir), f"already holds {case.path.name}: give another folder, or --force "
                                                   "to overwrite it")
        args.dir.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(case.path, target)
        print(f"wrote {target}")
        return 0
    for case in shipped_cases():
        conditions = f" [conditions: {', '.join(case.conditions)}]" if case.conditions else ""
        print(f"{case.name:<26}{case.description}{conditions}")
    return 0
