"""`quenchsim report RUN_DIR [RUN_DIR ...] [--out FILE.html]`: HTML (self-contained) + Markdown report."""

from __future__ import annotations

import argparse
from pathlib import Path


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("dirs", nargs="+", type=Path, metavar="RUN_DIR",
                        help="run directories (quenchsim run) and/or sweep directories (quenchsim sweep)")
    parser.add_argument("--out", type=Path, help="HTML file to write (default RUN_DIR/report.html of the first "
                                                 "directory); the Markdown goes next to it with suffix .md")
    parser.add_argument("--title", default="quenchsim report", help="report title")


def run(args: argparse.Namespace) -> int:
    from quenchsim.errors import InputError
    from quenchsim.report.run_report import write_report

    out = args.out or args.dirs[0] / "report.html"
    if out.suffix.lower() not in (".html", ".htm"):
        raise InputError("--out", str(out), "must end in .html (the Markdown is written next to it as .md)")
    written = write_report(args.dirs, out, title=args.title)
    png_dir = written[0].parent / f"{written[0].stem}_files"
    print(f"{written[0]}\n{written[1]} (+ {len(written) - 2} PNG in {png_dir})")
    return 0
