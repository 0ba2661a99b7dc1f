"""`quenchsim cases [list]` and `quenchsim cases copy NAME [DIR] [--force]`: the case files quenchsim ships.

``list`` prints each shipped case's name, description and conditions (also from a wheel installed outside the
checkout, where the cases live inside the package), and the example files the guides use; ``copy`` writes one of
either into the user's folder (default: the working directory) to read and edit, refusing to overwrite an existing
file unless ``--force``. A shipped case also
runs by its name: ``quenchsim run crb_outer_ring --condition 1``.
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from quenchsim.errors import InputError
from quenchsim.shipped import shipped_cases, shipped_examples, shipped_file


def configure(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="action")
    sub.add_parser("list", help="name, description and conditions of every shipped case (the default)")
    copy = sub.add_parser("copy", help="copy a shipped case or example file into your folder")
    copy.add_argument("name", help="a shipped case's name or an example file's (quenchsim cases lists them)")
    copy.add_argument("dir", nargs="?", type=Path, default=Path("."), help="folder to copy into (default: here)")
    copy.add_argument("--force", action="store_true", help="overwrite an existing file of that name")


def run(args: argparse.Namespace) -> int:
    if getattr(args, "action", None) == "copy":
        source = shipped_file(args.name, field="NAME")
        if args.dir.exists() and not args.dir.is_dir():
            raise InputError("DIR", str(args.dir), "is a file: give a folder to copy the case into")
        target = args.dir / source.name
        if target.exists() and not args.force:
            raise InputError("DIR", str(args.dir), f"already holds {source.name}: give another folder, or --force "
                                                   "to overwrite it")
        args.dir.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source, target)
        print(f"wrote {target}")
        return 0
    for case in shipped_cases():
        conditions = f" [conditions: {', '.join(case.conditions)}]" if case.conditions else ""
        print(f"{case.name:<26}{case.description}{conditions}")
    print(f"example files (quenchsim cases copy NAME): {', '.join(p.name for p in shipped_examples())}")
    return 0
