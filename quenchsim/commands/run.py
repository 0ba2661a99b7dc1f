"""`quenchsim run CASE.toml --condition NAME --out DIR [--mesh-size MM] [--set KEY=VALUE ...]`."""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

from quenchsim.case import load_case
from quenchsim.errors import InputError


def parse_sets(items: list[str]) -> dict[str, object]:
    """``["quench.time_s=600", "geometry.type=\\"profile\\""]`` -> dotted overrides (values parsed as TOML)."""
    import tomllib

    out: dict[str, object] = {}
    for item in items or []:
        key, sep, raw = item.partition("=")
        if not sep or not key:
            raise InputError("--set", item, "must look like KEY=VALUE, e.g. quench.time_s=600")
        try:
            out[key.strip()] = tomllib.loads(f"v = {raw}")["v"]
        except tomllib.TOMLDecodeError:
            out[key.strip()] = raw
    return out


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("case", type=Path, help="case file (TOML)")
    parser.add_argument("--condition", help="named condition of the case file")
    parser.add_argument("--out", type=Path, help="output directory (default runs/<case>_<condition>)")
    parser.add_argument("--mesh-size", type=float, help="core element size in mm (surface size scales with it)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="override any case field, e.g. --set quench.time_s=600")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    from quenchsim.pipeline import run as run_case

    overrides = parse_sets(args.set)
    case = load_case(args.case, args.condition, overrides)
    if args.mesh_size is not None:
        if args.mesh_size <= 0:
            raise InputError("--mesh-size", args.mesh_size, "must be > 0 (mm)")
        case = case.with_mesh_size(args.mesh_size)
    out = args.out or Path("runs") / f"{case.name}_{case.condition or 'base'}"
    logging.basicConfig(level=logging.WARNING, format="quenchsim: %(message)s")
    result = run_case(case, out, progress=not args.quiet)
    s = result.summary
    print(json.dumps({"out": str(out), "status": s["status"], "probes": s["probes"], "hardness": s["hardness"],
                      **({"dimensions_mm": s["dimensions_mm"]} if "dimensions_mm" in s else {}),
                      "solver": s["solver"]}, indent=2))
    return 0
