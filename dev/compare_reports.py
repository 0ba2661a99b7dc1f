"""Compare every number of two reports folders' study metrics (reports/*.json), key by key.

    python dev/compare_reports.py OLD_REPORTS NEW_REPORTS [--rtol 1e-9] [--ignore time,load,...]

Prints, per study, how many numbers are equal (within rtol), which differ (old -> new, relative change), which keys
are only in one of them; timings, load averages, cache bookkeeping and the rendered page text (page_md) are left out by the words of their key names. A maintainer's
tool for "results unchanged" checks after a refactor; nothing in the package imports it.
"""
from __future__ import annotations

import argparse
import json
import re
from pathlib import Path
from typing import Any

from bench import relative_difference  # dev/ is on the path when this runs as a script

IGNORED = ("generated", "page", "time", "wall", "load", "fingerprint", "cached", "cpu", "seconds", "elapsed", "out", "date")
PREFIXES = ("inputs.",)  # the list of code and data files a study read


def flatten(value: Any, prefix: str = "") -> dict[str, Any]:
    """Every leaf of a JSON value under a dotted key (lists by index)."""
    if isinstance(value, dict):
        items = value.items()
    elif isinstance(value, list):
        items = ((str(i), v) for i, v in enumerate(value))
    else:
        return {prefix: value}
    out: dict[str, Any] = {}
    for key, item in items:
        out.update(flatten(item, f"{prefix}.{key}" if prefix else str(key)))
    return out


def differs(a: Any, b: Any, rtol: float) -> bool:
    """Numbers by their relative difference (dev/bench.py's, NaN equal to NaN), anything else by equality."""
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) or not isinstance(b, (int, float)):
        return a != b
    return relative_difference(float(a), float(b)) > rtol and abs(a - b) > 1e-12


def compare(old: Path, new: Path, rtol: float, ignore: set[str]) -> int:
    changed_studies = 0
    for path in sorted(new.glob("*.json")):
        before = old / path.name
        if not before.is_file():
            print(f"{path.stem}: new")
            continue
        a = flatten(json.loads(before.read_text()))
        b = flatten(json.loads(path.read_text()))
        keys = sorted(set(a) | set(b))
        keep = [k for k in keys if not k.startswith(PREFIXES) and not ignore & set(re.split(r"[._]", k.lower()))]
        only_old = [k for k in keep if k not in b]
        only_new = [k for k in keep if k not in a]
        diff = [k for k in keep if k in a and k in b and differs(a[k], b[k], rtol)]
        equal = len(keep) - len(only_old) - len(only_new) - len(diff)
        changed_studies += bool(diff or only_old or only_new)
        print(f"{path.stem}: {equal} equal, {len(diff)} differ, {len(only_old)} only old, {len(only_new)} only new "
              f"({len(keys) - len(keep)} timing / bookkeeping keys left out)")
        for k in diff[:40]:
            x, y = a[k], b[k]
            rel = ""
            if isinstance(x, (int, float)) and isinstance(y, (int, float)) and x:
                rel = f" ({(y - x) / abs(x):+.2e})"
            print(f"    {k}: {x!r} -> {y!r}{rel}")
        if len(diff) > 40:
            print(f"    ... {len(diff) - 40} more")
    return changed_studies


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    parser.add_argument("--rtol", type=float, default=1e-9)
    parser.add_argument("--ignore", default=",".join(IGNORED), help="comma-separated words: keys with one of them as a word (split at . and _) are left out")
    args = parser.parse_args()
    n = compare(args.old, args.new, args.rtol, {w for w in args.ignore.split(",") if w})
    print(f"{n} studies with a changed number")


if __name__ == "__main__":
    main()
